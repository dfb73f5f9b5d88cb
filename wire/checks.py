"""Checks and repairs for vectors and rotations received from outside (no transport code)."""

from __future__ import annotations

import math

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
    if not np.isfinite(array).all():
        raise InvalidArgumentError(f"{what} contains NaN or Inf: {array.tolist()}",
                                   reason="NOT_FINITE")
    return array


def cross3(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """np.cross of two 3-vectors, to the same bits, in a twentieth of its time (np.cross's
    generality costs ~20 µs a call; this runs on every command and every wrench sample)."""
    ax, ay, az = a.tolist()
    bx, by, bz = b.tolist()
    return np.array([ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx])


def vector_norm(values) -> float:
    """np.linalg.norm of a vector, in floats. np.linalg.norm computes through ndarray.dot,
    which lets go of the interpreter lock: in a process whose other threads are busy, the
    caller then waits for it again, about 0.1 ms on this host, where this takes 0.2 µs."""
    return math.hypot(*np.asarray(values, dtype=float).ravel().tolist())


def gram_schmidt(matrix: np.ndarray) -> np.ndarray:
    """The orthonormal matrix nearest in the Gram-Schmidt sense: columns normalized in order,
    the third taken as the cross product so the result is a proper rotation."""
    return _gram_schmidt(*np.asarray(matrix, float).reshape(9).tolist())


def _gram_schmidt(a: float, b: float, c: float, d: float, e: float, f: float, g: float,
                  h: float, i: float) -> np.ndarray:
    """gram_schmidt on a row-major 3x3's nine values, in floats: numpy's per-call overhead
    was most of its cost, and every command's rotation goes through it."""
    norm = math.sqrt(a * a + d * d + g * g)
    x0, x1, x2 = a / norm, d / norm, g / norm
    along = x0 * b + x1 * e + x2 * h
    y0, y1, y2 = b - along * x0, e - along * x1, h - along * x2
    norm = math.sqrt(y0 * y0 + y1 * y1 + y2 * y2)
    y0, y1, y2 = y0 / norm, y1 / norm, y2 / norm
    return np.array([[x0, y0, x1 * y2 - x2 * y1],
                     [x1, y1, x2 * y0 - x0 * y2],
                     [x2, y2, x0 * y1 - x1 * y0]])


def rotation_matrix(values, what: str) -> np.ndarray:
    """A 3x3 rotation from nine row-major values (none: identity), re-orthonormalized.

    InvalidArgumentError when it is not within ROTATION_TOLERANCE of a rotation (det +1)."""
    values = list(values)
    if not values:
        return np.eye(3)
    a, b, c, d, e, f, g, h, i = finite_vector(values, 9, what).tolist()
    # MᵀM − I, entry by entry (the columns' norms and dot products), in floats.
    error = max(abs(a * a + d * d + g * g - 1.0), abs(b * b + e * e + h * h - 1.0),
                abs(c * c + f * f + i * i - 1.0), abs(a * b + d * e + g * h),
                abs(a * c + d * f + g * i), abs(b * c + e * f + h * i))
    determinant = a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g)
    if error > ROTATION_TOLERANCE or determinant <= 0:
        raise InvalidArgumentError(
            f"{what} is not a rotation matrix (|MᵀM − I| = {error:.2g}, det = "
            f"{determinant:.3g}); send an orthonormal row-major 3x3 with det +1, "
            "or leave it empty for no rotation", reason="NOT_A_ROTATION")
    return _gram_schmidt(a, b, c, d, e, f, g, h, i)
