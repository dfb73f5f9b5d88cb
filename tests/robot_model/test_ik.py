"""Damped least-squares IK: accuracy, success rate, limits, and singularity reporting.

Fairness of the success-rate test: targets are FK of joint vectors drawn uniformly within the
limits (near-singular ones included, nothing filtered out), and each solve starts from a seed
0.3 rad (17 deg) per joint away from the generating configuration, in a random direction. That is
the teleoperation use case: the solver tracks a target from the current, nearby configuration.
A local solver seeded far away (e.g. always from ``home``) lands on another of the PUMA's eight
solution branches or on a joint limit about 37 % of the time: choosing the branch is the caller's
job.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from domain.robot_model.ik import IK_MAX_ITERATIONS, solve_ik
from domain.robot_model.kinematics import ArmKinematics
from domain.robot_model.singularity import SINGULAR_REFUSE_SIGMA, singularity_measures

NUM_TARGETS = 300
SEED_OFFSET = 0.3  # rad per joint
REQUIRED_SUCCESS_RATE = 0.99
POSITION_TOLERANCE = 1e-5  # m
ROTATION_TOLERANCE = 1e-4  # rad


def test_ik_reaches_random_poses(kin: ArmKinematics) -> None:
    rng = np.random.default_rng(2024)
    lower, upper = kin.lower_limits, kin.upper_limits
    successes = 0
    for _ in range(NUM_TARGETS):
        q_true = rng.uniform(lower, upper)
        seed = q_true + rng.choice((-1.0, 1.0), size=6) * SEED_OFFSET
        target = kin.tool_pose(q_true)
        result = solve_ik(kin, target, seed)

        assert kin.within_limits(result.q)
        reached = kin.tool_pose(result.q)
        position_error = np.linalg.norm(reached.translation - target.translation)
        rotation_error = np.linalg.norm(pin.log3(reached.rotation.T @ target.rotation))
        assert abs(result.position_error - position_error) < 1e-12
        assert abs(result.rotation_error - rotation_error) < 1e-12
        if result.success:
            assert position_error < POSITION_TOLERANCE and rotation_error < ROTATION_TOLERANCE
            successes += 1
    assert successes / NUM_TARGETS >= REQUIRED_SUCCESS_RATE, f"{successes}/{NUM_TARGETS} solved"


def test_ik_from_home_to_a_pose_near_the_fixture(kin: ArmKinematics) -> None:
    home = kin.tool_pose(kin.home_q)
    target = pin.SE3(home.rotation, home.translation + np.array([0.05, 0.03, -0.15]))
    result = solve_ik(kin, target, kin.home_q)
    assert result.success and result.iterations < 20
    np.testing.assert_allclose(kin.tool_pose(result.q).translation, target.translation, atol=1e-6)


def test_ik_reports_failure_for_unreachable_targets_without_raising(kin: ArmKinematics) -> None:
    far_away = pin.SE3(np.eye(3), np.array([3.0, 0.0, 0.5]))
    result = solve_ik(kin, far_away, kin.home_q)
    assert not result.success
    assert result.iterations == IK_MAX_ITERATIONS
    assert result.position_error > 1.0
    assert kin.within_limits(result.q) and np.isfinite(result.q).all()


def test_ik_clamps_seeds_outside_the_limits(kin: ArmKinematics) -> None:
    target = kin.tool_pose(kin.home_q)
    seed = kin.home_q.copy()
    seed[4] = 3.0  # beyond the 100 deg wrist limit
    result = solve_ik(kin, target, seed)
    assert result.success and kin.within_limits(result.q)


def test_singularity_measures(kin: ArmKinematics) -> None:
    home = singularity_measures(kin, kin.home_q)
    assert not home.near_singular and home.speed_scale() == 1.0
    assert home.manipulability > 0.0 and np.isfinite(home.condition_number)

    wrist_singular = kin.home_q.copy()
    wrist_singular[4] = 0.0  # wrist axes 4 and 6 aligned
    at_wrist = singularity_measures(kin, wrist_singular)
    assert at_wrist.near_singular and at_wrist.speed_scale() == 0.0
    assert at_wrist.min_singular_value < 1e-9 and at_wrist.manipulability < 1e-9

    elbow_stretched = kin.home_q.copy()
    elbow_stretched[2] = -np.pi / 2 + np.arctan2(0.0203, 0.4318)  # forearm in line with upper arm
    assert singularity_measures(kin, elbow_stretched).min_singular_value < SINGULAR_REFUSE_SIGMA
