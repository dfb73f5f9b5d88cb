"""A serial arm given the way its maker publishes it, and the MJCF body tree it makes.

Each link is placed the URDF way: the pose of its joint frame in the parent link's frame (the
joint turns about its own z axis), with its inertia in its own frame. Franka's and Universal
Robots' published descriptions both come in this form; ``fr3.py`` and ``ur5e.py`` hold their
numbers. ``mjcf.py`` writes the tree into each arm's ``arm.xml``.

Geometry is primitive: a capsule from each joint to the next, and a housing around each joint.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import mujoco
import numpy as np

Vec3 = tuple[float, float, float]


@dataclass(frozen=True)
class ChainJoint:
    """One revolute joint and its drive."""

    name: str
    lower: float  # rad
    upper: float  # rad
    max_velocity: float  # rad/s
    max_torque: float  # N*m
    armature: float  # kg*m^2, rotor inertia seen at the joint
    damping: float  # N*m*s/rad, viscous friction seen at the joint


@dataclass(frozen=True)
class ChainInertial:
    """Mass, centre of mass and inertia tensor about it, in the link's own frame."""

    mass: float  # kg
    com: Vec3  # m
    inertia: tuple[float, float, float, float, float, float]  # kg*m^2: xx yy zz xy xz yz


@dataclass(frozen=True)
class ChainLink:
    """A moving link: the pose of its joint frame in the parent's, its joint and its inertia."""

    name: str
    origin: np.ndarray  # 4x4, joint frame in the parent link's frame
    joint: ChainJoint
    inertial: ChainInertial
    radius: float  # m, of the primitive geometry


@dataclass(frozen=True)
class SerialChain:
    """Every number of one arm that its description file records."""

    name: str
    base_inertial: ChainInertial  # the fixed base (link 0)
    base_radius: float  # m
    links: tuple[ChainLink, ...]
    flange: np.ndarray  # 4x4, the flange in the last link's frame
    home_q: np.ndarray  # rad

    @property
    def joint_names(self) -> tuple[str, ...]:
        return tuple(link.joint.name for link in self.links)


def rpy_xyz(roll: float, pitch: float, yaw: float, xyz: Vec3) -> np.ndarray:
    """A URDF origin as a 4x4: ``Rz(yaw) Ry(pitch) Rx(roll)`` then the translation."""
    cr, sr = math.cos(roll), math.sin(roll)
    cp, sp = math.cos(pitch), math.sin(pitch)
    cy, sy = math.cos(yaw), math.sin(yaw)
    transform = np.eye(4)
    transform[:3, :3] = [
        [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
        [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
        [-sp, cp * sr, cp * cr],
    ]
    transform[:3, 3] = xyz
    return transform


def standard_dh(d: float, a: float, alpha: float) -> np.ndarray:
    """The constant part of a standard DH transform, ``Tz(d) Tx(a) Rx(alpha)``, as a 4x4."""
    transform = rpy_xyz(alpha, 0.0, 0.0, (a, 0.0, 0.0))
    transform[2, 3] = d
    return transform


def quaternion(rotation: np.ndarray) -> tuple[float, float, float, float]:
    """(w, x, y, z) of a rotation matrix."""
    quat = np.zeros(4)
    mujoco.mju_mat2Quat(quat, np.ascontiguousarray(rotation, float).ravel())
    return tuple(float(v) for v in quat)


def pose_attributes(transform: np.ndarray) -> dict[str, tuple[float, ...]]:
    """MJCF pos/quat of a 4x4 pose."""
    return {"pos": tuple(transform[:3, 3]), "quat": quaternion(transform[:3, :3])}


def forward_kinematics(chain: SerialChain, q: np.ndarray) -> np.ndarray:
    """The flange in the base frame at ``q`` (4x4), straight from the chain's numbers."""
    pose = np.eye(4)
    for link, angle in zip(chain.links, q, strict=True):
        pose = pose @ link.origin @ rpy_xyz(0.0, 0.0, float(angle), (0.0, 0.0, 0.0))
    return pose @ chain.flange
