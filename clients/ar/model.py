"""RobotModel: the operator station's local proxy of the arm (section IV-B of the full paper).

It "locates the future position of the robot gripper based on the current command": every
Cartesian increment the operator sends is applied to the model's own predicted tool pose at once,
so the AR ball leads the video (which shows the arm a network delay and a servo lag behind).
The server's word corrects it:

- `acknowledge(command_id, target_tool_pose)`: the ProxyRobot's reply to a move carries the
  target it accepted (reduced near a singularity, solved by IK). The model re-anchors on it and
  re-applies only the commands sent after that one that are not acknowledged yet. A refused
  command is taken back with `reject(command_id)`.
- `correct(tool_pose)`: a *moved* event (the arm reached its target) or a state sample taken
  at rest. This is the paper's OnMove update ("mechanical and mathematical round off errors").
  The pose is taken to include every command sent so far, so pending commands are dropped. A
  command that was still in flight (its reply not back yet) and that the arm had not reached is
  restored by its acknowledgement, which re-anchors the model on the server's target. Known
  race: a moved event for an earlier target delivered after a newer command's reply pulls the
  model back until the next moved event (the messages carry no command id to tell); BLEND
  softens the jump. Two modes:

  * SNAP (default, the paper's): the prediction becomes the server's pose. One moved event
    removes any accumulated bias, but the ball jumps by the error.
  * BLEND with gain g in (0, 1]: the prediction moves the fraction g of the way (position
    linearly, rotation along the geodesic). The error shrinks by (1 - g) per correction: after
    k corrections it is (1 - g)^k of what it was, so the ball glides instead of jumping and
    converges while the arm rests (state samples arrive at tens of Hz, so g = 0.3 settles in a
    fraction of a second). g = 1 is SNAP.

  Samples taken while the arm is still moving lag the command (they are the past, the model is
  the future): do not feed them to `correct` (the protobuf adapter skips them).

Increments follow the ProxyRobot contract (ReferenceFrame in types.proto, eq. 1):
BASE translates along the base axes and rotates about the tool point in base axes
(R⁺ = ΔM R, p⁺ = p + ΔX); TOOL is tool⁺ = tool · (ΔM, ΔX); WRIST is flange⁺ = flange · (ΔM, ΔX)
with the tool following rigidly (needs `flange_to_tool`).

Poses are 4x4 homogeneous matrices (a pin.SE3 is accepted wherever a pose is taken). Thread-safe:
commands come from the operator's loop, corrections from an event stream's thread.
"""

from __future__ import annotations

import enum
import threading
from collections.abc import Callable

import numpy as np

from clients.ar.pose_history import PoseHistory


class Frame(enum.StrEnum):
    """The frame a Cartesian increment is expressed in (types.proto ReferenceFrame)."""

    BASE = "BASE"
    TOOL = "TOOL"
    WRIST = "WRIST"


class CorrectionMode(enum.StrEnum):
    SNAP = "snap"
    BLEND = "blend"


ForwardKinematics = Callable[[np.ndarray], object]  # joint angles (rad) -> tool pose


def as_pose(pose) -> np.ndarray:
    """A 4x4 float matrix from a 4x4 array, a pin.SE3 (or anything with `.homogeneous`), or a
    (rotation 3x3, position 3) pair."""
    if hasattr(pose, "homogeneous"):
        matrix = np.array(pose.homogeneous, dtype=float)
    elif isinstance(pose, tuple) and len(pose) == 2:
        matrix = np.eye(4)
        matrix[:3, :3] = np.asarray(pose[0], float)
        matrix[:3, 3] = np.asarray(pose[1], float)
    else:
        matrix = np.array(pose, dtype=float)
    if matrix.shape != (4, 4) or not np.isfinite(matrix).all():
        raise ValueError(f"a pose is a finite 4x4 homogeneous matrix, got {matrix.shape}")
    return matrix


def make_pose(rotation=None, position_m=None) -> np.ndarray:
    pose = np.eye(4)
    if rotation is not None:
        pose[:3, :3] = np.asarray(rotation, float)
    if position_m is not None:
        pose[:3, 3] = np.asarray(position_m, float)
    return pose


