"""Spreads each new joint target over the time since the previous one, at the servo rate.

Master commands arrive at 50 Hz or so; handing each target to the servo at once would make the
arm accelerate and brake between commands. Instead each target becomes a straight joint-space
segment from the current setpoint, lasting one command interval, and a thread writes the
setpoint to the hardware link every SETPOINT_PERIOD_S. The interval is a running average of
the gaps between commands (at most MAX_SEGMENT_S): over a network the gaps jitter, and following
each one would turn the jitter into velocity steps, which a stiff servo in contact turns into
force spikes. Commands at the servo rate pass straight through.

A command after a pause (no command for MAX_SEGMENT_S or more) belongs to no stream: there is
no interval to spread it over, so it takes only as long as its largest joint motion needs at
LONE_COMMAND_SPEED_RAD_PER_S (at least one servo period), and the running average starts
again. Spreading it over MAX_SEGMENT_S instead made a lone command reach the servo's target
50 ms late, which was most of the closed loop's time (the bench's `closed_loop`).
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable

import numpy as np

SETPOINT_PERIOD_S = 0.001  # the servo rate
MAX_SEGMENT_S = 0.05  # a segment never lasts longer: slower senders see 50 ms of smoothing
INTERVAL_SMOOTHING = 0.1  # weight of the newest gap in the running average
# The fastest joint speed a lone command's segment asks for; the PUMA 560's joints reach about
# 2-4 rad/s, so this leaves the servo margin.
LONE_COMMAND_SPEED_RAD_PER_S = 1.0


class SetpointInterpolator:
    """Writes setpoints through `write(q)` (the link's write_target). Thread-safe."""

    def __init__(self, write: Callable[[np.ndarray], None], start: np.ndarray,
                 on_error: Callable[[Exception], None],
                 monotonic_ns: Callable[[], int] = time.monotonic_ns, thread: bool = True):
        self._write = write
        self._on_error = on_error
        self._monotonic_ns = monotonic_ns
        self._lock = threading.Lock()
        self._wake = threading.Condition(self._lock)
        self._setpoint = np.asarray(start, float).copy()
        self._segment: tuple[np.ndarray, np.ndarray, float, float] | None = None
        self._last_command_s: float | None = None  # None: the next command is a lone one
        self._interval_s = MAX_SEGMENT_S
        self._closed = False
        self._thread: threading.Thread | None = None
        if thread:
            self._thread = threading.Thread(target=self._run, name="setpoints", daemon=True)
            self._thread.start()

    def _now_s(self) -> float:
        return self._monotonic_ns() * 1e-9

    def go(self, target: np.ndarray) -> None:
        """Head for `target`: over the running average of the gaps between commands, or, after
        a pause, as fast as LONE_COMMAND_SPEED_RAD_PER_S allows."""
        now = self._now_s()
        target = np.asarray(target, float)
        with self._lock:
            last = self._last_command_s
            self._last_command_s = now
            if last is None or now - last >= MAX_SEGMENT_S:
                self._interval_s = MAX_SEGMENT_S  # the next stream starts smoothing afresh
                motion = float(np.max(np.abs(target - self._setpoint)))
                duration = min(MAX_SEGMENT_S, motion / LONE_COMMAND_SPEED_RAD_PER_S)
            else:
                self._interval_s += INTERVAL_SMOOTHING * (max(now - last, 0.0) - self._interval_s)
                duration = self._interval_s
            if duration <= SETPOINT_PERIOD_S:
                self._segment = None
                self._setpoint = target.copy()
                self._write(self._setpoint)
                return
            self._segment = (self._setpoint.copy(), target.copy(), now, duration)
            self._wake.notify()

    def stop(self, setpoint: np.ndarray) -> None:
        """Abandon the segment; `setpoint` is where the caller has sent the servo instead."""
        with self._lock:
            self._segment = None
            self._setpoint = np.asarray(setpoint, float).copy()

    def close(self) -> None:
        with self._lock:
            self._closed = True
            self._segment = None
            self._wake.notify()
        if self._thread is not None:
            self._thread.join(1.0)

    def step(self) -> None:
        """Write the setpoint for now, if a segment is in progress: the thread's work for one
        period."""
        with self._lock:
            self._advance()

    def _run(self) -> None:
        with self._lock:
            while not self._closed:
                if self._segment is None:
                    self._wake.wait()
                    continue
                self._advance()
                self._wake.wait(SETPOINT_PERIOD_S)

    def _advance(self) -> None:
        """One setpoint along the segment (the lock is held)."""
        if self._segment is None:
            return
        start, end, t0, duration = self._segment
        fraction = min(1.0, (self._now_s() - t0) / duration)
        self._setpoint = start + (end - start) * fraction
        if fraction >= 1.0:
            self._segment = None
        try:
            self._write(self._setpoint)
        except Exception as exc:  # noqa: BLE001 - reported to the owner, which decides
            self._segment = None
            self._on_error(exc)
