"""The typed Python clients against the real processes: values, typed errors, the lease,
context managers, streams and the Teleoperate session."""

from __future__ import annotations

import pickle
import threading

import grpc
import numpy as np
import pinocchio as pin
import pytest

from clients.python import (
    AbortedError,
    CommandOutcome,
    ControlMode,
    DecisionClient,
    FailedPreconditionError,
    ForceSensorClient,
    InvalidArgumentError,
    MoveResult,
    OutOfRangeError,
    PermissionDeniedError,
    Pose,
    ProxyRobotClient,
    ReferenceFrame,
    RobotState,
    RobotStatus,
    StereoCameraClient,
    TelerobotError,
    UnavailableError,
)
from clients.python.errors import STATUS_DETAILS_KEY, from_rpc_error
from domain.robot_model.puma560 import HOME_Q
from services.runtime.rpc import error_status
from services.stereo_camera.pattern import read_tick
from telerobot.v1 import decision_server_pb2 as pb
from telerobot.v1 import decision_server_pb2_grpc
from tests.clients.conftest import CAMERA_HEIGHT_PX, CAMERA_WIDTH_PX
from tests.conftest import wait_for
from tests.processes import refused_address


def lease_metadata(client: DecisionClient) -> list[tuple[str, str]]:
    return [("telerobot-lease-id", client.lease.lease_id)]


@pytest.fixture
def operator(station):
    """A DecisionClient holding control, with the arm READY at home."""
    with DecisionClient(station.address) as client:
        client.acquire_control("ann")
        station.ready_at_home(lease_metadata(client))
        yield client
        station.wait_status(RobotStatus.READY)


# -- errors -----------------------------------------------------------------------------------

class FakeRpcError(grpc.RpcError):
    def __init__(self, code, details, trailers=()):
        self._code, self._details, self._trailers = code, details, trailers

    def code(self):
        return self._code

    def details(self):
        return self._details

    def trailing_metadata(self):
        return self._trailers


def test_errors_carry_code_message_and_error_info_reason():
    status = error_status(grpc.StatusCode.OUT_OF_RANGE, "joint 2 past its limit", "JOINT_LIMIT")
    error = from_rpc_error(FakeRpcError(
        grpc.StatusCode.OUT_OF_RANGE, "joint 2 past its limit",
        ((STATUS_DETAILS_KEY, status.SerializeToString()),)), "/telerobot.v1.ProxyRobot/X")
    assert isinstance(error, OutOfRangeError) and isinstance(error, TelerobotError)
    assert (error.code, error.message, error.reason, error.domain) == (
        grpc.StatusCode.OUT_OF_RANGE, "joint 2 past its limit", "JOINT_LIMIT", "telerobot.v1")
    assert "OUT_OF_RANGE [JOINT_LIMIT] in /telerobot.v1.ProxyRobot/X" in str(error)
    copy = pickle.loads(pickle.dumps(error))
    assert type(copy) is OutOfRangeError and copy.reason == "JOINT_LIMIT"
    bare = from_rpc_error(FakeRpcError(grpc.StatusCode.DATA_LOSS, "lost"))
    assert type(bare) is TelerobotError and bare.reason is None


def test_a_dead_server_fails_at_once_without_retries():
    with ProxyRobotClient(refused_address()) as robot:
        with pytest.raises(UnavailableError) as error:
            robot.move_joints(np.zeros(6), timeout=5)
        assert error.value.code is grpc.StatusCode.UNAVAILABLE
        with pytest.raises(UnavailableError, match="client side"):
            robot.wait_for_ready(0.2)


# -- ProxyRobot and ForceSensor on their own ports --------------------------------------------

