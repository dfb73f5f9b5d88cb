"""Operator sessions: one operator's stream of master increments, the watchdog behind them,
and what lets a session outlive its stream. No transport code.

A session is served by one stream at a time. When that stream breaks (a cut link: anything but
the operator's own close), the arm holds and the session waits, *detached*, for up to
RESUME_WINDOW_S for a stream with the same lease to resume it. Every command carries a sequence
number that increases within the session; a command whose sequence was already processed is a
resend (the master did not get its ack before the cut) and is answered with its first result
instead of being applied again. So across a cut nothing is applied twice, and nothing the
master still waits for is lost: it resends what was not acked.

No command moves the arm on its own once it is stale: one that waited in the station longer than
the session's `max_command_age` before its turn (a backlog behind a slow arm or a starved
process) is carried, its ack held back, until a fresh command comes; the two go to the arm as one
move, and the late one's ack says MERGED_LATE. Motion is not lost, and the arm goes to where the
operator is now instead of replaying where they were. A carry that grows past one move's bounds,
or older than BACKLOG_AGE_FACTOR ages, is refused instead and the arm holds; so is one that
anything else overtakes (the clutch, a latch, a hold): its acks say REJECTED and why.
"""

from __future__ import annotations

import dataclasses
import logging
import math
import threading
import uuid
from collections import OrderedDict
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from typing import Protocol

import numpy as np
import pinocchio as pin

from domain.geometry import moved_by, rotation_angle, vector_norm
from domain.passivity import SlavePassivity
from services.decision_server.arbitration import Lease
from services.decision_server.assistance import Assistance, apply_assistance
from services.decision_server.clock_offset import ClockOffsetEstimator
from services.decision_server.slave import Slave, SlaveWrench
from services.runtime.clock import Clock
from wire.errors import AbortedError, FailedPreconditionError, TelerobotError, UnavailableError

log = logging.getLogger(__name__)

# A broken session waits this long to be resumed (and its lease must still be held): a cut of
# a few seconds, the ~1 s the keepalives take to notice it and a reconnect fit well inside.
RESUME_WINDOW_S = 10.0
# Results kept for answering resends. A resend is a command whose ack was lost in a cut: at
# most what was in flight when the link went, about a round trip's worth (400 at 1 kHz over
# 400 ms), so 4,096 is ample; an older resend is answered DUPLICATE without its first result.
RESULTS_KEPT = 4096
# A command may wait this long in the station and still be applied on its own (the session's
# max_command_age unless its init says otherwise), within these bounds.
DEFAULT_MAX_COMMAND_AGE_S = 0.05
MIN_MAX_COMMAND_AGE_S, MAX_MAX_COMMAND_AGE_S = 0.005, 1.0
# A late carry older than this many max_command_ages is a backlog: refused, and the arm holds.
BACKLOG_AGE_FACTOR = 10


# -- events -----------------------------------------------------------------------------------

@dataclass(frozen=True)
class WatchdogHold:
    session_id: str
    reason: str
    silence_s: float


@dataclass(frozen=True)
class SessionCounts:
    processed: int = 0  # commands given an outcome, once each
    applied: int = 0  # of those, APPLIED or MODIFIED
    resends: int = 0  # resends answered with their first result
    last_sequence: int = 0


@dataclass(frozen=True)
class SessionChanged:
    session_id: str
    operator_id: str
    state: str  # OPENED, DETACHED, RESUMED, CLOSED
    reason: str
    counts: SessionCounts


class SessionHost(Protocol):
    """What a session needs of the DecisionServer's core (DecisionCore is the one)."""

    clock: Clock
    slave: Slave

    def emit(self, payload) -> None:
        """Publish an event to the watchers."""

    def require_lease(self, lease_id: str) -> Lease:
        """The lease, renewed; FailedPreconditionError if it is no longer held."""

    def snapshot(self) -> tuple[Assistance, bool, str | None]:
        """(assistance, indexing engaged, the latched stop or None), read together."""

    def sensor_lost(self) -> str | None:
        """Why the force sensor is lost, or None."""

    def wrench(self) -> SlaveWrench | None:
        """The latest wrench, or None."""

    def record_increment(self, mapping: str, translation: np.ndarray, rotation: np.ndarray,
                         target_translation: np.ndarray) -> None:
        """Add an applied increment to the recording in progress, if any."""

    def forget_session(self, session_id: str) -> None:
        """The session ended: stop routing resumes to it."""


