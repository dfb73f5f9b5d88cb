"""The simulated arm and its joint servo: what the world process steps once per millisecond.

Domain code only (no threads, no transport). Each ``step()``:

1. advances the joint reference toward the commanded target (``trajectory.JointReference``:
   at most MAX_JOINT_SPEED_RAD_PER_S and MAX_JOINT_ACCEL_RAD_PER_S2 per joint, so a big target
   change never jumps);
2. computes the servo torque: PD on (reference - q) plus the model's own feed-forward terms
   (bias forces qfrc_bias = gravity + Coriolis, inertia M * reference acceleration, motor viscous
   friction * reference velocity), clipped to each motor's ctrlrange;
3. steps MuJoCo (mj_step1 / mj_step2, so the feed-forward uses the current state);
4. checks the state and latches a hold with a fault if it is not finite.

A latched hold is a controlled stop (IEC 60204-1 category 2): the reference restarts from the
measured position and velocity and brakes at the acceleration cap; the arm then holds where it
stopped and later targets are ignored until ``release_hold()``.
"""

from __future__ import annotations

import time

import mujoco
import numpy as np

from domain.robot_model.description import ArmDescription, arm_description
from domain.robot_model.loader import load_mujoco_model, mujoco_ids
from services.world.link import ArmSample, RawWrench
from services.world.trajectory import JointReference
from wire.errors import InvalidArgumentError

MAX_JOINT_SPEED_RAD_PER_S = 1.0  # every joint (or its own bound, if lower): the reference never
# moves faster
GOAL_SMOOTHING_S = 0.005  # absorbs jitter in streamed targets (see trajectory.py)
MAX_JOINT_ACCEL_RAD_PER_S2 = 10.0  # every joint; from 1 rad/s a hold stops in 0.1 s and 0.05 rad
# Servo tuning: each joint is a critically damped second-order loop around the reference with
# this natural frequency, given the joint inertia at the home pose (armature included). 80 rad/s
# (13 Hz) stays far below the 1 kHz rate (omega * dt = 0.08) and stiff enough that 1 mrad of
# error already costs 26 N*m at the shoulder; at rest the feed-forward leaves no error at all.
SERVO_NATURAL_FREQUENCY_RAD_PER_S = 80.0
SERVO_DAMPING_RATIO = 1.0

_BAD_STATE_WARNINGS = (
    mujoco.mjtWarning.mjWARN_BADQPOS,
    mujoco.mjtWarning.mjWARN_BADQVEL,
    mujoco.mjtWarning.mjWARN_BADQACC,
)


