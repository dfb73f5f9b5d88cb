"""Read-only view of the world's shared memory: what the servo was told, and when.

The world publishes one state record per 1 ms servo step (shm_layout.STATE_DTYPE) with the
joint `target` the servo tracks, `hold_latched`, the joint velocities and `arm_time_ns`
(time.time_ns() of that step, the same host clock as the bench's). While started, the watcher
polls every ~0.2 ms and keeps a timeline of (step time, target of joint 1) for every step it
sees, so it sees (almost) every step; it counts the steps it missed (`missed_steps`): a missed
step can make one latency up to a step too long, never too short.

This never writes to the segment (the command record has a single writer: the driver).
"""

from __future__ import annotations

import threading
import time

import numpy as np

from services.world.seqlock import TornRead
from services.world.shm_layout import WorldSegment, attach_untracked

POLL_S = 0.0002
READ_TIMEOUT_S = 0.05


class WorldWatch:
    """Attach to the world `shm_name` (read only)."""

    def __init__(self, shm_name: str):
        self._segment = WorldSegment(attach_untracked(shm_name))
        problem = self._segment.layout_problem()
        if problem:
            self.close()
            raise RuntimeError(f"world segment {shm_name!r} is not usable: {problem}")
        self._thread: threading.Thread | None = None
        self._stop = threading.Event()
        self.times_ns: list[int] = []  # arm_time_ns of each step seen while started
        self.targets: list[float] = []  # joint 1's servo target at that step (rad)
        self.missed_steps = 0

    def read(self) -> np.void:
        """A consistent copy of the latest state record."""
        for _ in range(100):
            try:
                return self._segment.state.read(READ_TIMEOUT_S)[0]
            except TornRead:
                time.sleep(POLL_S)
        raise RuntimeError("the world's state record stays torn: is the world stuck?")

    # -- the timeline ---------------------------------------------------------------------

    def start(self) -> None:
        """Record the timeline in a thread until stop()."""
        self._stop.clear()
        self.times_ns, self.targets, self.missed_steps = [], [], 0
        self._thread = threading.Thread(target=self._run, name="world-watch", daemon=True)
        self._thread.start()

    def stop(self) -> None:
        self._stop.set()
        if self._thread is not None:
            self._thread.join(1.0)
            self._thread = None

    def _run(self) -> None:
        last_sequence = None
        while not self._stop.is_set():
            record = self.read()
            sequence = int(record["arm_sequence"])
            if sequence != last_sequence:
                if last_sequence is not None and sequence > last_sequence + 1:
                    self.missed_steps += sequence - last_sequence - 1
                last_sequence = sequence
                self.times_ns.append(int(record["arm_time_ns"]))
                self.targets.append(float(record["target"][0]))
            time.sleep(POLL_S)

    def wait_until(self, predicate, timeout_s: float, poll_s: float = 0.0001):
        """Poll the state until predicate(record) holds: (record, observed time.time_ns(),
        gap), where gap says a step went unseen just before (so the record's time may be late
        by a step), or (None, None, True) on timeout."""
        deadline = time.monotonic() + timeout_s
        last_sequence = None
        while time.monotonic() < deadline:
            record = self.read()
            sequence = int(record["arm_sequence"])
            if predicate(record):
                gap = last_sequence is None or sequence > last_sequence + 1
                return record, time.time_ns(), gap
            last_sequence = sequence
            time.sleep(poll_s)
        return None, None, True

    def close(self) -> None:
        self.stop()
        segment, self._segment = self._segment, None
        if segment is not None:
            segment.close()
