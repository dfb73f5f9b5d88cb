"""A DecisionServer recording as one MCAP file, in the project's protobuf messages. No gRPC here.

The channels and the metadata are documented on RecordingFormat (decision_server.proto):
/recording/increment (RecordedIncrement: what a replay sends again), /recording/ack,
/robot/state and /robot/wrench (sampled at SAMPLE_PERIOD_S), /decision_server/events, and a
metadata record "recording". Each channel's schema is the message's file descriptors
(mcap-protobuf-support writes them), so any MCAP reader decodes the file without gen/.

`McapRecorder` drains on a thread of its own (`Recorder`, which the JSONL recorder shares): the
command path only queues, or packs an increment or an ack into a buffer (recording_records), so
a slow or full disk never slows or fails a command. The file itself
is written by a process of its own, at ordinary priority (recording_writer, reached through
writer_process.RemoteMcapFile): the MCAP writer's records, CRCs and compression, and the
stereo video, take none of the DecisionServer's GIL or its real-time time. A full disk
stops the recording. A writer that falls behind keeps what it wrote: new messages are dropped,
counted, while it catches up, and each such gap is a "recording_gap" metadata record; the
"recording" metadata then says what was dropped ("dropped", by channel). A recording that lost
increments is kept, but not replayed (INCOMPLETE_RECORDING): its path would not be the one
recorded.
"""

from __future__ import annotations

import json
import logging
import os
import queue
import struct
import threading
import zlib
from collections import Counter
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, BinaryIO

import numpy as np
from mcap.exceptions import EndOfFile
from mcap.reader import make_reader
from mcap.well_known import MessageEncoding
from mcap.writer import LIBRARY_IDENTIFIER, CompressionType
from mcap.writer import Writer as McapWriter
from mcap_protobuf.decoder import DecoderFactory
from mcap_protobuf.schema import register_schema

from services.common.inbox import queued_now
from services.decision_server.recording_records import pack_ack, pack_increment
from services.decision_server.writer_process import RemoteMcapFile, WriterStart
from services.runtime.clock import Clock
from telerobot.v1 import decision_server_pb2 as pb
from telerobot.v1 import types_pb2
from wire import convert
from wire.errors import FailedPreconditionError, TelerobotError

if TYPE_CHECKING:
    from services.decision_server.camera_feed import CameraSource

log = logging.getLogger(__name__)

INCREMENT = "/recording/increment"
ACK = "/recording/ack"
STATE = "/robot/state"
WRENCH = "/robot/wrench"
EVENTS = "/decision_server/events"
STEREO_HEADER = "/camera/stereo_header"
STEREO_VIDEO = "/camera/stereo/video"  # foxglove.CompressedVideo, as make teleop --mcap writes
CHANNELS = (INCREMENT, ACK, STATE, WRENCH, EVENTS)
PROFILE = "telerobot"
LIBRARY = f"{LIBRARY_IDENTIFIER} telerobot"
METADATA = "recording"
MAGIC = b"\x89MCAP0\r\n"  # an MCAP file's first and last bytes

SAMPLE_PERIOD_S = 0.05  # robot state and wrench at 20 Hz: the arm's path, not its servo
# An episode's (a recording with a task): as fast as the streams bring them (100 Hz), so each
# frame of a dataset at up to 50 fps has its own samples rather than its neighbours' blend.
EPISODE_SAMPLE_PERIOD_S = 0.01
# Items waiting for the writer; past that it has fallen behind, and new acks and events are
# dropped (counted) until it is back under half of it. Increments, which a replay needs, have
# twice the room: a writer that stalls for a while loses its acks first.
QUEUE_LIMIT = 20_000
GAP = "recording_gap"  # the metadata record of each gap
# What each kind of queued item is written as: the channels a gap counts.
KIND_CHANNELS = {"increment": INCREMENT, "ack": ACK, "event": EVENTS}
# The writer takes what is queued once a period, not as each item comes: at 1 kHz of acks,
# waking for each cost the DecisionServer more than writing them (a wake is a GIL hand-over).
DRAIN_PERIOD_S = 0.01
CHUNK_BYTES = 256 * 1024  # smaller than the default 1 MB, so a full disk shows up early

