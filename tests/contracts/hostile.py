"""Hostile requests for any protobuf message, built by walking its descriptor.

Works on any descriptor, generated or obtained through server reflection (a dynamic pool), so
the fuzz test sends exactly what a client in another language could send.

`variants(descriptor, baseline, rng)` yields `Variant`s, a bounded number per field:

- one field at a time, set to hostile values on top of a baseline (the rest stays valid, so
  a hostile value reaches the deep checks instead of being refused for something else):
  unknown enum values; NaN, +-inf, +-1e308, a denormal, -0.0; the int32/int64 extremes; long,
  control-character, bidi and path-traversal strings; repeated fields with one hostile entry,
  10 000 entries, or none; nested messages present but empty, and walked recursively
  (depth-limited), which also sets each oneof member in turn; Durations and Timestamps past
  their valid range, negative, or with out-of-range nanos;
- a few "everything hostile at once" requests, from a seeded random generator.

`raw_garbage(descriptor)` gives bytes that are not a valid encoding of the message, to send
with identity serializers: truncated fields, impossible tags, a 4 GiB length, and strings
that are not UTF-8.

`contract_violations(message)` lists what the runtime promises to refuse with INVALID_ARGUMENT
(services/runtime/validation.py): enum values the contract does not define and strings past
their field's (telerobot.v1.max_length), at any depth. `well_known_violations(message)` lists
Durations and Timestamps outside the ranges their own .proto files define (no promise yet).
"""

from __future__ import annotations

import math
import random
from collections.abc import Iterator
from dataclasses import dataclass

from google.protobuf import descriptor_pb2, json_format, message_factory
from google.protobuf.descriptor import Descriptor, FieldDescriptor
from google.protobuf.message import Message

from telerobot.v1 import options_pb2

MAX_DEPTH = 4
COMBINATIONS = 3
LONG = 10_000
DEFAULT_MAX_STRING_LENGTH = 256  # services/runtime/validation.py, stated in options.proto

DOUBLES = [math.nan, math.inf, -math.inf, 1e308, -1e308, 5e-324, -0.0]
INT32 = [2**31 - 1, -(2**31), -1]
INT64 = [2**63 - 1, -(2**63), -1]
UINT32 = [2**32 - 1]
UINT64 = [2**64 - 1]
ENUM_CANDIDATES = [3, 99, -5, 2**31 - 1]
STRINGS = [
    "x" * LONG,
    "\x00\x01\xff",
    "\u0000\u202e\ufffd",  # NUL, right-to-left override, replacement character
    "\t\r\n\x1b[2J\x07\x7f\x08",  # control characters and an ANSI escape
    "../../../../etc/passwd",
    "\U0001d54f" * 64,  # astral-plane characters (4 UTF-8 bytes each)
]
BYTES = [b"\xff\xfe\x00" * 5, b"\x00" * LONG]
# (seconds, nanos): past the valid range (+-315576000000 s), negative, bad nanos, mixed signs.
# The most extreme first: a call that hangs on one is not sent the rest (see the test).
DURATIONS = [(2**63 - 1, 0), (-(2**63), 0), (315_576_000_001, 0), (10**10, 0), (-1, 0),
             (0, -1), (0, 10**9), (1, -1), (0, 2**31 - 1)]
# Past year 9999, before year 1, the int64 extremes, bad nanos.
TIMESTAMPS = [(2**63 - 1, 0), (-(2**63), 0), (253_402_300_800, 0), (-62_135_596_801, 0),
              (0, -1), (0, 10**9)]
_WELL_KNOWN = {"google.protobuf.Duration": DURATIONS, "google.protobuf.Timestamp": TIMESTAMPS}

_INT32_TYPES = {FieldDescriptor.TYPE_INT32, FieldDescriptor.TYPE_SINT32,
                FieldDescriptor.TYPE_SFIXED32}
_INT64_TYPES = {FieldDescriptor.TYPE_INT64, FieldDescriptor.TYPE_SINT64,
                FieldDescriptor.TYPE_SFIXED64}
_UINT32_TYPES = {FieldDescriptor.TYPE_UINT32, FieldDescriptor.TYPE_FIXED32}
_UINT64_TYPES = {FieldDescriptor.TYPE_UINT64, FieldDescriptor.TYPE_FIXED64}
_FLOAT_TYPES = {FieldDescriptor.TYPE_DOUBLE, FieldDescriptor.TYPE_FLOAT}


