"""Conversions between protobuf messages and the numpy/Pinocchio values the domain uses.

Incoming values are checked here (lengths, NaN, rotations) so every servicer refuses bad input
the same way, with InvalidArgument.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin
from google.protobuf.duration_pb2 import Duration
from google.protobuf.timestamp_pb2 import Timestamp

from services.common.geometry import finite_vector, rotation_matrix
from telerobot.v1 import types_pb2


def timestamp(time_ns: int) -> Timestamp:
    stamp = Timestamp()
    stamp.FromNanoseconds(int(time_ns))
    return stamp


def seconds(duration: Duration) -> float:
    return duration.seconds + duration.nanos * 1e-9


def vector3_to_proto(values) -> types_pb2.Vector3:
    x, y, z = (float(v) for v in values)
    return types_pb2.Vector3(x=x, y=y, z=z)


def vector3_from_proto(vector: types_pb2.Vector3, what: str) -> np.ndarray:
    return finite_vector([vector.x, vector.y, vector.z], 3, what)


def rotation_to_proto(rotation: np.ndarray) -> types_pb2.Matrix3:
    return types_pb2.Matrix3(row_major=np.asarray(rotation, float).reshape(9).tolist())


def rotation_from_proto(matrix: types_pb2.Matrix3, what: str) -> np.ndarray:
    """A checked, re-orthonormalized rotation; identity when empty."""
    return rotation_matrix(matrix.row_major, what)


def pose_to_proto(pose: pin.SE3) -> types_pb2.Pose:
    return types_pb2.Pose(position_m=vector3_to_proto(pose.translation),
                          rotation=rotation_to_proto(pose.rotation))


def pose_from_proto(pose: types_pb2.Pose, what: str) -> pin.SE3:
    return pin.SE3(rotation_from_proto(pose.rotation, f"{what}.rotation"),
                   vector3_from_proto(pose.position_m, f"{what}.position_m"))


def wrench_to_proto(force_n, torque_nm) -> types_pb2.Wrench:
    return types_pb2.Wrench(force_n=vector3_to_proto(force_n),
                            torque_nm=vector3_to_proto(torque_nm))


def duration(seconds_value: float) -> Duration:
    value = Duration()
    value.FromNanoseconds(int(round(seconds_value * 1e9)))
    return value
