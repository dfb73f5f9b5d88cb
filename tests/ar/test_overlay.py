"""The overlay: the ball drawn where the projection says, and the side-by-side stereo frame."""

from __future__ import annotations

import cv2
import numpy as np
import pytest

from clients.ar.identification import frame_points, identify_affine
from clients.ar.overlay import (
    BallStyle,
    SideBySideComposer,
    StereoOverlay,
    draw_ball,
    locate_ball,
    side_by_side,
)
from tests.ar.helpers import perspective

W, H = 160, 120
FOCAL = 0.5 * H / np.tan(np.radians(22.5))
LEFT = perspective((1.40, -0.21, 0.90), (0.645, -0.21, 0.40), focal_px=FOCAL, width=W, height=H)
RIGHT = perspective((1.40, -0.09, 0.90), (0.645, -0.09, 0.40), focal_px=FOCAL, width=W, height=H)
TOOL = np.array([0.645, -0.15, 0.50])
STYLE = BallStyle(radius_m=0.02, fill_rgb=(255, 0, 255), outline_rgb=(0, 255, 0), outline_px=1)


def _blank() -> np.ndarray:
    return np.full((H, W, 3), 40, np.uint8)


def _fill_centroid(image: np.ndarray, rgb=STYLE.fill_rgb) -> tuple[np.ndarray, int]:
    """Centroid (u, v) and count of the pixels painted exactly in the fill colour."""
    vs, us = np.nonzero(np.all(image == rgb, axis=2))
    return np.array([us.mean(), vs.mean()]), len(us)


def test_the_ball_is_centred_on_the_projected_tool_point_in_both_eyes():
    overlay = StereoOverlay(LEFT, RIGHT, STYLE)
    left, right, balls = overlay.draw(_blank(), _blank(), TOOL)
    for image, camera, ball in ((left, LEFT, balls.left), (right, RIGHT, balls.right)):
        expected = camera.project(TOOL)
        np.testing.assert_allclose(ball.centre_px, expected)
        centroid, count = _fill_centroid(image)
        assert np.linalg.norm(centroid - expected) < 0.3
        radius = STYLE.radius_m * FOCAL / camera.depth(TOOL)
        assert ball.radius_px == pytest.approx(radius, rel=0.02)  # near the optical axis
        vs, us = np.nonzero(np.any(image != 40, axis=2))  # fill, outline and antialiasing
        reach = np.hypot(us - expected[0], vs - expected[1]).max()
        assert radius - 0.5 < reach < radius + 1.5
        assert count > 0.5 * np.pi * (radius - 1) ** 2  # the outline covers the rim
        assert np.all(image[int(round(expected[1])), int(round(expected[0]))] == STYLE.fill_rgb)
        greenish = (image[..., 1] > 120) & (image[..., 0] < 120)  # the outline, antialiased
        assert np.any(greenish)
    # the two eyes differ by the disparity f * baseline / depth
    disparity = balls.left.centre_px[0] - balls.right.centre_px[0]
    assert disparity == pytest.approx(FOCAL * 0.12 / LEFT.depth(TOOL), rel=1e-6)


def test_the_ball_grows_as_the_tool_comes_nearer_with_perspective_only():
    nearer = TOOL + 0.4 * (np.array([1.40, -0.21, 0.90]) - TOOL)
    far_ball = locate_ball(LEFT, TOOL, STYLE, W, H)
    near_ball = locate_ball(LEFT, nearer, STYLE, W, H)
    assert near_ball.radius_px / far_ball.radius_px == pytest.approx(
        LEFT.depth(TOOL) / LEFT.depth(nearer), rel=0.01)
    frame = frame_points(TOOL - 0.1, 0.2)
    affine = identify_affine(frame, LEFT.project(frame))
    assert (locate_ball(affine, nearer, STYLE, W, H).radius_px
            == pytest.approx(locate_ball(affine, TOOL, STYLE, W, H).radius_px))
    tiny = BallStyle(radius_m=1e-6, min_radius_px=2.0)
    assert locate_ball(LEFT, TOOL, tiny, W, H).radius_px == 2.0


