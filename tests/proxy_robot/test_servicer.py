"""ProxyRobot over a real in-process gRPC server, on the fake arm and fake clock: what a client
sees, status codes included. The test thread drives the proxy's monitor and setpoints between
calls (tests/proxy_robot/conftest.py's Rig)."""

from __future__ import annotations

import math
import queue

import grpc
import numpy as np
import pytest

from clients.python.values import ArmInfo
from domain.robot_model.description import arm_description
from services.proxy_robot import core as core_module
from services.proxy_robot import servicer as servicer_module
from services.proxy_robot.servicer import ProxyRobotServicer
from services.proxy_robot.status import RobotStatus
from services.runtime.server import binding, create_server
from telerobot.v1 import proxy_robot_pb2 as pb
from telerobot.v1 import proxy_robot_pb2_grpc, types_pb2
from tests.fakes.arm_link import HOLD

BASE = types_pb2.REFERENCE_FRAME_BASE
TOOL = types_pb2.REFERENCE_FRAME_TOOL
SUBSCRIBE_TIMEOUT_S = 5.0  # only a deadline to fail by: the server's handler thread subscribes


@pytest.fixture
def robot(rig):
    server, port = create_server(
        "127.0.0.1:0", [binding(proxy_robot_pb2_grpc, "ProxyRobot", ProxyRobotServicer(rig.core))])
    server.start()
    channel = grpc.insecure_channel(f"127.0.0.1:{port}")
    yield proxy_robot_pb2_grpc.ProxyRobotStub(channel)
    channel.close()
    server.stop(0)


def watch_subscriptions(fanout, monkeypatch) -> queue.Queue:
    """Each subscription made on `fanout` from now on, as it is made (a stream's handler runs on
    a server thread: the test waits for it to subscribe before anything is published)."""
    made: queue.Queue = queue.Queue()
    attach = fanout.attach

    def attach_and_tell(subscription):
        attach(subscription)
        made.put(subscription)
        return subscription

    monkeypatch.setattr(fanout, "attach", attach_and_tell)
    return made


def code_of(call) -> grpc.StatusCode:
    with pytest.raises(grpc.RpcError) as error:
        call()
    return error.value.code()


def ready(robot) -> None:
    robot.Connect(pb.ConnectRequest(), timeout=5)
    reply = robot.Initialize(pb.InitializeRequest(), timeout=5)
    assert reply.status == types_pb2.ROBOT_STATUS_READY


def test_connect_initialize_and_read_state(rig, robot):
    assert robot.GetStatus(pb.GetStatusRequest()).status == types_pb2.ROBOT_STATUS_NOT_CONNECTED
    assert code_of(lambda: robot.GetState(pb.GetStateRequest())) == (
        grpc.StatusCode.FAILED_PRECONDITION)
    ready(robot)
    rig.run(0.01)
    state = robot.GetState(pb.GetStateRequest(), timeout=5).state
    arm = rig.arm.state()
    assert state.status == types_pb2.ROBOT_STATUS_READY
    assert state.sequence == arm.sequence > 0  # the latest sample, taken at this tick
    assert state.sample_time.ToNanoseconds() == arm.sample_time_ns == rig.clock.time_ns()
    np.testing.assert_allclose(state.joint_positions_rad, arm.joint_positions_rad, atol=1e-12)
    assert len(state.tool_pose.rotation.row_major) == 9
    frame = robot.GetToolFrame(pb.GetToolFrameRequest()).flange_to_tool
    assert math.isclose(frame.position_m.z, 0.1, abs_tol=1e-9)  # the peg's tip
    status = robot.GetStatus(pb.GetStatusRequest())
    assert status.status == types_pb2.ROBOT_STATUS_READY
    assert status.change_time.ToNanoseconds() <= rig.clock.time_ns()