_FRAMES = {"BASE": types_pb2.REFERENCE_FRAME_BASE, "WRIST": types_pb2.REFERENCE_FRAME_WRIST,
           "TOOL": types_pb2.REFERENCE_FRAME_TOOL}
_FRAME_NAMES = {value: name for name, value in _FRAMES.items()}


# -- RecordedCommand <-> RecordedIncrement ---------------------------------------------------

def increment_to_proto(command) -> pb.RecordedIncrement:
    return increment_message(command.offset_s, command.frame, command.delta_position_m,
                             command.delta_rotation.reshape(9), command.target_position_m,
                             command.delta_joints_rad)


def increment_message(offset_s: float, frame: str, delta_position, delta_rotation, target,
                      delta_joints) -> pb.RecordedIncrement:
    message = pb.RecordedIncrement(offset=convert.duration(offset_s),
                                   target_position_m=convert.vector3_to_proto(target))
    if delta_joints is not None:
        message.delta_joints_rad.extend(float(v) for v in delta_joints)
    else:
        message.frame = _FRAMES[frame]
        message.delta_position_m.CopyFrom(convert.vector3_to_proto(delta_position))
        message.delta_rotation.CopyFrom(convert.rotation_to_proto(delta_rotation))
    return message


def increment_from_proto(message, recorded_command_type):
    """A RecordedCommand (the type is passed in: recordings.py imports this module)."""
    offset_s = message.offset.seconds + message.offset.nanos / 1e9
    target = convert.vector3_value(message.target_position_m)
    if message.delta_joints_rad:
        return recorded_command_type(offset_s, "JOINTS", np.zeros(3), np.eye(3), target,
                                     np.array(message.delta_joints_rad, dtype=float))
    if message.frame not in _FRAME_NAMES:
        raise ValueError(f"an increment with no frame at {offset_s:.3f} s")
    return recorded_command_type(offset_s, _FRAME_NAMES[message.frame],
                                 convert.vector3_value(message.delta_position_m),
                                 convert.rotation_value(message.delta_rotation), target)


# -- writing -------------------------------------------------------------------------------

class McapFile:
    """One MCAP file being written, synchronously, to `output` (a path, or a binary file this
    takes over). Log times never go back on a channel. Its "recording" metadata holds `counts`,
    what it holds by channel."""

    def __init__(self, output: Path | BinaryIO):
        if isinstance(output, (str, Path)):
            self._file = open(output, "wb")  # noqa: SIM115 - closed in finish()/abandon()
        else:
            self._file = output
        self._writer = McapWriter(self._file, chunk_size=CHUNK_BYTES,
                                  compression=CompressionType.ZSTD)
        self._writer.start(profile=PROFILE, library=LIBRARY)
        self._channels: dict[str, int] = {}
        self._last: dict[str, int] = {}
        self.counts: Counter[str] = Counter()

    def write(self, topic: str, message, log_time_ns: int,
              publish_time_ns: int | None = None) -> None:
        self.write_serialized(topic, type(message), message.SerializeToString(), log_time_ns,
                              publish_time_ns)

    def write_serialized(self, topic: str, message_type, data: bytes, log_time_ns: int,
                         publish_time_ns: int | None = None) -> None:
        """A message already serialized, of `message_type` (its channel's schema)."""
        channel = self._channels.get(topic)
        if channel is None:
            channel = self._channels[topic] = self._writer.register_channel(
                topic=topic, message_encoding=MessageEncoding.Protobuf,
                schema_id=register_schema(self._writer, message_type))
        log_time = max(int(log_time_ns), self._last.get(topic, 0))
        self._writer.add_message(channel, log_time=log_time, data=data,
                                 publish_time=int(publish_time_ns or log_time),
                                 sequence=self.counts[topic])
        self._last[topic] = log_time
        self.counts[topic] += 1

    def flush(self) -> None:
        self._file.flush()

    def metadata(self, name: str, data: dict[str, str]) -> None:
        """A metadata record, between chunks (a gap's)."""
        self._writer.add_metadata(name, data)

    def finish(self, metadata: dict[str, str]) -> None:
        """The "recording" metadata (with `counts`), the summary; on the disk (fsync)."""
        try:
            self._writer.add_metadata(METADATA, {**metadata,
                                                 "counts": json.dumps(dict(self.counts))})
            self._writer.finish()
            self._file.flush()
            os.fsync(self._file.fileno())
        finally:
            self._file.close()

    def abandon(self) -> None:
        """Close without finishing (the file is left for the caller to delete)."""
        try:
            self._file.close()
        except OSError:
            pass  # the buffered bytes had nowhere to go either


