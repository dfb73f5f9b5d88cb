"""Kinematics and rigid-body dynamics of an arm on top of Pinocchio.

Units: joint angles rad, velocities rad/s, accelerations rad/s^2, torques N*m, lengths m.
Poses are ``pin.SE3`` (``.homogeneous`` gives the 4x4 matrix) of a frame in the world frame,
which is the robot base. Spatial vectors are ordered ``[linear; angular]``.
"""

from __future__ import annotations

import enum

import numpy as np
import pinocchio as pin

from domain.robot_model import names as n
from domain.robot_model.description import ArmDescription, arm_description
from domain.robot_model.loader import load_pinocchio_model

TOOL_FRAME = "tool_frame"  # frame added by ArmKinematics at flange * flange_T_tool


class JacobianFrame(enum.Enum):
    """Where a Jacobian's twist is expressed; both give the velocity of the frame's origin."""

    # World/base axes: the usual "geometric Jacobian".
    WORLD = pin.ReferenceFrame.LOCAL_WORLD_ALIGNED
    # Axes of the tool frame itself.
    LOCAL = pin.ReferenceFrame.LOCAL


def _frame_id(model: pin.Model, name: str) -> int:
    if not model.existFrame(name):
        raise KeyError(f"model has no frame named {name!r}")
    return model.getFrameId(name)


