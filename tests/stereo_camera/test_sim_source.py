"""The simulated rig: MuJoCo renders the work cell's two cameras at joint positions fed by an
in-process callable (the service reads them from the world process instead). Small images keep
software rendering quick."""

from __future__ import annotations

import argparse
import math
import uuid

import grpc
import mujoco
import numpy as np
import pytest

from domain.robot_model import workspace as ws
from services.stereo_camera.client import decode_pair
from services.stereo_camera.config import add_source_arguments, source_from_args
from services.stereo_camera.render_scale import FLOOR, LADDER, WINDOW
from services.stereo_camera.sim import SimSource, WorldJoints, home_joints
from telerobot.v1 import stereo_camera_pb2 as pb
from tests.stereo_camera.conftest import error_code, psnr, start_camera
from wire.errors import UnavailableError

W, H = 160, 120
# On the top face of the fixture (blue), beside the hole.
FIXTURE_TOP = np.array([ws.FIXTURE_CENTER_XY[0], ws.FIXTURE_CENTER_XY[1] + 0.0365,
                        ws.TABLE_TOP_Z + ws.FIXTURE_HEIGHT])


class Arm:
    """Joint positions as the world would give them; tests move the arm by setting `q`."""

    def __init__(self):
        self.q = home_joints()

    def __call__(self) -> np.ndarray:
        return self.q.copy()


@pytest.fixture(scope="module")
def rig():
    arm = Arm()
    camera = start_camera(SimSource(arm, W, H))
    yield camera, arm
    camera.close()


def _snapshot(camera):
    reply = camera.snapshot()  # PNG: exactly what was rendered
    return reply.header, reply.pair, decode_pair(reply.header, reply.pair)


def test_the_header_describes_the_mujoco_rig_in_opencv_convention(rig):
    camera, _ = rig
    header = camera.stub.GetStreamInfo(pb.GetStreamInfoRequest(), timeout=10).header
    assert header.source == "sim" and (header.width_px, header.height_px) == (W, H)
    focal = (H / 2) / math.tan(math.radians(ws.CAMERA_FOVY_DEG) / 2)
    for eye in (header.left, header.right):
        assert (eye.fx_px, eye.fy_px) == pytest.approx((focal, focal))
        assert (eye.cx_px, eye.cy_px) == pytest.approx(((W - 1) / 2, (H - 1) / 2))
        rotation = np.array(eye.camera_pose.rotation.row_major).reshape(3, 3)
        position = np.array([eye.camera_pose.position_m.x, eye.camera_pose.position_m.y,
                             eye.camera_pose.position_m.z])
        x_axis, y_axis, z_axis = rotation.T
        to_target = np.subtract(ws.CAMERA_TARGET, position)
        assert z_axis @ to_target / np.linalg.norm(to_target) > 0.99  # z looks at the scene
        assert y_axis[2] < 0  # y points down
        assert np.linalg.det(rotation) == pytest.approx(1.0)
    assert header.baseline_m == pytest.approx(ws.STEREO_BASELINE)
    left_x = header.left.camera_pose.position_m
    right_x = header.right.camera_pose.position_m
    baseline = np.array([right_x.x - left_x.x, right_x.y - left_x.y, right_x.z - left_x.z])
    assert baseline @ np.array(header.left.camera_pose.rotation.row_major).reshape(3, 3)[:, 0] \
        == pytest.approx(ws.STEREO_BASELINE)  # the right eye sits along the left's +x


def _project(eye: pb.CameraCalibration, point) -> np.ndarray:
    u, v, w = np.array(eye.projection).reshape(3, 4) @ np.append(point, 1.0)
    return np.array([u / w, v / w])


