"""A DecisionServer recording as one MCAP file, in the project's protobuf messages. No gRPC here.

The channels and the metadata are documented on RecordingFormat (decision_server.proto):
/recording/increment (RecordedIncrement: what a replay sends again), /recording/ack,
/robot/state and /robot/wrench (sampled at SAMPLE_PERIOD_S), /decision_server/events, and a
metadata record "recording". Each channel's schema is the message's file descriptors
(mcap-protobuf-support writes them), so any MCAP reader decodes the file without gen/.

`McapRecorder` writes on a thread of its own: the command path only queues (a deque append),
so a slow or full disk never slows or fails a command; it stops the recording instead.
"""

from __future__ import annotations

import json
import logging
import queue
import struct
import threading
import zlib
from collections import Counter
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from mcap.exceptions import EndOfFile
from mcap.reader import make_reader
from mcap_protobuf.decoder import DecoderFactory
from mcap_protobuf.writer import Writer

from services.common.inbox import queued_now
from services.runtime.clock import Clock
from telerobot.v1 import decision_server_pb2 as pb
from telerobot.v1 import types_pb2
from wire import convert
from wire.errors import FailedPreconditionError, TelerobotError

log = logging.getLogger(__name__)

INCREMENT = "/recording/increment"
ACK = "/recording/ack"
STATE = "/robot/state"
WRENCH = "/robot/wrench"
EVENTS = "/decision_server/events"
CHANNELS = (INCREMENT, ACK, STATE, WRENCH, EVENTS)
PROFILE = "telerobot"
METADATA = "recording"
MAGIC = b"\x89MCAP0\r\n"  # an MCAP file's first and last bytes

SAMPLE_PERIOD_S = 0.05  # robot state and wrench at 20 Hz: the arm's path, not its servo
QUEUE_LIMIT = 20_000  # items waiting for the writer; past that it has fallen behind: stop
# The writer takes what is queued once a period, not as each item comes: at 1 kHz of acks,
# waking for each cost the DecisionServer more than writing them (a wake is a GIL hand-over).
DRAIN_PERIOD_S = 0.01
CHUNK_BYTES = 256 * 1024  # smaller than the default 1 MB, so a full disk shows up early

_FRAMES = {"BASE": types_pb2.REFERENCE_FRAME_BASE, "WRIST": types_pb2.REFERENCE_FRAME_WRIST,
           "TOOL": types_pb2.REFERENCE_FRAME_TOOL}
_FRAME_NAMES = {value: name for name, value in _FRAMES.items()}


# -- RecordedCommand <-> RecordedIncrement ---------------------------------------------------

def increment_to_proto(command) -> pb.RecordedIncrement:
    message = pb.RecordedIncrement(
        offset=convert.duration(command.offset_s),
        target_position_m=convert.vector3_to_proto(command.target_position_m))
    if command.delta_joints_rad is not None:
        message.delta_joints_rad.extend(float(v) for v in command.delta_joints_rad)
    else:
        message.frame = _FRAMES[command.frame]
        message.delta_position_m.CopyFrom(convert.vector3_to_proto(command.delta_position_m))
        message.delta_rotation.CopyFrom(convert.rotation_to_proto(command.delta_rotation))
    return message


def increment_from_proto(message, recorded_command_type):
    """A RecordedCommand (the type is passed in: recordings.py imports this module)."""
    offset_s = message.offset.seconds + message.offset.nanos / 1e9
    target = _vector(message.target_position_m)
    if message.delta_joints_rad:
        return recorded_command_type(offset_s, "JOINTS", np.zeros(3), np.eye(3), target,
                                     np.array(message.delta_joints_rad, dtype=float))
    if message.frame not in _FRAME_NAMES:
        raise ValueError(f"an increment with no frame at {offset_s:.3f} s")
    rotation = (np.array(message.delta_rotation.row_major, dtype=float).reshape(3, 3)
                if message.delta_rotation.row_major else np.eye(3))
    return recorded_command_type(offset_s, _FRAME_NAMES[message.frame],
                                 _vector(message.delta_position_m), rotation, target)


def _vector(vector) -> np.ndarray:
    return np.array([vector.x, vector.y, vector.z], dtype=float)


# -- writing -------------------------------------------------------------------------------

class McapFile:
    """One MCAP file being written, synchronously. Log times never go back on a channel."""

    def __init__(self, path: Path):
        self.path = Path(path)
        self._file = open(self.path, "wb")  # noqa: SIM115 - closed in finish()/abandon()
        self._writer = Writer(self._file, chunk_size=CHUNK_BYTES, profile=PROFILE)
        self._last: dict[str, int] = {}
        self.counts: Counter[str] = Counter()

    def write(self, topic: str, message, log_time_ns: int,
              publish_time_ns: int | None = None) -> None:
        log_time = max(int(log_time_ns), self._last.get(topic, 0))
        self._writer.write_message(topic, message, log_time=log_time,
                                   publish_time=int(publish_time_ns or log_time),
                                   sequence=self.counts[topic])
        self._last[topic] = log_time
        self.counts[topic] += 1

    def flush(self) -> None:
        self._file.flush()

    def finish(self, metadata: dict[str, str]) -> None:
        try:
            self._writer.add_metadata(METADATA, metadata)
            self._writer.finish()
            self._file.flush()
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
    file.finish(metadata_for(name, create_time_ns, commands, file.counts))