# -- commands ---------------------------------------------------------------------------------

APPLIED_OUTCOMES = ("APPLIED", "MODIFIED", "MERGED_LATE")


@dataclass(frozen=True)
class CommandResult:
    outcome: str  # APPLIED, MODIFIED, MERGED_LATE, INDEXED, REJECTED, HEARTBEAT, DUPLICATE
    detail: str
    receive_time_ns: int
    apply_time_ns: int


@dataclass(frozen=True)
class MasterIncrement:
    """One master command: ΔX (m) and ΔM in the session's mapping frame, the clutch, when the
    server received it, and its sequence number (0: none, never taken for a resend)."""

    delta_position: np.ndarray
    delta_rotation: np.ndarray
    clutch_engaged: bool
    receive_time_ns: int
    sequence: int = 0
    master_energy_in_j: float | None = None  # the master port's E_in it carried (TDPA)
    send_time_ns: int = 0  # when the master sent it, on its clock (0: not said)


# A merged move stays well inside ProxyRobot's caps per move (50 mm, 15 deg), so merging never
# turns acceptable commands into one refused move; and at most 50 commands (50 ms at 1 kHz).
MAX_MERGED_COMMANDS = 50
MAX_MERGED_TRANSLATION_M = 0.02
MAX_MERGED_ROTATION_RAD = np.radians(5.0)


def merge_groups(increments: list[MasterIncrement]) -> list[list[MasterIncrement]]:
    """Consecutive commands that may share one move: all motion (clutch released) or all
    clutch, at most MAX_MERGED_COMMANDS, their summed sizes within the merge bounds."""
    groups: list[list[MasterIncrement]] = []
    translation = rotation = 0.0
    for increment in increments:
        size = vector_norm(increment.delta_position)
        angle = rotation_angle(increment.delta_rotation)
        group = groups[-1] if groups else None
        if (group is not None and group[0].clutch_engaged == increment.clutch_engaged
                and len(group) < MAX_MERGED_COMMANDS
                and translation + size <= MAX_MERGED_TRANSLATION_M
                and rotation + angle <= MAX_MERGED_ROTATION_RAD):
            group.append(increment)
            translation, rotation = translation + size, rotation + angle
        else:
            groups.append([increment])
            translation, rotation = size, angle
    return groups


def compose(first: pin.SE3, then: pin.SE3, mapping: str) -> pin.SE3:
    """One increment with the effect of `first` followed by `then` (see
    domain.geometry.moved_by)."""
    if mapping == "TOOL":
        return first * then
    return pin.SE3(then.rotation @ first.rotation, first.translation + then.translation)


class _Resends:
    """The session's memory of what it processed: the highest sequence, the results of the
    newest RESULTS_KEPT commands, and the counts."""

    def __init__(self):
        self.last_sequence = 0
        self._results: OrderedDict[int, CommandResult] = OrderedDict()
        self.processed = self.applied = self.answered = 0

    def split(self, increments: list[MasterIncrement]) -> list[bool]:
        """For each increment, in order: whether it is a resend (its sequence was processed,
        in an earlier batch or earlier in this one)."""
        high, flags = self.last_sequence, []
        for increment in increments:
            resend = 0 < increment.sequence <= high
            flags.append(resend)
            high = max(high, increment.sequence)
        return flags

    def record(self, increments: list[MasterIncrement], results: list[CommandResult]) -> None:
        for increment, result in zip(increments, results, strict=True):
            self.processed += 1
            self.applied += result.outcome in APPLIED_OUTCOMES
            if increment.sequence > 0:
                self.last_sequence = max(self.last_sequence, increment.sequence)
                self._results[increment.sequence] = result
        while len(self._results) > RESULTS_KEPT:
            self._results.popitem(last=False)

    def answer(self, increment: MasterIncrement) -> CommandResult:
        self.answered += 1
        first = self._results.get(increment.sequence)
        if first is not None:
            return first
        return CommandResult("DUPLICATE", f"command {increment.sequence} was processed before; "
                             "its result is no longer kept", increment.receive_time_ns,
                             increment.receive_time_ns)

    def counts(self) -> SessionCounts:
        return SessionCounts(self.processed, self.applied, self.answered, self.last_sequence)


