"""The hardware link over shared memory: the world publishes, drivers read and command.

World side: ``WorldPublisher`` creates the segment (see shm_layout.py), publishes one arm sample
and one wrench per servo step with a heartbeat, hands out the drivers' commands in the order they
were issued, and unlinks the segment on close.

Driver side: ``SharedMemoryArmLink`` (ArmLink), ``SharedMemoryWrenchLink`` (WrenchLink) and
``SharedMemoryEmergencyStop`` (EmergencyStopLink: the stop button wired past the driver). They
raise UnavailableError when the world is not running, has shut down, or has not stepped for
``stale_after_s``. One driver process commands a world at a time (the command record has a
single writer); within that process the links are thread-safe.

The heartbeat is the monotonic clock, which every process on the machine shares; a test may
give a world and its drivers one clock of its own (``clock``) to make the world go stale at will.
"""

from __future__ import annotations

import logging
import os
import threading
import time
from dataclasses import dataclass
from multiprocessing import shared_memory

import numpy as np

from domain.robot_model.description import selected_arm_name
from services.runtime.clock import SYSTEM_CLOCK, Clock
from services.world.link import (
    ArmSample,
    RawWrench,
    checked_duration,
    checked_joint_target,
)
from services.world.realtime import LoopStats
from services.world.seqlock import ORDERING_GUARANTEED, TornRead
from services.world.shm_layout import (
    FAULT_BYTES,
    LAYOUT_VERSION,
    MAGIC,
    SEGMENT_SIZE,
    STATE_DTYPE,
    STATUS_CLOSED,
    STATUS_RUNNING,
    STATUS_STARTING,
    WorldSegment,
    adopt_for_unlink,
    attach_untracked,
    create_segment,
    pid_alive,
    segment_name,
    unlink_segment,
)
from wire.errors import AlreadyExistsError, FailedPreconditionError, UnavailableError

log = logging.getLogger(__name__)

# A world that has not stepped for this long counts as gone. Long enough that a busy 2-core
# machine's scheduling stalls (tens of ms seen) are not taken for a dead world.
STALE_AFTER_S = 0.25
# How long a new driver waits for the command record a previous driver may have died writing.
# (A world preempted mid-publish is waited for as long as one that has not stepped.)
TORN_READ_TIMEOUT_S = 0.05
# A stale segment (its world killed) is replaced; one whose world stepped this recently, or whose
# pid is alive, belongs to a running world and is left alone.
REPLACE_AFTER_S = 1.0

_HOLD, _RELEASE, _TARGET = "hold", "release", "target"


@dataclass(frozen=True)
class Command:
    """One command from the driver, as the world receives it."""

    number: int  # command_sequence when it was issued; commands apply in this order
    kind: str  # "target", "hold" or "release"
    target: np.ndarray | None = None  # rad (6,), for "target"
    duration_s: float = 0.0  # for "target": the segment to reach it over (0: at once)


# -- world side ---------------------------------------------------------------------------------


