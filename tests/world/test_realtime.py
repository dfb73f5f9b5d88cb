"""The fixed-rate loop: schedule, lateness, overruns, catch-up and drop policy.

The schedule is checked against a manual clock (time passes only when the loop sleeps or a step
says so), so these tests are exact and never wait; one test runs the real clock briefly.
"""

from __future__ import annotations

import threading

from services.world.realtime import LoopStats, RealtimeLoop
from tests.conftest import wait_for

PERIOD_NS = 1_000_000
STEP_NS = 100_000  # each step takes 0.1 ms


class ManualClock:
    def __init__(self):
        self.now_ns = 5_000_000_000

    def __call__(self) -> int:
        return self.now_ns

    def sleep(self, seconds: float) -> None:
        self.now_ns += round(seconds * 1e9)


def run_steps(count: int, stall_ns: dict[int, int] | None = None,
              max_catch_up_s: float = 0.05) -> tuple[list[int], LoopStats]:
    """Run `count` steps; step i takes STEP_NS plus stall_ns[i]. Returns each step's start."""
    clock, stop, starts = ManualClock(), threading.Event(), []

    def step():
        starts.append(clock.now_ns)
        clock.now_ns += STEP_NS + (stall_ns or {}).get(len(starts) - 1, 0)
        if len(starts) == count:
            stop.set()

    loop = RealtimeLoop(step, period_s=PERIOD_NS / 1e9, max_catch_up_s=max_catch_up_s,
                        clock=clock, sleep=clock.sleep)
    loop.run(stop)
    origin = starts[0]
    return [start - origin for start in starts], loop.stats()


def test_on_schedule_every_step_starts_on_its_tick() -> None:
    starts, stats = run_steps(100)
    assert starts == [n * PERIOD_NS for n in range(100)]
    assert stats == LoopStats(steps=100, overruns=0, dropped_steps=0, worst_lateness_ns=0,
                              worst_step_ns=STEP_NS)


def test_a_short_hiccup_is_caught_up_back_to_back() -> None:
    # Step 10 takes 5.1 ms: steps 11..15 are late and run back to back, step 16 is on its tick.
    starts, stats = run_steps(30, stall_ns={10: 5_000_000})
    assert starts[11] == 10 * PERIOD_NS + 5_100_000
    assert all(b - a == STEP_NS for a, b in zip(starts[11:15], starts[12:16], strict=True))
    assert starts[16:] == [n * PERIOD_NS for n in range(16, 30)]  # simulated time on wall time
    late = [start - n * PERIOD_NS for n, start in enumerate(starts)]
    assert stats.overruns == sum(1 for lateness in late if lateness >= PERIOD_NS)
    assert stats.overruns == 4  # 4.1, 3.2, 2.3 and 1.4 ms late
    assert stats.worst_lateness_ns == max(late) == 4_100_000
    assert stats.dropped_steps == 0
    assert stats.steps == 30


def test_a_long_stall_drops_steps_instead_of_fast_forwarding() -> None:
    # Step 5 takes 1 s (a stopped process), past the 50 ms catch-up bound: the 999 steps due
    # meanwhile are dropped and step 6 runs as the one due at 1005 ms.
    starts, stats = run_steps(20, stall_ns={5: 1_000_000_000})
    assert stats.dropped_steps == 999
    assert stats.overruns == 0
    assert stats.worst_lateness_ns == STEP_NS
    assert starts[7] == 1006 * PERIOD_NS
    gaps = [b - a for a, b in zip(starts[7:], starts[8:], strict=False)]
    assert all(gap == PERIOD_NS for gap in gaps)  # steady again right after the stall


def test_runs_on_the_real_clock_until_stopped() -> None:
    stop, steps = threading.Event(), []
    loop = RealtimeLoop(lambda: steps.append(1))
    thread = threading.Thread(target=loop.run, args=(stop,))
    thread.start()
    wait_for(lambda: len(steps) >= 10, 5.0, "ten steps on the real clock")
    stop.set()
    thread.join(2.0)
    assert not thread.is_alive()
    stats = loop.stats()
    assert stats.steps == len(steps) > 0
    assert stats.worst_lateness_ns >= 0