def write_commands(path: Path, name: str, create_time_ns: int, commands) -> None:
    """A whole recording of increments only (the converter's JSONL → MCAP)."""
    file = McapFile(path)
    try:
        for command in commands:
            file.write(INCREMENT, increment_to_proto(command),
                       create_time_ns + round(command.offset_s * 1e9))
    except BaseException:
        file.abandon()
        raise
    duration = commands[-1].offset_s - commands[0].offset_s if commands else 0.0
    file.finish(metadata_of(name, create_time_ns, len(commands), duration))


def metadata_of(name: str, create_time_ns: int, command_count: int, duration_s: float,
                dropped: Counter | None = None, task: str = "", outcome: str = "",
                robot: str = "") -> dict[str, str]:
    """The "recording" metadata but its "counts" (the file's: McapFile.finish); "dropped" (by
    channel) only when a gap dropped messages; "task", "outcome" (an EpisodeOutcome name
    without its prefix) and "robot" (the arm's name, when known) for an episode."""
    metadata = {"name": name, "create_time_ns": str(create_time_ns),
                "duration_s": repr(float(duration_s)), "command_count": str(command_count)}
    if dropped:
        metadata["dropped"] = json.dumps(dict(dropped))
    if task:
        metadata["task"] = task
        metadata["outcome"] = outcome or "UNSPECIFIED"
        if robot:
            metadata["robot"] = robot
    return metadata


def incomplete(name: str, dropped_increments: int) -> FailedPreconditionError:
    """What a replay of a recording that lost increments answers."""
    return FailedPreconditionError(
        f"the recording '{name}' lost {dropped_increments} increments while its writer was "
        "behind: it is kept, but a replay would not retrace the recorded path",
        reason="INCOMPLETE_RECORDING")


def check_complete(name: str, metadata: dict[str, str]) -> None:
    """FailedPreconditionError (INCOMPLETE_RECORDING) when the "recording" metadata says
    increments were dropped."""
    try:
        lost = int(json.loads(metadata.get("dropped") or "{}").get(INCREMENT, 0))
    except (ValueError, TypeError, AttributeError) as error:
        raise FailedPreconditionError(f"the recording '{name}' has bad metadata: {error}",
                                      reason="CORRUPT_RECORDING") from error
    if lost:
        raise incomplete(name, lost)


@dataclass(frozen=True)
class Sources:
    """Where the recorder samples the arm: each returns the latest sample (a SlaveState, a
    SlaveWrench) or None, and may raise a TelerobotError (nothing to sample)."""

    state: Callable[[], object] | None = None
    wrench: Callable[[], object] | None = None
    # The stereo camera whose H.264 video the recording keeps: the writer process reads it
    # (recording_writer). Only MCAP recordings take it.
    video: CameraSource | None = None
    # The arm's name (GetArmInfo's), which an episode's metadata records as "robot".
    arm_name: str = ""


