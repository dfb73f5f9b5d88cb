"""What the DecisionServer needs from the slave arm and its sensor: a protocol, so the
supervisory logic stays free of gRPC. backends.py implements it over gRPC."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

import numpy as np
import pinocchio as pin


@dataclass(frozen=True)
class SlaveState:
    tool_pose: pin.SE3  # measured, base frame
    status: str  # RobotStatus name, e.g. "READY"
    sample_time_ns: int


@dataclass(frozen=True)
class SlaveWrench:
    force_n: np.ndarray  # tool frame, about the tool point (see ForceSensor)
    torque_nm: np.ndarray
    sequence: int
    sample_time_ns: int


@dataclass(frozen=True)
class MoveResult:
    target_tool_pose: pin.SE3
    applied_fraction: float


class Slave(Protocol):
    def move_cartesian(self, delta_position: np.ndarray, delta_rotation: np.ndarray,
                       frame: str) -> MoveResult:
        """Raises the domain error the arm answered with (OutOfRange, FailedPrecondition…)."""

    def hold(self, reason: str) -> None: ...

    def emergency_stop(self, reason: str) -> None: ...

    def reset(self) -> None: ...

    def state(self) -> SlaveState:
        """The latest measured state (Unavailable when none arrives)."""

    def wrench(self) -> SlaveWrench | None:
        """The latest wrench sample, None while the sensor is not reading."""
