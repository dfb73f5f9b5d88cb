"""The simulated arm and its servo, stepped directly (no threads, no shared memory)."""

from __future__ import annotations

import mujoco
import numpy as np
import pinocchio as pin
import pytest

from domain.robot_model.ik import solve_ik
from domain.robot_model.kinematics import ArmKinematics
from services.world.sim import MAX_JOINT_ACCEL_RAD_PER_S2, MAX_JOINT_SPEED_RAD_PER_S, ArmSim
from wire.errors import InvalidArgumentError

TRACKING_TOLERANCE_RAD = 1e-3  # steady state, after settling
SPEED_TOLERANCE = 0.05  # the joints may exceed the reference's cap by 5 % while following it
SETTLE_S = 0.5  # after the reference has arrived
# A hold from full speed stops within the braking distance v^2 / (2a) plus the servo's lag.
BRAKING_DISTANCE_RAD = MAX_JOINT_SPEED_RAD_PER_S**2 / (2 * MAX_JOINT_ACCEL_RAD_PER_S2)
TOOL_DOWN = np.diag([1.0, -1.0, -1.0])
STEP = np.array([0.3, -0.2, 0.25, 0.5, 0.4, -0.6])  # rad, a move every joint takes part in
BIG_STEP = np.array([0.8, -0.5, 0.6, 1.0, -0.5, 1.5])  # rad


@pytest.fixture
def sim() -> ArmSim:
    return ArmSim()


def run(sim: ArmSim, seconds: float) -> None:
    for _ in range(round(seconds / sim.period_s)):
        sim.step()


def run_until_arrived(sim: ArmSim, limit_s: float = 5.0) -> None:
    """Step until the reference reaches the target (fails after limit_s)."""
    for _ in range(round(limit_s / sim.period_s)):
        sim.step()
        if np.array_equal(sim.reference, sim.target):
            return
    pytest.fail(f"the reference did not reach the target within {limit_s} s")


def assert_clean(sim: ArmSim) -> None:
    assert [w.number for w in sim.data.warning] == [0] * len(sim.data.warning)
    assert np.isfinite(sim.data.qpos).all() and np.isfinite(sim.data.qvel).all()
    assert np.isfinite(sim.data.sensordata).all()
    assert sim.fault == ""


def test_starts_at_home_and_holds_it(sim: ArmSim) -> None:
    home = ArmKinematics().home_q
    np.testing.assert_allclose(sim.joint_positions, home, atol=1e-12)
    run(sim, 1.0)
    np.testing.assert_allclose(sim.joint_positions, home, atol=TRACKING_TOLERANCE_RAD)
    np.testing.assert_allclose(sim.target, home, atol=1e-12)


def test_tracks_a_joint_target_in_steady_state(sim: ArmSim) -> None:
    target = sim.joint_positions + STEP
    assert sim.set_target(target)
    run_until_arrived(sim)
    run(sim, SETTLE_S)
    assert np.abs(sim.joint_positions - target).max() < TRACKING_TOLERANCE_RAD
    assert np.abs(sim.joint_velocities).max() < 1e-3
    assert_clean(sim)


def test_a_big_target_change_respects_the_velocity_cap(sim: ArmSim) -> None:
    start = sim.joint_positions
    target = start + BIG_STEP
    sim.set_target(target)
    fastest, previous = 0.0, start
    for _ in range(2000):  # 2 s: the longest move (1.5 rad at 1 rad/s) is under way throughout
        sim.step()
        fastest = max(fastest, np.abs(sim.joint_velocities).max())
        # The reference never jumps: one step moves it at most cap * period.
        step = np.abs(sim.reference - previous).max()
        assert step <= MAX_JOINT_SPEED_RAD_PER_S * sim.period_s + 1e-12
        previous = sim.reference
    assert fastest > 0.9 * MAX_JOINT_SPEED_RAD_PER_S  # it did go at the cap
    assert fastest < MAX_JOINT_SPEED_RAD_PER_S * (1 + SPEED_TOLERANCE)
    run_until_arrived(sim)
    run(sim, SETTLE_S)
    assert np.abs(sim.joint_positions - target).max() < TRACKING_TOLERANCE_RAD


def test_targets_are_clipped_into_the_joint_limits(sim: ArmSim) -> None:
    sim.set_target(sim.joint_upper + 1.0)
    np.testing.assert_array_equal(sim.target, sim.joint_upper)


@pytest.mark.parametrize("bad", [np.zeros(5), np.full(6, np.nan), np.full(6, np.inf)])
def test_malformed_targets_are_refused(sim: ArmSim, bad: np.ndarray) -> None:
    before = sim.target
    with pytest.raises(InvalidArgumentError):
        sim.set_target(bad)
    np.testing.assert_array_equal(sim.target, before)


def test_latched_hold_keeps_position_and_ignores_later_targets(sim: ArmSim) -> None:
    run(sim, 0.1)
    held = sim.joint_positions
    sim.hold()
    assert sim.hold_latched
    assert not sim.set_target(held + STEP)
    run(sim, 1.0)
    assert np.abs(sim.joint_positions - held).max() < TRACKING_TOLERANCE_RAD
    np.testing.assert_allclose(sim.target, held, atol=1e-12)
    assert sim.arm_sample().hold_latched