class OperatorSession:
    """One operator's Teleoperate session: increments in, the watchdog behind them.

    Threads: one stream at a time calls `commands`/`heartbeat` (`_serving` keeps a superseded
    stream's last batch and a resuming one apart); the watchdog thread, `end`, `resume` and
    `close` share `_lock`; every hold waits for a move in flight (`_moving`), so the hold is
    the last word. `stream` numbers the streams: each resume supersedes the one before."""

    def __init__(self, core: SessionHost, operator_id: str, lease: Lease, mapping: str | None,
                 watchdog_s: float, resume_window_s: float = RESUME_WINDOW_S,
                 passivity: SlavePassivity | None = None,
                 max_command_age_s: float = DEFAULT_MAX_COMMAND_AGE_S):
        self.core = core
        # TDPA's slave port (domain.passivity), or None: increments applied as sent.
        self.passivity = passivity
        self.session_id = uuid.uuid4().hex[:12]
        self.operator_id = operator_id
        self.lease = lease
        self.mapping = mapping
        self.watchdog_s = watchdog_s
        self.resume_window_s = resume_window_s
        self.max_command_age_s = max_command_age_s
        self._clock = core.clock
        self._lock = threading.Lock()
        self._moving = threading.Lock()  # held across a move; see close()
        self._serving = threading.Lock()  # held across a batch; see `stream`
        self._resends = _Resends()
        # The master's clock offset from the session's exchanges (its serving thread's).
        self.clock_offset = ClockOffsetEstimator()
        # Late commands waiting for a fresh one (see the module's docstring), with the stream
        # they came on and the holds so far when they were carried: a new stream or a hold since
        # overtakes them.
        self._late: list[MasterIncrement] = []
        self._late_since: tuple[int, int] = (0, 0)
        self._holds = 0
        # Called after a hold the watchdog made, so the stream's serving thread answers the
        # late commands it overtook (decide([])) without waiting for a command that may never
        # come: a client that waits for each ack sends none. Set by the stream's server.
        self.wake_server: Callable[[], None] | None = None
        self.stream = 1
        self._detached_at: float | None = None
        self._last_activity = self._clock.monotonic()
        self._target: pin.SE3 | None = None  # tool pose at the last accepted target
        # (where a sensor check's stop left the arm, where it was going)
        self._held_short_of: tuple[pin.SE3, pin.SE3] | None = None
        self._held = False  # for the operator's silence, or the session's end
        # The watchdog asked the sensor during this quiet spell (the next command asks again):
        # apart from _held, so that a lost sensor's hold never hides the operator's silence.
        self._sensor_asked = False
        self._sensor_was_lost = False
        self._sensor_checking = threading.Lock()
        self._closed = threading.Event()
        self._activity = threading.Event()
        self._watch_until = math.inf  # when the watchdog's wait ends (monotonic s)
        self._watchdog = threading.Thread(target=self._watch, name=f"watchdog-{self.session_id}",
                                          daemon=True)

    def start(self) -> OperatorSession:
        self._watchdog.start()
        self.core.emit(self._changed("OPENED", f"watchdog {self.watchdog_s * 1e3:.0f} ms"))
        return self

    @property
    def last_sequence(self) -> int:
        return self._resends.last_sequence

    @property
    def detached(self) -> bool:
        return self._detached_at is not None

    @property
    def closed(self) -> bool:
        return self._closed.is_set()

    def counts(self) -> SessionCounts:
        with self._serving:
            return self._resends.counts()

    def heartbeat(self, stream: int = 1, master_energy_in_j: float | None = None
                  ) -> CommandResult:
        with self._serving:
            self._require_stream(stream)
            self._heard(master_energy_in_j)
            now = self._clock.time_ns()
            self._touch()
            # Renews the lease; FailedPreconditionError if it is lost.
            self.core.require_lease(self.lease.lease_id)
            return CommandResult("HEARTBEAT", "", now, now)

    def ending(self, stream: int = 1) -> list[tuple[MasterIncrement, CommandResult]]:
        """The operator ends the session on `stream`: the late commands it carries, which no
        fresh command will join now, refused (every command the operator sent is answered)."""
        with self._serving:
            if stream != self.stream or not self._late:
                return []
            late, self._late = self._late, []
            group, results = self._refused(late, "the operator ended the session before a "
                                                 "fresh command came")
            self._resends.record(group, results)
            return list(zip(group, results, strict=True))

    def command(self, delta_position: np.ndarray, delta_rotation: np.ndarray,
                clutch_engaged: bool) -> CommandResult:
        """One master command, received now."""
        return self.commands([MasterIncrement(delta_position, delta_rotation, clutch_engaged,
                                              self._clock.time_ns())])[0]

    def commands(self, increments: list[MasterIncrement], stream: int = 1
                 ) -> list[CommandResult]:
        """The results `decide` gives, without their commands."""
        return [result for _, result in self.decide(increments, stream)]

    def decide(self, increments: list[MasterIncrement], stream: int = 1
               ) -> list[tuple[MasterIncrement, CommandResult]]:
        """Master commands that arrived together on `stream` (a backlog behind a slow arm), in
        order, and the results decided now, each with its command, in order: resends answered
        with their first result, then the rest processed, consecutive motion commands going to
        the arm as one move, their increments composed (see `merge_groups`), so a backlog costs
        one arm round trip instead of one per command, and the newest command reaches the arm
        soonest. Late commands (see the module's docstring) get their results later, with the
        fresh command they join; ones carried from earlier batches may come first here."""
        if not increments and not self._late:
            return []
        with self._serving:
            self._require_stream(stream)
            for increment in increments:
                self._heard(increment.master_energy_in_j)
            resend = self._resends.split(increments)
            decided = [(i, self._resends.answer(i))
                       for i, again in zip(increments, resend, strict=True) if again]
            fresh = [i for i, again in zip(increments, resend, strict=True) if not again]
            # Recorded group by group: if the stream breaks mid-batch, what moved the arm is
            # remembered (a resend of it is answered) and the rest counts as never received.
            for group, results in self._process(fresh, stream):
                self._resends.record(group, results)
                decided += zip(group, results, strict=True)
            return decided

    def _heard(self, master_energy_in_j: float | None) -> None:
        if self.passivity is not None and master_energy_in_j is not None:
            self.passivity.heard(master_energy_in_j)

    def _require_stream(self, stream: int) -> None:
        if stream != self.stream:
            raise AbortedError("another stream resumed this session", reason="SUPERSEDED")

    def _process(self, increments: list[MasterIncrement], stream: int
                 ) -> Iterator[tuple[list[MasterIncrement], list[CommandResult]]]:
        """Each group of `increments` (see merge_groups) with its results, as it is done;
        first, late commands a hold overtook (none left to join)."""
        yield from self._refuse_overtaken(stream)
        if not increments:
            return
        self._touch()
        holds = self._holds  # a hold from here on (the watchdog's) overtakes what this carries
        self.core.require_lease(self.lease.lease_id)  # FailedPreconditionError ends the stream
        assistance, indexing, latched = self.core.snapshot()
        sensor_lost = self._sensor_check()
        for group in merge_groups(increments):
            first = group[0]
            if first.clutch_engaged or indexing:
                self._target = None  # the reference follows the hand; re-read the pose after
                yield from self._refuse_late("indexing engaged before a fresh command came")
                yield group, [CommandResult("INDEXED", "indexing is engaged", i.receive_time_ns,
                                            i.receive_time_ns) for i in group]
            elif latched or sensor_lost:
                why = f"the arm is {latched}: Reset it first" if latched else sensor_lost
                yield from self._refuse_late(why)
                yield self._refused(group, why)
            elif self._is_late(group[-1]):
                first = not self._late
                if first:
                    self._late_since = (stream, holds)
                self._late += group  # its results come with the fresh command it joins
                if first:  # the watchdog watches for that command (after the carry exists)
                    with self._lock:
                        self._held = self._sensor_asked = False
                    self._activity.set()
            else:
                group, self._late = self._late + group, []
                ages = [self._age_s(i) for i in group]
                backlog = self._backlog(group, ages)
                if backlog:
                    with self._moving:
                        self._hold(backlog)
                    holds = self._holds  # (this batch's own hold: a later carry is not behind it)
                    yield self._refused(group, backlog)
                else:
                    yield group, self._with_late(group, ages,
                                                 self._move(assistance, group, stream))
        # A carry the watchdog overtook meanwhile (its wake-up came before the carry did).
        yield from self._refuse_overtaken(stream)

    def _is_late(self, increment: MasterIncrement) -> bool:
        return self._age_s(increment) > self.max_command_age_s

    def _age_s(self, increment: MasterIncrement) -> float:
        """How long `increment` has waited in the station."""
        return (self._clock.time_ns() - increment.receive_time_ns) / 1e9

    def _backlog(self, group: list[MasterIncrement], ages: list[float]) -> str | None:
        """Why `group` (late commands and the fresh one they join) is a backlog to refuse rather
        than one move, or None."""
        late = sum(age > self.max_command_age_s for age in ages)
        if not late:
            return None
        if ages[0] > BACKLOG_AGE_FACTOR * self.max_command_age_s:
            return (f"a backlog: {late} commands waited up to {ages[0] * 1e3:.0f} ms, past "
                    f"{BACKLOG_AGE_FACTOR} x max_command_age; the arm holds")
        translation = vector_norm(sum(i.delta_position for i in group))
        rotation = sum(rotation_angle(i.delta_rotation) for i in group)
        if translation > MAX_MERGED_TRANSLATION_M or rotation > MAX_MERGED_ROTATION_RAD:
            return (f"a backlog: {late} late commands and the fresh one add up to "
                    f"{translation * 1e3:.1f} mm and {np.degrees(rotation):.1f} deg, more than "
                    "one move may carry; the arm holds")
        return None

    def _with_late(self, group: list[MasterIncrement], ages: list[float],
                   results: list[CommandResult]) -> list[CommandResult]:
        """The move's results, the late commands' marked MERGED_LATE."""
        joined = group[-1].sequence
        return [dataclasses.replace(result, outcome="MERGED_LATE",
                                    detail=f"waited {age * 1e3:.0f} ms; applied with command "
                                           f"{joined}")
                if result.outcome in ("APPLIED", "MODIFIED") and age > self.max_command_age_s
                else result
                for age, result in zip(ages, results, strict=True)]

    def _refuse_overtaken(self, stream: int):
        if self._late and self._late_since != (stream, self._holds):
            if self._late_since[0] == stream:  # a hold overtook them; (a new stream: resent)
                yield self._refused(self._late, "the arm held before a fresh command came")
            self._late = []

    def _refuse_late(self, why: str):
        if self._late:
            late, self._late = self._late, []
            yield self._refused(late, why)

    def _refused(self, group: list[MasterIncrement], why: str
                 ) -> tuple[list[MasterIncrement], list[CommandResult]]:
        now = self._clock.time_ns()
        return group, [CommandResult("REJECTED", why, i.receive_time_ns, now) for i in group]

    def _sensor_check(self) -> str | None:
        """Why the sensor is lost (see DecisionCore.sensor_lost); the first time, the arm is
        told to hold, so a move in flight stops too. Once it is back, the next move starts from
        the arm's measured pose. Called for each batch of commands, and by the watchdog when
        the wrench goes quiet between them; one at a time."""
        with self._sensor_checking:
            self._held_short_of = None
            lost = self.core.sensor_lost(before_asking=self._hold_while_asking)
            if lost and not self._sensor_was_lost:
                log.warning("session %s: %s", self.session_id, lost)
                with self._moving:
                    self._hold(lost)  # (with a watchdog_hold event that says why)
            elif not lost and self._held_short_of is not None:
                self._finish_held_segment(*self._held_short_of)
            self._sensor_was_lost = bool(lost)
        # What the sensor said may bring the watchdog's next check of it sooner (a sensor now
        # streaming, which it was not when the watchdog planned its wait).
        due_in_s = self.core.sensor_check_due_in_s()
        if due_in_s is not None and self._clock.monotonic() + max(due_in_s, 0.0) < \
                self._watch_until:
            self._activity.set()
        return lost

    def _hold_while_asking(self) -> None:
        """The wrench went stale: the arm stops where it can while the sensor is asked
        whether it is alive (a hung one takes all of the probe's time to say nothing). If it
        answers, the segment the stop cut is finished (_finish_held_segment)."""
        if self._sensor_was_lost:
            return
        self._target = None
        with self._moving:  # (no event: the stop lasts one question, and is most often resumed)
            try:
                self._held_short_of = self.core.slave.hold(
                    "the force sensor's wrench went stale; asking the sensor")
            except TelerobotError as error:  # the arm's own watchdogs hold it anyway
                log.warning("could not hold the arm: %s", error.message)

    def _finish_held_segment(self, here: pin.SE3, target: pin.SE3) -> None:
        """The sensor answered after a stop while it was asked: the arm goes on from where the
        stop left it (`here`) to where it was going, so the stop loses no motion (whoever gave
        it that target). Not recorded: the recorded increments already lead there."""
        with self._moving:
            if self._closed.is_set() or self._detached_at is not None:
                return
            try:
                result = self.core.slave.move_cartesian(
                    target.translation - here.translation,
                    target.rotation @ here.rotation.T, "BASE")
            except TelerobotError as error:
                log.warning("could not finish the segment the sensor check cut: %s",
                            error.message)
                return
        self._target = result.target_tool_pose

    def _move(self, assistance: Assistance, group: list[MasterIncrement], stream: int
              ) -> list[CommandResult]:
        """One move for a group of motion commands: each gets the assistance at the pose the
        ones before it lead to; the composed increment goes to the arm."""
        mapping = self.mapping or assistance.mapping
        assistance = dataclasses.replace(assistance, mapping=mapping)
        tool = self._target or self.core.slave.state().tool_pose
        total = pin.SE3.Identity()
        modified_by_assistance = []
        force_tool = self._environment_force() if self.passivity is not None else None
        for increment in group:
            dx, dm, modified = apply_assistance(assistance, increment.delta_position,
                                                increment.delta_rotation, tool)
            if self.passivity is not None:
                # The environment's force in the mapping frame, where the increments are.
                force = force_tool if mapping == "TOOL" else tool.rotation @ force_tool
                limited = self.passivity.step(dx, force)
                dx, modified = limited.step_m, modified or limited.dissipated_j > 0.0
            step = pin.SE3(dm, dx)
            tool = moved_by(tool, step, mapping)
            total = compose(total, step, mapping)
            modified_by_assistance.append(modified)
        with self._moving:  # close() and end() hold the arm only after a move in flight landed
            if self._detached_at is not None or stream != self.stream:
                # The stream broke while this batch ran: the arm holds, and the rest of the
                # batch counts as never received (the master resends it after resuming).
                raise AbortedError("the session's stream broke", reason="STREAM_BROKEN")
            try:
                if self._closed.is_set():
                    raise FailedPreconditionError("the session has ended", reason="SESSION_ENDED")
                result = self.core.slave.move_cartesian(total.translation, total.rotation,
                                                        mapping)
            except UnavailableError:
                raise  # the arm is unreachable: the stream ends, it is not one refused command
            except TelerobotError as error:
                now = self._clock.time_ns()
                return [CommandResult("REJECTED", error.message, i.receive_time_ns, now)
                        for i in group]
        applied = self._clock.time_ns()
        self._target = result.target_tool_pose
        self.core.record_increment(mapping, total.translation, total.rotation,
                                   result.target_tool_pose.translation)
        reduced = result.applied_fraction < 1.0
        detail = f"reduced to {result.applied_fraction:.2f} near a singularity" if reduced else ""
        return [CommandResult("MODIFIED" if modified or reduced else "APPLIED", detail,
                              i.receive_time_ns, applied)
                for i, modified in zip(group, modified_by_assistance, strict=True)]

    def _environment_force(self) -> np.ndarray:
        """The environment's force on the tool now (tool axes, N); zero when the sensor has
        nothing (not reading: then no contact can be felt by the operator either)."""
        wrench = self.core.wrench()
        return np.zeros(3) if wrench is None else np.asarray(wrench.force_n, dtype=float)

    # -- the stream's end, resume, close ------------------------------------------------------

    def end(self, stream: int, reason: str, resumable: bool) -> None:
        """`stream` ended: the session closes, or (`resumable`: it broke) holds the arm and
        waits to be resumed. Nothing happens if a newer stream serves the session now."""
        if not resumable:
            with self._lock:
                superseded = stream != self.stream
            if not superseded:
                self.close(reason)
            return
        with self._lock:
            if stream != self.stream or self._closed.is_set():
                return
            self._detached_at = self._clock.monotonic()
            hold = not self._held
            self._held = True
        self._activity.set()  # the watchdog now waits for the resume window instead
        if hold:
            with self._moving:
                self._hold(reason)
        self.core.emit(self._changed("DETACHED", f"{reason}; resumable for "
                                                 f"{self.resume_window_s:.0f} s"))

    def resume(self) -> int:
        """A new stream takes the session over (a broken one, or one whose break the server
        has not noticed yet, which is then superseded). Returns the new stream's number."""
        with self._lock:
            if self._closed.is_set():
                raise FailedPreconditionError("the session has ended", reason="SESSION_ENDED")
            self.stream += 1
            self._detached_at = None
            stream = self.stream
        self._touch()
        self._activity.set()  # the watchdog waits for the resume window: its deadline is sooner
        self.core.emit(self._changed("RESUMED", "a new stream resumed the session"))
        return stream

    def close(self, reason: str) -> None:
        """The session ends for good: hold the arm, unless the watchdog already did."""
        with self._lock:
            if self._closed.is_set():
                return
            self._closed.set()
            hold = not self._held
            self._held = True
        self._activity.set()
        with self._moving:  # a move in flight lands first; none starts after
            if hold:
                self._hold(reason)
        self.core.forget_session(self.session_id)
        self.core.emit(self._changed("CLOSED", reason))

    def _changed(self, state: str, reason: str) -> SessionChanged:
        return SessionChanged(self.session_id, self.operator_id, state, reason,
                                    self._resends.counts())

    def _touch(self) -> None:
        with self._lock:
            self._last_activity = self._clock.monotonic()
            rearmed = self._held or self._sensor_asked
            self._held = self._sensor_asked = False
        # A command moves the operator's deadline later, which the watchdog finds out when its
        # wait ends: it is woken only when it must act sooner than it planned, for a hold or a
        # sensor check this re-arms (and see _sensor_check). Waking it for every command cost
        # a thread switch a command.
        if rearmed:
            self._activity.set()

    def _watch(self) -> None:
        """Holds the arm when the operator goes quiet, or when the force sensor's wrench does
        and the sensor does not answer (the operator moves by what it feels); closes the
        session when it stays detached past its resume window."""
        while not self._closed.is_set():
            # Clear before reading the state, so a close or a re-armed hold that lands in
            # between still wakes the wait below instead of being missed; until the wait's
            # deadline is known, so does any sensor check (_sensor_check).
            self._activity.clear()
            self._watch_until = math.inf
            sensor_due_in_s = self.core.sensor_check_due_in_s()
            with self._lock:
                now = self._clock.monotonic()
                check_sensor = False
                if self._detached_at is not None:
                    deadline = self._detached_at + self.resume_window_s
                    expire = deadline <= now
                    fire = due = False
                else:
                    deadline = self._last_activity + self.watchdog_s
                    due = deadline <= now
                    fire = due and not self._held and not self._closed.is_set()
                    expire = False
                    if (not due and not self._held and not self._sensor_asked
                            and sensor_due_in_s is not None):
                        check_sensor = sensor_due_in_s <= 0
                        deadline = min(deadline, now + max(sensor_due_in_s, 0.0))
                if fire:
                    self._held = True
            if expire:
                self.close(f"not resumed within {self.resume_window_s:.0f} s")
                return
            if fire:
                with self._moving:  # a move in flight lands first, so the hold is the last word
                    self._hold("watchdog timeout: no command or heartbeat")
            elif check_sensor and (lost := self._sensor_check()):
                with self._lock:
                    self._sensor_asked = True  # (it held the arm) the next command asks again
                    carried = bool(self._late)
                if carried:  # (no command moves the arm while the sensor is lost: answer it)
                    with self._moving:
                        self._hold(lost)
                continue
            self._watch_until = math.inf if due else deadline
            self._clock.wait_until(self._activity, None if due else deadline)

    def _hold(self, reason: str) -> None:
        silence = self._clock.monotonic() - self._last_activity
        with self._lock:
            self._holds += 1  # late commands carried before now will not join a later move
        self._target = None
        try:
            self.core.slave.hold(reason)
        except TelerobotError as error:
            log.warning("session %s: hold failed: %s", self.session_id, error.message)
        self.core.emit(WatchdogHold(self.session_id, reason, silence))
        if self._late and (wake := self.wake_server) is not None:
            wake()
