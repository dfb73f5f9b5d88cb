"""IdentifyCamera: both camera models against a known pinhole camera.

Perspective (DLT): a 640x480 camera with a 45-degree field of view, 1.1 m from the work cell as the
sim rig is; reference points anywhere in the workspace in view.

Affine (weak perspective): fair only when the scene is shallow against its distance. The error of
the four-point affine model over a cube of side L at distance d from a camera of focal length f
is about f L² / d² (the perspective term the affine model drops, at the cube's lateral extent
times its depth range). The test setting: f = 579 px, L = 0.1 m, d = 5 m, so f L² / d² = 0.23 px
and the test asserts < 1 px on held-out points inside the cube. At the paper's own geometry (a
20 cm frame, the camera 1.5 m away) the same camera would be off by about 10 px: there the
perspective model is the one to use.
"""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from clients.ar.identification import (
    CameraProjection,
    IdentificationError,
    ProjectionKind,
    frame_points,
    identify_affine,
    identify_camera,
    identify_dlt,
    identify_stereo,
    project_points,
    reprojection_errors,
)
from tests.ar.helpers import FOCAL_PX, HEIGHT, WIDTH, in_image, look_at, perspective

EYE = (1.40, -0.15, 0.90)  # the sim rig's left eye, near enough
TARGET = (0.645, -0.15, 0.40)


def _workspace_points(camera: CameraProjection, count: int, seed: int) -> np.ndarray:
    """`count` random points of the workspace (in front of the robot, table to shoulder height)
    that the camera sees."""
    rng = np.random.default_rng(seed)
    points = rng.uniform([0.35, -0.45, 0.25], [0.90, 0.15, 0.80], (8 * count, 3))
    return points[in_image(camera.project(points))][:count]


def test_dlt_from_six_exact_points_reprojects_held_out_points_exactly():
    camera = perspective(EYE, TARGET)
    points = _workspace_points(camera, 46, seed=1)
    found = identify_dlt(points[:6], camera.project(points[:6]))
    errors = reprojection_errors(found, points[6:], camera.project(points[6:]))
    assert found.kind is ProjectionKind.PERSPECTIVE
    assert errors.max() < 1e-6


def test_dlt_from_clicked_points_is_subpixel_on_held_out_points():
    """Twelve well-spread reference points (the corners of the workspace box and four inside)
    clicked with 0.25 px of noise (RMS); 300 held-out points inside the box. (Held-out points
    far outside the reference points' spread extrapolate the noise: spread them.)"""
    camera = perspective(EYE, TARGET)
    low, high = np.array([0.45, -0.40, 0.25]), np.array([0.85, 0.10, 0.70])
    corners = low + (high - low) * np.array(list(itertools.product((0, 1), repeat=3)))
    middle = (low + high) / 2
    inside = middle + np.array([[0, 0, 0], [0.1, 0, 0], [0, 0.12, 0.1], [-0.1, -0.12, 0.05]])
    references = np.vstack([corners, inside])
    rng = np.random.default_rng(0)
    clicked = camera.project(references) + rng.normal(0.0, 0.25, (12, 2))
    held_out = rng.uniform(low, high, (300, 3))
    assert in_image(camera.project(references)).all() and in_image(camera.project(held_out)).all()
    truth = camera.project(held_out)
    linear = identify_dlt(references, clicked, refine=False)
    refined = identify_dlt(references, clicked)
    for found in (linear, refined):
        assert reprojection_errors(found, held_out, truth).max() < 1.0
    # refinement minimizes the reprojection error on the clicked points
    assert (np.sum(reprojection_errors(refined, references, clicked) ** 2)
            <= np.sum(reprojection_errors(linear, references, clicked) ** 2) + 1e-12)


def test_dlt_recovers_the_cameras_intrinsics_and_pose():
    p, k, rotation = look_at(EYE, TARGET)
    camera = CameraProjection(ProjectionKind.PERSPECTIVE, p)
    points = _workspace_points(camera, 10, seed=4)
    found = identify_dlt(points, camera.project(points))
    k_found, r_found, centre = found.decompose()
    np.testing.assert_allclose(k_found, k, atol=1e-6)
    np.testing.assert_allclose(r_found, rotation, atol=1e-9)
    np.testing.assert_allclose(centre, EYE, atol=1e-9)
    # P is scaled so that w is the depth along the optical axis, in metres
    assert found.depth(TARGET) == pytest.approx(np.linalg.norm(np.subtract(TARGET, EYE)))


def test_affine_from_the_papers_four_point_frame_where_weak_perspective_is_fair():
    """L = 0.1 m frame, camera 5 m away, f = 579 px: f L² / d² = 0.23 px."""
    length, distance = 0.10, 5.0
    centre = np.array([0.60, -0.15, 0.40])
    direction = np.array([1.0, 0.2, 0.6]) / np.linalg.norm([1.0, 0.2, 0.6])
    camera = perspective(centre + distance * direction, centre)
    origin = centre - length / 2
    frame = frame_points(origin, length)  # origin, then 10 cm along x, y and z
    found = identify_affine(frame, camera.project(frame))
    held_out = np.random.default_rng(5).uniform(origin, origin + length, (500, 3))
    errors = reprojection_errors(found, held_out, camera.project(held_out))
    assert found.kind is ProjectionKind.AFFINE
    np.testing.assert_allclose(found.matrix[2], [0, 0, 0, 1])
    assert FOCAL_PX * length ** 2 / distance ** 2 < 0.25
    assert errors.max() < 1.0, errors.max()
    # the frame itself is reproduced exactly (four points, eight unknowns)
    assert reprojection_errors(found, frame, camera.project(frame)).max() < 1e-9


