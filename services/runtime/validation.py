"""Checks every request must pass before a handler sees it, whatever language sent it.

proto3 enums are open: any int32 can arrive on the wire, and a handler that maps it to a
name would crash. Strings are unbounded on the wire, and they end up in logs and events.
Durations and Timestamps are two integers that can say "10^11 years" or "-1 ns and +1 s". So
the runtime refuses, for every RPC in one place and naming the field: an enum value the
contract does not define, a string longer than its field's `(telerobot.v1.max_length)`
(DEFAULT_MAX_STRING_LENGTH when the field declares none), and a Duration or Timestamp outside
the range its own .proto defines.

One exception, for safety: an RPC on the emergency lane (EmergencyStop) is never refused for
its words. A string past its bound there is cut to the bound, and the stop goes through.
"""

from __future__ import annotations

import functools

from google.protobuf.descriptor import Descriptor, FieldDescriptor
from google.protobuf.message import Message

from telerobot.v1 import options_pb2
from wire.errors import InvalidArgumentError

DEFAULT_MAX_STRING_LENGTH = 256
DURATION_MAX_SECONDS = 315_576_000_000  # google/protobuf/duration.proto: ±10,000 years
TIMESTAMP_SECONDS = (-62_135_596_800, 253_402_300_799)  # 0001-01-01 .. 9999-12-31
NANOS_MAX = 999_999_999
_ENUM = FieldDescriptor.TYPE_ENUM
_STRING = FieldDescriptor.TYPE_STRING
_MESSAGE = FieldDescriptor.TYPE_MESSAGE
_TIME_TYPES = ("google.protobuf.Duration", "google.protobuf.Timestamp")


def check_request(message: Message, *, cut_long_strings: bool = False) -> None:
    """Raise InvalidArgumentError for the first unknown enum value, over-long string or
    out-of-range Duration or Timestamp in `message`, at any depth. With `cut_long_strings`,
    an over-long string is cut to its bound in place instead."""
    _check(message, "", cut_long_strings)


def max_length(field: FieldDescriptor) -> int:
    return field.GetOptions().Extensions[options_pb2.max_length] or DEFAULT_MAX_STRING_LENGTH


def _check(message: Message, prefix: str, cut_long_strings: bool) -> None:
    if not _may_refuse(message.DESCRIPTOR):
        return  # numbers only, at any depth (a Vector3, a Matrix3): nothing to look at
    for field, value in message.ListFields():
        path = f"{prefix}{field.name}"
        values = value if _is_repeated(field) else (value,)
        if field.type == _ENUM:
            for item in values:
                _check_enum(field, item, path)
        elif field.type == _STRING:
            limit = max_length(field)
            if cut_long_strings and not _is_repeated(field) and len(value) > limit:
                setattr(message, field.name, value[:limit])
                continue
            for item in values:
                if len(item) > limit:
                    raise InvalidArgumentError(
                        f"{path} has {len(item)} characters; it takes at most {limit}",
                        reason="STRING_TOO_LONG")
        elif field.type == _MESSAGE and not field.message_type.GetOptions().map_entry:
            for index, item in enumerate(values):
                where = f"{path}[{index}]" if _is_repeated(field) else path
                _check_time(field.message_type.full_name, item, where)
                _check(item, f"{where}.", cut_long_strings)


@functools.cache
def _may_refuse(descriptor: Descriptor) -> bool:
    """Whether a message of this type can hold anything _check refuses: an enum, a string, a
    Duration or a Timestamp, in it or in any message it can hold."""
    seen, pending = set(), [descriptor]
    while pending:
        current = pending.pop()
        if current.full_name in _TIME_TYPES:
            return True
        for field in current.fields:
            if field.type in (_ENUM, _STRING):
                return True
            if field.type == _MESSAGE and field.message_type.full_name not in seen:
                seen.add(field.message_type.full_name)
                pending.append(field.message_type)
    return False


def _check_time(type_name: str, value: Message, path: str) -> None:
    if type_name == "google.protobuf.Duration":
        seconds, nanos = value.seconds, value.nanos
        if abs(seconds) > DURATION_MAX_SECONDS or abs(nanos) > NANOS_MAX or seconds * nanos < 0:
            raise InvalidArgumentError(
                f"{path} is not a valid Duration ({seconds} s, {nanos} ns): at most "
                f"{DURATION_MAX_SECONDS} s, nanos under 1e9 with the sign of the seconds",
                reason="BAD_DURATION")
    elif type_name == "google.protobuf.Timestamp":
        seconds, nanos = value.seconds, value.nanos
        if not TIMESTAMP_SECONDS[0] <= seconds <= TIMESTAMP_SECONDS[1] or not (
                0 <= nanos <= NANOS_MAX):
            raise InvalidArgumentError(
                f"{path} is not a valid Timestamp ({seconds} s, {nanos} ns): "
                "years 1 to 9999, nanos 0 to 999999999",
                reason="BAD_TIMESTAMP")


def _check_enum(field: FieldDescriptor, value: int, path: str) -> None:
    enum = field.enum_type
    if value in enum.values_by_number:
        return
    names = ", ".join(v.name for v in enum.values if v.number != 0)
    raise InvalidArgumentError(f"{path} = {value} is not a {enum.name} value; use one of {names}",
                               reason="UNKNOWN_ENUM_VALUE")


def _is_repeated(field: FieldDescriptor) -> bool:
    return field.is_repeated
