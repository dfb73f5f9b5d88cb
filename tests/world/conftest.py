"""Helpers for the world tests: real `python -m services.world` processes on their own segments."""

from __future__ import annotations

import uuid
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import pytest

from services.world.shm_layout import SHM_NAME_ENV
from tests.conftest import RunningProcess, start_process

SHM_DIR = Path("/dev/shm")  # where Linux keeps POSIX shared memory


def unique_shm_name() -> str:
    return f"telerobot_test_{uuid.uuid4().hex[:12]}"


def segment_exists(name: str) -> bool:
    return (SHM_DIR / name).exists()


@dataclass
class World:
    """A running world process and the segment it publishes on."""

    running: RunningProcess
    shm_name: str

    @property
    def pid(self) -> int:
        return self.running.process.pid

    def output(self) -> str:
        return "\n".join(self.running.lines[-40:])


def start_world(shm_name: str | None = None) -> World:
    """Start a world on a fresh segment and wait for its ready line."""
    name = shm_name or unique_shm_name()
    running = start_process(["-m", "services.world", "--address", "127.0.0.1:0"],
                            env={SHM_NAME_ENV: name})
    running.wait_ready(["world"], timeout_s=60.0)
    return World(running, name)


def _cleanup(world: World) -> None:
    if world.running.process.poll() is None:
        world.running.stop()
    # Only after a kill: never leave segments behind (the killed world's resource tracker may
    # be removing it at the same moment).
    (SHM_DIR / world.shm_name).unlink(missing_ok=True)


@pytest.fixture
def world_factory() -> Iterator:
    """Factory for worlds owned by one test (stopped and cleaned up after it)."""
    worlds: list[World] = []

    def start(shm_name: str | None = None) -> World:
        world = start_world(shm_name)
        worlds.append(world)
        return world

    yield start
    for world in worlds:
        _cleanup(world)


@pytest.fixture(scope="module")
def shared_world() -> Iterator[World]:
    """One world for a module's tests that leave it running (and its arm released)."""
    world = start_world()
    yield world
    _cleanup(world)
