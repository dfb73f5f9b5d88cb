"""Checks and repairs for vectors and rotations received from outside (no transport code)."""

from __future__ import annotations

import numpy as np

from wire.errors import InvalidArgumentError

# How far from orthonormal a received rotation may be before it is refused rather than repaired.
# Loose enough for matrices typed by hand or sent as 6-digit JSON; Gram-Schmidt fixes the rest.
ROTATION_TOLERANCE = 1e-3


def finite_vector(values, length: int, what: str) -> np.ndarray:
    """`values` as a float array of `length`; InvalidArgumentError for a wrong length, NaN or
    Inf."""
    array = np.asarray(list(values), dtype=float)
    if array.shape != (length,):
        raise InvalidArgumentError(f"{what} needs {length} values, got {array.size}",
                                   reason="BAD_LENGTH")
    if not np.all(np.isfinite(array)):
        raise InvalidArgumentError(f"{what} contains NaN or Inf: {array.tolist()}",
                                   reason="NOT_FINITE")
    return array


def cross3(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """np.cross of two 3-vectors, to the same bits, in a twentieth of its time (np.cross's
    generality costs ~20 µs a call; this runs on every command and every wrench sample)."""
    ax, ay, az = a.tolist()
    bx, by, bz = b.tolist()
    return np.array([ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx])


def gram_schmidt(matrix: np.ndarray) -> np.ndarray:
    """The orthonormal matrix nearest in the Gram-Schmidt sense: columns normalized in order,
    the third taken as the cross product so the result is a proper rotation."""
    x = matrix[:, 0] / np.linalg.norm(matrix[:, 0])
    y = matrix[:, 1] - (x @ matrix[:, 1]) * x
    y /= np.linalg.norm(y)
    return np.column_stack([x, y, cross3(x, y)])


def rotation_matrix(values, what: str) -> np.ndarray:
    """A 3x3 rotation from nine row-major values (none: identity), re-orthonormalized.

    InvalidArgumentError when it is not within ROTATION_TOLERANCE of a rotation (det +1)."""
    values = list(values)
    if not values:
        return np.eye(3)
    matrix = finite_vector(values, 9, what).reshape(3, 3)
    error = np.abs(matrix.T @ matrix - np.eye(3)).max()
    if error > ROTATION_TOLERANCE or np.linalg.det(matrix) <= 0:
        raise InvalidArgumentError(
            f"{what} is not a rotation matrix (|MᵀM − I| = {error:.2g}, det = "
            f"{np.linalg.det(matrix):.3g}); send an orthonormal row-major 3x3 with det +1, "
            "or leave it empty for no rotation", reason="NOT_A_ROTATION")
    return gram_schmidt(matrix)