def test_arm_info_is_what_the_arms_file_declares(robot):
    """Answered before Connect: a client learns the arm before it drives it."""
    info = ArmInfo.from_proto(robot.GetArmInfo(pb.GetArmInfoRequest(), timeout=5))
    arm = arm_description("puma560")
    assert info.name == "puma560"
    assert info.joint_names == arm.joint_names == tuple(f"joint{i}" for i in range(1, 7))
    np.testing.assert_array_equal(info.lower_limits, arm.lower)
    np.testing.assert_array_equal(info.upper_limits, arm.upper)
    np.testing.assert_array_equal(info.velocity_limits, arm.max_velocity)
    np.testing.assert_array_equal(info.torque_limits, [97.6, 186.4, 89.4, 24.2, 20.1, 21.3])
    np.testing.assert_array_equal(info.home, arm.home_q)
    np.testing.assert_allclose(info.default_flange_to_tool.translation, [0, 0, 0.1], atol=1e-12)


def test_a_joint_move_of_the_wrong_length_names_the_arms_count(rig, robot):
    ready(robot)
    with pytest.raises(grpc.RpcError) as raised:
        robot.MoveJointsIncremental(pb.MoveJointsIncrementalRequest(
            delta_joint_positions_rad=[0.01] * 7))
    assert raised.value.code() == grpc.StatusCode.INVALID_ARGUMENT
    assert raised.value.details() == "delta_joint_positions_rad needs 6 values, got 7"


def test_bad_requests_get_the_right_codes(rig, robot):
    move = robot.MoveCartesianIncremental
    assert code_of(lambda: move(pb.MoveCartesianIncrementalRequest(frame=BASE))) == (
        grpc.StatusCode.FAILED_PRECONDITION)
    ready(robot)
    commands_before = len(rig.arm.commands)
    skewed = types_pb2.Matrix3(row_major=[1, 0.2, 0, 0, 1, 0, 0, 0, 1])
    cases = {
        grpc.StatusCode.INVALID_ARGUMENT: [
            lambda: move(pb.MoveCartesianIncrementalRequest(delta_rotation=skewed, frame=TOOL)),
            lambda: move(pb.MoveCartesianIncrementalRequest(
                delta_position_m=types_pb2.Vector3(x=float("nan")), frame=TOOL)),
            lambda: move(pb.MoveCartesianIncrementalRequest()),  # no frame
            lambda: robot.MoveJointsIncremental(
                pb.MoveJointsIncrementalRequest(delta_joint_positions_rad=[0.1] * 5)),
            lambda: robot.SetToolFrame(pb.SetToolFrameRequest(flange_to_tool=types_pb2.Pose(
                rotation=types_pb2.Matrix3(row_major=[1] * 9)))),
            lambda: next(robot.StreamState(pb.StreamStateRequest(period={"seconds": -1}))),
        ],
        grpc.StatusCode.OUT_OF_RANGE: [
            lambda: robot.MoveJointsIncremental(
                pb.MoveJointsIncrementalRequest(delta_joint_positions_rad=[0, 0, 0, 0, 0, 1.0])),
            lambda: move(pb.MoveCartesianIncrementalRequest(
                delta_position_m=types_pb2.Vector3(z=0.2), frame=BASE)),
        ],
    }
    for code, calls in cases.items():
        for call in calls:
            assert code_of(call) == code
    assert robot.GetStatus(pb.GetStatusRequest()).status == types_pb2.ROBOT_STATUS_READY
    assert len(rig.arm.commands) == commands_before  # nothing reached the arm


def test_cartesian_move_answers_the_target_and_the_arm_gets_there(rig, robot):
    ready(robot)
    before = robot.GetState(pb.GetStateRequest()).state.tool_pose.position_m
    reply = robot.MoveCartesianIncremental(pb.MoveCartesianIncrementalRequest(
        delta_position_m=types_pb2.Vector3(z=0.01), frame=BASE), timeout=5)
    assert reply.applied_fraction == 1.0
    assert math.isclose(reply.target_tool_pose.position_m.z - before.z, 0.01, abs_tol=1e-4)
    assert robot.GetStatus(pb.GetStatusRequest()).status == types_pb2.ROBOT_STATUS_MOVING
    rig.run_until_status(RobotStatus.READY)
    rig.run(0.2)  # settled
    after = robot.GetState(pb.GetStateRequest()).state
    assert math.isclose(after.tool_pose.position_m.z - before.z, 0.01, abs_tol=1e-4)
    np.testing.assert_allclose(after.joint_positions_rad, reply.target_joint_positions_rad,
                               atol=1e-4)


