"""Conversions between the contracts' messages and numpy values, poses, times and durations.

Two ways to read a value:

* ``*_from_proto(message, what)`` checks what came from outside (lengths, NaN, rotations;
  InvalidArgument naming `what`), as a server does with a request;
* ``*_value(message)`` takes it as sent, as a client does with a server's answer.

Poses go out from anything with ``rotation`` and ``translation`` (a `Pose`, a ``pin.SE3``) and
come in as `Pose`.
"""

from __future__ import annotations

import numpy as np
from google.protobuf.duration_pb2 import Duration
from google.protobuf.timestamp_pb2 import Timestamp

from telerobot.v1 import types_pb2
from wire.checks import finite_vector, rotation_matrix
from wire.pose import Pose

# -- times and durations ------------------------------------------------------------------------


def timestamp(time_ns: int) -> Timestamp:
    """A Timestamp from nanoseconds since the Unix epoch."""
    stamp = Timestamp()
    stamp.FromNanoseconds(int(time_ns))
    return stamp


def time_ns(stamp: Timestamp) -> int:
    """Nanoseconds since the Unix epoch (0 for an unset Timestamp)."""
    return int(stamp.ToNanoseconds())


def duration(seconds_value: float) -> Duration:
    """A Duration from seconds, to the nearest nanosecond."""
    value = Duration()
    value.FromNanoseconds(int(round(seconds_value * 1e9)))
    return value


def seconds(duration_value: Duration) -> float:
    return duration_value.seconds + duration_value.nanos * 1e-9


# -- vectors, rotations, poses, wrenches ----------------------------------------------------------


def vector3_to_proto(values) -> types_pb2.Vector3:
    x, y, z = (float(v) for v in values)
    return types_pb2.Vector3(x=x, y=y, z=z)


def vector3_from_proto(vector: types_pb2.Vector3, what: str) -> np.ndarray:
    """(3,) float array; InvalidArgument for NaN or Inf."""
    return finite_vector([vector.x, vector.y, vector.z], 3, what)


def vector3_value(vector: types_pb2.Vector3) -> np.ndarray:
    """(3,) float array, as sent."""
    return np.array([vector.x, vector.y, vector.z], dtype=float)


def rotation_to_proto(rotation) -> types_pb2.Matrix3:
    return types_pb2.Matrix3(row_major=np.asarray(rotation, float).reshape(9).tolist())


def rotation_from_proto(matrix: types_pb2.Matrix3, what: str) -> np.ndarray:
    """A checked, re-orthonormalized rotation; identity when empty."""
    return rotation_matrix(matrix.row_major, what)


def rotation_value(matrix: types_pb2.Matrix3) -> np.ndarray:
    """Nine row-major values as a 3x3 array, as sent; the identity when empty."""
    if not matrix.row_major:
        return np.eye(3)
    # fromiter: half the time of asarray on a protobuf repeated field (on every command).
    return np.fromiter(matrix.row_major, dtype=float).reshape(3, 3)


def pose_to_proto(pose) -> types_pb2.Pose:
    """From a `Pose`, a ``pin.SE3`` or anything with ``rotation`` and ``translation``."""
    return types_pb2.Pose(position_m=vector3_to_proto(pose.translation),
                          rotation=rotation_to_proto(pose.rotation))


def pose_from_proto(pose: types_pb2.Pose, what: str) -> Pose:
    """A checked pose (finite position; rotation checked and re-orthonormalized)."""
    return Pose(rotation_from_proto(pose.rotation, f"{what}.rotation"),
                vector3_from_proto(pose.position_m, f"{what}.position_m"))


def pose_value(pose: types_pb2.Pose) -> Pose:
    """The pose as sent."""
    return Pose(rotation_value(pose.rotation), vector3_value(pose.position_m))


def wrench_to_proto(force_n, torque_nm) -> types_pb2.Wrench:
    return types_pb2.Wrench(force_n=vector3_to_proto(force_n),
                            torque_nm=vector3_to_proto(torque_nm))
