"""`Schedule`: ticks at a fixed rate on absolute deadlines, the way a master sends commands.

Tick k is due at start + k / rate (so sleep jitter never accumulates). Iterating sleeps until
each tick is due and yields it; a tick the sender wakes up a whole period or more late for is
skipped and counted in `skipped`: a master that fell behind sends the current command, not a
backlog.
"""

from __future__ import annotations

import time
from collections.abc import Iterator


class Schedule:
    def __init__(self, rate_hz: float, ticks: int, lead_s: float = 0.005):
        self.period_s = 1.0 / rate_hz
        self.ticks = ticks
        self.start = time.perf_counter() + lead_s
        self.skipped = 0

    def __iter__(self) -> Iterator[int]:
        tick = 0
        while tick < self.ticks:
            due = self.start + tick * self.period_s
            now = time.perf_counter()
            if now < due:
                time.sleep(due - now)
            elif now - due >= self.period_s:  # this tick's slot is gone: on to the current one
                missed = min(int((now - due) / self.period_s), self.ticks - tick)
                self.skipped += missed
                tick += missed
                continue
            yield tick
            tick += 1
