"""ProxyRobotCore: the software proxy of the arm, with no transport code.

It keeps the status machine, the tool frame and the joint target; turns incremental joint and
Cartesian moves (eq. 1 of the full paper) into joint targets for the servo through the hardware
link; and publishes state samples and events. Increments apply to the current *target*, so
commands sent faster than the arm moves add up instead of being lost.

Cartesian increments, by frame (the increment is (ΔM, ΔX) as a rigid transform):
- TOOL:  tool⁺ = tool · (ΔM, ΔX)   — eq. 1's tool mapping: translate along the tool's own axes,
  rotate about the tool point in tool axes;
- WRIST: flange⁺ = flange · (ΔM, ΔX), the tool follows rigidly;
- BASE:  translate along the base axes and rotate about the tool point in base axes
  (R⁺ = ΔM · R, p⁺ = p + ΔX).

Each target goes to the servo once, with the segment's duration to spread it over
(segment_timing.py); the servo writes the setpoints along it. Time comes from an injectable
Clock. In service one thread runs beside the calls: the monitor samples the link every
STATE_PERIOD_S (`sample_once`). With ``threads=False`` it does not start and the caller runs it
itself, so a test on a fake clock and a fake link decides exactly when it happens.
"""

from __future__ import annotations

import logging
import threading
from collections.abc import Callable

import numpy as np
import pinocchio as pin

from domain.geometry import finite_vector, moved_by, rotation_angle, vector_norm
from domain.robot_model import names
from domain.robot_model.description import ArmDescription
from domain.robot_model.ik import solve_ik
from domain.robot_model.kinematics import ArmKinematics
from domain.robot_model.singularity import singularity_measures
from services.common.fanout import Fanout
from services.proxy_robot.segment_timing import SegmentTiming
from services.proxy_robot.status import (
    MOTION_STATUSES,
    Moved,
    RobotErrorRaised,
    RobotEvent,
    RobotSnapshot,
    RobotStatus,
    StatusChanged,
)
from services.runtime.clock import SYSTEM_CLOCK, Clock
from services.world.link import ArmLink, ArmSample
from wire.errors import (
    FailedPreconditionError,
    InvalidArgumentError,
    OutOfRangeError,
    UnavailableError,
)

log = logging.getLogger(__name__)

# Caps on one command. Bigger increments are refused, not clipped: the operator should know.
MAX_JOINT_INCREMENT_RAD = 0.5
MAX_TRANSLATION_INCREMENT_M = 0.05
MAX_ROTATION_INCREMENT_RAD = np.radians(15.0)
# A Cartesian increment whose IK answer moves a joint further than this is crossing a
# singular region: the step is reduced (or refused) rather than allowed to jump.
MAX_IK_JOINT_STEP_RAD = 0.35
REDUCED_FRACTIONS = (0.5, 0.25)
# The arm has arrived when every joint is this close to its target and this slow.
ARRIVAL_TOLERANCE_RAD = 2e-3
ARRIVAL_SPEED_RAD_PER_S = 2e-2
# How often the monitor samples the link (state stream, arrival, faults): 100 Hz, the rate the
# station's readers take the state at (the DecisionServer follows it every 10 ms). At 500 Hz the
# monitor's FK and wake-ups competed with the moves it serves: a Teleoperate move's round trip
# took 3.3-4.8 ms at p50 against 2.4-2.7 at 100 Hz (docs/performance.md, Profiles). Stops, holds
# and faults act at the hardware at once; the status shows them at the next sample.
STATE_PERIOD_S = 0.01
TOOL_OFFSET_LIMIT_M = 1.0
RELEASE_TIMEOUT_S = 0.2  # the hardware applies a release within a servo period or two
# Hold aims where the arm stops braking this hard: the servo's acceleration cap in the
# simulation (services/world/sim.py); a real controller brakes on its own terms.
HOLD_DECELERATION_RAD_PER_S2 = 10.0
RELEASE_POLL_S = 0.0005