def test_a_point_out_of_view_draws_nothing_and_says_so():
    overlay = StereoOverlay(LEFT, RIGHT, STYLE)
    behind = np.array([2.2, -0.15, 1.4])  # behind both cameras
    left, right, balls = overlay.draw(_blank(), _blank(), behind)
    assert balls.left is None and balls.right is None
    assert np.all(left == 40) and np.all(right == 40)
    aside = np.array([0.645, 1.5, 0.5])  # far to the side: projects outside the image
    left, _, balls = overlay.draw(_blank(), _blank(), aside)
    assert balls.left is not None and not balls.left.inside
    assert np.all(left == 40)


def test_drawing_copies_unless_told_not_to():
    overlay = StereoOverlay(LEFT, RIGHT, STYLE)
    left, right = _blank(), _blank()
    drawn_left, _, _ = overlay.draw(left, right, TOOL)
    assert np.all(left == 40) and drawn_left is not left
    drawn_left, _, _ = overlay.draw(left, right, TOOL, copy=False)
    assert drawn_left is left and not np.all(left == 40)
    with pytest.raises(ValueError, match="RGB8"):
        overlay.draw(left[:, :, 0], right, TOOL)
    with pytest.raises(ValueError, match="differ in size"):
        overlay.draw(left, right[:-1], TOOL)
    image = _blank()
    assert draw_ball(image, locate_ball(LEFT, TOOL, STYLE, W, H), STYLE) is image


def test_side_by_side_puts_left_then_right_in_one_frame():
    left = np.zeros((H, W, 3), np.uint8)
    right = np.zeros((H, W, 3), np.uint8)
    left[..., 0] = 200  # red
    right[..., 2] = 100  # blue
    frame = side_by_side(left, right)
    assert frame.shape == (H, 2 * W, 3)
    assert np.all(frame[:, :W] == (200, 0, 0)) and np.all(frame[:, W:] == (0, 0, 100))
    bgr = side_by_side(left, right, bgr=True)
    assert np.all(bgr[:, :W] == (0, 0, 200)) and np.all(bgr[:, W:] == (100, 0, 0))


def test_the_composer_double_buffers_its_pages():
    composer = SideBySideComposer(W, H)
    frames = [np.full((H, W, 3), value, np.uint8) for value in (10, 20, 30)]
    first = composer.compose(frames[0], frames[0])
    second = composer.compose(frames[1], frames[1])
    assert first is not second and composer.front is second
    assert np.all(first == 10)  # the previous page is intact while the next one is composed
    third = composer.compose(frames[2], frames[2])
    assert third is first and np.all(third == 30)  # the pages alternate
    assert composer.frames == 3 and composer.frame_size == (2 * W, H)
    with pytest.raises(ValueError, match="takes 160x120"):
        composer.compose(np.zeros((60, 80, 3), np.uint8), np.zeros((60, 80, 3), np.uint8))


def test_a_video_writer_consumes_the_composed_frames(tmp_path):
    overlay = StereoOverlay(LEFT, RIGHT, STYLE)
    composer = SideBySideComposer(W, H, bgr=True)
    path = tmp_path / "stereo.avi"
    writer = cv2.VideoWriter(str(path), cv2.VideoWriter_fourcc(*"MJPG"), 10.0,
                             composer.frame_size)
    if not writer.isOpened():
        pytest.skip("this OpenCV build has no MJPG writer")
    for step in range(3):
        left, right, _ = overlay.draw(_blank(), _blank(), TOOL + [0.0, 0.02 * step, 0.0])
        writer.write(composer.compose(left, right))
    writer.release()
    capture = cv2.VideoCapture(str(path))
    read = []
    while True:
        ok, frame = capture.read()
        if not ok:
            break
        read.append(frame)
    capture.release()
    assert len(read) == 3 and read[0].shape == (H, 2 * W, 3)
    # the ball (magenta in RGB: B and R high, G low) is in the left half of the first frame,
    # where the left eye saw it
    u, v = LEFT.project(TOOL)
    b, g, r = read[0][int(round(v)), int(round(u))].astype(int)
    assert b > 180 and r > 180 and g < 80
