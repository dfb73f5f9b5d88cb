"""PoseHistory: where the tool was at a given moment, from timed measurements.

A video frame shows the arm as it was when the frame was captured, one path delay and more ago;
the AR ball drawn on it belongs where the tool was then, not where it is predicted now. The
station measures the tool pose and stamps it (every Teleoperate ack carries one); this keeps the
last few seconds of them and answers for any time between two, by linear interpolation.
"""

from __future__ import annotations

import bisect
import threading

import numpy as np

KEEP_S = 5.0


class PoseHistory:
    """Timed tool points (base frame, metres; times in ns on the station's clock)."""

    def __init__(self, keep_s: float = KEEP_S):
        self._keep_ns = int(keep_s * 1e9)
        self._lock = threading.Lock()
        self._times: list[int] = []
        self._points: list[np.ndarray] = []

    def add(self, time_ns: int, point) -> None:
        """A measurement; an older one than the newest is ignored (measurements come in order
        from one stream, and a late duplicate says nothing new)."""
        point = np.asarray(point, float).reshape(3)
        with self._lock:
            if self._times and time_ns <= self._times[-1]:
                return
            self._times.append(time_ns)
            self._points.append(point)
            drop = bisect.bisect_left(self._times, time_ns - self._keep_ns)
            del self._times[:drop], self._points[:drop]

    def at(self, time_ns: int, tolerance_ns: int = 100_000_000) -> np.ndarray | None:
        """The point at `time_ns`, interpolated between the measurements around it; the
        nearest one if `time_ns` is within `tolerance_ns` outside them; None otherwise."""
        with self._lock:
            times, points = self._times, self._points
            if not times or time_ns < times[0] - tolerance_ns \
                    or time_ns > times[-1] + tolerance_ns:
                return None
            after = bisect.bisect_left(times, time_ns)
            if after == 0:
                return points[0].copy()
            if after == len(times):
                return points[-1].copy()
            t0, t1 = times[after - 1], times[after]
            share = (time_ns - t0) / (t1 - t0)
            return points[after - 1] + share * (points[after] - points[after - 1])
