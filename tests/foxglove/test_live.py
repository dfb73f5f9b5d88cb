"""The live view's core and feeds: a real foxglove-sdk WebSocket server in this process, a
client of the Foxglove protocol, and fake upstream streams (the end-to-end test through a real
station is in tests/e2e/test_station.py)."""

from __future__ import annotations

import threading

import cv2
import foxglove
import grpc
import numpy as np
import pytest
from foxglove_schemas_protobuf.FrameTransforms_pb2 import FrameTransforms
from foxglove_schemas_protobuf.JointStates_pb2 import JointStates

from domain.robot_model.kinematics import ArmKinematics
from services.common.feeds import Feed
from services.foxglove.live import (
    FEED_TOPICS,
    LIVE_TOPICS,
    STATE,
    STEREO,
    WRENCH,
    Demand,
    LiveChannels,
)
from telerobot.v1 import force_sensor_pb2 as fs_pb
from telerobot.v1 import stereo_camera_pb2 as sc_pb
from telerobot.v1 import types_pb2
from tests.conftest import wait_for
from tests.fake_calls import FakeCall
from tests.foxglove.test_channels import T0, stereo_header, world_poses
from tests.foxglove.ws_client import FoxgloveClient
from wire import convert
from wire import foxglove as fx


class Changes:
    """Demand's on_change calls, in order."""

    def __init__(self):
        self.calls: list[tuple[str, bool]] = []
        self.lock = threading.Lock()

    def __call__(self, feed: str, wanted: bool) -> None:
        with self.lock:
            self.calls.append((feed, wanted))


def test_a_feed_is_wanted_while_any_client_watches_any_of_its_topics():
    changes = Changes()
    demand = Demand(changes)
    demand.subscribed(1, fx.TF)
    demand.subscribed(2, fx.JOINT_STATES)  # the same feed: no change
    demand.subscribed(1, "/not/ours")  # a topic of no feed: ignored
    assert changes.calls == [(STATE, True)] and demand.wanted(STATE)
    demand.unsubscribed(1, fx.TF)
    assert changes.calls == [(STATE, True)]
    demand.unsubscribed(2, fx.JOINT_STATES)
    assert changes.calls == [(STATE, True), (STATE, False)] and not demand.wanted(STATE)
    demand.subscribed(3, fx.LEFT_IMAGE)
    demand.subscribed(3, fx.FORCE_ARROW)
    assert changes.calls[2:] == [(STEREO, True), (WRENCH, True)]
    assert {t for topics in FEED_TOPICS.values() for t in topics} == set(LIVE_TOPICS)


@pytest.fixture
def live():
    """A live view's server and channels in their own context (nothing flows until a client
    subscribes), with Demand recording what the clients ask for."""
    context = foxglove.Context()
    channels = LiveChannels(context)
    changes = Changes()
    server = foxglove.start_server(port=0, context=context, server_listener=Demand(changes))
    yield channels, changes, f"ws://127.0.0.1:{server.port}"
    server.stop()
    channels.close()


def state_at(q: np.ndarray, stamp_ns: int) -> types_pb2.RobotState:
    kinematics = ArmKinematics()
    return types_pb2.RobotState(
        sample_time=convert.timestamp(stamp_ns), joint_positions_rad=q.tolist(),
        joint_velocities_rad_per_s=[0.0] * 6,
        flange_pose=convert.pose_to_proto(kinematics.flange_pose(q)),
        tool_pose=convert.pose_to_proto(kinematics.tool_pose(q)))


def test_a_client_sees_every_channel_advertised_and_gets_what_it_subscribed_to(live):
    channels, changes, url = live
    kinematics = ArmKinematics()
    with FoxgloveClient(url) as client:
        client.wait_advertised(LIVE_TOPICS)
        for topic, message_class in LIVE_TOPICS.items():
            advertised = client.channels[topic]
            assert advertised["encoding"] == "protobuf"
            assert advertised["schemaName"] == message_class.DESCRIPTOR.full_name
        client.subscribe([fx.TF, fx.JOINT_STATES])
        wait_for(lambda: changes.calls == [(STATE, True)], timeout_s=5, what="the demand")
        q = kinematics.home_q + 0.1
        channels.robot_state(state_at(q, T0))
        channels.wrench(fs_pb.WrenchSample(sample_time=convert.timestamp(T0)))  # not watched
        client.collect(lambda got: fx.TF in got and fx.JOINT_STATES in got, timeout_s=5)
        ((stamp, data),) = client.received[fx.TF]
        assert stamp == T0
        poses = world_poses(FrameTransforms.FromString(data))
        assert np.allclose(poses[fx.TOOL_FRAME].homogeneous,
                           kinematics.tool_pose(q).homogeneous, atol=1e-9)
        joints = JointStates.FromString(client.received[fx.JOINT_STATES][0][1])
        assert [j.position for j in joints.joints] == pytest.approx(q.tolist())
        # Only what has a subscriber is converted and sent.
        assert channels.published == {fx.TF: 1, fx.JOINT_STATES: 1}
        client.unsubscribe_all()
        wait_for(lambda: changes.calls[-1] == (STATE, False), timeout_s=5, what="unsubscribed")


