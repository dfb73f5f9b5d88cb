"""A fake slave station for DecisionCore: the DecisionServer's `Slave` port with a few lines
of honest physics, driven by a FakeClock.

- The arm is the PUMA 560's kinematics (Pinocchio, in-process): joint targets from increments
  (Cartesian ones through the same IK the proxy uses), and joints that follow their target
  with a first-order lag when the test calls `step(dt)`.
- The table is a spring: below `floor_z` the tool point feels F = K·depth upwards, reported in
  tool axes like the wrist sensor does.
- The status machine is ProxyRobot's in small: READY/MOVING, a latched ESTOPPED that refuses
  motion until `reset`, and `latch_at_hardware()` for a stop that came through another door
  (the emergency-stop band). Every step publishes a state sample to `on_state`.
"""

from __future__ import annotations

import threading
from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from domain.robot_model.ik import solve_ik
from domain.robot_model.kinematics import ArmKinematics
from domain.robot_model.puma560 import HOME_Q
from services.decision_server.slave import MoveResult, SlaveState, SlaveWrench
from tests.fakes.clock import FakeClock
from wire.errors import FailedPreconditionError, OutOfRangeError, UnavailableError

LAG_TIME_CONSTANT_S = 0.02
ARRIVED_RAD = 1e-6
MAX_TRANSLATION_INCREMENT_M = 0.05  # ProxyRobot's caps
MAX_JOINT_INCREMENT_RAD = 0.5
TABLE_STIFFNESS_N_PER_M = 1e4


class _Subscription:
    """One wrench stream's queue. A sample counts as handled once the consumer asks for the
    next one, so `step` can wait until every consumer has acted on what it was given."""

    def __init__(self, slave: FakeSlave, decimation: int):
        self._slave = slave
        self.decimation = decimation
        self._cancelled = False
        self._items: list = []
        self._unhandled = 0
        self._changed = threading.Condition()

    def put(self, item) -> None:
        with self._changed:
            if self._cancelled:
                return  # its reader has gone: nothing will take it
            self._items.append(item)
            self._unhandled += 1
            self._changed.notify_all()

    def get(self, handled_previous: bool):
        with self._changed:
            if handled_previous:
                self._unhandled -= 1
                self._changed.notify_all()
            while not self._items and not self._cancelled:
                self._changed.wait()
            return None if self._cancelled else self._items.pop(0)

    def __iter__(self):
        self._slave._subscribe(self)  # noqa: SLF001 - the fake's own registry
        try:
            handled_previous = False
            while (sample := self.get(handled_previous)) is not None:
                yield sample
                handled_previous = True
            if not self._cancelled:  # ended by end_wrench_streams(), not by its reader
                raise UnavailableError("the sensor's stream ended", reason="SENSOR_STREAM_ENDED")
        finally:
            self.cancel()

    def cancel(self) -> None:
        with self._changed:
            self._cancelled = True
            self._items.clear()
            self._unhandled = 0
            self._changed.notify_all()
        self._slave._unsubscribe(self)  # noqa: SLF001 - the fake's own registry

    def wait_handled(self, timeout_s: float = 5.0) -> None:
        with self._changed:
            if not self._changed.wait_for(lambda: self._unhandled <= 0, timeout_s):
                raise AssertionError("a wrench consumer did not take its sample")


@dataclass
class Command:
    kind: str  # "cartesian", "joints", "hold", "estop", "reset", "tool_frame"
    detail: object = None