@dataclass(frozen=True)
class Variant:
    """One request: what was made hostile (for the report) and the message itself."""

    label: str
    message: Message
    path: str  # the field path made hostile; "" for the baseline, "*" for combinations


def message_class(descriptor: Descriptor) -> type[Message]:
    return message_factory.GetMessageClass(descriptor)


def build(descriptor: Descriptor, baseline: dict | None = None) -> Message:
    """A message of `descriptor`'s type, from a JSON-style dict (enum names, "0.1s" durations)."""
    message = message_class(descriptor)()
    if baseline:
        json_format.ParseDict(baseline, message)
    return message


def describe(value) -> str:
    """A short, exact description of a hostile value for the failure report."""
    if isinstance(value, tuple):  # (seconds, nanos) of a Duration or Timestamp
        return f"{{seconds: {value[0]}, nanos: {value[1]}}}"
    if isinstance(value, list):
        if not value:
            return "[] (no entries)"
        if len(value) > 20:
            return f"[{describe(value[0])}] * {len(value)}"
        return "[" + ", ".join(describe(v) for v in value) + "]"
    if isinstance(value, str | bytes) and len(value) > 40:
        unit = value[:1]
        if value == unit * len(value):
            return f"{unit!r} * {len(value)}"
        return f"{value[:20]!r}... ({len(value)} {'chars' if isinstance(value, str) else 'bytes'})"
    if isinstance(value, float) and value == 0 and math.copysign(1, value) < 0:
        return "-0.0"
    return repr(value)


def scalar_values(field: FieldDescriptor) -> list:
    """Hostile values for one scalar (or enum) field."""
    kind = field.type
    if kind in _FLOAT_TYPES:
        return list(DOUBLES)
    if kind in _INT32_TYPES:
        return list(INT32)
    if kind in _INT64_TYPES:
        return list(INT64)
    if kind in _UINT32_TYPES:
        return list(UINT32)
    if kind in _UINT64_TYPES:
        return list(UINT64)
    if kind == FieldDescriptor.TYPE_BOOL:
        return [True]
    if kind == FieldDescriptor.TYPE_STRING:
        return list(STRINGS)
    if kind == FieldDescriptor.TYPE_BYTES:
        return list(BYTES)
    if kind == FieldDescriptor.TYPE_ENUM:
        defined = field.enum_type.values_by_number
        return [v for v in ENUM_CANDIDATES if v not in defined]
    raise TypeError(f"no hostile values for field type {kind} ({field.full_name})")


def _padding(field: FieldDescriptor):
    if field.type == FieldDescriptor.TYPE_ENUM:
        values = [v.number for v in field.enum_type.values if v.number != 0]
        return values[0] if values else 0
    if field.type == FieldDescriptor.TYPE_STRING:
        return "p"
    if field.type == FieldDescriptor.TYPE_BYTES:
        return b"p"
    if field.type == FieldDescriptor.TYPE_BOOL:
        return False
    return 0.0 if field.type in _FLOAT_TYPES else 0


def repeated_values(field: FieldDescriptor, current: list) -> list[list]:
    """Hostile lists for a repeated scalar field: each hostile value in the first slot of a
    list as long as the baseline's (at least one entry), 10 000 entries, and no entries."""
    length = max(len(current), 1)
    rest = list(current[1:]) if current else []
    rest += [_padding(field)] * (length - 1 - len(rest))
    lists = [[value, *rest] for value in scalar_values(field)]
    lists.append([current[0] if current else _padding(field)] * LONG)
    if current:
        lists.append([])
    return lists


def _is_well_known(field: FieldDescriptor) -> bool:
    return field.message_type is not None and field.message_type.full_name in _WELL_KNOWN


def _is_repeated(field: FieldDescriptor) -> bool:
    return field.is_repeated


def _is_map(field: FieldDescriptor) -> bool:
    return field.message_type is not None and field.message_type.GetOptions().map_entry


