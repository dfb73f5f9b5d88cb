import datetime

from google.protobuf import duration_pb2 as _duration_pb2
from google.protobuf import field_mask_pb2 as _field_mask_pb2
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

class SensorThreadPriority(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    SENSOR_THREAD_PRIORITY_UNSPECIFIED: _ClassVar[SensorThreadPriority]
    SENSOR_THREAD_PRIORITY_LOWEST: _ClassVar[SensorThreadPriority]
    SENSOR_THREAD_PRIORITY_BELOW_NORMAL: _ClassVar[SensorThreadPriority]
    SENSOR_THREAD_PRIORITY_NORMAL: _ClassVar[SensorThreadPriority]
    SENSOR_THREAD_PRIORITY_ABOVE_NORMAL: _ClassVar[SensorThreadPriority]
    SENSOR_THREAD_PRIORITY_HIGHEST: _ClassVar[SensorThreadPriority]
SENSOR_THREAD_PRIORITY_UNSPECIFIED: SensorThreadPriority
SENSOR_THREAD_PRIORITY_LOWEST: SensorThreadPriority
SENSOR_THREAD_PRIORITY_BELOW_NORMAL: SensorThreadPriority
SENSOR_THREAD_PRIORITY_NORMAL: SensorThreadPriority
SENSOR_THREAD_PRIORITY_ABOVE_NORMAL: SensorThreadPriority
SENSOR_THREAD_PRIORITY_HIGHEST: SensorThreadPriority

class StartReadingRequest(_message.Message):
    __slots__ = ()
    def __init__(self) -> None: ...

class StartReadingResponse(_message.Message):
    __slots__ = ("config",)
    CONFIG_FIELD_NUMBER: _ClassVar[int]
    config: SensorConfig
    def __init__(self, config: _Optional[_Union[SensorConfig, _Mapping]] = ...) -> None: ...

class StopReadingRequest(_message.Message):
    __slots__ = ()
    def __init__(self) -> None: ...

class StopReadingResponse(_message.Message):
    __slots__ = ("last_sequence",)
    LAST_SEQUENCE_FIELD_NUMBER: _ClassVar[int]
    last_sequence: int
    def __init__(self, last_sequence: _Optional[int] = ...) -> None: ...

class TareRequest(_message.Message):
    __slots__ = ("duration",)
    DURATION_FIELD_NUMBER: _ClassVar[int]
    duration: _duration_pb2.Duration
    def __init__(self, duration: _Optional[_Union[datetime.timedelta, _duration_pb2.Duration, _Mapping]] = ...) -> None: ...

class TareResponse(_message.Message):
    __slots__ = ("bias", "sample_count")
    BIAS_FIELD_NUMBER: _ClassVar[int]
    SAMPLE_COUNT_FIELD_NUMBER: _ClassVar[int]
    bias: _types_pb2.Wrench
    sample_count: int
    def __init__(self, bias: _Optional[_Union[_types_pb2.Wrench, _Mapping]] = ..., sample_count: _Optional[int] = ...) -> None: ...

class GetSensorConfigRequest(_message.Message):
    __slots__ = ()
    def __init__(self) -> None: ...

class GetSensorConfigResponse(_message.Message):
    __slots__ = ("config",)
    CONFIG_FIELD_NUMBER: _ClassVar[int]
    config: SensorConfig
    def __init__(self, config: _Optional[_Union[SensorConfig, _Mapping]] = ...) -> None: ...

class SetSensorConfigRequest(_message.Message):
    __slots__ = ("config", "update_mask")
    CONFIG_FIELD_NUMBER: _ClassVar[int]
    UPDATE_MASK_FIELD_NUMBER: _ClassVar[int]
    config: SensorConfig
    update_mask: _field_mask_pb2.FieldMask
    def __init__(self, config: _Optional[_Union[SensorConfig, _Mapping]] = ..., update_mask: _Optional[_Union[_field_mask_pb2.FieldMask, _Mapping]] = ...) -> None: ...

class SetSensorConfigResponse(_message.Message):
    __slots__ = ("config",)
    CONFIG_FIELD_NUMBER: _ClassVar[int]
    config: SensorConfig
    def __init__(self, config: _Optional[_Union[SensorConfig, _Mapping]] = ...) -> None: ...

class GetWrenchRequest(_message.Message):
    __slots__ = ()
    def __init__(self) -> None: ...

class GetWrenchResponse(_message.Message):
    __slots__ = ("sample",)
    SAMPLE_FIELD_NUMBER: _ClassVar[int]
    sample: WrenchSample
    def __init__(self, sample: _Optional[_Union[WrenchSample, _Mapping]] = ...) -> None: ...

class StreamWrenchRequest(_message.Message):
    __slots__ = ("decimation", "threshold_force_n", "threshold_torque_nm", "batch_size", "queue_capacity")
    DECIMATION_FIELD_NUMBER: _ClassVar[int]
    THRESHOLD_FORCE_N_FIELD_NUMBER: _ClassVar[int]
    THRESHOLD_TORQUE_NM_FIELD_NUMBER: _ClassVar[int]
    BATCH_SIZE_FIELD_NUMBER: _ClassVar[int]
    QUEUE_CAPACITY_FIELD_NUMBER: _ClassVar[int]
    decimation: int
    threshold_force_n: float
    threshold_torque_nm: float
    batch_size: int
    queue_capacity: int
    def __init__(self, decimation: _Optional[int] = ..., threshold_force_n: _Optional[float] = ..., threshold_torque_nm: _Optional[float] = ..., batch_size: _Optional[int] = ..., queue_capacity: _Optional[int] = ...) -> None: ...

class StreamWrenchResponse(_message.Message):
    __slots__ = ("samples", "dropped_count")
    SAMPLES_FIELD_NUMBER: _ClassVar[int]
    DROPPED_COUNT_FIELD_NUMBER: _ClassVar[int]
    samples: _containers.RepeatedCompositeFieldContainer[WrenchSample]
    dropped_count: int
    def __init__(self, samples: _Optional[_Iterable[_Union[WrenchSample, _Mapping]]] = ..., dropped_count: _Optional[int] = ...) -> None: ...

class SensorConfig(_message.Message):
    __slots__ = ("period", "threshold_force_n", "threshold_torque_nm", "thread_priority", "reading", "flange_to_tool")
    PERIOD_FIELD_NUMBER: _ClassVar[int]
    THRESHOLD_FORCE_N_FIELD_NUMBER: _ClassVar[int]
    THRESHOLD_TORQUE_NM_FIELD_NUMBER: _ClassVar[int]
    THREAD_PRIORITY_FIELD_NUMBER: _ClassVar[int]
    READING_FIELD_NUMBER: _ClassVar[int]
    FLANGE_TO_TOOL_FIELD_NUMBER: _ClassVar[int]
    period: _duration_pb2.Duration
    threshold_force_n: float
    threshold_torque_nm: float
    thread_priority: SensorThreadPriority
    reading: bool
    flange_to_tool: _types_pb2.Pose
    def __init__(self, period: _Optional[_Union[datetime.timedelta, _duration_pb2.Duration, _Mapping]] = ..., threshold_force_n: _Optional[float] = ..., threshold_torque_nm: _Optional[float] = ..., thread_priority: _Optional[_Union[SensorThreadPriority, str]] = ..., reading: _Optional[bool] = ..., flange_to_tool: _Optional[_Union[_types_pb2.Pose, _Mapping]] = ...) -> None: ...

class WrenchSample(_message.Message):
    __slots__ = ("sequence", "sample_time", "wrench")
    SEQUENCE_FIELD_NUMBER: _ClassVar[int]
    SAMPLE_TIME_FIELD_NUMBER: _ClassVar[int]
    WRENCH_FIELD_NUMBER: _ClassVar[int]
    sequence: int
    sample_time: _timestamp_pb2.Timestamp
    wrench: _types_pb2.Wrench
    def __init__(self, sequence: _Optional[int] = ..., sample_time: _Optional[_Union[datetime.datetime, _timestamp_pb2.Timestamp, _Mapping]] = ..., wrench: _Optional[_Union[_types_pb2.Wrench, _Mapping]] = ...) -> None: ...
