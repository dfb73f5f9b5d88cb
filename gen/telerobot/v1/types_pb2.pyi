import datetime

from google.protobuf import timestamp_pb2 as _timestamp_pb2
from google.protobuf.internal import containers as _containers
from google.protobuf.internal import enum_type_wrapper as _enum_type_wrapper
from google.protobuf import descriptor as _descriptor
from google.protobuf import message as _message
from collections.abc import Iterable as _Iterable, Mapping as _Mapping
from typing import ClassVar as _ClassVar, Optional as _Optional, Union as _Union

DESCRIPTOR: _descriptor.FileDescriptor

class RobotStatus(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    ROBOT_STATUS_UNSPECIFIED: _ClassVar[RobotStatus]
    ROBOT_STATUS_NOT_CONNECTED: _ClassVar[RobotStatus]
    ROBOT_STATUS_CONNECTED: _ClassVar[RobotStatus]
    ROBOT_STATUS_INITIALIZING: _ClassVar[RobotStatus]
    ROBOT_STATUS_READY: _ClassVar[RobotStatus]
    ROBOT_STATUS_MOVING: _ClassVar[RobotStatus]
    ROBOT_STATUS_FAULT: _ClassVar[RobotStatus]
    ROBOT_STATUS_ESTOPPED: _ClassVar[RobotStatus]

class ReferenceFrame(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    REFERENCE_FRAME_UNSPECIFIED: _ClassVar[ReferenceFrame]
    REFERENCE_FRAME_BASE: _ClassVar[ReferenceFrame]
    REFERENCE_FRAME_WRIST: _ClassVar[ReferenceFrame]
    REFERENCE_FRAME_TOOL: _ClassVar[ReferenceFrame]
ROBOT_STATUS_UNSPECIFIED: RobotStatus
ROBOT_STATUS_NOT_CONNECTED: RobotStatus
ROBOT_STATUS_CONNECTED: RobotStatus
ROBOT_STATUS_INITIALIZING: RobotStatus
ROBOT_STATUS_READY: RobotStatus
ROBOT_STATUS_MOVING: RobotStatus
ROBOT_STATUS_FAULT: RobotStatus
ROBOT_STATUS_ESTOPPED: RobotStatus
REFERENCE_FRAME_UNSPECIFIED: ReferenceFrame
REFERENCE_FRAME_BASE: ReferenceFrame
REFERENCE_FRAME_WRIST: ReferenceFrame
REFERENCE_FRAME_TOOL: ReferenceFrame

class Vector3(_message.Message):
    __slots__ = ("x", "y", "z")
    X_FIELD_NUMBER: _ClassVar[int]
    Y_FIELD_NUMBER: _ClassVar[int]
    Z_FIELD_NUMBER: _ClassVar[int]
    x: float
    y: float
    z: float
    def __init__(self, x: _Optional[float] = ..., y: _Optional[float] = ..., z: _Optional[float] = ...) -> None: ...

class Matrix3(_message.Message):
    __slots__ = ("row_major",)
    ROW_MAJOR_FIELD_NUMBER: _ClassVar[int]
    row_major: _containers.RepeatedScalarFieldContainer[float]
    def __init__(self, row_major: _Optional[_Iterable[float]] = ...) -> None: ...

class Pose(_message.Message):
    __slots__ = ("position_m", "rotation")
    POSITION_M_FIELD_NUMBER: _ClassVar[int]
    ROTATION_FIELD_NUMBER: _ClassVar[int]
    position_m: Vector3
    rotation: Matrix3
    def __init__(self, position_m: _Optional[_Union[Vector3, _Mapping]] = ..., rotation: _Optional[_Union[Matrix3, _Mapping]] = ...) -> None: ...

class Wrench(_message.Message):
    __slots__ = ("force_n", "torque_nm")
    FORCE_N_FIELD_NUMBER: _ClassVar[int]
    TORQUE_NM_FIELD_NUMBER: _ClassVar[int]
    force_n: Vector3
    torque_nm: Vector3
    def __init__(self, force_n: _Optional[_Union[Vector3, _Mapping]] = ..., torque_nm: _Optional[_Union[Vector3, _Mapping]] = ...) -> None: ...

class RobotState(_message.Message):
    __slots__ = ("sequence", "sample_time", "status", "joint_positions_rad", "joint_velocities_rad_per_s", "flange_pose", "tool_pose")
    SEQUENCE_FIELD_NUMBER: _ClassVar[int]
    SAMPLE_TIME_FIELD_NUMBER: _ClassVar[int]
    STATUS_FIELD_NUMBER: _ClassVar[int]
    JOINT_POSITIONS_RAD_FIELD_NUMBER: _ClassVar[int]
    JOINT_VELOCITIES_RAD_PER_S_FIELD_NUMBER: _ClassVar[int]
    FLANGE_POSE_FIELD_NUMBER: _ClassVar[int]
    TOOL_POSE_FIELD_NUMBER: _ClassVar[int]
    sequence: int
    sample_time: _timestamp_pb2.Timestamp
    status: RobotStatus
    joint_positions_rad: _containers.RepeatedScalarFieldContainer[float]
    joint_velocities_rad_per_s: _containers.RepeatedScalarFieldContainer[float]
    flange_pose: Pose
    tool_pose: Pose
    def __init__(self, sequence: _Optional[int] = ..., sample_time: _Optional[_Union[datetime.datetime, _timestamp_pb2.Timestamp, _Mapping]] = ..., status: _Optional[_Union[RobotStatus, str]] = ..., joint_positions_rad: _Optional[_Iterable[float]] = ..., joint_velocities_rad_per_s: _Optional[_Iterable[float]] = ..., flange_pose: _Optional[_Union[Pose, _Mapping]] = ..., tool_pose: _Optional[_Union[Pose, _Mapping]] = ...) -> None: ...
