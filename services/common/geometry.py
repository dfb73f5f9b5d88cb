"""Checks and repairs for vectors and rotations received from outside (no transport code)."""

from __future__ import annotations

import numpy as np

from services.runtime.errors import InvalidArgument

# How far from orthonormal a received rotation may be before it is refused rather than repaired.
# Loose enough for matrices typed by hand or sent as 6-digit JSON; Gram-Schmidt fixes the rest.
ROTATION_TOLERANCE = 1e-3


def finite_vector(values, length: int, what: str) -> np.ndarray:
    """`values` as a float array of `length`; InvalidArgument for a wrong length, NaN or Inf."""
    array = np.asarray(list(values), dtype=float)
    if array.shape != (length,):
        raise InvalidArgument(f"{what} needs {length} values, got {array.size}",
                              reason="BAD_LENGTH")
    if not np.all(np.isfinite(array)):
        raise InvalidArgument(f"{what} contains NaN or Inf: {array.tolist()}",
                              reason="NOT_FINITE")
    return array


def gram_schmidt(matrix: np.ndarray) -> np.ndarray:
    """The orthonormal matrix nearest in the Gram-Schmidt sense: columns normalized in order,
    the third taken as the cross product so the result is a proper rotation."""
    x = matrix[:, 0] / np.linalg.norm(matrix[:, 0])
    y = matrix[:, 1] - (x @ matrix[:, 1]) * x
    y /= np.linalg.norm(y)
    return np.column_stack([x, y, np.cross(x, y)])


def rotation_matrix(values, what: str) -> np.ndarray:
    """A 3x3 rotation from nine row-major values (none: identity), re-orthonormalized.

    InvalidArgument when it is not within ROTATION_TOLERANCE of a rotation (det +1)."""
    values = list(values)
    if not values:
        return np.eye(3)
    matrix = finite_vector(values, 9, what).reshape(3, 3)
    error = np.abs(matrix.T @ matrix - np.eye(3)).max()
    if error > ROTATION_TOLERANCE or np.linalg.det(matrix) <= 0:
        raise InvalidArgument(
            f"{what} is not a rotation matrix (|MᵀM − I| = {error:.2g}, det = "
            f"{np.linalg.det(matrix):.3g}); send an orthonormal row-major 3x3 with det +1, "
            "or leave it empty for no rotation", reason="NOT_A_ROTATION")
    return gram_schmidt(matrix)


def rotation_angle(rotation: np.ndarray) -> float:
    """Angle of a rotation matrix, in radians (0..pi)."""
    return float(np.arccos(np.clip((np.trace(rotation) - 1.0) / 2.0, -1.0, 1.0)))


def euler_xyz(rotation: np.ndarray) -> np.ndarray:
    """(αx, αy, αz) in radians with rotation = Rx(αx) Ry(αy) Rz(αz), the papers' R_xyz⁻¹."""
    r = rotation
    beta = np.arcsin(np.clip(r[0, 2], -1.0, 1.0))
    alpha = np.arctan2(-r[1, 2], r[2, 2])
    gamma = np.arctan2(-r[0, 1], r[0, 0])
    return np.array([alpha, beta, gamma])


def from_euler_xyz(angles: np.ndarray) -> np.ndarray:
    """Rx(αx) Ry(αy) Rz(αz), the papers' R_xyz."""
    ax, ay, az = angles
    cx, sx, cy, sy, cz, sz = np.cos(ax), np.sin(ax), np.cos(ay), np.sin(ay), np.cos(az), np.sin(az)
    rx = np.array([[1, 0, 0], [0, cx, -sx], [0, sx, cx]])
    ry = np.array([[cy, 0, sy], [0, 1, 0], [-sy, 0, cy]])
    rz = np.array([[cz, -sz, 0], [sz, cz, 0], [0, 0, 1]])
    return rx @ ry @ rz


def scale_increment(delta_position: np.ndarray, delta_rotation: np.ndarray,
                    translation_scale: float, rotation_scale: float
                    ) -> tuple[np.ndarray, np.ndarray]:
    """Eq. 2 of the full paper: ΔX·s, and ΔM rebuilt from its XYZ Euler angles times s."""
    return (delta_position * translation_scale,
            from_euler_xyz(euler_xyz(delta_rotation) * rotation_scale))
