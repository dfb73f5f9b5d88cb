"""Recorded command sequences on disk: the DecisionServer's repeatability. No gRPC here.

A recording is a JSON-lines file (<name>.jsonl): a header line, then one line per applied
increment with its time offset from the first: a Cartesian one with its frame, ΔX and ΔM, or a
joint one (frame "JOINTS") with its Δθ; each with the tool target it led to (so a replay can be
checked against the original path). Or, when asked for, an MCAP file (<name>.mcap, see
recording_mcap) holding the same increments and, beside them, the acks, robot state, wrench and
events of the recording's time. A replay reads either. A file that cannot be read (truncated,
corrupt) is FailedPreconditionError (CORRUPT_RECORDING): the request was fine, the stored file is
not.
"""

from __future__ import annotations

import json
import re
import threading
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from services.decision_server import recording_mcap
from services.decision_server.recording_mcap import McapRecorder, Sources
from services.runtime.clock import SYSTEM_CLOCK, Clock
from wire.errors import (
    AlreadyExistsError,
    FailedPreconditionError,
    InvalidArgumentError,
    NotFoundError,
)

NAME_PATTERN = re.compile(r"[A-Za-z0-9_-]{1,64}")
SUFFIXES = {"JSONL": ".jsonl", "MCAP": ".mcap"}


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


# -- the JSONL format, whole files (the store and the converter) ------------------------------

def write_jsonl(path: Path, name: str, create_time_ns: int, commands) -> None:
    """All or nothing on disk: written beside, then renamed."""
    header = json.dumps({"name": name, "create_time_ns": create_time_ns})
    temporary = path.with_name(path.name + ".partial")
    temporary.write_text("\n".join([header, *(c.to_json() for c in commands)]) + "\n")
    temporary.replace(path)


def read_jsonl(path: Path) -> tuple[str, int, list[RecordedCommand]]:
    """(name in the header, create time, increments); FailedPreconditionError (CORRUPT_RECORDING)
    for a file that is not one."""
    try:
        header, *lines = path.read_text().splitlines()
        meta = json.loads(header)
        commands = [RecordedCommand.from_json(line) for line in lines if line]
        return str(meta.get("name", path.stem)), int(meta["create_time_ns"]), commands
    except (ValueError, KeyError, TypeError, AttributeError) as error:
        raise FailedPreconditionError(f"the recording file {path.name} cannot be read: "
                                      f"{type(error).__name__}: {error}",
                                      reason="CORRUPT_RECORDING") from error


def read_mcap(path: Path) -> tuple[str, int, list[RecordedCommand]]:
    contents = recording_mcap.read_commands(path, RecordedCommand)
    return contents.name, contents.create_time_ns, contents.commands


@dataclass
class _Active:
    name: str
    format: str
    create_time_ns: int
    started: float  # monotonic
    commands: list[RecordedCommand]  # JSONL: kept until stop; MCAP: written as they come
    recorder: McapRecorder | None = None
    count: int = 0
    first_offset: float | None = None
    last_offset: float = 0.0


