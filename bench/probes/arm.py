"""ProxyRobot's real servicer and core on an arm at rest, in this process: what the hop and
estop probes serve. The probes time the handler and the transport, not the motion, so the arm
never moves: it reports the home pose and keeps the last target written."""

from __future__ import annotations

import time

import numpy as np

from domain.robot_model.puma560 import HOME_Q
from services.world.link import ArmSample


class RestingArm:
    """An ArmLink (services/world/link.py) whose arm stays at home: each read is a fresh
    sample there, with the latest target and whether a hold is latched."""

    def __init__(self):
        self._q = np.asarray(HOME_Q, float).copy()
        self._target = self._q.copy()
        self._latched = False
        self._sequence = 0

    def read_arm(self) -> ArmSample:
        self._sequence += 1
        return ArmSample(self._sequence, time.time_ns(), self._q.copy(), np.zeros_like(self._q),
                         self._target.copy(), self._latched, "")

    def write_target(self, joint_positions_rad: np.ndarray, duration_s: float = 0.0) -> None:
        if not self._latched:
            self._target = np.asarray(joint_positions_rad, float).copy()

    def hold(self) -> None:
        self._latched = True

    def release_hold(self) -> None:
        self._latched = False

    def close(self) -> None:
        pass


def proxy_robot_servicer():
    """ProxyRobotServicer on a ProxyRobotCore (no monitor thread) on a RestingArm, connected
    and initialized: its handlers do all their work (checks, IK, the singularity check, the
    target written) and the arm stays at home."""
    from services.proxy_robot.core import ProxyRobotCore
    from services.proxy_robot.servicer import ProxyRobotServicer

    arm = RestingArm()
    core = ProxyRobotCore(lambda: arm, threads=False)
    core.connect()
    core.initialize()
    core.sample_once()
    return ProxyRobotServicer(core)
