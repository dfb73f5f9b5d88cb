"""DecisionCore: the DecisionServer's supervisory logic, and the one owner of the arm on the
operator's side. No transport code.

It owns the control lock, the assistance configuration, the teleoperation sessions and their
watchdogs, record and replay, the force-control loop and the cobegin barriers, and publishes
its events. It reaches the arm only through its `Slave` port.

Threads: gRPC handlers, the session watchdogs, the replay, the force loop, the lease reaper
and the slave's state stream all call in. Every piece of mutable state below lives behind
`self._lock`; nothing that waits on the slave or the lock manager runs while it is held (a slow
arm never blocks a stop, and the lock manager's callback may take it): threads and streams are
signalled or cancelled under it, and joined outside it.

The emergency stop has one source of truth: the latch at the hardware, as the arm's status
reports it. Whichever door stopped the arm (this server, ProxyRobot, the emergency-stop band),
the first state sample that says ESTOPPED stops replay and force control here, and commands
are refused until a Reset, whose answer is the status after it.
"""

from __future__ import annotations

import dataclasses
import itertools
import logging
import math
import threading
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from domain.passivity import SlavePassivity
from services.common.fanout import Fanout
from services.decision_server.arbitration import ControlView, Lease, LockManager
from services.decision_server.assistance import Assistance
from services.decision_server.cobegin import Barriers, SimulatedProcessor
from services.decision_server.force_control import ForceLoop
from services.decision_server.recording_mcap import Sources
from services.decision_server.recordings import RecordingInfo, RecordingStore
from services.decision_server.sessions import (
    DEFAULT_MAX_COMMAND_AGE_S,
    MAX_MAX_COMMAND_AGE_S,
    MIN_MAX_COMMAND_AGE_S,
    OperatorSession,
)
from services.decision_server.slave import (
    LATCHED_STATUSES,
    MoveResult,
    Slave,
    SlaveState,
    SlaveWrench,
)
from services.runtime.clock import SYSTEM_CLOCK, Clock
from wire.errors import (
    FailedPreconditionError,
    InvalidArgumentError,
    NotFoundError,
    PermissionDeniedError,
    TelerobotError,
    UnavailableError,
)

log = logging.getLogger(__name__)

# The sensor's wrench reaches the DecisionServer at 100 Hz: after 30 ms without one the
# sensor is asked whether it is alive, and may take 40 ms to answer (see sensor_lost). A
# session's watchdog asks at that moment, without waiting for a command, so a hung sensor holds
# the arm about 30 + 40 ms after its last wrench, cutting the segment the last command started.
# A shorter answer time refused about 1 command in 2,400 as "silent" on a loaded 2-core machine
# (load 12, the 10-minute soak) while the sensor was only slow; on such a machine a sensor 70 ms
# late is no feedback to move by either, and the ack says why.
SENSOR_QUIET_NS = 30_000_000
SENSOR_PROBE_S = 0.04
SENSOR_ALIVE_S = 0.1  # a quiet sensor that answered (a change threshold) is asked this often

DEFAULT_WATCHDOG_S = 0.1
MIN_WATCHDOG_S, MAX_WATCHDOG_S = 0.01, 5.0
MIN_REPLAY_SPEED, MAX_REPLAY_SPEED = 0.1, 10.0


# -- events -------------------------------------------------------------------------------

@dataclass(frozen=True)
class ControlChanged:
    view: ControlView
    reason: str


@dataclass(frozen=True)
class AssistanceChanged:
    assistance: Assistance
    operator_id: str


@dataclass(frozen=True)
class ReplayProgress:
    name: str
    replayed: int
    total: int
    state: str  # RUNNING, FINISHED, INTERRUPTED
    detail: str = ""


@dataclass(frozen=True)
class RecordingFailed:
    name: str
    reason: str


@dataclass(frozen=True)
class RobotEventForwarded:
    message: object  # the ProxyRobot event, as it came


@dataclass(frozen=True)
class DecisionEvent:
    sequence: int
    time_ns: int
    payload: object


@dataclass
class _Replay:
    """A running replay: its thread, how to stop it, and how far it got."""

    lease_id: str = ""  # the lease that started it: it moves the arm only while that is held
    thread: threading.Thread | None = None
    stop: threading.Event = dataclasses.field(default_factory=threading.Event)
    reason: str = ""
    replayed: int = 0


