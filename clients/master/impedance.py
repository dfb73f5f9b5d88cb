"""Impedance control of the master arm (eqs. 3 and 4) and force feedback τ_ff = Jᵀ F.

The master's rigid-body dynamics, with the motors' torque τ and the operator's hand torque τ_h:

    D(q) q̈ + C(q, q̇) q̇ + G(q) = τ + τ_h

Eq. 3 sets the motor torque to

    τ = α q̈ + β q̇ + C(q, q̇) q̇ + G(q) + τ_ff

so the motors cancel Coriolis, centrifugal and gravity effects and supply α q̈ + β q̇ of the
effort of moving the arm, and the arm's motion obeys

    (D(q) − α) q̈ = β q̇ + τ_ff + τ_h                                       (eq. 4)

The operator feels the reduced inertia D(q) − α (the impedance) plus whatever β q̇ and the force
feedback add. Signs, as eq. 3 writes them: β q̇ is added to the motor torque, so a positive β
assists motion (e.g. to cancel joint friction) and a negative β damps it; α = 0 leaves the
arm's whole inertia to the operator, α = D(q) cancels it (then eq. 3 is exactly inverse
dynamics plus β q̇ + τ_ff; the tests check it against ``pin.rnea``). α must leave D(q) − α
positive definite for the rendered arm to be stable. α and β are given as a scalar (times the
identity), six diagonal values, a 6x6 matrix, or a function of q returning a 6x6 matrix
(``FULL_INERTIA`` stands for D(q) itself).

Force feedback: τ_ff = Jᵀ F, with J the hand Jacobian in base axes (LOCAL_WORLD_ALIGNED, the
grip point's velocity and the hand's angular velocity) and F = [f; m] the wrench the motors
make the handle push on the operator's hand, in the master's base axes about the grip point.
For a small joint motion δq the virtual work is τ_ffᵀ δq = f·δX + m·δθ (the tests check this
numerically). `slave_wrench_to_master` maps the slave's measured wrench onto F.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from clients.master.cat import IncrementFrame
from clients.master.model import MasterModel

Gain = float | np.ndarray | Callable[[np.ndarray], np.ndarray]
FULL_INERTIA = "D(q)"  # alpha = D(q): the operator feels no inertia at all


@dataclass(frozen=True)
class ImpedanceTorques:
    """Eq. 3's terms at one instant (N*m, each (6,)); ``total`` is what the motors apply."""

    total: np.ndarray
    inertia: np.ndarray  # α q̈
    damping: np.ndarray  # β q̇
    coriolis: np.ndarray  # C(q, q̇) q̇
    gravity: np.ndarray  # G(q)
    feedback: np.ndarray  # τ_ff = Jᵀ F


def _matrix(gain, q: np.ndarray, model: MasterModel, what: str) -> np.ndarray:
    n = model.nq
    if isinstance(gain, str):
        if gain != FULL_INERTIA:
            raise ValueError(f"{what}: the only named gain is {FULL_INERTIA!r}, not {gain!r}")
        return model.mass_matrix(q)
    value = gain(q) if callable(gain) else gain
    array = np.asarray(value, dtype=float)
    if array.ndim == 0:
        return float(array) * np.eye(n)
    if array.shape == (n,):
        return np.diag(array)
    if array.shape == (n, n):
        return array
    raise ValueError(f"{what} must be a scalar, {n} values or a {n}x{n} matrix, "
                     f"got shape {array.shape}")


