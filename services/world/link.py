"""The hardware link: what a driver needs from an arm and a wrist force/torque sensor.

The simulated world implements it over shared memory (`shm_link.py`); a real robot controller or
a real F/T sensor driver implements the same protocols. Nothing here knows about MuJoCo or gRPC.
Errors: implementations raise wire.errors.UnavailableError when the hardware does not
answer (process gone, heartbeat stale, link closed).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Protocol

import numpy as np

from wire.errors import InvalidArgumentError, OutOfRangeError

# Targets may lie this far past a joint limit (the measured position of an arm pushed against
# its limit stop, sent back as a hold target); the servo clips them onto the limit.
LIMIT_TOLERANCE_RAD = 0.02


def checked_joint_target(joint_positions_rad, lower: np.ndarray,
                         upper: np.ndarray) -> np.ndarray:
    """A joint target (one angle per joint: the limits' length) in rad, as every ArmLink takes
    it: InvalidArgumentError on a wrong shape or NaN; OutOfRangeError past a joint limit by more
    than LIMIT_TOLERANCE_RAD."""
    target = np.asarray(joint_positions_rad, dtype=float)
    joints = len(lower)
    if target.shape != (joints,) or not np.isfinite(target).all():
        raise InvalidArgumentError(
            f"a joint target needs {joints} finite angles in rad, got {target!r}",
            reason="BAD_TARGET")
    outside = (target < lower - LIMIT_TOLERANCE_RAD) | (target > upper + LIMIT_TOLERANCE_RAD)
    if outside.any():
        joint = int(np.flatnonzero(outside)[0])
        raise OutOfRangeError(
            f"joint {joint + 1} target {np.degrees(target[joint]):.1f} deg is past its limit "
            f"({np.degrees(lower[joint]):.0f}..{np.degrees(upper[joint]):.0f} deg)",
            reason="JOINT_LIMIT")
    return target


def checked_duration(duration_s) -> float:
    """A target's segment duration (s), as every ArmLink takes it: InvalidArgumentError unless a
    finite number >= 0 (the servo clips a long one to its own cap)."""
    duration = float(duration_s)
    if not math.isfinite(duration) or duration < 0.0:
        raise InvalidArgumentError(f"a target's segment duration must be finite and >= 0 s, got "
                                   f"{duration_s!r}", reason="BAD_DURATION")
    return duration


@dataclass(frozen=True)
class ArmSample:
    """One servo-rate sample of the arm."""

    sequence: int  # servo step counter; increases by one per servo period
    sample_time_ns: int  # wall clock (time.time_ns) when the sample was taken
    joint_positions_rad: np.ndarray  # (joints,)
    joint_velocities_rad_per_s: np.ndarray  # (joints,)
    # (joints,) the latest target (the end of its segment, if one runs)
    joint_targets_rad: np.ndarray
    hold_latched: bool  # a latched hold (emergency stop) is in force: targets are ignored
    fault: str  # empty when healthy; otherwise what the hardware reported


@dataclass(frozen=True)
class RawWrench:
    """One sample of the wrist sensor, in the sensor's own frame, about its origin."""

    sequence: int  # increases by one per sensor sample
    sample_time_ns: int  # wall clock (time.time_ns)
    force_n: np.ndarray  # (3,)
    torque_nm: np.ndarray  # (3,)


class ArmLink(Protocol):
    """Joint-level access to an arm whose servo tracks a joint target under a velocity cap."""

    def read_arm(self) -> ArmSample:
        """The latest sample."""

    def write_target(self, joint_positions_rad: np.ndarray, duration_s: float = 0.0) -> None:
        """Make the servo track a new joint target (6,), reached along a straight joint-space
        segment from its setpoint now, lasting `duration_s` (0: at once); a target written
        meanwhile replaces the segment from where it is. Ignored while a hold is latched,
        which also drops the segment."""

    def hold(self) -> None:
        """Controlled stop: brake to rest at the acceleration cap and latch there, so later
        targets are ignored until release_hold(). At rest the arm holds where it is; from full
        speed it stops within about 0.05 rad."""

    def release_hold(self) -> None:
        """Clear the latch. The target stays the current position: nothing starts moving."""

    def close(self) -> None:
        """Detach from the hardware. The arm keeps holding its last target."""


class EmergencyStopLink(Protocol):
    """The arm's emergency-stop input, reached without the driver: on a real arm, a safety
    relay or the controller's own stop interface. It works while the driver process is busy or
    stuck, so the stop never queues behind that process's work."""

    def stop(self) -> int:
        """Latch the same controlled stop as ArmLink.hold(); returns when it was requested
        (time.time_ns()). Cleared only through the driver's release_hold()."""

    def close(self) -> None:
        """Detach. A latched stop stays latched."""


class WrenchLink(Protocol):
    """Access to a six-axis force/torque sensor."""

    def read_wrench(self) -> RawWrench:
        """The latest sample."""

    def close(self) -> None:
        """Detach from the sensor."""
