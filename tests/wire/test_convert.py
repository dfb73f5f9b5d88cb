"""wire.convert: protos <-> numpy values, poses, timestamps and durations."""

from __future__ import annotations

import types

import numpy as np
import pytest
from google.protobuf.duration_pb2 import Duration
from google.protobuf.timestamp_pb2 import Timestamp

from telerobot.v1 import types_pb2
from wire import convert
from wire.errors import InvalidArgumentError
from wire.pose import Pose


def rotation_y(angle: float) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def test_timestamps_round_trip_in_nanoseconds():
    time_ns = 1_700_000_000_123_456_789
    stamp = convert.timestamp(time_ns)
    assert isinstance(stamp, Timestamp) and stamp.seconds == 1_700_000_000
    assert stamp.nanos == 123_456_789 and convert.time_ns(stamp) == time_ns
    assert convert.time_ns(Timestamp()) == 0


@pytest.mark.parametrize("seconds", [0.0, 0.2, 1.5, 12.000000001, -0.25])
def test_durations_round_trip_to_the_nanosecond(seconds):
    value = convert.duration(seconds)
    assert isinstance(value, Duration)
    assert convert.seconds(value) == pytest.approx(seconds, abs=1e-9)
    assert value.ToNanoseconds() == round(seconds * 1e9)


def test_vectors_round_trip_and_are_checked_when_they_come_in():
    message = convert.vector3_to_proto(np.array([1, 2.5, -3]))
    assert (message.x, message.y, message.z) == (1.0, 2.5, -3.0)
    assert convert.vector3_from_proto(message, "v").tolist() == [1.0, 2.5, -3.0]
    assert convert.vector3_value(message).tolist() == [1.0, 2.5, -3.0]
    with pytest.raises(ValueError):
        convert.vector3_to_proto([1.0, 2.0])
    bad = types_pb2.Vector3(x=float("nan"))
    with pytest.raises(InvalidArgumentError) as error:
        convert.vector3_from_proto(bad, "force_n")
    assert error.value.reason == "NOT_FINITE" and "force_n" in error.value.message
    assert np.isnan(convert.vector3_value(bad)[0])  # as sent


def test_rotations_are_row_major_and_empty_is_the_identity():
    rotation = rotation_y(0.7)
    message = convert.rotation_to_proto(rotation)
    assert list(message.row_major) == rotation.reshape(9).tolist()
    np.testing.assert_allclose(convert.rotation_from_proto(message, "r"), rotation, atol=1e-15)
    np.testing.assert_array_equal(convert.rotation_value(message), rotation)
    empty = types_pb2.Matrix3()
    np.testing.assert_array_equal(convert.rotation_from_proto(empty, "r"), np.eye(3))
    np.testing.assert_array_equal(convert.rotation_value(empty), np.eye(3))


def test_a_bad_rotation_is_refused_coming_in_but_read_as_sent_from_a_peer():
    message = convert.rotation_to_proto(2 * np.eye(3))
    with pytest.raises(InvalidArgumentError) as error:
        convert.rotation_from_proto(message, "delta_rotation")
    assert error.value.reason == "NOT_A_ROTATION"
    np.testing.assert_array_equal(convert.rotation_value(message), 2 * np.eye(3))


def test_poses_go_out_from_anything_with_rotation_and_translation():
    pose = Pose(rotation_y(-0.3), [0.4, 0.0, 0.25])
    duck = types.SimpleNamespace(rotation=pose.rotation, translation=pose.translation)  # pin.SE3
    assert convert.pose_to_proto(duck) == convert.pose_to_proto(pose)
    message = convert.pose_to_proto(pose)
    assert (message.position_m.x, message.position_m.z) == (0.4, 0.25)
    for back in (convert.pose_from_proto(message, "tool_pose"), convert.pose_value(message)):
        assert isinstance(back, Pose) and back.isclose(pose, atol=1e-15)


def test_an_incoming_pose_names_the_bad_field():
    message = types_pb2.Pose(position_m=types_pb2.Vector3(y=float("inf")))
    with pytest.raises(InvalidArgumentError, match=r"flange_to_tool\.position_m"):
        convert.pose_from_proto(message, "flange_to_tool")
    message = types_pb2.Pose(rotation=convert.rotation_to_proto(-np.eye(3)))
    with pytest.raises(InvalidArgumentError, match=r"flange_to_tool\.rotation"):
        convert.pose_from_proto(message, "flange_to_tool")
    assert convert.pose_value(types_pb2.Pose()).isclose(Pose.identity(), atol=0)


def test_wrench():
    message = convert.wrench_to_proto([1, 2, 3], (0.1, 0.2, 0.3))
    assert convert.vector3_value(message.force_n).tolist() == [1.0, 2.0, 3.0]
    assert convert.vector3_value(message.torque_nm).tolist() == [0.1, 0.2, 0.3]
