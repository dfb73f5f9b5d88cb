"""WorldService in this process: the loop, the link and the failure path (no gRPC server)."""

from __future__ import annotations

import threading

import pytest

from services.world.service import WorldService
from services.world.shm_link import SharedMemoryArmLink
from services.world.sim import ArmSim
from tests.conftest import wait_for
from tests.processes import segment_exists, unique_shm_name

pytestmark = pytest.mark.e2e


class SimThatBreaks(ArmSim):
    """A simulation whose step raises after a few steps, like a bug in the physics would."""

    def step(self) -> None:
        if self.steps >= 20:
            raise RuntimeError("physics bug")
        super().step()


def test_runs_publishes_and_cleans_up() -> None:
    service = WorldService(unique_shm_name())
    service.start()
    try:
        link = SharedMemoryArmLink(service.publisher.name)
        first = link.read_arm().sequence
        wait_for(lambda: link.read_arm().sequence > first, 5.0, "the world to publish a step")
        link.close()
    finally:
        name = service.publisher.name
        service.close()
    assert not segment_exists(name)
    assert service.loop.stats().steps > 0 and not service.failed


def test_a_crashing_physics_loop_is_reported() -> None:
    crashed = threading.Event()
    service = WorldService(unique_shm_name(), sim_factory=SimThatBreaks,
                           on_failure=crashed.set)
    service.start()  # the first step works
    name = service.publisher.name
    assert crashed.wait(5.0)
    assert service.failed
    service.close()
    assert not segment_exists(name)


def test_a_loop_that_never_steps_fails_start_up() -> None:
    class BrokenAtOnce(ArmSim):
        def step(self) -> None:
            raise RuntimeError("physics bug")

    service = WorldService(unique_shm_name(), sim_factory=BrokenAtOnce)
    with pytest.raises(RuntimeError, match="did not start"):
        service.start()
    service.close()
