"""DecisionCore: the DecisionServer's supervisory logic, with no transport code.

It owns the control lock, the assistance configuration, the emergency-stop latch, the
teleoperation sessions and their watchdogs, record and replay, the force-control loop, and the
cobegin barriers, and it publishes its events. It reaches the arm through a `Slave`.
"""

from __future__ import annotations

import dataclasses
import itertools
import logging
import threading
import time
import uuid
from collections.abc import Callable, Iterator
from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from services.common.fanout import Fanout
from services.decision_server.arbitration import ControlView, Lease, LockManager
from services.decision_server.assistance import Assistance, apply_assistance
from services.decision_server.cobegin import Barriers, SimulatedProcessor
from services.decision_server.recordings import RecordingInfo, RecordingStore
from services.decision_server.slave import Slave, SlaveWrench
from services.runtime.errors import (
    FailedPrecondition,
    InvalidArgument,
    TelerobotError,
    Unavailable,
)

log = logging.getLogger(__name__)

DEFAULT_WATCHDOG_S = 0.1
MIN_WATCHDOG_S, MAX_WATCHDOG_S = 0.01, 5.0
MIN_REPLAY_SPEED, MAX_REPLAY_SPEED = 0.1, 10.0
FORCE_LOOP_RETRY_S = 0.2
FORCE_LOOP_DECIMATION = 5  # the force loop acts on every 5th 1 kHz sample: 200 Hz
# A sample older than this is history, not feedback: the loop skips it to catch up. Acting on
# a backlog (gRPC's transport buffers hold seconds of samples when the loop falls behind on a
# loaded machine) would add that whole delay to the loop, and a contact loop with K ≈ 1e5 N/m
# goes unstable once A·K·delay nears π/2.
FORCE_LOOP_MAX_SAMPLE_AGE_NS = 50_000_000


# -- events -------------------------------------------------------------------------------

@dataclass(frozen=True)
class ControlChanged:
    view: ControlView
    reason: str


@dataclass(frozen=True)
class WatchdogHold:
    session_id: str
    reason: str
    silence_s: float


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
class RobotEventForwarded:
    message: object  # the ProxyRobot event, as it came


@dataclass
class _Replay:
    """A running replay: its thread, how to stop it, and how far it got."""

    thread: threading.Thread | None = None
    stop: threading.Event = dataclasses.field(default_factory=threading.Event)
    reason: str = ""
    replayed: int = 0


@dataclass(frozen=True)
class DecisionEvent:
    sequence: int
    time_ns: int
    payload: object


# -- teleoperation --------------------------------------------------------------------------

@dataclass(frozen=True)
class CommandResult:
    outcome: str  # APPLIED, MODIFIED, INDEXED, REJECTED, HEARTBEAT
    detail: str
    receive_time_ns: int
    apply_time_ns: int