@pytest.mark.e2e
def test_proxy_robot_client_on_its_own_port(station, backends):
    lease, metadata = station.acquire()
    station.ready_at_home(metadata)
    with ProxyRobotClient(backends.proxy_address) as robot:
        assert robot.get_status().status in (RobotStatus.READY, RobotStatus.MOVING)
        state = robot.get_state()
        assert isinstance(state, RobotState) and state.joint_positions.shape == (6,)
        np.testing.assert_allclose(state.joint_positions, HOME_Q, atol=1e-3)
        assert isinstance(state.tool_pose, Pose) and isinstance(state.flange_pose, Pose)
        frame = robot.get_tool_frame()
        assert isinstance(frame, Pose)
        assert robot.set_tool_frame(frame).isclose(frame, atol=1e-12)  # a Pose goes out too
        with pytest.raises(InvalidArgumentError) as error:
            robot.move_joints([0.1, 0.0, 0.0])
        assert error.value.code is grpc.StatusCode.INVALID_ARGUMENT
        assert error.value.reason == "BAD_LENGTH" and "6 values" in error.value.message
        assert error.value.method == "/telerobot.v1.ProxyRobot/MoveJointsIncremental"
        with pytest.raises(OutOfRangeError) as error:
            robot.move_joints([1.0, 0, 0, 0, 0, 0])
        assert error.value.reason == "INCREMENT_CAP" and "split it" in error.value.message
        moved = robot.move_joints([0.02, 0, 0, 0, 0, 0])
        assert isinstance(moved, MoveResult)
        np.testing.assert_allclose(moved.target_joint_positions, HOME_Q + [0.02, 0, 0, 0, 0, 0],
                                   atol=1e-3)
        with robot.stream_state(0.01, timeout=10) as states:
            sequences = [next(states).sequence for _ in range(3)]
        assert sequences == sorted(sequences) and len(set(sequences)) == 3
    station.wait_status(RobotStatus.READY)


@pytest.mark.e2e
def test_force_sensor_client_on_its_own_port(station, backends):
    with ForceSensorClient(backends.sensor_address) as sensor:
        config = sensor.start_reading()
        assert config.reading and config.period_s == pytest.approx(0.001)
        sample = sensor.get_wrench()
        assert sample.force.shape == (3,) and sample.wrench.shape == (6,)
        with sensor.stream_wrench(10, batch_size=2, timeout=10) as stream:
            batches = [next(stream) for _ in range(2)]
        samples = [s for batch in batches for s in batch.samples]
        assert [len(b.samples) for b in batches] == [2, 2]
        assert set(np.diff([s.sequence for s in samples])) == {10}
        with pytest.raises(InvalidArgumentError) as error:
            sensor.tare(5.0)
        assert "duration" in error.value.message
        with pytest.raises(ValueError):
            sensor.set_sensor_config()


# -- the DecisionServer: lease, facades, context manager --------------------------------------

@pytest.mark.e2e
def test_the_lease_goes_in_metadata_and_errors_are_typed(station):
    with DecisionClient(station.address) as client:
        with pytest.raises(FailedPreconditionError) as error:
            client.robot.move_joints(np.zeros(6))
        assert error.value.reason == "NO_CONTROL" and "control lock" in error.value.message
        assert error.value.method == "/telerobot.v1.ProxyRobot/MoveJointsIncremental"
        with pytest.raises(RuntimeError, match="acquire_control"):
            client.renew_control()

        lease = client.acquire_control("ann", lease_duration_s=10)
        assert client.lease is lease and lease.lease_id and lease.operator_id == "ann"
        holders = client.get_control_state().holders
        assert [h.operator_id for h in holders] == ["ann"]
        with DecisionClient(station.address) as rival:
            with pytest.raises(AbortedError) as error:
                rival.acquire_control("bob")
            assert error.value.reason == "CONTROL_HELD" and "ann" in error.value.message
            with pytest.raises(FailedPreconditionError):
                rival.set_indexing(True)

        station.ready_at_home(lease_metadata(client))
        moved = client.robot.move_joints([0, 0.02, 0, 0, 0, 0])
        np.testing.assert_allclose(moved.target_joint_positions[1], HOME_Q[1] + 0.02, atol=1e-3)
        # Through the DecisionServer a backend's error keeps its code and message.
        with pytest.raises(OutOfRangeError, match="cap"):
            client.robot.move_cartesian((0.2, 0, 0), frame=ReferenceFrame.BASE)
        assert client.set_indexing(False) is False
        assert client.renew_control() >= lease.expire_time_ns
        station.wait_status(RobotStatus.READY)
    # Leaving the block released the lease and closed the channel.
    assert not station.decisions.GetControlState(pb.GetControlStateRequest()).state.holders
    with pytest.raises(RuntimeError, match="closed"):
        client.get_control_state()
    with pytest.raises(ValueError, match="closed channel"):
        decision_server_pb2_grpc.DecisionServerStub(client.channel).GetControlState(
            pb.GetControlStateRequest())