def rotation_log(rotation: np.ndarray) -> np.ndarray:
    """The rotation vector (axis * angle, rad) of a rotation matrix."""
    skew = np.array([rotation[2, 1] - rotation[1, 2], rotation[0, 2] - rotation[2, 0],
                     rotation[1, 0] - rotation[0, 1]])  # 2 sin(angle) axis
    cos = (np.trace(rotation) - 1.0) / 2.0
    sin = 0.5 * float(np.linalg.norm(skew))
    angle = float(np.arctan2(sin, cos))
    if angle < 1e-6:
        return 0.5 * skew
    if angle < 3.0:
        return angle / (2.0 * sin) * skew
    # near pi the skew part vanishes: the axis is in the symmetric part, axis axisᵀ =
    # ((R + Rᵀ) / 2 - cos I) / (1 - cos); the skew part still gives its sign
    outer = (0.5 * (rotation + rotation.T) - cos * np.eye(3)) / (1.0 - cos)
    column = int(np.argmax(np.diag(outer)))
    axis = outer[:, column] / np.sqrt(outer[column, column])
    if axis @ skew < 0:
        axis = -axis
    return angle * axis


def rotation_exp(vector) -> np.ndarray:
    """The rotation matrix of a rotation vector (Rodrigues)."""
    vector = np.asarray(vector, float)
    angle = float(np.linalg.norm(vector))
    if angle < 1e-12:
        return np.eye(3)
    k = vector / angle
    skew = np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])
    return np.eye(3) + np.sin(angle) * skew + (1.0 - np.cos(angle)) * skew @ skew


def pose_error(a, b) -> tuple[float, float]:
    """(position distance in metres, rotation angle in radians) between two poses."""
    a, b = as_pose(a), as_pose(b)
    distance = float(np.linalg.norm(a[:3, 3] - b[:3, 3]))
    angle = float(np.linalg.norm(rotation_log(a[:3, :3].T @ b[:3, :3])))
    return distance, angle


def apply_increment(tool_pose, delta_position_m, delta_rotation=None,
                    frame: Frame | str = Frame.BASE, flange_to_tool=None) -> np.ndarray:
    """The tool pose after the Cartesian increment (ΔX, ΔM) in `frame` (see the module
    docstring), as the ProxyRobot applies it to its target."""
    tool = as_pose(tool_pose)
    delta = make_pose(np.eye(3) if delta_rotation is None else delta_rotation,
                      delta_position_m)
    frame = Frame(frame)
    if frame is Frame.TOOL:
        return tool @ delta
    if frame is Frame.WRIST:
        offset = np.eye(4) if flange_to_tool is None else as_pose(flange_to_tool)
        return tool @ np.linalg.inv(offset) @ delta @ offset
    return make_pose(delta[:3, :3] @ tool[:3, :3], tool[:3, 3] + delta[:3, 3])


def blend_pose(a, b, gain: float) -> np.ndarray:
    """The pose the fraction `gain` of the way from a to b (position linear, rotation along the
    geodesic)."""
    a, b = as_pose(a), as_pose(b)
    rotation = a[:3, :3] @ rotation_exp(gain * rotation_log(a[:3, :3].T @ b[:3, :3]))
    return make_pose(rotation, a[:3, 3] + gain * (b[:3, 3] - a[:3, 3]))