def _leaf_assignments(descriptor: Descriptor, prefix: tuple[str, ...], current: Message | None,
                      depth: int) -> Iterator[tuple[tuple[str, ...], object]]:
    """(field path, value) for every hostile value of every field, walking nested messages.
    A value of None means "the message field present but empty"."""
    for field in descriptor.fields:
        path = (*prefix, field.name)
        value_now = getattr(current, field.name) if current is not None else None
        if _is_map(field):
            continue  # no request uses maps; their entries would need keys of their own
        if field.type == FieldDescriptor.TYPE_MESSAGE:
            if _is_repeated(field):
                yield path, [None] * LONG
                yield path, [None]
                continue
            yield path, None
            if _is_well_known(field):
                for pair in _WELL_KNOWN[field.message_type.full_name]:
                    yield path, pair
            elif depth < MAX_DEPTH:
                nested = (value_now if current is not None and current.HasField(field.name)
                          else None)
                yield from _leaf_assignments(field.message_type, path, nested, depth + 1)
            continue
        if _is_repeated(field):
            for values in repeated_values(field, list(value_now or [])):
                yield path, values
        else:
            for value in scalar_values(field):
                yield path, value


def assign(message: Message, path: tuple[str, ...], value) -> None:
    """Set the field at `path` (creating the messages on the way, which also selects oneof
    members) to `value` (see _leaf_assignments for its forms)."""
    *parents, name = path
    target = message
    for part in parents:
        target = getattr(target, part)
    field = target.DESCRIPTOR.fields_by_name[name]
    if field.type == FieldDescriptor.TYPE_MESSAGE:
        if _is_repeated(field):
            container = getattr(target, name)
            del container[:]
            for _ in value:
                container.add()
            return
        sub = getattr(target, name)
        if value is None:
            sub.SetInParent()
            return
        if isinstance(value, tuple):
            sub.seconds, sub.nanos = value
            return
        raise TypeError(f"cannot put {value!r} in message field {field.full_name}")
    if _is_repeated(field):
        container = getattr(target, name)
        del container[:]
        container.extend(value)
        return
    setattr(target, name, value)


def _label(path: tuple[str, ...], value) -> str:
    shown = "{} (present, empty)" if value is None else describe(value)
    if isinstance(value, list) and value and value[0] is None:
        shown = f"[{{}}] * {len(value)}" if len(value) > 1 else "[{}]"
    return f"{'.'.join(path)} = {shown}"


def variants(descriptor: Descriptor, baseline: dict | None = None,
             rng: random.Random | None = None) -> Iterator[Variant]:
    """The baseline itself, the empty message (if different), then one hostile field at a
    time on top of the baseline, then COMBINATIONS all-hostile messages."""
    base = build(descriptor, baseline)
    yield Variant("baseline " + (json_format.MessageToJson(base, indent=None) or "{}"), base, "")
    if baseline:
        yield Variant("empty request {}", build(descriptor), "")
    for path, value in _leaf_assignments(descriptor, (), base, 0):
        message = message_class(descriptor)()
        message.CopyFrom(base)
        assign(message, path, value)
        yield Variant(_label(path, value), message, ".".join(path))
    rng = rng or random.Random(0)
    leaves = list(_leaf_assignments(descriptor, (), None, 0))
    for index in range(COMBINATIONS):
        message = message_class(descriptor)()
        chosen: dict[tuple[str, ...], object] = {}
        for path, value in leaves:
            chosen.setdefault(path, [])
            chosen[path].append(value)
        picks = []
        for path, values in chosen.items():
            if rng.random() < 0.7:
                value = rng.choice(values)
                try:
                    assign(message, path, value)
                except (TypeError, ValueError):
                    continue
                picks.append(_label(path, value))
        yield Variant(f"combination {index + 1}: " + "; ".join(picks), message, "*")



# -- raw bytes ----------------------------------------------------------------------------------

def _varint(value: int) -> bytes:
    out = bytearray()
    while True:
        byte = value & 0x7F
        value >>= 7
        if value:
            out.append(byte | 0x80)
        else:
            out.append(byte)
            return bytes(out)