def test_the_cameras_images_and_calibration_flow_and_their_frames_join_tf(live):
    channels, _, url = live
    header = stereo_header(64, 48)
    image = np.zeros((48, 64, 3), np.uint8)
    image[10:20, 30:40] = 255
    jpeg = cv2.imencode(".jpg", image)[1].tobytes()
    pair = sc_pb.StereoPair(left_image=jpeg, right_image=jpeg,
                            left_capture_time=convert.timestamp(T0),
                            right_capture_time=convert.timestamp(T0 + 5))
    with FoxgloveClient(url) as client:
        client.wait_advertised(LIVE_TOPICS)
        topics = [*FEED_TOPICS[STEREO], fx.TF]
        client.subscribe(topics)
        wait_for(lambda: all(channels._channels[t].has_sinks() for t in topics), timeout_s=5,
                 what="the subscriptions")
        channels.set_cameras(header)
        channels.stereo_pair(pair)
        channels.robot_state(state_at(ArmKinematics().home_q, T0))
        client.collect(lambda got: all(t in got for t in topics), timeout_s=5)
    from foxglove_schemas_protobuf.CameraCalibration_pb2 import CameraCalibration
    from foxglove_schemas_protobuf.CompressedImage_pb2 import CompressedImage

    left = CompressedImage.FromString(client.received[fx.LEFT_IMAGE][0][1])
    decoded = cv2.imdecode(np.frombuffer(left.data, np.uint8), cv2.IMREAD_COLOR)
    assert left.format == "jpeg" and decoded.shape == (48, 64, 3)
    calibration = CameraCalibration.FromString(client.received[fx.RIGHT_CALIBRATION][0][1])
    assert (calibration.width, calibration.height) == (64, 48)
    assert calibration.K[0] == pytest.approx(header.right.fx_px)
    frames = {t.child_frame_id for t in
              FrameTransforms.FromString(client.received[fx.TF][0][1]).transforms}
    assert {fx.LEFT_CAMERA_FRAME, fx.RIGHT_CAMERA_FRAME} <= frames


def test_a_feed_opens_while_wanted_closes_when_not_and_reopens_after_an_error():
    calls: list[FakeCall] = []
    handled = []

    def open_stream():
        calls.append(FakeCall())
        return calls[-1]

    statuses = []
    feed = Feed("test", open_stream, handled.append,
                lambda name, why: statuses.append((name, why))).start()
    try:
        feed.want(True)
        wait_for(lambda: len(calls) == 1, timeout_s=5, what="the stream opened")
        calls[0].items.put("a")
        wait_for(lambda: handled == ["a"], timeout_s=5, what="a message handled")
        calls[0].items.put(grpc.StatusCode.UNAVAILABLE)  # the service restarting
        wait_for(lambda: len(calls) == 2, timeout_s=5, what="the stream reopened")
        assert feed.error and "UNAVAILABLE" in feed.error
        calls[1].items.put("b")
        wait_for(lambda: handled == ["a", "b"], timeout_s=5, what="the reopened stream")
        assert feed.error is None
        # The viewers were told why it stopped, and that it flows again.
        assert [name for name, _ in statuses] == ["test", "test"]
        assert "UNAVAILABLE" in statuses[0][1] and statuses[1][1] is None
        feed.want(False)
        assert calls[1].cancelled.is_set()
        feed.want(True)
        wait_for(lambda: len(calls) == 3, timeout_s=5, what="opened again when wanted")
    finally:
        feed.stop()
    assert calls[2].cancelled.is_set() and len(calls) == 3


def test_the_live_view_refuses_a_network_address_unless_allowed_and_checks_its_rates(capsys):
    from services.foxglove.__main__ import main

    assert main(["--address", "0.0.0.0:0"]) == 2
    assert "viewers are not authenticated" in capsys.readouterr().err
    assert main(["--address", "127.0.0.1:0", "--stereo-fps", "0"]) == 2
    assert "--stereo-fps must be > 0" in capsys.readouterr().err


def test_a_message_the_view_cannot_show_restarts_the_feed_instead_of_ending_it():
    calls: list[FakeCall] = []

    def open_stream():
        calls.append(FakeCall())
        return calls[-1]

    def handle(message):
        if message == "bad":
            raise ValueError("no Foxglove form")

    feed = Feed("test", open_stream, handle).start()
    try:
        feed.want(True)
        wait_for(lambda: len(calls) == 1, timeout_s=5, what="the stream opened")
        calls[0].items.put("bad")
        wait_for(lambda: len(calls) == 2, timeout_s=5, what="the stream reopened")
        assert calls[0].cancelled.is_set() and "ValueError" in feed.error
    finally:
        feed.stop()
