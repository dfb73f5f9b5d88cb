"""Checks every request must pass before a handler sees it, whatever language sent it.

proto3 enums are open: any int32 can arrive on the wire, and a handler that maps it to a
name would crash. Strings are unbounded on the wire, and they end up in logs and events. So
the runtime refuses, for every RPC in one place, an enum value the contract does not define
and a string longer than its field's `(telerobot.v1.max_length)` (DEFAULT_MAX_STRING_LENGTH
when the field declares none), naming the field.
"""

from __future__ import annotations

from google.protobuf.descriptor import FieldDescriptor
from google.protobuf.message import Message

from services.runtime.errors import InvalidArgument
from telerobot.v1 import options_pb2

DEFAULT_MAX_STRING_LENGTH = 256
_ENUM = FieldDescriptor.TYPE_ENUM
_STRING = FieldDescriptor.TYPE_STRING
_MESSAGE = FieldDescriptor.TYPE_MESSAGE


def check_request(message: Message) -> None:
    """Raise InvalidArgument for the first unknown enum value or over-long string in
    `message`, at any depth."""
    _check(message, "")


def max_length(field: FieldDescriptor) -> int:
    return field.GetOptions().Extensions[options_pb2.max_length] or DEFAULT_MAX_STRING_LENGTH


def _check(message: Message, prefix: str) -> None:
    for field, value in message.ListFields():
        path = f"{prefix}{field.name}"
        values = value if _is_repeated(field) else (value,)
        if field.type == _ENUM:
            for item in values:
                _check_enum(field, item, path)
        elif field.type == _STRING:
            limit = max_length(field)
            for item in values:
                if len(item) > limit:
                    raise InvalidArgument(
                        f"{path} has {len(item)} characters; it takes at most {limit}",
                        reason="STRING_TOO_LONG")
        elif field.type == _MESSAGE and not field.message_type.GetOptions().map_entry:
            for index, item in enumerate(values):
                _check(item, f"{path}[{index}]." if _is_repeated(field) else f"{path}.")


def _check_enum(field: FieldDescriptor, value: int, path: str) -> None:
    enum = field.enum_type
    if value in enum.values_by_number:
        return
    names = ", ".join(v.name for v in enum.values if v.number != 0)
    raise InvalidArgument(f"{path} = {value} is not a {enum.name} value; use one of {names}",
                          reason="UNKNOWN_ENUM_VALUE")


def _is_repeated(field: FieldDescriptor) -> bool:
    return field.is_repeated
