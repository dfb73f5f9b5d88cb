"""Recorded command sequences on disk: the DecisionServer's repeatability. No gRPC here.

A recording is a JSON-lines file: a header line, then one line per applied increment with its
time offset from the first: a Cartesian one with its frame, ΔX and ΔM, or a joint one
(frame "JOINTS") with its Δθ; each with the tool target it led to (so a replay can be checked
against the original path).
"""

from __future__ import annotations

import json
import re
import threading
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from services.runtime.clock import SYSTEM_CLOCK, Clock
from services.runtime.errors import AlreadyExists, FailedPrecondition, InvalidArgument, NotFound

NAME_PATTERN = re.compile(r"[A-Za-z0-9_-]{1,64}")


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


class RecordingStore:
    """Recordings in one directory. One recording at a time. Thread-safe."""

    def __init__(self, directory: Path, clock: Clock = SYSTEM_CLOCK):
        self.directory = Path(directory)
        self._clock = clock
        self.directory.mkdir(parents=True, exist_ok=True)
        self._lock = threading.Lock()
        self._active: tuple[str, int, float, list[RecordedCommand]] | None = None

    def _path(self, name: str) -> Path:
        if not NAME_PATTERN.fullmatch(name or ""):
            raise InvalidArgument("a recording name is 1 to 64 of A-Z a-z 0-9 _ -",
                                  reason="BAD_NAME")
        return self.directory / f"{name}.jsonl"

    def start(self, name: str) -> RecordingInfo:
        path = self._path(name)
        with self._lock:
            if self._active is not None:
                raise FailedPrecondition(f"already recording '{self._active[0]}': stop it first",
                                         reason="RECORDING")
            if path.exists():
                raise AlreadyExists(f"a recording named '{name}' exists: delete it or pick "
                                    "another name", reason="NAME_TAKEN")
            self._active = (name, self._clock.time_ns(), self._clock.monotonic(), [])
        return RecordingInfo(name, self._active[1], 0.0, 0)

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
            if self._active is None:
                return
            _, _, started, commands = self._active
            commands.append(RecordedCommand(
                self._clock.monotonic() - started, frame, np.asarray(delta_position, float),
                np.asarray(delta_rotation, float), np.asarray(target_position, float),
                None if delta_joints is None else np.asarray(delta_joints, float)))

    def stop(self) -> RecordingInfo:
        with self._lock:
            if self._active is None:
                raise FailedPrecondition("not recording", reason="NOT_RECORDING")
            name, created, _, commands = self._active
            self._active = None
        info = self._info(name, created, commands)
        header = json.dumps({"name": name, "create_time_ns": created})
        path = self._path(name)
        temporary = path.with_suffix(".partial")
        temporary.write_text("\n".join([header, *(c.to_json() for c in commands)]) + "\n")
        temporary.replace(path)  # all or nothing on disk
        return info

    def load(self, name: str) -> tuple[RecordingInfo, list[RecordedCommand]]:
        path = self._path(name)
        if not path.exists():
            raise NotFound(f"no recording named '{name}'", reason="NO_RECORDING")
        header, *lines = path.read_text().splitlines()
        created = json.loads(header)["create_time_ns"]
        commands = [RecordedCommand.from_json(line) for line in lines if line]
        return self._info(name, created, commands), commands

    def list(self) -> list[RecordingInfo]:
        return [self.load(path.stem)[0] for path in sorted(self.directory.glob("*.jsonl"))]

    def delete(self, name: str) -> None:
        path = self._path(name)
        if not path.exists():
            raise NotFound(f"no recording named '{name}'", reason="NO_RECORDING")
        path.unlink()

    @staticmethod
    def _info(name: str, created: int, commands: list[RecordedCommand]) -> RecordingInfo:
        duration = commands[-1].offset_s - commands[0].offset_s if commands else 0.0
        return RecordingInfo(name, created, duration, len(commands))
