"""Recorded command sequences on disk: the DecisionServer's repeatability. No gRPC here.

A recording is a JSON-lines file (<name>.jsonl): a header line, then one line per applied
increment with its time offset from the first: a Cartesian one with its frame, ΔX and ΔM, or a
joint one (frame "JOINTS") with its Δθ; each with the tool target it led to (so a replay can be
checked against the original path). Or, when asked for, an MCAP file (<name>.mcap, see
recording_mcap) holding the same increments and, beside them, the acks, robot state, wrench and
events of the recording's time. A replay reads either. A file that cannot be read (truncated,
corrupt) is FailedPreconditionError (CORRUPT_RECORDING): the request was fine, the stored file is
not.

Both formats are written as the recording runs, off the command path (recording_mcap.Recorder),
to <name>.<suffix>.partial, renamed when it stops. A JSONL recording reaches the OS every
DRAIN_PERIOD_S (and the disk, fsync, when it stops), so a crash loses only its last moments: the
next RecordingStore on the directory (the restarted server) finds the partial file and keeps
what it holds as the recording (a torn last line cut off). A writer that fell behind leaves a
gap line ({"gap": ...}); a recording that lost increments so is kept, but not replayed
(INCOMPLETE_RECORDING).
"""

from __future__ import annotations

import json
import logging
import os
import re
import threading
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from services.decision_server import recording_mcap
from services.decision_server.recording_mcap import INCREMENT, Gap, McapRecorder, Recorder, Sources
from services.decision_server.writer_process import WriterProcesses, WriterStart
from services.runtime.clock import SYSTEM_CLOCK, Clock
from wire.errors import (
    AlreadyExistsError,
    FailedPreconditionError,
    InvalidArgumentError,
    NotFoundError,
)

log = logging.getLogger(__name__)

NAME_PATTERN = re.compile(r"[A-Za-z0-9_-]{1,64}")
MAX_TASK_CHARS = 256
OUTCOMES = ("UNSPECIFIED", "SUCCEEDED", "FAILED", "DISCARDED")  # EpisodeOutcome's names
SUFFIXES = {"JSONL": ".jsonl", "MCAP": ".mcap"}
PARTIAL = ".partial"  # a recording being written: <name>.<suffix>.partial


@dataclass(frozen=True)
class RecordedCommand:
    offset_s: float
    frame: str  # BASE, WRIST or TOOL for a Cartesian increment; JOINTS for a joint one
    delta_position_m: np.ndarray
    delta_rotation: np.ndarray
    target_position_m: np.ndarray
    delta_joints_rad: np.ndarray | None = None  # with frame JOINTS only

    def to_json(self) -> str:
        data = {"offset_s": self.offset_s, "frame": self.frame,
                "delta_position_m": self.delta_position_m.tolist(),
                "delta_rotation": self.delta_rotation.reshape(9).tolist(),
                "target_position_m": self.target_position_m.tolist()}
        if self.delta_joints_rad is not None:
            data["delta_joints_rad"] = self.delta_joints_rad.tolist()
        return json.dumps(data)

    @classmethod
    def from_json(cls, line: str) -> RecordedCommand:
        data = json.loads(line)
        joints = data.get("delta_joints_rad")
        return cls(data["offset_s"], data["frame"], np.array(data["delta_position_m"]),
                   np.array(data["delta_rotation"]).reshape(3, 3),
                   np.array(data["target_position_m"]),
                   None if joints is None else np.array(joints))


@dataclass(frozen=True)
class RecordingInfo:
    name: str
    create_time_ns: int
    duration_s: float
    command_count: int
    format: str = "JSONL"  # or MCAP
    error: str = ""  # why the file cannot be read, when it cannot
    task: str = ""  # an episode's (MCAP): what the operator was doing
    outcome: str = ""  # an episode's: SUCCEEDED, FAILED, DISCARDED or UNSPECIFIED
    video_frames: int = 0


# -- the JSONL format, whole files (the store and the converter) ------------------------------

def write_jsonl(path: Path, name: str, create_time_ns: int, commands) -> None:
    """All or nothing on disk: written beside, then renamed."""
    header = json.dumps({"name": name, "create_time_ns": create_time_ns})
    temporary = path.with_name(path.name + ".partial")
    temporary.write_text("\n".join([header, *(c.to_json() for c in commands)]) + "\n")
    temporary.replace(path)


def read_jsonl(path: Path) -> tuple[str, int, list[RecordedCommand]]:
    """(name in the header, create time, increments); FailedPreconditionError (CORRUPT_RECORDING)
    for a file that is not one, (INCOMPLETE_RECORDING) for one whose writer lost increments."""
    name, created, commands, lost = _read_jsonl(path)
    if lost:
        raise recording_mcap.incomplete(name, lost)
    return name, created, commands


