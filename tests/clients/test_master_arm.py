"""The master arm: its model, the joint sources, indexing, scaling (eq. 2), impedance control
(eqs. 3 and 4) and force feedback (τ_ff = Jᵀ F). Domain only: no server."""

from __future__ import annotations

import json
import math
import sys
from types import SimpleNamespace

import numpy as np
import pinocchio as pin
import pytest

from clients.master import (
    FULL_INERTIA,
    ImpedanceController,
    IncrementFrame,
    MasterArm,
    MasterModel,
    ScriptedSource,
    SimulatedHand,
    SpaceMouseSource,
    SpaceMouseUnavailable,
    circle_path,
    hand_increment,
    line_path,
    load_script,
    scale,
    slave_wrench_to_master,
)
from domain.geometry import euler_xyz, from_euler_xyz


@pytest.fixture(scope="module")
def model() -> MasterModel:
    return MasterModel()


def random_q(model: MasterModel, rng: np.random.Generator) -> np.ndarray:
    """Joint angles well inside the limits (and so away from the elbow and gimbal lock)."""
    return rng.uniform(0.6 * model.lower_limits, 0.6 * model.upper_limits)


def assert_pose_close(a: pin.SE3, b: pin.SE3, atol: float = 1e-6) -> None:
    np.testing.assert_allclose(a.translation, b.translation, atol=atol)
    assert np.linalg.norm(pin.log3(a.rotation.T @ b.rotation)) <= atol


# -- the model ---------------------------------------------------------------------------------

def test_forward_kinematics_matches_the_documented_geometry(model):
    home = model.hand_pose(model.home_q)
    np.testing.assert_allclose(home.translation, [0.30, 0.0, 0.40], atol=1e-12)
    np.testing.assert_allclose(home.rotation, np.eye(3), atol=1e-12)
    # Elbow up by 0.3 rad: the forearm and handle (0.30 m) tilt up about y from (0, 0, 0.40).
    elbow = model.hand_pose([0, 0, -0.3, 0, 0, 0])
    np.testing.assert_allclose(elbow.translation,
                               [0.30 * math.cos(0.3), 0, 0.40 + 0.30 * math.sin(0.3)], atol=1e-12)
    # The turret turns the whole arm about z.
    turned = model.hand_pose([math.pi / 2, 0, 0, 0, 0, 0])
    np.testing.assert_allclose(turned.translation, [0, 0.30, 0.40], atol=1e-12)
    assert sum(i.mass for i in model.model.inertias) == pytest.approx(0.95)
    assert np.linalg.eigvalsh(model.mass_matrix(model.home_q)).min() > 0


# -- sources -------------------------------------------------------------------------------------

def test_the_simulated_hand_produces_the_intended_hand_motion(model):
    start = model.hand_pose(model.home_q)
    path = line_path(start, [0.0, 0.04, -0.02], pin.utils.rotate("z", 0.2), duration_s=1.0)
    hand = SimulatedHand(model, path)
    for t in np.arange(0.0, 1.2, 0.02):
        q = hand.read(t).q
        assert_pose_close(model.hand_pose(q), path(t))
    end = model.hand_pose(q)
    np.testing.assert_allclose(end.translation - start.translation, [0, 0.04, -0.02], atol=1e-6)
    np.testing.assert_allclose(pin.log3(end.rotation @ start.rotation.T), [0, 0, 0.2], atol=1e-6)

    circle = SimulatedHand(model)  # the default: a 3 cm circle in the y-z plane
    rest = model.hand_pose(model.home_q).translation
    centre = rest - [0, 0.03, 0]  # the circle starts from the rest pose (eased on over 1 s)
    for t in np.arange(0.0, 4.0, 0.05):
        reached = model.hand_pose(circle.read(t).q)
        assert_pose_close(reached, circle.target(t))
        if t >= 1.0:
            assert np.linalg.norm(reached.translation - centre) == pytest.approx(0.03, abs=1e-6)
            assert reached.translation[0] == pytest.approx(rest[0], abs=1e-6)


