"""Conversions between protobuf messages and the numpy/Pinocchio values the domain uses.

Incoming values are checked here (lengths, NaN, rotations) so every servicer refuses bad input
the same way, with InvalidArgument. Built on ``wire.convert`` (shared with the clients), which
this re-exports; the one difference is that poses come in as ``pin.SE3`` here.
"""

from __future__ import annotations

import pinocchio as pin

from telerobot.v1 import types_pb2
from wire import convert as _wire
from wire.convert import (
    duration,
    pose_to_proto,
    rotation_from_proto,
    rotation_to_proto,
    seconds,
    time_ns,
    timestamp,
    vector3_from_proto,
    vector3_to_proto,
    wrench_to_proto,
)

__all__ = [
    "duration", "pose_from_proto", "pose_to_proto", "rotation_from_proto", "rotation_to_proto",
    "seconds", "time_ns", "timestamp", "trusted_pose", "vector3_from_proto", "vector3_to_proto",
    "wrench_to_proto",
]


def pose_from_proto(pose: types_pb2.Pose, what: str) -> pin.SE3:
    """A checked pose (``wire.convert.pose_from_proto``) as a ``pin.SE3``."""
    checked = _wire.pose_from_proto(pose, what)
    return pin.SE3(checked.rotation, checked.translation)


def trusted_pose(pose: types_pb2.Pose) -> pin.SE3:
    """A pose from the station's own services, as sent: no checks, no re-orthonormalization
    (they cost more than the rest of a command's handling on the DecisionServer)."""
    return pin.SE3(_wire.rotation_value(pose.rotation), _wire.vector3_value(pose.position_m))
