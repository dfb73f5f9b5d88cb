"""The AR chain on the simulated work cell: identify the MuJoCo scene cameras, predict the tool,
and the ball lands on the rendered peg tip.

The pair is rendered by the StereoCamera's own sim source (160x120, no shadows) at a known joint
configuration. The reference points' pixels come from the stream header's projection (the MuJoCo
camera model), rounded to whole pixels as an operator's clicks would be. The scene's visible
corners (table top, fixture) lie on two planes 4 cm apart, while the tool works up to 45 cm
above them: identified from those alone, the projection extrapolates the half-pixel clicks to
about 8 px at the tool. So four more reference points span the tool's volume: the peg tip itself
at four calibration poses of the arm (world positions from the arm's kinematics), the arm
serving as its own fiducial.
"""

from __future__ import annotations

import itertools

import mujoco
import numpy as np
import pytest

import services.stereo_camera  # noqa: F401  (chooses MUJOCO_GL=egl before mujoco loads)
from clients.ar.adapters import projections_from_header
from clients.ar.identification import frame_points, identify_affine, identify_stereo
from clients.ar.model import RobotModel, puma_forward_kinematics
from clients.ar.overlay import BallStyle, StereoOverlay
from domain.robot_model import workspace as ws
from domain.robot_model.loader import load_mujoco_model, mujoco_ids
from domain.robot_model.puma560 import HOME_Q
from services.stereo_camera.calibration import mujoco_eye
from services.stereo_camera.encoding import ImageFormat
from services.stereo_camera.servicer import header_proto
from services.stereo_camera.sim import SimSource
from telerobot.v1 import stereo_camera_pb2 as pb

W, H = 160, 120
Q = HOME_Q + np.array([0.25, 0.12, -0.15, 0.4, 0.3, 0.6])  # the tool tilted, off to the side
CALIBRATION_POSES = [HOME_Q + np.array(offset) for offset in (
    (0.0, 0.0, 0.0, 0.0, 0.0, 0.0), (-0.3, 0.15, -0.1, 0.0, 0.2, 0.0),
    (0.35, -0.1, 0.2, 0.0, -0.2, 0.0), (0.0, 0.25, 0.1, 0.0, -0.3, 0.0))]
STYLE = BallStyle(radius_m=0.02, fill_rgb=(255, 0, 255), outline_rgb=(255, 255, 255))


def _scene_corners() -> np.ndarray:
    """Corners the cameras see: the fixture's top, the bottom of its front face, and three
    corners of the table top (the fourth is out of view at this size)."""
    fx, fy = ws.FIXTURE_CENTER_XY
    half = ws.FIXTURE_HALF_WIDTH
    top = ws.TABLE_TOP_Z
    tx, ty = ws.TABLE_CENTER_XY
    hx, hy = ws.TABLE_HALF_SIZE_XY
    fixture_top = [(fx + sx * half, fy + sy * half, top + ws.FIXTURE_HEIGHT)
                   for sx, sy in itertools.product((-1, 1), repeat=2)]
    fixture_front = [(fx + half, fy - half, top), (fx + half, fy + half, top)]
    table = [(tx - hx, ty - hy, top), (tx - hx, ty + hy, top), (tx + hx, ty - hy, top)]
    return np.array(fixture_top + fixture_front + table)


@pytest.fixture(scope="module")
def scene():
    """The rendered pair at Q, the stream header, and the MuJoCo truth (tool tip, peg masks)."""
    source = SimSource(lambda: Q.copy(), W, H, shadows=False)
    source.open()
    try:
        left, right = source.grab(0)
    finally:
        source.close()
    header = header_proto(source.geometry, ImageFormat(W, H, pb.IMAGE_ENCODING_RAW_RGB8, 90),
                          pb.TRANSFER_MODE_DOUBLE_BUFFER_CONCURRENT)

    model = load_mujoco_model()
    ids = mujoco_ids(model)
    data = mujoco.MjData(model)
    data.qpos[ids.qpos] = Q
    mujoco.mj_kinematics(model, data)
    mujoco.mj_camlight(model, data)
    peg = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_GEOM, "peg")
    renderer = mujoco.Renderer(model, H, W)
    renderer.enable_segmentation_rendering()
    masks = []
    try:
        for camera in (ids.left_camera, ids.right_camera):
            renderer.update_scene(data, camera=camera)
            segmentation = renderer.render()
            masks.append((segmentation[..., 0] == peg)
                         & (segmentation[..., 1] == mujoco.mjtObj.mjOBJ_GEOM))
    finally:
        renderer.close()
    truth = [mujoco_eye(model, data, camera, W, H) for camera in (ids.left_camera,
                                                                  ids.right_camera)]
    tool_tip = data.site_xpos[ids.tool_site].copy()
    tool_axis = data.site_xmat[ids.tool_site].reshape(3, 3)[:, 2].copy()
    return dict(images=(left.image, right.image), header=header, truth=truth, masks=masks,
                tool_tip=tool_tip, tool_axis=tool_axis)


