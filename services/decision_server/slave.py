"""The DecisionServer's one port to the slave station: everything the supervisory logic does
to the arm and its sensor, and everything it learns from them. A protocol, so DecisionCore
stays free of gRPC: backends.py implements it over gRPC, tests/fakes/slave.py with a few
lines of physics."""

from __future__ import annotations

from collections.abc import Callable, Iterator
from dataclasses import dataclass
from typing import Protocol

import numpy as np
import pinocchio as pin

# Statuses in which the arm refuses motion until Reset (ProxyRobot's RobotStatus names).
LATCHED_STATUSES = frozenset({"ESTOPPED", "FAULT"})


@dataclass(frozen=True)
class SlaveState:
    tool_pose: pin.SE3  # measured, base frame
    status: str  # RobotStatus name, e.g. "READY"
    sample_time_ns: int
    reason: str = ""  # why the status was entered, when the source says
    joint_positions_rad: tuple[float, ...] = ()  # measured, when the source says


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


class WrenchStream(Protocol):
    """Wrench samples as they come; `cancel()` (from any thread) ends the iteration."""

    def __iter__(self) -> Iterator[SlaveWrench]: ...

    def cancel(self) -> None: ...


class Slave(Protocol):
    """The arm (ProxyRobot) and its wrist sensor (ForceSensor), as one dependency.

    Every call raises the domain error the slave answered with (OutOfRange,
    FailedPrecondition…), or Unavailable when it cannot be reached."""

    on_state: Callable[[SlaveState], None]
    """Called with every state sample the arm reports (its status included), in order."""

    on_robot_event: Callable[[object], None]
    """Called with every event the arm raises, as it came."""

    def move_cartesian(self, delta_position: np.ndarray, delta_rotation: np.ndarray,
                       frame: str) -> MoveResult: ...

    def move_joints(self, delta_joints_rad: np.ndarray) -> MoveResult: ...

    def hold(self, reason: str) -> tuple[pin.SE3, pin.SE3]:
        """A controlled stop without a latch; returns the tool pose the arm stops at and the
        one it was going to."""

    def sensor_is_reading(self, timeout_s: float) -> bool:
        """Whether the sensor is sampling, asked of the sensor itself; Unavailable when it does
        not answer within `timeout_s` (down, or hung)."""

    def emergency_stop(self, reason: str) -> str:
        """Latch a stop at the hardware; returns the status after it (ESTOPPED)."""

    def stop_now(self) -> None:
        """Start latching a stop without waiting for it: an emergency stop is on its way
        (emergency_stop() follows with the reason). Must not block."""

    def reset(self) -> str:
        """Clear a latch; returns the status after it."""

    def arm_name(self) -> str:
        """The arm's name, as its description declares it (ProxyRobot.GetArmInfo's)."""
        ...

    def set_tool_frame(self, flange_to_tool: pin.SE3) -> pin.SE3:
        """Set the tool frame on the arm and on the sensor alike; returns the one in force."""

    def state(self) -> SlaveState:
        """The latest measured state (Unavailable when none arrives)."""

    def wrench(self) -> SlaveWrench | None:
        """The latest wrench sample if it is fresh, None while the sensor is not reading."""

    def wrench_stream(self, decimation: int) -> WrenchStream:
        """Every `decimation`-th sample until cancelled; Unavailable if it ends otherwise."""

    def health(self) -> dict[str, str]:
        """Each dependency the DecisionServer has ("proxy_robot", "force_sensor",
        "stereo_camera", and "emergency_stop" when it has the band) and whether it answers:
        "ok" while its health check says it serves, why not otherwise, for people
        ("UNAVAILABLE: failed to connect to all addresses…"). Never blocks or raises."""

    def close(self) -> None: ...