class ArmKinematics:
    """Forward kinematics, Jacobians and dynamics of one arm, for joint vectors ``q`` of shape
    (nq,).

    Holds its own copy of the Pinocchio ``model`` (the description, plus the tool frame) and one
    ``data`` (scratch buffers). Every method recomputes what it needs from its arguments, so
    calls are independent, but an instance is not thread-safe: give each thread its own.
    """

    def __init__(
        self,
        model: pin.Model | None = None,
        flange_T_tool: pin.SE3 | None = None,
        arm: ArmDescription | None = None,
    ) -> None:
        """``arm`` defaults to the selected arm, ``model`` to its ``arm.xml``, ``flange_T_tool``
        to its tool_point site (the description's, which GetArmInfo reports too)."""
        self.arm = arm or arm_description()
        model = pin.Model(load_pinocchio_model(self.arm) if model is None else model)
        self._flange = _frame_id(model, n.FLANGE_SITE)
        flange = model.frames[self._flange]
        if flange_T_tool is None:
            flange_T_tool = pin.SE3(self.arm.flange_T_tool)
        tool = pin.Frame(
            TOOL_FRAME,
            flange.parentJoint,
            self._flange,
            flange.placement * flange_T_tool,
            pin.OP_FRAME,
        )
        self._tool = model.addFrame(tool)
        self.model = model
        self.data = model.createData()

    # --- model facts --------------------------------------------------------------------------
    @property
    def nq(self) -> int:
        return self.model.nq

    @property
    def lower_limits(self) -> np.ndarray:
        """Joint lower limits (rad)."""
        return self.model.lowerPositionLimit.copy()

    @property
    def upper_limits(self) -> np.ndarray:
        """Joint upper limits (rad)."""
        return self.model.upperPositionLimit.copy()

    @property
    def torque_limits(self) -> np.ndarray:
        """Symmetric joint torque limits (N*m)."""
        return self.model.effortLimit.copy()

    @property
    def velocity_limits(self) -> np.ndarray:
        """Symmetric joint velocity limits (rad/s)."""
        return self.model.velocityLimit.copy()

    @property
    def home_q(self) -> np.ndarray:
        """The ``home`` keyframe of the MJCF (rad)."""
        return self.model.referenceConfigurations[n.HOME_KEY].copy()

    def within_limits(self, q: np.ndarray, tolerance: float = 0.0) -> bool:
        """True when every joint is inside its limits widened by ``tolerance`` (rad)."""
        q = np.asarray(q, float)
        return bool(
            np.all(q >= self.model.lowerPositionLimit - tolerance)
            and np.all(q <= self.model.upperPositionLimit + tolerance)
        )

    def frame_id(self, name: str) -> int:
        """Pinocchio frame index of a body, joint or site name (or ``TOOL_FRAME``)."""
        return _frame_id(self.model, name)

    # --- tool definition ----------------------------------------------------------------------
    @property
    def flange_T_tool(self) -> pin.SE3:
        """Tool frame relative to the flange."""
        return self.model.frames[self._flange].placement.actInv(
            self.model.frames[self._tool].placement
        )

    @flange_T_tool.setter
    def flange_T_tool(self, flange_T_tool: pin.SE3) -> None:
        self.model.frames[self._tool].placement = (
            self.model.frames[self._flange].placement * flange_T_tool
        )

    # --- kinematics ---------------------------------------------------------------------------
    def frame_pose(self, q: np.ndarray, name: str) -> pin.SE3:
        """World pose of a named frame at ``q``."""
        return self._pose(q, self.frame_id(name))

    def flange_pose(self, q: np.ndarray) -> pin.SE3:
        """World pose of the flange."""
        return self._pose(q, self._flange)

    def tool_pose(self, q: np.ndarray) -> pin.SE3:
        """World pose of the tool frame (flange * flange_T_tool)."""
        return self._pose(q, self._tool)

    def frame_jacobian(
        self, q: np.ndarray, name: str, expressed_in: JacobianFrame = JacobianFrame.WORLD
    ) -> np.ndarray:
        """6 x nq geometric Jacobian of a named frame: ``[v (m/s); w (rad/s)] = J @ qd``."""
        return self._jacobian(q, self.frame_id(name), expressed_in)

    def tool_jacobian(
        self, q: np.ndarray, expressed_in: JacobianFrame = JacobianFrame.WORLD
    ) -> np.ndarray:
        """6 x nq geometric Jacobian of the tool point: ``[v (m/s); w (rad/s)] = J @ qd``."""
        return self._jacobian(q, self._tool, expressed_in)

    def _jacobian(self, q: np.ndarray, frame: int, expressed_in: JacobianFrame) -> np.ndarray:
        q = np.asarray(q, float)
        reference = expressed_in.value
        return pin.computeFrameJacobian(self.model, self.data, q, frame, reference).copy()

    def _pose(self, q: np.ndarray, frame: int) -> pin.SE3:
        pin.framesForwardKinematics(self.model, self.data, np.asarray(q, float))
        return pin.SE3(self.data.oMf[frame])

    # --- dynamics (tau = D(q) qdd + C(q, qd) qd + G(q)) ----------------------------------------
    def gravity(self, q: np.ndarray) -> np.ndarray:
        """Joint torques that hold the arm still against gravity, G(q) (N*m)."""
        return pin.computeGeneralizedGravity(self.model, self.data, np.asarray(q, float)).copy()

    def mass_matrix(self, q: np.ndarray) -> np.ndarray:
        """Joint-space inertia D(q) (kg*m^2), including the reflected motor inertia (armature)."""
        upper = pin.crba(self.model, self.data, np.asarray(q, float))
        return np.triu(upper) + np.triu(upper, 1).T

    def coriolis(self, q: np.ndarray, qd: np.ndarray) -> np.ndarray:
        """Coriolis/centrifugal matrix C(q, qd) (N*m*s/rad): C @ qd is their torque."""
        return pin.computeCoriolisMatrix(
            self.model, self.data, np.asarray(q, float), np.asarray(qd, float)
        ).copy()

    def inverse_dynamics(self, q: np.ndarray, qd: np.ndarray, qdd: np.ndarray) -> np.ndarray:
        """Torques producing ``qdd`` at (q, qd) by RNEA (N*m), armature included.

        Joint damping and contact forces are not part of it (MuJoCo adds those itself).
        """
        return pin.rnea(
            self.model,
            self.data,
            np.asarray(q, float),
            np.asarray(qd, float),
            np.asarray(qdd, float),
        ).copy()