@pytest.mark.e2e
def test_a_collaborative_group_is_joined_with_its_secret(station):
    with DecisionClient(station.address) as first, DecisionClient(station.address) as second:
        lease = first.acquire_control("ann", ControlMode.COLLABORATIVE, group="lab")
        assert lease.group_secret
        with pytest.raises(PermissionDeniedError) as error:
            second.acquire_control("bob", ControlMode.COLLABORATIVE, group="lab")
        assert error.value.reason == "BAD_GROUP_SECRET"
        joined = second.acquire_control("bob", ControlMode.COLLABORATIVE, group="lab",
                                        group_secret=lease.group_secret)
        assert joined.group_secret == lease.group_secret
        assert {h.operator_id for h in first.get_control_state().holders} == {"ann", "bob"}


@pytest.mark.e2e
def test_lanes_and_forwarded_camera_errors(station):
    with DecisionClient(station.address, lane="low") as client:
        assert client.get_control_state(lane="high") is not None
        with pytest.raises(ValueError, match="lane"):
            client.get_control_state(lane="urgent")
        # This station has no camera behind its StereoCamera facade: a typed UNAVAILABLE.
        with pytest.raises(UnavailableError):
            client.camera.get_stream_info(timeout=5)


@pytest.mark.e2e
def test_a_shared_channel_stays_open(station):
    with grpc.insecure_channel(station.address) as channel:
        with DecisionClient(channel) as client:
            assert client.robot.get_status().status is not None
        assert not station.decisions.GetControlState(pb.GetControlStateRequest()).state.holders
        with ProxyRobotClient(channel) as robot:  # the channel still works
            assert isinstance(robot.get_status().status, RobotStatus)


@pytest.mark.e2e
def test_events_stream_sees_the_lock_change(station):
    stop = threading.Event()

    def change_hands(client: DecisionClient) -> None:
        # Until the watcher has seen it: its subscription may reach the server after the
        # first change, and the client cannot see when it does, so the change is repeated
        # every 50 ms (Event.wait: no later than the watcher has seen it).
        while not stop.is_set():
            client.acquire_control("ann")
            stop.wait(0.05)
            client.release_control()
            stop.wait(0.05)

    with DecisionClient(station.address) as watcher, DecisionClient(station.address) as ann:
        with watcher.stream_events(timeout=20) as events:
            changer = threading.Thread(target=change_hands, args=(ann,))
            changer.start()
            try:
                for event in events:
                    if (event.WhichOneof("event") == "control_changed"
                            and event.control_changed.state.holders):
                        break
            finally:
                stop.set()
                changer.join()
        assert [h.operator_id for h in event.control_changed.state.holders] == ["ann"]


# -- Teleoperate --------------------------------------------------------------------------------