@dataclass
class Gap:
    """Messages dropped while the writer was behind: from the first to the last dropped
    (the server's wall clock, ns), counted by kind (increment, ack, event)."""

    first_ns: int
    last_ns: int
    counts: Counter = field(default_factory=Counter)

    def as_metadata(self) -> dict[str, str]:
        return {"first_ns": str(self.first_ns), "last_ns": str(self.last_ns),
                "dropped": json.dumps({KIND_CHANNELS[kind]: n for kind, n in self.counts.items()})}


class Recorder:
    """A recording being written on its own thread. `add` (an increment), `ack` and `event`
    only queue (McapRecorder packs increments and acks instead: recording_records); the
    writer takes what is queued every `drain_period_s` (DRAIN_PERIOD_S unless a format says
    otherwise). `on_failure(reason)` is called (on
    the writer thread) when writing fails (a full disk): the recording is then over, nothing
    more is queued, and the partial file is deleted. A writer QUEUE_LIMIT behind loses no file:
    new items are dropped and counted (`dropped`, by channel) until it catches up, and the gap
    is written in the file (`write_gap`).

    A format subclasses it: `open()` (in the constructor: a bad directory fails
    StartRecording), `write(item)`, `write_gap(gap)`, `tick()` after each drain,
    `finish_file()` and `abandon()`."""

    drain_period_s = DRAIN_PERIOD_S

    def __init__(self, path: Path, name: str, create_time_ns: int, clock: Clock,
                 on_failure: Callable[[str], None]):
        self.path = Path(path)
        self.name, self.create_time_ns = name, create_time_ns
        self._clock = clock
        self._on_failure = on_failure
        self._queue: queue.SimpleQueue = queue.SimpleQueue()
        self._finishing = threading.Event()  # wakes the writer at once for the end
        self._lock = threading.Lock()  # the count of queued items and the open gap
        self._queued = 0
        self._gap: Gap | None = None
        self.error: str | None = None
        # What was written (the writer thread's): the increments' count and span, and the
        # messages dropped in gaps, by channel.
        self.command_count = 0
        self.first_offset_s: float | None = None
        self.last_offset_s = 0.0
        self.dropped: Counter[str] = Counter()
        self.open()
        self._thread = threading.Thread(target=self._run, name=f"recording-{name}",
                                        daemon=True)
        self._thread.start()

    @property
    def duration_s(self) -> float:
        return 0.0 if self.first_offset_s is None else self.last_offset_s - self.first_offset_s

    # -- from any thread: queue only --------------------------------------------------------
    def add(self, offset_s: float, frame: str, delta_position, delta_rotation,
            target_position, delta_joints) -> None:
        """An applied increment, `offset_s` into the recording (a RecordedCommand's fields;
        the arrays are the caller's, not to be kept)."""
        raise NotImplementedError

    def ack(self, ack: pb.CommandAck) -> None:
        """An ack the server sent."""
        raise NotImplementedError

    def event(self, event) -> None:
        self._put("event", event)

    def _put(self, kind: str, *payload) -> None:
        if self.error is not None:
            return
        with self._lock:
            if self._admit(kind):
                self._queue.put((kind, *payload))

    def _admit(self, kind: str) -> bool:
        """With the lock held: whether there is room for one more item of `kind` (then
        counted as queued), else it is dropped and counted in the open gap."""
        resume = QUEUE_LIMIT // 2
        if self._gap is not None and self._queued <= resume:
            self._enqueue(("gap", self._gap))  # caught up: the gap is over
            self._gap = None
        limit = 2 * QUEUE_LIMIT if kind == "increment" else (
            resume if self._gap is not None else QUEUE_LIMIT)
        if self._queued < limit:
            self._queued += 1
            return True
        now = self._clock.time_ns()
        if self._gap is None:  # (said once per gap, so under the lock)
            self._gap = Gap(now, now)
            log.warning("the recording '%s' fell %d messages behind: new ones are dropped, "
                        "and counted, until it catches up", self.name, limit)
        self._gap.last_ns = now
        self._gap.counts[kind] += 1
        return False

    def _enqueue(self, item) -> None:
        """With the lock held."""
        self._queued += 1
        self._queue.put(item)

    def _done(self, count: int) -> None:
        """`count` queued items are written."""
        with self._lock:
            self._queued -= count

    def finish(self) -> None:
        """Write what is queued (and the gap still open), the end, and close. Raises
        FailedPreconditionError (RECORDING_FAILED) when the writing failed."""
        with self._lock:
            if self._gap is not None:
                self._enqueue(("gap", self._gap))
                self._gap = None
            self._enqueue(("finish",))
        self._finishing.set()
        self._thread.join()
        if self.error is not None:
            raise FailedPreconditionError(f"the recording '{self.name}' stopped by itself: "
                                          f"{self.error}; nothing was saved",
                                          reason="RECORDING_FAILED")

    # -- the writer thread ------------------------------------------------------------------
    def _run(self) -> None:
        try:
            while True:
                self._finishing.wait(self.drain_period_s)
                for item in queued_now(self._queue):
                    kind = item[0]
                    if kind == "finish":
                        self.finish_file()
                        return
                    if kind == "gap":
                        gap = item[1]
                        self.dropped.update({KIND_CHANNELS[k]: n for k, n in gap.counts.items()})
                        self.write_gap(gap)
                    else:
                        if kind == "increment":
                            self._count(item[1].offset_s)
                        self.write(item)
                    self._done(1)
                self.drain_packed()
                self.tick()
        except Exception as error:  # noqa: BLE001 - any failure to write ends the recording
            self.error = f"writing {self.path.name} failed: {error}"
        # Failed: the recording is over, and its partial file goes.
        self.abandon()
        log.warning("the recording '%s' stopped: %s", self.name, self.error)
        self._on_failure(self.error)

    def _count(self, offset_s: float) -> None:
        """An increment written (or packed)."""
        self.command_count += 1
        if self.first_offset_s is None:
            self.first_offset_s = offset_s
        self.last_offset_s = offset_s

    # -- a format's ----------------------------------------------------------------------------
    def open(self) -> None:
        raise NotImplementedError

    def drain_packed(self) -> None:
        """Each drain, after the queued items: send on what the command path packed itself
        (McapRecorder's increments and acks)."""

    def write(self, item) -> None:
        raise NotImplementedError

    def write_gap(self, gap: Gap) -> None:
        raise NotImplementedError

    def tick(self) -> None:
        """After each drain: make what was written reach the disk (or at least the OS)."""

    def finish_file(self) -> None:
        raise NotImplementedError

    def abandon(self) -> None:
        raise NotImplementedError


