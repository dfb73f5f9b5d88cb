"""The joint reference generator: caps respected, exact arrival, no overshoot."""

from __future__ import annotations

import numpy as np
import pytest

from services.world.trajectory import MAX_SEGMENT_S, JointReference, SegmentedGoal

PERIOD_S = 0.001
MAX_SPEED = 1.0  # rad/s
MAX_ACCEL = 10.0  # rad/s^2
EPS = 1e-9


def make(position=(0.0, 0.0, 0.0)) -> JointReference:
    n = len(position)
    return JointReference(np.array(position, float), np.full(n, MAX_SPEED),
                          np.full(n, MAX_ACCEL), PERIOD_S)


def test_lands_exactly_without_overshoot_within_the_caps() -> None:
    ref = make()
    goals = np.array([1.0, -0.3, 1e-5])  # long (cruises), short (never cruises), tiny
    ref.set_goal(goals)
    previous_velocity = ref.velocity.copy()
    for _ in range(2000):
        ref.step()
        assert np.all(np.abs(ref.velocity) <= MAX_SPEED + EPS)
        assert np.all(np.abs(ref.velocity - previous_velocity) <= MAX_ACCEL * PERIOD_S + EPS)
        assert np.all(np.abs(ref.position) <= np.abs(goals) + EPS)  # never past the goal
        previous_velocity = ref.velocity.copy()
    np.testing.assert_allclose(ref.position, goals, atol=1e-12)
    np.testing.assert_array_equal(ref.velocity, 0.0)


def test_takes_the_time_the_caps_impose() -> None:
    ref = make((0.0,))
    ref.set_goal(np.full(ref.position.shape, 1.0))
    steps = 0
    while ref.position[0] != ref.goal[0]:
        ref.step()
        steps += 1
    # 0.1 s up to speed, 0.9 s cruising, 0.1 s braking.
    assert abs(steps * PERIOD_S - (1.0 / MAX_SPEED + MAX_SPEED / MAX_ACCEL)) < 0.005


def test_reset_with_speed_stops_at_the_stopping_point() -> None:
    ref = make((0.0, 0.0))
    ref.reset(np.array([0.5, 0.5]), np.array([1.0, -3.0]))  # the second is clipped to the cap
    np.testing.assert_array_equal(ref.velocity, [1.0, -1.0])
    stop = ref.goal.copy()
    np.testing.assert_allclose(stop, [0.5 + 0.0505, 0.5 - 0.0505])
    for _ in range(200):
        ref.step()
        assert np.all(np.abs(ref.velocity) <= MAX_SPEED + EPS)
    np.testing.assert_allclose(ref.position, stop, atol=1e-12)


def test_a_segment_moves_the_setpoint_in_a_straight_line_over_the_periods_asked():
    goal = SegmentedGoal(np.array([0.0, 1.0]), PERIOD_S)
    goal.head_for(np.array([0.1, 0.8]), 0.010)  # ten periods
    np.testing.assert_array_equal(goal.target, [0.1, 0.8])
    for k in range(1, 11):
        np.testing.assert_allclose(goal.step(), [0.01 * k, 1.0 - 0.02 * k], atol=1e-12)
    np.testing.assert_array_equal(goal.step(), [0.1, 0.8])  # and stays
    # A new target half-way starts from where the setpoint is, not from the old target.
    goal.head_for(np.array([0.0, 0.8]), 0.004)
    goal.step(), goal.step()
    goal.head_for(np.array([0.2, 0.8]), 0.002)
    np.testing.assert_allclose(goal.step(), [0.125, 0.8], atol=1e-12)  # from 0.05, half-way
    np.testing.assert_allclose(goal.step(), [0.2, 0.8], atol=1e-12)


@pytest.mark.parametrize("duration_s,periods", [(0.0, 0), (0.001, 0), (float("nan"), 0),
                                                (-1.0, 0), (1e9, MAX_SEGMENT_S / PERIOD_S)])
def test_a_segment_too_short_or_nonsense_is_at_once_and_a_long_one_is_clipped(duration_s,
                                                                             periods):
    goal = SegmentedGoal(np.zeros(1), PERIOD_S)
    goal.head_for(np.ones(1), duration_s)
    steps = 0 if goal.setpoint[0] == 1.0 else 1
    while goal.step()[0] < 1.0:
        steps += 1
    assert steps == pytest.approx(max(periods, 0), abs=1)


def test_the_reference_follows_a_segmented_goal_and_a_reset_drops_the_segment():
    ref = make((0.0,))
    ref.set_goal(np.array([0.02]), 0.200)  # 0.1 rad/s: well within the caps
    for _ in range(100):
        ref.step()
    # Half-way along the line (0.01), a little behind it; at once, it would be at the goal.
    assert 0.008 < ref.position[0] <= 0.01
    assert ref.goal[0] == 0.02
    with pytest.raises(ValueError):
        ref.goal[0] = 1.0  # read-only: set_goal() is the way
    ref.reset(ref.position.copy())
    here = ref.position.copy()
    for _ in range(100):
        ref.step()
    np.testing.assert_allclose(ref.position, here, atol=1e-12)  # the rest of the line dropped
