"""Universal Robots UR5e: the numbers of its description file, ``arms/ur5e/arm.xml``.

Kinematics are Universal Robots' published standard-DH table for the UR5e; masses and centres of
mass are UR's published dynamics table (both in DH frame i). UR publishes no inertia tensors: the
moments are ``ur_description``'s cylinder approximations, about each link's centre of mass.
Joint limits, velocity (180 deg/s) and torque bounds are UR's data sheet. Armature and damping are
MuJoCo Menagerie's ``universal_robots_ur5e`` armature (0.1 kg*m^2) with 1 N*m*s/rad of damping.

Each link's joint frame is DH frame i-1 (the joint turns about its z axis), so the link after it
sits at the constant part of the DH transform, and inertias given in DH frame i go through it.
Joint 1 sits d1 up, on top of the base drum, as in UR's own URDF (Tz and Rz commute, so the
kinematics are the table's).
Home has the tool pointing straight down in front of the base.
"""

from __future__ import annotations

import math

import numpy as np

from domain.robot_model.serial_chain import (
    ChainInertial,
    ChainJoint,
    ChainLink,
    SerialChain,
    standard_dh,
)

ARMATURE = 0.1  # kg*m^2
DAMPING = 1.0  # N*m*s/rad
HALF_PI = math.pi / 2
TWO_PI = 2 * math.pi

# fmt: off
#     d (m)    a (m)    alpha (rad)
DH_TABLE = (
    (0.1625,  0.0,     HALF_PI),
    (0.0,    -0.425,   0.0),
    (0.0,    -0.3922,  0.0),
    (0.1333,  0.0,     HALF_PI),
    (0.0997,  0.0,    -HALF_PI),
    (0.0996,  0.0,     0.0),
)
#        name                   lower     upper    max vel  max torque
_JOINTS = (
    ("shoulder_pan_joint",  -TWO_PI,  TWO_PI,  math.pi, 150.0),
    ("shoulder_lift_joint", -TWO_PI,  TWO_PI,  math.pi, 150.0),
    ("elbow_joint",         -math.pi, math.pi, math.pi, 150.0),
    ("wrist_1_joint",       -TWO_PI,  TWO_PI,  math.pi, 28.0),
    ("wrist_2_joint",       -TWO_PI,  TWO_PI,  math.pi, 28.0),
    ("wrist_3_joint",       -TWO_PI,  TWO_PI,  math.pi, 28.0),
)
# mass (kg), centre of mass (m) and principal moments (kg*m^2), in DH frame i
_MASSES = (
    (3.761, (0.0, -0.02561, 0.00193),  (0.010267, 0.010267, 0.00666)),
    (8.058, (0.2125, 0.0, 0.11336),    (0.015107, 0.133886, 0.133886)),
    (2.846, (0.15, 0.0, 0.0265),       (0.004095, 0.031178, 0.031178)),
    (1.37,  (0.0, -0.0018, 0.01634),   (0.002560, 0.002560, 0.002194)),
    (1.3,   (0.0, 0.0018, 0.01634),    (0.002560, 0.002560, 0.002194)),
    (0.365, (0.0, 0.0, -0.001159),     (0.000098, 0.000098, 0.000132)),
)
_RADII = (0.06, 0.055, 0.045, 0.04, 0.04, 0.035)
# fmt: on


def _in_joint_frame(dh: np.ndarray, mass: float, com, moments) -> ChainInertial:
    """An inertia given in DH frame i, expressed in the link's joint frame (DH frame i-1)."""
    rotation = dh[:3, :3]
    tensor = rotation @ np.diag(moments) @ rotation.T
    centre = dh[:3, :3] @ np.asarray(com, float) + dh[:3, 3]
    return ChainInertial(mass, tuple(float(c) for c in centre),
                         (tensor[0, 0], tensor[1, 1], tensor[2, 2],
                          tensor[0, 1], tensor[0, 2], tensor[1, 2]))


# The constant part of each link's DH transform, after its joint; joint 1's d1 comes before it.
_SHOULDER_HEIGHT = DH_TABLE[0][0]
_FIXED = (standard_dh(0.0, *DH_TABLE[0][1:]),) + tuple(standard_dh(*row) for row in DH_TABLE[1:])

CHAIN = SerialChain(
    name="ur5e",
    base_inertial=ChainInertial(4.0, (0.0, 0.0, 0.05), (0.0044, 0.0044, 0.0072, 0.0, 0.0, 0.0)),
    base_radius=0.075,
    links=tuple(
        ChainLink(
            name=f"ur5e_link{i}",
            origin=standard_dh(_SHOULDER_HEIGHT, 0.0, 0.0) if i == 1 else _FIXED[i - 2],
            joint=ChainJoint(name, lower, upper, velocity, torque, ARMATURE, DAMPING),
            inertial=_in_joint_frame(_FIXED[i - 1], *masses),
            radius=radius,
        )
        for i, ((name, lower, upper, velocity, torque), masses, radius)
        in enumerate(zip(_JOINTS, _MASSES, _RADII, strict=True), start=1)
    ),
    flange=_FIXED[-1],
    home_q=np.array([math.pi, -HALF_PI, HALF_PI, -HALF_PI, -HALF_PI, 0.0]),
)
