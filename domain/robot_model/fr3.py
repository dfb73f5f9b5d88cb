"""Franka Research 3 (FR3): the numbers of its description file, ``arms/fr3/arm.xml``.

Kinematics, joint limits, velocity and torque bounds and link inertias are Franka's own, from
``franka_description`` (Apache-2.0) as shipped in franka-sim's ``fr3.urdf``: each joint's origin
is Franka's modified-DH table written the URDF way. The URDF carries no armature or damping:
damping is MuJoCo Menagerie's (1 N*m*s/rad on every joint). Franka publishes no rotor inertias:
the armature is the least that keeps a stiff 1 kHz joint servo stable on every link, franka-sim's
included (its position gains' damping, up to 450 N*m*s/rad, needs KD*dt/2 below the joint's
inertia: 0.3 kg*m^2 on joints 1-4, 0.15 on the wrist). With MuJoCo Menagerie's 0.1 the twist of
joints 1 and 3 about their shared axis (q2 = 0) diverges under that servo.

Home is Franka's own ready pose, the tool pointing straight down.
"""

from __future__ import annotations

import math

import numpy as np

from domain.robot_model.serial_chain import (
    ChainInertial,
    ChainJoint,
    ChainLink,
    SerialChain,
    rpy_xyz,
)

ARMATURE = (0.3, 0.3, 0.3, 0.3, 0.15, 0.15, 0.15)  # kg*m^2
DAMPING = 1.0  # N*m*s/rad
HALF_PI = math.pi / 2

# fmt: off
#        name          lower     upper    max vel  max torque
_JOINTS = (
    ("fr3_joint1", -2.7501,  2.7501,  2.62, 87.0),
    ("fr3_joint2", -1.7918,  1.7918,  2.62, 87.0),
    ("fr3_joint3", -2.9065,  2.9065,  2.62, 87.0),
    ("fr3_joint4", -3.0481, -0.1458,  2.62, 87.0),
    ("fr3_joint5", -2.8101,  2.8101,  5.26, 12.0),
    ("fr3_joint6",  0.54092, 4.5205,  4.18, 12.0),
    ("fr3_joint7", -3.0196,  3.0196,  5.26, 12.0),
)
# joint origin in the parent link: roll (rad), xyz (m)
_ORIGINS = (
    (0.0,       (0.0, 0.0, 0.333)),
    (-HALF_PI,  (0.0, 0.0, 0.0)),
    (HALF_PI,   (0.0, -0.316, 0.0)),
    (HALF_PI,   (0.0825, 0.0, 0.0)),
    (-HALF_PI,  (-0.0825, 0.384, 0.0)),
    (HALF_PI,   (0.0, 0.0, 0.0)),
    (HALF_PI,   (0.088, 0.0, 0.0)),
)
# mass (kg), centre of mass (m), inertia xx yy zz xy xz yz (kg*m^2), in the link's frame
_INERTIALS = (
    ChainInertial(2.9274653454, (0.0000004128, -0.0181251324, -0.0386035970),
                  (0.023927316485107913, 0.0224821613275756, 0.006350098258530016,
                   1.3317903455714081e-05, -0.00011404774918616684, -0.0019950320628240115)),
    ChainInertial(2.9355370338, (0.0031828864, -0.0743221644, 0.0088146084),
                  (0.041938946257609425, 0.02514514885014724, 0.06170214472888839,
                   0.00020257331521090626, 0.004077784227179924, -0.0042252158006570156)),
    ChainInertial(2.2449013699, (0.0407015686, -0.0048200565, -0.0289730823),
                  (0.02410142547240885, 0.01974053266708178, 0.019044494482244823,
                   0.002404694559042109, -0.002856269270114313, -0.002104212683891874)),
    ChainInertial(2.6155955791, (-0.0459100965, 0.0630492960, -0.0085187868),
                  (0.03452998321913202, 0.028881621933049058, 0.04125471171146641,
                   0.01322552265982813, 0.01015142998484113, -0.0009762833870704552)),
    ChainInertial(2.3271207594, (-0.0016039605, 0.0292536262, -0.0972965990),
                  (0.051610278463662895, 0.04787729713371481, 0.016423625579357254,
                   -0.005715173387783472, -0.0035673167625872135, 0.010673985108535986)),
    ChainInertial(1.8170376524, (0.0597131221, -0.0410294666, -0.0101692726),
                  (0.005412333594383447, 0.014058329545509979, 0.016080817924212554,
                   0.006193456360285834, 0.0014219289306117652, -0.0013140753741120031)),
    ChainInertial(0.6271432862, (0.0045225817, 0.0086261921, -0.0161633251),
                  (0.00021092389150104718, 0.00017718568002411474, 5.993190599659971e-05,
                   -2.433299114461931e-05, 4.564480393778983e-05, 8.744070223226438e-05)),
)
_RADII = (0.06, 0.06, 0.055, 0.055, 0.05, 0.045, 0.04)
# fmt: on

CHAIN = SerialChain(
    name="fr3",
    base_inertial=ChainInertial(2.3966, (-0.0172, 0.0004, 0.0745),
                                (0.009, 0.0115, 0.0085, 0.0, 0.002, 0.0)),
    base_radius=0.07,
    links=tuple(
        ChainLink(
            name=f"fr3_link{i}",
            origin=rpy_xyz(roll, 0.0, 0.0, xyz),
            joint=ChainJoint(name, lower, upper, velocity, torque, armature, DAMPING),
            inertial=inertial,
            radius=radius,
        )
        for i, ((name, lower, upper, velocity, torque), (roll, xyz), inertial, radius, armature)
        in enumerate(zip(_JOINTS, _ORIGINS, _INERTIALS, _RADII, ARMATURE, strict=True), start=1)
    ),
    flange=rpy_xyz(0.0, 0.0, 0.0, (0.0, 0.0, 0.107)),
    home_q=np.array([0.0, -math.pi / 4, 0.0, -3 * math.pi / 4, 0.0, math.pi / 2, math.pi / 4]),
)
