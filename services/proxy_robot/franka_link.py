"""The hardware link to a Franka arm through libfranka (pylibfranka): ProxyRobot's Franka driver.

libfranka's 1 kHz joint-position loop runs on a thread of this process, in libfranka's joint
impedance controller. Each cycle it reads the robot's state and writes the next setpoint of the
same reference generator the simulated servo uses (``services/world/trajectory.py``): targets
arrive as straight segments, are chased under the arm's velocity and acceleration caps, and a
hold brakes at the acceleration cap. libfranka's own rate limiter sits after it.

Every cycle also goes to the station's segment when a mirror is given (arm_mirror.py): the
force sensor then reads the Franka's own estimate of the push on its tool, the cameras its
joints, and the emergency-stop band's stop latches the same hold as EmergencyStop. The
estimate comes from the joint torques the environment applies: the robot's own
(``tau_ext_hat_filtered``, from its torque sensors), or its joint-impedance spring's, K (q − q_d),
with the stiffness K the driver sets (JOINT_STIFFNESS).

Franka's robot modes and errors come through as they are: a reflex or a lost connection ends the
control loop, latches a hold and becomes the link's fault, with the robot's mode and libfranka's
error ("communication_constraints_violation"…), so ProxyRobot goes to FAULT and says why.
``release_hold()`` (ProxyRobot's Reset) then reconnects, runs libfranka's automatic error
recovery and starts the loop again where the arm stands.

Nothing here knows gRPC; errors are wire.errors, as every ArmLink raises them.
"""

from __future__ import annotations

import contextlib
import logging
import os
import threading
import time
from collections import deque

import numpy as np

from domain.robot_model.description import ArmDescription
from domain.robot_model.external_wrench import impedance_torques
from services.proxy_robot.arm_mirror import ArmMirror
from services.world.link import ArmSample, checked_duration, checked_joint_target
from services.world.sim import (
    GOAL_SMOOTHING_S,
    MAX_JOINT_ACCEL_RAD_PER_S2,
    MAX_JOINT_SPEED_RAD_PER_S,
)
from services.world.trajectory import JointReference
from wire.errors import FailedPreconditionError, UnavailableError

log = logging.getLogger(__name__)

CONTROL_PERIOD_S = 0.001  # libfranka's cycle
START_TIMEOUT_S = 5.0  # for the control loop's first cycle
STOP_TIMEOUT_S = 2.0
# A state older than this (the control loop gone quiet without an exception: a hung robot or a
# hung libfranka) makes every call UNAVAILABLE, as a stale world does.
STALE_AFTER_S = 0.25
APPLIED_KEPT = 100_000
# The joint impedance controller's stiffness (N·m/rad), set on connect for the "impedance"
# torque source, which reads this spring. franka-sim's joint servo has these gains whatever it
# is told. (With the "robot" source the robot keeps its own, libfranka's 3000…2000 default.)
JOINT_STIFFNESS = np.array([4500.0, 4500.0, 3500.0, 3500.0, 2000.0, 2000.0, 2000.0])
# Where the environment's joint torques come from: the robot's estimate, or the spring.
TORQUE_SOURCES = ("robot", "impedance")
# The spring's reading is low-passed with this time constant, as the robot filters its own
# (tau_ext_hat_filtered): moving, the servo's tracking error reads as a push in bursts of a
# few ms when setpoints come unevenly (docs/arms.md).
IMPEDANCE_FILTER_S = 0.03


def libfranka_exceptions(franka) -> tuple[type[BaseException], ...]:
    """What libfranka raises: FrankaException, and its network, control and command errors,
    which its Python binding derives from RuntimeError (as it does a bare "Net Exception")."""
    return (franka.FrankaException, RuntimeError)


@contextlib.contextmanager
def scheduling_kept():
    """Keep the calling thread's scheduling across a libfranka call. Where it may, libfranka
    raises the thread that connects or starts a control loop to SCHED_FIFO 99, even with
    RealtimeConfig.kIgnore; every thread started from it after would inherit that, above the
    station's own real-time priorities (services/runtime/priority.py) and everything else on
    the host."""
    policy, param = os.sched_getscheduler(0), os.sched_getparam(0)
    try:
        yield
    finally:
        if (os.sched_getscheduler(0), os.sched_getparam(0)) != (policy, param):
            os.sched_setscheduler(0, policy, param)


def franka_errors(errors) -> list[str]:
    """The names of the libfranka errors set in an ``Errors`` (its boolean flags)."""
    return [name for name in dir(errors)
            if not name.startswith("_") and getattr(errors, name) is True]