class McapRecorder(Recorder):
    """An MCAP recording (see Recorder), which also samples `sources` every SAMPLE_PERIOD_S
    and keeps the server's events (`event_to_message` makes each the message to keep, or
    None to leave it out). The file is written by a writer of its own, which `writer` starts
    (RemoteMcapFile: a process, or a thread in the unit tests): here each event and sample is
    only serialized, the command path's packed increments and acks taken whole, and all sent
    on, each drain."""

    def __init__(self, path: Path, name: str, create_time_ns: int, clock: Clock,
                 sources: Sources, event_to_message: Callable | None,
                 on_failure: Callable[[str], None], task: str,
                 writer: WriterStart):
        self._sources = sources
        self._writer_start = writer
        self._event_to_message = event_to_message
        self._last_samples: dict[str, int] = {}
        self._next_sample = clock.monotonic()
        self.task = task
        # Drained as often as it samples: an episode at 100 Hz, else at the 20 Hz of the arm's
        # path. Each drain serializes a batch and sends it to the writer: at 20 Hz the
        # recording's thread takes about 2.5 µs of the DecisionServer's CPU per command at
        # 1 kHz, against 16-20 at 100 Hz.
        self.drain_period_s = EPISODE_SAMPLE_PERIOD_S if task else SAMPLE_PERIOD_S
        self.outcome = ""  # set before finish(): how the episode went
        # What the command path packed since the last drain (recording_records), under the
        # lock: increments and acks, and how many of each.
        self._increments, self._acks = bytearray(), bytearray()
        self._packed = [0, 0]
        super().__init__(path, name, create_time_ns, clock, on_failure)

    @property
    def video_frames(self) -> int:
        return self._file.counts[STEREO_VIDEO]  # the writer's count, once finished

    def open(self) -> None:
        self._file = RemoteMcapFile(self.path, self._sources.video, self._writer_start)

    def tick(self) -> None:
        now = self._clock.monotonic()
        if now >= self._next_sample:
            self._sample()
            self._next_sample = now + (EPISODE_SAMPLE_PERIOD_S if self.task else SAMPLE_PERIOD_S)
        self._file.flush()  # to the writer; a full disk there shows up now, not at the end

    # -- the command path: packed, not queued ------------------------------------------------
    def add(self, offset_s: float, frame: str, delta_position, delta_rotation,
            target_position, delta_joints) -> None:
        if self.error is not None:
            return
        with self._lock:
            if self._admit("increment"):
                pack_increment(self._increments, self.create_time_ns + round(offset_s * 1e9),
                               offset_s, frame, delta_position, delta_rotation,
                               target_position, delta_joints)
                self._packed[0] += 1
                self._count(offset_s)

    def ack(self, ack: pb.CommandAck) -> None:
        if self.error is not None:
            return
        serialized = ack.SerializeToString()  # (outside the lock)
        with self._lock:
            if self._admit("ack"):
                pack_ack(self._acks, self._clock.time_ns(), serialized)
                self._packed[1] += 1

    def drain_packed(self) -> None:
        with self._lock:
            if not any(self._packed):
                return
            increments, self._increments = self._increments, bytearray()
            acks, self._acks = self._acks, bytearray()
            counts, self._packed = self._packed, [0, 0]
        self._file.write_packed(increments, acks, {INCREMENT: counts[0], ACK: counts[1]})
        self._done(counts[0] + counts[1])

    def finish_file(self) -> None:
        self.drain_packed()
        self._sample()
        self._file.finish(metadata_of(self.name, self.create_time_ns, self.command_count,
                                      self.duration_s, self.dropped, self.task, self.outcome,
                                      self._sources.arm_name))

    def abandon(self) -> None:
        self._file.abandon()
        self.path.unlink(missing_ok=True)

    def write_gap(self, gap: Gap) -> None:
        self._file.metadata(GAP, gap.as_metadata())

    def write(self, item) -> None:
        """An event (the only kind queued: increments and acks are packed)."""
        if self._event_to_message is not None:
            event = item[1]
            message = self._event_to_message(event)
            if message is not None:
                self._file.write(EVENTS, message, event.time_ns)

    def _sample(self) -> None:
        """The latest robot state and wrench, each written once."""
        now = self._clock.time_ns()
        state = self._latest(self._sources.state)
        if state is not None and state.sample_time_ns != self._last_samples.get(STATE):
            self._last_samples[STATE] = state.sample_time_ns
            self._file.write(STATE, types_pb2.RobotState(
                sequence=self._file.counts[STATE] + 1,
                sample_time=convert.timestamp(state.sample_time_ns),
                status=types_pb2.RobotStatus.Value(f"ROBOT_STATUS_{state.status}"),
                tool_pose=convert.pose_to_proto(state.tool_pose),
                joint_positions_rad=getattr(state, "joint_positions_rad", ())),
                now, state.sample_time_ns)
        wrench = self._latest(self._sources.wrench)
        if wrench is not None and wrench.sample_time_ns != self._last_samples.get(WRENCH):
            self._last_samples[WRENCH] = wrench.sample_time_ns
            self._file.write(WRENCH, convert.wrench_to_proto(wrench.force_n, wrench.torque_nm),
                             now, wrench.sample_time_ns)

    @staticmethod
    def _latest(source):
        if source is None:
            return None
        try:
            return source()
        except TelerobotError:
            return None  # nothing to sample now (the arm unreachable)


