"""Our telerobot.v1 messages as Foxglove's own schemas (foxglove_schemas_protobuf), so Foxglove
or Lichtblick shows a recording or a live stream in its stock panels: the arm in the 3D panel
(/tf), the joint angles (/joint_states), the contact force as an arrow (/force/arrow), each
eye's images with its calibration, and an H.264 stream's side-by-side video
(/camera/stereo/video, CompressedVideo). Pure conversion: no grpc, no I/O.

Frames (Foxglove frame ids):

- ``base``: the robot base, DH frame 0 (also the simulation's world frame); the root.
- ``link1`` .. ``link6``: each link's body frame, as a parent chain (``base`` -> ``link1`` ->
  ... -> ``link6``), each child in its parent, so the 3D panel draws the arm as a kinematic
  chain (a line from each frame to its parent) and a joint's motion moves everything after it.
- ``flange`` (DH frame 6) in ``link6``; ``tool`` (the tool frame) in ``flange``.
- ``camera_left`` / ``camera_right`` in ``base``, where the calibration gives the eye's pose
  (OpenCV axes: x right, y down, z forward, which are also Foxglove's camera axes).
- ``camera_stereo``: the side-by-side video's frame id (both eyes in one picture, the left eye
  in the left half); no transform gives it a pose, as no single pinhole model describes the
  picture (each eye's calibration describes its own half).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
import pinocchio as pin
from foxglove_schemas_protobuf.ArrowPrimitive_pb2 import ArrowPrimitive
from foxglove_schemas_protobuf.CameraCalibration_pb2 import CameraCalibration
from foxglove_schemas_protobuf.Color_pb2 import Color
from foxglove_schemas_protobuf.CompressedImage_pb2 import CompressedImage
from foxglove_schemas_protobuf.CompressedVideo_pb2 import CompressedVideo
from foxglove_schemas_protobuf.FrameTransform_pb2 import FrameTransform
from foxglove_schemas_protobuf.FrameTransforms_pb2 import FrameTransforms
from foxglove_schemas_protobuf.JointState_pb2 import JointState
from foxglove_schemas_protobuf.JointStates_pb2 import JointStates
from foxglove_schemas_protobuf.Pose_pb2 import Pose as FoxglovePose
from foxglove_schemas_protobuf.Quaternion_pb2 import Quaternion
from foxglove_schemas_protobuf.SceneEntity_pb2 import SceneEntity
from foxglove_schemas_protobuf.SceneUpdate_pb2 import SceneUpdate
from foxglove_schemas_protobuf.Vector3_pb2 import Vector3
from google.protobuf.timestamp_pb2 import Timestamp

from domain.robot_model import names
from domain.robot_model.description import arm_description
from domain.robot_model.kinematics import ArmKinematics
from telerobot.v1 import stereo_camera_pb2 as sc_pb
from telerobot.v1 import types_pb2
from wire import convert
from wire.foxglove_video import STEREO_CAMERA_FRAME as STEREO_CAMERA_FRAME
from wire.foxglove_video import h264_is_keyframe as h264_is_keyframe
from wire.foxglove_video import stereo_video as stereo_video

TF = "/tf"
JOINT_STATES = "/joint_states"
FORCE_ARROW = "/force/arrow"
LEFT_IMAGE = "/camera/left/image"
RIGHT_IMAGE = "/camera/right/image"
LEFT_CALIBRATION = "/camera/left/calibration"
RIGHT_CALIBRATION = "/camera/right/calibration"
STEREO_VIDEO = "/camera/stereo/video"  # an H.264 stream's side-by-side frames
# Our own messages, next to Foxglove's, in recordings and the live view.
ROBOT_STATE = "/robot/state"  # telerobot.v1.RobotState
ROBOT_WRENCH = "/robot/wrench"  # telerobot.v1.Wrench, in tool axes
FOXGLOVE_TOPICS: dict[str, type] = {
    TF: FrameTransforms,
    JOINT_STATES: JointStates,
    FORCE_ARROW: SceneUpdate,
    LEFT_IMAGE: CompressedImage,
    RIGHT_IMAGE: CompressedImage,
    LEFT_CALIBRATION: CameraCalibration,
    RIGHT_CALIBRATION: CameraCalibration,
    STEREO_VIDEO: CompressedVideo,
}

BASE_FRAME = "base"
FLANGE_FRAME = "flange"
TOOL_FRAME = "tool"
LEFT_CAMERA_FRAME = "camera_left"
RIGHT_CAMERA_FRAME = "camera_right"

FORCE_ARROW_M_PER_N = 0.01  # arrow length per newton: 10 N draws 0.1 m
FORCE_ARROW_ENTITY = "tool_force"
_ARROW_HEAD_FRACTION = 0.25  # of the arrow's length, at most _ARROW_HEAD_MAX_M
_ARROW_HEAD_MAX_M = 0.03
_ARROW_SHAFT_DIAMETER_M = 0.006
_ARROW_HEAD_DIAMETER_M = 0.015
_ARROW_COLOR = Color(r=1.0, g=0.35, b=0.1, a=1.0)
_MIN_FORCE_N = 1e-9  # below this the force has no direction: the arrow is cleared


def _stamp(stamp_ns: int) -> Timestamp:
    stamp = Timestamp()
    stamp.FromNanoseconds(int(stamp_ns))
    return stamp


def _quaternion(rotation: np.ndarray) -> Quaternion:
    q = pin.Quaternion(np.asarray(rotation, float)).normalized()
    return Quaternion(x=float(q.x), y=float(q.y), z=float(q.z), w=float(q.w))


def _transform(parent: str, child: str, parent_T_child: pin.SE3, stamp: Timestamp
               ) -> FrameTransform:
    x, y, z = (float(v) for v in parent_T_child.translation)
    return FrameTransform(timestamp=stamp, parent_frame_id=parent, child_frame_id=child,
                          translation=Vector3(x=x, y=y, z=z),
                          rotation=_quaternion(parent_T_child.rotation))


def _pose_se3(pose: types_pb2.Pose) -> pin.SE3:
    return pin.SE3(convert.rotation_value(pose.rotation), convert.vector3_value(pose.position_m))


def camera_transforms(header: sc_pb.StereoHeader, stamp_ns: int) -> list[FrameTransform]:
    """``base`` -> each eye's frame, for the eyes whose calibration carries a pose."""
    stamp = _stamp(stamp_ns)
    return [_transform(BASE_FRAME, frame, _pose_se3(eye.camera_pose), stamp)
            for frame, eye in ((LEFT_CAMERA_FRAME, header.left),
                               (RIGHT_CAMERA_FRAME, header.right))
            if eye.HasField("camera_pose")]


