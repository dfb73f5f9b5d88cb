"""Joint reference generator: moves a reference toward a goal under velocity and acceleration caps.

Each joint is treated on its own (no synchronisation between joints): the reference accelerates
at most ``max_accel`` up to at most ``max_speed`` and brakes along the discrete-time braking curve
so it lands exactly on the goal, with no overshoot, when the goal holds still. A goal that moves
mid-motion is chased the same way (it may then overshoot by the braking distance and come back).

The goal it chases is the commanded one passed through a first-order filter (time constant
``goal_smoothing_s``): targets streamed over a network arrive with jitter, a setpoint frozen for
a few periods then jumping, and chasing each jump at full acceleration would turn the jitter
into force spikes whenever a stiff servo is in contact with something.
"""

from __future__ import annotations

import numpy as np

GOAL_SNAP_RAD = 1e-9


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
        self.goal = self.position.copy()  # commanded
        self.smoothed_goal = self.position.copy()  # what the reference chases
        self._smoothing = 1.0 if goal_smoothing_s <= 0 else min(1.0, period_s / goal_smoothing_s)
        # Speed change allowed in one period, and the distance braking covers per period squared.
        self._dv = self.max_accel * self.period_s
        self._accel_dt2 = self.max_accel * self.period_s**2

    def reset(self, position: np.ndarray, velocity: np.ndarray | None = None) -> None:
        """Jump the reference to ``position`` (rad) moving at ``velocity`` (rad/s, clipped to the
        speed cap; default at rest). The goal becomes where it can stop (see stopping_point)."""
        self.position[:] = position
        if velocity is None:
            self.velocity[:] = 0.0
        else:
            np.clip(velocity, -self.max_speed, self.max_speed, out=self.velocity)
        self.acceleration[:] = 0.0
        self.goal[:] = self.stopping_point()
        self.smoothed_goal[:] = self.goal

    def stopping_point(self) -> np.ndarray:
        """Where the reference comes to rest braking as hard as allowed from its velocity (rad).

        Braking from v = n * a * dt covers a * dt^2 * n (n + 1) / 2 = v^2 / (2a) + v dt / 2."""
        speed = np.abs(self.velocity)
        distance = speed**2 / (2.0 * self.max_accel) + speed * self.period_s / 2.0
        return self.position + np.sign(self.velocity) * distance

    def step(self) -> None:
        """Advance one period toward the goal."""
        self.smoothed_goal += self._smoothing * (self.goal - self.smoothed_goal)
        # The filter only approaches the goal; snap the last nanoradians so a still goal is
        # reached exactly, as the braking curve promises.
        settled = np.abs(self.goal - self.smoothed_goal) < GOAL_SNAP_RAD
        self.smoothed_goal[settled] = self.goal[settled]
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
