"""Joint reference generator: moves a reference toward a goal under velocity and acceleration caps.

Each joint is treated on its own (no synchronisation between joints): the reference accelerates
at most ``max_accel`` up to at most ``max_speed`` and brakes along the discrete-time braking curve
so it lands exactly on the goal, with no overshoot, when the goal holds still. A goal that moves
mid-motion is chased the same way (it may then overshoot by the braking distance and come back).

The goal it chases is the commanded one passed through a first-order filter (time constant
``goal_smoothing_s``): targets streamed over a network arrive with jitter, a setpoint frozen for
a few periods then jumping, and chasing each jump at full acceleration would turn the jitter
into force spikes whenever a stiff servo is in contact with something.

Before either, a new goal is reached along a straight joint-space segment lasting as long as the
driver asks (``set_goal(goal, duration_s)``: about its command interval; SegmentedGoal). The
driver sends each target once and the servo, which runs on time, spreads it over its periods:
a Python driver that wrote the intermediate setpoints itself at 1 kHz spent a third of its time
on them and, delayed by its own calls, turned its scheduling hiccups into setpoint jumps.
"""

from __future__ import annotations

import numpy as np

GOAL_SNAP_RAD = 1e-9
# The longest segment the servo accepts (a driver asks for about its command interval, at most
# 50 ms); longer requests, or nonsense ones from shared memory, are clipped into [0, this].
MAX_SEGMENT_S = 1.0


class SegmentedGoal:
    """The setpoint on its way to the latest target: a straight line in joint space from where
    the setpoint was when the target came, over the number of servo periods asked for."""

    def __init__(self, position: np.ndarray, period_s: float):
        self.period_s = float(period_s)
        self.target = np.asarray(position, float).copy()  # the latest target (rad)
        self.setpoint = self.target.copy()  # where the line is now (rad)
        self._start = self.target.copy()
        self._steps = 0  # periods the current segment lasts (0: none in progress)
        self._done = 0

    def head_for(self, target: np.ndarray, duration_s: float) -> None:
        """Go to `target` (rad) over `duration_s` (clipped into [0, MAX_SEGMENT_S]; a NaN is
        0): from the setpoint as it is now, so a target replacing one half-way starts there."""
        duration = float(duration_s) if np.isfinite(duration_s) else 0.0
        steps = round(min(max(duration, 0.0), MAX_SEGMENT_S) / self.period_s)
        self.target[:] = target
        self._start[:] = self.setpoint
        self._steps, self._done = (steps, 0) if steps > 1 else (0, 0)
        if not self._steps:
            self.setpoint[:] = self.target

    def reset(self, position: np.ndarray) -> None:
        """Drop any segment: target and setpoint become `position`."""
        self.target[:] = position
        self.setpoint[:] = position
        self._steps = self._done = 0

    def step(self) -> np.ndarray:
        """Advance one period; the setpoint (the array itself, not a copy)."""
        if self._steps:
            self._done += 1
            if self._done >= self._steps:
                self._steps = 0
                self.setpoint[:] = self.target
            else:
                self.setpoint[:] = self._start + (self.target - self._start) * (
                    self._done / self._steps)
        return self.setpoint


class JointReference:
    """Per-joint rate-limited reference (rad, rad/s, rad/s^2), advanced once per period."""

    def __init__(self, position: np.ndarray, max_speed: np.ndarray, max_accel: np.ndarray,
                 period_s: float, goal_smoothing_s: float = 0.0):
        self.period_s = float(period_s)
        self.max_speed = np.asarray(max_speed, float).copy()
        self.max_accel = np.asarray(max_accel, float).copy()
        self.position = np.asarray(position, float).copy()
        self.velocity = np.zeros_like(self.position)
        self.acceleration = np.zeros_like(self.position)
        self._segment = SegmentedGoal(self.position, self.period_s)
        self.smoothed_goal = self.position.copy()  # what the reference chases
        self._smoothing = 1.0 if goal_smoothing_s <= 0 else min(1.0, period_s / goal_smoothing_s)
        # Speed change allowed in one period, and the distance braking covers per period squared.
        self._dv = self.max_accel * self.period_s
        self._accel_dt2 = self.max_accel * self.period_s**2

    @property
    def goal(self) -> np.ndarray:
        """The commanded goal (rad): the end of the segment in progress, if any. Read-only:
        set_goal() changes it."""
        view = self._segment.target.view()
        view.flags.writeable = False
        return view

    def set_goal(self, goal: np.ndarray, duration_s: float = 0.0) -> None:
        """Head for `goal` (rad) along a straight segment of `duration_s` (0: at once)."""
        self._segment.head_for(goal, duration_s)

    def reset(self, position: np.ndarray, velocity: np.ndarray | None = None) -> None:
        """Jump the reference to ``position`` (rad) moving at ``velocity`` (rad/s, clipped to the
        speed cap; default at rest). The goal becomes where it can stop (see stopping_point),
        with no segment in progress."""
        self.position[:] = position
        if velocity is None:
            self.velocity[:] = 0.0
        else:
            np.clip(velocity, -self.max_speed, self.max_speed, out=self.velocity)
        self.acceleration[:] = 0.0
        self._segment.reset(self.stopping_point())
        self.smoothed_goal[:] = self.goal

    def stopping_point(self) -> np.ndarray:
        """Where the reference comes to rest braking as hard as allowed from its velocity (rad).

        Braking from v = n * a * dt covers a * dt^2 * n (n + 1) / 2 = v^2 / (2a) + v dt / 2."""
        speed = np.abs(self.velocity)
        distance = speed**2 / (2.0 * self.max_accel) + speed * self.period_s / 2.0
        return self.position + np.sign(self.velocity) * distance

    def step(self) -> None:
        """Advance one period toward the goal (along its segment)."""
        setpoint = self._segment.step()
        self.smoothed_goal += self._smoothing * (setpoint - self.smoothed_goal)
        # The filter only approaches the setpoint; snap the last nanoradians so a still goal is
        # reached exactly, as the braking curve promises.
        settled = np.abs(setpoint - self.smoothed_goal) < GOAL_SNAP_RAD
        self.smoothed_goal[settled] = setpoint[settled]
        error = self.smoothed_goal - self.position
        distance = np.abs(error)
        # Fastest speed from which braking still stops at the goal (the discrete braking curve),
        # never more than the distance left in one period (so the last step lands on the goal).
        braking = 0.5 * self._dv * (np.sqrt(1.0 + 8.0 * distance / self._accel_dt2) - 1.0)
        wanted = np.sign(error) * np.minimum(np.minimum(self.max_speed, braking),
                                             distance / self.period_s)
        velocity = np.clip(wanted, self.velocity - self._dv, self.velocity + self._dv)
        self.acceleration[:] = (velocity - self.velocity) / self.period_s
        self.velocity[:] = velocity
        self.position += velocity * self.period_s