class FakeSlave:
    def __init__(self, clock: FakeClock, floor_z: float = -np.inf,
                 stiffness_n_per_m: float = TABLE_STIFFNESS_N_PER_M):
        self.clock = clock
        self.kinematics = ArmKinematics()
        self.q = HOME_Q.copy()
        self.q_target = HOME_Q.copy()
        self.status = "READY"
        self.reason = ""
        self.floor_z = floor_z
        self.stiffness = stiffness_n_per_m
        self.commands: list[Command] = []  # everything the core asked of the arm, in order
        self.sensor_flange_to_tool = self.kinematics.flange_T_tool
        self.sensor_reading = True
        self.sensor_hung = False  # a hung sensor process: no samples, no answers
        self.sensor_is_reading_calls = 0
        self.wrench_delay_s = 0.0  # how late samples arrive (a backlog on a loaded machine)
        self.publish_state = True  # False: the state stream lags (samples held back)
        # What state() answers instead of the arm's own, while set: the state stream's cached
        # sample from before (GrpcSlave answers its latest sample while it is fresh).
        self.lagging_state: SlaveState | None = None
        self.reachable = True
        # What health() says of each dependency: "ok" or why not (a test sets them); the arm
        # and the sensor also say "unreachable" while `reachable` is False.
        self.dependency_health = {"proxy_robot": "ok", "force_sensor": "ok",
                                  "stereo_camera": "ok", "emergency_stop": "ok"}
        self.on_state = lambda state: None
        self.on_robot_event = lambda message: None
        self._lock = threading.Lock()
        self._sequence = 0
        self._subscribers: list[_Subscription] = []
        self._latest_wrench: SlaveWrench | None = None

    # -- what the test drives -------------------------------------------------------------

    def step(self, dt_s: float, steps: int = 1) -> None:
        """Advance the clock and the arm by `steps` × `dt_s`, publishing a state and a wrench
        sample after each."""
        for _ in range(steps):
            self.clock.advance(dt_s)
            with self._lock:
                self.q += (self.q_target - self.q) * (1 - np.exp(-dt_s / LAG_TIME_CONSTANT_S))
                if self.status == "MOVING" and np.max(np.abs(self.q_target - self.q)) < (
                        ARRIVED_RAD):
                    self.status = "READY"
                state = self._state()
                wrench = self._sample_wrench()
            if self.publish_state:
                self.on_state(state)
            if wrench is not None:
                with self._lock:
                    subscriptions = list(self._subscribers)
                for subscription in subscriptions:
                    if wrench.sequence % subscription.decimation == 0:
                        subscription.put(wrench)
                for subscription in subscriptions:  # lockstep: each acts before time moves on
                    subscription.wait_handled()

    def latch_at_hardware(self, reason: str = "stopped through the band") -> None:
        """A stop that came through another door: the next state sample says ESTOPPED."""
        with self._lock:
            self.q_target = self.q.copy()
            self.status, self.reason = "ESTOPPED", reason

    def tool_pose(self) -> pin.SE3:
        return self.kinematics.tool_pose(self.q)

    def end_wrench_streams(self) -> None:
        with self._lock:
            subscriptions = list(self._subscribers)
        for subscription in subscriptions:
            subscription.put(None)

    # -- the Slave port -------------------------------------------------------------------

    def move_cartesian(self, delta_position, delta_rotation, frame: str) -> MoveResult:
        self._check_reachable()
        if np.linalg.norm(delta_position) > MAX_TRANSLATION_INCREMENT_M:
            raise OutOfRangeError("the increment is over its cap of 0.05 m", reason="INCREMENT_CAP")
        with self._lock:
            self._check_can_move()
            target = self.kinematics.tool_pose(self.q_target)
            increment = pin.SE3(np.asarray(delta_rotation, float),
                                np.asarray(delta_position, float))
            if frame == "BASE":
                desired = pin.SE3(increment.rotation @ target.rotation,
                                  target.translation + increment.translation)
            else:  # TOOL (the fake's wrist is its tool)
                desired = target * increment
            solution = solve_ik(self.kinematics, desired, self.q_target)
            if not solution.success:
                raise OutOfRangeError("the pose is out of reach", reason="UNREACHABLE")
            self.q_target = solution.q
            self.status = "MOVING"
            self.commands.append(Command("cartesian", (frame, np.array(delta_position))))
            return MoveResult(self.kinematics.tool_pose(self.q_target), 1.0)

    def move_joints(self, delta_joints_rad) -> MoveResult:
        self._check_reachable()
        deltas = np.asarray(delta_joints_rad, float)
        if np.max(np.abs(deltas)) > MAX_JOINT_INCREMENT_RAD:
            raise OutOfRangeError(
                "the increment is over its cap of 0.5 rad", reason="INCREMENT_CAP")
        with self._lock:
            self._check_can_move()
            self.q_target = self.q_target + deltas
            self.status = "MOVING"
            self.commands.append(Command("joints", deltas))
            return MoveResult(self.kinematics.tool_pose(self.q_target), 1.0)

    def hold(self, reason: str) -> tuple[pin.SE3, pin.SE3]:
        self._check_reachable()
        with self._lock:
            cut = self.kinematics.tool_pose(self.q_target)
            self.q_target = self.q.copy()
            self.commands.append(Command("hold", reason))
            return self.kinematics.tool_pose(self.q_target), cut

    def sensor_is_reading(self, timeout_s: float) -> bool:
        self.sensor_is_reading_calls += 1
        self._check_reachable()
        if self.sensor_hung:
            raise UnavailableError(f"no answer within {timeout_s * 1e3:.0f} ms",
                                   reason="SENSOR_SILENT")
        return self.sensor_reading

    def emergency_stop(self, reason: str) -> str:
        self._check_reachable()
        self.latch_at_hardware(reason)
        self.commands.append(Command("estop", reason))
        return "ESTOPPED"

    def stop_now(self) -> None:
        self.commands.append(Command("stop_now"))
        self.latch_at_hardware("an emergency stop is arriving")

    def reset(self) -> str:
        self._check_reachable()
        with self._lock:
            if self.status == "ESTOPPED":
                self.status, self.reason = "READY", "reset"
            self.commands.append(Command("reset"))
            return self.status

    def arm_name(self) -> str:
        self._check_reachable()
        return self.kinematics.arm.name

    def set_tool_frame(self, flange_to_tool: pin.SE3) -> pin.SE3:
        self._check_reachable()
        with self._lock:
            self.kinematics.flange_T_tool = flange_to_tool
            self.sensor_flange_to_tool = flange_to_tool
            self.commands.append(Command("tool_frame", flange_to_tool))
            return flange_to_tool

    def state(self) -> SlaveState:
        self._check_reachable()
        with self._lock:
            return self.lagging_state or self._state()

    def wrench(self) -> SlaveWrench | None:
        return self._latest_wrench if self.sensor_reading and not self.sensor_hung else None

    def wrench_stream(self, decimation: int) -> _Subscription:
        return _Subscription(self, decimation)

    def subscribers(self) -> int:
        with self._lock:
            return len(self._subscribers)

    def _subscribe(self, subscription: _Subscription) -> None:
        with self._lock:
            self._subscribers.append(subscription)

    def _unsubscribe(self, subscription: _Subscription) -> None:
        with self._lock:
            if subscription in self._subscribers:
                self._subscribers.remove(subscription)

    def health(self) -> dict[str, str]:
        health = dict(self.dependency_health)
        if not self.reachable:
            health.update(proxy_robot="unreachable", force_sensor="unreachable")
        return health

    def close(self) -> None:
        self.end_wrench_streams()

    # -- inside ---------------------------------------------------------------------------

    def _check_reachable(self) -> None:
        if not self.reachable:
            raise UnavailableError("the slave station does not answer", reason="UNREACHABLE")

    def _check_can_move(self) -> None:
        if self.status in ("ESTOPPED", "FAULT"):
            raise FailedPreconditionError(f"the arm is {self.status}: Reset it first",
                                          reason=self.status)

    def _state(self) -> SlaveState:
        return SlaveState(self.kinematics.tool_pose(self.q), self.status, self.clock.time_ns(),
                          self.reason)

    def _sample_wrench(self) -> SlaveWrench | None:
        if not self.sensor_reading:
            return None
        tool = self.kinematics.tool_pose(self.q)
        depth = self.floor_z - tool.translation[2]
        force_base = np.array([0.0, 0.0, self.stiffness * depth if depth > 0 else 0.0])
        self._sequence += 1
        sampled_ns = self.clock.time_ns() - round(self.wrench_delay_s * 1e9)
        self._latest_wrench = SlaveWrench(tool.rotation.T @ force_base, np.zeros(3),
                                          self._sequence, sampled_ns)
        return self._latest_wrench
