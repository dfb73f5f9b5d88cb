"""The environment's wrench on an arm's tool, from the torques it puts on the joints.

An arm with no wrist F/T sensor still feels a push: in its joints. For a wrench W = (F, C) on a
frame of the last link (F and C in the frame's axes, C about its origin),

    τ_ext = Jᵀ W

with J that frame's Jacobian in its own axes (LOCAL). W is the damped least-squares solution,
(J Jᵀ + λ² I) W = J τ_ext: on a 7-joint arm what lies outside Jᵀ's range (a push on the elbow)
is no wrench at the tool and is left out; near a singularity the damping (DAMPING) keeps the
directions the arm cannot resist from being amplified.

Where τ_ext comes from:
- a torque-sensing arm estimates it itself (a Franka's ``tau_ext_hat_filtered``);
- a joint-impedance servo, τ = K (q_d − q) − D q̇ with gravity compensated, balances a push at
  rest with its spring: τ_ext = K (q − q_d). Moving, the servo's tracking error reads as a
  small push too (damping and inertia over K).
"""

from __future__ import annotations

import numpy as np

from domain.robot_model.kinematics import ArmKinematics, JacobianFrame

# λ of the damped least squares (see above), in the Jacobian's units (m, and rad/rad): far
# below the FR3's and the PUMA's smallest singular value away from a singularity.
DAMPING = 1e-3


def impedance_torques(stiffness: np.ndarray, commanded_q: np.ndarray,
                      measured_q: np.ndarray) -> np.ndarray:
    """The joint torques the environment applies to a joint-impedance servo at rest (N·m)."""
    return np.asarray(stiffness, float) * (np.asarray(measured_q, float)
                                           - np.asarray(commanded_q, float))


def wrench_at_frame(kinematics: ArmKinematics, q: np.ndarray, frame: str,
                    external_torques: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(force N, moment N·m) on `frame` from the environment, in its axes, about its origin."""
    jacobian = kinematics.frame_jacobian(q, frame, JacobianFrame.LOCAL)
    wrench = np.linalg.solve(jacobian @ jacobian.T + DAMPING**2 * np.eye(6),
                             jacobian @ np.asarray(external_torques, float))
    return wrench[:3], wrench[3:]