def test_state_stream_honours_the_period(rig, robot, monkeypatch):
    # A queue that holds every sample, so the driver can publish them all before the server
    # reads: the pacing is under test here, not the drop policy.
    monkeypatch.setattr(servicer_module, "STATE_QUEUE", 1000)
    subscriptions = watch_subscriptions(rig.core.states, monkeypatch)
    ready(robot)
    stream = robot.StreamState(pb.StreamStateRequest(period={"nanos": 20_000_000}), timeout=10)
    subscriptions.get(timeout=SUBSCRIBE_TIMEOUT_S)
    rig.run(0.2)  # 20 samples, 10 ms apart
    stamps = [next(stream).state.sample_time.ToNanoseconds() for _ in range(6)]
    stream.cancel()
    assert np.diff(stamps).tolist() == [20_000_000] * 5


def test_state_stream_ends_unavailable_when_the_link_drops(rig, robot, monkeypatch):
    subscriptions = watch_subscriptions(rig.core.states, monkeypatch)
    ready(robot)
    stream = robot.StreamState(pb.StreamStateRequest(), timeout=10)
    subscriptions.get(timeout=SUBSCRIBE_TIMEOUT_S)
    rig.run(core_module.STATE_PERIOD_S)  # one monitor sample
    assert next(stream).state.status == types_pb2.ROBOT_STATUS_READY
    rig.arm.shut_down()
    rig.run_until_status(RobotStatus.NOT_CONNECTED, timeout_s=0.01)
    with pytest.raises(grpc.RpcError) as error:
        for _ in stream:
            pass
    assert error.value.code() == grpc.StatusCode.UNAVAILABLE


def test_event_stream_reports_status_changes_and_moves(rig, robot, monkeypatch):
    subscriptions = watch_subscriptions(rig.core.events, monkeypatch)
    events = robot.StreamRobotEvents(pb.StreamRobotEventsRequest(kinds=[
        pb.ROBOT_EVENT_KIND_STATUS_CHANGED, pb.ROBOT_EVENT_KIND_MOVED]), timeout=20)
    subscriptions.get(timeout=SUBSCRIBE_TIMEOUT_S)
    ready(robot)
    robot.MoveJointsIncremental(pb.MoveJointsIncrementalRequest(
        delta_joint_positions_rad=[0.05, 0, 0, 0, 0, 0]), timeout=5)
    rig.run_until_status(RobotStatus.READY)
    received = []
    for event in events:
        received.append(event)
        if event.WhichOneof("event") == "moved":
            break
    events.cancel()
    statuses = [types_pb2.RobotStatus.Name(e.status_changed.status) for e in received
                if e.WhichOneof("event") == "status_changed"]
    assert statuses == ["ROBOT_STATUS_CONNECTED", "ROBOT_STATUS_INITIALIZING",
                        "ROBOT_STATUS_READY", "ROBOT_STATUS_MOVING", "ROBOT_STATUS_READY"]
    moved = received[-1].moved
    np.testing.assert_array_equal(moved.joint_positions_rad,
                                  rig.core.snapshot().joint_positions_rad)
    sequences = [e.sequence for e in received]
    assert sequences == list(range(sequences[0], sequences[0] + len(sequences)))
    assert received[-1].event_time.ToNanoseconds() == rig.clock.time_ns()


def test_emergency_stop_and_reset(rig, robot):
    ready(robot)
    robot.MoveJointsIncremental(pb.MoveJointsIncrementalRequest(
        delta_joint_positions_rad=[0.3, 0, 0, 0, 0, 0]))
    rig.run(0.05)
    stop = robot.EmergencyStop(pb.EmergencyStopRequest(reason="test"), timeout=5)
    assert stop.status == types_pb2.ROBOT_STATUS_ESTOPPED
    assert stop.stop_time.ToNanoseconds() == rig.clock.time_ns()
    assert rig.arm.commands[-1].kind == HOLD
    rig.run(0.002)
    assert rig.arm.state().hold_latched
    assert code_of(lambda: robot.MoveJointsIncremental(pb.MoveJointsIncrementalRequest(
        delta_joint_positions_rad=[0.01, 0, 0, 0, 0, 0]))) == grpc.StatusCode.FAILED_PRECONDITION
    assert robot.Reset(pb.ResetRequest(), timeout=5).status == types_pb2.ROBOT_STATUS_READY
    assert not rig.arm.state().hold_latched


