"""From what a wrist F/T sensor measures to the contact wrench at the tool (no transport code).

The sensor reports the wrench its mounting (the flange side) applies to the tool side,
in the sensor frame, about the sensor origin. The tool hangs from it, so at rest that reading
is the tool's weight, and in contact it also carries the environment's push. What the operator
should feel is the environment's push alone, where it acts:

    F_ext = −F_s − m g_s                 (force on the tool from the environment, sensor axes)
    C_ext = −C_s − c × (m g_s)           (its moment about the sensor origin)
    F_t   = R_stᵀ F_ext                  (tool axes)
    C_t   = R_stᵀ (C_ext − p_st × F_ext) (about the tool point)

with g_s gravity in sensor axes, m and c the tool's mass and centre of mass (sensor frame), and
(R_st, p_st) the tool frame in the sensor frame. Tare subtracts a bias from (F_t, C_t).

The papers' sensor is two plates joined by elastic links: it measures the deflection of one
plate against the other and turns it into F_t = K_l ΔT_t, C_t = K_r ΔM_t. The simulated sensor
(MuJoCo's force/torque sensor on a weld) is infinitely stiff: it reports the constraint wrench
directly, with no deflection, so K_l and K_r do not appear; a real sensor's calibration matrix
plays their part. The deflection view is still the right one for the DecisionServer's active
compliance, ΔT = A·F_t and ΔM = B·C_t (A and B act like the inverse stiffness of a virtual
spring), which is where the model lives in this framework.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from domain.geometry import cross3
from domain.robot_model import puma560

GRAVITY_WORLD = np.array([0.0, 0.0, -9.81])  # m/s², as in the simulation


@dataclass(frozen=True)
class Payload:
    """What hangs on the sensor: mass in kg and centre of mass in the sensor frame, in m."""

    mass_kg: float
    center_of_mass_m: np.ndarray


def default_payload() -> Payload:
    """The shipped peg: a uniform cylinder along the sensor's z axis."""
    tool = puma560.TOOL
    return Payload(tool.mass, np.array([0.0, 0.0, tool.length / 2.0]))


@dataclass(frozen=True)
class ContactWrench:
    """Force in N and moment in N·m on the tool from the environment, tool axes, tool point."""

    force_n: np.ndarray
    torque_nm: np.ndarray


def contact_wrench(force_n: np.ndarray, torque_nm: np.ndarray, sensor_rotation: np.ndarray,
                   sensor_to_tool: pin.SE3, payload: Payload,
                   bias: ContactWrench | None = None) -> ContactWrench:
    """The contact wrench at the tool point from one raw reading (see the module docstring).

    sensor_rotation: the sensor frame's axes in the world (3x3), for the weight; identity if the
    sensor's orientation is unknown and the weight is to be tared instead.
    """
    weight = payload.mass_kg * (sensor_rotation.T @ GRAVITY_WORLD)
    force_ext = -force_n - weight
    torque_ext = -torque_nm - cross3(payload.center_of_mass_m, weight)
    rotation, offset = sensor_to_tool.rotation, sensor_to_tool.translation
    force = rotation.T @ force_ext
    torque = rotation.T @ (torque_ext - cross3(offset, force_ext))
    if bias is not None:
        force, torque = force - bias.force_n, torque - bias.torque_nm
    return ContactWrench(force, torque)


def wrist_reading(force_ext_n: np.ndarray, torque_ext_nm: np.ndarray,
                  sensor_rotation: np.ndarray, payload: Payload) -> tuple[np.ndarray, np.ndarray]:
    """What a wrist sensor reads (force, moment: sensor axes, about its origin) when the
    environment pushes on the tool with (force_ext_n, torque_ext_nm) (sensor axes, about the
    sensor origin) and the payload hangs from it: the inverse of contact_wrench's first step.
    For an arm that estimates its external wrench instead of measuring it at the wrist
    (services/proxy_robot/arm_mirror.py), so the force sensor's own model applies unchanged."""
    weight = payload.mass_kg * (sensor_rotation.T @ GRAVITY_WORLD)
    return -force_ext_n - weight, -torque_ext_nm - cross3(payload.center_of_mass_m, weight)
