"""The emergency-stop band: a real process that latches the stop beside a real ProxyRobot."""

from __future__ import annotations

import subprocess
import sys

import grpc
import numpy as np
import pytest

from clients.python import ProxyRobotClient
from clients.python.values import RobotStatus
from telerobot.v1 import proxy_robot_pb2 as pb
from telerobot.v1 import proxy_robot_pb2_grpc, types_pb2
from tests.conftest import wait_for
from tests.processes import start_service, unique_shm_name
from wire.errors import UnimplementedError


@pytest.fixture
def stubs(backends):
    with (grpc.insecure_channel(backends.proxy_address) as robot_channel,
          grpc.insecure_channel(backends.emergency_address) as band_channel):
        robot = proxy_robot_pb2_grpc.ProxyRobotStub(robot_channel)
        robot.Connect(pb.ConnectRequest(), timeout=5)
        if robot.GetStatus(pb.GetStatusRequest()).status in (
                types_pb2.ROBOT_STATUS_ESTOPPED, types_pb2.ROBOT_STATUS_FAULT):
            robot.Reset(pb.ResetRequest(), timeout=5)
        if robot.GetStatus(pb.GetStatusRequest()).status == types_pb2.ROBOT_STATUS_CONNECTED:
            robot.Initialize(pb.InitializeRequest(), timeout=5)
        yield robot, proxy_robot_pb2_grpc.ProxyRobotStub(band_channel)
        if robot.GetStatus(pb.GetStatusRequest()).status == types_pb2.ROBOT_STATUS_ESTOPPED:
            robot.Reset(pb.ResetRequest(), timeout=5)  # leave the shared arm usable


def joints(robot) -> tuple[np.ndarray, np.ndarray]:
    state = robot.GetState(pb.GetStateRequest()).state
    return np.array(state.joint_positions_rad), np.array(state.joint_velocities_rad_per_s)


@pytest.mark.e2e
def test_the_band_halts_a_moving_arm_and_proxy_robot_reports_the_latch(stubs):
    robot, band = stubs
    start, _ = joints(robot)
    target = robot.MoveJointsIncremental(pb.MoveJointsIncrementalRequest(
        delta_joint_positions_rad=[0.3, 0, 0, 0, 0, 0])).target_joint_positions_rad
    wait_for(lambda: abs(joints(robot)[1][0]) > 0.3, what="the arm to move")

    reply = band.EmergencyStop(pb.EmergencyStopRequest(reason="band test"), timeout=5)

    assert reply.status == types_pb2.ROBOT_STATUS_ESTOPPED and reply.stop_time.seconds > 0
    wait_for(lambda: np.max(np.abs(joints(robot)[1])) < 0.01, what="the arm to halt")
    halted, _ = joints(robot)
    assert 0 < halted[0] - start[0] < target[0] - start[0] - 0.05  # stopped well short
    status = robot.GetStatus(pb.GetStatusRequest())
    assert status.status == types_pb2.ROBOT_STATUS_ESTOPPED
    assert "latched stop" in status.reason
    with pytest.raises(grpc.RpcError) as refused:
        robot.MoveJointsIncremental(pb.MoveJointsIncrementalRequest(
            delta_joint_positions_rad=[0.01, 0, 0, 0, 0, 0]))
    assert refused.value.code() == grpc.StatusCode.FAILED_PRECONDITION
    # Cleared as ever, through ProxyRobot: the arm stays where it stopped.
    assert robot.Reset(pb.ResetRequest(), timeout=5).status == types_pb2.ROBOT_STATUS_READY
    reset_at_ns = robot.GetState(pb.GetStateRequest()).state.sample_time.ToNanoseconds()

    def state_100_ms_later():
        state = robot.GetState(pb.GetStateRequest()).state
        return state if state.sample_time.ToNanoseconds() >= reset_at_ns + 100_000_000 else None

    later = wait_for(state_100_ms_later, what="the arm's samples 100 ms after the reset")
    assert np.max(np.abs(np.array(later.joint_positions_rad) - halted)) < 1e-3


@pytest.mark.e2e
def test_the_python_client_stops_through_the_band(stubs, backends):
    robot, _ = stubs
    with ProxyRobotClient(backends.emergency_address) as band:
        assert band.emergency_stop("client test") == RobotStatus.ESTOPPED
        with pytest.raises(UnimplementedError):
            band.get_status()
    wait_for(lambda: robot.GetStatus(pb.GetStatusRequest()).status
             == types_pb2.ROBOT_STATUS_ESTOPPED, what="ProxyRobot to see the latch")


@pytest.mark.e2e
def test_the_band_serves_only_emergency_stop(stubs):
    _, band = stubs
    for call in (lambda: band.GetState(pb.GetStateRequest(), timeout=5),
                 lambda: next(band.StreamState(pb.StreamStateRequest(), timeout=5))):
        with pytest.raises(grpc.RpcError) as error:
            call()
        assert error.value.code() == grpc.StatusCode.UNIMPLEMENTED
        assert "serves only EmergencyStop" in error.value.details()
        assert "TELEROBOT_PROXY_ROBOT_ADDRESS" in error.value.details()


@pytest.mark.e2e
def test_a_stop_that_cannot_reach_the_arm_is_unavailable():
    band = start_service("emergency_stop", "--shm-name", unique_shm_name())
    try:
        with grpc.insecure_channel(band.address) as channel:
            with pytest.raises(grpc.RpcError) as error:
                proxy_robot_pb2_grpc.ProxyRobotStub(channel).EmergencyStop(
                    pb.EmergencyStopRequest(reason="nothing there"), timeout=5)
        assert error.value.code() == grpc.StatusCode.UNAVAILABLE
        assert "no world is running" in error.value.details()
    finally:
        band.stop()


@pytest.mark.e2e
def test_the_band_imports_no_robot_model():
    """A killed band must be back within 5 s (#16), on a loaded machine too: it loads neither
    Pinocchio nor MuJoCo, which took a second of its start-up (four under load)."""
    loaded = subprocess.run(
        [sys.executable, "-c", "import sys, services.emergency_stop.__main__; "
         "print(sorted({'pinocchio', 'mujoco'} & set(sys.modules)))"],
        check=True, capture_output=True, text=True, timeout=60).stdout.strip()
    assert loaded == "[]", loaded
