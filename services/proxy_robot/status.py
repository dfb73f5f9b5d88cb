"""The arm proxy's status machine and events (the papers' PUMA component), without transport."""

from __future__ import annotations

import enum
from dataclasses import dataclass

import numpy as np
import pinocchio as pin


class RobotStatus(enum.Enum):
    """Mirrors telerobot.v1.RobotStatus."""

    NOT_CONNECTED = 1
    CONNECTED = 2
    INITIALIZING = 3
    READY = 4
    MOVING = 5
    FAULT = 6
    ESTOPPED = 7


# Statuses in which the arm accepts motion commands.
MOTION_STATUSES = frozenset({RobotStatus.READY, RobotStatus.MOVING})


@dataclass(frozen=True)
class RobotSnapshot:
    """One state sample, with poses in the base frame."""

    sequence: int
    sample_time_ns: int
    status: RobotStatus
    joint_positions_rad: np.ndarray
    joint_velocities_rad_per_s: np.ndarray
    flange_pose: pin.SE3
    tool_pose: pin.SE3


@dataclass(frozen=True)
class StatusChanged:
    previous: RobotStatus
    status: RobotStatus
    reason: str


@dataclass(frozen=True)
class Moved:
    """The arm reached its commanded target."""

    joint_positions_rad: np.ndarray
    tool_pose: pin.SE3


@dataclass(frozen=True)
class RobotErrorRaised:
    reason: str  # UPPER_SNAKE_CASE
    message: str


@dataclass(frozen=True)
class RobotEvent:
    """An event with its place in the proxy's event sequence."""

    sequence: int
    time_ns: int
    payload: StatusChanged | Moved | RobotErrorRaised
