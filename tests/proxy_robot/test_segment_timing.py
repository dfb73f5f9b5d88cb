"""SegmentTiming on a fake clock: how long each target's segment lasts. What the servo makes of
a segment is tested with the world's SegmentedGoal (tests/world/test_trajectory.py) and through
ProxyRobotCore on the fake arm (tests/proxy_robot/test_core.py)."""

from __future__ import annotations

import pytest

from services.proxy_robot.segment_timing import (
    INTERVAL_SMOOTHING,
    LONE_COMMAND_SPEED_RAD_PER_S,
    MAX_SEGMENT_S,
    SERVO_PERIOD_S,
    SegmentTiming,
)


class Clock:
    def __init__(self):
        self.now_ns = 1_000_000_000

    def advance(self, seconds: float) -> None:
        self.now_ns += round(seconds * 1e9)


@pytest.fixture
def clock() -> Clock:
    return Clock()


@pytest.fixture
def timing(clock) -> SegmentTiming:
    return SegmentTiming(lambda: clock.now_ns)


def test_a_lone_command_moves_at_the_lone_speed_not_over_a_whole_segment(timing):
    duration = timing.duration_s(0.01)  # 10 mrad on the largest joint
    assert duration == pytest.approx(0.01 / LONE_COMMAND_SPEED_RAD_PER_S)
    assert duration < MAX_SEGMENT_S / 2


def test_a_tiny_lone_command_goes_straight_to_the_servo(timing):
    assert timing.duration_s(1e-4) == 0.0  # 0.1 ms at the lone speed: under a servo period


def test_a_big_lone_command_is_capped_at_the_longest_segment(timing):
    assert timing.duration_s(0.2) == MAX_SEGMENT_S


def test_a_stream_is_spread_over_the_running_average_of_its_gaps(timing, clock):
    durations = []
    for _ in range(3):  # a 50 Hz stream
        durations.append(timing.duration_s(1e-3))
        clock.advance(0.02)
    average = MAX_SEGMENT_S + INTERVAL_SMOOTHING * (0.02 - MAX_SEGMENT_S)
    assert durations[1] == pytest.approx(average)
    average += INTERVAL_SMOOTHING * (0.02 - average)
    assert durations[2] == pytest.approx(average)


def test_a_stream_at_the_servo_rate_passes_straight_through(timing, clock):
    for _ in range(200):  # 1 kHz: the average falls to a servo period
        duration = timing.duration_s(1e-4)
        clock.advance(SERVO_PERIOD_S * 0.9)
    assert duration == 0.0


def test_a_pause_ends_the_stream_and_the_next_command_is_lone_again(timing, clock):
    for _ in range(5):
        timing.duration_s(1e-3)
        clock.advance(0.02)
    clock.advance(MAX_SEGMENT_S)  # a pause
    assert timing.duration_s(0.01) == pytest.approx(0.01 / LONE_COMMAND_SPEED_RAD_PER_S)