class ProxyRobotCore:
    """The arm proxy. Thread-safe; `close()` stops its monitor thread.

    ``threads=False`` starts no monitor: the caller calls `sample_once()` every STATE_PERIOD_S
    of its clock instead."""

    def __init__(self, link_factory: Callable[[], ArmLink],
                 state_period_s: float = STATE_PERIOD_S, *, clock: Clock = SYSTEM_CLOCK,
                 threads: bool = True):
        self._link_factory = link_factory
        self._state_period_s = state_period_s
        self._clock = clock
        self._threads = threads
        self._lock = threading.RLock()  # status, target, link, tool frame
        self._move_lock = threading.Lock()  # one move computation at a time (kinematics buffers)
        self._move_kinematics = ArmKinematics()
        self._monitor_kinematics = ArmKinematics()
        self._tool_frame = self._move_kinematics.flange_T_tool
        self._status = RobotStatus.NOT_CONNECTED
        self._reason = "not connected yet"
        self._change_time_ns = self._clock.time_ns()
        self._initialized = False
        self._link: ArmLink | None = None
        self._segments = SegmentTiming(clock.monotonic_ns)
        self._target_q: np.ndarray | None = None
        self._latest: RobotSnapshot | None = None
        self._event_sequence = 0
        # The first sample after the last Reset released the hardware's hold: an older one
        # that shows a latch or a fault shows the one the Reset cleared, not a new one.
        self._released_at_sequence = -1
        self._monitor: threading.Thread | None = None
        self._monitor_stop = threading.Event()
        self.states: Fanout[RobotSnapshot] = Fanout()
        self.events: Fanout[RobotEvent] = Fanout()

    # -- status -----------------------------------------------------------------------------

    @property
    def status(self) -> tuple[RobotStatus, str, int]:
        """(status, reason, change time in ns)."""
        with self._lock:
            return self._status, self._reason, self._change_time_ns

    def _set_status(self, status: RobotStatus, reason: str) -> None:
        with self._lock:
            previous = self._status
            if previous == status:
                return
            self._status, self._reason, self._change_time_ns = (status, reason,
                                                                 self._clock.time_ns())
            self._emit(StatusChanged(previous, status, reason))
        # READY <-> MOVING comes with every command: an INFO line each would cost the hot path
        # (a log write per command at 1 kHz) and bury the changes that matter.
        routine = {previous, status} == {RobotStatus.READY, RobotStatus.MOVING}
        log.log(logging.DEBUG if routine else logging.INFO, "status %s -> %s: %s",
                previous.name, status.name, reason)

    def _emit(self, payload) -> None:
        with self._lock:
            self._event_sequence += 1
            event = RobotEvent(self._event_sequence, self._clock.time_ns(), payload)
        self.events.publish(event)

    # -- life cycle -------------------------------------------------------------------------

    def connect(self, reason: str = "hardware link open") -> RobotStatus:
        """Open the hardware link. UnavailableError when it does not answer."""
        with self._lock:
            if self._status != RobotStatus.NOT_CONNECTED:
                return self._status
            link = self._link_factory()
            self._released_at_sequence = -1  # (a new link counts its samples anew)
            sample, self._latest = self._sample(link, self._monitor_kinematics)
            self._link = link
            self._target_q = sample.joint_targets_rad.copy()
            self._initialized = False
            self._start_monitor()
            if sample.hold_latched:
                self._set_status(RobotStatus.ESTOPPED, "the hardware holds a latched stop; Reset")
            else:
                self._set_status(RobotStatus.CONNECTED, reason)
            return self._status

    def reattach(self, previous_end: str) -> RobotStatus:
        """After a restart: open the link to the arm the previous process drove, without
        moving it (its target is where the hardware holds it), and say why motion needs a new
        Initialize. UnavailableError when the hardware does not answer."""
        return self.connect(
            f"restarted by the station's supervisor: the previous ProxyRobot {previous_end}; "
            "the arm held where it was. Initialize to move again")

    def initialize(self) -> RobotStatus:
        """CONNECTED -> INITIALIZING -> READY: hold where the arm is and accept motion."""
        with self._lock:
            if self._status != RobotStatus.CONNECTED:
                raise FailedPreconditionError(
                    f"Initialize needs CONNECTED, the arm is {self._status.name}: "
                    + ("Connect first" if self._status == RobotStatus.NOT_CONNECTED
                       else "Reset first" if self._status in (RobotStatus.ESTOPPED,
                                                              RobotStatus.FAULT)
                       else "it is already initialized"),
                    reason="BAD_STATUS")
            self._set_status(RobotStatus.INITIALIZING, "initializing")
            self._hold_at(self._require_link().read_arm().joint_positions_rad)
            self._initialized = True
            self._set_status(RobotStatus.READY, "initialized; holding position")
            return self._status

    def disconnect(self) -> RobotStatus:
        """Hold the arm where it is and close the link."""
        with self._lock:
            link = self._link
            if link is not None:
                try:
                    self._hold_at(link.read_arm().joint_positions_rad)
                except UnavailableError:
                    pass  # nothing to hold: the hardware is already gone
        self._drop_link("disconnected")
        return self.status[0]

    def close(self) -> None:
        """Release the hardware (used on process shutdown)."""
        self.disconnect()
        self.events.close_all()
        self.states.close_all()

    def _drop_link(self, reason: str) -> None:
        with self._lock:
            self._monitor_stop.set()
            link, self._link = self._link, None
            self._initialized = False
            self._latest = None
            self._set_status(RobotStatus.NOT_CONNECTED, reason)
        monitor = self._monitor
        if monitor is not None and monitor is not threading.current_thread():
            monitor.join(1.0)
        if link is not None:
            link.close()

    def _require_link(self) -> ArmLink:
        if self._link is None:
            raise FailedPreconditionError("the arm is NOT_CONNECTED: call Connect first",
                                          reason="NOT_CONNECTED")
        return self._link

    # -- state ------------------------------------------------------------------------------

    def snapshot(self) -> RobotSnapshot:
        """The latest state sample. FailedPreconditionError when not connected."""
        with self._lock:
            self._require_link()
            return self._latest

    @property
    def arm(self) -> ArmDescription:
        """The arm this driver drives, as its description file declares it."""
        return self._move_kinematics.arm

    @property
    def tool_frame(self) -> pin.SE3:
        """The tool frame in the flange frame (T_t, M_e^t)."""
        with self._lock:
            return pin.SE3(self._tool_frame)

    def set_tool_frame(self, flange_to_tool: pin.SE3) -> pin.SE3:
        with self._lock:
            if self._status == RobotStatus.MOVING:
                raise FailedPreconditionError(
                    "the arm is MOVING: set the tool frame once it is READY",
                    reason="MOVING")
            offset = vector_norm(flange_to_tool.translation)
            if offset > TOOL_OFFSET_LIMIT_M:
                raise InvalidArgumentError(
                    f"the tool point is {offset:.3f} m from the flange; at most "
                    f"{TOOL_OFFSET_LIMIT_M} m", reason="TOOL_TOO_LONG")
            self._tool_frame = pin.SE3(flange_to_tool)
            return pin.SE3(self._tool_frame)

    # -- motion -----------------------------------------------------------------------------

    def move_joints(self, delta_rad) -> tuple[np.ndarray, pin.SE3]:
        """Add a joint increment to the target. Returns (new target, its tool pose)."""
        delta = finite_vector(delta_rad, self._move_kinematics.nq, "delta_joint_positions_rad")
        largest = int(np.argmax(np.abs(delta)))
        if abs(delta[largest]) > MAX_JOINT_INCREMENT_RAD:
            raise OutOfRangeError(
                f"joint {largest + 1} increment {np.degrees(delta[largest]):.1f} deg exceeds the "
                f"cap of {np.degrees(MAX_JOINT_INCREMENT_RAD):.1f} deg per command; split it",
                reason="INCREMENT_CAP")
        with self._move_lock:
            base = self._motion_base()
            target = base + delta
            self._check_limits(target)
            return self._command(target), self._tool_pose(target)

    def move_cartesian(self, delta_position_m, delta_rotation: np.ndarray,
                       frame: str) -> tuple[np.ndarray, pin.SE3, float]:
        """Move the tool by (ΔX, ΔM) expressed in `frame` ("BASE", "WRIST" or "TOOL").

        Returns (new joint target, its tool pose, applied fraction in (0, 1])."""
        delta_x = finite_vector(delta_position_m, 3, "delta_position_m")
        distance = vector_norm(delta_x)
        if distance > MAX_TRANSLATION_INCREMENT_M:
            raise OutOfRangeError(
                f"translation increment {distance * 1e3:.1f} mm exceeds the cap "
                f"of {MAX_TRANSLATION_INCREMENT_M * 1e3:.0f} mm per command; split it",
                reason="INCREMENT_CAP")
        angle = rotation_angle(delta_rotation)
        if angle > MAX_ROTATION_INCREMENT_RAD:
            raise OutOfRangeError(
                f"rotation increment {np.degrees(angle):.1f} deg exceeds the cap of "
                f"{np.degrees(MAX_ROTATION_INCREMENT_RAD):.0f} deg per command; split it",
                reason="INCREMENT_CAP")
        with self._move_lock:
            q_base = self._motion_base()
            tool_now = self._tool_pose(q_base)
            tool_goal = self._apply_increment(q_base, tool_now, pin.SE3(delta_rotation, delta_x),
                                              frame)
            for fraction in (1.0, *REDUCED_FRACTIONS):
                goal = tool_goal if fraction == 1.0 else tool_now * pin.exp6(
                    fraction * pin.log6(tool_now.actInv(tool_goal)))
                q_goal = self._solve(goal, q_base, first_try=fraction == 1.0)
                if q_goal is not None:
                    return self._command(q_goal), self._tool_pose(q_goal), fraction
            raise OutOfRangeError(
                "the move is too near a singularity (the wrist, elbow or shoulder aligned): "
                "move in joint space away from it first", reason="SINGULARITY")

    def _apply_increment(self, q: np.ndarray, tool: pin.SE3, delta: pin.SE3,
                         frame: str) -> pin.SE3:
        if frame in ("TOOL", "BASE"):
            return moved_by(tool, delta, frame)
        if frame == "WRIST":
            flange = self._move_kinematics.flange_pose(q)
            return flange * delta * self._tool_frame
        raise InvalidArgumentError(f"unknown frame {frame!r}: use BASE, WRIST or TOOL",
                                   reason="BAD_FRAME")

    def _solve(self, tool_goal: pin.SE3, q_seed: np.ndarray, first_try: bool) -> np.ndarray | None:
        """Joint target for a tool pose; None when the step is too big (near a singularity);
        OutOfRangeError when the pose is unreachable or past the joint limits."""
        flange_goal = tool_goal * self._tool_frame.inverse()
        result = solve_ik(self._move_kinematics, flange_goal, q_seed, frame=names.FLANGE_SITE)
        if not result.success:
            if not first_try:
                return None
            at_limit = self._joints_at_limit(result.q)
            if at_limit:
                raise OutOfRangeError(
                    f"the target needs joint {at_limit[0] + 1} past its limit "
                    f"({self._limit_text(at_limit[0])})", reason="JOINT_LIMIT")
            raise OutOfRangeError(
                f"the target is outside the reachable workspace (IK stopped "
                f"{result.position_error * 1e3:.1f} mm / {np.degrees(result.rotation_error):.1f} "
                "deg away)", reason="WORKSPACE")
        if np.max(np.abs(result.q - q_seed)) > MAX_IK_JOINT_STEP_RAD:
            return None
        # Near a singularity, only moves that do not go deeper are allowed, so the operator
        # can always steer back out.
        after = singularity_measures(self._move_kinematics, result.q)
        if after.near_singular and after.min_singular_value < singularity_measures(
                self._move_kinematics, q_seed).min_singular_value:
            return None
        return result.q

    def _joints_at_limit(self, q: np.ndarray) -> list[int]:
        lower, upper = self._move_kinematics.lower_limits, self._move_kinematics.upper_limits
        return [int(i) for i in np.flatnonzero((q <= lower + 1e-9) | (q >= upper - 1e-9))]

    def _limit_text(self, joint: int) -> str:
        lower = np.degrees(self._move_kinematics.lower_limits[joint])
        upper = np.degrees(self._move_kinematics.upper_limits[joint])
        return f"{lower:.0f}..{upper:.0f} deg"

    def _check_limits(self, target: np.ndarray) -> None:
        lower, upper = self._move_kinematics.lower_limits, self._move_kinematics.upper_limits
        outside = np.flatnonzero((target < lower) | (target > upper))
        if outside.size:
            joint = int(outside[0])
            raise OutOfRangeError(
                f"joint {joint + 1} target {np.degrees(target[joint]):.1f} deg is past its limit "
                f"({self._limit_text(joint)})", reason="JOINT_LIMIT")

    def _motion_base(self) -> np.ndarray:
        """The joint target to add increments to; FailedPreconditionError unless motion is
        allowed."""
        with self._lock:
            if self._status not in MOTION_STATUSES:
                hint = {
                    RobotStatus.NOT_CONNECTED: "Connect and Initialize first",
                    RobotStatus.CONNECTED: "Initialize first",
                    RobotStatus.INITIALIZING: "wait for READY",
                    RobotStatus.ESTOPPED: "an emergency stop is latched; Reset it first",
                    RobotStatus.FAULT: f"the arm is in FAULT ({self._reason}); Reset first",
                }[self._status]
                raise FailedPreconditionError(f"the arm is {self._status.name}: {hint}",
                                              reason=self._status.name)
            return self._target_q.copy()

    def _command(self, target: np.ndarray) -> np.ndarray:
        """Hand a target to the servo, with the segment to reach it over (unless the status
        changed meanwhile)."""
        with self._lock:
            self._motion_base()  # an e-stop may have landed during the IK
            link = self._require_link()
            motion = float(abs(target - self._target_q).max())
            link.write_target(target, self._segments.duration_s(motion))
            self._target_q = target.copy()
            self._set_status(RobotStatus.MOVING, "moving to a new target")
            return target.copy()

    def _tool_pose(self, q: np.ndarray) -> pin.SE3:
        return self._move_kinematics.flange_pose(q) * self._tool_frame

    # -- emergency stop ---------------------------------------------------------------------

    def emergency_stop(self, reason: str) -> tuple[RobotStatus, int]:
        """Latch a controlled stop at the hardware first, then in the status. Idempotent."""
        link = self._link
        if link is None:
            return RobotStatus.NOT_CONNECTED, self._clock.time_ns()
        link.hold()  # before any lock: nothing may delay the stop (it drops the segment too)
        stop_time_ns = self._clock.time_ns()
        with self._lock:
            text = f"emergency stop: {reason or 'no reason given'}"
            if self._status == RobotStatus.ESTOPPED:
                self._reason = text  # the latch came first (hold_now, the band): say why
            self._set_status(RobotStatus.ESTOPPED, text)
            return self._status, stop_time_ns

    def hold_now(self) -> None:
        """Latch the hold at the hardware at once, taking no lock: an emergency stop is on its
        way (emergency_stop() follows, with the reason). Nothing happens without a link."""
        link = self._link
        if link is not None:
            link.hold()

    def reset(self) -> RobotStatus:
        """Clear an e-stop or fault latch; the arm stays where it is."""
        with self._lock:
            link = self._require_link()
            if self._status not in (RobotStatus.ESTOPPED, RobotStatus.FAULT):
                return self._status
            link.release_hold()
            self._released_at_sequence = self._await_release(link).sequence
            self._hold_at(link.read_arm().joint_positions_rad)
            after = RobotStatus.READY if self._initialized else RobotStatus.CONNECTED
            self._set_status(after, "reset; holding position")
            return self._status

    def hold(self) -> tuple[np.ndarray, pin.SE3, pin.SE3]:
        """Stop where the arm can, without latching: the target becomes the point where braking
        at the servo's acceleration cap brings it to rest. Motion commands stay accepted.
        Returns the new target, its tool pose, and the tool pose at the target it replaced
        (a caller that resumes goes on from one to the other)."""
        with self._lock:
            link = self._require_link()
            sample = link.read_arm()
            speed = sample.joint_velocities_rad_per_s
            braking = np.sign(speed) * speed**2 / (2.0 * HOLD_DECELERATION_RAD_PER_S2)
            lower = self._move_kinematics.lower_limits
            upper = self._move_kinematics.upper_limits
            target = np.clip(sample.joint_positions_rad + braking, lower, upper)
            cut = target if self._target_q is None else self._target_q
            cut_tool = self._tool_pose(cut)
            self._hold_at(target)  # if MOVING, arrival there ends it with a moved event
            return target.copy(), self._tool_pose(target), cut_tool

    def _hold_at(self, target: np.ndarray) -> None:
        """Send the servo straight to `target`, dropping any segment in progress."""
        self._require_link().write_target(target)
        self._target_q = np.asarray(target, float).copy()

    def _await_release(self, link: ArmLink) -> ArmSample:
        """Wait until the hardware reports the hold released, so the monitor does not read the
        old latch as a new stop; the first sample that says so."""
        clock = self._clock
        deadline_ns = clock.monotonic_ns() + round(RELEASE_TIMEOUT_S * 1e9)
        while (sample := link.read_arm()).hold_latched:
            if clock.monotonic_ns() > deadline_ns:
                raise UnavailableError("the hardware did not release its hold; check it and Reset "
                                       "again", reason="HOLD_STUCK")
            clock.sleep(RELEASE_POLL_S)
        return sample

    # -- monitor ----------------------------------------------------------------------------

    def sample_once(self) -> bool:
        """The monitor's work for one period: sample the link; note arrival, faults and latched
        stops; publish the state. False when there is no link (any more)."""
        return self._sample_once(self._monitor_stop)

    def _start_monitor(self) -> None:
        self._monitor_stop = threading.Event()
        if not self._threads:
            return
        self._monitor = threading.Thread(target=self._run_monitor, args=(self._monitor_stop,),
                                         name="arm-monitor", daemon=True)
        self._monitor.start()

    def _run_monitor(self, stop: threading.Event) -> None:
        while not stop.wait(self._state_period_s):
            if not self._sample_once(stop):
                return

    def _sample_once(self, stop: threading.Event) -> bool:
        with self._lock:
            link = self._link
        if link is None:
            return False
        try:
            sample, snapshot = self._sample(link, self._monitor_kinematics)
        except UnavailableError as exc:
            self._emit(RobotErrorRaised("LINK_LOST", str(exc)))
            self._drop_link(f"hardware link lost: {exc}")
            return False
        if stop.is_set():
            return False
        self._observe(sample, snapshot)
        self.states.publish(snapshot)
        return True

    def _sample(self, link: ArmLink, kinematics: ArmKinematics) -> tuple[ArmSample,
                                                                             RobotSnapshot]:
        arm = link.read_arm()
        flange = kinematics.flange_pose(arm.joint_positions_rad)
        with self._lock:
            status = self._status
            tool = flange * self._tool_frame
        return arm, RobotSnapshot(arm.sequence, arm.sample_time_ns, status,
                                  arm.joint_positions_rad, arm.joint_velocities_rad_per_s,
                                  flange, tool)

    def _observe(self, sample: ArmSample, snapshot: RobotSnapshot) -> None:
        """Arrival, faults and hardware holds, from one sample."""
        arm_q, arm_qd = snapshot.joint_positions_rad, snapshot.joint_velocities_rad_per_s
        with self._lock:
            self._latest = snapshot
            if self._status == RobotStatus.MOVING:
                if (np.max(np.abs(arm_q - self._target_q)) < ARRIVAL_TOLERANCE_RAD
                        and np.max(np.abs(arm_qd)) < ARRIVAL_SPEED_RAD_PER_S):
                    self._set_status(RobotStatus.READY, "target reached")
                    self._emit(Moved(arm_q.copy(), snapshot.tool_pose))
        if sample.sequence < self._released_at_sequence:
            return  # read before the last Reset released the hold: its latch is the old one
        if sample.fault and self._status != RobotStatus.FAULT:
            self._emit(RobotErrorRaised("HARDWARE_FAULT", sample.fault))
            self._set_status(RobotStatus.FAULT, sample.fault)
        elif (sample.hold_latched and self._status not in
              (RobotStatus.ESTOPPED, RobotStatus.FAULT, RobotStatus.NOT_CONNECTED)):
            self._set_status(RobotStatus.ESTOPPED, "a latched stop was set at the hardware")
