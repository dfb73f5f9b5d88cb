import datetime

from google.protobuf import duration_pb2 as _duration_pb2
from google.protobuf import timestamp_pb2 as _timestamp_pb2
from telerobot.v1 import options_pb2 as _options_pb2
from telerobot.v1 import proxy_robot_pb2 as _proxy_robot_pb2
from telerobot.v1 import types_pb2 as _types_pb2
from google.protobuf.internal import containers as _containers
from google.protobuf.internal import enum_type_wrapper as _enum_type_wrapper
from google.protobuf import descriptor as _descriptor
from google.protobuf import message as _message
from collections.abc import Iterable as _Iterable, Mapping as _Mapping
from typing import ClassVar as _ClassVar, Optional as _Optional, Union as _Union

DESCRIPTOR: _descriptor.FileDescriptor

class EpisodeOutcome(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    EPISODE_OUTCOME_UNSPECIFIED: _ClassVar[EpisodeOutcome]
    EPISODE_OUTCOME_SUCCEEDED: _ClassVar[EpisodeOutcome]
    EPISODE_OUTCOME_FAILED: _ClassVar[EpisodeOutcome]
    EPISODE_OUTCOME_DISCARDED: _ClassVar[EpisodeOutcome]

class RecordingFormat(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    RECORDING_FORMAT_UNSPECIFIED: _ClassVar[RecordingFormat]
    RECORDING_FORMAT_JSONL: _ClassVar[RecordingFormat]
    RECORDING_FORMAT_MCAP: _ClassVar[RecordingFormat]

class TeleopSessionState(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    TELEOP_SESSION_STATE_UNSPECIFIED: _ClassVar[TeleopSessionState]
    TELEOP_SESSION_STATE_OPENED: _ClassVar[TeleopSessionState]
    TELEOP_SESSION_STATE_DETACHED: _ClassVar[TeleopSessionState]
    TELEOP_SESSION_STATE_RESUMED: _ClassVar[TeleopSessionState]
    TELEOP_SESSION_STATE_CLOSED: _ClassVar[TeleopSessionState]

class CommandOutcome(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    COMMAND_OUTCOME_UNSPECIFIED: _ClassVar[CommandOutcome]
    COMMAND_OUTCOME_APPLIED: _ClassVar[CommandOutcome]
    COMMAND_OUTCOME_MODIFIED: _ClassVar[CommandOutcome]
    COMMAND_OUTCOME_INDEXED: _ClassVar[CommandOutcome]
    COMMAND_OUTCOME_REJECTED: _ClassVar[CommandOutcome]
    COMMAND_OUTCOME_HEARTBEAT: _ClassVar[CommandOutcome]
    COMMAND_OUTCOME_DUPLICATE: _ClassVar[CommandOutcome]
    COMMAND_OUTCOME_MERGED_LATE: _ClassVar[CommandOutcome]

class ControlMode(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    CONTROL_MODE_UNSPECIFIED: _ClassVar[ControlMode]
    CONTROL_MODE_EXCLUSIVE: _ClassVar[ControlMode]
    CONTROL_MODE_COLLABORATIVE: _ClassVar[ControlMode]

class ConstraintType(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    CONSTRAINT_TYPE_UNSPECIFIED: _ClassVar[ConstraintType]
    CONSTRAINT_TYPE_PLANAR: _ClassVar[ConstraintType]
    CONSTRAINT_TYPE_LINEAR: _ClassVar[ConstraintType]

class ReplayState(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    REPLAY_STATE_UNSPECIFIED: _ClassVar[ReplayState]
    REPLAY_STATE_RUNNING: _ClassVar[ReplayState]
    REPLAY_STATE_FINISHED: _ClassVar[ReplayState]
    REPLAY_STATE_INTERRUPTED: _ClassVar[ReplayState]

class DependencyState(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    DEPENDENCY_STATE_UNSPECIFIED: _ClassVar[DependencyState]
    DEPENDENCY_STATE_SERVING: _ClassVar[DependencyState]
    DEPENDENCY_STATE_NOT_SERVING: _ClassVar[DependencyState]
    DEPENDENCY_STATE_RESTARTING: _ClassVar[DependencyState]

class Passivity(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    PASSIVITY_UNSPECIFIED: _ClassVar[Passivity]
    PASSIVITY_OFF: _ClassVar[Passivity]
    PASSIVITY_TDPA: _ClassVar[Passivity]
EPISODE_OUTCOME_UNSPECIFIED: EpisodeOutcome
EPISODE_OUTCOME_SUCCEEDED: EpisodeOutcome
EPISODE_OUTCOME_FAILED: EpisodeOutcome
EPISODE_OUTCOME_DISCARDED: EpisodeOutcome
RECORDING_FORMAT_UNSPECIFIED: RecordingFormat
RECORDING_FORMAT_JSONL: RecordingFormat
RECORDING_FORMAT_MCAP: RecordingFormat
TELEOP_SESSION_STATE_UNSPECIFIED: TeleopSessionState
TELEOP_SESSION_STATE_OPENED: TeleopSessionState
TELEOP_SESSION_STATE_DETACHED: TeleopSessionState
TELEOP_SESSION_STATE_RESUMED: TeleopSessionState
TELEOP_SESSION_STATE_CLOSED: TeleopSessionState
COMMAND_OUTCOME_UNSPECIFIED: CommandOutcome
COMMAND_OUTCOME_APPLIED: CommandOutcome
COMMAND_OUTCOME_MODIFIED: CommandOutcome
COMMAND_OUTCOME_INDEXED: CommandOutcome
COMMAND_OUTCOME_REJECTED: CommandOutcome
COMMAND_OUTCOME_HEARTBEAT: CommandOutcome
COMMAND_OUTCOME_DUPLICATE: CommandOutcome
COMMAND_OUTCOME_MERGED_LATE: CommandOutcome
CONTROL_MODE_UNSPECIFIED: ControlMode
CONTROL_MODE_EXCLUSIVE: ControlMode
CONTROL_MODE_COLLABORATIVE: ControlMode
CONSTRAINT_TYPE_UNSPECIFIED: ConstraintType
CONSTRAINT_TYPE_PLANAR: ConstraintType
CONSTRAINT_TYPE_LINEAR: ConstraintType
REPLAY_STATE_UNSPECIFIED: ReplayState
REPLAY_STATE_RUNNING: ReplayState
REPLAY_STATE_FINISHED: ReplayState
REPLAY_STATE_INTERRUPTED: ReplayState
DEPENDENCY_STATE_UNSPECIFIED: DependencyState
DEPENDENCY_STATE_SERVING: DependencyState
DEPENDENCY_STATE_NOT_SERVING: DependencyState
DEPENDENCY_STATE_RESTARTING: DependencyState
PASSIVITY_UNSPECIFIED: Passivity
PASSIVITY_OFF: Passivity
PASSIVITY_TDPA: Passivity

class TeleoperateRequest(_message.Message):
    __slots__ = ("init", "command", "heartbeat", "end", "commands")
    INIT_FIELD_NUMBER: _ClassVar[int]
    COMMAND_FIELD_NUMBER: _ClassVar[int]
    HEARTBEAT_FIELD_NUMBER: _ClassVar[int]
    END_FIELD_NUMBER: _ClassVar[int]
    COMMANDS_FIELD_NUMBER: _ClassVar[int]
    init: TeleoperateInit
    command: MasterCommand
    heartbeat: Heartbeat
    end: TeleoperateEnd
    commands: MasterCommands
    def __init__(self, init: _Optional[_Union[TeleoperateInit, _Mapping]] = ..., command: _Optional[_Union[MasterCommand, _Mapping]] = ..., heartbeat: _Optional[_Union[Heartbeat, _Mapping]] = ..., end: _Optional[_Union[TeleoperateEnd, _Mapping]] = ..., commands: _Optional[_Union[MasterCommands, _Mapping]] = ...) -> None: ...

class MasterCommands(_message.Message):
    __slots__ = ("commands",)
    COMMANDS_FIELD_NUMBER: _ClassVar[int]
    commands: _containers.RepeatedCompositeFieldContainer[MasterCommand]
    def __init__(self, commands: _Optional[_Iterable[_Union[MasterCommand, _Mapping]]] = ...) -> None: ...

class TeleoperateEnd(_message.Message):
    __slots__ = ()
    def __init__(self) -> None: ...

class TeleoperateInit(_message.Message):
    __slots__ = ("operator_id", "lease_id", "mapping", "watchdog_timeout", "resume_session_id", "passivity", "grouped_acks", "max_command_age")
    OPERATOR_ID_FIELD_NUMBER: _ClassVar[int]
    LEASE_ID_FIELD_NUMBER: _ClassVar[int]
    MAPPING_FIELD_NUMBER: _ClassVar[int]
    WATCHDOG_TIMEOUT_FIELD_NUMBER: _ClassVar[int]
    RESUME_SESSION_ID_FIELD_NUMBER: _ClassVar[int]
    PASSIVITY_FIELD_NUMBER: _ClassVar[int]
    GROUPED_ACKS_FIELD_NUMBER: _ClassVar[int]
    MAX_COMMAND_AGE_FIELD_NUMBER: _ClassVar[int]
    operator_id: str
    lease_id: str
    mapping: _types_pb2.ReferenceFrame
    watchdog_timeout: _duration_pb2.Duration
    resume_session_id: str
    passivity: Passivity
    grouped_acks: bool
    max_command_age: _duration_pb2.Duration
    def __init__(self, operator_id: _Optional[str] = ..., lease_id: _Optional[str] = ..., mapping: _Optional[_Union[_types_pb2.ReferenceFrame, str]] = ..., watchdog_timeout: _Optional[_Union[datetime.timedelta, _duration_pb2.Duration, _Mapping]] = ..., resume_session_id: _Optional[str] = ..., passivity: _Optional[_Union[Passivity, str]] = ..., grouped_acks: _Optional[bool] = ..., max_command_age: _Optional[_Union[datetime.timedelta, _duration_pb2.Duration, _Mapping]] = ...) -> None: ...

class MasterCommand(_message.Message):
    __slots__ = ("sequence", "send_time", "delta_position_m", "delta_rotation", "clutch_engaged", "master_energy", "ack_receipt")
    SEQUENCE_FIELD_NUMBER: _ClassVar[int]
    SEND_TIME_FIELD_NUMBER: _ClassVar[int]
    DELTA_POSITION_M_FIELD_NUMBER: _ClassVar[int]
    DELTA_ROTATION_FIELD_NUMBER: _ClassVar[int]
    CLUTCH_ENGAGED_FIELD_NUMBER: _ClassVar[int]
    MASTER_ENERGY_FIELD_NUMBER: _ClassVar[int]
    ACK_RECEIPT_FIELD_NUMBER: _ClassVar[int]
    sequence: int
    send_time: _timestamp_pb2.Timestamp
    delta_position_m: _types_pb2.Vector3
    delta_rotation: _types_pb2.Matrix3
    clutch_engaged: bool
    master_energy: PortEnergy
    ack_receipt: AckReceipt
    def __init__(self, sequence: _Optional[int] = ..., send_time: _Optional[_Union[datetime.datetime, _timestamp_pb2.Timestamp, _Mapping]] = ..., delta_position_m: _Optional[_Union[_types_pb2.Vector3, _Mapping]] = ..., delta_rotation: _Optional[_Union[_types_pb2.Matrix3, _Mapping]] = ..., clutch_engaged: _Optional[bool] = ..., master_energy: _Optional[_Union[PortEnergy, _Mapping]] = ..., ack_receipt: _Optional[_Union[AckReceipt, _Mapping]] = ...) -> None: ...

class Heartbeat(_message.Message):
    __slots__ = ("send_time", "master_energy", "ack_receipt")
    SEND_TIME_FIELD_NUMBER: _ClassVar[int]
    MASTER_ENERGY_FIELD_NUMBER: _ClassVar[int]
    ACK_RECEIPT_FIELD_NUMBER: _ClassVar[int]
    send_time: _timestamp_pb2.Timestamp
    master_energy: PortEnergy
    ack_receipt: AckReceipt
    def __init__(self, send_time: _Optional[_Union[datetime.datetime, _timestamp_pb2.Timestamp, _Mapping]] = ..., master_energy: _Optional[_Union[PortEnergy, _Mapping]] = ..., ack_receipt: _Optional[_Union[AckReceipt, _Mapping]] = ...) -> None: ...

class AckReceipt(_message.Message):
    __slots__ = ("sequence", "receive_time")
    SEQUENCE_FIELD_NUMBER: _ClassVar[int]
    RECEIVE_TIME_FIELD_NUMBER: _ClassVar[int]
    sequence: int
    receive_time: _timestamp_pb2.Timestamp
    def __init__(self, sequence: _Optional[int] = ..., receive_time: _Optional[_Union[datetime.datetime, _timestamp_pb2.Timestamp, _Mapping]] = ...) -> None: ...

class PortEnergy(_message.Message):
    __slots__ = ("energy_in_j", "energy_out_j", "dissipated_j", "sample_time")
    ENERGY_IN_J_FIELD_NUMBER: _ClassVar[int]
    ENERGY_OUT_J_FIELD_NUMBER: _ClassVar[int]
    DISSIPATED_J_FIELD_NUMBER: _ClassVar[int]
    SAMPLE_TIME_FIELD_NUMBER: _ClassVar[int]
    energy_in_j: float
    energy_out_j: float
    dissipated_j: float
    sample_time: _timestamp_pb2.Timestamp
    def __init__(self, energy_in_j: _Optional[float] = ..., energy_out_j: _Optional[float] = ..., dissipated_j: _Optional[float] = ..., sample_time: _Optional[_Union[datetime.datetime, _timestamp_pb2.Timestamp, _Mapping]] = ...) -> None: ...

class TeleoperateResponse(_message.Message):
    __slots__ = ("ready", "ack", "acks")
    READY_FIELD_NUMBER: _ClassVar[int]
    ACK_FIELD_NUMBER: _ClassVar[int]
    ACKS_FIELD_NUMBER: _ClassVar[int]
    ready: TeleoperateReady
    ack: CommandAck
    acks: CommandAcks
    def __init__(self, ready: _Optional[_Union[TeleoperateReady, _Mapping]] = ..., ack: _Optional[_Union[CommandAck, _Mapping]] = ..., acks: _Optional[_Union[CommandAcks, _Mapping]] = ...) -> None: ...

class CommandAcks(_message.Message):
    __slots__ = ("acks",)
    ACKS_FIELD_NUMBER: _ClassVar[int]
    acks: _containers.RepeatedCompositeFieldContainer[CommandAck]
    def __init__(self, acks: _Optional[_Iterable[_Union[CommandAck, _Mapping]]] = ...) -> None: ...

class TeleoperateReady(_message.Message):
    __slots__ = ("session_id", "mapping", "watchdog_timeout", "assistance", "resumed", "last_sequence", "resume_window", "passivity", "max_command_age")
    SESSION_ID_FIELD_NUMBER: _ClassVar[int]
    MAPPING_FIELD_NUMBER: _ClassVar[int]
    WATCHDOG_TIMEOUT_FIELD_NUMBER: _ClassVar[int]
    ASSISTANCE_FIELD_NUMBER: _ClassVar[int]
    RESUMED_FIELD_NUMBER: _ClassVar[int]
    LAST_SEQUENCE_FIELD_NUMBER: _ClassVar[int]
    RESUME_WINDOW_FIELD_NUMBER: _ClassVar[int]
    PASSIVITY_FIELD_NUMBER: _ClassVar[int]
    MAX_COMMAND_AGE_FIELD_NUMBER: _ClassVar[int]
    session_id: str
    mapping: _types_pb2.ReferenceFrame
    watchdog_timeout: _duration_pb2.Duration
    assistance: AssistanceConfig
    resumed: bool
    last_sequence: int
    resume_window: _duration_pb2.Duration
    passivity: Passivity
    max_command_age: _duration_pb2.Duration
    def __init__(self, session_id: _Optional[str] = ..., mapping: _Optional[_Union[_types_pb2.ReferenceFrame, str]] = ..., watchdog_timeout: _Optional[_Union[datetime.timedelta, _duration_pb2.Duration, _Mapping]] = ..., assistance: _Optional[_Union[AssistanceConfig, _Mapping]] = ..., resumed: _Optional[bool] = ..., last_sequence: _Optional[int] = ..., resume_window: _Optional[_Union[datetime.timedelta, _duration_pb2.Duration, _Mapping]] = ..., passivity: _Optional[_Union[Passivity, str]] = ..., max_command_age: _Optional[_Union[datetime.timedelta, _duration_pb2.Duration, _Mapping]] = ...) -> None: ...

class CommandAck(_message.Message):
    __slots__ = ("sequence", "command_send_time", "receive_time", "apply_time", "outcome", "detail", "tool_pose", "tool_wrench", "status", "slave_energy", "passivity_drift_m", "clock_offset", "clock_offset_error")
    SEQUENCE_FIELD_NUMBER: _ClassVar[int]
    COMMAND_SEND_TIME_FIELD_NUMBER: _ClassVar[int]
    RECEIVE_TIME_FIELD_NUMBER: _ClassVar[int]
    APPLY_TIME_FIELD_NUMBER: _ClassVar[int]
    OUTCOME_FIELD_NUMBER: _ClassVar[int]
    DETAIL_FIELD_NUMBER: _ClassVar[int]
    TOOL_POSE_FIELD_NUMBER: _ClassVar[int]
    TOOL_WRENCH_FIELD_NUMBER: _ClassVar[int]
    STATUS_FIELD_NUMBER: _ClassVar[int]
    SLAVE_ENERGY_FIELD_NUMBER: _ClassVar[int]
    PASSIVITY_DRIFT_M_FIELD_NUMBER: _ClassVar[int]
    CLOCK_OFFSET_FIELD_NUMBER: _ClassVar[int]
    CLOCK_OFFSET_ERROR_FIELD_NUMBER: _ClassVar[int]
    sequence: int
    command_send_time: _timestamp_pb2.Timestamp
    receive_time: _timestamp_pb2.Timestamp
    apply_time: _timestamp_pb2.Timestamp
    outcome: CommandOutcome
    detail: str
    tool_pose: _types_pb2.Pose
    tool_wrench: _types_pb2.Wrench
    status: _types_pb2.RobotStatus
    slave_energy: PortEnergy
    passivity_drift_m: _types_pb2.Vector3
    clock_offset: _duration_pb2.Duration
    clock_offset_error: _duration_pb2.Duration
    def __init__(self, sequence: _Optional[int] = ..., command_send_time: _Optional[_Union[datetime.datetime, _timestamp_pb2.Timestamp, _Mapping]] = ..., receive_time: _Optional[_Union[datetime.datetime, _timestamp_pb2.Timestamp, _Mapping]] = ..., apply_time: _Optional[_Union[datetime.datetime, _timestamp_pb2.Timestamp, _Mapping]] = ..., outcome: _Optional[_Union[CommandOutcome, str]] = ..., detail: _Optional[str] = ..., tool_pose: _Optional[_Union[_types_pb2.Pose, _Mapping]] = ..., tool_wrench: _Optional[_Union[_types_pb2.Wrench, _Mapping]] = ..., status: _Optional[_Union[_types_pb2.RobotStatus, str]] = ..., slave_energy: _Optional[_Union[PortEnergy, _Mapping]] = ..., passivity_drift_m: _Optional[_Union[_types_pb2.Vector3, _Mapping]] = ..., clock_offset: _Optional[_Union[datetime.timedelta, _duration_pb2.Duration, _Mapping]] = ..., clock_offset_error: _Optional[_Union[datetime.timedelta, _duration_pb2.Duration, _Mapping]] = ...) -> None: ...

class GetAssistanceRequest(_message.Message):
    __slots__ = ()
    def __init__(self) -> None: ...

class GetAssistanceResponse(_message.Message):
    __slots__ = ("assistance",)
    ASSISTANCE_FIELD_NUMBER: _ClassVar[int]
    assistance: AssistanceConfig
    def __init__(self, assistance: _Optional[_Union[AssistanceConfig, _Mapping]] = ...) -> None: ...

class SetAssistanceRequest(_message.Message):
    __slots__ = ("assistance",)
    ASSISTANCE_FIELD_NUMBER: _ClassVar[int]
    assistance: AssistanceConfig
    def __init__(self, assistance: _Optional[_Union[AssistanceConfig, _Mapping]] = ...) -> None: ...

class SetAssistanceResponse(_message.Message):
    __slots__ = ("assistance",)
    ASSISTANCE_FIELD_NUMBER: _ClassVar[int]
    assistance: AssistanceConfig
    def __init__(self, assistance: _Optional[_Union[AssistanceConfig, _Mapping]] = ...) -> None: ...

class SetIndexingRequest(_message.Message):
    __slots__ = ("engaged",)
    ENGAGED_FIELD_NUMBER: _ClassVar[int]
    engaged: bool
    def __init__(self, engaged: _Optional[bool] = ...) -> None: ...

class SetIndexingResponse(_message.Message):
    __slots__ = ("engaged",)
    ENGAGED_FIELD_NUMBER: _ClassVar[int]
    engaged: bool
    def __init__(self, engaged: _Optional[bool] = ...) -> None: ...

class AcquireControlRequest(_message.Message):
    __slots__ = ("operator_id", "mode", "group", "wait", "wait_timeout", "lease_duration", "group_secret")
    OPERATOR_ID_FIELD_NUMBER: _ClassVar[int]
    MODE_FIELD_NUMBER: _ClassVar[int]
    GROUP_FIELD_NUMBER: _ClassVar[int]
    WAIT_FIELD_NUMBER: _ClassVar[int]
    WAIT_TIMEOUT_FIELD_NUMBER: _ClassVar[int]
    LEASE_DURATION_FIELD_NUMBER: _ClassVar[int]
    GROUP_SECRET_FIELD_NUMBER: _ClassVar[int]
    operator_id: str
    mode: ControlMode
    group: str
    wait: bool
    wait_timeout: _duration_pb2.Duration
    lease_duration: _duration_pb2.Duration
    group_secret: str
    def __init__(self, operator_id: _Optional[str] = ..., mode: _Optional[_Union[ControlMode, str]] = ..., group: _Optional[str] = ..., wait: _Optional[bool] = ..., wait_timeout: _Optional[_Union[datetime.timedelta, _duration_pb2.Duration, _Mapping]] = ..., lease_duration: _Optional[_Union[datetime.timedelta, _duration_pb2.Duration, _Mapping]] = ..., group_secret: _Optional[str] = ...) -> None: ...

class AcquireControlResponse(_message.Message):
    __slots__ = ("lease_id", "expire_time", "state", "operator_id", "group_secret")
    LEASE_ID_FIELD_NUMBER: _ClassVar[int]
    EXPIRE_TIME_FIELD_NUMBER: _ClassVar[int]
    STATE_FIELD_NUMBER: _ClassVar[int]
    OPERATOR_ID_FIELD_NUMBER: _ClassVar[int]
    GROUP_SECRET_FIELD_NUMBER: _ClassVar[int]
    lease_id: str
    expire_time: _timestamp_pb2.Timestamp
    state: ControlState
    operator_id: str
    group_secret: str
    def __init__(self, lease_id: _Optional[str] = ..., expire_time: _Optional[_Union[datetime.datetime, _timestamp_pb2.Timestamp, _Mapping]] = ..., state: _Optional[_Union[ControlState, _Mapping]] = ..., operator_id: _Optional[str] = ..., group_secret: _Optional[str] = ...) -> None: ...

class RenewControlRequest(_message.Message):
    __slots__ = ("lease_id",)
    LEASE_ID_FIELD_NUMBER: _ClassVar[int]
    lease_id: str
    def __init__(self, lease_id: _Optional[str] = ...) -> None: ...

class RenewControlResponse(_message.Message):
    __slots__ = ("expire_time",)
    EXPIRE_TIME_FIELD_NUMBER: _ClassVar[int]
    expire_time: _timestamp_pb2.Timestamp
    def __init__(self, expire_time: _Optional[_Union[datetime.datetime, _timestamp_pb2.Timestamp, _Mapping]] = ...) -> None: ...

class ReleaseControlRequest(_message.Message):
    __slots__ = ("lease_id",)
    LEASE_ID_FIELD_NUMBER: _ClassVar[int]
    lease_id: str
    def __init__(self, lease_id: _Optional[str] = ...) -> None: ...

class ReleaseControlResponse(_message.Message):
    __slots__ = ("state",)
    STATE_FIELD_NUMBER: _ClassVar[int]
    state: ControlState
    def __init__(self, state: _Optional[_Union[ControlState, _Mapping]] = ...) -> None: ...

class GetControlStateRequest(_message.Message):
    __slots__ = ()
    def __init__(self) -> None: ...

class GetControlStateResponse(_message.Message):
    __slots__ = ("state",)
    STATE_FIELD_NUMBER: _ClassVar[int]
    state: ControlState
    def __init__(self, state: _Optional[_Union[ControlState, _Mapping]] = ...) -> None: ...

class ControlState(_message.Message):
    __slots__ = ("mode", "holders", "waiters")
    MODE_FIELD_NUMBER: _ClassVar[int]
    HOLDERS_FIELD_NUMBER: _ClassVar[int]
    WAITERS_FIELD_NUMBER: _ClassVar[int]
    mode: ControlMode
    holders: _containers.RepeatedCompositeFieldContainer[ControlHolder]
    waiters: _containers.RepeatedCompositeFieldContainer[ControlHolder]
    def __init__(self, mode: _Optional[_Union[ControlMode, str]] = ..., holders: _Optional[_Iterable[_Union[ControlHolder, _Mapping]]] = ..., waiters: _Optional[_Iterable[_Union[ControlHolder, _Mapping]]] = ...) -> None: ...

class ControlHolder(_message.Message):
    __slots__ = ("operator_id", "mode", "group", "expire_time")
    OPERATOR_ID_FIELD_NUMBER: _ClassVar[int]
    MODE_FIELD_NUMBER: _ClassVar[int]
    GROUP_FIELD_NUMBER: _ClassVar[int]
    EXPIRE_TIME_FIELD_NUMBER: _ClassVar[int]
    operator_id: str
    mode: ControlMode
    group: str
    expire_time: _timestamp_pb2.Timestamp
    def __init__(self, operator_id: _Optional[str] = ..., mode: _Optional[_Union[ControlMode, str]] = ..., group: _Optional[str] = ..., expire_time: _Optional[_Union[datetime.datetime, _timestamp_pb2.Timestamp, _Mapping]] = ...) -> None: ...

class StartRecordingRequest(_message.Message):
    __slots__ = ("name", "format", "task")
    NAME_FIELD_NUMBER: _ClassVar[int]
    FORMAT_FIELD_NUMBER: _ClassVar[int]
    TASK_FIELD_NUMBER: _ClassVar[int]
    name: str
    format: RecordingFormat
    task: str
    def __init__(self, name: _Optional[str] = ..., format: _Optional[_Union[RecordingFormat, str]] = ..., task: _Optional[str] = ...) -> None: ...

class StartRecordingResponse(_message.Message):
    __slots__ = ("recording",)
    RECORDING_FIELD_NUMBER: _ClassVar[int]
    recording: Recording
    def __init__(self, recording: _Optional[_Union[Recording, _Mapping]] = ...) -> None: ...

class StopRecordingRequest(_message.Message):
    __slots__ = ("outcome",)
    OUTCOME_FIELD_NUMBER: _ClassVar[int]
    outcome: EpisodeOutcome
    def __init__(self, outcome: _Optional[_Union[EpisodeOutcome, str]] = ...) -> None: ...

class StopRecordingResponse(_message.Message):
    __slots__ = ("recording",)
    RECORDING_FIELD_NUMBER: _ClassVar[int]
    recording: Recording
    def __init__(self, recording: _Optional[_Union[Recording, _Mapping]] = ...) -> None: ...

class ListRecordingsRequest(_message.Message):
    __slots__ = ()
    def __init__(self) -> None: ...

class ListRecordingsResponse(_message.Message):
    __slots__ = ("recordings",)
    RECORDINGS_FIELD_NUMBER: _ClassVar[int]
    recordings: _containers.RepeatedCompositeFieldContainer[Recording]
    def __init__(self, recordings: _Optional[_Iterable[_Union[Recording, _Mapping]]] = ...) -> None: ...

class DeleteRecordingRequest(_message.Message):
    __slots__ = ("name",)
    NAME_FIELD_NUMBER: _ClassVar[int]
    name: str
    def __init__(self, name: _Optional[str] = ...) -> None: ...

class DeleteRecordingResponse(_message.Message):
    __slots__ = ()
    def __init__(self) -> None: ...

class StartReplayRequest(_message.Message):
    __slots__ = ("name", "speed", "increments")
    NAME_FIELD_NUMBER: _ClassVar[int]
    SPEED_FIELD_NUMBER: _ClassVar[int]
    INCREMENTS_FIELD_NUMBER: _ClassVar[int]
    name: str
    speed: float
    increments: _containers.RepeatedCompositeFieldContainer[RecordedIncrement]
    def __init__(self, name: _Optional[str] = ..., speed: _Optional[float] = ..., increments: _Optional[_Iterable[_Union[RecordedIncrement, _Mapping]]] = ...) -> None: ...

class StartReplayResponse(_message.Message):
    __slots__ = ("recording",)
    RECORDING_FIELD_NUMBER: _ClassVar[int]
    recording: Recording
    def __init__(self, recording: _Optional[_Union[Recording, _Mapping]] = ...) -> None: ...

class StopReplayRequest(_message.Message):
    __slots__ = ()
    def __init__(self) -> None: ...

class StopReplayResponse(_message.Message):
    __slots__ = ("commands_replayed",)
    COMMANDS_REPLAYED_FIELD_NUMBER: _ClassVar[int]
    commands_replayed: int
    def __init__(self, commands_replayed: _Optional[int] = ...) -> None: ...

class Recording(_message.Message):
    __slots__ = ("name", "create_time", "duration", "command_count", "format", "error", "task", "outcome", "video_frames")
    NAME_FIELD_NUMBER: _ClassVar[int]
    CREATE_TIME_FIELD_NUMBER: _ClassVar[int]
    DURATION_FIELD_NUMBER: _ClassVar[int]
    COMMAND_COUNT_FIELD_NUMBER: _ClassVar[int]
    FORMAT_FIELD_NUMBER: _ClassVar[int]
    ERROR_FIELD_NUMBER: _ClassVar[int]
    TASK_FIELD_NUMBER: _ClassVar[int]
    OUTCOME_FIELD_NUMBER: _ClassVar[int]
    VIDEO_FRAMES_FIELD_NUMBER: _ClassVar[int]
    name: str
    create_time: _timestamp_pb2.Timestamp
    duration: _duration_pb2.Duration
    command_count: int
    format: RecordingFormat
    error: str
    task: str
    outcome: EpisodeOutcome
    video_frames: int
    def __init__(self, name: _Optional[str] = ..., create_time: _Optional[_Union[datetime.datetime, _timestamp_pb2.Timestamp, _Mapping]] = ..., duration: _Optional[_Union[datetime.timedelta, _duration_pb2.Duration, _Mapping]] = ..., command_count: _Optional[int] = ..., format: _Optional[_Union[RecordingFormat, str]] = ..., error: _Optional[str] = ..., task: _Optional[str] = ..., outcome: _Optional[_Union[EpisodeOutcome, str]] = ..., video_frames: _Optional[int] = ...) -> None: ...

class RecordedIncrement(_message.Message):
    __slots__ = ("offset", "frame", "delta_position_m", "delta_rotation", "delta_joints_rad", "target_position_m")
    OFFSET_FIELD_NUMBER: _ClassVar[int]
    FRAME_FIELD_NUMBER: _ClassVar[int]
    DELTA_POSITION_M_FIELD_NUMBER: _ClassVar[int]
    DELTA_ROTATION_FIELD_NUMBER: _ClassVar[int]
    DELTA_JOINTS_RAD_FIELD_NUMBER: _ClassVar[int]
    TARGET_POSITION_M_FIELD_NUMBER: _ClassVar[int]
    offset: _duration_pb2.Duration
    frame: _types_pb2.ReferenceFrame
    delta_position_m: _types_pb2.Vector3
    delta_rotation: _types_pb2.Matrix3
    delta_joints_rad: _containers.RepeatedScalarFieldContainer[float]
    target_position_m: _types_pb2.Vector3
    def __init__(self, offset: _Optional[_Union[datetime.timedelta, _duration_pb2.Duration, _Mapping]] = ..., frame: _Optional[_Union[_types_pb2.ReferenceFrame, str]] = ..., delta_position_m: _Optional[_Union[_types_pb2.Vector3, _Mapping]] = ..., delta_rotation: _Optional[_Union[_types_pb2.Matrix3, _Mapping]] = ..., delta_joints_rad: _Optional[_Iterable[float]] = ..., target_position_m: _Optional[_Union[_types_pb2.Vector3, _Mapping]] = ...) -> None: ...

class BeginCobeginRequest(_message.Message):
    __slots__ = ("action_count", "barrier_timeout")
    ACTION_COUNT_FIELD_NUMBER: _ClassVar[int]
    BARRIER_TIMEOUT_FIELD_NUMBER: _ClassVar[int]
    action_count: int
    barrier_timeout: _duration_pb2.Duration
    def __init__(self, action_count: _Optional[int] = ..., barrier_timeout: _Optional[_Union[datetime.timedelta, _duration_pb2.Duration, _Mapping]] = ...) -> None: ...

class BeginCobeginResponse(_message.Message):
    __slots__ = ("cobegin_id", "deadline_time")
    COBEGIN_ID_FIELD_NUMBER: _ClassVar[int]
    DEADLINE_TIME_FIELD_NUMBER: _ClassVar[int]
    cobegin_id: str
    deadline_time: _timestamp_pb2.Timestamp
    def __init__(self, cobegin_id: _Optional[str] = ..., deadline_time: _Optional[_Union[datetime.datetime, _timestamp_pb2.Timestamp, _Mapping]] = ...) -> None: ...

class RunActionRequest(_message.Message):
    __slots__ = ("cobegin_id", "action_id", "busy_work", "move_joints", "move_cartesian")
    COBEGIN_ID_FIELD_NUMBER: _ClassVar[int]
    ACTION_ID_FIELD_NUMBER: _ClassVar[int]
    BUSY_WORK_FIELD_NUMBER: _ClassVar[int]
    MOVE_JOINTS_FIELD_NUMBER: _ClassVar[int]
    MOVE_CARTESIAN_FIELD_NUMBER: _ClassVar[int]
    cobegin_id: str
    action_id: str
    busy_work: BusyWorkAction
    move_joints: _proxy_robot_pb2.MoveJointsIncrementalRequest
    move_cartesian: _proxy_robot_pb2.MoveCartesianIncrementalRequest
    def __init__(self, cobegin_id: _Optional[str] = ..., action_id: _Optional[str] = ..., busy_work: _Optional[_Union[BusyWorkAction, _Mapping]] = ..., move_joints: _Optional[_Union[_proxy_robot_pb2.MoveJointsIncrementalRequest, _Mapping]] = ..., move_cartesian: _Optional[_Union[_proxy_robot_pb2.MoveCartesianIncrementalRequest, _Mapping]] = ...) -> None: ...

class BusyWorkAction(_message.Message):
    __slots__ = ("duration",)
    DURATION_FIELD_NUMBER: _ClassVar[int]
    duration: _duration_pb2.Duration
    def __init__(self, duration: _Optional[_Union[datetime.timedelta, _duration_pb2.Duration, _Mapping]] = ...) -> None: ...

class RunActionResponse(_message.Message):
    __slots__ = ("action_id", "lane", "arrive_time", "start_time", "end_time")
    ACTION_ID_FIELD_NUMBER: _ClassVar[int]
    LANE_FIELD_NUMBER: _ClassVar[int]
    ARRIVE_TIME_FIELD_NUMBER: _ClassVar[int]
    START_TIME_FIELD_NUMBER: _ClassVar[int]
    END_TIME_FIELD_NUMBER: _ClassVar[int]
    action_id: str
    lane: _options_pb2.Lane
    arrive_time: _timestamp_pb2.Timestamp
    start_time: _timestamp_pb2.Timestamp
    end_time: _timestamp_pb2.Timestamp
    def __init__(self, action_id: _Optional[str] = ..., lane: _Optional[_Union[_options_pb2.Lane, str]] = ..., arrive_time: _Optional[_Union[datetime.datetime, _timestamp_pb2.Timestamp, _Mapping]] = ..., start_time: _Optional[_Union[datetime.datetime, _timestamp_pb2.Timestamp, _Mapping]] = ..., end_time: _Optional[_Union[datetime.datetime, _timestamp_pb2.Timestamp, _Mapping]] = ...) -> None: ...

class StreamEventsRequest(_message.Message):
    __slots__ = ("include_data_received",)
    INCLUDE_DATA_RECEIVED_FIELD_NUMBER: _ClassVar[int]
    include_data_received: bool
    def __init__(self, include_data_received: _Optional[bool] = ...) -> None: ...

class StreamEventsResponse(_message.Message):
    __slots__ = ("sequence", "event_time", "robot", "control_changed", "watchdog_hold", "assistance_changed", "replay_progress", "dependency_changed", "teleop_session", "recording_failed")
    SEQUENCE_FIELD_NUMBER: _ClassVar[int]
    EVENT_TIME_FIELD_NUMBER: _ClassVar[int]
    ROBOT_FIELD_NUMBER: _ClassVar[int]
    CONTROL_CHANGED_FIELD_NUMBER: _ClassVar[int]
    WATCHDOG_HOLD_FIELD_NUMBER: _ClassVar[int]
    ASSISTANCE_CHANGED_FIELD_NUMBER: _ClassVar[int]
    REPLAY_PROGRESS_FIELD_NUMBER: _ClassVar[int]
    DEPENDENCY_CHANGED_FIELD_NUMBER: _ClassVar[int]
    TELEOP_SESSION_FIELD_NUMBER: _ClassVar[int]
    RECORDING_FAILED_FIELD_NUMBER: _ClassVar[int]
    sequence: int
    event_time: _timestamp_pb2.Timestamp
    robot: _proxy_robot_pb2.StreamRobotEventsResponse
    control_changed: ControlChangedEvent
    watchdog_hold: WatchdogHoldEvent
    assistance_changed: AssistanceChangedEvent
    replay_progress: ReplayProgressEvent
    dependency_changed: DependencyChangedEvent
    teleop_session: TeleopSessionEvent
    recording_failed: RecordingFailedEvent
    def __init__(self, sequence: _Optional[int] = ..., event_time: _Optional[_Union[datetime.datetime, _timestamp_pb2.Timestamp, _Mapping]] = ..., robot: _Optional[_Union[_proxy_robot_pb2.StreamRobotEventsResponse, _Mapping]] = ..., control_changed: _Optional[_Union[ControlChangedEvent, _Mapping]] = ..., watchdog_hold: _Optional[_Union[WatchdogHoldEvent, _Mapping]] = ..., assistance_changed: _Optional[_Union[AssistanceChangedEvent, _Mapping]] = ..., replay_progress: _Optional[_Union[ReplayProgressEvent, _Mapping]] = ..., dependency_changed: _Optional[_Union[DependencyChangedEvent, _Mapping]] = ..., teleop_session: _Optional[_Union[TeleopSessionEvent, _Mapping]] = ..., recording_failed: _Optional[_Union[RecordingFailedEvent, _Mapping]] = ...) -> None: ...

class RecordingFailedEvent(_message.Message):
    __slots__ = ("name", "reason")
    NAME_FIELD_NUMBER: _ClassVar[int]
    REASON_FIELD_NUMBER: _ClassVar[int]
    name: str
    reason: str
    def __init__(self, name: _Optional[str] = ..., reason: _Optional[str] = ...) -> None: ...

class ControlChangedEvent(_message.Message):
    __slots__ = ("state", "reason")
    STATE_FIELD_NUMBER: _ClassVar[int]
    REASON_FIELD_NUMBER: _ClassVar[int]
    state: ControlState
    reason: str
    def __init__(self, state: _Optional[_Union[ControlState, _Mapping]] = ..., reason: _Optional[str] = ...) -> None: ...

class WatchdogHoldEvent(_message.Message):
    __slots__ = ("session_id", "reason", "silence")
    SESSION_ID_FIELD_NUMBER: _ClassVar[int]
    REASON_FIELD_NUMBER: _ClassVar[int]
    SILENCE_FIELD_NUMBER: _ClassVar[int]
    session_id: str
    reason: str
    silence: _duration_pb2.Duration
    def __init__(self, session_id: _Optional[str] = ..., reason: _Optional[str] = ..., silence: _Optional[_Union[datetime.timedelta, _duration_pb2.Duration, _Mapping]] = ...) -> None: ...

class AssistanceChangedEvent(_message.Message):
    __slots__ = ("assistance", "operator_id")
    ASSISTANCE_FIELD_NUMBER: _ClassVar[int]
    OPERATOR_ID_FIELD_NUMBER: _ClassVar[int]
    assistance: AssistanceConfig
    operator_id: str
    def __init__(self, assistance: _Optional[_Union[AssistanceConfig, _Mapping]] = ..., operator_id: _Optional[str] = ...) -> None: ...

class ReplayProgressEvent(_message.Message):
    __slots__ = ("name", "commands_replayed", "command_count", "state", "detail")
    NAME_FIELD_NUMBER: _ClassVar[int]
    COMMANDS_REPLAYED_FIELD_NUMBER: _ClassVar[int]
    COMMAND_COUNT_FIELD_NUMBER: _ClassVar[int]
    STATE_FIELD_NUMBER: _ClassVar[int]
    DETAIL_FIELD_NUMBER: _ClassVar[int]
    name: str
    commands_replayed: int
    command_count: int
    state: ReplayState
    detail: str
    def __init__(self, name: _Optional[str] = ..., commands_replayed: _Optional[int] = ..., command_count: _Optional[int] = ..., state: _Optional[_Union[ReplayState, str]] = ..., detail: _Optional[str] = ...) -> None: ...

class TeleopSessionEvent(_message.Message):
    __slots__ = ("session_id", "operator_id", "state", "reason", "commands_processed", "commands_applied", "resends_answered", "last_sequence")
    SESSION_ID_FIELD_NUMBER: _ClassVar[int]
    OPERATOR_ID_FIELD_NUMBER: _ClassVar[int]
    STATE_FIELD_NUMBER: _ClassVar[int]
    REASON_FIELD_NUMBER: _ClassVar[int]
    COMMANDS_PROCESSED_FIELD_NUMBER: _ClassVar[int]
    COMMANDS_APPLIED_FIELD_NUMBER: _ClassVar[int]
    RESENDS_ANSWERED_FIELD_NUMBER: _ClassVar[int]
    LAST_SEQUENCE_FIELD_NUMBER: _ClassVar[int]
    session_id: str
    operator_id: str
    state: TeleopSessionState
    reason: str
    commands_processed: int
    commands_applied: int
    resends_answered: int
    last_sequence: int
    def __init__(self, session_id: _Optional[str] = ..., operator_id: _Optional[str] = ..., state: _Optional[_Union[TeleopSessionState, str]] = ..., reason: _Optional[str] = ..., commands_processed: _Optional[int] = ..., commands_applied: _Optional[int] = ..., resends_answered: _Optional[int] = ..., last_sequence: _Optional[int] = ...) -> None: ...

class DependencyChangedEvent(_message.Message):
    __slots__ = ("dependency", "previous_state")
    DEPENDENCY_FIELD_NUMBER: _ClassVar[int]
    PREVIOUS_STATE_FIELD_NUMBER: _ClassVar[int]
    dependency: Dependency
    previous_state: DependencyState
    def __init__(self, dependency: _Optional[_Union[Dependency, _Mapping]] = ..., previous_state: _Optional[_Union[DependencyState, str]] = ...) -> None: ...

class GetDependenciesRequest(_message.Message):
    __slots__ = ()
    def __init__(self) -> None: ...

class GetDependenciesResponse(_message.Message):
    __slots__ = ("dependencies",)
    DEPENDENCIES_FIELD_NUMBER: _ClassVar[int]
    dependencies: _containers.RepeatedCompositeFieldContainer[Dependency]
    def __init__(self, dependencies: _Optional[_Iterable[_Union[Dependency, _Mapping]]] = ...) -> None: ...

class Dependency(_message.Message):
    __slots__ = ("name", "state", "reason", "change_time", "restarts")
    NAME_FIELD_NUMBER: _ClassVar[int]
    STATE_FIELD_NUMBER: _ClassVar[int]
    REASON_FIELD_NUMBER: _ClassVar[int]
    CHANGE_TIME_FIELD_NUMBER: _ClassVar[int]
    RESTARTS_FIELD_NUMBER: _ClassVar[int]
    name: str
    state: DependencyState
    reason: str
    change_time: _timestamp_pb2.Timestamp
    restarts: int
    def __init__(self, name: _Optional[str] = ..., state: _Optional[_Union[DependencyState, str]] = ..., reason: _Optional[str] = ..., change_time: _Optional[_Union[datetime.datetime, _timestamp_pb2.Timestamp, _Mapping]] = ..., restarts: _Optional[int] = ...) -> None: ...

class AssistanceConfig(_message.Message):
    __slots__ = ("mapping", "floating_tool_frame", "constraint", "force_control", "scaling")
    MAPPING_FIELD_NUMBER: _ClassVar[int]
    FLOATING_TOOL_FRAME_FIELD_NUMBER: _ClassVar[int]
    CONSTRAINT_FIELD_NUMBER: _ClassVar[int]
    FORCE_CONTROL_FIELD_NUMBER: _ClassVar[int]
    SCALING_FIELD_NUMBER: _ClassVar[int]
    mapping: _types_pb2.ReferenceFrame
    floating_tool_frame: FloatingToolFrame
    constraint: MotionConstraint
    force_control: ForceControl
    scaling: Scaling
    def __init__(self, mapping: _Optional[_Union[_types_pb2.ReferenceFrame, str]] = ..., floating_tool_frame: _Optional[_Union[FloatingToolFrame, _Mapping]] = ..., constraint: _Optional[_Union[MotionConstraint, _Mapping]] = ..., force_control: _Optional[_Union[ForceControl, _Mapping]] = ..., scaling: _Optional[_Union[Scaling, _Mapping]] = ...) -> None: ...

class FloatingToolFrame(_message.Message):
    __slots__ = ("enabled", "point_m")
    ENABLED_FIELD_NUMBER: _ClassVar[int]
    POINT_M_FIELD_NUMBER: _ClassVar[int]
    enabled: bool
    point_m: _types_pb2.Vector3
    def __init__(self, enabled: _Optional[bool] = ..., point_m: _Optional[_Union[_types_pb2.Vector3, _Mapping]] = ...) -> None: ...

class MotionConstraint(_message.Message):
    __slots__ = ("type", "axis", "frame")
    TYPE_FIELD_NUMBER: _ClassVar[int]
    AXIS_FIELD_NUMBER: _ClassVar[int]
    FRAME_FIELD_NUMBER: _ClassVar[int]
    type: ConstraintType
    axis: _types_pb2.Vector3
    frame: _types_pb2.ReferenceFrame
    def __init__(self, type: _Optional[_Union[ConstraintType, str]] = ..., axis: _Optional[_Union[_types_pb2.Vector3, _Mapping]] = ..., frame: _Optional[_Union[_types_pb2.ReferenceFrame, str]] = ...) -> None: ...

class ForceControl(_message.Message):
    __slots__ = ("enabled", "axes", "desired_wrench", "translation_gain_m_per_n_s", "rotation_gain_rad_per_nm_s")
    ENABLED_FIELD_NUMBER: _ClassVar[int]
    AXES_FIELD_NUMBER: _ClassVar[int]
    DESIRED_WRENCH_FIELD_NUMBER: _ClassVar[int]
    TRANSLATION_GAIN_M_PER_N_S_FIELD_NUMBER: _ClassVar[int]
    ROTATION_GAIN_RAD_PER_NM_S_FIELD_NUMBER: _ClassVar[int]
    enabled: bool
    axes: AxisSelection
    desired_wrench: _types_pb2.Wrench
    translation_gain_m_per_n_s: float
    rotation_gain_rad_per_nm_s: float
    def __init__(self, enabled: _Optional[bool] = ..., axes: _Optional[_Union[AxisSelection, _Mapping]] = ..., desired_wrench: _Optional[_Union[_types_pb2.Wrench, _Mapping]] = ..., translation_gain_m_per_n_s: _Optional[float] = ..., rotation_gain_rad_per_nm_s: _Optional[float] = ...) -> None: ...

class AxisSelection(_message.Message):
    __slots__ = ("x", "y", "z", "rx", "ry", "rz")
    X_FIELD_NUMBER: _ClassVar[int]
    Y_FIELD_NUMBER: _ClassVar[int]
    Z_FIELD_NUMBER: _ClassVar[int]
    RX_FIELD_NUMBER: _ClassVar[int]
    RY_FIELD_NUMBER: _ClassVar[int]
    RZ_FIELD_NUMBER: _ClassVar[int]
    x: bool
    y: bool
    z: bool
    rx: bool
    ry: bool
    rz: bool
    def __init__(self, x: _Optional[bool] = ..., y: _Optional[bool] = ..., z: _Optional[bool] = ..., rx: _Optional[bool] = ..., ry: _Optional[bool] = ..., rz: _Optional[bool] = ...) -> None: ...

class Scaling(_message.Message):
    __slots__ = ("translation_scale", "rotation_scale")
    TRANSLATION_SCALE_FIELD_NUMBER: _ClassVar[int]
    ROTATION_SCALE_FIELD_NUMBER: _ClassVar[int]
    translation_scale: float
    rotation_scale: float
    def __init__(self, translation_scale: _Optional[float] = ..., rotation_scale: _Optional[float] = ...) -> None: ...

class SessionStatus(_message.Message):
    __slots__ = ("status_time", "control", "assistance", "dependencies")
    STATUS_TIME_FIELD_NUMBER: _ClassVar[int]
    CONTROL_FIELD_NUMBER: _ClassVar[int]
    ASSISTANCE_FIELD_NUMBER: _ClassVar[int]
    DEPENDENCIES_FIELD_NUMBER: _ClassVar[int]
    status_time: _timestamp_pb2.Timestamp
    control: ControlState
    assistance: AssistanceConfig
    dependencies: _containers.RepeatedCompositeFieldContainer[Dependency]
    def __init__(self, status_time: _Optional[_Union[datetime.datetime, _timestamp_pb2.Timestamp, _Mapping]] = ..., control: _Optional[_Union[ControlState, _Mapping]] = ..., assistance: _Optional[_Union[AssistanceConfig, _Mapping]] = ..., dependencies: _Optional[_Iterable[_Union[Dependency, _Mapping]]] = ...) -> None: ...