def test_a_plausible_pair_whose_eyes_differ_by_the_baseline_disparity(rig):
    camera, _ = rig
    header, pair, (left, right) = _snapshot(camera)
    assert left.std() > 20 and right.std() > 20  # a scene, not a blank frame
    assert not np.array_equal(left, right)
    assert pair.eye_skew.ToNanoseconds() == 0  # one state, two virtual shutters
    # the header's projections put the fixture's top on blue pixels in both eyes
    u_left = _project(header.left, FIXTURE_TOP)
    u_right = _project(header.right, FIXTURE_TOP)
    for image, (u, v) in ((left, u_left), (right, u_right)):
        red, green, blue = image[round(v), round(u)].astype(int)
        assert blue > red + 30 and blue > green + 20, (red, green, blue)  # not floor or table
    assert u_left[1] == pytest.approx(u_right[1])  # rectified: same row
    predicted = u_left[0] - u_right[0]  # f * baseline / depth, about 18 px here
    assert predicted > 10
    # block matching along the row finds the same disparity in the rendered images
    row, column = round(u_left[1]), round(u_left[0])
    patch = left[row - 6:row + 7, column - 10:column + 11].astype(float)
    costs = [np.sum((right[row - 6:row + 7, column - d - 10:column - d + 11] - patch) ** 2)
             for d in range(0, 40)]
    assert int(np.argmin(costs)) == pytest.approx(predicted, abs=1.5)


def test_it_renders_the_live_joint_positions(rig):
    camera, arm = rig
    _, _, (before, _) = _snapshot(camera)
    home = arm.q.copy()
    arm.q = home + np.array([0.5, 0.0, 0.0, 0.0, 0.0, 0.0])  # turn the waist
    try:
        _, _, (turned, _) = _snapshot(camera)
    finally:
        arm.q = home
    _, _, (back, _) = _snapshot(camera)
    changed = np.abs(turned.astype(int) - before).max(axis=2) > 30
    assert changed.mean() > 0.02  # the arm moved in the picture
    assert psnr(back, before) > 40  # and the same pose renders the same picture


