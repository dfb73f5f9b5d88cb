"""A clock that moves only when the test says so: FakeClock.advance(dt) runs every timer
that falls due, so watchdogs, lease expiry and rate loops are tested without the wall clock."""

from __future__ import annotations

import threading

START_WALL_NS = 1_800_000_000_000_000_000  # an arbitrary, recognisable epoch time


class FakeClock:
    """Implements services.runtime.clock.Clock. Threads blocked in `wait` wake when their
    event is set or when `advance` moves the time past their deadline."""

    def __init__(self, start_s: float = 1000.0):
        self._now_s = start_s
        self._start_s = start_s
        self._changed = threading.Condition()
        self._waiters = 0

    def monotonic(self) -> float:
        return self._now_s

    def time_ns(self) -> int:
        return START_WALL_NS + round((self._now_s - self._start_s) * 1e9)

    def advance(self, dt_s: float) -> None:
        with self._changed:
            self._now_s += dt_s
            self._changed.notify_all()

    def wait(self, event: threading.Event, timeout_s: float | None) -> bool:
        deadline = None if timeout_s is None else self._now_s + timeout_s
        with self._changed:
            self._waiters += 1
            self._changed.notify_all()
            try:
                while not event.is_set():
                    if deadline is not None and self._now_s >= deadline:
                        return False
                    # Event.set() does not notify this condition: look again shortly. This
                    # bounds how late a set event is seen, it orders nothing.
                    self._changed.wait(0.001)
                return True
            finally:
                self._waiters -= 1

    def waiters(self) -> int:
        """How many threads are blocked in `wait` now (tests wait for a timer to be armed)."""
        return self._waiters