def _read_jsonl(path: Path) -> tuple[str, int, list[RecordedCommand], int]:
    """read_jsonl's, and how many increments its gaps lost."""
    try:
        header, *lines = path.read_text().splitlines()
        meta = json.loads(header)
        commands, lost = [], 0
        for line in lines:
            if line.startswith('{"gap"'):
                lost += int(json.loads(line)["gap"]["dropped"].get(INCREMENT, 0))
            elif line:
                commands.append(RecordedCommand.from_json(line))
        return str(meta.get("name", path.stem)), int(meta["create_time_ns"]), commands, lost
    except (ValueError, KeyError, TypeError, AttributeError) as error:
        raise FailedPreconditionError(f"the recording file {path.name} cannot be read: "
                                      f"{type(error).__name__}: {error}",
                                      reason="CORRUPT_RECORDING") from error


def read_mcap(path: Path) -> tuple[str, int, list[RecordedCommand]]:
    contents = recording_mcap.read_commands(path, RecordedCommand)
    return contents.name, contents.create_time_ns, contents.commands


class JsonlRecorder(Recorder):
    """A JSONL recording written as it runs (see recording_mcap.Recorder): the header at once,
    each increment as a line, flushed to the OS after each drain, fsynced at the end. Acks and
    events have no place in JSONL: they are not queued."""

    def open(self) -> None:
        self._file = open(self.path, "w", encoding="utf-8")  # noqa: SIM115 - closed at the end
        try:
            self._file.write(json.dumps({"name": self.name,
                                         "create_time_ns": self.create_time_ns}) + "\n")
            self._file.flush()
        except OSError:
            self.abandon()
            raise

    def add(self, offset_s: float, frame: str, delta_position, delta_rotation,
            target_position, delta_joints) -> None:
        self._put("increment", RecordedCommand(
            offset_s, frame, np.array(delta_position, float), np.array(delta_rotation, float),
            np.array(target_position, float),
            None if delta_joints is None else np.array(delta_joints, float)))

    def ack(self, ack) -> None:
        pass

    def event(self, event) -> None:
        pass

    def write(self, item) -> None:
        self._file.write(item[1].to_json() + "\n")

    def write_gap(self, gap: Gap) -> None:
        dropped = {recording_mcap.KIND_CHANNELS[kind]: n for kind, n in gap.counts.items()}
        self._file.write(json.dumps({"gap": {"first_ns": gap.first_ns, "last_ns": gap.last_ns,
                                             "dropped": dropped}}) + "\n")

    def tick(self) -> None:
        self._file.flush()  # in the OS: a crash of the server loses nothing written

    def finish_file(self) -> None:
        self._file.flush()
        os.fsync(self._file.fileno())
        self._file.close()

    def abandon(self) -> None:
        try:
            self._file.close()
        except OSError:
            pass  # the buffered lines had nowhere to go either
        self.path.unlink(missing_ok=True)


@dataclass
class _Active:
    name: str
    format: str
    create_time_ns: int
    started: float  # monotonic
    recorder: Recorder


