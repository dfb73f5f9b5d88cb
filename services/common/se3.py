"""Poses from protobuf messages as ``pin.SE3``, the type the station's domain computes with.

Every other conversion is ``wire.convert`` (shared with the clients), which checks incoming
values (lengths, NaN, rotations) so every servicer refuses bad input the same way.
"""

from __future__ import annotations

import pinocchio as pin

from telerobot.v1 import types_pb2
from wire import convert


def pose_from_proto(pose: types_pb2.Pose, what: str) -> pin.SE3:
    """A checked pose (``wire.convert.pose_from_proto``) as a ``pin.SE3``."""
    checked = convert.pose_from_proto(pose, what)
    return pin.SE3(checked.rotation, checked.translation)


def trusted_pose(pose: types_pb2.Pose) -> pin.SE3:
    """A pose from the station's own services, as sent: no checks, no re-orthonormalization
    (they cost more than the rest of a command's handling on the DecisionServer)."""
    return pin.SE3(convert.rotation_value(pose.rotation), convert.vector3_value(pose.position_m))