def test_script_source_replays_a_json_joint_file(tmp_path):
    script = {"format": "telerobot-master-script", "version": 1, "kind": "joints", "samples": [
        {"t": 0.0, "q": [0, 0, 0, 0, 0, 0]},
        {"t": 1.0, "q": [0.2, -0.1, 0.3, 0, 0.1, 0], "clutch": True},
        {"t": 2.0, "q": [0.4, -0.2, 0.0, 0.1, 0.1, -0.2]}]}
    path = tmp_path / "joints.json"
    path.write_text(json.dumps(script))
    source = ScriptedSource(path)
    for sample in script["samples"]:
        np.testing.assert_allclose(source.read(sample["t"]).q, sample["q"])
    np.testing.assert_allclose(source.read(0.5).q, [0.1, -0.05, 0.15, 0, 0.05, 0])
    np.testing.assert_allclose(source.read(-1.0).q, np.zeros(6))  # before: the first holds
    np.testing.assert_allclose(source.read(9.0).q, script["samples"][-1]["q"])  # after: last
    assert [source.read(t).clutch for t in (0.5, 1.0, 1.5, 2.0)] == [False, True, True, False]


def test_script_source_replays_a_csv_hand_pose_file(tmp_path, model):
    path = tmp_path / "poses.csv"
    path.write_text("# a hand-pose script\n"
                    "t,x,y,z,ax,ay,az,clutch\n"
                    "0.0,0.30,0.00,0.40,0.0,0.0,0.0,0\n"
                    "0.5,0.30,0.03,0.42,0.1,0.0,0.0,0\n"
                    "1.0,0.28,0.03,0.38,0.1,-0.1,0.2,1\n")
    source = ScriptedSource(path, model)
    assert source.script.kind == "hand_poses" and source.script.duration_s == 1.0
    for t, position, angles in ((0.0, [0.30, 0, 0.40], [0, 0, 0]),
                                (0.5, [0.30, 0.03, 0.42], [0.1, 0, 0]),
                                (1.0, [0.28, 0.03, 0.38], [0.1, -0.1, 0.2])):
        reading = source.read(t)
        assert_pose_close(model.hand_pose(reading.q),
                          pin.SE3(from_euler_xyz(np.array(angles)), np.array(position)))
    reading = source.read(0.25)  # halfway between the first two samples
    np.testing.assert_allclose(model.hand_pose(reading.q).translation, [0.30, 0.015, 0.41],
                               atol=1e-6)
    assert source.read(1.0).clutch is True


def test_bad_scripts_say_what_is_wrong(tmp_path):
    bad = tmp_path / "bad.csv"
    bad.write_text("t,q1,q2\n0,0,0\n")
    with pytest.raises(ValueError, match="header"):
        load_script(bad)
    backwards = tmp_path / "backwards.csv"
    backwards.write_text("t,q1,q2,q3,q4,q5,q6\n1,0,0,0,0,0,0\n0,0,0,0,0,0,0\n")
    with pytest.raises(ValueError, match="increasing"):
        load_script(backwards)
    wrong = tmp_path / "wrong.json"
    wrong.write_text(json.dumps({"format": "something-else", "version": 1}))
    with pytest.raises(ValueError, match="telerobot-master-script"):
        load_script(wrong)


def test_spacemouse_needs_its_optional_package(monkeypatch):
    monkeypatch.setitem(sys.modules, "pyspacemouse", None)  # makes the import fail
    with pytest.raises(SpaceMouseUnavailable, match="pip install pyspacemouse"):
        SpaceMouseSource()


def test_spacemouse_deflection_moves_the_hand(model):
    state = SimpleNamespace(x=0.525, y=0.0, z=0.0, roll=0.0, pitch=0.0, yaw=0.0, buttons=[0, 0])
    device = SimpleNamespace(read=lambda: state)
    source = SpaceMouseSource(model, device, max_speed_m_s=0.1, deadband=0.05)
    start = model.hand_pose(source.read(0.0).q).translation
    reading = source.read(0.1)  # half deflection past the deadband: 0.05 m/s for 0.1 s
    np.testing.assert_allclose(model.hand_pose(reading.q).translation - start,
                               [0.005, 0, 0], atol=1e-6)
    assert reading.clutch is False
    state.buttons = [1, 0]
    assert source.read(0.2).clutch is True


# -- increments, indexing and scaling -------------------------------------------------------------

