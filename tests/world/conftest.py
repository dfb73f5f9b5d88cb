"""Fixtures for the world tests: real `python -m services.world` processes on their own
segments (e2e only; the helpers are in tests/processes.py)."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from tests.conftest import starts_processes
from tests.processes import World, start_world, stop_world


@pytest.fixture
@starts_processes
def world_factory() -> Iterator:
    """Factory for worlds owned by one test (stopped and cleaned up after it)."""
    worlds: list[World] = []

    def start(shm_name: str | None = None) -> World:
        world = start_world(shm_name)
        worlds.append(world)
        return world

    yield start
    for world in worlds:
        stop_world(world)


@pytest.fixture(scope="module")
@starts_processes
def shared_world() -> Iterator[World]:
    """One world for a module's tests that leave it running (and its arm released)."""
    world = start_world()
    yield world
    stop_world(world)
