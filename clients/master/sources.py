"""Where the master arm's joint readings come from.

A source answers ``read(time_s) -> JointReading`` with the master's joint angles at that time
(the paper's position sensors) and, if the source knows it, the clutch button's state. Three:

- `SimulatedHand` (the default): an operator's hand that follows a Cartesian path (a function
  of time giving the hand pose); the master's own IK (damped least squares from the previous
  angles) gives the joint angles the encoders would read. `circle_path` and `line_path` make
  paths.
- `ScriptedSource`: a file of timed joint angles or hand poses (format below), replayed with
  linear interpolation (poses: positions linearly, rotations along the geodesic, then IK).
- `SpaceMouseSource`: a 3Dconnexion SpaceMouse through the optional ``pyspacemouse`` package,
  as a rate device: its deflection moves the simulated hand, whose joint angles are read.

Script files
------------

JSON (``.json``)::

    {"format": "telerobot-master-script", "version": 1, "kind": "joints",
     "samples": [{"t": 0.0, "q": [0, 0, 0, 0, 0, 0]},
                 {"t": 0.5, "q": [0.1, 0, 0, 0, 0, 0], "clutch": true}]}

    {"format": "telerobot-master-script", "version": 1, "kind": "hand_poses",
     "samples": [{"t": 0.0, "position_m": [0.3, 0, 0.4], "euler_xyz_rad": [0, 0, 0]}, ...]}

CSV (any other suffix): a header naming the columns, then one sample per line; ``#`` starts a
comment line. ``t,q1,q2,q3,q4,q5,q6`` is a joint script, ``t,x,y,z,ax,ay,az`` a hand-pose
script (metres; XYZ Euler angles in radians, M = Rx(ax) Ry(ay) Rz(az)); an optional last
column ``clutch`` (0/1) holds the clutch button.

``t`` is in seconds from the start of the script and strictly increasing. Before the first
sample the first one holds, after the last the last one. The clutch is a button: it keeps the
state of the latest sample at or before ``t`` (omitted: released).
"""

from __future__ import annotations

import csv
import json
import math
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Protocol

import numpy as np
import pinocchio as pin

from clients.master.model import MasterModel
from domain.geometry import from_euler_xyz

SCRIPT_FORMAT = "telerobot-master-script"
SCRIPT_VERSION = 1
JOINT_COLUMNS = ("t", "q1", "q2", "q3", "q4", "q5", "q6")
POSE_COLUMNS = ("t", "x", "y", "z", "ax", "ay", "az")

Path_ = Callable[[float], pin.SE3]  # a hand path: time (s) -> hand pose in the master's base


@dataclass(frozen=True)
class JointReading:
    """The master's joint angles at `time_s`; `clutch` is the button's state if the source
    knows it (None: it does not)."""

    time_s: float
    q: np.ndarray
    clutch: bool | None = None


class JointSource(Protocol):
    def read(self, time_s: float) -> JointReading: ...


# -- paths ------------------------------------------------------------------------------------

def interpolate_pose(start: pin.SE3, end: pin.SE3, fraction: float) -> pin.SE3:
    """The pose `fraction` of the way from `start` to `end`: position on the line, rotation
    on the geodesic (both expressed in base axes)."""
    rotation = start.rotation @ pin.exp3(fraction * pin.log3(start.rotation.T @ end.rotation))
    return pin.SE3(rotation, start.translation + fraction * (end.translation - start.translation))


def line_path(start: pin.SE3, delta_position, delta_rotation: np.ndarray | None = None,
              duration_s: float = 1.0) -> Path_:
    """From `start`, move by `delta_position` (base axes) and turn by `delta_rotation` (base
    axes: M_end = ΔM·M_start) over `duration_s`, at constant speed; hold after."""
    rotation = np.eye(3) if delta_rotation is None else np.asarray(delta_rotation, float)
    end = pin.SE3(rotation @ start.rotation,
                  start.translation + np.asarray(delta_position, float))

    def path(t: float) -> pin.SE3:
        return interpolate_pose(start, end, min(max(t / duration_s, 0.0), 1.0))

    return path


