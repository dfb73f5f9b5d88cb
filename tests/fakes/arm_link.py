"""A fake arm behind the hardware link (services/world/link.py), on a fake clock.

`FakeArm` is the hardware: six joints whose servo steps once per SERVO_PERIOD_S of the clock.
Each step it applies the commands issued since the last one, in order (as the world does), then
moves the setpoint one period along the target's segment (the world's own SegmentedGoal: a
straight line over the duration the driver asked) and every joint toward that setpoint with a
first-order lag of time constant `time_constant_s`, at most `max_speed_rad_per_s`:

    dq = clip((setpoint - q) * (1 - exp(-dt / tau)), -v_max * dt, v_max * dt)
    q += dq;  qd = dq / dt

so the reported velocity is what the position really did over the last period. Steps are taken
lazily, whenever a link or the test looks at the arm, for every whole period the clock has
advanced since: nothing happens between two readings of a clock that stands still, and a command
shows in `read_arm()` only once the clock has passed the next step, as with the real world.

Like the simulation (services/world/sim.py, shm_link.py):
- a hold latches: the target freezes where the arm is (this arm has no inertia to brake), later
  targets are ignored, and `release_hold()` clears the latch and a fault, the target staying the
  current position; a release without a latch does nothing;
- `latch_stop()` is the emergency word another process (the emergency-stop band) writes: the
  next step latches a hold after the driver's commands; `emergency_stop_link()` is that band's
  EmergencyStopLink;
- `inject_fault()` makes the next step report a fault and latch a hold, as a diverged simulation;
- targets are checked (InvalidArgumentError, OutOfRangeError past a limit by more than the
  tolerance) and clipped onto the joint limits;
- samples carry the servo step as `sequence` and the wall time of that step as `sample_time_ns`;
- links raise UnavailableError when the arm is shut down (`shut_down()`), when it has not stepped
  for `stale_after_s` (`freeze()`: a hung or killed world), or once closed.

Every command the drivers issue is kept in `commands`, oldest first, for the tests to inspect.
"""

from __future__ import annotations

import math
import threading
from dataclasses import dataclass

import numpy as np

from domain.robot_model.puma560 import HOME_Q, JOINT_LOWER, JOINT_UPPER
from services.world.link import ArmSample, checked_duration, checked_joint_target
from services.world.shm_link import STALE_AFTER_S
from services.world.trajectory import SegmentedGoal
from tests.fakes.clock import FakeClock
from wire.errors import UnavailableError

SERVO_PERIOD_S = 0.001  # the world's servo rate
TIME_CONSTANT_S = 0.03
MAX_JOINT_SPEED_RAD_PER_S = 1.0  # the simulation's cap (services/world/sim.py)

HOLD, RELEASE, TARGET = "hold", "release", "target"


@dataclass(frozen=True)
class Command:
    """One command a driver issued: kind HOLD, RELEASE or TARGET (with its target, rad, and
    its segment's duration, s)."""

    kind: str
    target: np.ndarray | None = None
    issued_ns: int = 0  # monotonic
    duration_s: float = 0.0