# -- reading -------------------------------------------------------------------------------

@dataclass(frozen=True)
class McapContents:
    name: str
    create_time_ns: int
    commands: list


def read_summary(path: Path) -> dict[str, str]:
    """The "recording" metadata of a finished file (cheap: the summary only). Raises
    FailedPreconditionError (CORRUPT_RECORDING) when the file is truncated or not MCAP."""
    try:
        with open(path, "rb") as stream:
            if stream.read(len(MAGIC)) != MAGIC:
                raise ValueError("not an MCAP file")
            stream.seek(-len(MAGIC), 2)
            if stream.read(len(MAGIC)) != MAGIC:  # a finished file ends with it too
                raise EndOfFile()
            stream.seek(0)
            reader = make_reader(stream)
            if reader.get_summary() is None:
                raise ValueError("no summary: the file was not finished (truncated?)")
            for record in reader.iter_metadata():
                if record.name == METADATA:
                    return dict(record.metadata)
        raise ValueError(f"no '{METADATA}' metadata")
    except Exception as error:  # noqa: BLE001 - whatever the parser says of a bad file
        raise _corrupt(path, error) from error


def read_commands(path: Path, recorded_command_type) -> McapContents:
    """Every increment, with the recording's name and start time. Reads the whole file,
    checking its CRCs; FailedPreconditionError (CORRUPT_RECORDING) when it is truncated, corrupt
    or holds a malformed increment, (INCOMPLETE_RECORDING) when increments were dropped."""
    try:
        metadata = read_summary(path)
        check_complete(metadata.get("name", path.stem), metadata)
        _check_crcs(path.read_bytes())
        with open(path, "rb") as stream:
            reader = make_reader(stream, validate_crcs=True,
                                 decoder_factories=[DecoderFactory()])
            commands = [increment_from_proto(message, recorded_command_type)
                        for _, _, _, message in reader.iter_decoded_messages(
                            topics=[INCREMENT], log_time_order=True)]
        return McapContents(metadata.get("name", path.stem),
                            int(metadata.get("create_time_ns", "0")), commands)
    except FailedPreconditionError:
        raise
    except Exception as error:  # noqa: BLE001 - whatever the parser says of a bad file
        raise _corrupt(path, error) from error