class ImpedanceController:
    """Eq. 3 on a `MasterModel` with tunable α (inertia compensation) and β (velocity term)."""

    def __init__(self, model: MasterModel, alpha: Gain | str = 0.0, beta: Gain = 0.0):
        self.model = model
        self.alpha = alpha
        self.beta = beta

    def alpha_matrix(self, q: np.ndarray) -> np.ndarray:
        return _matrix(self.alpha, q, self.model, "alpha")

    def beta_matrix(self, q: np.ndarray) -> np.ndarray:
        return _matrix(self.beta, q, self.model, "beta")

    def rendered_inertia(self, q: np.ndarray) -> np.ndarray:
        """D(q) − α: the inertia the operator feels (eq. 4)."""
        return self.model.mass_matrix(q) - self.alpha_matrix(q)

    def feedback_torques(self, q: np.ndarray, wrench: np.ndarray) -> np.ndarray:
        """τ_ff = Jᵀ F for a wrench F = [f; m] on the hand (base axes, about the grip)."""
        wrench = np.asarray(wrench, dtype=float)
        if wrench.shape != (6,):
            raise ValueError(f"the wrench needs 6 values [f; m], got shape {wrench.shape}")
        return self.model.hand_jacobian(q).T @ wrench

    def torques(self, q: np.ndarray, qd: np.ndarray, qdd: np.ndarray,
                wrench: np.ndarray | None = None) -> ImpedanceTorques:
        """The motor torques of eq. 3 at (q, q̇, q̈), with force feedback from `wrench` (None:
        none)."""
        q, qd, qdd = (np.asarray(v, dtype=float) for v in (q, qd, qdd))
        inertia = self.alpha_matrix(q) @ qdd
        damping = self.beta_matrix(q) @ qd
        coriolis = self.model.coriolis(q, qd)
        gravity = self.model.gravity(q)
        feedback = (np.zeros(self.model.nq) if wrench is None
                    else self.feedback_torques(q, wrench))
        return ImpedanceTorques(inertia + damping + coriolis + gravity + feedback, inertia,
                                damping, coriolis, gravity, feedback)

    def closed_loop_acceleration(self, q: np.ndarray, qd: np.ndarray,
                                 hand_torque: np.ndarray,
                                 wrench: np.ndarray | None = None) -> np.ndarray:
        """q̈ from eq. 4, (D − α) q̈ = β q̇ + τ_ff + τ_h: how the arm moves under the
        operator's joint torque `hand_torque` while the motors apply eq. 3."""
        q, qd = np.asarray(q, dtype=float), np.asarray(qd, dtype=float)
        feedback = (np.zeros(self.model.nq) if wrench is None
                    else self.feedback_torques(q, wrench))
        rhs = self.beta_matrix(q) @ qd + feedback + np.asarray(hand_torque, dtype=float)
        return np.linalg.solve(self.rendered_inertia(q), rhs)


def slave_wrench_to_master(force_tool: np.ndarray, torque_tool: np.ndarray, *,
                           frame: IncrementFrame, slave_tool_rotation: np.ndarray | None = None,
                           hand_rotation: np.ndarray | None = None, force_scale: float = 1.0,
                           torque_scale: float = 1.0) -> np.ndarray:
    """The wrench F = [f; m] for the master's hand (base axes, about the grip) from the
    slave's measured one (the environment's wrench on the tool, tool axes, about the tool point:
    a CommandAck's ``tool_wrench``).

    The mapping mirrors the increments: the axes in which the master's motion is sent are the
    axes in which the slave's force comes back.

    - ``BASE`` and ``PAPER`` increments move the slave along its base axes as the hand moves
      along the master's base axes, so the two bases are identified: F = R_tool · F_t, with
      `slave_tool_rotation` the slave tool's orientation in its base (the ack's ``tool_pose``).
    - ``TOOL`` increments identify the hand frame with the tool frame: F = M · F_t, with
      `hand_rotation` the hand's orientation M in the master's base.

    The tool point corresponds to the grip point, so moments are carried over as they are.

    Scaling: with the slave moving s times the hand's motion, F = s·F_slave makes the operator
    do the same work as the slave (power f·ẋ_hand = f_slave·ẋ_slave), so the coupling stays
    passive; `MasterArm` therefore uses force_scale = s and torque_scale = the rotation scale
    unless told otherwise. Both scales multiply the mapped wrench.
    """
    force = np.asarray(force_tool, dtype=float)
    torque = np.asarray(torque_tool, dtype=float)
    if frame is IncrementFrame.TOOL:
        if hand_rotation is None:
            raise ValueError("the TOOL mapping needs the hand's rotation")
        rotation = np.asarray(hand_rotation, dtype=float)
    else:
        if slave_tool_rotation is None:
            raise ValueError("the BASE mapping needs the slave tool's rotation (the ack's "
                             "tool_pose)")
        rotation = np.asarray(slave_tool_rotation, dtype=float)
    return np.concatenate([force_scale * (rotation @ force), torque_scale * (rotation @ torque)])
