"""The generic fanout's lag report: how long each item waited in its subscriber's queue."""

from __future__ import annotations

import pytest

from services.common.fanout import Fanout
from tests.fakes.clock import FakeClock


def fanout_on(clock: FakeClock) -> tuple[Fanout[str], list[float]]:
    fanout: Fanout[str] = Fanout(clock=lambda: clock.monotonic_ns() / 1e9)
    lags: list[float] = []
    fanout.on_lag = lags.append
    return fanout, lags


def test_each_item_reports_the_time_it_waited_in_its_queue():
    clock = FakeClock()
    fanout, lags = fanout_on(clock)
    prompt, slow = fanout.subscribe(), fanout.subscribe()
    fanout.publish("a")
    assert prompt.get(0) == "a"  # taken at once
    clock.advance(0.010)
    fanout.publish("b")
    clock.advance(0.005)
    assert prompt.get(0) == "b"
    assert [slow.get(0), slow.get(0)] == ["a", "b"]  # 15 ms and 5 ms after their publication
    assert lags == pytest.approx([0.0, 0.005, 0.015, 0.005])


def test_a_dropped_item_reports_no_lag_and_an_empty_queue_none():
    clock = FakeClock()
    fanout, lags = fanout_on(clock)
    full = fanout.subscribe(capacity=1)
    fanout.publish("old")
    clock.advance(0.002)
    fanout.publish("new")  # "old" is dropped: only what is taken has a lag
    assert full.get(0) == "new" and full.get(0) is None
    assert lags == pytest.approx([0.0])


def test_a_failing_lag_report_never_fails_the_subscriber():
    fanout: Fanout[int] = Fanout()
    fanout.on_lag = lambda lag_s: 1 / 0
    subscription = fanout.subscribe()
    fanout.publish(7)
    assert subscription.get(0) == 7