def test_a_stop_latched_at_the_hardware_shows_in_the_status(rig, robot):
    ready(robot)
    rig.arm.emergency_stop_link().stop()  # the band, past the driver
    rig.run(core_module.STATE_PERIOD_S)  # the monitor's next sample sees the latch
    status = robot.GetStatus(pb.GetStatusRequest())
    assert status.status == types_pb2.ROBOT_STATUS_ESTOPPED
    assert "at the hardware" in status.reason
    assert robot.Reset(pb.ResetRequest(), timeout=5).status == types_pb2.ROBOT_STATUS_READY


def test_hold_answers_the_braking_target(rig, robot):
    ready(robot)
    robot.MoveJointsIncremental(pb.MoveJointsIncrementalRequest(
        delta_joint_positions_rad=[0.4, 0, 0, 0, 0, 0]))
    rig.run(0.1)
    position = rig.arm.state().joint_positions_rad[0]
    target = robot.Hold(pb.HoldRequest(), timeout=5).target_joint_positions_rad
    assert position < target[0] < position + 0.06  # at most the braking distance from 1 rad/s
    rig.run_until_status(RobotStatus.READY)
    assert robot.GetStatus(pb.GetStatusRequest()).status == types_pb2.ROBOT_STATUS_READY


def test_the_local_moves_answer_as_grpc_does(rig, robot, tmp_path):
    """The DecisionServer's moves on the local socket (wire/local_call.py) reach the same
    handlers behind the same checks: the same replies, and each refusal's class and reason."""
    from wire.errors import FailedPreconditionError, InvalidArgumentError, OutOfRangeError
    from wire.local_call import LocalCallClient, LocalCallServer

    server = LocalCallServer(tmp_path / "moves.sock",
                             servicer_module.local_moves(ProxyRobotServicer(rig.core)))
    server.start()
    client = LocalCallClient(server.path, timeout_s=5.0)
    path = "/telerobot.v1.ProxyRobot/{}".format

    def move(request):
        return client.call(path("MoveCartesianIncremental"), request,
                           pb.MoveCartesianIncrementalResponse)

    try:
        with pytest.raises(FailedPreconditionError):
            move(pb.MoveCartesianIncrementalRequest(frame=BASE))  # not READY
        ready(robot)
        commands_before = len(rig.arm.commands)
        skewed = types_pb2.Matrix3(row_major=[1, 0.2, 0, 0, 1, 0, 0, 0, 1])
        for request, error in (
                (pb.MoveCartesianIncrementalRequest(delta_rotation=skewed, frame=TOOL),
                 InvalidArgumentError),
                (pb.MoveCartesianIncrementalRequest(frame=99), InvalidArgumentError),
                (pb.MoveCartesianIncrementalRequest(
                    delta_position_m=types_pb2.Vector3(z=0.2), frame=BASE), OutOfRangeError)):
            with pytest.raises(error):
                move(request)
        with pytest.raises(InvalidArgumentError, match="needs 6 values, got 7"):
            client.call(path("MoveJointsIncremental"), pb.MoveJointsIncrementalRequest(
                delta_joint_positions_rad=[0.01] * 7), pb.MoveJointsIncrementalResponse)
        assert len(rig.arm.commands) == commands_before  # nothing reached the arm
        local = move(pb.MoveCartesianIncrementalRequest(
            delta_position_m=types_pb2.Vector3(z=0.01), frame=BASE))
        over_grpc = robot.MoveCartesianIncremental(pb.MoveCartesianIncrementalRequest(
            delta_position_m=types_pb2.Vector3(z=0.01), frame=BASE), timeout=5)
        assert local.applied_fraction == over_grpc.applied_fraction == 1.0
        assert math.isclose(over_grpc.target_tool_pose.position_m.z
                            - local.target_tool_pose.position_m.z, 0.01, abs_tol=1e-4)
    finally:
        client.close()
        server.stop()
