"""Pinocchio dynamics equal MuJoCo's, and the inertial data are the published ones."""

from __future__ import annotations

import mujoco
import numpy as np
import pinocchio as pin
import pytest

from domain.robot_model.kinematics import ArmKinematics
from domain.robot_model.loader import MujocoIds, load_mujoco_model

# Armstrong, Khatib & Burdick (1986) in Corke's mdl_puma560 (standard DH frames), typed in here
# independently of the parameter module.
MASSES = (0.0, 17.4, 4.8, 0.82, 0.34, 0.09)  # kg; link 1 has no published mass
COMS = (
    (0, 0, 0),
    (-0.3638, 0.006, 0.2275),
    (-0.0203, -0.0141, 0.070),
    (0, 0.019, 0),
    (0, 0, 0),
    (0, 0, 0.032),
)
INERTIAS = (
    (0.0, 0.35, 0.0),
    (0.13, 0.524, 0.539),
    (0.066, 0.086, 0.0125),
    (1.8e-3, 1.3e-3, 1.8e-3),
    (0.3e-3, 0.4e-3, 0.3e-3),
    (0.15e-3, 0.15e-3, 0.04e-3),
)
MOTOR_INERTIA = (200e-6, 200e-6, 200e-6, 33e-6, 33e-6, 33e-6)  # kg*m^2, Jm
GEAR_RATIO = (-62.6111, 107.815, -53.7063, 76.0364, 71.923, 76.686)  # G
MAX_TORQUE = (97.6, 186.4, 89.4, 24.2, 20.1, 21.3)  # N*m
LINK_BODIES = ("link1", "link2", "link3", "link4", "link5", "link6")

# The documented deviations from the table: (link index, axis) -> value used.
LINK1_PLACEHOLDER_MASS = 1.0
INERTIA_OVERRIDES = {(0, 0): 0.35, (0, 2): 0.35, (2, 0): 0.0735}