class ArmTransforms:
    """The arm's frames at a joint configuration, as a Foxglove FrameTransforms (see the module
    docstring for the tree). Not thread-safe (one Pinocchio data): one per thread."""

    def __init__(self, kinematics: ArmKinematics | None = None) -> None:
        self.kinematics = kinematics or ArmKinematics()
        model = self.kinematics.model
        self.link_frames = _link_frames(model)
        self._links = [model.getFrameId(name) for name in self.link_frames]
        self._flange = self.kinematics.frame_id(names.FLANGE_SITE)
        self.joint_names = tuple(model.names[1:])
        self.cameras: list[FrameTransform] = []  # the eyes' frames, from set_cameras()

    def set_cameras(self, header: sc_pb.StereoHeader | None) -> None:
        """Include the eyes' frames from this calibration in every transforms() (None: none)."""
        self.cameras = [] if header is None else camera_transforms(header, 0)

    def transforms(self, joint_positions_rad: Sequence[float], stamp_ns: int,
                   flange_T_tool: pin.SE3 | None = None) -> FrameTransforms:
        """Every frame at ``joint_positions_rad`` (rad, six values), stamped ``stamp_ns``; the
        tool at ``flange_T_tool`` (default: the kinematics' own tool frame)."""
        q = np.asarray(joint_positions_rad, float)
        if q.shape != (self.kinematics.nq,):
            raise ValueError(f"need {self.kinematics.nq} joint positions, got {q.shape}")
        model, data = self.kinematics.model, self.kinematics.data
        pin.framesForwardKinematics(model, data, q)
        stamp = _stamp(stamp_ns)
        out = FrameTransforms()
        parent, world_T_parent = BASE_FRAME, pin.SE3.Identity()
        for name, frame in zip(self.link_frames, self._links, strict=True):
            world_T_link = data.oMf[frame]
            out.transforms.append(
                _transform(parent, name, world_T_parent.actInv(world_T_link), stamp))
            parent, world_T_parent = name, world_T_link
        out.transforms.append(_transform(
            parent, FLANGE_FRAME, world_T_parent.actInv(data.oMf[self._flange]), stamp))
        tool = self.kinematics.flange_T_tool if flange_T_tool is None else flange_T_tool
        out.transforms.append(_transform(FLANGE_FRAME, TOOL_FRAME, tool, stamp))
        for camera in self.cameras:
            moved = FrameTransform()
            moved.CopyFrom(camera)
            moved.timestamp.CopyFrom(stamp)
            out.transforms.append(moved)
        return out

    def state_transforms(self, state: types_pb2.RobotState) -> FrameTransforms:
        """transforms() of a RobotState: its joint angles at its sample time, and its tool frame
        (flange_pose⁻¹ tool_pose) when it carries both poses."""
        tool = None
        if state.HasField("flange_pose") and state.HasField("tool_pose"):
            tool = _pose_se3(state.flange_pose).actInv(_pose_se3(state.tool_pose))
        return self.transforms(state.joint_positions_rad, state.sample_time.ToNanoseconds(),
                               tool)


