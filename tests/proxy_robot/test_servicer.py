"""ProxyRobot over a real in-process gRPC server, on the real simulated arm: what a client sees,
status codes included."""

from __future__ import annotations

import math
import threading

import grpc
import pytest

from services.proxy_robot.core import ProxyRobotCore
from services.proxy_robot.servicer import ProxyRobotServicer
from services.runtime.server import binding, create_server
from services.world.shm_link import SharedMemoryArmLink
from telerobot.v1 import proxy_robot_pb2 as pb
from telerobot.v1 import proxy_robot_pb2_grpc, types_pb2
from tests.proxy_robot.conftest import send_home
from tests.proxy_robot.test_core import wait_for

BASE = types_pb2.REFERENCE_FRAME_BASE
TOOL = types_pb2.REFERENCE_FRAME_TOOL


@pytest.fixture
def robot(world):
    send_home(world)
    core = ProxyRobotCore(lambda: SharedMemoryArmLink(world.shm_name))
    server, port = create_server(
        "127.0.0.1:0", [binding(proxy_robot_pb2_grpc, "ProxyRobot", ProxyRobotServicer(core))])
    server.start()
    channel = grpc.insecure_channel(f"127.0.0.1:{port}")
    stub = proxy_robot_pb2_grpc.ProxyRobotStub(channel)
    stub.core = core  # for tests that must wait on the server side
    yield stub
    channel.close()
    server.stop(0)
    if core.status[0].name in ("ESTOPPED", "FAULT"):
        core.reset()
    core.close()


def code_of(call) -> grpc.StatusCode:
    with pytest.raises(grpc.RpcError) as error:
        call()
    return error.value.code()


def ready(robot) -> None:
    robot.Connect(pb.ConnectRequest(), timeout=5)
    reply = robot.Initialize(pb.InitializeRequest(), timeout=5)
    assert reply.status == types_pb2.ROBOT_STATUS_READY


def test_connect_initialize_and_read_state(robot):
    assert robot.GetStatus(pb.GetStatusRequest()).status == types_pb2.ROBOT_STATUS_NOT_CONNECTED
    assert code_of(lambda: robot.GetState(pb.GetStateRequest())) == (
        grpc.StatusCode.FAILED_PRECONDITION)
    ready(robot)
    state = robot.GetState(pb.GetStateRequest(), timeout=5).state
    assert len(state.joint_positions_rad) == 6 and len(state.tool_pose.rotation.row_major) == 9
    assert state.sample_time.seconds > 0 and state.sequence > 0
    frame = robot.GetToolFrame(pb.GetToolFrameRequest()).flange_to_tool
    assert math.isclose(frame.position_m.z, 0.1, abs_tol=1e-9)  # the peg's tip


def test_bad_requests_get_the_right_codes(robot):
    move = robot.MoveCartesianIncremental
    assert code_of(lambda: move(pb.MoveCartesianIncrementalRequest(frame=BASE))) == (
        grpc.StatusCode.FAILED_PRECONDITION)
    ready(robot)
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


def test_cartesian_move_answers_the_target(robot):
    ready(robot)
    before = robot.GetState(pb.GetStateRequest()).state.tool_pose.position_m
    reply = robot.MoveCartesianIncremental(pb.MoveCartesianIncrementalRequest(
        delta_position_m=types_pb2.Vector3(z=0.01), frame=BASE), timeout=5)
    assert reply.applied_fraction == 1.0
    assert math.isclose(reply.target_tool_pose.position_m.z - before.z, 0.01, abs_tol=1e-4)


def test_state_stream_honours_the_period(robot):
    ready(robot)
    stream = robot.StreamState(pb.StreamStateRequest(period={"nanos": 20_000_000}), timeout=10)
    times = []
    for message in stream:
        stamp = message.state.sample_time
        times.append(stamp.seconds + stamp.nanos * 1e-9)
        if len(times) == 6:
            break
    stream.cancel()
    gaps = [b - a for a, b in zip(times, times[1:], strict=False)]
    assert all(gap >= 0.0199 for gap in gaps), gaps


def test_event_stream_reports_status_changes_and_moves(robot):
    events = robot.StreamRobotEvents(pb.StreamRobotEventsRequest(kinds=[
        pb.ROBOT_EVENT_KIND_STATUS_CHANGED, pb.ROBOT_EVENT_KIND_MOVED]), timeout=20)
    received: list[pb.StreamRobotEventsResponse] = []
    done = threading.Event()

    def read():
        for event in events:
            received.append(event)
            if event.WhichOneof("event") == "moved":
                done.set()
                return

    threading.Thread(target=read, daemon=True).start()
    wait_for(lambda: robot.core.events.subscriber_count == 1, what="the server's subscription")
    ready(robot)
    robot.MoveJointsIncremental(pb.MoveJointsIncrementalRequest(
        delta_joint_positions_rad=[0.05, 0, 0, 0, 0, 0]), timeout=5)
    assert done.wait(10), received
    events.cancel()
    kinds = [e.WhichOneof("event") for e in received]
    statuses = [types_pb2.RobotStatus.Name(e.status_changed.status) for e in received
                if e.WhichOneof("event") == "status_changed"]
    assert statuses == ["ROBOT_STATUS_CONNECTED", "ROBOT_STATUS_INITIALIZING",
                        "ROBOT_STATUS_READY", "ROBOT_STATUS_MOVING", "ROBOT_STATUS_READY"]
    assert kinds[-1] == "moved"
    sequences = [e.sequence for e in received]
    assert sequences == list(range(sequences[0], sequences[0] + len(sequences)))


def test_emergency_stop_and_reset(robot):
    ready(robot)
    robot.MoveJointsIncremental(pb.MoveJointsIncrementalRequest(
        delta_joint_positions_rad=[0.3, 0, 0, 0, 0, 0]))
    stop = robot.EmergencyStop(pb.EmergencyStopRequest(reason="test"), timeout=5)
    assert stop.status == types_pb2.ROBOT_STATUS_ESTOPPED
    assert code_of(lambda: robot.MoveJointsIncremental(pb.MoveJointsIncrementalRequest(
        delta_joint_positions_rad=[0.01, 0, 0, 0, 0, 0]))) == grpc.StatusCode.FAILED_PRECONDITION
    assert robot.Reset(pb.ResetRequest(), timeout=5).status == types_pb2.ROBOT_STATUS_READY