class WorldPublisher:
    """The world's end of the link. Single-threaded: the servo thread calls everything.
    ``clock``'s monotonic time stamps the heartbeat."""

    def __init__(self, arm: str, joint_lower: np.ndarray, joint_upper: np.ndarray,
                 period_s: float, name: str | None = None, clock: Clock = SYSTEM_CLOCK):
        self.name = segment_name(name)
        self._clock = clock
        if not ORDERING_GUARANTEED:
            log.warning("this CPU is not x86: the seqlock has no memory fences here, so a "
                        "driver may (rarely) read a torn sample")
        self._segment = WorldSegment(_create_or_replace(self.name))
        header = self._segment.header
        header["layout_version"] = LAYOUT_VERSION
        header["world_pid"] = os.getpid()
        header["status"] = STATUS_STARTING  # RUNNING from the first publish on
        header["heartbeat_ns"] = clock.monotonic_ns()
        header["period_ns"] = round(period_s * 1e9)
        self._joints = joints = len(joint_lower)
        header["arm"] = arm.encode("ascii")
        header["joint_count"] = joints
        header["joint_lower"][0, :joints] = joint_lower
        header["joint_upper"][0, :joints] = joint_upper
        header["magic"] = MAGIC  # last: the segment is complete
        self._applied = 0
        self._emergency_seen = 0  # the stop_request_ns already latched
        self._latched_ns = 0  # arm_time_ns of the step the current hold latched at
        self._running = False
        self._state = np.zeros(1, STATE_DTYPE)  # filled here, then copied in one go

    def publish(self, arm: ArmSample, wrench: RawWrench, loop: LoopStats | None = None) -> None:
        """Publish one step's samples and beat the heartbeat."""
        now = self._clock.monotonic_ns()
        loop = loop or LoopStats()
        record = self._state
        record["heartbeat_ns"] = now
        record["arm_sequence"] = arm.sequence
        record["arm_time_ns"] = arm.sample_time_ns
        joints = self._joints
        record["q"][0, :joints] = arm.joint_positions_rad
        record["qd"][0, :joints] = arm.joint_velocities_rad_per_s
        record["target"][0, :joints] = arm.joint_targets_rad
        record["hold_latched"] = arm.hold_latched
        if not arm.hold_latched:
            self._latched_ns = 0
        elif not self._latched_ns:
            self._latched_ns = arm.sample_time_ns
        record["hold_latched_ns"] = self._latched_ns
        record["fault"] = arm.fault.encode()[:FAULT_BYTES]
        record["wrench_sequence"] = wrench.sequence
        record["wrench_time_ns"] = wrench.sample_time_ns
        record["force"] = wrench.force_n
        record["torque"] = wrench.torque_nm
        record["applied_command"] = self._applied
        record["loop_steps"] = loop.steps
        record["loop_overruns"] = loop.overruns
        record["loop_dropped_steps"] = loop.dropped_steps
        record["loop_worst_lateness_ns"] = loop.worst_lateness_ns
        record["loop_worst_step_ns"] = loop.worst_step_ns
        self._segment.state.write(record)
        self._segment.header["heartbeat_ns"] = now
        if not self._running:
            self._segment.header["status"] = STATUS_RUNNING
            self._running = True

    def poll_commands(self) -> list[Command]:
        """Commands issued since the last poll, oldest first, and a hold last when an
        emergency stop was requested. Driver commands count as applied from the next publish
        on; they are left for the next step while the driver is mid-write."""
        commands = self._poll_driver()
        requested = int(self._segment.emergency["stop_request_ns"][0])
        if requested != self._emergency_seen:
            self._emergency_seen = requested
            commands.append(Command(self._applied, _HOLD))
        return commands

    def _poll_driver(self) -> list[Command]:
        try:
            record = self._segment.command.read(timeout_s=0.0)[0]
        except TornRead:
            return []
        commands = []
        for kind, field in ((_HOLD, "hold_command"), (_RELEASE, "release_command"),
                            (_TARGET, "target_command")):
            number = int(record[field])
            if number > self._applied:
                if kind == _TARGET:
                    commands.append(Command(number, kind, record["target"][:self._joints].copy(),
                                            float(record["target_duration_s"])))
                else:
                    commands.append(Command(number, kind))
        self._applied = max(self._applied, int(record["command_sequence"]))
        return sorted(commands, key=lambda command: command.number)

    def close(self) -> None:
        """Tell drivers the world is gone and remove the segment."""
        segment, self._segment = self._segment, None
        if segment is None:
            return
        segment.header["status"] = STATUS_CLOSED
        shm = segment.shm
        segment.close()
        unlink_segment(shm)


def _create_or_replace(name: str) -> shared_memory.SharedMemory:
    """Create the segment; replace a stale one left by a killed world; refuse a live one."""
    try:
        return create_segment(name)
    except FileExistsError:
        pass
    try:
        old = attach_untracked(name)
    except FileNotFoundError:  # removed meanwhile
        return create_segment(name)
    owner = _live_owner(old)
    if owner is not None:
        old.close()
        raise AlreadyExistsError(
            f"a world (pid {owner}) is already running on shared memory {name!r}: stop it, or "
            f"give this one another name with TELEROBOT_WORLD_SHM", reason="WORLD_RUNNING")
    log.warning("replacing the stale shared memory %r left by a world that did not shut down",
                name)
    adopt_for_unlink(old)
    old.close()
    unlink_segment(old)
    return create_segment(name)