def test_increment_frames_match_the_slave_mappings(model):
    rng = np.random.default_rng(3)
    reference = model.hand_pose(random_q(model, rng))
    hand = model.hand_pose(random_q(model, rng))
    dx, dm = hand_increment(reference, hand, IncrementFrame.PAPER)  # the paper's formulas
    np.testing.assert_allclose(dx, hand.translation - reference.translation)
    np.testing.assert_allclose(dm, reference.rotation.T @ hand.rotation)
    dx, dm = hand_increment(reference, hand, IncrementFrame.BASE)  # T⁺ = T + ΔX, R⁺ = ΔM R
    np.testing.assert_allclose(dm @ reference.rotation, hand.rotation, atol=1e-12)
    dx, dm = hand_increment(reference, hand, IncrementFrame.TOOL)  # tool⁺ = tool · (ΔM, ΔX)
    assert_pose_close(reference * pin.SE3(dm, dx), hand, atol=1e-12)


def test_indexing_sends_nothing_and_the_reference_follows_the_hand(model):
    start = model.hand_pose(model.home_q)
    arm = MasterArm(SimulatedHand(model, line_path(start, [0.05, 0, 0], duration_s=1.0)))
    sent = []
    assert arm.step(0.0, sent.append) is None  # the first reading sets the reference
    arm.step(0.1, sent.append)
    assert len(sent) == 1
    np.testing.assert_allclose(sent[0].delta_position, [0.005, 0, 0], atol=1e-6)

    arm.clutch = True
    for t in (0.2, 0.3, 0.4):
        assert arm.step(t, sent.append) is None
        assert arm.indexing
        # the reference follows the hand
        np.testing.assert_array_equal(arm.reference.homogeneous, arm.hand.homogeneous)
    assert len(sent) == 1  # nothing was sent while clutched
    np.testing.assert_allclose(arm.reference.translation, start.translation + [0.02, 0, 0],
                               atol=1e-6)

    arm.clutch = False
    increment = arm.step(0.5, sent.append)
    # Only the motion after the release is sent, not the 3 cm made while clutched.
    np.testing.assert_allclose(increment.delta_position, [0.005, 0, 0], atol=1e-6)
    assert len(sent) == 2 and not arm.indexing


def test_a_scripted_clutch_indexes_too(tmp_path):
    path = tmp_path / "clutch.csv"
    path.write_text("t,q1,q2,q3,q4,q5,q6,clutch\n"
                    "0,0,0,0,0,0,0,0\n1,0.1,0,0,0,0,0,1\n2,0.2,0,0,0,0,0,0\n")
    arm = MasterArm(ScriptedSource(path))
    sent = []
    for t in np.arange(0.0, 2.01, 0.25):
        arm.step(t, sent.append)
    assert [round(i.time_s, 2) for i in sent] == [0.25, 0.5, 0.75, 2.0]


def test_scaling_by_eq_2_halves_translations_and_small_rotation_angles(model):
    rng = np.random.default_rng(5)
    q0 = random_q(model, rng)
    start = model.hand_pose(q0)
    angles = np.array([0.02, -0.03, 0.05])
    target = pin.SE3(start.rotation @ from_euler_xyz(angles),
                     start.translation + [0.01, -0.02, 0.004])
    q1 = model.solve_ik(target, q0).q
    for frame in IncrementFrame:
        arm = MasterArm(SimulatedHand(model), model, translation_scale=0.5, frame=frame)
        arm.update(0.0, q0)
        increment = arm.update(0.02, q1)
        raw_dx, raw_dm = hand_increment(start, target, frame)
        np.testing.assert_allclose(increment.raw_delta_position, raw_dx, atol=1e-7)
        np.testing.assert_allclose(increment.delta_position, 0.5 * raw_dx, atol=1e-7)
        np.testing.assert_allclose(euler_xyz(increment.delta_rotation),
                                   0.5 * euler_xyz(raw_dm), atol=1e-7)
    # In the hand's own axes (PAPER and TOOL) the rotation is exactly the one applied.
    paper = hand_increment(start, target, IncrementFrame.PAPER)
    np.testing.assert_allclose(euler_xyz(scale(*paper, 0.5, 0.5)[1]), 0.5 * angles, atol=1e-7)
    with pytest.raises(ValueError):
        MasterArm(translation_scale=0)


# -- impedance control and force feedback -------------------------------------------------------