def test_streams_carry_sim_pairs_in_both_modes(rig):
    camera, _ = rig
    for mode in (pb.TRANSFER_MODE_SINGLE_BUFFER_SERIALIZED,
                 pb.TRANSFER_MODE_DOUBLE_BUFFER_CONCURRENT):
        messages = camera.stream(2, transfer_mode=mode, encoding=pb.IMAGE_ENCODING_JPEG,
                                 width_px=W // 2, height_px=H // 2)
        header = messages[0].header
        assert header.left.fx_px == pytest.approx(
            (H / 4) / math.tan(math.radians(ws.CAMERA_FOVY_DEG) / 2))
        for message in messages[1:]:
            left, right = decode_pair(header, message.pair)
            assert left.shape == (H // 2, W // 2, 3) and left.std() > 20


def test_without_a_world_pairs_are_unavailable_saying_so(serve):
    joints = WorldJoints(f"telerobot_test_absent_{uuid.uuid4().hex[:8]}")
    with pytest.raises(UnavailableError, match="no world is running"):
        joints()
    camera = serve(SimSource(joints, 64, 48))
    code, details = error_code(lambda: camera.snapshot())
    assert code is grpc.StatusCode.UNAVAILABLE and "no world is running" in details
    call = camera.stub.StreamPairs(pb.StreamPairsRequest(), timeout=10)
    assert next(call).HasField("header")  # the header needs no world
    with pytest.raises(grpc.RpcError) as error:
        next(call)
    assert error.value.code() is grpc.StatusCode.UNAVAILABLE
    assert "no world is running" in error.value.details()


def test_the_defaults_render_without_shadows_or_multisampling():
    """What reaches the papers' 17 fps at 640x480 on software rendering (sim.py's docstring)."""
    parser = argparse.ArgumentParser()
    add_source_arguments(parser)
    args = parser.parse_args(["--sim-joints", "home"])
    assert (args.sim_shadows, args.sim_shadow_map, args.sim_multisample) == (False, 1024, 0)
    args = parser.parse_args(["--sim-joints", "home", "--width", "64", "--height", "48",
                              "--sim-shadows", "on", "--sim-shadow-map", "256",
                              "--sim-multisample", "2"])
    source = source_from_args(args).source
    source.open()
    try:
        quality = source._model.vis.quality
        assert (quality.shadowsize, quality.offsamples) == (256, 2)
        assert source._renderer(source.render_scale).scene.flags[mujoco.mjtRndFlag.mjRND_SHADOW]
    finally:
        source.close()


def _render(arm, **options) -> np.ndarray:
    source = SimSource(arm, W, H, **options)
    source.open()
    try:
        return source.grab(0)[0].image
    finally:
        source.close()


def test_shadows_darken_the_table_under_the_arm():
    arm = Arm()
    plain, shadowed = _render(arm), _render(arm, shadows=True, shadow_map_px=512)
    darker = plain.astype(int).sum(axis=2) - shadowed.astype(int).sum(axis=2) > 60
    assert darker.mean() > 0.005  # the arm's shadow falls on the table and the fixture


def _blue_centroid(image: np.ndarray) -> np.ndarray:
    """Mean pixel (u, v) of the fixture's blue top."""
    red, green, blue = (image[..., k].astype(int) for k in range(3))
    v, u = np.nonzero((blue > red + 30) & (blue > green + 20))
    return np.array([u.mean(), v.mean()])


def test_a_pair_rendered_small_streams_at_full_size_with_the_same_geometry():
    """A camera short of CPU renders fewer pixels (render_scale.py); the stream scales the
    picture back, so the calibration and the AR overlay hold and only detail is lost."""
    arm = Arm()
    full = _render(arm)
    half = SimSource(arm, W, H, render_scale=0.5)
    half.open()
    try:
        left, _ = half.grab(0)
        assert left.image.shape == (H // 2, W // 2, 3) and left.render_scale == 0.5
    finally:
        half.close()
    camera = start_camera(SimSource(arm, W, H, render_scale=0.5))
    try:
        messages = camera.stream(2, encoding=pb.IMAGE_ENCODING_PNG)
    finally:
        camera.close()
    header = messages[0].header
    assert (header.width_px, header.height_px) == (W, H)
    pair = messages[1].pair
    assert pair.render_scale == 0.5
    streamed, _ = decode_pair(header, pair)
    assert streamed.shape == full.shape
    assert 20 < psnr(streamed, full) < 60  # the same scene, less detail
    # the fixture's top sits where the full render has it, within a fraction of a pixel
    assert np.abs(_blue_centroid(streamed) - _blue_centroid(full)).max() < 0.5
    u, v = _project(header.left, FIXTURE_TOP)
    red, green, blue = streamed[round(v), round(u)].astype(int)
    assert blue > red + 30 and blue > green + 20


def test_a_sim_camera_over_its_render_budget_draws_fewer_pixels():
    """At 1000 pairs a second no render fits the budget (0.6 ms): each window of pairs steps
    the scale down until the floor."""
    source = SimSource(Arm(), W, H, fps=1000.0, render_scale=None)
    source.open()
    try:
        frames = [source.grab(tick)[0] for tick in range((LADDER.index(FLOOR) + 1) * WINDOW)]
    finally:
        source.close()
    scales = [frame.render_scale for frame in frames]
    assert scales == sorted(scales, reverse=True) and scales[0] == 1.0
    assert scales[-1] == FLOOR
    assert frames[-1].image.shape == (round(H * FLOOR), round(W * FLOOR), 3)


def test_the_flag_chooses_an_adaptive_or_a_fixed_render_scale():
    parser = argparse.ArgumentParser()
    add_source_arguments(parser)
    args = parser.parse_args(["--sim-joints", "home"])
    assert args.sim_render_scale is None  # adaptive by default
    args = parser.parse_args(["--sim-joints", "home", "--sim-render-scale", "0.5"])
    assert source_from_args(args).source.render_scale == 0.5
    with pytest.raises(SystemExit):
        parser.parse_args(["--sim-render-scale", "0.6"])


def test_bad_render_settings_are_refused():
    with pytest.raises(ValueError, match="shadow map"):
        SimSource(Arm(), W, H, shadow_map_px=0)
    with pytest.raises(ValueError, match="multisampling"):
        SimSource(Arm(), W, H, multisamples=-1)
    with pytest.raises(ValueError, match="render scale"):
        SimSource(Arm(), W, H, render_scale=0.3)