GARBAGE = [
    (b"\xff\xff\xff", "bytes ff ff ff (a varint tag that never ends)"),
    (b"\x0a\xff", "bytes 0a ff (field 1, length-delimited, truncated length)"),
    (b"\x0a\x05\x0a", "bytes 0a 05 0a (field 1 says 5 bytes, 1 follows)"),
    (b"\x0a\xff\xff\xff\xff\x0f", "field 1 with a 4 GiB length and no data"),
    (b"\x0f\x01", "wire type 7 (does not exist)"),
    (b"\x0b\x08\x01", "group start on field 1, never ended"),
]
# Sent, but not required to be refused: protobuf's own parser (upb) accepts a tag with field
# number 0 in a message that has no fields, so a server cannot tell it from an empty request.
LENIENT_GARBAGE = [(b"\x00\x01", "tag with field number 0")]


def raw_garbage(descriptor: Descriptor) -> list[tuple[bytes, str]]:
    """Bytes that do not decode as `descriptor`'s message: GARBAGE, plus each top-level string
    field holding bytes that are not UTF-8 (proto3 strings must be). LENIENT_GARBAGE is not
    among them."""
    blobs = list(GARBAGE)
    for field in descriptor.fields:
        if field.type == FieldDescriptor.TYPE_STRING:
            tag = _varint(field.number << 3 | 2)
            blobs.append((tag + b"\x03\xff\xfe\xc0",
                          f"{field.name} = bytes ff fe c0 (not UTF-8)"))
    return blobs


# -- what the runtime promises to refuse ----------------------------------------------------------

def max_length(field: FieldDescriptor) -> int:
    """The field's (telerobot.v1.max_length), read from its serialized options so it works
    for descriptors from a reflection pool too; DEFAULT_MAX_STRING_LENGTH when it has none."""
    options = descriptor_pb2.FieldOptions.FromString(field.GetOptions().SerializeToString())
    return options.Extensions[options_pb2.max_length] or DEFAULT_MAX_STRING_LENGTH


def contract_violations(message: Message, prefix: str = "") -> list[str]:
    """Unknown enum values, over-long strings and out-of-range Durations and Timestamps in
    `message`, at any depth, as services/runtime/validation.py defines them."""
    found = well_known_violations(message, prefix) if not prefix else []
    for field, value in message.ListFields():
        path = f"{prefix}{field.name}"
        values = value if _is_repeated(field) else (value,)
        if field.type == FieldDescriptor.TYPE_ENUM:
            bad = [v for v in values if v not in field.enum_type.values_by_number]
            if bad:
                found.append(f"{path} = {bad[0]} is not a {field.enum_type.name} value")
        elif field.type == FieldDescriptor.TYPE_STRING:
            limit = max_length(field)
            if any(len(v) > limit for v in values):
                found.append(f"{path} is longer than its {limit}-character bound")
        elif field.type == FieldDescriptor.TYPE_MESSAGE and not _is_map(field):
            for index, item in enumerate(values):
                found += contract_violations(
                    item, f"{path}[{index}]." if _is_repeated(field) else f"{path}.")
    return found


DURATION_MAX_SECONDS = 315_576_000_000  # google/protobuf/duration.proto: about 10 000 years
TIMESTAMP_SECONDS = (-62_135_596_800, 253_402_300_799)  # 0001-01-01 .. 9999-12-31
NANOS_MAX = 999_999_999


def well_known_violations(message: Message, prefix: str = "") -> list[str]:
    """Durations and Timestamps in `message`, at any depth, outside the ranges their own
    .proto files define (seconds, nanos, and for a Duration the signs agreeing)."""
    found = []
    for field, value in message.ListFields():
        if field.type != FieldDescriptor.TYPE_MESSAGE or _is_map(field):
            continue
        path = f"{prefix}{field.name}"
        items = value if _is_repeated(field) else (value,)
        for item in items:
            name = field.message_type.full_name
            seconds, nanos = (getattr(item, "seconds", 0), getattr(item, "nanos", 0))
            if name == "google.protobuf.Duration":
                if (abs(seconds) > DURATION_MAX_SECONDS or abs(nanos) > NANOS_MAX
                        or seconds * nanos < 0):
                    found.append(f"{path} = {describe((seconds, nanos))}")
            elif name == "google.protobuf.Timestamp":
                if (not TIMESTAMP_SECONDS[0] <= seconds <= TIMESTAMP_SECONDS[1]
                        or not 0 <= nanos <= NANOS_MAX):
                    found.append(f"{path} = {describe((seconds, nanos))}")
            else:
                found += well_known_violations(item, f"{path}.")
    return found