def _live_owner(shm: shared_memory.SharedMemory) -> int | None:
    """The pid of the running world that owns this segment, or None if it is stale."""
    if shm.size < SEGMENT_SIZE:
        return None
    segment = WorldSegment(shm)
    try:
        if segment.layout_problem() or segment.status != STATUS_RUNNING:
            return None
        fresh = time.monotonic_ns() - segment.heartbeat_ns < REPLACE_AFTER_S * 1e9
        pid = segment.world_pid
        return pid if fresh or pid_alive(pid) else None
    finally:
        segment.release()


# -- driver side --------------------------------------------------------------------------------


class _WorldConnection:
    """An attachment to a running world's segment, with the liveness checks every read makes."""

    def __init__(self, name: str | None, stale_after_s: float, clock: Clock):
        self.name = segment_name(name)
        self._stale_after_ns = round(stale_after_s * 1e9)
        self._clock = clock
        try:
            shm = attach_untracked(self.name)
        except FileNotFoundError:
            raise UnavailableError(
                f"no world is running: shared memory {self.name!r} does not exist. Start it "
                "with `python -m services.world` (TELEROBOT_WORLD_SHM names the segment)",
                reason="WORLD_NOT_RUNNING") from None
        if shm.size < SEGMENT_SIZE:
            shm.close()
            raise UnavailableError(f"shared memory {self.name!r} is {shm.size} bytes, not a world "
                                   f"segment ({SEGMENT_SIZE}): check TELEROBOT_WORLD_SHM",
                                   reason="WORLD_SEGMENT_INVALID")
        self.segment: WorldSegment | None = WorldSegment(shm)
        problem = self.segment.layout_problem()
        try:
            if problem:
                raise UnavailableError(f"shared memory {self.name!r} is not usable: {problem}",
                                       reason="WORLD_SEGMENT_INVALID")
            self.check_alive()
        except UnavailableError:
            self.close()
            raise

    def require(self) -> WorldSegment:
        if self.segment is None:
            raise UnavailableError("the hardware link is closed: open a new one",
                                   reason="LINK_CLOSED")
        return self.segment

    def check_alive(self) -> None:
        """Unavailable unless the world is running and stepped within stale_after_s."""
        now_ns = self._clock.monotonic_ns()
        self._check_alive(self.require().heartbeat_ns, now_ns)

    def _check_alive(self, heartbeat_ns: int, now_ns: int) -> None:
        """As check_alive, for a heartbeat read after `now_ns` was: the clock is read first, so
        a reader preempted in between sees the world younger, never older, than it is."""
        segment = self.require()
        status = segment.status
        if status == STATUS_CLOSED:
            raise UnavailableError(
                f"the world (pid {segment.world_pid}) has shut down; restart it and reconnect",
                reason="WORLD_STOPPED")
        if status != STATUS_RUNNING:
            raise UnavailableError(f"the world (pid {segment.world_pid}) is starting; try again",
                                   reason="WORLD_STARTING")
        age_ns = now_ns - heartbeat_ns
        if age_ns > self._stale_after_ns:
            raise UnavailableError(
                f"the world (pid {segment.world_pid}) has not stepped for {age_ns / 1e6:.0f} ms "
                f"(limit {self._stale_after_ns / 1e6:.0f} ms): it is stopped, stuck or gone",
                reason="WORLD_STALE")

    def read_state(self) -> np.void:
        """A consistent copy of the latest state record, from a live world."""
        segment = self.require()
        now_ns = self._clock.monotonic_ns()
        try:
            # A world preempted mid-publish (the GIL or the scheduler, on a loaded machine) is
            # one that has not stepped yet: it gets the same time before it counts as gone.
            record = segment.state.read(self._stale_after_ns / 1e9,
                                        monotonic=self._clock.monotonic)[0]
        except TornRead:
            raise UnavailableError(
                f"the world (pid {segment.world_pid}) stopped in the middle of publishing a "
                f"sample for {self._stale_after_ns / 1e6:.0f} ms: it is stuck or gone",
                reason="WORLD_STALE") from None
        self._check_alive(int(record["heartbeat_ns"]), now_ns)
        return record

    def close(self) -> None:
        segment, self.segment = self.segment, None
        if segment is not None:
            segment.close()