class TeleopSession:
    """One operator's Teleoperate stream: increments in, the watchdog behind them."""

    def __init__(self, core: DecisionCore, operator_id: str, lease: Lease, mapping: str | None,
                 watchdog_s: float):
        self.core = core
        self.session_id = uuid.uuid4().hex[:12]
        self.operator_id = operator_id
        self.lease = lease
        self.mapping = mapping
        self.watchdog_s = watchdog_s
        self._last_activity = time.monotonic()
        self._target: pin.SE3 | None = None  # tool pose at the last accepted target
        self._held = False
        self._closed = threading.Event()
        self._activity = threading.Event()
        self._watchdog = threading.Thread(target=self._watch, name=f"watchdog-{self.session_id}",
                                          daemon=True)
        self._watchdog.start()

    def heartbeat(self) -> CommandResult:
        now = time.time_ns()
        self._touch()
        return CommandResult("HEARTBEAT", "", now, now)

    def command(self, delta_position: np.ndarray, delta_rotation: np.ndarray,
                clutch_engaged: bool) -> CommandResult:
        receive = time.time_ns()
        self._touch()
        self.core.locks.require(self.lease.lease_id)  # FailedPrecondition ends the stream
        if clutch_engaged or self.core.indexing:
            self._target = None  # the reference follows the hand; re-read the pose after
            return CommandResult("INDEXED", "indexing is engaged", receive, receive)
        if self.core.estopped:
            return CommandResult("REJECTED", "an emergency stop is latched: reset it first",
                                 receive, receive)
        assistance = self.core.assistance
        mapping = self.mapping or assistance.mapping
        assistance = dataclasses.replace(assistance, mapping=mapping)
        tool = self._target or self.core.slave.state().tool_pose
        dx, dm, modified = apply_assistance(assistance, delta_position, delta_rotation, tool)
        try:
            result = self.core.slave.move_cartesian(dx, dm, mapping)
        except Unavailable:
            raise  # the arm is unreachable: the stream ends, it is not one refused command
        except TelerobotError as error:
            return CommandResult("REJECTED", error.message, receive, time.time_ns())
        applied = time.time_ns()
        self._target = result.target_tool_pose
        self.core.recordings.add(mapping, dx, dm, result.target_tool_pose.translation)
        modified = modified or result.applied_fraction < 1.0
        return CommandResult("MODIFIED" if modified else "APPLIED",
                             "" if result.applied_fraction == 1.0 else
                             f"reduced to {result.applied_fraction:.2f} near a singularity",
                             receive, applied)

    def close(self, reason: str) -> None:
        """The stream ended: hold the arm, unless the watchdog already did."""
        if self._closed.is_set():
            return
        self._closed.set()
        self._activity.set()
        if not self._held:
            self._hold(reason)
        self.core._sessions.pop(self.session_id, None)  # noqa: SLF001 - the core's registry

    def _touch(self) -> None:
        self._last_activity = time.monotonic()
        self._held = False
        self._activity.set()

    def _watch(self) -> None:
        while True:
            # Clear before reading the state, so a command or a close that lands in between
            # still wakes the wait below instead of being missed.
            self._activity.clear()
            if self._closed.is_set():
                return
            remaining = self._last_activity + self.watchdog_s - time.monotonic()
            if remaining > 0:
                self._activity.wait(remaining)
                continue
            if not self._held:
                self._hold("watchdog timeout: no command or heartbeat")
            self._activity.wait()

    def _hold(self, reason: str) -> None:
        self._held = True
        silence = time.monotonic() - self._last_activity
        self._target = None
        try:
            self.core.slave.hold(reason)
        except TelerobotError as error:
            log.warning("session %s: hold failed: %s", self.session_id, error.message)
        self.core.emit(WatchdogHold(self.session_id, reason, silence))


# -- the core -------------------------------------------------------------------------------

