"""The joint reference generator: caps respected, exact arrival, no overshoot."""

from __future__ import annotations

import numpy as np

from services.world.trajectory import JointReference

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
    ref.goal[:] = goals
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
    ref.goal[:] = 1.0
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