def circle_path(center: pin.SE3, radius_m: float = 0.03, period_s: float = 4.0,
                plane: str = "yz", wobble_rad: float = 0.1) -> Path_:
    """The hand draws a circle of `radius_m` in the base `plane` through `center`'s position,
    starting at the centre and easing onto the circle over the first quarter period, while
    its orientation rocks about the base x axis by up to `wobble_rad`."""
    axes = {"x": 0, "y": 1, "z": 2}
    if len(plane) != 2 or any(a not in axes for a in plane):
        raise ValueError(f"plane names two base axes, like 'yz', not {plane!r}")
    first, second = (np.eye(3)[axes[a]] for a in plane)

    def path(t: float) -> pin.SE3:
        ease = min(max(t / (period_s / 4), 0.0), 1.0)
        phase = 2 * math.pi * t / period_s
        offset = ease * radius_m * (math.cos(phase) * first + math.sin(phase) * second
                                    - first)
        rock = pin.exp3(np.array([ease * wobble_rad * math.sin(phase), 0.0, 0.0]))
        return pin.SE3(rock @ center.rotation, center.translation + offset)

    return path


# -- the simulated operator's hand ------------------------------------------------------------

class SimulatedHand:
    """A hand moving the master's handle along `path`; reads the joint angles the master's
    encoders would show (IK from the previous reading). Default path: `circle_path` about the
    hand's rest pose. ``last_ik`` keeps the last IK result, whose errors say how well the arm
    could follow (a path outside the master's reach stops at its limits)."""

    def __init__(self, model: MasterModel | None = None, path: Path_ | None = None,
                 q0: np.ndarray | None = None):
        self.model = model or MasterModel()
        self.q = self.model.home_q if q0 is None else np.asarray(q0, dtype=float).copy()
        self.path = path or circle_path(self.model.hand_pose(self.q))
        self.last_ik = None

    def target(self, time_s: float) -> pin.SE3:
        return self.path(time_s)

    def read(self, time_s: float) -> JointReading:
        self.last_ik = self.model.solve_ik(self.path(time_s), self.q)
        self.q = self.last_ik.q
        return JointReading(time_s, self.q.copy())


# -- scripts ----------------------------------------------------------------------------------

@dataclass(frozen=True)
class Script:
    """A parsed script: sample times, values (joint angles (n, 6), or hand poses as
    positions (n, 3) plus rotations (n, 3, 3)) and clutch states."""

    kind: str  # "joints" or "hand_poses"
    times: np.ndarray
    joints: np.ndarray | None
    positions: np.ndarray | None
    rotations: np.ndarray | None
    clutch: np.ndarray  # bool, (n,)

    @property
    def duration_s(self) -> float:
        return float(self.times[-1] - self.times[0])


def _floats(values, length: int, what: str) -> np.ndarray:
    array = np.asarray(values, dtype=float)
    if array.shape != (length,) or not np.all(np.isfinite(array)):
        raise ValueError(f"{what} needs {length} finite numbers, got {values!r}")
    return array


def _build_script(kind: str, times: list, values: list, clutch: list, where: str) -> Script:
    if not times:
        raise ValueError(f"{where}: the script has no samples")
    times_array = np.asarray(times, dtype=float)
    if not np.all(np.isfinite(times_array)) or np.any(np.diff(times_array) <= 0):
        raise ValueError(f"{where}: sample times must be finite and strictly increasing")
    clutch_array = np.asarray(clutch, dtype=bool)
    if kind == "joints":
        return Script(kind, times_array, np.asarray(values), None, None, clutch_array)
    positions = np.asarray([v[0] for v in values])
    rotations = np.asarray([v[1] for v in values])
    return Script(kind, times_array, None, positions, rotations, clutch_array)


