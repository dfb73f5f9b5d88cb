"""Distance-to-singularity measures of the tool Jacobian.

The PUMA 560 loses a degree of freedom at the wrist (q5 = 0), the elbow (forearm in line with the
upper arm) and the shoulder (wrist centre over the joint-1 axis). A Cartesian command should be
scaled down or refused when ``min_singular_value`` drops below a threshold. The Jacobian mixes
m/rad (linear rows) and rad/rad (angular rows), so its singular values are in mixed units and
depend on the tool length; the thresholds below are tuned for the shipped 0.1 m peg.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from domain.robot_model.kinematics import ArmKinematics, JacobianFrame

# Smallest tool-Jacobian singular value below which Cartesian motion should be refused (q5 within
# about 2.3 deg of the wrist singularity), and below which it should be slowed down (about 10 deg).
SINGULAR_REFUSE_SIGMA = 0.02
SINGULAR_SLOWDOWN_SIGMA = 0.08


@dataclass(frozen=True)
class SingularityMeasures:
    manipulability: float  # sqrt(det(J J^T)), Yoshikawa's measure (0 at a singularity)
    min_singular_value: float  # smallest singular value of J (0 at a singularity)
    condition_number: float  # largest / smallest singular value (inf at a singularity)

    @property
    def near_singular(self) -> bool:
        """Too close to a singularity for Cartesian motion (see SINGULAR_REFUSE_SIGMA)."""
        return self.min_singular_value < SINGULAR_REFUSE_SIGMA

    def speed_scale(self) -> float:
        """Factor in [0, 1] for Cartesian speed: 1 far away, ramps to 0 at the refuse threshold."""
        span = SINGULAR_SLOWDOWN_SIGMA - SINGULAR_REFUSE_SIGMA
        return float(np.clip((self.min_singular_value - SINGULAR_REFUSE_SIGMA) / span, 0.0, 1.0))


def measures_from_jacobian(jacobian: np.ndarray) -> SingularityMeasures:
    """Singularity measures of a square 6x6 Jacobian."""
    sigma = np.linalg.svd(jacobian, compute_uv=False)
    smallest = float(sigma[-1])
    return SingularityMeasures(
        manipulability=float(np.prod(sigma)),
        min_singular_value=smallest,
        condition_number=float(sigma[0] / smallest) if smallest > 0.0 else float("inf"),
    )


def singularity_measures(kinematics: ArmKinematics, q: np.ndarray) -> SingularityMeasures:
    """Singularity measures of the world-frame tool Jacobian at ``q`` (rad).

    Singular values are frame-invariant, so WORLD and LOCAL Jacobians give the same numbers.
    """
    return measures_from_jacobian(kinematics.tool_jacobian(q, JacobianFrame.WORLD))
