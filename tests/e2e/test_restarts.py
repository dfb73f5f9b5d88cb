"""The launcher supervises: a child that dies is restarted on its address while the rest of
the station serves; the world's death, or a child failing too often, stops the station."""

from __future__ import annotations

import contextlib
import os
import signal

import grpc
import pytest

from telerobot.v1 import proxy_robot_pb2, proxy_robot_pb2_grpc, types_pb2
from tests.conftest import wait_for
from tests.processes import (
    health_serving,
    pid_alive,
    restarted,
    service_pid,
    start_station,
    station_env,
)

pytestmark = pytest.mark.e2e


@pytest.fixture(scope="module")
def station():
    launcher = start_station(station_env())
    yield launcher
    if launcher.process.poll() is None:
        launcher.stop(signal.SIGINT)


def test_a_killed_sensor_is_restarted_on_its_address_and_the_stop_button_stays(station):
    victim = service_pid(station, "force_sensor")
    os.kill(victim, signal.SIGKILL)
    # The band and the operator's door serve all along.
    assert health_serving(station.ready["emergency_stop"])
    assert health_serving(station.ready["decision_server"])
    wait_for(lambda: restarted(station, "force_sensor", victim), timeout_s=5,
             what="force_sensor restarted and serving within 5 s")
    assert station.process.poll() is None
    output = "\n".join(station.lines)
    assert "was killed by signal 9 (SIGKILL)" in output and "restarting force_sensor" in output


def test_a_restarted_proxy_robot_reattaches_holding_and_says_why(station):
    with grpc.insecure_channel(station.ready["proxy_robot"]) as channel:
        robot = proxy_robot_pb2_grpc.ProxyRobotStub(channel)
        robot.Connect(proxy_robot_pb2.ConnectRequest(), timeout=30)
        robot.Initialize(proxy_robot_pb2.InitializeRequest(), timeout=30)
        before = robot.GetState(proxy_robot_pb2.GetStateRequest(), timeout=5).state
    victim = service_pid(station, "proxy_robot")
    os.kill(victim, signal.SIGKILL)
    wait_for(lambda: restarted(station, "proxy_robot", victim), timeout_s=5,
             what="proxy_robot restarted and serving within 5 s")
    with grpc.insecure_channel(station.ready["proxy_robot"]) as channel:
        robot = proxy_robot_pb2_grpc.ProxyRobotStub(channel)
        status = robot.GetStatus(proxy_robot_pb2.GetStatusRequest(), timeout=5)
        after = robot.GetState(proxy_robot_pb2.GetStateRequest(), timeout=5).state
    assert status.status == types_pb2.ROBOT_STATUS_CONNECTED, status
    assert "restarted by the station's supervisor" in status.reason
    assert "killed by signal 9" in status.reason and "Initialize to move again" in status.reason
    moved = max(abs(a - b) for a, b in zip(after.joint_positions_rad,
                                            before.joint_positions_rad, strict=True))
    assert moved < 1e-3, moved  # held where it was


@contextlib.contextmanager
def _own_station(**settings: str):
    """A station of the test's own, killed after it if it did not stop by itself."""
    launcher = start_station(station_env(**settings))
    try:
        yield launcher
    finally:
        if launcher.process.poll() is None:
            launcher.stop(signal.SIGKILL)


def _assert_killing_stops_the_station(launcher, victim: int, others: list[int], why: str):
    """SIGKILL `victim`: the launcher exits 1 saying `why`, with `others` stopped before."""
    os.kill(victim, signal.SIGKILL)
    assert launcher.wait(timeout_s=15) == 1
    launcher.exited.wait(5)
    assert why in "\n".join(launcher.lines)
    assert not [pid for pid in others if pid_alive(pid)]


def test_a_child_failing_too_often_stops_the_station():
    with _own_station(TELEROBOT_MAX_FAILURES="2") as launcher:
        first = service_pid(launcher, "stereo_camera")
        os.kill(first, signal.SIGKILL)
        second = wait_for(lambda: restarted(launcher, "stereo_camera", first), timeout_s=10,
                          what="the first restart")
        others = [service_pid(launcher, name) for name in ("world", "proxy_robot")]
        _assert_killing_stops_the_station(launcher, second, others,
                                          "stereo_camera failed 2 failures within 60 s")


def test_the_world_dying_stops_the_whole_station():
    with _own_station() as launcher:
        others = [service_pid(launcher, name) for name in ("proxy_robot", "decision_server")]
        _assert_killing_stops_the_station(launcher, service_pid(launcher, "world"), others,
                                          "the hardware link is gone")
