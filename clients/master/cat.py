"""The client CAT functions that turn hand poses into commands (section II.4 of the full paper):
increments against a reference, space scaling (eq. 2) and the frames they are expressed in.

The paper computes, from the last reference (X, M) and the new hand pose (X⁺, M⁺),
ΔX = X⁺ − X and ΔM = Mᵀ M⁺. Those two are in different axes: ΔX in the master's base axes, ΔM
in the hand's own axes (a body-frame rotation). `IncrementFrame` makes the choice explicit:

- ``PAPER`` (the default): exactly the paper's ΔX = X⁺ − X, ΔM = Mᵀ M⁺.
- ``BASE``: both in base axes, ΔX = X⁺ − X and ΔM = M⁺ Mᵀ. This is what the slave's BASE
  (world) mapping applies (T⁺ = T + ΔX, R⁺ = ΔM R): the slave tool turns about the same base
  axes as the hand, whatever the hand's orientation.
- ``TOOL``: both in the hand's axes, (ΔM, ΔX) = (X, M)⁻¹ (X⁺, M⁺), i.e. ΔM = Mᵀ M⁺ and
  ΔX = Mᵀ (X⁺ − X). This is the slave's TOOL mapping (tool⁺ = tool · (ΔM, ΔX)), with the hand
  frame standing for the tool frame.

With the hand aligned to the base (M = I, the master's rest pose) the three agree. PAPER and
BASE differ once the hand is turned: for the BASE mapping use ``BASE``, for the TOOL mapping
``TOOL``.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from domain.geometry import scale_increment


class IncrementFrame(enum.Enum):
    """Axes of the increments a master arm computes (see the module docstring)."""

    PAPER = "paper"
    BASE = "base"
    TOOL = "tool"


@dataclass(frozen=True)
class Increment:
    """One command for the slave: the scaled increment, and what it was before scaling."""

    delta_position: np.ndarray  # m, (3,), scaled by eq. 2
    delta_rotation: np.ndarray  # 3x3 rotation, scaled by eq. 2
    raw_delta_position: np.ndarray  # m, the hand's own increment
    raw_delta_rotation: np.ndarray  # the hand's own rotation increment
    time_s: float  # when the hand pose it ends at was read
    frame: IncrementFrame


def hand_increment(reference: pin.SE3, hand: pin.SE3,
                   frame: IncrementFrame = IncrementFrame.PAPER
                   ) -> tuple[np.ndarray, np.ndarray]:
    """(ΔX, ΔM) from the reference (X, M) to the hand pose (X⁺, M⁺), in `frame`'s axes."""
    x, m = reference.translation, reference.rotation
    x_new, m_new = hand.translation, hand.rotation
    if frame is IncrementFrame.PAPER:
        return x_new - x, m.T @ m_new
    if frame is IncrementFrame.BASE:
        return x_new - x, m_new @ m.T
    if frame is IncrementFrame.TOOL:
        return m.T @ (x_new - x), m.T @ m_new
    raise ValueError(f"unknown increment frame {frame!r}")


def scale(delta_position: np.ndarray, delta_rotation: np.ndarray, translation_scale: float,
          rotation_scale: float) -> tuple[np.ndarray, np.ndarray]:
    """Eq. 2: ((X⁺ − X)·s, R_xyz(R_xyz⁻¹(ΔM)·s)), with separate scales for translation and
    rotation (``domain.geometry.scale_increment``). The Euler angles of a small ΔM
    are far from their singularity (|αy| = π/2), which is why eq. 2 scales increments, not
    poses."""
    if not (translation_scale > 0 and rotation_scale > 0):
        raise ValueError(f"scales must be positive, got {translation_scale}, {rotation_scale}")
    return scale_increment(np.asarray(delta_position, float), np.asarray(delta_rotation, float),
                           translation_scale, rotation_scale)
