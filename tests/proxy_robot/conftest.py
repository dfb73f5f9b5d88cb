"""ProxyRobot tests run in-process on a fake arm and a fake clock (tests/fakes), and drive the
proxy's monitor themselves, so every event happens at a known instant. The few
tests marked e2e run against a real world process through the shared-memory link."""

from __future__ import annotations

from collections.abc import Callable, Iterator

import numpy as np
import pytest

from domain.robot_model.puma560 import HOME_Q
from services.proxy_robot import core as core_module
from services.proxy_robot import segment_timing as segment_timing_module
from services.proxy_robot.core import ProxyRobotCore
from services.proxy_robot.status import RobotStatus
from services.world.shm_link import SharedMemoryArmLink
from tests.conftest import wait_for
from tests.fakes.arm_link import FakeArm
from tests.fakes.clock import FakeClock

TICK_S = segment_timing_module.SERVO_PERIOD_S  # the servo's period, 1 ms
TICKS_PER_SAMPLE = round(core_module.STATE_PERIOD_S / TICK_S)  # the monitor's period


@pytest.fixture
def modules_on_the_clock() -> tuple:
    """Tests not marked e2e read no real time in the proxy (tests/conftest.py's guard also
    keeps them from starting a process or attaching shared memory, so a world)."""
    return (core_module, segment_timing_module)


class Rig:
    """A ProxyRobotCore on a FakeArm, both on one FakeClock, driven tick by tick: each tick
    (1 ms) advances the clock (the arm steps with it), and every STATE_PERIOD_S the monitor
    samples the arm, as the core's own thread would in service."""

    def __init__(self) -> None:
        self.clock = FakeClock()
        self.arm = FakeArm(self.clock)
        self.core = ProxyRobotCore(self.arm.open_link, clock=self.clock, threads=False)
        self.ticks = 0

    def tick(self) -> None:
        self.clock.advance(TICK_S)
        self.ticks += 1
        if self.ticks % TICKS_PER_SAMPLE == 0:
            self.core.sample_once()

    def run(self, seconds: float) -> None:
        """Let `seconds` of fake time pass."""
        for _ in range(round(seconds / TICK_S)):
            self.tick()

    def run_until(self, predicate: Callable[[], object], timeout_s: float = 2.0,
                  what: str = "condition") -> float:
        """Tick until `predicate()` is true; the fake time it took (s). Fails after `timeout_s`
        of fake time."""
        start = self.ticks
        while not predicate():
            if (self.ticks - start) * TICK_S >= timeout_s:
                raise AssertionError(f"{what} did not happen within {timeout_s} s (fake time)")
            self.tick()
        return (self.ticks - start) * TICK_S

    def run_until_status(self, status: RobotStatus, timeout_s: float = 2.0) -> float:
        return self.run_until(lambda: self.core.status[0] == status, timeout_s, status.name)


@pytest.fixture
def rig() -> Iterator[Rig]:
    made = Rig()
    yield made
    made.core.close()


@pytest.fixture
def core(rig) -> ProxyRobotCore:
    """A fresh proxy on a fake arm at home, not connected."""
    return rig.core


@pytest.fixture
def ready(rig) -> ProxyRobotCore:
    """A connected, initialized proxy with the arm at rest at home."""
    rig.core.connect()
    rig.core.initialize()
    rig.run(0.01)
    return rig.core


# -- e2e: the real world process ------------------------------------------------------------


def send_home(world, timeout_s: float = 10.0) -> None:
    """Drive the real arm back to the home pose through the link (before a proxy connects)."""
    link = SharedMemoryArmLink(world.shm_name)
    try:
        link.release_hold()
        link.write_target(HOME_Q)
        wait_for(lambda: np.max(np.abs(link.read_arm().joint_positions_rad - HOME_Q)) <= 1e-4,
                 timeout_s, "the arm back home")
    finally:
        link.close()


@pytest.fixture
def world_ready(world) -> Iterator[ProxyRobotCore]:
    """A connected, initialized proxy on the real world, the arm at home; leaves the world
    un-latched for the next test."""
    send_home(world)
    proxy = ProxyRobotCore(lambda: SharedMemoryArmLink(world.shm_name))
    proxy.connect()
    proxy.initialize()
    yield proxy
    if proxy.status[0] in (RobotStatus.ESTOPPED, RobotStatus.FAULT):
        proxy.reset()
    proxy.close()
