"""Numerical inverse kinematics: damped least squares on SE(3), kept inside the joint limits.

Each iteration linearises the pose error ``log6(current^-1 * target)`` (expressed in the current
tool frame), takes a damped Gauss-Newton step, limits its size, applies it with ``pin.integrate``
and clamps to the joint limits. An arm with more joints than the six a pose needs (the FR3's
seven) spends the spare motion in the task's null space: toward its home pose, and away from a
limit it comes near, so the elbow does not wander as the tool is driven. Non-convergence is
reported in the result, never raised: the caller decides whether to use, retry or reject the
answer.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from domain.geometry import vector_norm
from domain.robot_model.kinematics import TOOL_FRAME, ArmKinematics

# Damping lambda^2 added to J J^T (Sugihara 2011): a floor that keeps steps finite at singularities
# plus a part growing with the squared pose error, so far from the target the solver takes cautious
# gradient-like steps and near it fast Gauss-Newton ones.
IK_DAMPING = 1e-6
IK_ERROR_DAMPING = 0.1  # per unit of |error|^2 (error mixes m and rad)
IK_MAX_ITERATIONS = 100
IK_POSITION_TOLERANCE = 1e-6  # m
IK_ROTATION_TOLERANCE = 1e-6  # rad
IK_MAX_STEP = 0.5  # rad, largest joint change per iteration (a trust region for far-away targets)
TASK_DIMENSION = 6  # a pose: joints beyond these are redundant
POSTURE_GAIN = 0.02  # per iteration, of the way back to home, in the null space
LIMIT_GAIN = 0.02  # rad per iteration, away from a limit the joint is at
LIMIT_MARGIN = 0.8  # of a joint's half range from its middle, before the limit push starts
# The posture task rests once the pose is this close (m, or rad), so the last iterations converge
# on the pose alone: the damped projector leaks a little of each posture step into the task.
POSTURE_UNTIL = 1e-4


@dataclass(frozen=True)
class IkResult:
    q: np.ndarray  # rad, the last iterate (within joint limits even when success is False)
    success: bool  # both errors below the tolerances
    iterations: int  # Gauss-Newton steps taken
    position_error: float  # m, distance between reached and target frame origins
    rotation_error: float  # rad, angle of the rotation between reached and target orientations


def pose_errors(reached: pin.SE3, target: pin.SE3) -> tuple[float, float]:
    """(position error in m, rotation error in rad) between two poses."""
    return (vector_norm(target.translation - reached.translation),
            vector_norm(pin.log3(reached.rotation.T @ target.rotation)))


def solve_ik(
    kinematics: ArmKinematics,
    target: pin.SE3,
    q_seed: np.ndarray,
    *,
    frame: str = TOOL_FRAME,
    max_iterations: int = IK_MAX_ITERATIONS,
    position_tolerance: float = IK_POSITION_TOLERANCE,
    rotation_tolerance: float = IK_ROTATION_TOLERANCE,
    damping: float = IK_DAMPING,
) -> IkResult:
    """Joint angles that put ``frame`` (default: the tool frame) at the world pose ``target``.

    Starts from ``q_seed`` (rad, clamped into the limits), so it converges to the solution branch
    nearest the seed: pass the current joint angles when tracking a moving target.
    """
    model, data = kinematics.model, kinematics.data
    frame_id = kinematics.frame_id(frame)
    lower, upper = model.lowerPositionLimit, model.upperPositionLimit
    q = _clamp(np.asarray(q_seed, float), lower, upper)

    iteration = 0
    while True:
        pin.framesForwardKinematics(model, data, q)
        reached = data.oMf[frame_id]
        position_error, rotation_error = pose_errors(reached, target)
        converged = position_error < position_tolerance and rotation_error < rotation_tolerance
        if converged or iteration >= max_iterations:
            return IkResult(q.copy(), converged, iteration, position_error, rotation_error)

        current_T_target = reached.actInv(target)
        error = pin.log6(current_T_target).vector
        # d(error)/dq = -Jlog6(target^-1 * current) J_local (Pinocchio's IK recipe).
        jacobian = pin.computeFrameJacobian(model, data, q, frame_id, pin.LOCAL)
        error_jacobian = -pin.Jlog6(current_T_target.inverse()) @ jacobian
        step_damping = damping + IK_ERROR_DAMPING * float(error @ error)
        step = _damped_step(error_jacobian, error, step_damping)
        # Joints resting on a limit and pushed outwards would just be clamped back, stalling the
        # solver: freeze them and let the remaining joints take up the error.
        blocked = ((q <= lower) & (step < 0.0)) | ((q >= upper) & (step > 0.0))
        if blocked.any():
            step = _damped_step(error_jacobian * ~blocked, error, step_damping)
        if model.nq > TASK_DIMENSION and max(position_error, rotation_error) > POSTURE_UNTIL:
            step += _null_space(error_jacobian, step_damping) @ _posture_step(
                q, kinematics.home_q, lower, upper)
        largest = abs(step).max()
        if largest > IK_MAX_STEP:
            step *= IK_MAX_STEP / largest
        q = _clamp(pin.integrate(model, q, step), lower, upper)
        iteration += 1


def _clamp(q: np.ndarray, lower: np.ndarray, upper: np.ndarray) -> np.ndarray:
    """np.clip's result, without its per-call overhead (this runs on every command)."""
    return np.minimum(np.maximum(q, lower), upper)


def _posture_step(q: np.ndarray, home: np.ndarray, lower: np.ndarray,
                  upper: np.ndarray) -> np.ndarray:
    """Where spare joint motion should go: back toward home, and away from a near limit."""
    middle, half = (upper + lower) / 2.0, (upper - lower) / 2.0
    offset = (q - middle) / half  # -1 at the lower limit, 1 at the upper
    nearness = np.clip((np.abs(offset) - LIMIT_MARGIN) / (1.0 - LIMIT_MARGIN), 0.0, 1.0)
    return POSTURE_GAIN * (home - q) - LIMIT_GAIN * nearness * np.sign(offset)


def _null_space(jacobian: np.ndarray, damping: float) -> np.ndarray:
    """Projector onto joint motions that (to first order) leave the task where it is."""
    return np.eye(jacobian.shape[1]) - jacobian.T @ np.linalg.solve(_gram(jacobian, damping),
                                                                    jacobian)


def _damped_step(jacobian: np.ndarray, error: np.ndarray, damping: float) -> np.ndarray:
    """Damped least-squares solution of ``jacobian @ step = -error``."""
    return -jacobian.T @ np.linalg.solve(_gram(jacobian, damping), error)


def _gram(jacobian: np.ndarray, damping: float) -> np.ndarray:
    """J Jᵀ + damping·I."""
    gram = jacobian @ jacobian.T
    gram.flat[::gram.shape[0] + 1] += damping  # the diagonal
    return gram
