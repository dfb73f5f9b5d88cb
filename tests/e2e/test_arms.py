"""A whole station for each arm besides the default (`make serve ARM=…`): it describes itself
as its file does, moves where it is told, and refuses a service started for another arm."""

from __future__ import annotations

import os
import signal
import subprocess
import sys

import numpy as np
import pytest

from clients.python import (
    DecisionClient,
    FailedPreconditionError,
    ProxyRobotClient,
    RobotStatus,
)
from domain.robot_model.description import arm_description
from tests.conftest import wait_for
from tests.processes import REPO, start_process, start_station, station_env

pytestmark = pytest.mark.e2e


@pytest.fixture(scope="module", params=["fr3", "ur5e"])
def station(request):
    env = station_env(TELEROBOT_ARM=request.param)
    launcher = start_station(env)
    yield request.param, launcher.ready["decision_server"], env
    if launcher.process.poll() is None:
        launcher.stop(signal.SIGKILL)


def test_the_operator_address_describes_the_arm_as_its_file_does(station):
    name, address, _ = station
    arm = arm_description(name)
    with DecisionClient(address) as client:
        info = client.robot.get_arm_info()
    assert info.name == name and info.joint_names == arm.joint_names
    assert info.joint_count == {"fr3": 7, "ur5e": 6}[name]
    for got, want in ((info.lower_limits, arm.lower), (info.upper_limits, arm.upper),
                      (info.velocity_limits, arm.max_velocity),
                      (info.torque_limits, arm.max_torque), (info.home, arm.home_q)):
        np.testing.assert_array_equal(got, want)


def test_cartesian_moves_land_within_a_millimetre(station):
    _, address, _ = station
    with DecisionClient(address, default_timeout=5.0) as client:
        client.acquire_control("arms", lease_duration_s=30.0)
        robot = client.robot
        if robot.get_status().status is RobotStatus.NOT_CONNECTED:
            robot.connect()
        robot.initialize()
        start = robot.get_state().tool_pose.translation.copy()
        for _ in range(20):
            robot.move_cartesian([0.0, 0.005, -0.002])
        goal = start + np.array([0.0, 0.1, -0.04])
        wait_for(lambda: np.linalg.norm(robot.get_state().tool_pose.translation - goal) < 1e-3,
                 timeout_s=10, what="the tool to reach the sum of the moves")
        joints = robot.get_state().joint_positions
        assert joints.shape == (client.robot.get_arm_info().joint_count,)


def test_a_service_started_for_another_arm_refuses_the_world(station):
    name, _, env = station
    other = "puma560"
    child = start_process(["-m", "services.proxy_robot", "--arm", other,
                           "--address", "127.0.0.1:0"], env=env)
    try:
        with ProxyRobotClient(child.wait_ready("proxy_robot", timeout_s=30)) as robot:
            with pytest.raises(FailedPreconditionError,
                               match=f"simulates the {name}, and this process drives the {other}"):
                robot.connect()
    finally:
        child.stop(signal.SIGINT)


def test_make_teleop_for_another_arm_is_refused_with_the_reason(station, tmp_path):
    name, address, env = station
    result = subprocess.run(
        [sys.executable, "-m", "clients.teleop", "--address", address, "--arm", "puma560",
         "--out", str(tmp_path / "run"), "--no-video"],
        cwd=REPO, env={**os.environ, **env}, capture_output=True, text=True, timeout=120)
    assert result.returncode == 3, result.stdout[-2000:] + result.stderr[-2000:]
    assert f"drives the {name}, not the puma560" in result.stderr
