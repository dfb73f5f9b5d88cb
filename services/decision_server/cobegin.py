"""Cobegin barriers and the simulated workload of the Parma paper's precedence experiment.

A cobegin batch of n actions starts only when all n have reached the server; each then runs on
the lane its caller asked for. The workload action (BusyWork) models Parma's actions: each
occupies the server's one simulated processor for a duration, which a fixed-priority scheduler
hands out in 1 ms slices to the most urgent lane waiting, as the paper's SCHED_RR real-time
threads would. Without cobegin the action that arrives first runs first; with it, the most
urgent one does. Each slice really computes, so the load is real. No gRPC here.
"""

from __future__ import annotations

import threading
import time
import uuid
from collections.abc import Callable
from dataclasses import dataclass, field

from services.runtime.clock import SYSTEM_CLOCK, Clock
from wire.errors import (
    DeadlineExceededError,
    InvalidArgumentError,
    NotFoundError,
    ResourceExhaustedError,
)

SLICE_S = 0.001
MAX_ACTIONS = 64
DEFAULT_BARRIER_TIMEOUT_S = 10.0
MAX_BARRIER_TIMEOUT_S = 60.0
# Cobegins open at once, across every caller: each holds a little memory until its actions
# arrive or, abandoned (none arrived by its deadline), the next opening drops it.
MAX_OPEN_BARRIERS = 256


@dataclass
class _Barrier:
    expected: int
    deadline: float
    arrived: int = 0
    failed: bool = False
    released: threading.Condition = field(default_factory=threading.Condition)


class Barriers:
    """Open cobegin barriers, by id."""

    def __init__(self, clock: Clock = SYSTEM_CLOCK):
        self._clock = clock
        self._lock = threading.Lock()
        self._barriers: dict[str, _Barrier] = {}

    def open(self, count: int, timeout_s: float) -> tuple[str, float]:
        if not 1 <= count <= MAX_ACTIONS:
            raise InvalidArgumentError(f"action_count must be 1..{MAX_ACTIONS}", reason="BAD_COUNT")
        timeout_s = timeout_s or DEFAULT_BARRIER_TIMEOUT_S
        if not 0 < timeout_s <= MAX_BARRIER_TIMEOUT_S:
            raise InvalidArgumentError(f"barrier_timeout must be 0..{MAX_BARRIER_TIMEOUT_S} s",
                                       reason="BAD_TIMEOUT")
        barrier_id = uuid.uuid4().hex
        now = self._clock.monotonic()
        with self._lock:
            abandoned = [key for key, barrier in self._barriers.items()
                         if barrier.arrived == 0 and barrier.deadline <= now]
            for key in abandoned:
                del self._barriers[key]
            if len(self._barriers) >= MAX_OPEN_BARRIERS:
                raise ResourceExhaustedError(
                    f"{MAX_OPEN_BARRIERS} cobegins are open: run their actions, or let them "
                    "time out, before opening another", reason="TOO_MANY_COBEGINS")
            self._barriers[barrier_id] = _Barrier(count, now + timeout_s)
        return barrier_id, timeout_s

    def arrived(self, barrier_id: str) -> int:
        """How many actions wait at an open barrier (0 once it is released or unknown)."""
        with self._lock:
            barrier = self._barriers.get(barrier_id)
        return barrier.arrived if barrier is not None else 0

    def arrive_and_wait(self, barrier_id: str) -> None:
        """Block until every action of the batch has arrived; DeadlineExceededError for all of them
        if one never does."""
        with self._lock:
            barrier = self._barriers.get(barrier_id)
        if barrier is None:
            raise NotFoundError(f"no open cobegin '{barrier_id}'", reason="NO_COBEGIN")
        with barrier.released:
            barrier.arrived += 1
            if barrier.arrived > barrier.expected:
                raise InvalidArgumentError("more actions than the cobegin declared",
                                           reason="TOO_MANY_ACTIONS")
            if barrier.arrived == barrier.expected:
                barrier.released.notify_all()
            while barrier.arrived < barrier.expected and not barrier.failed:
                remaining = barrier.deadline - self._clock.monotonic()
                if remaining <= 0:
                    barrier.failed = True
                    barrier.released.notify_all()
                    break
                barrier.released.wait(remaining)
            failed = barrier.failed
        if barrier.arrived >= barrier.expected or failed:
            with self._lock:
                self._barriers.pop(barrier_id, None)
        if failed:
            raise DeadlineExceededError(f"cobegin: only {barrier.arrived} of {barrier.expected} "
                                        "actions arrived in time; none ran",
                                        reason="BARRIER_TIMEOUT")


# The longest BusyWork action: Parma's workloads last milliseconds, and a longer one would
# hold a lane thread and a core for nothing.
MAX_BUSY_WORK_S = 10.0


class SimulatedProcessor:
    """One processor shared by BusyWork actions, sliced by priority (0 is the most urgent)."""

    def __init__(self):
        self._lock = threading.Condition()
        self._waiting: list[int] = []  # priorities of actions wanting the next slice
        self._busy = False

    @property
    def busy(self) -> bool:
        """Whether an action holds the processor now (it has started, and has a slice)."""
        return self._busy

    def run(self, priority: int, duration_s: float,
            cancelled: Callable[[], bool] = lambda: False) -> tuple[int, int]:
        """Compute for `duration_s` of processor time, or until `cancelled()`; returns (start,
        end) in time.time_ns()."""
        if not 0 <= duration_s <= MAX_BUSY_WORK_S:
            raise InvalidArgumentError(f"busy_work.duration must be 0..{MAX_BUSY_WORK_S:.0f} s",
                                       reason="BAD_DURATION")
        start_ns = 0
        remaining = duration_s
        while remaining > 0 and not cancelled():
            with self._lock:
                self._waiting.append(priority)
                while self._busy or min(self._waiting) < priority:
                    self._lock.wait()
                self._waiting.remove(priority)
                self._busy = True
            if not start_ns:
                start_ns = time.time_ns()
            _compute(min(SLICE_S, remaining))
            remaining -= SLICE_S
            with self._lock:
                self._busy = False
                self._lock.notify_all()
        return start_ns or time.time_ns(), time.time_ns()


def _compute(seconds: float) -> None:
    """Real work for `seconds` of wall time."""
    end = time.perf_counter() + seconds
    value = 0
    while time.perf_counter() < end:
        value += 1
