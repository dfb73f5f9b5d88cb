"""A fake clock: time stands still until a test advances it.

It has what the cores read (services/runtime/clock.py's Clock: `monotonic()`,
`monotonic_ns()`, `time_ns()`, `sleep(s)`, `wait(event, timeout_s)`, `wait_until(event,
deadline_s)`) and what a test drives
(`advance(s)`, `waiters()`). Both readings move together. `sleep` advances the clock, so code
that polls with a deadline runs to that deadline at once instead of hanging; `wait` blocks
until its event is set or a test advances the clock past its deadline, so watchdogs and lease
expiry fire exactly when the test says. Thread-safe.
"""

from __future__ import annotations

import threading

# Not zero, as real clocks are not: code that subtracts a start time of 0 would be wrong by
# the whole epoch, and this shows it.
START_MONOTONIC_NS = 1_000 * 10**9  # 1000 s since boot
START_WALL_NS = 1_767_225_600 * 10**9  # 2026-01-01T00:00:00Z
# Event.set() does not notify the clock: a thread in `wait` looks at its event this often
# (real time). It bounds how late a set event is seen; it orders nothing.
EVENT_POLL_S = 0.001


class FakeClock:
    """Monotonic and wall time in ns that move only when advanced."""

    def __init__(self, monotonic_ns: int = START_MONOTONIC_NS, wall_ns: int = START_WALL_NS):
        self._changed = threading.Condition()
        self._monotonic_ns = int(monotonic_ns)
        self._wall_ns = int(wall_ns)
        self._waiters = 0

    def monotonic_ns(self) -> int:
        with self._changed:
            return self._monotonic_ns

    def time_ns(self) -> int:
        """Wall clock (ns since the Unix epoch)."""
        with self._changed:
            return self._wall_ns

    def monotonic(self) -> float:
        """Seconds, as time.monotonic()."""
        return self.monotonic_ns() * 1e-9

    def time(self) -> float:
        """Seconds, as time.time()."""
        return self.time_ns() * 1e-9

    def advance(self, seconds: float) -> None:
        """Move both clocks forward by `seconds` (rounded to the ns; never backwards), waking
        every `wait` whose deadline has passed."""
        step_ns = round(seconds * 1e9)
        if step_ns < 0:
            raise ValueError(f"a clock never goes back: advance({seconds})")
        with self._changed:
            self._monotonic_ns += step_ns
            self._wall_ns += step_ns
            self._changed.notify_all()

    def sleep(self, seconds: float) -> None:
        """What time.sleep would do, instantly: the clock advances by `seconds`."""
        self.advance(max(seconds, 0.0))

    def wait(self, event: threading.Event, timeout_s: float | None) -> bool:
        """Block until `event` is set (True) or the clock is advanced past `timeout_s` from
        now (False)."""
        with self._changed:
            deadline_ns = (None if timeout_s is None
                           else self._monotonic_ns + max(round(timeout_s * 1e9), 0))
            return self._wait_locked(event, deadline_ns)

    def wait_until(self, event: threading.Event, deadline_s: float | None) -> bool:
        """Block until `event` is set (True) or the clock reaches `deadline_s` (False)."""
        with self._changed:
            return self._wait_locked(event, None if deadline_s is None
                                     else round(deadline_s * 1e9))

    def _wait_locked(self, event: threading.Event, deadline_ns: int | None) -> bool:
        """`wait` and `wait_until`, with `_changed` held by the caller."""
        self._waiters += 1
        self._changed.notify_all()
        try:
            while not event.is_set():
                if deadline_ns is not None and self._monotonic_ns >= deadline_ns:
                    return False
                self._changed.wait(EVENT_POLL_S)
            return True
        finally:
            self._waiters -= 1

    def waiters(self) -> int:
        """How many threads are blocked in `wait` now (a test waits for a timer to be armed)."""
        with self._changed:
            return self._waiters
