from google.protobuf import descriptor_pb2 as _descriptor_pb2
from google.protobuf.internal import enum_type_wrapper as _enum_type_wrapper
from google.protobuf import descriptor as _descriptor
from typing import ClassVar as _ClassVar

DESCRIPTOR: _descriptor.FileDescriptor

class Lane(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    LANE_UNSPECIFIED: _ClassVar[Lane]
    LANE_EMERGENCY: _ClassVar[Lane]
    LANE_HIGH: _ClassVar[Lane]
    LANE_MEDIUM: _ClassVar[Lane]
    LANE_LOW: _ClassVar[Lane]

class Role(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    ROLE_UNSPECIFIED: _ClassVar[Role]
    ROLE_OBSERVER: _ClassVar[Role]
    ROLE_OPERATOR: _ClassVar[Role]
    ROLE_STATION: _ClassVar[Role]
    ROLE_ADMIN: _ClassVar[Role]
LANE_UNSPECIFIED: Lane
LANE_EMERGENCY: Lane
LANE_HIGH: Lane
LANE_MEDIUM: Lane
LANE_LOW: Lane
ROLE_UNSPECIFIED: Role
ROLE_OBSERVER: Role
ROLE_OPERATOR: Role
ROLE_STATION: Role
ROLE_ADMIN: Role
DEFAULT_LANE_FIELD_NUMBER: _ClassVar[int]
default_lane: _descriptor.FieldDescriptor
MIN_ROLE_FIELD_NUMBER: _ClassVar[int]
min_role: _descriptor.FieldDescriptor
MAX_LENGTH_FIELD_NUMBER: _ClassVar[int]
max_length: _descriptor.FieldDescriptor