def test_affine_with_more_points_is_a_least_squares_fit():
    camera = perspective((6.0, 1.0, 3.0), (0.6, -0.15, 0.4))
    points = np.random.default_rng(6).uniform([0.55, -0.2, 0.35], [0.65, -0.1, 0.45], (30, 3))
    found = identify_affine(points[:10], camera.project(points[:10]))
    assert reprojection_errors(found, points[10:], camera.project(points[10:])).max() < 0.5


def test_the_affine_model_is_poor_at_close_range_and_the_perspective_one_is_not():
    """The paper's geometry (20 cm frame, camera 1.5 m away) at 640x480 and 45 degrees."""
    origin = np.array([0.5, -0.25, 0.3])
    camera = perspective(origin + 0.1 + 1.5 * np.array([0.8, 0.0, 0.6]), origin + 0.1)
    frame = frame_points(origin, 0.20)
    held_out = np.random.default_rng(7).uniform(origin, origin + 0.2, (300, 3))
    affine = identify_affine(frame, camera.project(frame))
    extra = np.random.default_rng(8).uniform(origin, origin + 0.2, (4, 3))
    six = np.vstack([frame, extra[:2]])
    dlt = identify_dlt(six, camera.project(six))
    assert reprojection_errors(affine, held_out, camera.project(held_out)).max() > 3.0
    assert reprojection_errors(dlt, held_out, camera.project(held_out)).max() < 1e-6


def test_identify_camera_picks_the_model_from_the_number_of_points():
    camera = perspective(EYE, TARGET)
    points = _workspace_points(camera, 6, seed=9)
    assert identify_camera(points[:4], camera.project(points[:4])).kind is ProjectionKind.AFFINE
    assert identify_camera(points, camera.project(points)).kind is ProjectionKind.PERSPECTIVE
    assert identify_camera(points, camera.project(points), "affine").kind is ProjectionKind.AFFINE


@pytest.mark.parametrize("builder, count", [(identify_affine, 4), (identify_dlt, 8)])
def test_coplanar_points_are_refused(builder, count):
    rng = np.random.default_rng(10)
    points = np.column_stack([rng.uniform(0.4, 0.8, count), rng.uniform(-0.3, 0.1, count),
                              np.full(count, 0.25)])  # all on the table top
    with pytest.raises(IdentificationError, match="not all on one plane"):
        builder(points, rng.uniform(0, 400, (count, 2)))


def test_bad_input_is_refused_with_what_to_do():
    frame = frame_points((0.5, 0.0, 0.3))
    with pytest.raises(IdentificationError, match="at least 6"):
        identify_dlt(frame, np.zeros((4, 2)))
    with pytest.raises(IdentificationError, match="at least 4"):
        identify_affine(frame[:3], np.zeros((3, 2)))
    with pytest.raises(IdentificationError, match="one per world point"):
        identify_affine(frame, np.zeros((3, 2)))
    with pytest.raises(IdentificationError, match="finite"):
        identify_affine(frame, np.full((4, 2), np.nan))


def test_projecting_with_either_model():
    camera = perspective(EYE, TARGET)
    points = _workspace_points(camera, 8, seed=11)
    affine = identify_affine(points[:4], camera.project(points[:4]))
    for model in (camera, affine):
        one = project_points(model, points[0])
        many = project_points(model, points)
        assert one.shape == (2,) and many.shape == (8, 2)
        np.testing.assert_allclose(many[0], one)
    # a point behind the camera has no image
    behind = np.asarray(EYE) + (np.asarray(EYE) - TARGET)
    assert np.isnan(camera.project(behind)).all()


def test_ball_scale_follows_depth_for_perspective_only():
    camera = perspective(EYE, TARGET)
    near = np.asarray(EYE) + 0.5 * (np.subtract(TARGET, EYE))
    assert camera.pixels_per_metre(TARGET) == pytest.approx(
        FOCAL_PX / np.linalg.norm(np.subtract(TARGET, EYE)), rel=1e-9)
    assert camera.pixels_per_metre(near) == pytest.approx(2 * camera.pixels_per_metre(TARGET))
    frame = frame_points(np.subtract(TARGET, 0.05), 0.1)
    affine = identify_affine(frame, camera.project(frame))
    assert affine.pixels_per_metre(near) == pytest.approx(affine.pixels_per_metre(TARGET))


def test_stereo_identification_and_resizing():
    left = perspective(EYE, TARGET)
    right = perspective(np.add(EYE, (0.0, 0.12, 0.0)), np.add(TARGET, (0.0, 0.12, 0.0)))
    points = _workspace_points(left, 8, seed=12)
    stereo = identify_stereo(points, left.project(points), right.project(points), WIDTH, HEIGHT,
                             source="test")
    assert stereo.kind is ProjectionKind.PERSPECTIVE
    assert stereo.left.rms_error_px < 1e-6 and stereo.right.rms_error_px < 1e-6
    assert stereo.created_utc.endswith("+00:00")
    half = stereo.for_size(WIDTH // 2, HEIGHT // 2)
    small = perspective(EYE, TARGET, focal_px=FOCAL_PX / 2, width=WIDTH // 2, height=HEIGHT // 2)
    np.testing.assert_allclose(half.left.projection.project(points), small.project(points),
                               atol=1e-6)
    np.testing.assert_allclose(half.left.pixels_px, small.project(points), atol=1e-6)