def _check_crcs(data: bytes) -> None:
    """The CRCs of the data and summary sections (the file's, beside each chunk's): a flipped
    byte anywhere, even in an index the reader would skip, makes the file corrupt."""
    footer = data[-len(MAGIC) - 29:-len(MAGIC)]
    opcode, _, summary_start, _, summary_crc = struct.unpack("<BQQQI", footer)
    if opcode != 0x02:
        raise ValueError("no footer record")
    if not summary_start:
        return
    opcode, _, data_crc = struct.unpack("<BQI", data[summary_start - 13:summary_start])
    if opcode != 0x0F:
        raise ValueError("no data end record before the summary")
    if data_crc and zlib.crc32(data[:summary_start - 13]) != data_crc:
        raise ValueError("the data section's CRC does not match (corrupt)")
    if summary_crc and zlib.crc32(data[summary_start:-len(MAGIC) - 4]) != summary_crc:
        raise ValueError("the summary section's CRC does not match (corrupt)")


def _corrupt(path: Path, error: Exception) -> FailedPreconditionError:
    what = str(error) or type(error).__name__
    if isinstance(error, EndOfFile):
        what = "it ends early (truncated: the recording was not finished, or cut short)"
    return FailedPreconditionError(f"the recording file {path.name} cannot be read: {what}",
                                   reason="CORRUPT_RECORDING")
