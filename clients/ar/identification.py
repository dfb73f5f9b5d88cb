"""IdentifyCamera: each eye's projection from reference points whose world positions are known.

Section IV-B of the full paper: the operator points, in each eye's image, at four non-coplanar
reference points forming a frame of reference (an origin and one point on each of three axes,
about 20 cm from the origin, the cameras 1.5 m or more away), and the left (M_l) and right (M_r)
projection matrices follow. Two camera models, one representation (a 3x4 matrix P, pixels
= P · [X; 1] divided by the third component):

- **affine** (weak perspective, the paper's model): u = M X + t, P = [[M, t], [0 0 0 1]], 8
  unknowns. Four non-coplanar points determine it exactly: with the frame's edge vectors
  E = [X1 - X0, X2 - X0, X3 - X0] and their images D = [u1 - u0, u2 - u0, u3 - u0],
  M = D E⁻¹ and t = u0 - M X0 (what `identify_affine` computes, as a least-squares fit that is
  exact for four points and averages for more). A fair model when the scene's depth range is
  small against its distance to the camera: the error grows as f · (lateral extent) · (depth
  range) / distance².
- **perspective** (pinhole, full 3x4 P, 11 unknowns): the normalized direct linear transform
  (Hartley) from six or more points not all on one plane, optionally refined by
  Levenberg-Marquardt on the reprojection error. P is scaled so that its third row's first three
  entries have unit norm and the identification points lie in front (w > 0): w is then the
  depth along the optical axis, in metres.

Conventions (those of services/stereo_camera/calibration.py and the StereoHeader): world points
in the robot base frame, metres; pixel (0, 0) is the centre of the top-left pixel, u to the right,
v down. No transport code here.
"""

from __future__ import annotations

import datetime
import enum
from dataclasses import dataclass, field

import numpy as np

MIN_AFFINE_POINTS = 4
MIN_PERSPECTIVE_POINTS = 6
# Smallest spread out of the best-fitting plane, relative to the largest spread, for the points
# to count as non-coplanar (a 20 cm frame may sit 0.2 mm off a plane and still be refused).
COPLANAR_TOLERANCE = 1e-3


class ProjectionKind(enum.StrEnum):
    """The camera model of a projection."""

    AFFINE = "affine"  # weak perspective: the paper's four-point model
    PERSPECTIVE = "perspective"  # pinhole: full 3x4, from six or more points


class IdentificationError(ValueError):
    """The points cannot identify a camera (too few, coplanar, not finite, degenerate)."""


