"""world_loop: the world's 1 kHz loop, counted over the bench run and per scenario.

The world publishes its loop counters in every state record (services/world/realtime.py):
`loop_steps`, `loop_overruns` (a step that started a whole period or more late) and
`loop_dropped_steps` (steps skipped because the loop fell too far behind). They count from the
world's start, so the bench reads them (read only, through WorldWatch) when the station is up
and at the end of the run, and at every scenario's start and end: the differences are the
run's and each scenario's overruns. A read is a few microseconds in the orchestrator's
process, which measures nothing itself.
"""

from __future__ import annotations

import time

from bench.worldwatch import WorldWatch

FIELDS = ("steps", "overruns", "dropped_steps")
NOMINAL_HZ = 1000.0


def delta(before: dict[str, int], after: dict[str, int]) -> dict:
    """Steps, overruns and dropped steps from `before` to `after`, and overruns in % of the
    steps (None when no step was taken)."""
    counts = {key: after[key] - before[key] for key in FIELDS}
    steps = counts["steps"]
    counts["overrun_pct"] = round(100.0 * counts["overruns"] / steps, 4) if steps > 0 else None
    return counts


def with_pct(counts: dict) -> dict:
    """A worker's {steps, overruns, dropped_steps} with overrun_pct added."""
    steps = counts.get("steps") or 0
    return {**counts, "overrun_pct": (round(100.0 * counts["overruns"] / steps, 4)
                                      if steps > 0 else None)}


class LoopMeter:
    """The world's loop counters (the world `shm_name` must be up): the run's from here, and
    each scenario's from its mark."""

    def __init__(self, shm_name: str):
        self._watch = WorldWatch(shm_name)
        self._start = self._mark = self.read()
        self._started = time.monotonic()

    def read(self) -> dict[str, int]:
        record = self._watch.read()
        return {key: int(record[f"loop_{key}"]) for key in FIELDS}

    def mark(self) -> None:
        """A scenario starts here."""
        self._mark = self.read()

    def since_mark(self) -> dict:
        """The counters since the mark; the mark moves here (the next scenario starts)."""
        now = self.read()
        counts, self._mark = delta(self._mark, now), now
        return counts

    def row(self) -> dict:
        """The world_loop row: the run's counters, plus the totals since the world started
        (its start-up included)."""
        now = self.read()
        elapsed = time.monotonic() - self._started
        counts = delta(self._start, now)
        return {"rate_hz": NOMINAL_HZ,
                "delivered_hz": round(counts["steps"] / elapsed, 3) if elapsed > 0 else None,
                "p50_ms": None, "p99_ms": None, "max_ms": None,
                "dropped": counts["dropped_steps"], "samples": counts["steps"],
                "transport": "shared-memory loop counters (read only)",
                "duration_s": round(elapsed, 3), **counts,
                "since_world_start": {**now, "overrun_pct": delta(
                    dict.fromkeys(FIELDS, 0), now)["overrun_pct"]}}

    def close(self) -> None:
        self._watch.close()
