"""The per-command records an MCAP recording hands its writer process, packed in fixed binary
layouts. No gRPC here.

At 1 kHz, a command's increment and its ack are most of what an episode records. The command
path packs each into a bytearray (a struct and the ack's serialization, a few µs), and the
recorder's drain sends the buffers whole: the messages are built, indexed and compressed in the
writer (recording_writer), a process with a GIL of its own. Anything more per item on the
DecisionServer's side costs its command path: queueing, converting and pickling each one costs
about 25 µs of its GIL per command on a busy 2-core machine, enough to move teleop_1000's p99
(docs/demonstrations.md, "Cost to teleoperation").

An increment: INCREMENT_HEAD (log time ns, offset s, frame code, Δposition, Δrotation row-major,
target position, joint count), then that many float64 joint increments. An ack: ACK_HEAD (log
time ns, length), then the serialized CommandAck.
"""

from __future__ import annotations

import struct
from collections.abc import Iterator

import numpy as np

INCREMENT_HEAD = struct.Struct("<qdB3d9d3dB")
ACK_HEAD = struct.Struct("<qI")
FRAME_CODES = {"BASE": 0, "WRIST": 1, "TOOL": 2, "JOINTS": 3}
FRAME_NAMES = {code: name for name, code in FRAME_CODES.items()}


def pack_increment(buffer: bytearray, log_time_ns: int, offset_s: float, frame: str,
                   delta_position, delta_rotation, target_position, delta_joints) -> None:
    """One increment appended to `buffer` (Δrotation: 3×3; `delta_joints`: None for a
    Cartesian increment)."""
    joints = () if delta_joints is None else np.ravel(delta_joints).tolist()
    # (.tolist(): Python floats, which struct packs several times faster than numpy's)
    buffer += INCREMENT_HEAD.pack(log_time_ns, offset_s, FRAME_CODES[frame],
                                  *np.ravel(delta_position).tolist(),
                                  *np.ravel(delta_rotation).tolist(),
                                  *np.ravel(target_position).tolist(), len(joints))
    if joints:
        buffer += struct.pack(f"<{len(joints)}d", *joints)


def unpack_increments(data: bytes) -> Iterator[tuple[int, tuple]]:
    """(log time ns, (offset s, frame, Δposition, Δrotation (9 row-major), target, Δjoints or
    None)) for each increment packed in `data`, in order."""
    view = memoryview(data)
    at = 0
    while at < len(view):
        log_time, offset, code, *values = INCREMENT_HEAD.unpack_from(view, at)
        at += INCREMENT_HEAD.size
        count = values[15]
        joints = None
        if count:
            joints = list(struct.unpack_from(f"<{count}d", view, at))
            at += 8 * count
        yield log_time, (offset, FRAME_NAMES[code], values[0:3], values[3:12], values[12:15],
                         joints)


def pack_ack(buffer: bytearray, log_time_ns: int, serialized: bytes) -> None:
    """One serialized CommandAck appended to `buffer`."""
    buffer += ACK_HEAD.pack(log_time_ns, len(serialized))
    buffer += serialized


def unpack_acks(data: bytes) -> Iterator[tuple[int, bytes]]:
    """(log time ns, serialized CommandAck) for each ack packed in `data`, in order."""
    view = memoryview(data)
    at = 0
    while at < len(view):
        log_time, length = ACK_HEAD.unpack_from(view, at)
        at += ACK_HEAD.size
        yield log_time, bytes(view[at:at + length])
        at += length