@dataclass(frozen=True, eq=False)
class CameraProjection:
    """One eye's projection: world points (base frame, metres) to pixels.

    `matrix` is 3x4; for AFFINE its third row is [0, 0, 0, 1]."""

    kind: ProjectionKind
    matrix: np.ndarray

    def __post_init__(self):
        matrix = np.array(self.matrix, dtype=float)
        if matrix.shape != (3, 4) or not np.isfinite(matrix).all():
            raise ValueError(f"a projection is a finite 3x4 matrix, got shape {matrix.shape}")
        kind = ProjectionKind(self.kind)
        if kind is ProjectionKind.AFFINE and not np.allclose(matrix[2], [0, 0, 0, 1]):
            raise ValueError("an affine projection's third row must be [0, 0, 0, 1]")
        matrix.setflags(write=False)
        object.__setattr__(self, "matrix", matrix)
        object.__setattr__(self, "kind", kind)

    def homogeneous(self, points_m) -> np.ndarray:
        """(N, 3) homogeneous pixels P · [X; 1] of (N, 3) points (or (3,) for one point)."""
        points = np.asarray(points_m, dtype=float)
        return np.append(points, np.ones(points.shape[:-1] + (1,)), axis=-1) @ self.matrix.T

    def project(self, points_m) -> np.ndarray:
        """Pixels (u, v) of world points: (N, 2) for (N, 3), (2,) for (3,). NaN for points on or
        behind the camera's plane (perspective, w <= 0): they have no image."""
        h = self.homogeneous(points_m)
        w = h[..., 2:3]
        with np.errstate(divide="ignore", invalid="ignore"):
            pixels = h[..., :2] / w
        return np.where(w > 0, pixels, np.nan)

    def depth(self, points_m) -> np.ndarray:
        """Depth of world points along the optical axis (metres; perspective only)."""
        if self.kind is not ProjectionKind.PERSPECTIVE:
            raise ValueError("an affine projection has no depth; use a perspective one")
        return self.homogeneous(points_m)[..., 2]

    def jacobian(self, point_m) -> np.ndarray:
        """d(u, v)/dX (2x3, pixels per metre) at one world point."""
        h = self.homogeneous(point_m)
        uv = h[:2] / h[2]
        return (self.matrix[:2, :3] - np.outer(uv, self.matrix[2, :3])) / h[2]

    def pixels_per_metre(self, point_m) -> float:
        """How many pixels a short length at `point_m`, square to the line of sight, spans: the
        geometric mean of the Jacobian's two singular values. f / depth near the optical axis
        for a perspective camera; a constant for an affine one."""
        singular = np.linalg.svd(self.jacobian(point_m), compute_uv=False)
        return float(np.sqrt(singular[0] * singular[1]))

    def decompose(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(K, R, centre) of a perspective projection: intrinsics (3x3, K[2, 2] = 1, positive
        focal lengths), the camera's axes in the world as R's columns (x right, y down, z
        forward) and the optical centre (metres), so that P ∝ K [Rᵀ | -Rᵀ centre]."""
        if self.kind is not ProjectionKind.PERSPECTIVE:
            raise ValueError("only a perspective projection has an optical centre")
        m = self.matrix[:, :3]
        centre = -np.linalg.solve(m, self.matrix[:, 3])
        k, r_world_to_camera = _rq(m)
        k = k / k[2, 2]
        return k, r_world_to_camera.T, centre

    def scaled(self, sx: float, sy: float) -> CameraProjection:
        """The projection for the image resized by (sx, sy) (pixel centres at integers)."""
        scale = np.array([[sx, 0.0, 0.5 * sx - 0.5], [0.0, sy, 0.5 * sy - 0.5], [0, 0, 1.0]])
        return CameraProjection(self.kind, scale @ self.matrix)


def project_points(projection: CameraProjection, points_m) -> np.ndarray:
    """Pixels of world points with either model (see CameraProjection.project)."""
    return projection.project(points_m)


def reprojection_errors(projection: CameraProjection, points_m, pixels_px) -> np.ndarray:
    """Distance in pixels between each point's projection and its measured pixel."""
    return np.linalg.norm(projection.project(points_m) - np.asarray(pixels_px, float), axis=-1)


def frame_points(origin_m, length_m: float = 0.20, rotation=None) -> np.ndarray:
    """The paper's reference frame as four points (4, 3): the origin, then one point `length_m`
    along each of the frame's x, y and z axes (the columns of `rotation`; default the base
    axes)."""
    axes = np.eye(3) if rotation is None else np.asarray(rotation, float)
    origin = np.asarray(origin_m, float)
    return np.vstack([origin, origin + length_m * axes.T])


# -- identification ------------------------------------------------------------------------------


def identify_camera(points_m, pixels_px, kind: ProjectionKind | str | None = None,
                    refine: bool = True) -> CameraProjection:
    """One eye's projection from world points and their pixels. `kind` None picks the
    perspective model from six points on and the affine one below."""
    points, _ = _checked(points_m, pixels_px, MIN_AFFINE_POINTS)
    if kind is None:
        kind = (ProjectionKind.PERSPECTIVE if len(points) >= MIN_PERSPECTIVE_POINTS
                else ProjectionKind.AFFINE)
    if ProjectionKind(kind) is ProjectionKind.AFFINE:
        return identify_affine(points_m, pixels_px)
    return identify_dlt(points_m, pixels_px, refine=refine)


def identify_affine(points_m, pixels_px) -> CameraProjection:
    """The weak-perspective projection from four or more non-coplanar points: exact for four
    (the paper's frame), least squares for more."""
    points, pixels = _checked(points_m, pixels_px, MIN_AFFINE_POINTS)
    _require_non_coplanar(points, "the affine model")
    design = np.hstack([points, np.ones((len(points), 1))])
    rows, *_ = np.linalg.lstsq(design, pixels, rcond=None)
    return CameraProjection(ProjectionKind.AFFINE, np.vstack([rows.T, [0.0, 0.0, 0.0, 1.0]]))


def identify_dlt(points_m, pixels_px, refine: bool = True,
                 max_iterations: int = 50) -> CameraProjection:
    """The perspective projection from six or more points not all on one plane: normalized DLT,
    then (with `refine`) Levenberg-Marquardt on the squared reprojection error."""
    points, pixels = _checked(points_m, pixels_px, MIN_PERSPECTIVE_POINTS)
    _require_non_coplanar(points, "the perspective model (DLT)")
    t3 = _normalizer(points)
    t2 = _normalizer(pixels)
    xn = _apply(t3, points)
    un = _apply(t2, pixels)
    n = len(points)
    xh = np.hstack([xn, np.ones((n, 1))])
    a = np.zeros((2 * n, 12))
    a[0::2, 0:4] = xh
    a[0::2, 8:12] = -un[:, :1] * xh
    a[1::2, 4:8] = xh
    a[1::2, 8:12] = -un[:, 1:] * xh
    _, singular, vt = np.linalg.svd(a)
    if singular[-2] <= 1e-9 * singular[0]:
        raise IdentificationError("the points do not determine a perspective camera (a "
                                  "degenerate configuration): use points spread in depth")
    p = vt[-1].reshape(3, 4)
    if refine:
        p = _refine(p, xh, un, max_iterations)
    matrix = np.linalg.inv(t2) @ p @ t3
    return CameraProjection(ProjectionKind.PERSPECTIVE, _normalized(matrix, points))


# -- helpers -------------------------------------------------------------------------------------


def _checked(points_m, pixels_px, minimum: int) -> tuple[np.ndarray, np.ndarray]:
    points = np.asarray(points_m, dtype=float)
    pixels = np.asarray(pixels_px, dtype=float)
    if points.ndim != 2 or points.shape[1] != 3:
        raise IdentificationError(f"world points must be (N, 3), got shape {points.shape}")
    if pixels.shape != (len(points), 2):
        raise IdentificationError(f"pixels must be ({len(points)}, 2), one per world point, "
                                  f"got shape {pixels.shape}")
    if not (np.isfinite(points).all() and np.isfinite(pixels).all()):
        raise IdentificationError("the points and pixels must be finite (no NaN or Inf)")
    if len(points) < minimum:
        raise IdentificationError(f"need at least {minimum} points, got {len(points)}")
    return points, pixels


def _require_non_coplanar(points: np.ndarray, what: str) -> None:
    spread = np.linalg.svd(points - points.mean(axis=0), compute_uv=False)
    if spread[0] == 0 or spread[2] < COPLANAR_TOLERANCE * spread[0]:
        raise IdentificationError(
            f"{what} needs points that are not all on one plane (or line); these are "
            f"(out-of-plane spread {spread[2]:.3g} against {spread[0]:.3g}): pick a point off "
            "the plane, such as the frame's z axis point")


def _normalizer(points: np.ndarray) -> np.ndarray:
    """Hartley's similarity: centroid to the origin, mean distance to sqrt(dimension)."""
    dim = points.shape[1]
    centroid = points.mean(axis=0)
    mean_distance = np.linalg.norm(points - centroid, axis=1).mean()
    scale = np.sqrt(dim) / mean_distance
    t = np.eye(dim + 1)
    t[:dim, :dim] *= scale
    t[:dim, dim] = -scale * centroid
    return t


def _apply(t: np.ndarray, points: np.ndarray) -> np.ndarray:
    return points @ t[:-1, :-1].T + t[:-1, -1]


def _residuals(p: np.ndarray, xh: np.ndarray, un: np.ndarray) -> np.ndarray:
    h = xh @ p.T
    return (h[:, :2] / h[:, 2:3] - un).reshape(-1)


def _refine(p: np.ndarray, xh: np.ndarray, un: np.ndarray, max_iterations: int) -> np.ndarray:
    """Levenberg-Marquardt over the 12 entries (kept at unit norm: the scale is free)."""
    p = p / np.linalg.norm(p)
    cost = float(np.sum(_residuals(p, xh, un) ** 2))
    damping = 1e-3
    for _ in range(max_iterations):
        h = xh @ p.T
        w = h[:, 2:3]
        uv = h[:, :2] / w
        n = len(xh)
        jac = np.zeros((2 * n, 12))
        jac[0::2, 0:4] = xh / w
        jac[0::2, 8:12] = -uv[:, :1] * xh / w
        jac[1::2, 4:8] = xh / w
        jac[1::2, 8:12] = -uv[:, 1:] * xh / w
        r = (uv - un).reshape(-1)
        jtj = jac.T @ jac
        gradient = jac.T @ r
        improved = False
        while damping < 1e8:
            step = np.linalg.solve(jtj + damping * (np.diag(np.diag(jtj)) + 1e-9 * np.eye(12)),
                                   -gradient)
            candidate = p + step.reshape(3, 4)
            candidate /= np.linalg.norm(candidate)
            candidate_cost = float(np.sum(_residuals(candidate, xh, un) ** 2))
            if np.isfinite(candidate_cost) and candidate_cost < cost:
                improved = cost - candidate_cost > 1e-12 * max(cost, 1e-30)
                p, cost = candidate, candidate_cost
                damping = max(damping / 10.0, 1e-12)
                break
            damping *= 10.0
        if not improved:
            break
    return p


def _normalized(matrix: np.ndarray, points: np.ndarray) -> np.ndarray:
    """Scale so that ||P[2, :3]|| = 1 and the points are in front (w > 0)."""
    matrix = matrix / np.linalg.norm(matrix[2, :3])
    w = np.hstack([points, np.ones((len(points), 1))]) @ matrix[2]
    if np.median(w) < 0:
        matrix = -matrix
    return matrix


def _rq(m: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """m = K R with K upper triangular (positive diagonal) and R a rotation."""
    flip = np.eye(3)[::-1]
    q, r = np.linalg.qr((flip @ m).T)
    k = flip @ r.T @ flip
    rot = flip @ q.T
    signs = np.diag(np.sign(np.diag(k)))
    return k @ signs, signs @ rot  # det(rot) = sign(det m): -1 only for a mirrored camera


# -- both eyes -----------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class EyeIdentification:
    """One eye's projection and the points it was identified from."""

    projection: CameraProjection
    points_m: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)))  # (N, 3)
    pixels_px: np.ndarray = field(default_factory=lambda: np.zeros((0, 2)))  # (N, 2)

    def __post_init__(self):
        object.__setattr__(self, "points_m", np.asarray(self.points_m, float).reshape(-1, 3))
        object.__setattr__(self, "pixels_px", np.asarray(self.pixels_px, float).reshape(-1, 2))
        if len(self.points_m) != len(self.pixels_px):
            raise ValueError("one pixel per identification point")

    @property
    def rms_error_px(self) -> float:
        """RMS reprojection error on the identification points (0 for exactly four affine
        points, which the model always fits: hold one point out to judge it)."""
        if not len(self.points_m):
            return 0.0
        errors = reprojection_errors(self.projection, self.points_m, self.pixels_px)
        return float(np.sqrt(np.mean(errors ** 2)))


