"""A fixed-rate loop that keeps simulated time on wall time and counts when it cannot.

Step n is due at start + n * period (absolute deadlines, so sleep jitter never accumulates).
The loop sleeps until a step is due, runs it, and records how late it started:

- lateness: start time - due time of a step. ``worst_lateness_ns`` is the largest seen.
- overrun: a step that started a whole period or more late (its successor was already due).
- catch-up policy: steps that fell behind by up to ``max_catch_up_s`` run back to back until the
  loop is on schedule again, so a short hiccup (a GC pause, a busy core) leaves simulated time
  exactly on wall time. Further behind than that (the process was stopped, the machine
  suspended), the missed steps are dropped: the schedule restarts from now and
  ``dropped_steps`` counts them, because replaying seconds of motion in fast-forward would
  hog the CPU and show the operator a time-lapse. Simulated time then lags wall time by the
  dropped steps.

It uses time.sleep (clock_nanosleep on Linux), not a spin, so it leaves the CPU to others; the
price is ~0.1 ms of wake-up jitter, which the absolute schedule absorbs. What wakes it on time
under load is the thread's priority: the world runs this loop at SCHED_FIFO where allowed
(service.py), which took the overruns under load from 13-36 % at nice -10 to 0.05-0.5 % on a
shared 2-core VM, the rest being the hypervisor's steal time (docs/services/world.md, "Real-time
priority").
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable
from dataclasses import dataclass

DEFAULT_PERIOD_S = 0.001  # 1 kHz
DEFAULT_MAX_CATCH_UP_S = 0.05  # up to 50 steps replayed back to back; more are dropped


@dataclass(frozen=True)
class LoopStats:
    """Counters of a RealtimeLoop since it started."""

    steps: int = 0  # steps run
    overruns: int = 0  # steps that started a period or more late
    dropped_steps: int = 0  # steps skipped because the loop fell too far behind
    worst_lateness_ns: int = 0  # largest (start - due time) of any step
    worst_step_ns: int = 0  # longest time one step took to run

    def describe(self) -> str:
        return (f"{self.steps} steps, {self.overruns} overruns, {self.dropped_steps} dropped, "
                f"worst lateness {self.worst_lateness_ns / 1e6:.3f} ms, "
                f"worst step {self.worst_step_ns / 1e6:.3f} ms")


class RealtimeLoop:
    """Runs ``step()`` every ``period_s`` on the calling thread until ``stop`` is set.

    ``clock`` (ns, monotonic) and ``sleep`` (s) default to the real ones; tests may pass their
    own to check the schedule without waiting.
    """

    def __init__(
        self,
        step: Callable[[], None],
        period_s: float = DEFAULT_PERIOD_S,
        max_catch_up_s: float = DEFAULT_MAX_CATCH_UP_S,
        clock: Callable[[], int] = time.monotonic_ns,
        sleep: Callable[[float], None] = time.sleep,
    ):
        self._step = step
        self._period_ns = round(period_s * 1e9)
        self._max_catch_up_ns = round(max_catch_up_s * 1e9)
        self._clock = clock
        self._sleep = sleep
        self._stats = LoopStats()
        self._lock = threading.Lock()  # stats are written here and read from other threads

    @property
    def period_s(self) -> float:
        return self._period_ns / 1e9

    def stats(self) -> LoopStats:
        """A consistent snapshot of the counters."""
        with self._lock:
            return self._stats

    def run(self, stop: threading.Event) -> None:
        """Step on schedule until ``stop`` is set (checked before every step)."""
        period, clock = self._period_ns, self._clock
        steps = overruns = dropped = worst_late = worst_step = 0
        due = clock()
        while not stop.is_set():
            now = clock()
            if now < due:
                self._sleep((due - now) / 1e9)
                continue
            late = now - due
            if late > self._max_catch_up_ns:
                skipped = late // period
                dropped += skipped
                due += skipped * period
                late -= skipped * period
            if late >= period:
                overruns += 1
            worst_late = max(worst_late, late)
            self._step()
            worst_step = max(worst_step, clock() - now)
            steps += 1
            due += period
            with self._lock:
                self._stats = LoopStats(steps, overruns, dropped, worst_late, worst_step)