class FakeArm:
    """The fake hardware. Thread-safe. `open_link` is an ArmLink factory."""

    def __init__(self, clock: FakeClock, start_q: np.ndarray = HOME_Q, *,
                 time_constant_s: float = TIME_CONSTANT_S,
                 max_speed_rad_per_s: float = MAX_JOINT_SPEED_RAD_PER_S,
                 period_s: float = SERVO_PERIOD_S, stale_after_s: float = STALE_AFTER_S):
        self.clock = clock
        self.joint_lower = JOINT_LOWER.copy()
        self.joint_upper = JOINT_UPPER.copy()
        self._lock = threading.Lock()
        self._period_ns = round(period_s * 1e9)
        self._stale_after_ns = round(stale_after_s * 1e9)
        self._decay = math.exp(-period_s / time_constant_s)
        self._max_step = max_speed_rad_per_s * period_s
        self._start_ns = clock.monotonic_ns()
        self._q = np.asarray(start_q, float).copy()
        self._qd = np.zeros(len(self.joint_lower))
        self._goal = SegmentedGoal(self._q, period_s)
        self._latched = False
        self._fault = ""
        self._steps = 0
        self._pending: list[Command] = []
        self._stop_requested = False
        self._fault_requested = ""
        self._frozen = False
        self._shut_down = False
        self.commands: list[Command] = []

    # -- the hardware's side, for tests -------------------------------------------------------

    def open_link(self) -> FakeArmLink:
        """A driver's link (the ProxyRobotCore's link factory). UnavailableError when no arm
        runs."""
        return FakeArmLink(self)

    def emergency_stop_link(self) -> FakeEmergencyStopLink:
        """The emergency-stop band's link: latches the stop without the driver."""
        return FakeEmergencyStopLink(self)

    def latch_stop(self) -> None:
        """Another process writes the emergency word: the next step latches a hold."""
        with self._lock:
            self._catch_up()
            self._stop_requested = True

    def inject_fault(self, message: str) -> None:
        """The next step reports `message` as a fault and latches a hold."""
        with self._lock:
            self._catch_up()
            self._fault_requested = message

    def freeze(self) -> None:
        """The servo stops stepping (a hung or killed world): links see the last sample until
        it is `stale_after_s` old, then UnavailableError."""
        with self._lock:
            self._catch_up()
            self._frozen = True

    def shut_down(self) -> None:
        """The world shuts down in order: every link is UnavailableError from now on."""
        with self._lock:
            self._catch_up()
            self._shut_down = True

    def state(self) -> ArmSample:
        """The latest sample, whatever the links' liveness (for assertions)."""
        with self._lock:
            self._catch_up()
            return self._sample()

    # -- the links' side ----------------------------------------------------------------------

    def read(self) -> ArmSample:
        with self._lock:
            self._catch_up()
            self._check_alive()
            return self._sample()

    def issue(self, command: Command) -> None:
        with self._lock:
            self._catch_up()
            self._check_alive()
            command = Command(command.kind, command.target, self.clock.monotonic_ns(),
                              command.duration_s)
            self.commands.append(command)
            self._pending.append(command)

    def request_stop(self) -> int:
        with self._lock:
            self._catch_up()
            self._check_alive()
            self._stop_requested = True
            return self.clock.time_ns()

    def check_open(self) -> None:
        with self._lock:
            if self._shut_down:
                raise UnavailableError("no world is running: the fake arm was shut down",
                                       reason="WORLD_NOT_RUNNING")
            self._catch_up()
            self._check_alive()

    # -- the servo ----------------------------------------------------------------------------

    def _check_alive(self) -> None:
        if self._shut_down:
            raise UnavailableError("the world (fake) has shut down; restart it and reconnect",
                                   reason="WORLD_STOPPED")
        age_ns = self.clock.monotonic_ns() - self._step_ns(self._steps)
        if age_ns > self._stale_after_ns:
            raise UnavailableError(f"the world (fake) has not stepped for {age_ns / 1e6:.0f} ms "
                                   f"(limit {self._stale_after_ns / 1e6:.0f} ms): it is stopped, "
                                   "stuck or gone", reason="WORLD_STALE")

    def _step_ns(self, step: int) -> int:
        return self._start_ns + step * self._period_ns

    def _catch_up(self) -> None:
        """Take every servo step the clock has passed."""
        if self._frozen or self._shut_down:
            return
        due = (self.clock.monotonic_ns() - self._start_ns) // self._period_ns
        while self._steps < due:
            self._step()

    def _step(self) -> None:
        for command in self._pending:
            if command.kind == TARGET and not self._latched:
                self._goal.head_for(np.clip(command.target, self.joint_lower, self.joint_upper),
                                    command.duration_s)
            elif command.kind == HOLD:
                self._latch()
            elif command.kind == RELEASE and self._latched:
                self._latched, self._fault = False, ""
                self._goal.reset(self._q)
        self._pending.clear()
        if self._stop_requested:  # after the driver's commands, as the world does
            self._stop_requested = False
            self._latch()
        if self._fault_requested:
            self._fault, self._fault_requested = self._fault_requested, ""
            self._latch()
        step = np.clip((self._goal.step() - self._q) * (1.0 - self._decay),
                       -self._max_step, self._max_step)
        self._q = self._q + step
        self._qd = step * (1e9 / self._period_ns)
        self._steps += 1

    def _latch(self) -> None:
        if not self._latched:
            self._latched = True
            self._goal.reset(self._q)

    def _sample(self) -> ArmSample:
        now_ns = self.clock.monotonic_ns()
        return ArmSample(
            sequence=self._steps,
            sample_time_ns=self.clock.time_ns() - (now_ns - self._step_ns(self._steps)),
            joint_positions_rad=self._q.copy(),
            joint_velocities_rad_per_s=self._qd.copy(),
            joint_targets_rad=self._goal.target.copy(),
            hold_latched=self._latched,
            fault=self._fault,
        )


class FakeArmLink:
    """ArmLink to a FakeArm. UnavailableError once closed, or when the arm is gone or stale."""

    def __init__(self, arm: FakeArm):
        arm.check_open()
        self._arm = arm
        self.closed = False

    def _require(self) -> FakeArm:
        if self.closed:
            raise UnavailableError("the hardware link is closed: open a new one",
                                   reason="LINK_CLOSED")
        return self._arm

    def read_arm(self) -> ArmSample:
        return self._require().read()

    def write_target(self, joint_positions_rad: np.ndarray, duration_s: float = 0.0) -> None:
        arm = self._require()
        target = checked_joint_target(joint_positions_rad, arm.joint_lower, arm.joint_upper)
        arm.issue(Command(TARGET, target.copy(), duration_s=checked_duration(duration_s)))

    def hold(self) -> None:
        self._require().issue(Command(HOLD))

    def release_hold(self) -> None:
        self._require().issue(Command(RELEASE))

    def close(self) -> None:
        self.closed = True


class FakeEmergencyStopLink:
    """EmergencyStopLink to a FakeArm: the band's stop, past the driver."""

    def __init__(self, arm: FakeArm):
        arm.check_open()
        self._arm = arm
        self.closed = False

    def stop(self) -> int:
        if self.closed:
            raise UnavailableError("the emergency-stop link is closed", reason="LINK_CLOSED")
        return self._arm.request_stop()

    def close(self) -> None:
        self.closed = True