def _link_frames(model: pin.Model) -> tuple[str, ...]:
    """The body each joint moves (its first body frame), in joint order."""
    bodies: dict[int, str] = {}
    for frame in model.frames:
        if frame.type == pin.FrameType.BODY and frame.parentJoint > 0:
            bodies.setdefault(frame.parentJoint, frame.name)
    return tuple(bodies[joint] for joint in range(1, model.njoints))


def joint_states(state: types_pb2.RobotState,
                 joint_names: Sequence[str] | None = None) -> JointStates:
    """The state's joint angles (rad) and rates (rad/s), named as the arm's file names them
    (default: the selected arm's), at its sample time."""
    joint_names = joint_names or arm_description().joint_names
    if len(state.joint_positions_rad) != len(joint_names):
        raise ValueError(f"a RobotState has {len(joint_names)} joint positions, "
                         f"not {len(state.joint_positions_rad)}")
    rates = list(state.joint_velocities_rad_per_s)
    joints = []
    for i, name in enumerate(joint_names):
        joint = JointState(name=name, position=float(state.joint_positions_rad[i]))
        if len(rates) == len(joint_names):
            joint.velocity = float(rates[i])
        joints.append(joint)
    return JointStates(timestamp=state.sample_time, joints=joints)


def force_arrow(wrench: types_pb2.Wrench, stamp_ns: int, frame_id: str = TOOL_FRAME
                ) -> SceneUpdate:
    """The wrench's force as an arrow from ``frame_id``'s origin (the tool frame's: the wrench
    is in tool axes), pointing along the force, FORCE_ARROW_M_PER_N (0.01 m per newton) long.
    A force of (near) zero clears the arrow (an entity with no arrows). Plain float math: it
    runs once per wrench a recording or the live view takes (up to 1 kHz)."""
    fx, fy, fz = wrench.force_n.x, wrench.force_n.y, wrench.force_n.z
    if not all(math.isfinite(v) for v in (fx, fy, fz)):
        raise ValueError(f"the wrench's force is not finite: {[fx, fy, fz]}")
    entity = SceneEntity(timestamp=_stamp(stamp_ns), frame_id=frame_id, id=FORCE_ARROW_ENTITY,
                         frame_locked=True)
    magnitude = math.sqrt(fx * fx + fy * fy + fz * fz)
    if magnitude > _MIN_FORCE_N:
        length = FORCE_ARROW_M_PER_N * magnitude
        head = min(_ARROW_HEAD_FRACTION * length, _ARROW_HEAD_MAX_M)
        entity.arrows.append(ArrowPrimitive(
            pose=FoxglovePose(position=Vector3(x=0.0, y=0.0, z=0.0),
                              orientation=_x_onto(fx / magnitude, fy / magnitude,
                                                  fz / magnitude)),
            shaft_length=length - head, shaft_diameter=_ARROW_SHAFT_DIAMETER_M,
            head_length=head, head_diameter=_ARROW_HEAD_DIAMETER_M, color=_ARROW_COLOR))
    return SceneUpdate(entities=[entity])