class RecordingStore:
    """Recordings in one directory. One recording at a time. Thread-safe."""

    def __init__(self, directory: Path, clock: Clock = SYSTEM_CLOCK):
        self.directory = Path(directory)
        self._clock = clock
        self.directory.mkdir(parents=True, exist_ok=True)
        self._lock = threading.Lock()
        self._active: _Active | None = None
        self._failure: tuple[str, str] | None = None  # (name, why) of a recording that died
        # The servicer sets this: a DecisionEvent as the protobuf event the MCAP recordings
        # hold (None to leave one out). Without it, MCAP recordings hold no events.
        self.event_to_message: Callable[[object], object] | None = None
        # Told (name, why) when a recording stops by itself (the core raises an event).
        self.on_failed: Callable[[str, str], None] | None = None

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

    def start(self, name: str, format: str = "JSONL", sources: Sources | None = None
              ) -> RecordingInfo:
        """Start recording; MCAP recordings also sample `sources` (the arm's state, wrench)."""
        if format not in SUFFIXES:
            raise InvalidArgumentError(f"unknown recording format {format!r}", reason="BAD_FORMAT")
        path = self._path(name, format)
        with self._lock:
            if self._active is not None:
                raise FailedPreconditionError(f"already recording '{self._active.name}': stop it "
                                              "first", reason="RECORDING")
            if any(self._path(name, other).exists() for other in SUFFIXES):
                raise AlreadyExistsError(f"a recording named '{name}' exists: delete it or pick "
                                         "another name", reason="NAME_TAKEN")
            self._failure = None
            active = _Active(name, format, self._clock.time_ns(), self._clock.monotonic(), [])
            if format == "MCAP":
                try:
                    active.recorder = McapRecorder(
                        path.with_name(path.name + ".partial"), name, active.create_time_ns,
                        self._clock, sources or Sources(), self.event_to_message,
                        lambda why, active=active: self._died(active, why))
                except OSError as error:
                    raise FailedPreconditionError(f"cannot write the recording: {error}",
                                                  reason="RECORDING_FAILED") from error
            self._active = active
        return RecordingInfo(name, active.create_time_ns, 0.0, 0, format)

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
            command = RecordedCommand(
                self._clock.monotonic() - active.started, frame,
                np.array(delta_position, float), np.array(delta_rotation, float),
                np.array(target_position, float),
                None if delta_joints is None else np.array(delta_joints, float))
            active.count += 1
            if active.first_offset is None:
                active.first_offset = command.offset_s
            active.last_offset = command.offset_s
            if active.recorder is not None:
                active.recorder.increment(command)  # queued: written off this thread
            else:
                active.commands.append(command)

    def note_ack(self, ack) -> None:
        """An ack the server sent (a CommandAck): kept by an MCAP recording."""
        active = self._active
        if active is not None and active.recorder is not None:
            active.recorder.ack(ack)

    def note_event(self, event) -> None:
        """One of the server's events (a DecisionEvent): kept by an MCAP recording."""
        active = self._active
        if active is not None and active.recorder is not None:
            active.recorder.event(event)

    def _died(self, active: _Active, why: str) -> None:
        """An MCAP recording's writer failed: the recording is over (StopRecording says why,
        and `on_failed` hears of it now)."""
        with self._lock:
            if self._active is not active:
                return  # stopped meanwhile: StopRecording answered the failure itself
            self._active = None
            self._failure = (active.name, why)
        on_failed = self.on_failed
        if on_failed is not None:
            on_failed(active.name, why)

    def stop(self) -> RecordingInfo:
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
        try:
            if active.recorder is None:
                write_jsonl(path, active.name, active.create_time_ns, active.commands)
                commands = active.commands
            else:
                commands = active.recorder.finish()  # raises when the writing failed
                active.recorder.path.replace(path)
        except OSError as error:  # a full disk at the last write: nothing half-written stays
            path.with_name(path.name + ".partial").unlink(missing_ok=True)
            raise FailedPreconditionError(f"the recording '{active.name}' could not be saved: "
                                          f"{error}", reason="RECORDING_FAILED") from error
        return self._info(active.name, active.create_time_ns, commands, active.format)

    def load(self, name: str) -> tuple[RecordingInfo, list[RecordedCommand]]:
        path, format = self._existing(name)
        _, created, commands = read_jsonl(path) if format == "JSONL" else read_mcap(path)
        return self._info(name, created, commands, format), commands

    def info(self, name: str) -> RecordingInfo:
        """What ListRecordings says of one (an MCAP file's summary only: cheap)."""
        path, format = self._existing(name)
        try:
            if format == "JSONL":
                return self.load(name)[0]
            meta = recording_mcap.read_summary(path)
            return RecordingInfo(name, int(meta["create_time_ns"]), float(meta["duration_s"]),
                                 int(meta["command_count"]), format)
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