class FrankaArmLink:
    """ArmLink on a Franka arm at ``host`` (libfranka's port 1337). UnavailableError when it
    cannot be reached. Thread-safe."""

    def __init__(self, host: str, arm: ArmDescription, mirror: ArmMirror | None = None,
                 torque_source: str = "robot"):
        import pylibfranka  # here: only the Franka driver needs libfranka

        if torque_source not in TORQUE_SOURCES:
            raise ValueError(f"torque_source must be one of {TORQUE_SOURCES}")
        self._mirror = mirror
        self._torque_source = torque_source
        self._filtered_spring = np.zeros(arm.joint_count)  # the control thread's own
        self._franka = pylibfranka
        self._failures = libfranka_exceptions(pylibfranka)
        self.host = host
        self.arm = arm
        self.joint_lower, self.joint_upper = arm.lower.copy(), arm.upper.copy()
        if arm.joint_count != 7:
            raise FailedPreconditionError(
                f"the Franka driver drives a 7-joint Franka arm, and this station was started "
                f"for the {arm.name} ({arm.joint_count} joints): start it with --arm fr3",
                reason="WRONG_ARM")
        try:
            self._robot = connect(host)
            self._set_stiffness()
            state = self._robot.read_once()
        except self._failures as error:
            raise UnavailableError(f"cannot reach the Franka at {host}: {error}",
                                   reason="ROBOT_UNREACHABLE") from None
        self._lock = threading.Lock()
        q = np.array(state.q, float)
        self._reference = JointReference(
            q, np.minimum(arm.max_velocity, MAX_JOINT_SPEED_RAD_PER_S),
            np.full(7, MAX_JOINT_ACCEL_RAD_PER_S2), CONTROL_PERIOD_S, GOAL_SMOOTHING_S)
        self._q, self._dq = q, np.array(state.dq, float)
        self._sequence = 0
        self._sample_ns = time.time_ns()
        self._heard_ns = time.monotonic_ns()
        self._latched = False
        self._fault = ""
        self.mode = str(state.robot_mode)
        self.success_rate = 1.0  # libfranka's control_command_success_rate, latest
        # Control cycles from the latest hold() to the first setpoint written after it (the
        # braking one): what the e-stop costs in libfranka's time.
        self.hold_latency_cycles: int | None = None
        self._held_at_sequence: int | None = None
        # Command -> applied: from write_target() until the robot's commanded position (its
        # q_d, after libfranka's filter) moves off where it stood when the loop sent the first
        # setpoint written after it, in ns; the latest APPLIED_KEPT (make bench's
        # franka_command_1000).
        self.applied_ns: deque[int] = deque(maxlen=APPLIED_KEPT)
        self._written_ns: int | None = None  # a target written, no setpoint sent since
        self._in_flight: tuple[int, np.ndarray] | None = None  # (written ns, q_d at sending)
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None
        self._start_loop()

    # -- the control loop --------------------------------------------------------------------

    def _start_loop(self) -> None:
        started = threading.Event()
        self._stop.clear()
        self._thread = threading.Thread(target=self._run, args=(started,), name="franka-control",
                                        daemon=True)
        self._thread.start()
        if not started.wait(START_TIMEOUT_S):
            raise UnavailableError(f"the Franka at {self.host} did not start its control loop "
                                   f"within {START_TIMEOUT_S:.0f} s", reason="ROBOT_UNREACHABLE")

    def _run(self, started: threading.Event) -> None:
        franka = self._franka
        try:
            with scheduling_kept():
                control = self._robot.start_joint_position_control(
                    franka.ControllerMode.JointImpedance)
            while not self._stop.is_set():
                state, _period = control.readOnce()
                with self._lock:
                    commanded = np.array(state.q_d, float)
                    self._note_applied(commanded)
                    self._reference.step()
                    setpoint = self._reference.position.copy()
                    if self._written_ns is not None and self._in_flight is None:
                        self._in_flight = (self._written_ns, commanded)
                        self._written_ns = None
                    if self._held_at_sequence is not None:
                        self.hold_latency_cycles = self._sequence + 1 - self._held_at_sequence
                        self._held_at_sequence = None
                    self._q = np.array(state.q, float)
                    self._dq = np.array(state.dq, float)
                    self._sequence += 1
                    self._sample_ns = time.time_ns()
                    self._heard_ns = time.monotonic_ns()
                    self.mode = str(state.robot_mode)
                    self.success_rate = float(state.control_command_success_rate)
                    sample = self._sample() if self._mirror is not None else None
                started.set()
                control.writeOnce(franka.JointPositions(setpoint.tolist()))
                if sample is not None and self._mirror.publish(
                        sample, self._external_torques(state, commanded)):
                    self.hold()  # the band's stop
        except self._failures as error:
            self._fail(self._describe(error))
        except Exception as error:  # noqa: BLE001 (anything else ends the loop the same way)
            self._fail(f"the control loop failed: {error!r}")
        finally:
            started.set()

    def _set_stiffness(self) -> None:
        if self._torque_source == "impedance":
            self._robot.set_joint_impedance(JOINT_STIFFNESS.tolist())

    def _external_torques(self, state, commanded: np.ndarray) -> np.ndarray:
        if self._torque_source == "robot":
            return np.array(state.tau_ext_hat_filtered, float)
        spring = impedance_torques(JOINT_STIFFNESS, commanded, self._q)
        self._filtered_spring += (spring - self._filtered_spring) * (
            CONTROL_PERIOD_S / (IMPEDANCE_FILTER_S + CONTROL_PERIOD_S))
        return self._filtered_spring.copy()

    def _sample(self) -> ArmSample:
        """The latest state as an ArmSample (lock held)."""
        return ArmSample(self._sequence, self._sample_ns, self._q.copy(), self._dq.copy(),
                         self._reference.goal.copy(), self._latched, self._fault)

    def _note_applied(self, commanded: np.ndarray) -> None:
        """The robot's command has moved since the setpoint in flight was sent: applied."""
        if self._in_flight is not None:
            written_ns, before = self._in_flight
            if not np.array_equal(commanded, before):
                self.applied_ns.append(time.monotonic_ns() - written_ns)
                self._in_flight = None

    def _describe(self, error) -> str:
        """What libfranka said, with the errors the robot reports when it still answers. A
        network failure asks it nothing: pylibfranka waits out its 2 s receive timeout on a
        robot that is gone without letting go of the GIL, which would freeze the whole process
        (ProxyRobot's handlers, the hold's answer) for that long."""
        robot = self._robot
        named = []
        if robot is not None and not isinstance(error, self._franka.NetworkException):
            try:
                named = franka_errors(robot.read_once().last_motion_errors)
            except self._failures:
                pass
        return f"{error}" + (f" ({', '.join(named)})" if named else "")

    def _fail(self, why: str) -> None:
        with self._lock:
            if self._stop.is_set():
                return  # closing: not a fault
            self._fault = f"Franka ({self.mode}): {why}"
            self._latched = True
        log.error("the Franka's control loop ended: %s", why)

    # -- ArmLink -----------------------------------------------------------------------------

    def read_arm(self) -> ArmSample:
        with self._lock:
            self._check_heard()
            return self._sample()

    def write_target(self, joint_positions_rad: np.ndarray, duration_s: float = 0.0) -> None:
        target = checked_joint_target(joint_positions_rad, self.joint_lower, self.joint_upper)
        duration = checked_duration(duration_s)
        with self._lock:
            self._check_heard()
            if not self._latched:
                self._reference.set_goal(np.clip(target, self.joint_lower, self.joint_upper),
                                         duration)
                if self._written_ns is None:
                    self._written_ns = time.monotonic_ns()

    def hold(self) -> None:
        # The setpoint brakes from where it is: a Franka's commands must stay continuous.
        with self._lock:
            if self._latched:
                return
            self._latched = True
            self._held_at_sequence = self._sequence
            reference = self._reference
            reference.reset(reference.position.copy(), reference.velocity.copy())
            reference.set_goal(np.clip(reference.goal, self.joint_lower, self.joint_upper))

    def release_hold(self) -> None:
        with self._lock:
            fault = self._fault
        if fault:  # the loop ended: reconnect, recover the robot, run again where it stands
            self._join_loop()
            # The old connection goes first: the robot serves one client at a time, and a
            # second one would wait behind it for good.
            self._robot = None
            try:
                self._robot = connect(self.host)
                self._set_stiffness()
                with scheduling_kept():
                    self._robot.automatic_error_recovery()
                state = self._robot.read_once()
            except self._failures as error:
                raise UnavailableError(f"the Franka at {self.host} did not recover: {error}",
                                       reason="ROBOT_UNREACHABLE") from None
            with self._lock:
                self._q, self._dq = np.array(state.q, float), np.zeros(7)
                self._fault = ""
                self._latched = False
                self._reference.reset(self._q)
                self._heard_ns = time.monotonic_ns()
            self._start_loop()
            return
        with self._lock:
            if self._latched:
                self._latched = False
                self._reference.reset(self._reference.position.copy())

    def close(self) -> None:
        self._join_loop()
        robot, self._robot = self._robot, None  # libfranka disconnects when it goes
        if robot is not None:
            try:
                robot.stop()
            except self._failures:
                pass

    def _join_loop(self) -> None:
        self._stop.set()
        thread = self._thread
        if thread is not None and thread is not threading.current_thread():
            thread.join(STOP_TIMEOUT_S)

    def _check_heard(self) -> None:
        """UNAVAILABLE when the loop has gone quiet while it should run (lock held)."""
        if self._fault:
            return  # a fault is an answer: the state is the last one heard
        quiet_s = (time.monotonic_ns() - self._heard_ns) / 1e9
        if quiet_s > STALE_AFTER_S:
            raise UnavailableError(f"the Franka at {self.host} has not answered for "
                                   f"{quiet_s * 1e3:.0f} ms", reason="ROBOT_STALE")


def connect(host: str):
    """A libfranka connection to the Franka at ``host`` (no real-time kernel needed), leaving
    the calling thread's scheduling as it was."""
    import pylibfranka  # here: only the Franka driver needs libfranka

    with scheduling_kept():
        return pylibfranka.Robot(host, pylibfranka.RealtimeConfig.kIgnore)


def probe_franka(host: str) -> str:
    """Why the Franka at ``host`` cannot be driven ("" when it answers): a state read over a
    connection that is closed again."""
    import pylibfranka

    try:
        robot = connect(host)
        robot.read_once()
    except libfranka_exceptions(pylibfranka) as error:
        return f"cannot reach the Franka at {host} (libfranka, port 1337): {error}"
    del robot  # libfranka disconnects when the Robot goes
    return ""