def test_hold_while_moving_is_a_controlled_stop(sim: ArmSim) -> None:
    sim.set_target(sim.joint_positions + BIG_STEP)
    run(sim, 0.5)  # every joint at full speed
    at_hold = sim.joint_positions
    sim.hold()
    fastest_after = 0.0
    for _ in range(200):
        sim.step()
        fastest_after = max(fastest_after, np.abs(sim.joint_velocities).max())
    assert fastest_after < MAX_JOINT_SPEED_RAD_PER_S * (1 + SPEED_TOLERANCE)
    assert np.abs(sim.joint_velocities).max() < 1e-2  # stopped within 0.2 s
    assert np.abs(sim.joint_positions - at_hold).max() < 1.2 * BRAKING_DISTANCE_RAD
    stopped = sim.joint_positions
    run(sim, 1.0)
    assert np.abs(sim.joint_positions - stopped).max() < TRACKING_TOLERANCE_RAD
    assert_clean(sim)


def test_release_does_not_start_motion(sim: ArmSim) -> None:
    sim.set_target(sim.joint_positions + STEP)
    run(sim, 0.2)
    sim.hold()
    run(sim, 0.5)
    held = sim.joint_positions
    sim.release_hold()
    assert not sim.hold_latched
    np.testing.assert_array_equal(sim.target, held)  # not the pre-hold target
    run(sim, 1.0)
    assert np.abs(sim.joint_positions - held).max() < TRACKING_TOLERANCE_RAD
    assert sim.set_target(held + STEP)  # targets are accepted again


def test_release_without_a_hold_leaves_a_move_alone(sim: ArmSim) -> None:
    target = sim.joint_positions + STEP
    sim.set_target(target)
    run(sim, 0.1)
    sim.release_hold()
    np.testing.assert_array_equal(sim.target, target)
    run_until_arrived(sim)


def test_ten_simulated_seconds_of_motion_stay_clean(sim: ArmSim) -> None:
    home = sim.joint_positions
    for second in range(10):
        sim.set_target(home + (STEP if second % 2 == 0 else -STEP))
        run(sim, 1.0)
    assert sim.time_s == pytest.approx(10.0)
    assert sim.steps == 10_000
    assert_clean(sim)


def test_stable_pressing_on_the_table() -> None:
    """Target 5 mm below the table top: the peg presses on the table and the arm settles."""
    sim, kin = ArmSim(), ArmKinematics()
    beside_fixture = sim.data.site_xpos[sim.ids.hole_bottom_site] + np.array([-0.15, 0.10, 0.0])
    above = solve_ik(kin, pin.SE3(TOOL_DOWN, beside_fixture + [0, 0, 0.03]), kin.home_q)
    below = solve_ik(kin, pin.SE3(TOOL_DOWN, beside_fixture - [0, 0, 0.005]), above.q)
    assert above.success and below.success
    sim.set_target(above.q)
    run(sim, 2.5)
    sim.set_target(below.q)
    run(sim, 2.5)
    fastest = 0.0
    for _ in range(500):
        sim.step()
        fastest = max(fastest, np.abs(sim.joint_velocities).max())
    assert fastest < 0.02  # rad/s: resting on the table, no chatter
    assert sim.data.ncon > 0
    force = sim.wrench_sample().force_n
    assert np.isfinite(force).all() and np.linalg.norm(force) > 50.0  # N: it does press
    assert_clean(sim)


@pytest.fixture
def mujoco_warnings():
    """MuJoCo's warnings, captured here instead of appended to ./MUJOCO_LOG.TXT."""
    previous, captured = mujoco.get_mju_user_warning(), []
    mujoco.set_mju_user_warning(captured.append)
    yield captured
    mujoco.set_mju_user_warning(previous)


def test_a_diverged_state_is_a_fault_with_a_hold(sim: ArmSim, mujoco_warnings) -> None:
    run(sim, 0.05)
    good = sim.joint_positions
    sim.data.qvel[0] = np.nan  # what a blown-up simulation looks like
    sim.step()
    assert any("QVEL" in message for message in mujoco_warnings)
    assert sim.hold_latched
    assert "diverged" in sim.fault
    assert np.isfinite(sim.data.qpos).all() and np.isfinite(sim.data.qvel).all()
    np.testing.assert_allclose(sim.joint_positions, good, atol=1e-9)
    assert not sim.set_target(good + STEP)
    run(sim, 0.5)
    assert np.abs(sim.joint_positions - good).max() < TRACKING_TOLERANCE_RAD
    sim.release_hold()
    assert sim.fault == "" and not sim.hold_latched


def test_samples_carry_the_step_count_and_the_wrist_sensor(sim: ArmSim) -> None:
    run(sim, 0.01)
    arm, wrench = sim.arm_sample(123), sim.wrench_sample(123)
    assert arm.sequence == wrench.sequence == 10
    assert arm.sample_time_ns == wrench.sample_time_ns == 123
    # At rest the sensor carries the weight of the 0.1 kg peg.
    assert np.linalg.norm(wrench.force_n) == pytest.approx(0.1 * 9.81, rel=1e-3)