@pytest.mark.e2e
def test_teleoperate_session_sends_commands_and_gets_acks(station, operator):
    received = []
    assert operator.sensor.start_reading().reading  # the facade carries the lease too
    with operator.teleoperate(watchdog_timeout_s=0.5, on_ack=received.append) as session:
        assert session.session_id and session.mapping is ReferenceFrame.BASE
        assert session.watchdog_timeout_s == pytest.approx(0.5)
        wait_for(lambda: session.heartbeat().force is not None, 5,
                 "the acks to carry a wrench (the server to have a fresh one)")
        received.clear()
        ack = session.send((0, 0, 0.003))
        assert ack.sequence == 1 and ack.outcome is CommandOutcome.APPLIED and ack.applied
        assert isinstance(ack.tool_pose, Pose) and ack.force.shape == (3,)
        assert ack.status in (RobotStatus.MOVING, RobotStatus.READY)
        assert ack.round_trip_s > 0 and ack.receive_time_ns <= ack.apply_time_ns
        indexed = session.send((0, 0, 0.003), clutch=True)
        assert indexed.sequence == 2 and indexed.outcome is CommandOutcome.INDEXED
        rejected = session.send((0.2, 0, 0))  # a refused command is an ack, not an error
        assert rejected.outcome is CommandOutcome.REJECTED and "cap" in rejected.detail
        heartbeat = session.heartbeat()
        assert heartbeat.sequence == 0 and heartbeat.outcome is CommandOutcome.HEARTBEAT
        sent = [session.send_nowait((0, 0.001, 0), pin.utils.rotate("z", 0.005))
                for _ in range(5)]
        assert sent == [4, 5, 6, 7, 8]
        session.heartbeat()  # acks come in order: the pipelined ones are all in by now
        assert [a.sequence for a in received] == [1, 2, 3, 0, 4, 5, 6, 7, 8, 0]
        assert all(a.applied for a in received[4:9])
        assert session.latest_ack is received[-1]
    assert session.closed and session.error is None
    with pytest.raises(RuntimeError, match="closed"):
        session.send((0, 0, 0))


@pytest.mark.e2e
def test_teleoperate_needs_the_lease(station):
    with DecisionClient(station.address) as client:
        with pytest.raises(FailedPreconditionError) as error:
            client.teleoperate()
        assert error.value.reason == "NO_CONTROL"
        assert error.value.method == "/telerobot.v1.DecisionServer/Teleoperate"


@pytest.mark.e2e
def test_losing_the_lease_ends_the_session_with_aborted(station, operator):
    session = operator.teleoperate(watchdog_timeout_s=0.5)
    assert session.send((0, 0, 0.002)).applied
    station.decisions.ReleaseControl(pb.ReleaseControlRequest(lease_id=operator.lease.lease_id))
    with pytest.raises(AbortedError) as error:
        session.send((0, 0, 0.002))
    assert error.value.reason == "CONTROL_LOST" and "lost" in error.value.message
    assert isinstance(session.error, AbortedError)
    with pytest.raises(AbortedError):  # the session is over; a new one is needed
        session.heartbeat()
    session.close()


@pytest.mark.e2e
def test_a_malformed_command_ends_the_stream_with_invalid_argument(station, operator):
    with operator.teleoperate(watchdog_timeout_s=0.5) as session:
        with pytest.raises(InvalidArgumentError) as error:
            session.send((0, 0, 0), 2 * np.eye(3))
        assert error.value.reason == "NOT_A_ROTATION"
    with pytest.raises(ValueError):  # shapes are checked before anything is sent
        session.send((0, 0))


# -- StereoCamera -------------------------------------------------------------------------------

def test_stereo_camera_client(camera_address):
    with StereoCameraClient(camera_address) as camera:
        header = camera.get_stream_info()
        assert (header.width_px, header.height_px) == (CAMERA_WIDTH_PX, CAMERA_HEIGHT_PX)
        snapshot = camera.get_snapshot()
        assert snapshot.left.shape == (CAMERA_HEIGHT_PX, CAMERA_WIDTH_PX, 3)
        assert read_tick(snapshot.left) == read_tick(snapshot.right) == snapshot.sequence
        with camera.stream_pairs(timeout=20) as stream:
            frames = [next(stream) for _ in range(3)]
            assert stream.header.width_px == CAMERA_WIDTH_PX
        sequences = [f.sequence for f in frames]
        assert sequences == sorted(set(sequences))
        assert all(read_tick(f.left) == f.sequence for f in frames)
        with pytest.raises(InvalidArgumentError) as error:
            next(iter(camera.stream_pairs(jpeg_quality=500, timeout=20)))
        assert "quality" in error.value.message.lower()
        raw = camera.get_snapshot(decode=False)
        assert raw.left is None and raw.pair.left_image
