"""Rotation helpers of the domain: angles, XYZ Euler angles, scaled increments, and how an
increment in the base or tool frame moves the tool.

The checks and repairs of values received from outside (`finite_vector`, `rotation_matrix`,
`gram_schmidt`), a fast 3-vector cross product (`cross3`) and a vector's norm that keeps the
interpreter lock (`vector_norm`) live in ``wire.checks``, shared with the clients; they are
re-exported here.
"""

from __future__ import annotations

import math

import numpy as np
import pinocchio as pin

from wire.checks import (
    ROTATION_TOLERANCE,
    cross3,
    finite_vector,
    gram_schmidt,
    rotation_matrix,
    vector_norm,
)

__all__ = [
    "ROTATION_TOLERANCE", "cross3", "euler_xyz", "finite_vector", "from_euler_xyz",
    "gram_schmidt", "moved_by", "rotation_angle", "rotation_matrix", "scale_increment",
    "vector_norm",
]


def rotation_angle(rotation: np.ndarray) -> float:
    """Angle of a rotation matrix, in radians (0..pi)."""
    cosine = (rotation[0, 0] + rotation[1, 1] + rotation[2, 2] - 1.0) / 2.0
    return math.acos(min(1.0, max(-1.0, cosine)))  # in floats: it runs on every command


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
    """Eq. 2 of the full paper: ΔX·s, and ΔM rebuilt from its XYZ Euler angles times s.
    At a rotation scale of 1, ΔM is kept as it is (the Euler round trip would only add
    rounding; it was a tenth of the DecisionServer's time per command)."""
    if rotation_scale == 1.0:
        return delta_position * translation_scale, delta_rotation
    return (delta_position * translation_scale,
            from_euler_xyz(euler_xyz(delta_rotation) * rotation_scale))


def moved_by(tool: pin.SE3, increment: pin.SE3, frame: str) -> pin.SE3:
    """The tool pose after an increment (ΔM, ΔX) in `frame`, eq. 1: TOOL, in the tool frame
    (tool · Δ); BASE, translated along the base axes and rotated about the tool point in base
    axes (R⁺ = ΔM · R, p⁺ = p + ΔX). ProxyRobot moves the arm so; the DecisionServer composes
    a backlog of increments by it."""
    if frame == "TOOL":
        return tool * increment
    if frame == "BASE":
        return pin.SE3(increment.rotation @ tool.rotation, tool.translation + increment.translation)
    raise ValueError(f"an increment moves the tool in the BASE or TOOL frame, not {frame!r}")