@dataclass(frozen=True, eq=False)
class StereoIdentification:
    """Both eyes' projections (M_l, M_r) for images of width_px x height_px."""

    left: EyeIdentification
    right: EyeIdentification
    width_px: int
    height_px: int
    created_utc: str = ""  # ISO 8601, set when identified
    source: str = ""  # where the images came from (the header's `source`), for people

    @property
    def kind(self) -> ProjectionKind:
        return self.left.projection.kind

    def for_size(self, width_px: int, height_px: int) -> StereoIdentification:
        """The same identification for images resized to width_px x height_px."""
        if (width_px, height_px) == (self.width_px, self.height_px):
            return self
        sx, sy = width_px / self.width_px, height_px / self.height_px

        def eye(e: EyeIdentification) -> EyeIdentification:
            pixels = (e.pixels_px + 0.5) * [sx, sy] - 0.5
            return EyeIdentification(e.projection.scaled(sx, sy), e.points_m, pixels)

        return StereoIdentification(eye(self.left), eye(self.right), width_px, height_px,
                                    self.created_utc, self.source)


def identify_stereo(points_m, left_pixels_px, right_pixels_px, width_px: int, height_px: int,
                    kind: ProjectionKind | str | None = None, refine: bool = True,
                    source: str = "", right_points_m=None) -> StereoIdentification:
    """Identify both eyes from the same world points (or `right_points_m` for the right eye, when
    it saw different ones)."""
    right_points = points_m if right_points_m is None else right_points_m
    if kind is None:
        count = min(len(np.asarray(points_m)), len(np.asarray(right_points)))
        kind = (ProjectionKind.PERSPECTIVE if count >= MIN_PERSPECTIVE_POINTS
                else ProjectionKind.AFFINE)
    eyes = []
    for name, points, pixels in (("left", points_m, left_pixels_px),
                                 ("right", right_points, right_pixels_px)):
        try:
            projection = identify_camera(points, pixels, kind, refine)
        except IdentificationError as exc:
            raise IdentificationError(f"{name} eye: {exc}") from None
        eyes.append(EyeIdentification(projection, points, pixels))
    created = datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds")
    return StereoIdentification(eyes[0], eyes[1], int(width_px), int(height_px), created, source)
