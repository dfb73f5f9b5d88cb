"""Cobegin barriers cannot pile up: abandoned ones go, and the open ones are capped."""

from __future__ import annotations

import pytest

from services.decision_server.cobegin import MAX_OPEN_BARRIERS, Barriers
from tests.fakes.clock import FakeClock
from wire.errors import NotFoundError, ResourceExhaustedError


def test_open_cobegins_are_capped_and_abandoned_ones_go_at_their_deadline():
    clock = FakeClock()
    barriers = Barriers(clock)
    opened = [barriers.open(2, 5.0)[0] for _ in range(MAX_OPEN_BARRIERS)]
    with pytest.raises(ResourceExhaustedError, match="cobegins are open"):
        barriers.open(2, 5.0)
    clock.advance(5.0)  # nobody arrived at any of them by its deadline
    fresh, _ = barriers.open(2, 5.0)
    assert barriers.arrived(fresh) == 0
    with pytest.raises(NotFoundError):  # an abandoned one is gone
        barriers.arrive_and_wait(opened[0])


def test_a_barrier_with_actions_waiting_is_not_dropped_as_abandoned():
    clock = FakeClock()
    barriers = Barriers(clock)
    waited, _ = barriers.open(2, 5.0)
    barriers._barriers[waited].arrived = 1  # one action waits at it (its thread ends it)
    clock.advance(5.0)
    barriers.open(1, 5.0)
    assert barriers.arrived(waited) == 1