class RecordingStore:
    """Recordings in one directory. One recording at a time. Thread-safe."""

    def __init__(self, directory: Path, clock: Clock = SYSTEM_CLOCK,
                 writer: WriterStart | None = None):
        """`writer` gives each MCAP recording its writer (writer_process): by default a
        WriterProcesses of its own; recording_writer.on_a_thread where no process may start
        (the unit tests)."""
        self.directory = Path(directory)
        self._clock = clock
        self._writer = writer or WriterProcesses()
        self.directory.mkdir(parents=True, exist_ok=True)
        self._lock = threading.Lock()
        self._active: _Active | None = None
        self._failure: tuple[str, str] | None = None  # (name, why) of a recording that died
        # The servicer sets this: a DecisionEvent as the protobuf event the MCAP recordings
        # hold (None to leave one out). Without it, MCAP recordings hold no events.
        self.event_to_message: Callable[[object], object] | None = None
        # Told (name, why) when a recording stops by itself (the core raises an event).
        self.on_failed: Callable[[str, str], None] | None = None
        for partial in sorted(self.directory.glob(f"*{SUFFIXES['JSONL']}{PARTIAL}")):
            self._recover(partial)

    def _path(self, name: str, format: str = "JSONL") -> Path:
        if not NAME_PATTERN.fullmatch(name or ""):
            raise InvalidArgumentError("a recording name is 1 to 64 of A-Z a-z 0-9 _ -",
                                       reason="BAD_NAME")
        return self.directory / f"{name}{SUFFIXES[format]}"

    def _existing(self, name: str) -> tuple[Path, str]:
        for format in SUFFIXES:
            path = self._path(name, format)
            if path.exists():
                return path, format
        raise NotFoundError(f"no recording named '{name}'", reason="NO_RECORDING")

    def start(self, name: str, format: str = "JSONL", sources: Sources | None = None,
              task: str = "") -> RecordingInfo:
        """Start recording; MCAP recordings also sample `sources` (the arm's state, wrench),
        and keep the stereo video when there is a camera. A `task` makes it an episode (MCAP
        only)."""
        if format not in SUFFIXES:
            raise InvalidArgumentError(f"unknown recording format {format!r}", reason="BAD_FORMAT")
        _check_task(task, format)
        path = self._path(name, format)
        with self._lock:
            if self._active is not None:
                raise FailedPreconditionError(f"already recording '{self._active.name}': stop it "
                                              "first", reason="RECORDING")
            if any(self._path(name, other).exists() for other in SUFFIXES):
                raise AlreadyExistsError(f"a recording named '{name}' exists: delete it or pick "
                                         "another name", reason="NAME_TAKEN")
            self._failure = None
            created, started = self._clock.time_ns(), self._clock.monotonic()
            partial = path.with_name(path.name + PARTIAL)
            # A writer that fails at once waits in _died for this lock: `made` is set by then.
            made: list[Recorder] = []

            def died(why: str) -> None:
                self._died(made[0], why)

            try:
                if format == "MCAP":
                    recorder: Recorder = McapRecorder(
                        partial, name, created, self._clock, sources or Sources(),
                        self.event_to_message, died, task, self._writer)
                else:
                    recorder = JsonlRecorder(partial, name, created, self._clock, died)
            except OSError as error:
                raise FailedPreconditionError(f"cannot write the recording: {error}",
                                              reason="RECORDING_FAILED") from error
            made.append(recorder)
            active = _Active(name, format, created, started, recorder)
            self._active = active
        return RecordingInfo(name, active.create_time_ns, 0.0, 0, format, task=task)

    @property
    def recording(self) -> bool:
        return self._active is not None

    def add(self, frame: str, delta_position: np.ndarray, delta_rotation: np.ndarray,
            target_position: np.ndarray) -> None:
        self._add(frame, delta_position, delta_rotation, target_position, None)

    def add_joints(self, delta_joints: np.ndarray, target_position: np.ndarray) -> None:
        self._add("JOINTS", np.zeros(3), np.eye(3), target_position, delta_joints)

    def _add(self, frame, delta_position, delta_rotation, target_position, delta_joints):
        with self._lock:
            active = self._active
            if active is None:
                return
            active.recorder.add(self._clock.monotonic() - active.started, frame,
                                delta_position, delta_rotation, target_position, delta_joints)

    def note_ack(self, ack) -> None:
        """An ack the server sent (a CommandAck): kept by an MCAP recording."""
        active = self._active
        if active is not None:
            active.recorder.ack(ack)

    def note_event(self, event) -> None:
        """One of the server's events (a DecisionEvent): kept by an MCAP recording."""
        active = self._active
        if active is not None:
            active.recorder.event(event)

    def _died(self, recorder: Recorder, why: str) -> None:
        """A recording's writer failed: the recording is over (StopRecording says why, and
        `on_failed` hears of it now)."""
        with self._lock:
            if self._active is None or self._active.recorder is not recorder:
                return  # stopped meanwhile: StopRecording answered the failure itself
            self._active = None
            self._failure = (recorder.name, why)
        on_failed = self.on_failed
        if on_failed is not None:
            on_failed(recorder.name, why)

    def stop(self, outcome: str = "UNSPECIFIED") -> RecordingInfo:
        """Save the recording; `outcome` (OUTCOMES) is how an episode went."""
        if outcome not in OUTCOMES:
            raise InvalidArgumentError(f"unknown episode outcome {outcome!r}: one of "
                                       f"{', '.join(OUTCOMES)}", reason="BAD_OUTCOME")
        with self._lock:
            active = self._active
            if active is None:
                failure, self._failure = self._failure, None
                if failure is not None:
                    raise FailedPreconditionError(
                        f"the recording '{failure[0]}' stopped by itself: "
                        f"{failure[1]}; nothing was saved",
                        reason="RECORDING_FAILED")
                raise FailedPreconditionError("not recording", reason="NOT_RECORDING")
            self._active = None
        path = self._path(active.name, active.format)
        recorder = active.recorder
        task = getattr(recorder, "task", "")
        if task:
            recorder.outcome = outcome
        try:
            recorder.finish()  # raises when the writing failed
            recorder.path.replace(path)
            _sync_directory(self.directory)
        except OSError as error:  # a full disk at the last write: nothing half-written stays
            recorder.path.unlink(missing_ok=True)
            raise FailedPreconditionError(f"the recording '{active.name}' could not be saved: "
                                          f"{error}", reason="RECORDING_FAILED") from error
        lost = recorder.dropped.get(INCREMENT, 0)
        return RecordingInfo(active.name, active.create_time_ns, recorder.duration_s,
                             recorder.command_count, active.format,
                             recording_mcap.incomplete(active.name, lost).message if lost else "",
                             task, outcome if task else "",
                             getattr(recorder, "video_frames", 0))

    def _recover(self, partial: Path) -> None:
        """A JSONL recording the server did not stop (it crashed, or was killed): what its file
        holds becomes the recording, a torn last line cut off. Left alone when its name is taken
        or its header is not whole."""
        name = partial.name.removesuffix(SUFFIXES["JSONL"] + PARTIAL)
        if not NAME_PATTERN.fullmatch(name) or any(
                self._path(name, format).exists() for format in SUFFIXES):
            log.warning("left %s as it is: not a recording's name, or the name is taken",
                        partial.name)
            return
        try:
            with open(partial, "r+b") as file:
                data = file.read()
                whole = data.rfind(b"\n") + 1
                if whole == 0:
                    log.warning("left %s as it is: its header is not whole", partial.name)
                    return
                if whole < len(data):
                    file.truncate(whole)
                file.flush()
                os.fsync(file.fileno())
            final = self._path(name)
            partial.replace(final)
            _sync_directory(self.directory)
            info = self.info(name)
        except (OSError, FailedPreconditionError, NotFoundError) as error:
            log.warning("cannot recover the recording in %s: %s", partial.name, error)
            return
        log.warning("recovered the recording '%s' that was not stopped (the server ended without "
                    "saving it): %d increments over %.3f s%s", name, info.command_count,
                    info.duration_s, f"; {info.error}" if info.error else "")

    def load(self, name: str) -> tuple[RecordingInfo, list[RecordedCommand]]:
        path, format = self._existing(name)
        _, created, commands = read_jsonl(path) if format == "JSONL" else read_mcap(path)
        return self._info(name, created, commands, format), commands

    def info(self, name: str) -> RecordingInfo:
        """What ListRecordings says of one (an MCAP file's summary only: cheap)."""
        path, format = self._existing(name)
        try:
            if format == "JSONL":
                _, created, commands, lost = _read_jsonl(path)
                info = self._info(name, created, commands, format)
                error = recording_mcap.incomplete(name, lost).message if lost else ""
                return RecordingInfo(info.name, info.create_time_ns, info.duration_s,
                                     info.command_count, format, error)
            meta = recording_mcap.read_summary(path)
            try:
                recording_mcap.check_complete(name, meta)
                error = ""
            except FailedPreconditionError as incomplete:
                error = incomplete.message
            counts = json.loads(meta.get("counts", "{}"))
            return RecordingInfo(name, int(meta["create_time_ns"]), float(meta["duration_s"]),
                                 int(meta["command_count"]), format, error,
                                 meta.get("task", ""), meta.get("outcome", ""),
                                 int(counts.get(recording_mcap.STEREO_VIDEO, 0)))
        except FailedPreconditionError as error:
            return RecordingInfo(name, 0, 0.0, 0, format, error.message)
        except (KeyError, ValueError) as error:
            return RecordingInfo(name, 0, 0.0, 0, format, f"bad metadata: {error}")

    def list(self) -> list[RecordingInfo]:
        names = sorted({path.stem for suffix in SUFFIXES.values()
                        for path in self.directory.glob(f"*{suffix}")})
        infos = []
        for name in names:
            try:
                infos.append(self.info(name))
            except (NotFoundError, InvalidArgumentError):
                continue  # deleted meanwhile, or a stray file whose name is not one of ours
        return infos

    def delete(self, name: str) -> None:
        path, _ = self._existing(name)
        path.unlink()

    @staticmethod
    def _info(name: str, created: int, commands: list[RecordedCommand],
              format: str = "JSONL") -> RecordingInfo:
        duration = commands[-1].offset_s - commands[0].offset_s if commands else 0.0
        return RecordingInfo(name, created, duration, len(commands), format)


def _check_task(task: str, format: str) -> None:
    if not task:
        return
    if format != "MCAP":
        raise InvalidArgumentError("a task makes the recording an episode, which is recorded as "
                                   "MCAP (format RECORDING_FORMAT_MCAP), not JSONL",
                                   reason="TASK_NEEDS_MCAP")
    if len(task) > MAX_TASK_CHARS or not task.isprintable() or not task.strip():
        raise InvalidArgumentError(
            f"a task is 1..{MAX_TASK_CHARS} printable characters, not only spaces (got "
            f"{len(task)} characters{'' if task.isprintable() else ', some not printable'})",
            reason="BAD_TASK")


def _sync_directory(directory: Path) -> None:
    """fsync a directory, so a rename in it survives a power cut."""
    descriptor = os.open(directory, os.O_RDONLY)
    try:
        os.fsync(descriptor)
    finally:
        os.close(descriptor)
