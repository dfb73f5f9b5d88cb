"""The sensor's configuration (the papers' TimerValue, ThresholdValue, SensorThreadPriority)."""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass

from wire.errors import InvalidArgumentError

# The simulated sensor updates at the servo rate, so sampling faster only repeats samples.
MIN_PERIOD_S = 0.001
MAX_PERIOD_S = 1.0


class ThreadPriority(enum.Enum):
    """Five OS levels, as in the papers, with the Linux nice value each maps to (per thread).
    Levels above NORMAL need CAP_SYS_NICE (root has it); without it they stay at NORMAL and the
    sensor logs so. A nice value is a scheduling hint, not a real-time guarantee: under the GIL
    it decides which runnable thread the OS prefers, not which one holds the interpreter."""

    LOWEST = 10
    BELOW_NORMAL = 5
    NORMAL = 0
    ABOVE_NORMAL = -5
    HIGHEST = -10


@dataclass(frozen=True)
class SensorSettings:
    period_s: float = MIN_PERIOD_S
    threshold_force_n: float = 0.0
    threshold_torque_nm: float = 0.0
    thread_priority: ThreadPriority = ThreadPriority.NORMAL

    def validated(self) -> SensorSettings:
        """self, or InvalidArgumentError naming the first bad field."""
        if not math.isfinite(self.period_s) or not MIN_PERIOD_S <= self.period_s <= MAX_PERIOD_S:
            raise InvalidArgumentError(
                f"period {self.period_s * 1e3:.3f} ms is outside the sensor's range "
                f"{MIN_PERIOD_S * 1e3:.0f} ms .. {MAX_PERIOD_S * 1e3:.0f} ms", reason="BAD_PERIOD")
        for name in ("threshold_force_n", "threshold_torque_nm"):
            value = getattr(self, name)
            if not math.isfinite(value) or value < 0:
                raise InvalidArgumentError(f"{name} must be a finite number >= 0, got {value}",
                                           reason="BAD_THRESHOLD")
        return self


def exceeds(change_force: float, change_torque: float, threshold_force: float,
            threshold_torque: float) -> bool:
    """The papers' ThresholdValue test: true when some component moved by more than its
    threshold; thresholds of zero let every sample through."""
    if threshold_force == 0 and threshold_torque == 0:
        return True
    return ((threshold_force > 0 and change_force > threshold_force)
            or (threshold_torque > 0 and change_torque > threshold_torque))
