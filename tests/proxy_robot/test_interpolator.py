"""SetpointInterpolator on a fake clock: how long each segment lasts, and what reaches the servo."""

from __future__ import annotations

import numpy as np
import pytest

from services.proxy_robot.interpolator import (
    LONE_COMMAND_SPEED_RAD_PER_S,
    MAX_SEGMENT_S,
    SETPOINT_PERIOD_S,
    SetpointInterpolator,
)


class Servo:
    """The interpolator on a clock the test moves; records every setpoint written."""

    def __init__(self, start: np.ndarray):
        self.now_ns = 1_000_000_000
        self.written: list[tuple[float, np.ndarray]] = []
        self.interpolator = SetpointInterpolator(
            lambda q: self.written.append((self.now_ns / 1e9, np.array(q))), start,
            on_error=lambda exc: pytest.fail(f"write failed: {exc}"),
            monotonic_ns=lambda: self.now_ns, thread=False)

    def advance(self, seconds: float) -> None:
        """Move the clock on, one servo period at a time, writing setpoints as the thread
        would."""
        for _ in range(round(seconds / SETPOINT_PERIOD_S)):
            self.now_ns += round(SETPOINT_PERIOD_S * 1e9)
            self.interpolator.step()

    def time_to_reach(self, target: np.ndarray) -> float:
        """Seconds from the first setpoint of the last command to the one at `target`."""
        reached = [t for t, q in self.written if np.allclose(q, target, atol=1e-12)]
        return reached[0] - self.commanded_at

    def go(self, target: np.ndarray) -> None:
        self.commanded_at = self.now_ns / 1e9
        self.interpolator.go(target)


def test_a_lone_command_moves_at_the_lone_speed_not_over_a_whole_segment():
    servo = Servo(np.zeros(6))
    target = np.array([0.01, 0.0, 0.0, 0.0, 0.0, -0.005])  # 10 mrad on the largest joint
    servo.go(target)
    servo.advance(MAX_SEGMENT_S)
    expected = 0.01 / LONE_COMMAND_SPEED_RAD_PER_S
    assert servo.time_to_reach(target) == pytest.approx(expected, abs=SETPOINT_PERIOD_S)
    assert expected < MAX_SEGMENT_S / 2
    # No joint ever moved faster than the lone speed.
    times = np.array([t for t, _ in servo.written])
    qs = np.array([q for _, q in servo.written])
    speeds = np.abs(np.diff(qs, axis=0)) / np.diff(times)[:, None]
    assert speeds.max() <= LONE_COMMAND_SPEED_RAD_PER_S * 1.001


def test_a_tiny_lone_command_goes_straight_to_the_servo():
    servo = Servo(np.zeros(6))
    target = np.full(6, 1e-4)
    servo.go(target)
    assert np.array_equal(servo.written[-1][1], target)


def test_a_big_lone_command_is_capped_at_the_longest_segment():
    servo = Servo(np.zeros(6))
    target = np.array([0.2, 0, 0, 0, 0, 0])
    servo.go(target)
    servo.advance(2 * MAX_SEGMENT_S)
    assert servo.time_to_reach(target) == pytest.approx(MAX_SEGMENT_S, abs=SETPOINT_PERIOD_S)


def test_a_stream_is_spread_over_the_running_average_of_its_gaps():
    servo = Servo(np.zeros(6))
    q = np.zeros(6)
    for _ in range(3):  # a 50 Hz stream of 1 mrad steps on joint 1
        q = q + np.array([1e-3, 0, 0, 0, 0, 0])
        servo.go(q)
        servo.advance(0.02)
    # The third command's segment lasts the running average: 50 ms smoothed toward 20 ms gaps.
    average = MAX_SEGMENT_S + 0.1 * (0.02 - MAX_SEGMENT_S)
    average += 0.1 * (0.02 - average)
    _, start = next((t, q0) for t, q0 in reversed(servo.written) if t <= servo.commanded_at)
    first_after = [q0 for t, q0 in servo.written if t > servo.commanded_at][0]
    step = first_after[0] - start[0]
    expected_step = (q[0] - start[0]) * SETPOINT_PERIOD_S / average
    assert step == pytest.approx(expected_step, rel=1e-6)


def test_a_pause_ends_the_stream_and_the_next_command_is_lone_again():
    servo = Servo(np.zeros(6))
    q = np.zeros(6)
    for _ in range(5):
        q = q + np.array([1e-3, 0, 0, 0, 0, 0])
        servo.go(q)
        servo.advance(0.02)
    servo.advance(MAX_SEGMENT_S)  # a pause
    target = q + np.array([0.01, 0, 0, 0, 0, 0])
    servo.go(target)
    servo.advance(MAX_SEGMENT_S)
    assert servo.time_to_reach(target) == pytest.approx(
        0.01 / LONE_COMMAND_SPEED_RAD_PER_S, abs=SETPOINT_PERIOD_S)