def test_eq_3_reduces_to_inverse_dynamics_with_alpha_equal_to_the_inertia(model):
    """With α = D(q), β = 0 and no feedback, eq. 3 is D q̈ + C(q, q̇) q̇ + G(q): exactly the
    torque that produces q̈ at (q, q̇), which RNEA computes by a different algorithm. So the
    controller's D (CRBA), C (Coriolis matrix) and G agree with pin.rnea to rounding."""
    rng = np.random.default_rng(11)
    full = ImpedanceController(model, alpha=FULL_INERTIA)
    constant = ImpedanceController(model, alpha=np.full(6, 1e-3), beta=-0.02)
    for _ in range(20):
        q, qd, qdd = random_q(model, rng), rng.normal(0, 2, 6), rng.normal(0, 5, 6)
        rnea = pin.rnea(model.model, model.model.createData(), q, qd, qdd)
        np.testing.assert_allclose(full.torques(q, qd, qdd).total, rnea, atol=1e-10)
        # Other gains: eq. 3 differs from the full dynamics by exactly (α − D) q̈ + β q̇.
        terms = constant.torques(q, qd, qdd)
        np.testing.assert_allclose(
            terms.total - rnea,
            (1e-3 * np.eye(6) - model.mass_matrix(q)) @ qdd - 0.02 * qd, atol=1e-10)
        np.testing.assert_allclose(terms.total, terms.inertia + terms.damping + terms.coriolis
                                   + terms.gravity + terms.feedback)


def test_eq_4_is_the_motion_the_arm_makes_under_eq_3(model):
    """Closed loop: the operator's torque τ_h plus eq. 3's motor torque, through the arm's own
    forward dynamics (pin.aba), give the q̈ of eq. 4, (D − α) q̈ = β q̇ + τ_ff + τ_h."""
    rng = np.random.default_rng(13)
    controller = ImpedanceController(model, alpha=lambda q: 0.5 * model.mass_matrix(q),
                                     beta=-0.05)
    for _ in range(10):
        q, qd = random_q(model, rng), rng.normal(0, 1, 6)
        hand, wrench = rng.normal(0, 0.1, 6), rng.normal(0, 2, 6)
        qdd = controller.closed_loop_acceleration(q, qd, hand, wrench)
        motors = controller.torques(q, qd, qdd, wrench).total
        np.testing.assert_allclose(model.forward_dynamics(q, qd, motors + hand), qdd,
                                   rtol=1e-8, atol=1e-8)
        # Halving the inertia the operator feels doubles the acceleration from their push.
        free = ImpedanceController(model, alpha=0.0, beta=0.0)
        np.testing.assert_allclose(
            ImpedanceController(model, lambda q: 0.5 * model.mass_matrix(q)).
            closed_loop_acceleration(q, qd, hand), 2 * free.closed_loop_acceleration(q, qd, hand),
            rtol=1e-8, atol=1e-10)


def test_force_feedback_torques_do_the_virtual_work_of_the_wrench(model):
    """τ_ff = Jᵀ F checked without the Jacobian: for each joint, a small motion δq moves the
    grip by δX and turns the hand by δθ (finite differences of the forward kinematics), and
    the work the wrench does, f·δX + m·δθ, must equal τ_ff·δq."""
    rng = np.random.default_rng(17)
    controller = ImpedanceController(model)
    h = 1e-6
    for _ in range(5):
        q, wrench = random_q(model, rng), rng.normal(0, 5, 6)
        torques = controller.feedback_torques(q, wrench)
        work = np.empty(6)
        for joint in range(6):
            step = np.zeros(6)
            step[joint] = h
            after, before = model.hand_pose(q + step), model.hand_pose(q - step)
            moved = after.translation - before.translation
            turned = pin.log3(after.rotation @ before.rotation.T)  # base axes
            work[joint] = (wrench[:3] @ moved + wrench[3:] @ turned) / (2 * h)
        np.testing.assert_allclose(torques, work, rtol=1e-6, atol=1e-8)


