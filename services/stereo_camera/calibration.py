"""Per-eye pinhole calibration: intrinsics, pose, 3x4 projection; from MuJoCo or a JSON file.

Conventions (those of the proto's CameraCalibration and of OpenCV):

- camera frame: x right, y down, z forward (out of the lens);
- pixel coordinates: (0, 0) is the centre of the top-left pixel, so a centred principal point
  of a W x H image is ((W - 1) / 2, (H - 1) / 2);
- pose: the camera frame in the robot base frame (position, and a rotation whose columns are
  the camera's x, y, z axes in base coordinates);
- projection P = K [Rᵀ | -Rᵀ p]: base-frame points (metres) to homogeneous pixels.

Calibration file (``--calibration FILE`` for device and file sources), JSON:

    {
      "width_px": 640, "height_px": 480,   # the image size the numbers refer to; optional
                                           # (default: the source's); rescaled to the source's
      "baseline_m": 0.12,                  # optional; default |right.position - left.position|
                                           # when both positions are given, else 0
      "left": {
        "fx_px": 700.0, "fy_px": 700.0, "cx_px": 319.5, "cy_px": 239.5,   # required
        "distortion": [k1, k2, p1, p2, k3],   # optional, OpenCV order; default none
        "position_m": [x, y, z],              # optional, camera origin in the base frame
        "rotation": [r00, r01, ..., r22],     # optional (needs position_m), row-major 3x3,
                                              # columns = camera x, y, z in the base frame
        "projection": [p00, ..., p23]         # optional, row-major 3x4, e.g. measured from
                                              # fiducial points; overrides K [Rᵀ | -Rᵀ p]
      },
      "right": { ... the same keys ... }
    }

Without a file the calibration is unknown: the header then carries zeros (fx_px = 0 means
"unknown"), no projection and no pose.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from domain.geometry import rotation_matrix
from telerobot.v1 import stereo_camera_pb2, types_pb2
from wire import convert
from wire.errors import InvalidArgumentError

if TYPE_CHECKING:
    import mujoco

# MuJoCo cameras look along -z with y up; OpenCV's look along +z with y down.
MUJOCO_TO_OPENCV = np.diag([1.0, -1.0, -1.0])


def _pixel_scale(sx: float, sy: float) -> np.ndarray:
    """Maps pixel coordinates of an image to those of the image resized by (sx, sy), with
    pixel centres at integers (u' = (u + 0.5) sx - 0.5), as cv2.resize samples."""
    return np.array([[sx, 0.0, 0.5 * sx - 0.5], [0.0, sy, 0.5 * sy - 0.5], [0.0, 0.0, 1.0]])


@dataclass(frozen=True)
class EyeCalibration:
    """One eye's pinhole model (see the module docstring for conventions)."""

    fx_px: float
    fy_px: float
    cx_px: float
    cy_px: float
    distortion: tuple[float, ...] = ()
    position_m: np.ndarray | None = None  # (3,) camera origin in the base frame
    rotation: np.ndarray | None = None  # (3, 3) columns = camera axes in the base frame
    explicit_projection: np.ndarray | None = field(default=None)  # (3, 4), overrides K[R|t]

    @property
    def intrinsics(self) -> np.ndarray:
        """K (3x3)."""
        return np.array([[self.fx_px, 0.0, self.cx_px], [0.0, self.fy_px, self.cy_px],
                         [0.0, 0.0, 1.0]])

    @property
    def projection(self) -> np.ndarray | None:
        """P (3x4) from base-frame points to pixels; None when the pose is unknown."""
        if self.explicit_projection is not None:
            return self.explicit_projection
        if self.position_m is None or self.rotation is None:
            return None
        world_to_camera = self.rotation.T
        extrinsics = np.hstack([world_to_camera, (-world_to_camera @ self.position_m)[:, None]])
        return self.intrinsics @ extrinsics

    def project(self, point_m) -> np.ndarray:
        """Pixel (u, v) of a base-frame point (no distortion)."""
        projection = self.projection
        if projection is None:
            raise ValueError("this eye has no pose, so base-frame points cannot be projected")
        u, v, w = projection @ np.append(np.asarray(point_m, float), 1.0)
        return np.array([u / w, v / w])

    def scaled(self, sx: float, sy: float) -> EyeCalibration:
        """The calibration of the image resized by (sx, sy)."""
        scale = _pixel_scale(sx, sy)
        k = scale @ self.intrinsics
        explicit = None if self.explicit_projection is None else scale @ self.explicit_projection
        return replace(self, fx_px=float(k[0, 0]), fy_px=float(k[1, 1]), cx_px=float(k[0, 2]),
                       cy_px=float(k[1, 2]), explicit_projection=explicit)

    def to_proto(self) -> stereo_camera_pb2.CameraCalibration:
        message = stereo_camera_pb2.CameraCalibration(
            fx_px=self.fx_px, fy_px=self.fy_px, cx_px=self.cx_px, cy_px=self.cy_px,
            distortion=list(self.distortion))
        projection = self.projection
        if projection is not None:
            message.projection.extend(projection.reshape(12).tolist())
        if self.position_m is not None and self.rotation is not None:
            message.camera_pose.CopyFrom(types_pb2.Pose(
                position_m=convert.vector3_to_proto(self.position_m),
                rotation=convert.rotation_to_proto(self.rotation)))
        return message


@dataclass(frozen=True)
class StereoCalibration:
    """Both eyes (None: unknown) and the baseline, for images of width_px x height_px."""

    width_px: int
    height_px: int
    left: EyeCalibration | None = None
    right: EyeCalibration | None = None
    baseline_m: float = 0.0

    def for_size(self, width_px: int, height_px: int) -> StereoCalibration:
        """The same cameras, for images resized to width_px x height_px."""
        if (width_px, height_px) == (self.width_px, self.height_px):
            return self
        sx, sy = width_px / self.width_px, height_px / self.height_px
        return replace(self, width_px=width_px, height_px=height_px,
                       left=self.left and self.left.scaled(sx, sy),
                       right=self.right and self.right.scaled(sx, sy))

    def eye_protos(self) -> tuple[stereo_camera_pb2.CameraCalibration, ...]:
        """(left, right) for the header; all zeros for an unknown eye."""
        return tuple(eye.to_proto() if eye else stereo_camera_pb2.CameraCalibration()
                     for eye in (self.left, self.right))


def unknown_calibration(width_px: int, height_px: int) -> StereoCalibration:
    return StereoCalibration(width_px, height_px)


# -- MuJoCo --------------------------------------------------------------------------------------


def mujoco_eye(model: mujoco.MjModel, data: mujoco.MjData, camera: int, width_px: int,
               height_px: int) -> EyeCalibration:
    """The pinhole model of a MuJoCo camera rendered at width_px x height_px.

    Needs data's kinematics (mj_kinematics or mj_forward). MuJoCo's fovy is the full vertical
    field of view and its pixels are square, so fx = fy = (H / 2) / tan(fovy / 2); the optical
    axis goes through the image centre."""
    fovy = math.radians(float(model.cam_fovy[camera]))
    focal = 0.5 * height_px / math.tan(0.5 * fovy)
    rotation = data.cam_xmat[camera].reshape(3, 3) @ MUJOCO_TO_OPENCV
    return EyeCalibration(fx_px=focal, fy_px=focal, cx_px=0.5 * (width_px - 1),
                          cy_px=0.5 * (height_px - 1), position_m=data.cam_xpos[camera].copy(),
                          rotation=rotation)


def mujoco_stereo(model: mujoco.MjModel, data: mujoco.MjData, left: int, right: int,
                  width_px: int, height_px: int) -> StereoCalibration:
    left_eye = mujoco_eye(model, data, left, width_px, height_px)
    right_eye = mujoco_eye(model, data, right, width_px, height_px)
    baseline = float(np.linalg.norm(right_eye.position_m - left_eye.position_m))
    return StereoCalibration(width_px, height_px, left_eye, right_eye, baseline)


# -- JSON ----------------------------------------------------------------------------------------


def load_calibration(path: Path | str, width_px: int, height_px: int) -> StereoCalibration:
    """The calibration file at `path` (format in the module docstring), for images of
    width_px x height_px. ValueError naming the file and the problem."""
    path = Path(path)
    try:
        document = json.loads(path.read_text())
    except (OSError, ValueError) as exc:
        raise ValueError(f"cannot read the calibration file {path}: {exc}") from None
    try:
        return parse_calibration(document, width_px, height_px)
    except (InvalidArgumentError, ValueError, TypeError, KeyError) as exc:
        detail = exc.message if isinstance(exc, InvalidArgumentError) else str(exc)
        raise ValueError(f"the calibration file {path} is not valid: {detail}") from None


def parse_calibration(document: dict, width_px: int, height_px: int) -> StereoCalibration:
    """A calibration from the parsed JSON document (see the module docstring)."""
    if not isinstance(document, dict):
        raise ValueError("the document must be a JSON object")
    base_width = int(document.get("width_px", width_px))
    base_height = int(document.get("height_px", height_px))
    if base_width <= 0 or base_height <= 0:
        raise ValueError("width_px and height_px must be positive")
    eyes = [_parse_eye(document[name], name) for name in ("left", "right")]
    if "baseline_m" in document:
        baseline = _finite(document["baseline_m"], "baseline_m")
    elif eyes[0].position_m is not None and eyes[1].position_m is not None:
        baseline = float(np.linalg.norm(eyes[1].position_m - eyes[0].position_m))
    else:
        baseline = 0.0
    calibration = StereoCalibration(base_width, base_height, eyes[0], eyes[1], baseline)
    return calibration.for_size(width_px, height_px)


def _finite(value, what: str) -> float:
    number = float(value)
    if not math.isfinite(number):
        raise ValueError(f"{what} must be a finite number, got {value!r}")
    return number


def _parse_eye(entry: dict, name: str) -> EyeCalibration:
    if not isinstance(entry, dict):
        raise ValueError(f"{name} must be an object")
    values = {key: _finite(entry[key], f"{name}.{key}")
              for key in ("fx_px", "fy_px", "cx_px", "cy_px")}
    if values["fx_px"] <= 0 or values["fy_px"] <= 0:
        raise ValueError(f"{name}.fx_px and {name}.fy_px must be positive")
    distortion = tuple(_finite(v, f"{name}.distortion") for v in entry.get("distortion", ()))
    position = rotation = projection = None
    if "position_m" in entry:
        position = np.array([_finite(v, f"{name}.position_m") for v in entry["position_m"]])
        if position.shape != (3,):
            raise ValueError(f"{name}.position_m needs 3 values")
        rotation = rotation_matrix(np.asarray(entry.get("rotation", []), float).reshape(-1),
                                   f"{name}.rotation")
    elif "rotation" in entry:
        raise ValueError(f"{name}.rotation needs {name}.position_m")
    if "projection" in entry:
        projection = np.array([_finite(v, f"{name}.projection") for v in entry["projection"]])
        if projection.shape != (12,):
            raise ValueError(f"{name}.projection needs 12 values (3x4, row-major)")
        projection = projection.reshape(3, 4)
    return EyeCalibration(**values, distortion=distortion, position_m=position,
                          rotation=rotation, explicit_projection=projection)
