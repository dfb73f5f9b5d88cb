"""franka_command_1000: ProxyRobot's Franka driver at 1 kHz, against franka-sim.

franka-sim (a MuJoCo FR3 behind libfranka's own protocol, `python -m services.franka_sim` from
its venv) is the robot; the driver's link (services/proxy_robot/franka_link.py) runs libfranka's
1 kHz joint-position loop in this worker. `mirrored`: the loop also publishes every cycle on its
mirror of the arm (services/proxy_robot/arm_mirror.py: the state and the estimated wrench), as
in the station. From home, a joint target is written every 1 ms (joint
7 swinging 0.1 rad at 0.5 Hz), as ProxyRobot writes a streamed command's target. Command ->
applied runs from write_target() until the robot reports (its RobotState.q_d, as libfranka
reads it back) the first setpoint the loop sent after it: the driver's queue, one control cycle
and libfranka's network round. One command in flight is measured at a time; commands written
meanwhile are sent but not timed (`samples`). libfranka's control_command_success_rate (the
share of the robot's cycles that got a command in time) is the run's lowest reading.
"""

from __future__ import annotations

import math
import os
import signal
import time

import numpy as np

from bench.schedule import Schedule
from bench.stats import summary
from domain.robot_model.description import arm_description
from services.franka_sim.process import start_franka_sim
from services.proxy_robot.arm_mirror import ArmMirror
from services.proxy_robot.franka_link import CONTROL_PERIOD_S, FrankaArmLink

HOST = "127.0.0.1"
RATE_HZ = 1000
SWING_RAD = 0.1
SWING_HZ = 0.5
HOME_TIMEOUT_S = 15.0


def measure(duration_s: float, mirrored: bool) -> dict:
    sim = start_franka_sim(HOST)
    arm = arm_description("fr3")
    mirror = (ArmMirror(arm, CONTROL_PERIOD_S, f"telerobot_bench_franka_{os.getpid()}")
              if mirrored else None)
    try:
        link = FrankaArmLink(HOST, arm, mirror, torque_source="impedance")
        try:
            return _run(link, arm.home_q, duration_s)
        finally:
            link.close()
    finally:
        if mirror is not None:
            mirror.close()
        sim.stop(signal.SIGTERM)


def _run(link: FrankaArmLink, home: np.ndarray, duration_s: float) -> dict:
    link.write_target(home)
    deadline = time.monotonic() + HOME_TIMEOUT_S
    while np.abs(link.read_arm().joint_positions_rad - home).max() > 1e-3:
        if time.monotonic() > deadline:
            raise RuntimeError("the FR3 did not reach home")
        time.sleep(0.01)
    link.applied_ns.clear()
    schedule = Schedule(RATE_HZ, round(duration_s * RATE_HZ))
    sent, lowest_success = 0, 1.0
    start = time.monotonic()
    for tick in schedule:
        target = home.copy()
        target[6] += SWING_RAD * math.sin(2 * math.pi * SWING_HZ * tick / RATE_HZ)
        link.write_target(target, 1.0 / RATE_HZ)
        sent += 1
        lowest_success = min(lowest_success, link.success_rate)
    window_s = time.monotonic() - start
    # Copied at once (list() of a deque holds the interpreter throughout): the link's
    # control thread still appends as the last targets land.
    latencies_ms = [ns / 1e6 for ns in list(link.applied_ns)]
    result = summary(latencies_ms, RATE_HZ, sent, window_s, schedule.skipped,
                     control_success_rate=round(lowest_success, 4))
    result["latencies_ms"] = latencies_ms  # for the plots (Session.record takes it out)
    return result
