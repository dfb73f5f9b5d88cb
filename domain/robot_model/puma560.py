"""PUMA 560 parameters: the single source for the MuJoCo and Pinocchio models.

Every number describing the arm lives here. ``mjcf.py`` turns it into MJCF, MuJoCo and
Pinocchio both load that MJCF, so the two engines cannot disagree.

Conventions
-----------
* Standard (distal) Denavit-Hartenberg, as in Corke's ``mdl_puma560``:
  ``A_i = Rz(q_i) Tz(d_i) Tx(a_i) Rx(alpha_i)``; joint ``i`` rotates about ``z_{i-1}`` and DH
  frame ``i`` is fixed to link ``i``. Frame 0 is the robot base on the floor, frame 6 the flange.
* SI units throughout: metres, radians, kilograms, kg*m^2, N*m, N*m*s/rad.
* Inertial data (mass, centre of mass ``com`` and principal moments ``inertia`` about the centre
  of mass, both expressed in DH frame ``i``) are Armstrong, Khatib and Burdick (1986), "The
  explicit dynamic model and inertial parameters of the PUMA 560 arm", as re-expressed for the
  standard DH frames in Corke's ``mdl_puma560`` (params of 8/95), with the two deviations
  documented at ``LINK1_INERTIAL`` and ``LINK3_INERTIAL``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

# The element names every arm file uses (re-exported: look things up by name, never by index)
from domain.robot_model.names import (  # noqa: F401
    BASE_BODY,
    FLANGE_SITE,
    FORCE_SENSOR,
    FT_SITE,
    HOME_KEY,
    TOOL_BODY,
    TOOL_SITE,
    TORQUE_SENSOR,
)

Vec3 = tuple[float, float, float]


@dataclass(frozen=True)
class DH:
    """Standard DH parameters of one link (theta is the joint variable)."""

    d: float  # m, offset along z_{i-1}
    a: float  # m, length along x_i
    alpha: float  # rad, twist about x_i


@dataclass(frozen=True)
class Inertial:
    """Rigid-body inertia of one link, expressed in its DH frame."""

    mass: float  # kg
    com: Vec3  # m, centre of mass in DH frame i
    inertia: Vec3  # kg*m^2, principal moments about the COM along the axes of DH frame i


@dataclass(frozen=True)
class Drive:
    """Joint drive: limits and the motor reflected through the gearbox."""

    lower: float  # rad
    upper: float  # rad
    motor_inertia: float  # kg*m^2 at the motor shaft (Corke's Jm)
    gear_ratio: float  # motor turns per joint turn (Corke's G; the sign is the motor direction)
    motor_viscous: float  # N*m*s/rad at the motor shaft (Corke's B)
    max_torque: float  # N*m at the joint

    @property
    def armature(self) -> float:
        """Motor rotor inertia seen at the joint, Jm * G^2 (kg*m^2)."""
        return self.motor_inertia * self.gear_ratio**2

    @property
    def damping(self) -> float:
        """Motor viscous friction seen at the joint, B * G^2 (N*m*s/rad)."""
        return self.motor_viscous * self.gear_ratio**2


@dataclass(frozen=True)
class Link:
    """One moving link: body ``name``, driven by hinge ``joint`` and its motor ``actuator``."""

    name: str
    joint: str
    actuator: str
    dh: DH
    inertial: Inertial
    drive: Drive


@dataclass(frozen=True)
class Tool:
    """A solid cylindrical peg mounted on the flange, its axis along the flange z axis."""

    length: float  # m, flange to tool tip
    radius: float  # m
    mass: float  # kg

    def inertia(self) -> Vec3:
        """Principal moments of a solid cylinder about its centre (kg*m^2)."""
        transverse = self.mass * (3.0 * self.radius**2 + self.length**2) / 12.0
        axial = self.mass * self.radius**2 / 2.0
        return (transverse, transverse, axial)


def _deg(lower: float, upper: float) -> tuple[float, float]:
    return (math.radians(lower), math.radians(upper))


# --- Kinematics: standard DH (Corke mdl_puma560 with the base height of the real arm) ---------
BASE_HEIGHT = 0.6718  # m, floor to shoulder (d1)
UPPER_ARM_LENGTH = 0.4318  # m (a2)
SHOULDER_OFFSET = 0.15005  # m, lateral offset between upper arm and forearm (d3)
ELBOW_OFFSET = 0.0203  # m (a3)
FOREARM_LENGTH = 0.4318  # m, elbow to wrist centre (d4)

DH_TABLE: tuple[DH, ...] = (
    DH(d=BASE_HEIGHT, a=0.0, alpha=math.pi / 2),
    DH(d=0.0, a=UPPER_ARM_LENGTH, alpha=0.0),
    DH(d=SHOULDER_OFFSET, a=ELBOW_OFFSET, alpha=-math.pi / 2),
    DH(d=FOREARM_LENGTH, a=0.0, alpha=math.pi / 2),
    DH(d=0.0, a=0.0, alpha=-math.pi / 2),
    DH(d=0.0, a=0.0, alpha=0.0),
)

# --- Dynamics ------------------------------------------------------------------------------
# Armstrong et al. found no mass for link 1: it never appears in the joint torques because link 1
# only spins about its own y axis (= z0) and its COM lies on that axis. MuJoCo rejects massless
# moving bodies, so it gets a 1 kg placeholder on the axis (invisible to all joint torques) and
# Ixx = Izz = Iyy so the tensor is physically valid (only Iyy = 0.35, the published value,
# affects the joint dynamics).
LINK1_PLACEHOLDER_MASS = 1.0  # kg
LINK1_INERTIAL = Inertial(
    mass=LINK1_PLACEHOLDER_MASS, com=(0.0, 0.0, 0.0), inertia=(0.35, 0.35, 0.35)
)
# The tabulated link-3 moments (0.066, 0.086, 0.0125) violate the triangle inequality
# Ixx + Izz >= Iyy that any real body satisfies (MuJoCo refuses them). Ixx is raised to
# Iyy - Izz = 0.0735 (+11 %), the smallest relative change that makes the tensor valid.
LINK3_INERTIAL = Inertial(mass=4.8, com=(-0.0203, -0.0141, 0.070), inertia=(0.0735, 0.086, 0.0125))

INERTIALS: tuple[Inertial, ...] = (
    LINK1_INERTIAL,
    Inertial(mass=17.4, com=(-0.3638, 0.006, 0.2275), inertia=(0.13, 0.524, 0.539)),
    LINK3_INERTIAL,
    Inertial(mass=0.82, com=(0.0, 0.019, 0.0), inertia=(1.8e-3, 1.3e-3, 1.8e-3)),
    Inertial(mass=0.34, com=(0.0, 0.0, 0.0), inertia=(0.3e-3, 0.4e-3, 0.3e-3)),
    Inertial(mass=0.09, com=(0.0, 0.0, 0.032), inertia=(0.15e-3, 0.15e-3, 0.04e-3)),
)

# Joint limits from Wang & Chen (1991) and motor data (Jm, G, B) as in Corke's mdl_puma560;
# maximum joint torques from Armstrong, Khatib and Burdick (1986), Table 7.
# fmt: off
DRIVES: tuple[Drive, ...] = (
    #     limits (deg)     Jm (kg*m^2) G         B (N*m*s)  max torque (N*m)
    Drive(*_deg(-160, 160),  200e-6,  -62.6111,  1.48e-3,   97.6),
    Drive(*_deg(-45, 225),   200e-6,  107.815,   0.817e-3,  186.4),
    Drive(*_deg(-225, 45),   200e-6,  -53.7063,  1.38e-3,   89.4),
    Drive(*_deg(-110, 170),  33e-6,   76.0364,   71.2e-6,   24.2),
    Drive(*_deg(-100, 100),  33e-6,   71.923,    82.6e-6,   20.1),
    Drive(*_deg(-266, 266),  33e-6,   76.686,    36.7e-6,   21.3),
)
# fmt: on

LINKS: tuple[Link, ...] = tuple(
    Link(
        name=f"link{i}",
        joint=f"joint{i}",
        actuator=f"motor{i}",
        dh=dh,
        inertial=inertial,
        drive=drive,
    )
    for i, (dh, inertial, drive) in enumerate(
        zip(DH_TABLE, INERTIALS, DRIVES, strict=True), start=1
    )
)

JOINT_NAMES: tuple[str, ...] = tuple(link.joint for link in LINKS)
ACTUATOR_NAMES: tuple[str, ...] = tuple(link.actuator for link in LINKS)
BODY_NAMES: tuple[str, ...] = tuple(link.name for link in LINKS)
NUM_JOINTS = len(LINKS)

JOINT_LOWER = np.array([link.drive.lower for link in LINKS])  # rad
JOINT_UPPER = np.array([link.drive.upper for link in LINKS])  # rad
MAX_TORQUE = np.array([link.drive.max_torque for link in LINKS])  # N*m
# No published joint-speed figure: the bound is the simulated servo's own cap on every joint.
MAX_VELOCITY = np.full(len(LINKS), 1.0)  # rad/s

# --- Tool: a peg behind a wrist force/torque sensor -------------------------------------------
# An aluminium-sized peg (20 mm diameter, 100 mm long); the sensor itself is treated as massless.
TOOL = Tool(length=0.10, radius=0.010, mass=0.10)

# Ready pose: elbow up, tool pointing straight down with its tip at (0.645, -0.150, 0.500) m,
# 0.21 m above the hole of the peg-in-hole fixture. q2 + q3 + q5 = -180 deg with q4 = 0 keeps the
# tool vertical; q5 = -45 deg is far from the wrist singularity (q5 = 0), q3 = -170 deg from the
# elbow singularity (q3 = -87.3 deg), and every joint is well inside its limits.
HOME_Q_DEG = (0.0, 35.0, -170.0, 0.0, -45.0, 0.0)
HOME_Q = np.radians(HOME_Q_DEG)  # rad

# --- Simulation ----------------------------------------------------------------------------
TIMESTEP = 0.001  # s, 1 kHz to match the servo rate
GRAVITY = (0.0, 0.0, -9.81)  # m/s^2 (Pinocchio's default, stated explicitly for MuJoCo)


def dh_transform(theta: float, dh: DH) -> np.ndarray:
    """Homogeneous transform ``Rz(theta) Tz(d) Tx(a) Rx(alpha)`` (4x4, metres)."""
    ct, st = math.cos(theta), math.sin(theta)
    ca, sa = math.cos(dh.alpha), math.sin(dh.alpha)
    return np.array(
        [
            [ct, -st * ca, st * sa, dh.a * ct],
            [st, ct * ca, -ct * sa, dh.a * st],
            [0.0, sa, ca, dh.d],
            [0.0, 0.0, 0.0, 1.0],
        ]
    )
