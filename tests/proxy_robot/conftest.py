"""ProxyRobot tests run against a real world process through the shared-memory link."""

from __future__ import annotations

import time
from collections.abc import Iterator

import numpy as np
import pytest

from services.proxy_robot.core import ProxyRobotCore
from services.proxy_robot.status import RobotStatus
from services.robot_model.puma560 import HOME_Q
from services.world.shm_link import SharedMemoryArmLink
from tests.world.conftest import World, _cleanup, start_world


@pytest.fixture
def core(world) -> Iterator[ProxyRobotCore]:
    """A fresh proxy on the shared world; leaves the world un-latched for the next test."""
    proxy = ProxyRobotCore(lambda: SharedMemoryArmLink(world.shm_name))
    yield proxy
    if proxy.status[0] in (RobotStatus.ESTOPPED, RobotStatus.FAULT):
        proxy.reset()
    proxy.close()


def send_home(world: World, timeout_s: float = 10.0) -> None:
    """Drive the arm back to the home pose through the link (before a proxy connects)."""
    link = SharedMemoryArmLink(world.shm_name)
    try:
        link.release_hold()
        link.write_target(HOME_Q)
        deadline = time.monotonic() + timeout_s
        while np.max(np.abs(link.read_arm().joint_positions_rad - HOME_Q)) > 1e-4:
            if time.monotonic() > deadline:
                raise AssertionError("the arm did not return home")
            time.sleep(0.01)
    finally:
        link.close()


@pytest.fixture
def ready(world, core) -> ProxyRobotCore:
    """A connected, initialized proxy with the arm at home."""
    send_home(world)
    core.connect()
    core.initialize()
    return core


@pytest.fixture
def world_factory():
    """Worlds owned by one test (stopped and cleaned up after it)."""
    worlds: list[World] = []

    def start() -> World:
        worlds.append(start_world())
        return worlds[-1]

    yield start
    for world in worlds:
        _cleanup(world)
