"""The increments and acks the command path packs for an MCAP recording's writer
(recording_records): what goes in comes out, in order, whatever the mix."""

from __future__ import annotations

import numpy as np
import pytest

from services.decision_server.recording_mcap import increment_message
from services.decision_server.recording_records import (
    pack_ack,
    pack_increment,
    unpack_acks,
    unpack_increments,
)
from telerobot.v1 import decision_server_pb2 as pb
from telerobot.v1 import types_pb2


def _rotation_about_z(angle: float) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def test_increments_come_out_as_they_went_in_cartesian_and_joint_alike():
    buffer = bytearray()
    rotation = _rotation_about_z(0.01)
    pack_increment(buffer, 1_000, 0.001, "TOOL", np.array([1e-4, -2e-4, 3e-4]), rotation,
                   np.array([0.5, 0.1, 0.3]), None)
    pack_increment(buffer, 2_000, 0.002, "JOINTS", np.zeros(3), np.eye(3),
                   np.array([0.4, 0.0, 0.2]), np.array([0.01, -0.02, 0.0, 0.0, 0.03, 0.0, 0.1]))
    pack_increment(buffer, 3_000, 0.003, "BASE", [0.0, 0.0, 1e-3], [[1, 0, 0], [0, 1, 0],
                                                                    [0, 0, 1]],
                   [0.5, 0.1, 0.301], None)

    records = list(unpack_increments(bytes(buffer)))

    assert [log_time for log_time, _ in records] == [1_000, 2_000, 3_000]
    offset, frame, delta, rows, target, joints = records[0][1]
    assert (offset, frame, joints) == (0.001, "TOOL", None)
    np.testing.assert_array_equal(delta, [1e-4, -2e-4, 3e-4])
    np.testing.assert_array_equal(np.reshape(rows, (3, 3)), rotation)
    np.testing.assert_array_equal(target, [0.5, 0.1, 0.3])
    assert records[1][1][1] == "JOINTS"
    assert records[1][1][5] == [0.01, -0.02, 0.0, 0.0, 0.03, 0.0, 0.1]
    assert records[2][1][1] == "BASE" and records[2][1][2] == [0.0, 0.0, 1e-3]


def test_an_unpacked_increment_makes_the_message_a_queued_one_made():
    buffer = bytearray()
    rotation = _rotation_about_z(-0.02)
    pack_increment(buffer, 5, 1.25, "WRIST", np.array([1e-3, 0.0, 0.0]), rotation,
                   np.array([0.3, 0.2, 0.1]), None)
    (_, fields), = unpack_increments(bytes(buffer))

    message = increment_message(*fields)

    assert message.frame == types_pb2.REFERENCE_FRAME_WRIST
    assert message.offset.ToNanoseconds() == 1_250_000_000
    np.testing.assert_allclose(message.delta_rotation.row_major, rotation.reshape(9))
    assert (message.target_position_m.x, message.target_position_m.y) == (0.3, 0.2)


def test_acks_come_out_whole_and_in_order():
    buffer = bytearray()
    acks = [pb.CommandAck(sequence=n, outcome=pb.COMMAND_OUTCOME_APPLIED, detail="é" * n)
            for n in range(4)]  # sizes differ, one is empty
    for n, ack in enumerate(acks):
        pack_ack(buffer, 100 + n, ack.SerializeToString())

    out = list(unpack_acks(bytes(buffer)))

    assert [log_time for log_time, _ in out] == [100, 101, 102, 103]
    assert [pb.CommandAck.FromString(data) for _, data in out] == acks


def test_an_unknown_frame_is_refused_when_packed():
    with pytest.raises(KeyError):
        pack_increment(bytearray(), 0, 0.0, "ELBOW", np.zeros(3), np.eye(3), np.zeros(3), None)