def _x_onto(ux: float, uy: float, uz: float) -> Quaternion:
    """The shortest rotation taking +x onto the unit vector u (an arrow points along its
    pose's +x): the half-way quaternion (1 + x·u, x × u) normalized, x × u = (0, -uz, uy);
    for u = -x, half a turn about z."""
    w = 1.0 + ux
    if w < 1e-12:
        return Quaternion(x=0.0, y=0.0, z=1.0, w=0.0)
    norm = math.sqrt(w * w + uy * uy + uz * uz)
    return Quaternion(x=0.0, y=-uz / norm, z=uy / norm, w=w / norm)


_FORMATS = ((b"\xff\xd8\xff", "jpeg"), (b"\x89PNG\r\n\x1a\n", "png"))


def _image_format(data: bytes) -> str:
    for magic, name in _FORMATS:
        if data.startswith(magic):
            return name
    raise ValueError("a CompressedImage needs JPEG or PNG bytes; this stream's images are "
                     "neither (raw RGB8?): ask the camera for IMAGE_ENCODING_JPEG")


def camera_images(pair: sc_pb.StereoPair) -> tuple[CompressedImage, CompressedImage]:
    """Both eyes' images as they came (JPEG or PNG bytes, not re-encoded), stamped with their
    capture times, in the camera frames."""
    return tuple(
        CompressedImage(timestamp=stamp, frame_id=frame, data=data, format=_image_format(data))
        for stamp, frame, data in ((pair.left_capture_time, LEFT_CAMERA_FRAME, pair.left_image),
                                   (pair.right_capture_time, RIGHT_CAMERA_FRAME,
                                    pair.right_image)))


def _calibration(eye: sc_pb.CameraCalibration, frame: str, header: sc_pb.StereoHeader,
                 stamp: Timestamp) -> CameraCalibration:
    fx, fy, cx, cy = eye.fx_px, eye.fy_px, eye.cx_px, eye.cy_px
    distortion = list(eye.distortion)
    if len(distortion) > 8:
        raise ValueError(f"{frame}: {len(distortion)} distortion coefficients; Foxglove takes "
                         "at most 8 (rational_polynomial)")
    model = "plumb_bob" if len(distortion) <= 5 else "rational_polynomial"
    distortion += [0.0] * ((5 if model == "plumb_bob" else 8) - len(distortion))
    # Each eye has its own frame (its pose is in /tf), so P is K with no stereo offset (Tx = 0):
    # P projects points given in that eye's own frame. Our `projection` (base-frame points) is
    # P[:, :3] times the eye's pose inverted.
    return CameraCalibration(
        timestamp=stamp, frame_id=frame, width=header.width_px, height=header.height_px,
        distortion_model=model,
        D=distortion, K=[fx, 0.0, cx, 0.0, fy, cy, 0.0, 0.0, 1.0],
        R=[1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0],
        P=[fx, 0.0, cx, 0.0, 0.0, fy, cy, 0.0, 0.0, 0.0, 1.0, 0.0])


def camera_calibrations(header: sc_pb.StereoHeader, stamp_ns: int
                        ) -> tuple[CameraCalibration, CameraCalibration]:
    """Each eye's pinhole model (K, P, D, width, height) in its camera frame, stamped
    ``stamp_ns``. An eye without a calibration (fx 0) gets K[0] = 0, which Foxglove reads as
    uncalibrated."""
    stamp = _stamp(stamp_ns)
    return (_calibration(header.left, LEFT_CAMERA_FRAME, header, stamp),
            _calibration(header.right, RIGHT_CAMERA_FRAME, header, stamp))
