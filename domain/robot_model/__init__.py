"""Simulated PUMA 560: parameters, generated MJCF, kinematics, dynamics and IK.

Pure domain code (no transport). Modules, one job each:

* ``puma560``     -- every robot parameter (DH, inertia, drives, tool, names, home pose)
* ``workspace``   -- layout of the work cell (table, peg-in-hole fixture, stereo cameras)
* ``mjcf``        -- generates ``puma560.xml`` and ``scene.xml`` from the two modules above
* ``loader``      -- loads the MuJoCo / Pinocchio models and resolves MuJoCo ids by name
* ``kinematics``  -- ``ArmKinematics``: poses, Jacobians, D(q), C(q, qd), G(q), RNEA
* ``ik``          -- damped least-squares inverse kinematics within the joint limits
* ``singularity`` -- distance-to-singularity measures for Cartesian motion
"""

from domain.robot_model.ik import IkResult, solve_ik
from domain.robot_model.kinematics import TOOL_FRAME, ArmKinematics, JacobianFrame
from domain.robot_model.loader import (
    MujocoIds,
    load_mujoco_model,
    load_pinocchio_model,
    mujoco_ids,
)
from domain.robot_model.singularity import SingularityMeasures, singularity_measures

__all__ = [
    "TOOL_FRAME",
    "IkResult",
    "JacobianFrame",
    "MujocoIds",
    "ArmKinematics",
    "SingularityMeasures",
    "load_mujoco_model",
    "load_pinocchio_model",
    "mujoco_ids",
    "singularity_measures",
    "solve_ik",
]