def test_the_slave_wrench_is_mapped_rotated_and_scaled(model):
    quarter_turn = pin.utils.rotate("z", math.pi / 2)
    force, torque = np.array([1.0, 0, 0]), np.array([0, 0, 0.5])
    mapped = slave_wrench_to_master(force, torque, frame=IncrementFrame.BASE,
                                    slave_tool_rotation=quarter_turn, force_scale=0.5,
                                    torque_scale=0.25)
    np.testing.assert_allclose(mapped, [0, 0.5, 0, 0, 0, 0.125], atol=1e-12)
    with pytest.raises(ValueError, match="tool_pose"):
        slave_wrench_to_master(force, torque, frame=IncrementFrame.BASE)

    hand = SimulatedHand(model, line_path(model.hand_pose(model.home_q), [0, 0, 0],
                                          pin.utils.rotate("x", 0.3)))
    arm = MasterArm(hand, translation_scale=0.5, frame=IncrementFrame.TOOL)
    arm.update(1.0)
    # TOOL: the tool's axes are the hand's; the default scale is the motion's, s = 0.5.
    np.testing.assert_allclose(arm.feedback_wrench(force, torque),
                               np.concatenate([0.5 * arm.hand.rotation @ force,
                                               0.5 * arm.hand.rotation @ torque]), atol=1e-12)
    with_feedback = arm.motor_torques(force, torque)
    np.testing.assert_allclose(with_feedback.feedback,
                               model.hand_jacobian(arm.q).T @ arm.feedback_wrench(force, torque))
    arm.force_feedback = False
    np.testing.assert_allclose(arm.motor_torques(force, torque).feedback, np.zeros(6))


def test_the_arm_estimates_velocity_and_acceleration_from_readings(model):
    path = circle_path(model.hand_pose(model.home_q), radius_m=0.03, period_s=2.0)
    arm = MasterArm(SimulatedHand(model, path), alpha=FULL_INERTIA)
    dt = 0.001
    for k in range(600):
        arm.update(k * dt)
    # Gravity dominates; the estimated q̇, q̈ feed the Coriolis and inertia terms.
    terms = arm.motor_torques()
    np.testing.assert_allclose(terms.gravity, model.gravity(arm.q))
    np.testing.assert_allclose(terms.total, model.inverse_dynamics(arm.q, arm.qd, arm.qdd),
                               atol=1e-9)
    assert np.abs(arm.qd).max() > 0.01


def test_tdpa_on_the_displayed_force_gives_the_hand_only_the_energy_the_slave_took_in(model):
    """#15: the master port's controller. Pushing down against the slave's force puts energy
    in and is shown in full; backing off along it is shown only as far as the slave's port has
    taken energy in (from its acks)."""
    from domain.passivity import MasterPassivity

    start = model.hand_pose(model.home_q)
    passivity = MasterPassivity()
    down = MasterArm(SimulatedHand(model, line_path(start, [0, 0, -0.02], duration_s=1.0)),
                     model, translation_scale=0.5, frame=IncrementFrame.BASE,
                     passivity=passivity)
    up_force_tool = np.array([0.0, 0.0, 20.0])  # the slave's tool axes = its base here
    down.update(0.0)
    for t in np.linspace(0.1, 1.0, 10):
        down.update(t)
        shown = down.feedback_wrench(up_force_tool, np.zeros(3), np.eye(3))
        np.testing.assert_allclose(shown[:3], 0.5 * up_force_tool)  # s·F, untouched
    # 20 mm of hand against 10 N shown: 0.2 J in (= 20 N over the slave's 10 mm).
    assert passivity.ledger.energy_in_j == pytest.approx(0.2, rel=1e-3)

    up = MasterArm(SimulatedHand(model, line_path(start, [0, 0, 0.02], duration_s=1.0)),
                   model, translation_scale=0.5, frame=IncrementFrame.BASE, passivity=passivity)
    up.update(0.0)
    up.update(0.5)
    assert np.allclose(up.feedback_wrench(up_force_tool, np.zeros(3), np.eye(3))[:3], 0.0,
                       atol=1e-4)  # (the IK strays by microns across the step)
    passivity.heard(0.05)  # the slave's port took in 50 mJ as it backed off
    up.update(1.0)
    shown = up.feedback_wrench(up_force_tool, np.zeros(3), np.eye(3))
    assert shown[2] * 0.01 == pytest.approx(0.05)  # exactly the energy there was, over 10 mm
    without = MasterArm(SimulatedHand(model, line_path(start, [0, 0, 0.02], duration_s=1.0)),
                        model, translation_scale=0.5, frame=IncrementFrame.BASE)
    without.update(0.0)
    without.update(0.5)
    np.testing.assert_allclose(without.feedback_wrench(up_force_tool, np.zeros(3),
                                                       np.eye(3))[:3], 0.5 * up_force_tool)
