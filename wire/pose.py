"""`Pose`: a rigid transform (the child frame in the parent frame) without Pinocchio.

It has the attributes of a ``pinocchio.SE3`` that code reads (``rotation``, ``translation``,
``homogeneous``, ``inverse()``, ``*``), so code written for either reads both; the services
turn it into a ``pin.SE3`` where they compute with it (``services.common.convert``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


def _frozen(values, shape: tuple[int, ...], what: str) -> np.ndarray:
    array = np.array(values, dtype=float)  # a copy: the caller's array stays the caller's
    if array.shape != shape:
        raise ValueError(f"a pose's {what} must have shape {shape}, not {array.shape}")
    array.flags.writeable = False
    return array


@dataclass(frozen=True, eq=False)
class Pose:
    """``rotation`` (3x3) and ``translation`` (3,) as read-only float arrays. Acting on a point:
    ``rotation @ point + translation``."""

    rotation: np.ndarray
    translation: np.ndarray

    def __post_init__(self) -> None:
        object.__setattr__(self, "rotation", _frozen(self.rotation, (3, 3), "rotation"))
        object.__setattr__(self, "translation", _frozen(self.translation, (3,), "translation"))

    @classmethod
    def identity(cls) -> Pose:
        return cls(np.eye(3), np.zeros(3))

    @classmethod
    def from_homogeneous(cls, matrix) -> Pose:
        """From a 4x4 homogeneous matrix (its last row is not checked)."""
        matrix = np.asarray(matrix, dtype=float)
        if matrix.shape != (4, 4):
            raise ValueError(f"a homogeneous matrix is 4x4, not {matrix.shape}")
        return cls(matrix[:3, :3], matrix[:3, 3])

    @property
    def homogeneous(self) -> np.ndarray:
        """The 4x4 homogeneous matrix (a new, writable array)."""
        matrix = np.eye(4)
        matrix[:3, :3] = self.rotation
        matrix[:3, 3] = self.translation
        return matrix

    def inverse(self) -> Pose:
        return Pose(self.rotation.T, -self.rotation.T @ self.translation)

    def __mul__(self, other: Pose) -> Pose:
        """The composition ``self * other`` (other's frame expressed in self's parent)."""
        if not hasattr(other, "rotation") or not hasattr(other, "translation"):
            return NotImplemented
        return Pose(self.rotation @ other.rotation,
                    self.rotation @ other.translation + self.translation)

    def isclose(self, other, atol: float = 1e-9) -> bool:
        """True when `other` (a Pose or anything with ``rotation``/``translation``) is within
        `atol` element-wise."""
        return bool(np.allclose(self.rotation, np.asarray(other.rotation), atol=atol, rtol=0)
                    and np.allclose(self.translation, np.asarray(other.translation), atol=atol,
                                    rtol=0))

    def __reduce__(self):
        return (Pose, (self.rotation, self.translation))  # through __init__: read-only again

    def __repr__(self) -> str:
        return (f"Pose(rotation={self.rotation.tolist()}, "
                f"translation={self.translation.tolist()})")