class RobotModel:
    """The predicted tool pose: the last server-anchored pose plus the commands sent since."""

    def __init__(self, tool_pose, mode: CorrectionMode | str = CorrectionMode.SNAP,
                 gain: float = 1.0, flange_to_tool=None,
                 forward_kinematics: ForwardKinematics | None = None):
        """`tool_pose`: where the tool is now (from GetState). `gain` in (0, 1] is used in BLEND
        mode. `forward_kinematics(q)` maps joint angles to the tool pose, for
        `correct_joints` (see `puma_forward_kinematics`)."""
        self._mode = CorrectionMode(mode)
        if not 0.0 < gain <= 1.0:
            raise ValueError(f"the blend gain must be in (0, 1], got {gain}")
        self._gain = 1.0 if self._mode is CorrectionMode.SNAP else float(gain)
        self._flange_to_tool = None if flange_to_tool is None else as_pose(flange_to_tool)
        self._fk = forward_kinematics
        self._lock = threading.Lock()
        self._anchor = as_pose(tool_pose)
        self._pending: list[tuple[int, np.ndarray, np.ndarray, Frame]] = []
        self._last_id = 0
        self._last_acknowledged = 0
        self._prediction = self._anchor.copy()
        self.corrections = 0  # how many corrections were applied
        self.measured = PoseHistory()  # the station's timed tool poses, for the video

    @property
    def mode(self) -> CorrectionMode:
        return self._mode

    @property
    def gain(self) -> float:
        return self._gain

    @property
    def tool_pose(self) -> np.ndarray:
        """The predicted tool pose (4x4, a copy)."""
        with self._lock:
            return self._prediction.copy()

    @property
    def tool_point(self) -> np.ndarray:
        """The predicted tool point (the gripper) in the base frame, metres: where the AR ball
        goes."""
        with self._lock:
            return self._prediction[:3, 3].copy()

    def observe(self, time_ns: int, tool_pose) -> None:
        """The station measured the tool at `tool_pose` at `time_ns` (its clock): kept for
        `tool_point_at`, without changing the prediction."""
        self.measured.add(time_ns, as_pose(tool_pose)[:3, 3])

    def tool_point_at(self, time_ns: int) -> np.ndarray:
        """Where the tool was at `time_ns` (a video frame's capture time), from the station's
        measurements around it; the prediction when none is near."""
        point = self.measured.at(time_ns)
        return self.tool_point if point is None else point

    @property
    def pending(self) -> int:
        """Commands sent and neither acknowledged nor covered by a correction yet."""
        with self._lock:
            return len(self._pending)

    def command(self, delta_position_m, delta_rotation=None,
                frame: Frame | str = Frame.BASE) -> int:
        """Predict the effect of a Cartesian increment about to be sent; returns its id for
        `acknowledge`."""
        delta_position = np.asarray(delta_position_m, float).reshape(3)
        delta_rotation = np.eye(3) if delta_rotation is None else np.asarray(delta_rotation,
                                                                             float)
        if not (np.isfinite(delta_position).all() and np.isfinite(delta_rotation).all()):
            raise ValueError("the increment must be finite")
        frame = Frame(frame)
        with self._lock:
            self._last_id += 1
            command_id = self._last_id
            self._pending.append((command_id, delta_position, delta_rotation, frame))
            self._prediction = self._apply(self._prediction, delta_position, delta_rotation,
                                           frame)
            return command_id

    def acknowledge(self, command_id: int, target_tool_pose) -> None:
        """The server accepted command `command_id` with this target tool pose: re-anchor there
        and re-apply the later commands still pending. An acknowledgement older than one
        already applied is ignored."""
        target = as_pose(target_tool_pose)
        with self._lock:
            if command_id <= self._last_acknowledged:
                return
            self._last_acknowledged = command_id
            self._pending = [entry for entry in self._pending if entry[0] > command_id]
            self._anchor = target
            self._replay()

    def reject(self, command_id: int) -> None:
        """The server refused command `command_id` (out of range, near a singularity, no
        control lock...): forget its predicted effect."""
        with self._lock:
            remaining = [entry for entry in self._pending if entry[0] != command_id]
            if len(remaining) != len(self._pending):
                self._pending = remaining
                self._replay()

    def correct(self, tool_pose) -> None:
        """The arm is at rest at this tool pose (a moved event, or a state sample at rest): snap
        or blend towards it (see the module docstring). Drops pending commands."""
        measured = as_pose(tool_pose)
        with self._lock:
            self._anchor = blend_pose(self._prediction, measured, self._gain)
            self._pending.clear()
            self._prediction = self._anchor.copy()
            self.corrections += 1

    def correct_joints(self, joint_positions_rad) -> None:
        """As `correct`, from the joint angles the server reports (the paper sends the angles):
        needs `forward_kinematics`."""
        if self._fk is None:
            raise ValueError("this RobotModel has no forward kinematics: give one "
                             "(puma_forward_kinematics()) or correct with a tool pose")
        self.correct(self._fk(np.asarray(joint_positions_rad, float)))

    def reset(self, tool_pose) -> None:
        """Forget everything: the tool is at `tool_pose` (after a reconnect or an e-stop)."""
        with self._lock:
            self._anchor = as_pose(tool_pose)
            self._pending.clear()
            self._last_acknowledged = self._last_id
            self._prediction = self._anchor.copy()

    def _apply(self, pose, delta_position, delta_rotation, frame) -> np.ndarray:
        return apply_increment(pose, delta_position, delta_rotation, frame,
                               self._flange_to_tool)

    def _replay(self) -> None:
        prediction = self._anchor.copy()
        for _, delta_position, delta_rotation, frame in self._pending:
            prediction = self._apply(prediction, delta_position, delta_rotation, frame)
        self._prediction = prediction


def puma_forward_kinematics(flange_to_tool=None) -> ForwardKinematics:
    """q -> tool pose (4x4) of the simulated PUMA 560 (domain.robot_model), with the default
    tool or `flange_to_tool` (4x4 or pin.SE3). Not thread-safe: one per thread."""
    import pinocchio as pin

    from domain.robot_model.kinematics import ArmKinematics

    kinematics = ArmKinematics()
    if flange_to_tool is not None:
        offset = as_pose(flange_to_tool)
        kinematics.flange_T_tool = pin.SE3(offset[:3, :3], offset[:3, 3])

    def tool_pose(q: np.ndarray) -> np.ndarray:
        return np.array(kinematics.tool_pose(np.asarray(q, float)).homogeneous)

    return tool_pose