def _load_json(path: Path) -> Script:
    document = json.loads(path.read_text())
    if document.get("format") != SCRIPT_FORMAT or document.get("version") != SCRIPT_VERSION:
        raise ValueError(f"{path}: not a {SCRIPT_FORMAT} version {SCRIPT_VERSION} file")
    kind = document.get("kind")
    if kind not in ("joints", "hand_poses"):
        raise ValueError(f"{path}: kind must be 'joints' or 'hand_poses', not {kind!r}")
    times, values, clutch = [], [], []
    for index, sample in enumerate(document.get("samples", [])):
        where = f"{path}: sample {index}"
        times.append(float(sample["t"]))
        clutch.append(bool(sample.get("clutch", False)))
        if kind == "joints":
            values.append(_floats(sample["q"], 6, f"{where} q"))
        else:
            values.append((_floats(sample["position_m"], 3, f"{where} position_m"),
                           from_euler_xyz(_floats(sample["euler_xyz_rad"], 3,
                                                  f"{where} euler_xyz_rad"))))
    return _build_script(kind, times, values, clutch, str(path))


def _load_csv(path: Path) -> Script:
    lines = [line for line in path.read_text().splitlines()
             if line.strip() and not line.lstrip().startswith("#")]
    rows = list(csv.reader(lines))
    if not rows:
        raise ValueError(f"{path}: empty script")
    header = tuple(name.strip() for name in rows[0])
    has_clutch = header[-1:] == ("clutch",)
    columns = header[:-1] if has_clutch else header
    if columns == JOINT_COLUMNS:
        kind = "joints"
    elif columns == POSE_COLUMNS:
        kind = "hand_poses"
    else:
        raise ValueError(f"{path}: the header must be {','.join(JOINT_COLUMNS)} or "
                         f"{','.join(POSE_COLUMNS)} (then optionally ,clutch), not "
                         f"{','.join(header)}")
    times, values, clutch = [], [], []
    for number, row in enumerate(rows[1:], start=2):
        numbers = _floats([cell.strip() for cell in row], len(header),
                          f"{path}: data row {number - 1}")
        times.append(numbers[0])
        clutch.append(bool(numbers[-1]) if has_clutch else False)
        if kind == "joints":
            values.append(numbers[1:7])
        else:
            values.append((numbers[1:4], from_euler_xyz(numbers[4:7])))
    return _build_script(kind, times, values, clutch, str(path))


def load_script(path: str | Path) -> Script:
    """Parse a script file (JSON by suffix, else CSV); ValueError saying what is wrong."""
    path = Path(path)
    return _load_json(path) if path.suffix.lower() == ".json" else _load_csv(path)


class ScriptedSource:
    """Replays a script: ``read(t)`` interpolates at time t on the script's own clock (its
    ``t`` column); hand poses go through the master's IK, seeded with the previous answer."""

    def __init__(self, script: Script | str | Path, model: MasterModel | None = None,
                 q0: np.ndarray | None = None):
        self.script = script if isinstance(script, Script) else load_script(script)
        self.model = model
        self._hand = None
        if self.script.kind == "hand_poses":
            self.model = model or MasterModel()
            self._hand = SimulatedHand(self.model, self.pose_at, q0)

    def _segment(self, time_s: float) -> tuple[int, float]:
        """(i, f): t lies between samples i and i + 1, fraction f of the way."""
        times = self.script.times
        t = min(max(time_s, times[0]), times[-1])
        i = int(np.clip(np.searchsorted(times, t, side="right") - 1, 0, len(times) - 1))
        if i == len(times) - 1:
            return i, 0.0
        return i, float((t - times[i]) / (times[i + 1] - times[i]))

    def pose_at(self, time_s: float) -> pin.SE3:
        """The scripted hand pose at `time_s` (hand-pose scripts only)."""
        s = self.script
        i, f = self._segment(time_s)
        start = pin.SE3(s.rotations[i], s.positions[i])
        if f == 0.0:
            return start
        return interpolate_pose(start, pin.SE3(s.rotations[i + 1], s.positions[i + 1]), f)

    def clutch_at(self, time_s: float) -> bool:
        i, _ = self._segment(time_s)
        return bool(self.script.clutch[i])

    def read(self, time_s: float) -> JointReading:
        clutch = self.clutch_at(time_s)
        if self._hand is not None:
            return JointReading(time_s, self._hand.read(time_s).q, clutch)
        i, f = self._segment(time_s)
        joints = self.script.joints
        q = joints[i] if f == 0.0 else joints[i] + f * (joints[i + 1] - joints[i])
        return JointReading(time_s, np.array(q, dtype=float), clutch)


