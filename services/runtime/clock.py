"""Time as the domain reads it: one small port, so tests can drive timers and watchdogs
with a fake clock instead of the wall clock."""

from __future__ import annotations

import threading
import time
from typing import Protocol


class Clock(Protocol):
    def monotonic(self) -> float:
        """Seconds on a clock that never goes back, for intervals and deadlines."""

    def monotonic_ns(self) -> int:
        """The same clock in ns."""

    def time_ns(self) -> int:
        """Wall-clock time in ns since the epoch, for timestamps."""

    def sleep(self, seconds: float) -> None:
        """Let `seconds` of this clock pass."""

    def wait(self, event: threading.Event, timeout_s: float | None) -> bool:
        """Block until `event` is set (True) or `timeout_s` of this clock passed (False)."""

    def wait_until(self, event: threading.Event, deadline_s: float | None) -> bool:
        """Block until `event` is set (True) or `monotonic()` reaches `deadline_s` (False). A
        deadline, unlike a timeout, does not move if time passes before the wait begins."""


class SystemClock:
    """The real clock."""

    monotonic = staticmethod(time.monotonic)
    monotonic_ns = staticmethod(time.monotonic_ns)
    time_ns = staticmethod(time.time_ns)
    sleep = staticmethod(time.sleep)

    @staticmethod
    def wait(event: threading.Event, timeout_s: float | None) -> bool:
        return event.wait(timeout_s)

    @staticmethod
    def wait_until(event: threading.Event, deadline_s: float | None) -> bool:
        if deadline_s is None:
            return event.wait()
        return event.wait(max(0.0, deadline_s - time.monotonic()))


SYSTEM_CLOCK = SystemClock()