# -- the core -------------------------------------------------------------------------------

class DecisionCore:
    def __init__(self, slave: Slave, recordings: RecordingStore, clock: Clock = SYSTEM_CLOCK,
                 camera=None):
        self.slave = slave
        self.recordings = recordings
        self.camera = camera  # whose video MCAP recordings keep (a CameraSource, Sources.video)
        self.clock = clock
        self._lock = threading.RLock()
        self._event_sequence = itertools.count(1)
        self.events: Fanout[DecisionEvent] = Fanout()
        self.locks = LockManager(self._on_control_change, clock=clock)
        self._assistance = Assistance()
        self._force_lease: Lease | None = None  # the lease that switched force control on
        self._force_loop: ForceLoop | None = None
        self._indexing = False
        self._sensor_streamed = False  # a fresh wrench was seen (see sensor_lost)
        self._sensor_alive_until = 0.0
        # One question to the sensor at a time: a command waits for a watchdog's answer.
        self._sensor_lock = threading.Lock()
        # The arm's latest status, from state samples and from the answers of stop and reset;
        # an older sample never overrides a newer answer.
        self._state: SlaveState | None = None
        self._sessions: dict[str, OperatorSession] = {}
        self._replay: _Replay | None = None
        self.barriers = Barriers()
        self.processor = SimulatedProcessor()
        slave.on_state = self._note_state
        slave.on_robot_event = lambda message: self.emit(RobotEventForwarded(message))
        recordings.on_failed = lambda name, why: self.emit(RecordingFailed(name, why))

    def emit(self, payload) -> None:
        event = DecisionEvent(next(self._event_sequence), self.clock.time_ns(), payload)
        self.events.publish(event)
        self.recordings.note_event(event)  # an MCAP recording keeps it (queued, not written)

    def close(self) -> None:
        self._stop_replay("the server is stopping")
        if self.recordings.recording:  # saved, not lost with the process
            try:
                self.recordings.stop()
            except TelerobotError as error:
                log.warning("the recording was not saved: %s", error.message)
        old = self._replace_force_loop(None)
        if old is not None:
            old.stop()
        with self._lock:
            sessions = list(self._sessions.values())
        for session in sessions:
            session.close("the server is stopping")
        self.locks.close()
        self.events.close_all()

    # -- what the servicer reads ------------------------------------------------------------

    @property
    def assistance(self) -> Assistance:
        return self._assistance

    @property
    def indexing(self) -> bool:
        return self._indexing

    @property
    def latched(self) -> str | None:
        """ESTOPPED or FAULT while the arm refuses motion until a Reset, else None."""
        state = self._state
        return state.status if state is not None and state.status in LATCHED_STATUSES else None

    @property
    def force_loop(self) -> ForceLoop | None:
        return self._force_loop

    def snapshot(self) -> tuple[Assistance, bool, str | None]:
        """(assistance, indexing, latched status or None), read together."""
        with self._lock:
            return self._assistance, self._indexing, self.latched

    def robot_state(self) -> SlaveState:
        """The arm's latest state, with the latched status if it is newer than the sample."""
        state = self.slave.state()
        known = self._state
        if known is not None and known.sample_time_ns > state.sample_time_ns:
            return dataclasses.replace(state, status=known.status, reason=known.reason)
        return state

    def wrench(self) -> SlaveWrench | None:
        return self.slave.wrench()

    def sensor_lost(self, before_asking: Callable[[], None] | None = None) -> str | None:
        """Why the force sensor is lost, or None. The operator moves by what it feels, so
        without the sensor the arm must not move. Lost: its process is down, or its wrench
        went stale after it had been streaming and the sensor does not answer within
        SENSOR_PROBE_S (a hung process answers nothing, not even its health). A sensor that
        answers that it stopped reading (StopReading), or never streamed, is not lost; one
        that reads but streams nothing (a change threshold) is not either. A restarted sensor
        resumes reading by itself, and motion with it. `before_asking` runs when a wrench
        that was fresh went stale, before the sensor is asked: the probe can take all of
        SENSOR_PROBE_S, and the operator's feel is stale already."""
        health = self.slave.health().get("force_sensor", "ok")
        if health != "ok":
            return f"the force sensor is unavailable ({health}); the arm holds"
        with self._sensor_lock:
            now = self.clock.monotonic()
            if self._wrench_age_ns() <= SENSOR_QUIET_NS:
                self._sensor_streamed, self._sensor_alive_until = True, 0.0
                return None
            if not self._sensor_streamed or now < self._sensor_alive_until:
                return None
            if before_asking is not None and not self._sensor_alive_until:
                before_asking()  # (not for a sensor known to be quiet but alive)
            try:
                self._sensor_streamed = self.slave.sensor_is_reading(SENSOR_PROBE_S)
            except UnavailableError as error:
                return f"the force sensor went silent ({error.message}); the arm holds"
            self._sensor_alive_until = now + SENSOR_ALIVE_S  # quiet but alive: ask again later
            return None

    def sensor_check_due_in_s(self) -> float | None:
        """Seconds until sensor_lost would ask the sensor whether it is alive (<= 0: it would
        now), or None while nothing but a fresh wrench could make it ask (the sensor never
        streamed, or it answered that it stopped reading)."""
        if not self._sensor_streamed:
            return None
        quiet_in_s = (SENSOR_QUIET_NS - self._wrench_age_ns()) / 1e9
        return max(quiet_in_s, self._sensor_alive_until - self.clock.monotonic())

    def _wrench_age_ns(self) -> float:
        """How old the latest wrench is; infinite when there is none (the slave says nothing
        of a wrench that stalled)."""
        wrench = self.slave.wrench()
        return math.inf if wrench is None else self.clock.time_ns() - wrench.sample_time_ns

    # -- the arm's status: one source of truth ----------------------------------------------

    def _note_state(self, state: SlaveState, answer: bool = False) -> None:
        """A state sample, or (`answer`) the status a stop or reset answered with. Whatever is
        older than what we know is history; at the same instant, an answer wins."""
        with self._lock:
            known = self._state
            if known is not None and (state.sample_time_ns < known.sample_time_ns or (
                    state.sample_time_ns == known.sample_time_ns and not answer)):
                return
            was_latched = self.latched
            self._state = state
            newly_latched = self.latched if was_latched is None else None
            if newly_latched:
                self._replace_force_loop(None)  # paused: a Reset resumes it
        if newly_latched:
            log.warning("the arm is %s (%s): replay and force control stop", newly_latched,
                        state.reason or "no reason given")
            self._stop_replay(f"the arm is {newly_latched}: {state.reason}".rstrip(": "))

    def note_status(self, status: str, reason: str) -> None:
        """The status an answer from the arm reported, as of now: it wins over state samples
        taken before it, which the state stream may still deliver (a Teleoperate right after
        Initialize's READY must not see the CONNECTED of a sample from before it)."""
        state = self._state
        pose = state.tool_pose if state is not None else pin.SE3.Identity()
        self._note_state(SlaveState(pose, status, self.clock.time_ns(), reason), answer=True)

    # -- teleoperation ----------------------------------------------------------------------

    def open_session(self, operator_id: str, lease_id: str, mapping: str | None,
                     watchdog_s: float, passivity: bool = False,
                     max_command_age_s: float = 0.0) -> OperatorSession:
        """A new Teleoperate session; with `passivity`, TDPA's slave port keeps the channel
        passive (domain.passivity). Zero for `watchdog_s` or `max_command_age_s`: the
        default."""
        watchdog_s = watchdog_s or DEFAULT_WATCHDOG_S
        if not MIN_WATCHDOG_S <= watchdog_s <= MAX_WATCHDOG_S:
            raise InvalidArgumentError(f"watchdog_timeout must be {MIN_WATCHDOG_S * 1e3:.0f} ms.."
                                       f"{MAX_WATCHDOG_S:.0f} s", reason="BAD_WATCHDOG")
        max_command_age_s = max_command_age_s or DEFAULT_MAX_COMMAND_AGE_S
        if not MIN_MAX_COMMAND_AGE_S <= max_command_age_s <= MAX_MAX_COMMAND_AGE_S:
            raise InvalidArgumentError(
                f"max_command_age must be {MIN_MAX_COMMAND_AGE_S * 1e3:.0f} ms.."
                f"{MAX_MAX_COMMAND_AGE_S:.0f} s", reason="BAD_MAX_COMMAND_AGE")
        lease = self.locks.require(lease_id)
        status = self.robot_state().status
        if status in LATCHED_STATUSES:
            raise FailedPreconditionError(f"the arm is {status}: Reset it first", reason=status)
        if status not in ("READY", "MOVING"):
            raise FailedPreconditionError(f"the arm is {status}: Connect and Initialize it first",
                                          reason=status)
        # An authenticated holder drives as itself, whatever the session's init says.
        session = OperatorSession(self, lease.identity or operator_id or lease.operator_id, lease,
                                mapping, watchdog_s,
                                passivity=SlavePassivity() if passivity else None,
                                max_command_age_s=max_command_age_s)
        with self._lock:
            if self._replay is not None:
                raise FailedPreconditionError("a replay is running: stop it first",
                                              reason="REPLAYING")
            self._sessions[session.session_id] = session
        return session.start()

    def resume_session(self, session_id: str, lease_id: str) -> tuple[OperatorSession, int]:
        """A broken session (see services.decision_server.sessions), taken over by a new stream
        of the same lease: the session and the new stream's number."""
        with self._lock:
            session = self._sessions.get(session_id)
        if session is None:
            raise NotFoundError(
                f"no session {session_id} to resume: it ended, or its resume window "
                "passed; open a new one", reason="NO_SESSION")
        if lease_id != session.lease.lease_id:
            raise PermissionDeniedError(f"session {session_id} belongs to another lease",
                                        reason="NOT_YOUR_SESSION")
        self.locks.require(lease_id)  # the lease still held, by this caller; renewed
        with self._lock:  # (start_replay looks for attached sessions under it too)
            if self._replay is not None:  # started while the session was detached
                raise FailedPreconditionError("a replay is running: stop it first",
                                              reason="REPLAYING")
            return session, session.resume()

    def require_lease(self, lease_id: str) -> Lease:
        """The lease, renewed; FailedPreconditionError if it is no longer held."""
        return self.locks.require(lease_id)

    def record_increment(self, mapping: str, translation: np.ndarray, rotation: np.ndarray,
                         target_translation: np.ndarray) -> None:
        """Add an applied increment to the recording in progress, if any."""
        self.recordings.add(mapping, translation, rotation, target_translation)

    def forget_session(self, session_id: str) -> None:
        with self._lock:
            self._sessions.pop(session_id, None)

    # -- direct moves (RunAction) -------------------------------------------------------------

    def move_cartesian(self, lease_id: str, delta_position: np.ndarray,
                       delta_rotation: np.ndarray, frame: str) -> MoveResult:
        """One Cartesian increment from the lock holder, recorded like a teleoperated one."""
        self._require_motion_allowed(lease_id)
        result = self.slave.move_cartesian(delta_position, delta_rotation, frame)
        self.recordings.add(frame, delta_position, delta_rotation,
                            result.target_tool_pose.translation)
        return result

    def move_joints(self, lease_id: str, delta_joints_rad: np.ndarray) -> MoveResult:
        """One joint increment from the lock holder, recorded."""
        self._require_motion_allowed(lease_id)
        result = self.slave.move_joints(delta_joints_rad)
        self.recordings.add_joints(delta_joints_rad, result.target_tool_pose.translation)
        return result

    def _require_motion_allowed(self, lease_id: str | None) -> None:
        self.locks.require(lease_id)
        with self._lock:
            latched, replaying = self.latched, self._replay is not None
        if latched:
            raise FailedPreconditionError(f"the arm is {latched}: Reset it first", reason=latched)
        if replaying:
            raise FailedPreconditionError("a replay is running: stop it first", reason="REPLAYING")

    # -- assistance, indexing, tool frame ---------------------------------------------------

    def set_assistance(self, lease_id: str, assistance: Assistance) -> Assistance:
        lease = self.locks.require(lease_id)
        assistance.validated()
        constraint = assistance.constraint
        if constraint is not None and constraint.anchor_m is None:
            anchor = self.slave.state().tool_pose.translation.copy()
            assistance = dataclasses.replace(
                assistance, constraint=dataclasses.replace(constraint, anchor_m=anchor))
        with self._lock:
            self._assistance = assistance
            self._force_lease = lease if assistance.force_control is not None else None
            self._replace_force_loop(assistance)
        if assistance.force_control is not None:
            # The lease may have gone while this call ran (released, lapsed): then nobody's
            # change of control would stop the loop just started, so look again now.
            try:
                self.locks.require(lease.lease_id)
            except FailedPreconditionError:
                self._switch_force_control_off()
                raise
        self.emit(AssistanceChanged(assistance, lease.operator_id))
        return assistance

    def set_indexing(self, lease_id: str, engaged: bool) -> bool:
        self.locks.require(lease_id)
        with self._lock:
            self._indexing = engaged
        return engaged

    def set_tool_frame(self, lease_id: str, flange_to_tool: pin.SE3) -> pin.SE3:
        """The tool frame on the arm and the sensor alike (the contracts promise they agree)."""
        self.locks.require(lease_id)
        return self.slave.set_tool_frame(flange_to_tool)

    # -- control changes --------------------------------------------------------------------

    def _on_control_change(self, view: ControlView, reason: str) -> None:
        """Force control and a replay move the arm by themselves, so each lives only as long as
        the lease that started it: released or lapsed (a crashed operator), it stops and the
        arm holds where it is. The next holder starts them again if they want them."""
        self.emit(ControlChanged(view, reason))
        held = {lease.lease_id for lease in view.holders}
        with self._lock:
            orphans = [s for s in self._sessions.values()
                       if s.detached and s.lease.lease_id not in held]
            replay = self._replay
            if replay is not None and replay.lease_id not in held:
                replay.reason = f"the lease that started it ended ({reason})"
                replay.stop.set()  # its thread ends between two moves; nothing joins it here
        for session in orphans:  # nobody can resume them now
            session.close(f"the lease ended ({reason})")
        with self._lock:
            owner = self._force_lease
            if owner is None or any(h.lease_id == owner.lease_id for h in view.holders):
                return
            self._switch_force_control_off()
        log.warning("force control switched off: %s", reason)
        self.emit(AssistanceChanged(self._assistance, owner.operator_id))

    # -- emergency stop ---------------------------------------------------------------------

    def emergency_stop(self, reason: str) -> str:
        """Stop the arm first, then replay and force control; returns the arm's status.
        Never needs the lock. Raises UnavailableError only when no path latched the stop, and even
        then stops what runs here."""
        try:
            status = self.slave.emergency_stop(reason)
        except TelerobotError:
            self._replace_force_loop(None)
            self._stop_replay(f"emergency stop: {reason}")
            raise
        self.note_status(status, reason)  # the latch pauses force control until a Reset
        self._stop_replay(f"emergency stop: {reason}")
        return status

    def reset(self, lease_id: str) -> str:
        """Clear the latch (the lock holder only); force control, if configured, resumes."""
        self.locks.require(lease_id)
        status = self.slave.reset()
        self.note_status(status, "reset")
        with self._lock:
            if self.latched is None:
                self._replace_force_loop(self._assistance)
        return status

    # -- record and replay ------------------------------------------------------------------

    def start_recording(self, lease_id: str, name: str, format: str = "JSONL", task: str = ""
                        ) -> RecordingInfo:
        """An MCAP recording also samples the arm's latest state and wrench (20 Hz; an
        episode's, with a task, 100 Hz): the samples the streams brought (the arm is asked only
        before its stream's first), on the recording's writer thread; and the stereo video,
        when the server has a camera (which the recording's writer process reads)."""
        self.locks.require(lease_id)
        return self.recordings.start(name, format, Sources(
            lambda: self._state or self.slave.state(), self.slave.wrench, self.camera,
            self._arm_name() if task else ""), task)

    def _arm_name(self) -> str:
        """The arm's name for an episode's metadata; empty (the export then asks for one)
        when ProxyRobot cannot say."""
        try:
            return self.slave.arm_name()
        except TelerobotError as error:
            log.warning("an episode without the arm's name: %s", error.message)
            return ""

    def stop_recording(self, lease_id: str | None, outcome: str = "UNSPECIFIED"
                       ) -> RecordingInfo:
        """End the recording and save it: the lock holder only, as for StartRecording. Whoever
        holds control decides what is recorded of it, so a recording whose starter released
        control or vanished is stopped by the next holder, and nobody else can cut it short."""
        self.locks.require(lease_id)
        return self.recordings.stop(outcome)

    def start_replay(self, lease_id: str, name: str, speed: float,
                     commands: list | None = None) -> RecordingInfo:
        """Replay the stored recording `name`, or `commands` (RecordedCommands sent with the
        request, `name` their label)."""
        lease = self.locks.require(lease_id)
        speed = speed or 1.0
        if not MIN_REPLAY_SPEED <= speed <= MAX_REPLAY_SPEED:
            raise InvalidArgumentError(f"speed must be {MIN_REPLAY_SPEED}..{MAX_REPLAY_SPEED}",
                                       reason="BAD_SPEED")
        if commands is None:
            info, commands = self.recordings.load(name)
        else:
            info = RecordingInfo(name or "increments", self.clock.time_ns(),
                                 commands[-1].offset_s - commands[0].offset_s if commands
                                 else 0.0, len(commands), "UNSPECIFIED")
        with self._lock:
            if self._replay is not None:
                raise FailedPreconditionError("a replay is already running", reason="REPLAYING")
            if any(not session.detached for session in self._sessions.values()):
                raise FailedPreconditionError("an operator is teleoperating: end the session first",
                                              reason="TELEOPERATING")
            if self.latched:
                raise FailedPreconditionError(f"the arm is {self.latched}: Reset it first",
                                              reason=self.latched)
            replay = _Replay(lease.lease_id)
            replay.thread = threading.Thread(target=self._run_replay,
                                             args=(info, commands, speed, replay),
                                             name="replay", daemon=True)
            self._replay = replay
        replay.thread.start()
        return info

    def stop_replay(self, lease_id: str) -> int:
        self.locks.require(lease_id)
        with self._lock:
            if self._replay is None:
                raise FailedPreconditionError("no replay is running", reason="NOT_REPLAYING")
        return self._stop_replay("stopped by the lock holder")

    def _stop_replay(self, reason: str) -> int:
        with self._lock:
            replay = self._replay
            if replay is None:
                return 0
            replay.reason = reason
            replay.stop.set()
        if replay.thread is not threading.current_thread():
            replay.thread.join(2.0)
        return replay.replayed

    def _run_replay(self, info: RecordingInfo, commands, speed: float, replay: _Replay) -> None:
        started = self.clock.monotonic()
        first = commands[0].offset_s if commands else 0.0
        replayed, state, detail = 0, "FINISHED", ""
        self.emit(ReplayProgress(info.name, 0, len(commands), "RUNNING"))
        try:
            for command in commands:
                due = started + (command.offset_s - first) / speed
                if self.clock.wait_until(replay.stop, due):
                    state, detail = "INTERRUPTED", replay.reason
                    break
                if command.delta_joints_rad is not None:
                    self.slave.move_joints(command.delta_joints_rad)
                else:
                    self.slave.move_cartesian(command.delta_position_m, command.delta_rotation,
                                              command.frame)
                replayed = replay.replayed = replayed + 1
                if replayed % 10 == 0:
                    self.emit(ReplayProgress(info.name, replayed, len(commands), "RUNNING"))
        except TelerobotError as error:
            state, detail = "INTERRUPTED", error.message
        finally:
            with self._lock:
                if self._replay is replay:
                    self._replay = None
            self.emit(ReplayProgress(info.name, replayed, len(commands), state, detail))

    # -- force control (active compliance) -------------------------------------------------

    def _replace_force_loop(self, assistance: Assistance | None) -> ForceLoop | None:
        """Stop the running loop and, when `assistance` asks for force control and the arm is
        not latched, start its replacement, which waits for the old loop to end before its
        first step. Never blocks: returns the old loop, for a caller that must join it."""
        with self._lock:
            old = self._force_loop
            new = None
            control = assistance.force_control if assistance is not None else None
            if control is not None and self.latched is None:
                new = ForceLoop(self.slave, control, self.clock, after=old,
                                on_end=self._on_force_loop_end)
            self._force_loop = new
            if old is not None:
                old.stop(wait=False)
            if new is not None:
                new.start()
            return old

    def _switch_force_control_off(self) -> None:
        with self._lock:
            self._force_lease = None
            self._assistance = dataclasses.replace(self._assistance, force_control=None)
            self._replace_force_loop(None)

    def _on_force_loop_end(self, loop: ForceLoop, error: TelerobotError) -> None:
        """The arm refused a step. Refused for a latch (which the state stream may report
        after the loop met it): force control pauses, and a Reset resumes it. Refused for
        anything else (a limit): force control is off, and everyone is told."""
        with self._lock:
            if self._force_loop is not loop:
                return
            if error.reason in LATCHED_STATUSES:
                self._force_loop = None
                return
            owner = self._force_lease
            self._switch_force_control_off()
        self.emit(AssistanceChanged(self._assistance, owner.operator_id if owner else ""))