class DecisionCore:
    def __init__(self, slave: Slave, recordings: RecordingStore,
                 wrench_stream: Callable[[int], Iterator[SlaveWrench]] | None = None):
        self.slave = slave
        self.recordings = recordings
        self._wrench_stream = wrench_stream
        self._lock = threading.Lock()
        self._event_sequence = itertools.count(1)
        self.events: Fanout[DecisionEvent] = Fanout()
        self.locks = LockManager(self._on_control_change)
        self.assistance = Assistance()
        self._force_lease: Lease | None = None  # the lease that switched force control on
        self.indexing = False
        self.estopped = False
        self._sessions: dict[str, TeleopSession] = {}
        self._replay: _Replay | None = None
        self._force_loop: tuple[threading.Thread, threading.Event] | None = None
        self.barriers = Barriers()
        self.processor = SimulatedProcessor()

    def emit(self, payload) -> None:
        self.events.publish(DecisionEvent(next(self._event_sequence), time.time_ns(), payload))

    def _on_control_change(self, view: ControlView, reason: str) -> None:
        """Force control moves the arm by itself, so it lives only as long as the lease that
        switched it on: released or lapsed (a crashed operator), it stops and the arm holds
        where it is. The next holder switches it on again if they want it."""
        self.emit(ControlChanged(view, reason))
        owner = self._force_lease
        if owner is None or any(lease.lease_id == owner.lease_id for lease in view.holders):
            return
        self._force_lease = None
        self._stop_force_loop()
        self.assistance = dataclasses.replace(self.assistance, force_control=None)
        log.warning("force control switched off: %s", reason)
        self.emit(AssistanceChanged(self.assistance, owner.operator_id))

    def close(self) -> None:
        self._stop_replay("the server is stopping")
        self._stop_force_loop()
        for session in list(self._sessions.values()):
            session.close("the server is stopping")
        self.locks.close()
        self.events.close_all()

    # -- teleoperation ----------------------------------------------------------------------

    def open_session(self, operator_id: str, lease_id: str, mapping: str | None,
                     watchdog_s: float) -> TeleopSession:
        lease = self.locks.require(lease_id)
        watchdog_s = watchdog_s or DEFAULT_WATCHDOG_S
        if not MIN_WATCHDOG_S <= watchdog_s <= MAX_WATCHDOG_S:
            raise InvalidArgument(f"watchdog_timeout must be {MIN_WATCHDOG_S * 1e3:.0f} ms.."
                                  f"{MAX_WATCHDOG_S:.0f} s", reason="BAD_WATCHDOG")
        if self.estopped:
            raise FailedPrecondition("an emergency stop is latched: Reset it first",
                                     reason="ESTOPPED")
        status = self.slave.state().status
        if status not in ("READY", "MOVING"):
            raise FailedPrecondition(f"the arm is {status}: Connect and Initialize it first",
                                     reason=status)
        if self._replay is not None:
            raise FailedPrecondition("a replay is running: stop it first", reason="REPLAYING")
        session = TeleopSession(self, operator_id or lease.operator_id, lease, mapping,
                                watchdog_s)
        self._sessions[session.session_id] = session
        return session

    # -- assistance and indexing ------------------------------------------------------------

    def set_assistance(self, lease_id: str, assistance: Assistance) -> Assistance:
        lease = self.locks.require(lease_id)
        assistance.validated()
        constraint = assistance.constraint
        if constraint is not None and constraint.anchor_m is None:
            anchor = self.slave.state().tool_pose.translation.copy()
            assistance = dataclasses.replace(
                assistance, constraint=dataclasses.replace(constraint, anchor_m=anchor))
        self.assistance = assistance
        self._stop_force_loop()
        self._force_lease = lease if assistance.force_control is not None else None
        if assistance.force_control is not None:
            self._start_force_loop(assistance)
        self.emit(AssistanceChanged(assistance, lease.operator_id))
        return assistance

    def set_indexing(self, lease_id: str, engaged: bool) -> bool:
        self.locks.require(lease_id)
        self.indexing = engaged
        return engaged

    # -- emergency stop ---------------------------------------------------------------------

    def emergency_stop(self, reason: str) -> None:
        """Latch, stop replay and force control, and stop the arm. Never needs the lock."""
        self.estopped = True
        self.slave.emergency_stop(reason)
        self._stop_replay(f"emergency stop: {reason}")
        self._stop_force_loop()

    def reset(self, lease_id: str) -> None:
        self.locks.require(lease_id)
        self.slave.reset()
        self.estopped = False
        if self.assistance.force_control is not None:
            self._start_force_loop(self.assistance)

    # -- record and replay ------------------------------------------------------------------

    def start_recording(self, lease_id: str, name: str) -> RecordingInfo:
        self.locks.require(lease_id)
        return self.recordings.start(name)

    def start_replay(self, lease_id: str, name: str, speed: float) -> RecordingInfo:
        self.locks.require(lease_id)
        speed = speed or 1.0
        if not MIN_REPLAY_SPEED <= speed <= MAX_REPLAY_SPEED:
            raise InvalidArgument(f"speed must be {MIN_REPLAY_SPEED}..{MAX_REPLAY_SPEED}",
                                  reason="BAD_SPEED")
        info, commands = self.recordings.load(name)
        if self._replay is not None:
            raise FailedPrecondition("a replay is already running", reason="REPLAYING")
        if self._sessions:
            raise FailedPrecondition("an operator is teleoperating: end the session first",
                                     reason="TELEOPERATING")
        if self.estopped:
            raise FailedPrecondition("an emergency stop is latched: Reset it first",
                                     reason="ESTOPPED")
        replay = _Replay()
        replay.thread = threading.Thread(target=self._run_replay,
                                         args=(info, commands, speed, replay),
                                         name="replay", daemon=True)
        self._replay = replay
        replay.thread.start()
        return info

    def stop_replay(self, lease_id: str) -> int:
        self.locks.require(lease_id)
        if self._replay is None:
            raise FailedPrecondition("no replay is running", reason="NOT_REPLAYING")
        return self._stop_replay("stopped by the lock holder")

    def _stop_replay(self, reason: str) -> int:
        replay = self._replay
        if replay is None:
            return 0
        replay.reason = reason
        replay.stop.set()
        if replay.thread is not threading.current_thread():
            replay.thread.join(2.0)
        return replay.replayed

    def _run_replay(self, info: RecordingInfo, commands, speed: float, replay: _Replay) -> None:
        started = time.monotonic()
        first = commands[0].offset_s if commands else 0.0
        replayed, state, detail = 0, "FINISHED", ""
        self.emit(ReplayProgress(info.name, 0, len(commands), "RUNNING"))
        try:
            for command in commands:
                due = started + (command.offset_s - first) / speed
                if replay.stop.wait(max(0.0, due - time.monotonic())):
                    state, detail = "INTERRUPTED", replay.reason
                    break
                self.slave.move_cartesian(command.delta_position_m, command.delta_rotation,
                                          command.frame)
                replayed = replay.replayed = replayed + 1
                if replayed % 10 == 0:
                    self.emit(ReplayProgress(info.name, replayed, len(commands), "RUNNING"))
        except TelerobotError as error:
            state, detail = "INTERRUPTED", error.message
        finally:
            self._replay = None
            self.emit(ReplayProgress(info.name, replayed, len(commands), state, detail))

    # -- force control (active compliance) -------------------------------------------------

    def _start_force_loop(self, assistance: Assistance) -> None:
        if self._wrench_stream is None or self.estopped:
            return
        stop = threading.Event()
        thread = threading.Thread(target=self._run_force_loop, args=(assistance, stop),
                                  name="force-control", daemon=True)
        self._force_loop = (thread, stop)
        thread.start()

    def _stop_force_loop(self) -> None:
        loop, self._force_loop = self._force_loop, None
        if loop is not None:
            loop[1].set()
            if loop[0] is not threading.current_thread():
                loop[0].join(2.0)

    def _run_force_loop(self, assistance: Assistance, stop: threading.Event) -> None:
        while not stop.is_set():
            try:
                self._force_control_steps(assistance, stop)
            except Unavailable as error:  # the sensor stalled: subscribe again once it is back
                log.warning("force control paused: %s", error.message)
                stop.wait(FORCE_LOOP_RETRY_S)
            except TelerobotError as error:
                log.warning("force control stopped: %s", error.message)
                return

    def _force_control_steps(self, assistance: Assistance, stop: threading.Event) -> None:
        """ΔT = A·(F_t − F_d), ΔM = B·(C_t − C_d) on the selected tool axes, per sample, until
        stopped; Unavailable when the sensor's stream ends."""
        control = assistance.force_control
        axes = control.axes
        previous_ns = None
        for sample in self._wrench_stream(FORCE_LOOP_DECIMATION):
            if stop.is_set():
                return
            if time.time_ns() - sample.sample_time_ns > FORCE_LOOP_MAX_SAMPLE_AGE_NS:
                previous_ns = None  # the target did not move meanwhile: integrate nothing
                continue
            if previous_ns is None:
                previous_ns = sample.sample_time_ns
                continue
            dt = min((sample.sample_time_ns - previous_ns) * 1e-9, 0.05)
            previous_ns = sample.sample_time_ns
            if dt <= 0 or self.estopped:
                continue
            force_error = (sample.force_n - control.desired_force_n) * axes[:3]
            torque_error = (sample.torque_nm - control.desired_torque_nm) * axes[3:]
            delta_x = control.translation_gain_m_per_n_s * force_error * dt
            delta_m = pin.exp3(control.rotation_gain_rad_per_nm_s * torque_error * dt)
            try:
                self.slave.move_cartesian(delta_x, delta_m, "TOOL")
            except TelerobotError as error:
                if isinstance(error, Unavailable):
                    raise
                log.debug("force control step refused: %s", error.message)


def build_core(slave, recordings_dir) -> DecisionCore:
    """A core on a GrpcSlave-like slave, with its robot events forwarded to the core's own."""
    core = DecisionCore(slave, RecordingStore(recordings_dir), slave.wrench_stream)
    slave.on_robot_event = lambda message: core.emit(RobotEventForwarded(message))
    return core