class ArmSim:
    """The MuJoCo work cell with a joint servo on the arm, starting at the ``home`` keyframe.
    ``arm`` defaults to the selected arm, ``model`` to its work cell.

    Not thread-safe: one thread steps it and applies commands between steps.
    """

    def __init__(self, model: mujoco.MjModel | None = None, arm: ArmDescription | None = None):
        self.arm = arm or arm_description()
        self.model = model if model is not None else load_mujoco_model(self.arm.scene_xml)
        self.data = mujoco.MjData(self.model)
        self.ids = mujoco_ids(self.model, self.arm)
        self.period_s = float(self.model.opt.timestep)
        mujoco.mj_resetDataKeyframe(self.model, self.data, self.ids.home_key)
        mujoco.mj_forward(self.model, self.data)

        joints, dofs = self.ids.joints, self.ids.dofs
        self.joint_lower = self.model.jnt_range[joints, 0].copy()  # rad
        self.joint_upper = self.model.jnt_range[joints, 1].copy()  # rad
        self._torque_low = self.model.actuator_ctrlrange[self.ids.actuators, 0].copy()  # N*m
        self._torque_high = self.model.actuator_ctrlrange[self.ids.actuators, 1].copy()
        self._friction = self.model.dof_damping[dofs].copy()  # N*m*s/rad, the motors' viscous
        self.kp, self.kd = self._gains()

        self._reference = JointReference(
            self.joint_positions,
            np.minimum(self.arm.max_velocity, MAX_JOINT_SPEED_RAD_PER_S),
            np.full(self.arm.joint_count, MAX_JOINT_ACCEL_RAD_PER_S2),
            self.period_s,
            GOAL_SMOOTHING_S,
        )
        self._inertial = np.zeros(self.model.nv)  # scratch for M * reference acceleration
        self._accel = np.zeros(self.model.nv)
        self._last_good = (self.data.qpos.copy(), self.data.qvel.copy())
        self._warnings_seen = self._bad_state_warnings()
        self.steps = 0
        self.hold_latched = False
        self.fault = ""

    def _gains(self) -> tuple[np.ndarray, np.ndarray]:
        """PD gains (N*m/rad, N*m*s/rad) from the joint inertias at the current (home) pose."""
        inertia = np.zeros((self.model.nv, self.model.nv))
        mujoco.mj_fullM(self.model, self.data, inertia)
        joint_inertia = np.diag(inertia)[self.ids.dofs]
        omega = SERVO_NATURAL_FREQUENCY_RAD_PER_S
        return joint_inertia * omega**2, 2.0 * SERVO_DAMPING_RATIO * joint_inertia * omega

    # -- state ------------------------------------------------------------------------------

    @property
    def joint_positions(self) -> np.ndarray:
        """q (rad), a copy."""
        return self.data.qpos[self.ids.qpos].copy()

    @property
    def joint_velocities(self) -> np.ndarray:
        """dq/dt (rad/s), a copy."""
        return self.data.qvel[self.ids.dofs].copy()

    @property
    def target(self) -> np.ndarray:
        """The joint target the servo is heading for (rad), a copy."""
        return self._reference.goal.copy()

    @property
    def reference(self) -> np.ndarray:
        """Where the trajectory generator is now on its way to the target (rad), a copy."""
        return self._reference.position.copy()

    @property
    def time_s(self) -> float:
        """Simulated time since start (s)."""
        return float(self.data.time)

    def arm_sample(self, sample_time_ns: int | None = None) -> ArmSample:
        """The state after the last step, stamped ``sample_time_ns`` (default: now, wall clock)."""
        return ArmSample(
            sequence=self.steps,
            sample_time_ns=time.time_ns() if sample_time_ns is None else sample_time_ns,
            joint_positions_rad=self.joint_positions,
            joint_velocities_rad_per_s=self.joint_velocities,
            joint_targets_rad=self.target,
            hold_latched=self.hold_latched,
            fault=self.fault,
        )

    def wrench_sample(self, sample_time_ns: int | None = None) -> RawWrench:
        """The wrist sensor reading of the last step (N, N*m, in the sensor frame)."""
        return RawWrench(
            sequence=self.steps,
            sample_time_ns=time.time_ns() if sample_time_ns is None else sample_time_ns,
            force_n=self.data.sensordata[self.ids.wrist_force].copy(),
            torque_nm=self.data.sensordata[self.ids.wrist_torque].copy(),
        )

    # -- commands ---------------------------------------------------------------------------

    def set_target(self, joint_positions_rad: np.ndarray, duration_s: float = 0.0) -> bool:
        """Track a new joint target (rad), clipped into the joint limits, reached along a
        straight joint-space segment of `duration_s` (trajectory.SegmentedGoal). Returns False
        (and changes nothing) while a hold is latched. InvalidArgumentError on a wrong shape or
        NaN."""
        target = np.asarray(joint_positions_rad, dtype=float)
        joints = self.arm.joint_count
        if target.shape != (joints,) or not np.isfinite(target).all():
            raise InvalidArgumentError(
                f"a joint target needs {joints} finite angles in rad, got {target!r}")
        if self.hold_latched:
            return False
        self._reference.set_goal(np.clip(target, self.joint_lower, self.joint_upper), duration_s)
        return True

    def hold(self) -> None:
        """Latch a controlled stop: restart the reference from the measured position and
        velocity, brake at the acceleration cap and hold where it stops. Idempotent."""
        if self.hold_latched:
            return
        self.hold_latched = True
        self._reference.reset(self.joint_positions, self.joint_velocities)
        self._reference.set_goal(np.clip(self._reference.goal, self.joint_lower,
                                         self.joint_upper))

    def release_hold(self) -> None:
        """Clear the latch (and a fault). The target becomes the current position, so nothing
        starts moving. Without a latch it does nothing (it must not cut a move short)."""
        if not self.hold_latched:
            return
        self.hold_latched = False
        self.fault = ""
        self._reference.reset(self.joint_positions)

    # -- stepping ---------------------------------------------------------------------------

    def step(self) -> None:
        """Advance the servo and the physics by one period (1 ms)."""
        model, data, ids = self.model, self.data, self.ids
        self._reference.step()
        mujoco.mj_step1(model, data)  # positions and velocities: M and qfrc_bias for this state
        data.ctrl[ids.actuators] = self._servo_torque()
        mujoco.mj_step2(model, data)
        self.steps += 1
        self._check_state()

    def _servo_torque(self) -> np.ndarray:
        """PD on the reference plus the model's feed-forward, clipped to the motors (N*m)."""
        data, ids, ref = self.data, self.ids, self._reference
        self._accel[ids.dofs] = ref.acceleration
        mujoco.mj_mulM(self.model, data, self._inertial, self._accel)
        torque = (
            self.kp * (ref.position - data.qpos[ids.qpos])
            + self.kd * (ref.velocity - data.qvel[ids.dofs])
            + data.qfrc_bias[ids.dofs]
            + self._inertial[ids.dofs]
            + self._friction * ref.velocity
        )
        return np.clip(torque, self._torque_low, self._torque_high)

    def _bad_state_warnings(self) -> int:
        return sum(self.data.warning[w].number for w in _BAD_STATE_WARNINGS)

    def _check_state(self) -> None:
        """A non-finite state (MuJoCo resets the data when it sees one) is a fault: go back to
        the last good position at rest and latch a hold there."""
        data = self.data
        warnings = self._bad_state_warnings()
        finite = np.isfinite(data.qpos).all() and np.isfinite(data.qvel).all()
        if finite and warnings == self._warnings_seen:
            self._last_good[0][:] = data.qpos
            self._last_good[1][:] = data.qvel
            return
        self._warnings_seen = warnings
        data.qpos[:] = self._last_good[0]
        data.qvel[:] = 0.0
        mujoco.mj_forward(self.model, data)
        self.hold_latched = False  # re-latch from the restored state
        self.hold()
        self.fault = (f"simulation diverged at t={data.time:.3f} s (non-finite joint state); "
                      "holding the last good position: release the hold to continue")