class SharedMemoryArmLink:
    """ArmLink to the simulated arm through the world's shared memory.

    UnavailableError on open and on every call when the world is not running, has shut down or has
    not stepped for ``stale_after_s`` (s) by ``clock``, which must be the one that stamps the
    world's heartbeat. FailedPreconditionError on open when the world simulates another arm than
    ``arm`` (default: this process's selected arm). Thread-safe.
    """

    def __init__(self, name: str | None = None, stale_after_s: float = STALE_AFTER_S,
                 clock: Clock = SYSTEM_CLOCK, arm: str | None = None):
        self._state_lock = threading.Lock()
        self._command_lock = threading.Lock()
        self._connection = _WorldConnection(name, stale_after_s, clock)
        segment = self._connection.require()
        self.arm = segment.arm
        expected = arm or selected_arm_name()
        if self.arm != expected:
            raise FailedPreconditionError(
                f"the world on {self.name!r} simulates the {self.arm}, and this process drives "
                f"the {expected}: start every service with the same ARM", reason="WRONG_ARM")
        self._joints = joints = segment.joint_count
        self.joint_lower = segment.header["joint_lower"][0, :joints].copy()  # rad
        self.joint_upper = segment.header["joint_upper"][0, :joints].copy()  # rad
        self._issued = self._adopt_command_record(segment)

    @property
    def name(self) -> str:
        """The shared-memory segment name."""
        return self._connection.name

    def _adopt_command_record(self, segment: WorldSegment) -> int:
        """The latest command number in the record (we continue from it). If a previous driver
        died mid-write, its target may be torn: mark it as already applied so it never is."""
        try:
            return int(segment.command.read(TORN_READ_TIMEOUT_S)[0]["command_sequence"])
        except TornRead:
            pass
        applied = int(self._connection.read_state()["applied_command"])
        with segment.command.writing() as record:
            record["target_command"] = min(int(record["target_command"][0]), applied)
            return int(record["command_sequence"][0])

    # -- ArmLink ----------------------------------------------------------------------------

    def read_arm(self) -> ArmSample:
        """The latest servo sample. UnavailableError when the world is gone or stale."""
        with self._state_lock:
            record = self._connection.read_state()
        return ArmSample(
            sequence=int(record["arm_sequence"]),
            sample_time_ns=int(record["arm_time_ns"]),
            joint_positions_rad=record["q"][:self._joints].copy(),
            joint_velocities_rad_per_s=record["qd"][:self._joints].copy(),
            joint_targets_rad=record["target"][:self._joints].copy(),
            hold_latched=bool(record["hold_latched"]),
            fault=bytes(record["fault"]).decode("utf-8", "replace"),
        )

    def write_target(self, joint_positions_rad: np.ndarray, duration_s: float = 0.0) -> None:
        """Make the servo track a new joint target (one angle per joint) in rad, reached along a
        straight joint-space segment of `duration_s`; the world ignores it while a hold is latched.
        InvalidArgumentError on a wrong shape or NaN; OutOfRangeError past a joint limit (by more
        than LIMIT_TOLERANCE_RAD; the world clips onto the limit)."""
        target = checked_joint_target(joint_positions_rad, self.joint_lower, self.joint_upper)
        self._issue(_TARGET, target, checked_duration(duration_s))

    def hold(self) -> None:
        """Latch a controlled stop: the arm brakes at its acceleration cap and holds where it
        stops; later targets are ignored until release_hold()."""
        self._issue(_HOLD)

    def release_hold(self) -> None:
        """Clear the latch (and a fault); the target becomes the current position."""
        self._issue(_RELEASE)

    def close(self) -> None:
        """Detach. The world keeps holding the last target."""
        with self._state_lock, self._command_lock:
            self._connection.close()

    # -- beyond ArmLink ---------------------------------------------------------------------

    def commands_applied(self) -> bool:
        """Whether the world has applied every command this link issued (within one step)."""
        with self._state_lock:
            record = self._connection.read_state()
        with self._command_lock:
            return int(record["applied_command"]) >= self._issued

    def read_loop_stats(self) -> LoopStats:
        """The world's real-time loop counters (see realtime.py)."""
        with self._state_lock:
            record = self._connection.read_state()
        return LoopStats(
            steps=int(record["loop_steps"]),
            overruns=int(record["loop_overruns"]),
            dropped_steps=int(record["loop_dropped_steps"]),
            worst_lateness_ns=int(record["loop_worst_lateness_ns"]),
            worst_step_ns=int(record["loop_worst_step_ns"]),
        )

    def _issue(self, kind: str, target: np.ndarray | None = None, duration_s: float = 0.0
               ) -> None:
        with self._command_lock:
            connection = self._connection
            segment = connection.require()
            connection.check_alive()
            number = self._issued + 1
            with segment.command.writing() as record:
                # Payload first, numbers last: a driver killed in between leaves no new number.
                if kind == _TARGET:
                    record["target"][0, :self._joints] = target
                    record["target_duration_s"] = duration_s
                    record["target_command"] = number
                elif kind == _HOLD:
                    record["hold_command"] = number
                else:
                    record["release_command"] = number
                record["driver_pid"] = os.getpid()
                record["command_sequence"] = number
            self._issued = number


