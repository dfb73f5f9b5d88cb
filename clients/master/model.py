"""The master arm's model: a 6R arm built programmatically in Pinocchio.

The operator holds a handle at the end of a small anthropomorphic arm: a turret (yaw), a
shoulder and an elbow (pitch), and a three-axis gimbal under the handle whose axes meet at
one point. At q = 0 the upper arm stands vertical, the forearm points forward along the base's
x axis and the hand frame is aligned with the base frame, a comfortable, non-singular pose.

Joints, axes and offsets (each offset from the previous joint, in its frame at q = 0):

| joint | axis | offset (m)        | link it moves                                   |
|-------|------|-------------------|-------------------------------------------------|
| 1     | z    | (0, 0, 0.10)      | turret: 0.30 kg, CoM (0, 0, 0.025)              |
| 2     | y    | (0, 0, 0.05)      | upper arm, 0.25 m: 0.25 kg, CoM (0, 0, 0.125)   |
| 3     | y    | (0, 0, 0.25)      | forearm, 0.25 m: 0.20 kg, CoM (0.125, 0, 0)     |
| 4     | x    | (0.25, 0, 0)      | gimbal ring: 0.05 kg, CoM at the joint          |
| 5     | y    | (0, 0, 0)         | gimbal ring: 0.05 kg, CoM at the joint          |
| 6     | z    | (0, 0, 0)         | handle: 0.10 kg, CoM at the grip                |
| hand  | --   | (0.05, 0, 0)      | the grip point: the hand frame (X, M)           |

Inertias about each CoM, diagonal in the link frame (kg*m^2): turret (4e-4, 4e-4, 3e-4); the
arm links as 0.25 m rods of 1 cm radius (m L²/12 across, m r²/2 along): upper arm
(1.30e-3, 1.30e-3, 1.25e-5), forearm (1.25e-5, 1.04e-3, 1.04e-3); gimbal rings 2e-5 each
axis; handle (2e-5, 5e-5, 5e-5). Every one satisfies the triangle inequality. No motor
armature or friction is modelled. Gravity is -9.81 m/s² along the base's z.

Limits: joints 1, 4 and 6 ±2.6 rad; the shoulder ±1.5 rad; the elbow ±1.3 rad (at ∓π/2 the
forearm lines up with the upper arm, a singularity); the gimbal's middle joint ±1.3 rad (at
±π/2 its outer axes align: gimbal lock). Motors: 2 N*m, 10 rad/s.

G_M(θ) is ``hand_pose(q)``: the hand frame (X, M) in the master's base frame. Units: rad, m,
kg, N*m; spatial vectors ``[linear; angular]``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from domain.robot_model.ik import IkResult, solve_ik

HAND_FRAME = "hand"
JOINT_NAMES = tuple(f"master_joint{i}" for i in range(1, 7))
GRAVITY = np.array([0.0, 0.0, -9.81])


@dataclass(frozen=True)
class LinkSpec:
    """One joint and the link it moves."""

    axis: str  # "x", "y" or "z", in the parent joint's frame at q = 0
    offset_m: tuple[float, float, float]  # joint origin from the previous joint's
    mass_kg: float
    com_m: tuple[float, float, float]  # in the joint frame
    inertia_kg_m2: tuple[float, float, float]  # diagonal, about the CoM
    limit_rad: float  # symmetric position limit


MASTER_LINKS: tuple[LinkSpec, ...] = (
    LinkSpec("z", (0.0, 0.0, 0.10), 0.30, (0.0, 0.0, 0.025), (4e-4, 4e-4, 3e-4), 2.6),
    LinkSpec("y", (0.0, 0.0, 0.05), 0.25, (0.0, 0.0, 0.125), (1.30e-3, 1.30e-3, 1.25e-5), 1.5),
    LinkSpec("y", (0.0, 0.0, 0.25), 0.20, (0.125, 0.0, 0.0), (1.25e-5, 1.04e-3, 1.04e-3), 1.3),
    LinkSpec("x", (0.25, 0.0, 0.0), 0.05, (0.0, 0.0, 0.0), (2e-5, 2e-5, 2e-5), 2.6),
    LinkSpec("y", (0.0, 0.0, 0.0), 0.05, (0.0, 0.0, 0.0), (2e-5, 2e-5, 2e-5), 1.3),
    LinkSpec("z", (0.0, 0.0, 0.0), 0.10, (0.05, 0.0, 0.0), (2e-5, 5e-5, 5e-5), 2.6),
)
HAND_OFFSET_M = (0.05, 0.0, 0.0)  # the grip point, from joint 6
MAX_TORQUE_NM = 2.0
MAX_VELOCITY_RAD_S = 10.0

_JOINT_TYPES = {"x": pin.JointModelRX, "y": pin.JointModelRY, "z": pin.JointModelRZ}


def build_master_model(links: tuple[LinkSpec, ...] = MASTER_LINKS,
                       hand_offset_m=HAND_OFFSET_M) -> pin.Model:
    """The Pinocchio model of the master arm, with an OP_FRAME named ``hand`` at the grip."""
    model = pin.Model()
    model.name = "master_arm"
    model.gravity = pin.Motion(GRAVITY, np.zeros(3))
    parent, frame = 0, 0
    for name, link in zip(JOINT_NAMES, links, strict=True):
        placement = pin.SE3(np.eye(3), np.array(link.offset_m))
        parent = model.addJoint(parent, _JOINT_TYPES[link.axis](), placement, name,
                                np.array([MAX_TORQUE_NM]), np.array([MAX_VELOCITY_RAD_S]),
                                np.array([-link.limit_rad]), np.array([link.limit_rad]))
        inertia = pin.Inertia(link.mass_kg, np.array(link.com_m), np.diag(link.inertia_kg_m2))
        model.appendBodyToJoint(parent, inertia, pin.SE3.Identity())
        frame = model.addJointFrame(parent, frame)
    model.addFrame(pin.Frame(HAND_FRAME, parent, frame,
                             pin.SE3(np.eye(3), np.array(hand_offset_m)), pin.OP_FRAME))
    return model


class MasterModel:
    """Kinematics and dynamics of the master arm for joint vectors ``q`` of shape (6,).

    Every method recomputes what it needs from its arguments; one instance is not
    thread-safe (it owns one ``pin.Data``)."""

    def __init__(self, model: pin.Model | None = None):
        self.model = build_master_model() if model is None else model
        self.data = self.model.createData()
        self._hand = self.model.getFrameId(HAND_FRAME)

    # -- facts ------------------------------------------------------------------------------
    @property
    def nq(self) -> int:
        return self.model.nq

    @property
    def home_q(self) -> np.ndarray:
        """The rest pose: q = 0 (upper arm up, forearm forward, hand aligned with the base)."""
        return np.zeros(self.model.nq)

    @property
    def lower_limits(self) -> np.ndarray:
        return self.model.lowerPositionLimit.copy()

    @property
    def upper_limits(self) -> np.ndarray:
        return self.model.upperPositionLimit.copy()

    def frame_id(self, name: str) -> int:
        """Pinocchio frame index of `name` (``hand`` for the grip)."""
        if not self.model.existFrame(name):
            raise KeyError(f"the master model has no frame named {name!r}")
        return self.model.getFrameId(name)

    # -- kinematics ---------------------------------------------------------------------------
    def hand_pose(self, q: np.ndarray) -> pin.SE3:
        """G_M(θ): the hand frame (X, M) in the master's base frame."""
        pin.framesForwardKinematics(self.model, self.data, np.asarray(q, float))
        return pin.SE3(self.data.oMf[self._hand])

    def hand_jacobian(self, q: np.ndarray, local: bool = False) -> np.ndarray:
        """6x6 Jacobian of the hand: ``[v; ω] = J q̇``, v the velocity of the grip point. Base
        axes (LOCAL_WORLD_ALIGNED) by default, the hand's own axes with ``local=True``."""
        reference = pin.LOCAL if local else pin.LOCAL_WORLD_ALIGNED
        return pin.computeFrameJacobian(self.model, self.data, np.asarray(q, float), self._hand,
                                        reference).copy()

    def solve_ik(self, target: pin.SE3, seed: np.ndarray, *, max_iterations: int = 50,
                 tolerance: float = 1e-7) -> IkResult:
        """Joint angles putting the hand at `target`, from `seed` (damped least squares within
        the joint limits: ``domain.robot_model.ik.solve_ik``)."""
        return solve_ik(self, target, seed, frame=HAND_FRAME, max_iterations=max_iterations,
                        position_tolerance=tolerance, rotation_tolerance=tolerance)

    # -- dynamics: tau = D(q) qdd + C(q, qd) qd + G(q) ----------------------------------------
    def mass_matrix(self, q: np.ndarray) -> np.ndarray:
        """D(q), the joint-space inertia (CRBA), symmetric."""
        upper = pin.crba(self.model, self.data, np.asarray(q, float))
        return np.triu(upper) + np.triu(upper, 1).T

    def coriolis_matrix(self, q: np.ndarray, qd: np.ndarray) -> np.ndarray:
        """The Coriolis/centrifugal matrix C(q, q̇) (Pinocchio's, with Ḋ − 2C skew)."""
        return pin.computeCoriolisMatrix(self.model, self.data, np.asarray(q, float),
                                         np.asarray(qd, float)).copy()

    def coriolis(self, q: np.ndarray, qd: np.ndarray) -> np.ndarray:
        """C(q, q̇)·q̇: the Coriolis and centrifugal torques, the paper's C(q, q̇)."""
        return self.coriolis_matrix(q, qd) @ np.asarray(qd, float)

    def gravity(self, q: np.ndarray) -> np.ndarray:
        """G(q): the torques that hold the arm still against gravity."""
        return pin.computeGeneralizedGravity(self.model, self.data,
                                             np.asarray(q, float)).copy()

    def inverse_dynamics(self, q: np.ndarray, qd: np.ndarray, qdd: np.ndarray) -> np.ndarray:
        """RNEA: the torques producing q̈ at (q, q̇)."""
        return pin.rnea(self.model, self.data, np.asarray(q, float), np.asarray(qd, float),
                        np.asarray(qdd, float)).copy()

    def forward_dynamics(self, q: np.ndarray, qd: np.ndarray, tau: np.ndarray) -> np.ndarray:
        """ABA: the acceleration that joint torques `tau` produce at (q, q̇)."""
        return pin.aba(self.model, self.data, np.asarray(q, float), np.asarray(qd, float),
                       np.asarray(tau, float)).copy()