def test_the_header_carries_the_mujoco_camera_model(scene):
    points = _scene_corners()
    for projection, eye in zip(projections_from_header(scene["header"]), scene["truth"],
                               strict=True):
        np.testing.assert_allclose(projection.project(points),
                                   np.array([eye.project(p) for p in points]), atol=1e-9)


def test_identified_cameras_put_the_ball_on_the_rendered_tool_tip(scene):
    header_left, header_right = projections_from_header(scene["header"])
    fk = puma_forward_kinematics()
    references = np.vstack([_scene_corners(), [fk(q)[:3, 3] for q in CALIBRATION_POSES]])
    clicked_left = np.round(header_left.project(references))  # whole pixels, as clicked
    clicked_right = np.round(header_right.project(references))
    assert np.all((clicked_left >= 0) & (clicked_left < [W, H]))
    assert np.all((clicked_right >= 0) & (clicked_right < [W, H]))
    identification = identify_stereo(references, clicked_left, clicked_right, W, H,
                                     source=scene["header"].source)
    assert identification.left.rms_error_px < 0.5 and identification.right.rms_error_px < 0.5

    # the local model: at home, then the server's moved event with the joint angles Q
    model = RobotModel(fk(HOME_Q), forward_kinematics=fk)
    model.correct_joints(Q)
    np.testing.assert_allclose(model.tool_point, scene["tool_tip"], atol=1e-9)  # Pinocchio
    # and MuJoCo agree on the tool

    overlay = StereoOverlay.from_identification(identification, STYLE)
    left, right, balls = overlay.draw(*scene["images"], model.tool_point)
    for name, image, original, ball, eye, mask in zip(
            ("left", "right"), (left, right), scene["images"], (balls.left, balls.right),
            scene["truth"], scene["masks"], strict=True):
        truth = eye.project(scene["tool_tip"])
        assert ball is not None and ball.inside
        assert np.linalg.norm(ball.centre_px - truth) < 1.5, name  # measured: 0.3 px or less
        # the ball is in the image where it should be: the pixels drawn over (fill, outline,
        # antialiasing) are centred there
        vs, us = np.nonzero(np.any(image != original, axis=2))
        assert len(us) > 10
        assert np.linalg.norm([us.mean() - truth[0], vs.mean() - truth[1]]) < 1.5, name
        # and the rendered peg ends there: its silhouette reaches the ball centre, and its far
        # end along the peg's image direction is at the ball centre
        vs, us = np.nonzero(mask)
        peg = np.column_stack([us, vs]).astype(float)
        assert len(peg) > 10, f"the peg is not visible in the {name} eye"
        assert np.min(np.linalg.norm(peg - ball.centre_px, axis=1)) < 1.5, name
        back = eye.project(scene["tool_tip"] - 0.05 * scene["tool_axis"])
        direction = (truth - back) / np.linalg.norm(truth - back)
        assert abs(np.max((peg - ball.centre_px) @ direction)) < 1.5, name


def test_the_papers_affine_model_is_too_coarse_for_the_sim_rig(scene):
    """The rig stands about 1 m from the fixture with a 45 degree field of view: far from weak
    perspective. The paper's 20 cm frame on the fixture, identified exactly, still misplaces
    the tool by pixels even at 160x120; the perspective model is the one to use here."""
    header_left, _ = projections_from_header(scene["header"])
    origin = np.array([ws.FIXTURE_CENTER_XY[0] - ws.FIXTURE_HALF_WIDTH,
                       ws.FIXTURE_CENTER_XY[1] - ws.FIXTURE_HALF_WIDTH,
                       ws.TABLE_TOP_Z + ws.FIXTURE_HEIGHT])
    frame = frame_points(origin, 0.20)
    affine = identify_affine(frame, header_left.project(frame))
    error = np.linalg.norm(affine.project(scene["tool_tip"])
                           - header_left.project(scene["tool_tip"]))
    assert error > 2.0
