"""The assistance functions of the full paper (section II.3), applied to each master increment
before it reaches the arm. No gRPC here.

Order, for an increment (ΔX, ΔM) expressed in the session's mapping frame (BASE or TOOL):
1. space scaling (eq. 2): ΔX·s, ΔM from its XYZ Euler angles times s. This is the server's
   scaling, applied on top of whatever the master did: a master that scales sets it to 1.
2. floating tool frame: turning by ΔM about a point of interest p (tool frame) instead of the
   tool point adds (I − ΔM)·p to a TOOL increment, or (I − ΔM)·R·p to a BASE one.
3. planar or linear constraint on the tool point: the translation is projected onto the plane
   or the line through the anchor (the tool point when the constraint was set), correcting any
   drift away from it, so the constrained coordinate stays fixed.
4. force control axes: translations and rotations along the axes under force control are left
   to the force loop (removed from the operator's increment).
"""

from __future__ import annotations

import enum
from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from domain.geometry import scale_increment, vector_norm
from wire.errors import InvalidArgumentError


class ConstraintType(enum.Enum):
    PLANAR = 1
    LINEAR = 2


@dataclass(frozen=True)
class Constraint:
    type: ConstraintType
    axis: np.ndarray  # unit vector: the plane's normal or the line's direction
    frame: str  # "BASE" or "TOOL": the frame of `axis`
    anchor_m: np.ndarray | None = None  # a point of the plane or line, base frame


@dataclass(frozen=True)
class ForceControl:
    axes: np.ndarray  # six bools: x y z rx ry rz of the tool frame
    desired_force_n: np.ndarray
    desired_torque_nm: np.ndarray
    translation_gain_m_per_n_s: float  # A
    rotation_gain_rad_per_nm_s: float  # B


@dataclass(frozen=True)
class Assistance:
    mapping: str = "BASE"
    floating_point_m: np.ndarray | None = None  # tool frame; None: rotate about the tool point
    constraint: Constraint | None = None
    force_control: ForceControl | None = None
    translation_scale: float = 1.0
    rotation_scale: float = 1.0

    def validated(self) -> Assistance:
        if self.mapping not in ("BASE", "TOOL"):
            raise InvalidArgumentError("mapping must be BASE or TOOL", reason="BAD_MAPPING")
        for name in ("translation_scale", "rotation_scale"):
            value = getattr(self, name)
            if not np.isfinite(value) or value <= 0:
                raise InvalidArgumentError(f"{name} must be > 0", reason="BAD_SCALE")
        if self.constraint is not None:
            norm = vector_norm(self.constraint.axis)
            if not np.isfinite(norm) or norm < 1e-9:
                raise InvalidArgumentError("the constraint axis must be a non-zero vector",
                                           reason="BAD_AXIS")
        if self.force_control is not None:
            gains = (self.force_control.translation_gain_m_per_n_s,
                     self.force_control.rotation_gain_rad_per_nm_s)
            if not all(np.isfinite(g) and g >= 0 for g in gains):
                raise InvalidArgumentError("force-control gains must be finite and >= 0",
                                           reason="BAD_GAIN")
        return self


def _in_mapping_frame(vector_base: np.ndarray, mapping: str, tool: pin.SE3) -> np.ndarray:
    return vector_base if mapping == "BASE" else tool.rotation.T @ vector_base


def _to_base(vector: np.ndarray, mapping: str, tool: pin.SE3) -> np.ndarray:
    return vector if mapping == "BASE" else tool.rotation @ vector


def apply_assistance(assistance: Assistance, delta_position: np.ndarray,
                     delta_rotation: np.ndarray, tool: pin.SE3
                     ) -> tuple[np.ndarray, np.ndarray, bool]:
    """(ΔX, ΔM, modified) to send in the mapping frame, for the tool at pose `tool` (base
    frame: the last commanded target, so increments compose)."""
    mapping = assistance.mapping
    dx, dm = scale_increment(delta_position, delta_rotation, assistance.translation_scale,
                             assistance.rotation_scale)
    modified = False
    if assistance.floating_point_m is not None:
        point = assistance.floating_point_m
        lever = point if mapping == "TOOL" else tool.rotation @ point
        dx = dx + (np.eye(3) - dm) @ lever
    constraint = assistance.constraint
    if constraint is not None:
        axis_base = constraint.axis
        if constraint.frame == "TOOL":
            axis_base = tool.rotation @ axis_base
        axis_base = axis_base / vector_norm(axis_base)
        anchor = constraint.anchor_m if constraint.anchor_m is not None else tool.translation
        next_point = tool.translation + _to_base(dx, mapping, tool)
        offset = next_point - anchor
        if constraint.type == ConstraintType.PLANAR:
            correction = -(offset @ axis_base) * axis_base
        else:
            correction = -(offset - (offset @ axis_base) * axis_base)
        dx = dx + _in_mapping_frame(correction, mapping, tool)
        modified = vector_norm(correction) > 1e-12
    force = assistance.force_control
    if force is not None:
        keep_translation = ~force.axes[:3]
        keep_rotation = ~force.axes[3:]
        dx_tool = dx if mapping == "TOOL" else tool.rotation.T @ dx
        rotation_vector = pin.log3(dm)
        rotation_tool = rotation_vector if mapping == "TOOL" else tool.rotation.T @ rotation_vector
        dx_tool, rotation_tool = dx_tool * keep_translation, rotation_tool * keep_rotation
        dx = dx_tool if mapping == "TOOL" else tool.rotation @ dx_tool
        rotation_vector = rotation_tool if mapping == "TOOL" else tool.rotation @ rotation_tool
        dm = pin.exp3(rotation_vector)
        modified = modified or bool(force.axes.any())
    return dx, dm, modified