class SharedMemoryEmergencyStop:
    """EmergencyStopLink through the world's emergency word: it never touches the driver's
    command record, so any number of these may sit beside the one driver. ``stale_after_s`` and
    ``clock`` as for SharedMemoryArmLink. Thread-safe."""

    def __init__(self, name: str | None = None, stale_after_s: float = STALE_AFTER_S,
                 clock: Clock = SYSTEM_CLOCK):
        self._lock = threading.Lock()
        self._connection = _WorldConnection(name, stale_after_s, clock)
        self._last_request_ns = 0

    def stop(self) -> int:
        """Latch a controlled stop. UnavailableError when the world is gone or stale (the stop
        could not be delivered)."""
        with self._lock:
            connection = self._connection
            segment = connection.require()
            connection.check_alive()
            # Strictly new, even within one clock tick, so the world always sees a change.
            requested = max(time.time_ns(), self._last_request_ns + 1)
            segment.emergency["stop_request_ns"] = requested
            self._last_request_ns = requested
            return requested

    def close(self) -> None:
        """Detach; a latched stop stays latched."""
        with self._lock:
            self._connection.close()


class SharedMemoryWrenchLink:
    """WrenchLink to the simulated wrist force/torque sensor through the world's shared memory.

    UnavailableError on open and on every read when the world is not running, has shut down or has
    not stepped for ``stale_after_s`` (s). Thread-safe.
    """

    def __init__(self, name: str | None = None, stale_after_s: float = STALE_AFTER_S):
        self._lock = threading.Lock()
        self._connection = _WorldConnection(name, stale_after_s, SYSTEM_CLOCK)

    def read_wrench(self) -> RawWrench:
        """The latest sensor sample (N, N*m, sensor frame). UnavailableError when the world is
        gone."""
        with self._lock:
            record = self._connection.read_state()
        return RawWrench(
            sequence=int(record["wrench_sequence"]),
            sample_time_ns=int(record["wrench_time_ns"]),
            force_n=record["force"].copy(),
            torque_nm=record["torque"].copy(),
        )

    def close(self) -> None:
        """Detach from the sensor."""
        with self._lock:
            self._connection.close()