def metadata_for(name: str, create_time_ns: int, commands, counts) -> dict[str, str]:
    duration = commands[-1].offset_s - commands[0].offset_s if commands else 0.0
    return {"name": name, "create_time_ns": str(create_time_ns), "duration_s": repr(duration),
            "command_count": str(len(commands)), "counts": json.dumps(dict(counts))}


@dataclass(frozen=True)
class Sources:
    """Where the recorder samples the arm: each returns the latest sample (a SlaveState, a
    SlaveWrench) or None, and may raise a TelerobotError (nothing to sample)."""

    state: Callable[[], object] | None = None
    wrench: Callable[[], object] | None = None


class McapRecorder:
    """An MCAP recording being written on its own thread. `increment`, `ack` and `event`
    only queue; `on_failure(reason)` is called (on the writer thread) when writing fails, and
    the recording is then over: nothing more is queued, and the partial file is deleted."""

    def __init__(self, path: Path, name: str, create_time_ns: int, clock: Clock,
                 sources: Sources, event_to_message: Callable | None,
                 on_failure: Callable[[str], None]):
        self.path = Path(path)
        self.name, self.create_time_ns = name, create_time_ns
        self._clock = clock
        self._sources = sources
        self._event_to_message = event_to_message
        self._on_failure = on_failure
        self._file = McapFile(self.path)  # opened here: a bad directory fails StartRecording
        self._queue: queue.SimpleQueue = queue.SimpleQueue()
        self._finishing = threading.Event()  # wakes the writer at once for the end
        self._queued = 0  # approximate (no lock): only to notice a writer that fell behind
        self._commands: list = []
        self.error: str | None = None
        self._last_samples: dict[str, int] = {}
        self._thread = threading.Thread(target=self._run, name=f"recording-{name}",
                                        daemon=True)
        self._thread.start()

    # -- from any thread: queue only --------------------------------------------------------
    def increment(self, command) -> None:
        self._put(("increment", command))

    def ack(self, ack: pb.CommandAck) -> None:
        self._put(("ack", ack, self._clock.time_ns()))

    def event(self, event) -> None:
        self._put(("event", event))

    def _put(self, item) -> None:
        if self.error is not None:
            return
        if self._queued >= QUEUE_LIMIT:
            self.error = f"the writer fell {QUEUE_LIMIT} messages behind the server"
            return  # the writer thread sees `error` and stops
        self._queued += 1
        self._queue.put(item)

    def finish(self) -> list:
        """Write what is queued, the metadata, and close; returns the recorded increments.
        Raises FailedPreconditionError (RECORDING_FAILED) when the writing failed."""
        self._queue.put(("finish",))
        self._finishing.set()
        self._thread.join()
        if self.error is not None:
            raise FailedPreconditionError(f"the recording '{self.name}' stopped by itself: "
                                          f"{self.error}; nothing was saved",
                                          reason="RECORDING_FAILED")
        return self._commands

    # -- the writer thread ------------------------------------------------------------------
    def _run(self) -> None:
        next_sample = self._clock.monotonic()
        try:
            while self.error is None:
                self._finishing.wait(DRAIN_PERIOD_S)
                for item in queued_now(self._queue):
                    self._queued -= 1
                    if self.error is not None:
                        break  # it fell behind meanwhile: what is left is not written
                    if item[0] == "finish":
                        self._sample()
                        self._file.finish(metadata_for(self.name, self.create_time_ns,
                                                       self._commands, self._file.counts))
                        return
                    self._write(item)
                now = self._clock.monotonic()
                if now >= next_sample:
                    self._sample()
                    self._file.flush()  # a full disk shows up now, not at the end
                    next_sample = now + SAMPLE_PERIOD_S
        except Exception as error:  # noqa: BLE001 - any failure to write ends the recording
            self.error = f"writing {self.path.name} failed: {error}"
        # Failed (or fell behind): the recording is over, and its partial file goes.
        self._file.abandon()
        self.path.unlink(missing_ok=True)
        log.warning("the recording '%s' stopped: %s", self.name, self.error)
        self._on_failure(self.error)

    def _write(self, item) -> None:
        kind = item[0]
        if kind == "increment":
            command = item[1]
            self._commands.append(command)
            self._file.write(INCREMENT, increment_to_proto(command),
                             self.create_time_ns + round(command.offset_s * 1e9))
        elif kind == "ack":
            ack, received = item[1], item[2]
            self._file.write(ACK, ack, received, convert.time_ns(ack.apply_time) or received)
        elif kind == "event" and self._event_to_message is not None:
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
                tool_pose=convert.pose_to_proto(state.tool_pose)), now, state.sample_time_ns)
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
    or holds a malformed increment."""
    try:
        metadata = read_summary(path)
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