def random_state(
    rng: np.random.Generator, kin: ArmKinematics
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    q = rng.uniform(kin.lower_limits, kin.upper_limits)
    return q, rng.normal(scale=2.0, size=6), rng.normal(scale=5.0, size=6)


def mujoco_dynamics(model, data, ids, q, qd) -> tuple[np.ndarray, np.ndarray]:
    """(mass matrix, bias forces) from MuJoCo at (q, qd)."""
    data.qpos[ids.qpos], data.qvel[ids.dofs] = q, qd
    mujoco.mj_forward(model, data)
    full = np.zeros((model.nv, model.nv))
    mujoco.mj_fullM(model, data, full)
    return full[np.ix_(ids.dofs, ids.dofs)], data.qfrc_bias[ids.dofs].copy()


def test_dynamics_match_mujoco(
    mj_model, mj_data: mujoco.MjData, ids: MujocoIds, kin: ArmKinematics
) -> None:
    rng = np.random.default_rng(11)
    for _ in range(50):
        q, qd, qdd = random_state(rng, kin)
        mass, bias = mujoco_dynamics(mj_model, mj_data, ids, q, qd)
        gravity = mujoco_dynamics(mj_model, mj_data, ids, q, np.zeros(6))[1]

        np.testing.assert_allclose(kin.mass_matrix(q), mass, atol=1e-10)
        np.testing.assert_allclose(kin.gravity(q), gravity, atol=1e-10)
        np.testing.assert_allclose(kin.coriolis(q, qd) @ qd + kin.gravity(q), bias, atol=1e-9)
        np.testing.assert_allclose(kin.inverse_dynamics(q, qd, qdd), mass @ qdd + bias, atol=1e-9)


def test_mass_matrix_is_symmetric_positive_definite(kin: ArmKinematics) -> None:
    rng = np.random.default_rng(12)
    for _ in range(20):
        mass = kin.mass_matrix(random_state(rng, kin)[0])
        np.testing.assert_array_equal(mass, mass.T)
        assert np.linalg.eigvalsh(mass).min() > 0.0


def test_coriolis_matrix_is_passive(kin: ArmKinematics) -> None:
    """D_dot - 2C is skew-symmetric (energy conservation of the Pinocchio C)."""
    rng = np.random.default_rng(13)
    q, qd, _ = random_state(rng, kin)
    step = 1e-7
    mass_dot = (kin.mass_matrix(q + step * qd) - kin.mass_matrix(q - step * qd)) / (2 * step)
    skew = mass_dot - 2.0 * kin.coriolis(q, qd)
    np.testing.assert_allclose(skew, -skew.T, atol=1e-6)


@pytest.mark.parametrize("link", range(6))
def test_inertial_parameters_are_the_published_ones(mj_model, link: int) -> None:
    body = mujoco.mj_name2id(mj_model, mujoco.mjtObj.mjOBJ_BODY, LINK_BODIES[link])
    expected_mass = MASSES[link] if link > 0 else LINK1_PLACEHOLDER_MASS
    assert mj_model.body_mass[body] == pytest.approx(expected_mass, abs=1e-12)

    expected = [INERTIA_OVERRIDES.get((link, axis), INERTIAS[link][axis]) for axis in range(3)]
    np.testing.assert_allclose(np.sort(mj_model.body_inertia[body]), np.sort(expected), atol=1e-12)


def test_inertias_are_physical_in_both_engines(mj_model, kin: ArmKinematics) -> None:
    for link, name in enumerate(LINK_BODIES, start=1):
        body = mujoco.mj_name2id(mj_model, mujoco.mjtObj.mjOBJ_BODY, name)
        moments = np.sort(mj_model.body_inertia[body])
        assert moments[0] > 0.0 and moments[0] + moments[1] >= moments[2] - 1e-12, name

        inertia = kin.model.inertias[link]  # joint i carries link i (plus the tool on joint 6)
        assert inertia.mass > 0.0
        assert np.linalg.eigvalsh(inertia.inertia).min() > 0.0, name


def test_centres_of_mass_are_the_published_ones(kin: ArmKinematics) -> None:
    """COM of each link in its DH frame i equals the table (links 1-5; link 6 carries the tool)."""
    q = np.zeros(6)
    pin.forwardKinematics(kin.model, kin.data, q)
    # Body link_{i+1} sits at DH frame i (q = 0), so DH frame i = its pose; frame 6 = flange.
    frame_names = ("link2", "link3", "link4", "link5", "link6", "flange")
    for link in range(5):
        dh_frame = kin.frame_pose(q, frame_names[link])
        com_world = kin.data.oMi[link + 1].act(kin.model.inertias[link + 1].lever)
        np.testing.assert_allclose(dh_frame.actInv(com_world), COMS[link], atol=1e-12)


def test_drive_parameters(mj_model, ids: MujocoIds, kin: ArmKinematics) -> None:
    armature = np.array(MOTOR_INERTIA) * np.array(GEAR_RATIO) ** 2
    np.testing.assert_allclose(mj_model.dof_armature[ids.dofs], armature, rtol=1e-12)
    np.testing.assert_allclose(kin.model.armature, armature, rtol=1e-12)
    np.testing.assert_allclose(
        mj_model.actuator_ctrlrange[ids.actuators], np.c_[-np.array(MAX_TORQUE), MAX_TORQUE]
    )
    np.testing.assert_allclose(kin.torque_limits, MAX_TORQUE)
    np.testing.assert_allclose(mj_model.dof_damping[ids.dofs], kin.model.damping, rtol=1e-12)
    assert (mj_model.dof_damping[ids.dofs] > 0).all()


def test_computed_torque_gives_the_requested_acceleration_in_mujoco(
    ids: MujocoIds, kin: ArmKinematics
) -> None:
    """Feeding Pinocchio's RNEA torque (+ joint damping) to MuJoCo reproduces the acceleration."""
    model = load_mujoco_model()
    model.opt.disableflags |= mujoco.mjtDisableBit.mjDSBL_CONTACT  # free-space dynamics only
    data = mujoco.MjData(model)
    rng = np.random.default_rng(14)
    for _ in range(50):
        q, qd, qdd = random_state(rng, kin)
        data.qpos[ids.qpos], data.qvel[ids.dofs] = q, qd
        torque = kin.inverse_dynamics(q, qd, qdd) + model.dof_damping[ids.dofs] * qd
        data.qfrc_applied[ids.dofs] = torque  # bypasses the motors' torque limits
        mujoco.mj_forward(model, data)
        np.testing.assert_allclose(data.qacc[ids.dofs], qdd, atol=1e-8)
