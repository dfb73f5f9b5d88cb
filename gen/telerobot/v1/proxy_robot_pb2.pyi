import datetime

from google.protobuf import duration_pb2 as _duration_pb2
from google.protobuf import timestamp_pb2 as _timestamp_pb2
from telerobot.v1 import options_pb2 as _options_pb2
from telerobot.v1 import types_pb2 as _types_pb2
from google.protobuf.internal import containers as _containers
from google.protobuf.internal import enum_type_wrapper as _enum_type_wrapper
from google.protobuf import descriptor as _descriptor
from google.protobuf import message as _message
from collections.abc import Iterable as _Iterable, Mapping as _Mapping
from typing import ClassVar as _ClassVar, Optional as _Optional, Union as _Union

DESCRIPTOR: _descriptor.FileDescriptor

class RobotEventKind(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    ROBOT_EVENT_KIND_UNSPECIFIED: _ClassVar[RobotEventKind]
    ROBOT_EVENT_KIND_DATA_RECEIVED: _ClassVar[RobotEventKind]
    ROBOT_EVENT_KIND_ERROR: _ClassVar[RobotEventKind]
    ROBOT_EVENT_KIND_MOVED: _ClassVar[RobotEventKind]
    ROBOT_EVENT_KIND_STATUS_CHANGED: _ClassVar[RobotEventKind]
ROBOT_EVENT_KIND_UNSPECIFIED: RobotEventKind
ROBOT_EVENT_KIND_DATA_RECEIVED: RobotEventKind
ROBOT_EVENT_KIND_ERROR: RobotEventKind
ROBOT_EVENT_KIND_MOVED: RobotEventKind
ROBOT_EVENT_KIND_STATUS_CHANGED: RobotEventKind

class ConnectRequest(_message.Message):
    __slots__ = ()
    def __init__(self) -> None: ...

class ConnectResponse(_message.Message):
    __slots__ = ("status",)
    STATUS_FIELD_NUMBER: _ClassVar[int]
    status: _types_pb2.RobotStatus
    def __init__(self, status: _Optional[_Union[_types_pb2.RobotStatus, str]] = ...) -> None: ...

class InitializeRequest(_message.Message):
    __slots__ = ()
    def __init__(self) -> None: ...

class InitializeResponse(_message.Message):
    __slots__ = ("status",)
    STATUS_FIELD_NUMBER: _ClassVar[int]
    status: _types_pb2.RobotStatus
    def __init__(self, status: _Optional[_Union[_types_pb2.RobotStatus, str]] = ...) -> None: ...

class DisconnectRequest(_message.Message):
    __slots__ = ()
    def __init__(self) -> None: ...

class DisconnectResponse(_message.Message):
    __slots__ = ("status",)
    STATUS_FIELD_NUMBER: _ClassVar[int]
    status: _types_pb2.RobotStatus
    def __init__(self, status: _Optional[_Union[_types_pb2.RobotStatus, str]] = ...) -> None: ...

class GetStatusRequest(_message.Message):
    __slots__ = ()
    def __init__(self) -> None: ...

class GetStatusResponse(_message.Message):
    __slots__ = ("status", "reason", "change_time")
    STATUS_FIELD_NUMBER: _ClassVar[int]
    REASON_FIELD_NUMBER: _ClassVar[int]
    CHANGE_TIME_FIELD_NUMBER: _ClassVar[int]
    status: _types_pb2.RobotStatus
    reason: str
    change_time: _timestamp_pb2.Timestamp
    def __init__(self, status: _Optional[_Union[_types_pb2.RobotStatus, str]] = ..., reason: _Optional[str] = ..., change_time: _Optional[_Union[datetime.datetime, _timestamp_pb2.Timestamp, _Mapping]] = ...) -> None: ...

class GetStateRequest(_message.Message):
    __slots__ = ()
    def __init__(self) -> None: ...

class GetStateResponse(_message.Message):
    __slots__ = ("state",)
    STATE_FIELD_NUMBER: _ClassVar[int]
    state: _types_pb2.RobotState
    def __init__(self, state: _Optional[_Union[_types_pb2.RobotState, _Mapping]] = ...) -> None: ...

class GetToolFrameRequest(_message.Message):
    __slots__ = ()
    def __init__(self) -> None: ...

class GetArmInfoRequest(_message.Message):
    __slots__ = ()
    def __init__(self) -> None: ...

class GetArmInfoResponse(_message.Message):
    __slots__ = ("name", "joint_names", "joint_lower_limits_rad", "joint_upper_limits_rad", "joint_velocity_limits_rad_per_s", "joint_torque_limits_nm", "home_joint_positions_rad", "default_flange_to_tool")
    NAME_FIELD_NUMBER: _ClassVar[int]
    JOINT_NAMES_FIELD_NUMBER: _ClassVar[int]
    JOINT_LOWER_LIMITS_RAD_FIELD_NUMBER: _ClassVar[int]
    JOINT_UPPER_LIMITS_RAD_FIELD_NUMBER: _ClassVar[int]
    JOINT_VELOCITY_LIMITS_RAD_PER_S_FIELD_NUMBER: _ClassVar[int]
    JOINT_TORQUE_LIMITS_NM_FIELD_NUMBER: _ClassVar[int]
    HOME_JOINT_POSITIONS_RAD_FIELD_NUMBER: _ClassVar[int]
    DEFAULT_FLANGE_TO_TOOL_FIELD_NUMBER: _ClassVar[int]
    name: str
    joint_names: _containers.RepeatedScalarFieldContainer[str]
    joint_lower_limits_rad: _containers.RepeatedScalarFieldContainer[float]
    joint_upper_limits_rad: _containers.RepeatedScalarFieldContainer[float]
    joint_velocity_limits_rad_per_s: _containers.RepeatedScalarFieldContainer[float]
    joint_torque_limits_nm: _containers.RepeatedScalarFieldContainer[float]
    home_joint_positions_rad: _containers.RepeatedScalarFieldContainer[float]
    default_flange_to_tool: _types_pb2.Pose
    def __init__(self, name: _Optional[str] = ..., joint_names: _Optional[_Iterable[str]] = ..., joint_lower_limits_rad: _Optional[_Iterable[float]] = ..., joint_upper_limits_rad: _Optional[_Iterable[float]] = ..., joint_velocity_limits_rad_per_s: _Optional[_Iterable[float]] = ..., joint_torque_limits_nm: _Optional[_Iterable[float]] = ..., home_joint_positions_rad: _Optional[_Iterable[float]] = ..., default_flange_to_tool: _Optional[_Union[_types_pb2.Pose, _Mapping]] = ...) -> None: ...

class GetToolFrameResponse(_message.Message):
    __slots__ = ("flange_to_tool",)
    FLANGE_TO_TOOL_FIELD_NUMBER: _ClassVar[int]
    flange_to_tool: _types_pb2.Pose
    def __init__(self, flange_to_tool: _Optional[_Union[_types_pb2.Pose, _Mapping]] = ...) -> None: ...

class SetToolFrameRequest(_message.Message):
    __slots__ = ("flange_to_tool",)
    FLANGE_TO_TOOL_FIELD_NUMBER: _ClassVar[int]
    flange_to_tool: _types_pb2.Pose
    def __init__(self, flange_to_tool: _Optional[_Union[_types_pb2.Pose, _Mapping]] = ...) -> None: ...

class SetToolFrameResponse(_message.Message):
    __slots__ = ("flange_to_tool",)
    FLANGE_TO_TOOL_FIELD_NUMBER: _ClassVar[int]
    flange_to_tool: _types_pb2.Pose
    def __init__(self, flange_to_tool: _Optional[_Union[_types_pb2.Pose, _Mapping]] = ...) -> None: ...

class MoveJointsIncrementalRequest(_message.Message):
    __slots__ = ("delta_joint_positions_rad",)
    DELTA_JOINT_POSITIONS_RAD_FIELD_NUMBER: _ClassVar[int]
    delta_joint_positions_rad: _containers.RepeatedScalarFieldContainer[float]
    def __init__(self, delta_joint_positions_rad: _Optional[_Iterable[float]] = ...) -> None: ...

class MoveJointsIncrementalResponse(_message.Message):
    __slots__ = ("target_joint_positions_rad", "target_tool_pose")
    TARGET_JOINT_POSITIONS_RAD_FIELD_NUMBER: _ClassVar[int]
    TARGET_TOOL_POSE_FIELD_NUMBER: _ClassVar[int]
    target_joint_positions_rad: _containers.RepeatedScalarFieldContainer[float]
    target_tool_pose: _types_pb2.Pose
    def __init__(self, target_joint_positions_rad: _Optional[_Iterable[float]] = ..., target_tool_pose: _Optional[_Union[_types_pb2.Pose, _Mapping]] = ...) -> None: ...

class MoveCartesianIncrementalRequest(_message.Message):
    __slots__ = ("delta_position_m", "delta_rotation", "frame")
    DELTA_POSITION_M_FIELD_NUMBER: _ClassVar[int]
    DELTA_ROTATION_FIELD_NUMBER: _ClassVar[int]
    FRAME_FIELD_NUMBER: _ClassVar[int]
    delta_position_m: _types_pb2.Vector3
    delta_rotation: _types_pb2.Matrix3
    frame: _types_pb2.ReferenceFrame
    def __init__(self, delta_position_m: _Optional[_Union[_types_pb2.Vector3, _Mapping]] = ..., delta_rotation: _Optional[_Union[_types_pb2.Matrix3, _Mapping]] = ..., frame: _Optional[_Union[_types_pb2.ReferenceFrame, str]] = ...) -> None: ...

class MoveCartesianIncrementalResponse(_message.Message):
    __slots__ = ("target_joint_positions_rad", "target_tool_pose", "applied_fraction")
    TARGET_JOINT_POSITIONS_RAD_FIELD_NUMBER: _ClassVar[int]
    TARGET_TOOL_POSE_FIELD_NUMBER: _ClassVar[int]
    APPLIED_FRACTION_FIELD_NUMBER: _ClassVar[int]
    target_joint_positions_rad: _containers.RepeatedScalarFieldContainer[float]
    target_tool_pose: _types_pb2.Pose
    applied_fraction: float
    def __init__(self, target_joint_positions_rad: _Optional[_Iterable[float]] = ..., target_tool_pose: _Optional[_Union[_types_pb2.Pose, _Mapping]] = ..., applied_fraction: _Optional[float] = ...) -> None: ...

class HoldRequest(_message.Message):
    __slots__ = ("reason",)
    REASON_FIELD_NUMBER: _ClassVar[int]
    reason: str
    def __init__(self, reason: _Optional[str] = ...) -> None: ...

class HoldResponse(_message.Message):
    __slots__ = ("target_joint_positions_rad", "target_tool_pose", "cut_target_tool_pose")
    TARGET_JOINT_POSITIONS_RAD_FIELD_NUMBER: _ClassVar[int]
    TARGET_TOOL_POSE_FIELD_NUMBER: _ClassVar[int]
    CUT_TARGET_TOOL_POSE_FIELD_NUMBER: _ClassVar[int]
    target_joint_positions_rad: _containers.RepeatedScalarFieldContainer[float]
    target_tool_pose: _types_pb2.Pose
    cut_target_tool_pose: _types_pb2.Pose
    def __init__(self, target_joint_positions_rad: _Optional[_Iterable[float]] = ..., target_tool_pose: _Optional[_Union[_types_pb2.Pose, _Mapping]] = ..., cut_target_tool_pose: _Optional[_Union[_types_pb2.Pose, _Mapping]] = ...) -> None: ...

class StreamStateRequest(_message.Message):
    __slots__ = ("period",)
    PERIOD_FIELD_NUMBER: _ClassVar[int]
    period: _duration_pb2.Duration
    def __init__(self, period: _Optional[_Union[datetime.timedelta, _duration_pb2.Duration, _Mapping]] = ...) -> None: ...

class StreamStateResponse(_message.Message):
    __slots__ = ("state",)
    STATE_FIELD_NUMBER: _ClassVar[int]
    state: _types_pb2.RobotState
    def __init__(self, state: _Optional[_Union[_types_pb2.RobotState, _Mapping]] = ...) -> None: ...

class StreamRobotEventsRequest(_message.Message):
    __slots__ = ("kinds", "data_received_period")
    KINDS_FIELD_NUMBER: _ClassVar[int]
    DATA_RECEIVED_PERIOD_FIELD_NUMBER: _ClassVar[int]
    kinds: _containers.RepeatedScalarFieldContainer[RobotEventKind]
    data_received_period: _duration_pb2.Duration
    def __init__(self, kinds: _Optional[_Iterable[_Union[RobotEventKind, str]]] = ..., data_received_period: _Optional[_Union[datetime.timedelta, _duration_pb2.Duration, _Mapping]] = ...) -> None: ...

class StreamRobotEventsResponse(_message.Message):
    __slots__ = ("sequence", "event_time", "data_received", "error", "moved", "status_changed")
    SEQUENCE_FIELD_NUMBER: _ClassVar[int]
    EVENT_TIME_FIELD_NUMBER: _ClassVar[int]
    DATA_RECEIVED_FIELD_NUMBER: _ClassVar[int]
    ERROR_FIELD_NUMBER: _ClassVar[int]
    MOVED_FIELD_NUMBER: _ClassVar[int]
    STATUS_CHANGED_FIELD_NUMBER: _ClassVar[int]
    sequence: int
    event_time: _timestamp_pb2.Timestamp
    data_received: DataReceivedEvent
    error: RobotErrorEvent
    moved: MovedEvent
    status_changed: StatusChangedEvent
    def __init__(self, sequence: _Optional[int] = ..., event_time: _Optional[_Union[datetime.datetime, _timestamp_pb2.Timestamp, _Mapping]] = ..., data_received: _Optional[_Union[DataReceivedEvent, _Mapping]] = ..., error: _Optional[_Union[RobotErrorEvent, _Mapping]] = ..., moved: _Optional[_Union[MovedEvent, _Mapping]] = ..., status_changed: _Optional[_Union[StatusChangedEvent, _Mapping]] = ...) -> None: ...

class DataReceivedEvent(_message.Message):
    __slots__ = ("state",)
    STATE_FIELD_NUMBER: _ClassVar[int]
    state: _types_pb2.RobotState
    def __init__(self, state: _Optional[_Union[_types_pb2.RobotState, _Mapping]] = ...) -> None: ...

class RobotErrorEvent(_message.Message):
    __slots__ = ("reason", "message")
    REASON_FIELD_NUMBER: _ClassVar[int]
    MESSAGE_FIELD_NUMBER: _ClassVar[int]
    reason: str
    message: str
    def __init__(self, reason: _Optional[str] = ..., message: _Optional[str] = ...) -> None: ...

class MovedEvent(_message.Message):
    __slots__ = ("joint_positions_rad", "tool_pose")
    JOINT_POSITIONS_RAD_FIELD_NUMBER: _ClassVar[int]
    TOOL_POSE_FIELD_NUMBER: _ClassVar[int]
    joint_positions_rad: _containers.RepeatedScalarFieldContainer[float]
    tool_pose: _types_pb2.Pose
    def __init__(self, joint_positions_rad: _Optional[_Iterable[float]] = ..., tool_pose: _Optional[_Union[_types_pb2.Pose, _Mapping]] = ...) -> None: ...

class StatusChangedEvent(_message.Message):
    __slots__ = ("previous_status", "status", "reason")
    PREVIOUS_STATUS_FIELD_NUMBER: _ClassVar[int]
    STATUS_FIELD_NUMBER: _ClassVar[int]
    REASON_FIELD_NUMBER: _ClassVar[int]
    previous_status: _types_pb2.RobotStatus
    status: _types_pb2.RobotStatus
    reason: str
    def __init__(self, previous_status: _Optional[_Union[_types_pb2.RobotStatus, str]] = ..., status: _Optional[_Union[_types_pb2.RobotStatus, str]] = ..., reason: _Optional[str] = ...) -> None: ...

class EmergencyStopRequest(_message.Message):
    __slots__ = ("reason",)
    REASON_FIELD_NUMBER: _ClassVar[int]
    reason: str
    def __init__(self, reason: _Optional[str] = ...) -> None: ...

class EmergencyStopResponse(_message.Message):
    __slots__ = ("status", "stop_time")
    STATUS_FIELD_NUMBER: _ClassVar[int]
    STOP_TIME_FIELD_NUMBER: _ClassVar[int]
    status: _types_pb2.RobotStatus
    stop_time: _timestamp_pb2.Timestamp
    def __init__(self, status: _Optional[_Union[_types_pb2.RobotStatus, str]] = ..., stop_time: _Optional[_Union[datetime.datetime, _timestamp_pb2.Timestamp, _Mapping]] = ...) -> None: ...

class ResetRequest(_message.Message):
    __slots__ = ()
    def __init__(self) -> None: ...

class ResetResponse(_message.Message):
    __slots__ = ("status",)
    STATUS_FIELD_NUMBER: _ClassVar[int]
    status: _types_pb2.RobotStatus
    def __init__(self, status: _Optional[_Union[_types_pb2.RobotStatus, str]] = ...) -> None: ...