# -- the SpaceMouse ---------------------------------------------------------------------------

class SpaceMouseUnavailable(ImportError):
    """The optional ``pyspacemouse`` package is not installed, or no device was found."""


def _import_pyspacemouse():
    try:
        import pyspacemouse
    except ImportError as error:
        raise SpaceMouseUnavailable(
            "the SpaceMouse source needs the optional package pyspacemouse, which is not "
            "installed: `pip install pyspacemouse` (it needs the hidapi library, e.g. "
            "`apt-get install libhidapi-dev`, and read access to /dev/hidraw*). The telerobot "
            "package does not depend on it.") from error
    return pyspacemouse


class SpaceMouseSource:
    """A 3Dconnexion SpaceMouse as a rate device: each axis's deflection (-1..1, after a
    `deadband`) moves the simulated hand at up to `max_speed_m_s` and turns it at up to
    `max_rate_rad_s` about the base axes (x, y, z; roll, pitch, yaw), and the master's IK gives
    the joint angles. Button `clutch_button` (default the first) is the clutch.

    ``pyspacemouse`` is imported only here, and only when no `device` is given; pass any object
    with ``read()`` returning a state with ``x, y, z, roll, pitch, yaw`` and ``buttons`` (or
    ``button``) to use another driver."""

    def __init__(self, model: MasterModel | None = None, device=None, *,
                 max_speed_m_s: float = 0.1, max_rate_rad_s: float = 0.5,
                 deadband: float = 0.05, clutch_button: int = 0, q0: np.ndarray | None = None):
        self.model = model or MasterModel()
        self._owns_device = device is None
        if device is None:
            pyspacemouse = _import_pyspacemouse()
            device = pyspacemouse.open()
            if not device:
                raise SpaceMouseUnavailable("pyspacemouse found no SpaceMouse: is it plugged "
                                            "in, and is /dev/hidraw* readable?")
            if not hasattr(device, "read"):  # older pyspacemouse: module-level read()
                device = pyspacemouse
        self.device = device
        self.max_speed_m_s, self.max_rate_rad_s = max_speed_m_s, max_rate_rad_s
        self.deadband, self.clutch_button = deadband, clutch_button
        self.q = self.model.home_q if q0 is None else np.asarray(q0, dtype=float).copy()
        self.pose = self.model.hand_pose(self.q)
        self._last_time: float | None = None

    def _axis(self, value: float) -> float:
        value = max(-1.0, min(1.0, float(value)))
        if abs(value) <= self.deadband:
            return 0.0
        return math.copysign((abs(value) - self.deadband) / (1.0 - self.deadband), value)

    def read(self, time_s: float | None = None) -> JointReading:
        time_s = time.monotonic() if time_s is None else time_s
        state = self.device.read()
        dt = 0.0 if self._last_time is None else max(0.0, time_s - self._last_time)
        self._last_time = time_s
        velocity = self.max_speed_m_s * np.array([self._axis(state.x), self._axis(state.y),
                                                  self._axis(state.z)])
        rate = self.max_rate_rad_s * np.array([self._axis(state.roll), self._axis(state.pitch),
                                               self._axis(state.yaw)])
        target = pin.SE3(pin.exp3(rate * dt) @ self.pose.rotation,
                         self.pose.translation + velocity * dt)
        result = self.model.solve_ik(target, self.q)
        self.q = result.q
        self.pose = self.model.hand_pose(self.q)  # where the arm could actually go
        buttons = getattr(state, "buttons", None)
        if buttons is None:
            buttons = getattr(state, "button", ())
        clutch = bool(buttons[self.clutch_button]) if len(buttons) > self.clutch_button else None
        return JointReading(time_s, self.q.copy(), clutch)

    def close(self) -> None:
        if self._owns_device and hasattr(self.device, "close"):
            self.device.close()
