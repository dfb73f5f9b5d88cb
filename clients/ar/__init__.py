"""The operator station's augmented reality (section IV-B of the full paper).

Domain modules (numpy and cv2 only, no transport):

* ``identification`` -- IdentifyCamera: each eye's projection from reference points, with the
  paper's affine (weak-perspective) model from four non-coplanar points or the full perspective
  model (normalized DLT) from six or more; projecting world points with either
* ``persistence``    -- the identification saved to, and loaded from, a JSON file
* ``model``          -- RobotModel: the local proxy that predicts the gripper from the commands
  sent and corrects itself on the server's moved events and state samples
* ``overlay``        -- the ball at the gripper in both eyes, and the side-by-side stereo frame

``adapters`` turns the StereoCamera and ProxyRobot protobuf messages into those (no channel).
"""

from clients.ar.identification import (
    CameraProjection,
    EyeIdentification,
    IdentificationError,
    ProjectionKind,
    StereoIdentification,
    frame_points,
    identify_affine,
    identify_camera,
    identify_dlt,
    identify_stereo,
    project_points,
    reprojection_errors,
)
from clients.ar.model import CorrectionMode, Frame, RobotModel, puma_forward_kinematics
from clients.ar.overlay import (
    BallStyle,
    SideBySideComposer,
    StereoOverlay,
    draw_ball,
    locate_ball,
    side_by_side,
)
from clients.ar.persistence import (
    IdentificationFileError,
    load_identification,
    load_if_present,
    save_identification,
)

__all__ = [
    "BallStyle",
    "CameraProjection",
    "CorrectionMode",
    "EyeIdentification",
    "Frame",
    "IdentificationError",
    "IdentificationFileError",
    "ProjectionKind",
    "RobotModel",
    "SideBySideComposer",
    "StereoIdentification",
    "StereoOverlay",
    "draw_ball",
    "frame_points",
    "identify_affine",
    "identify_camera",
    "identify_dlt",
    "identify_stereo",
    "load_identification",
    "load_if_present",
    "locate_ball",
    "project_points",
    "puma_forward_kinematics",
    "reprojection_errors",
    "save_identification",
    "side_by_side",
]
