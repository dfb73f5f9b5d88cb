"""The generated work cell: up to date, steps cleanly, sensible home, contacts where intended."""

from __future__ import annotations

import mujoco
import numpy as np
import pinocchio as pin
import pytest

from domain.robot_model import mjcf
from domain.robot_model.ik import solve_ik
from domain.robot_model.kinematics import ArmKinematics
from domain.robot_model.loader import MujocoIds, load_mujoco_model, mujoco_ids
from domain.robot_model.model_files import DEFAULT_ARM, arm_xml_path
from domain.robot_model.singularity import singularity_measures

SIM_SECONDS = 10.0
HOME_DRIFT_TOLERANCE = 1e-6  # rad, after 10 s of gravity compensation
TOOL_MASS = 0.10  # kg
GRAVITY = 9.81  # m/s^2
TOOL_DOWN = np.diag([1.0, -1.0, -1.0])  # tool z axis along -world z
ENVIRONMENT_BODIES = ("world", "table", "fixture")


def test_generated_xml_is_up_to_date() -> None:
    assert mjcf.stale_files() == [], "run: python -m domain.robot_model.mjcf"


def test_all_named_elements_resolve(mj_model: mujoco.MjModel, ids: MujocoIds) -> None:
    assert mj_model.nq == mj_model.nv == mj_model.nu == 6
    assert len(set(ids.qpos)) == len(set(ids.dofs)) == len(set(ids.actuators)) == 6
    assert ids.wrist_force.stop - ids.wrist_force.start == 3
    assert ids.wrist_torque.stop - ids.wrist_torque.start == 3
    assert mj_model.opt.timestep == pytest.approx(0.001)
    np.testing.assert_allclose(
        mj_model.cam_pos[ids.right_camera] - mj_model.cam_pos[ids.left_camera],
        mj_model.cam_mat0[ids.left_camera].reshape(3, 3)[:, 0] * 0.12,
        atol=1e-12,
    )


def test_missing_names_raise_key_error() -> None:
    bare_arm = load_mujoco_model(arm_xml_path(DEFAULT_ARM))  # no cameras or fixture
    with pytest.raises(KeyError, match="hole_entry"):
        mujoco_ids(bare_arm)


def test_home_is_a_ready_pose(
    mj_model: mujoco.MjModel, mj_data: mujoco.MjData, ids: MujocoIds, kin: ArmKinematics
) -> None:
    home = mj_model.key_qpos[ids.home_key]
    np.testing.assert_array_equal(home[ids.qpos], kin.home_q)
    assert kin.within_limits(home, tolerance=-np.radians(10))  # at least 10 deg inside every limit
    assert not singularity_measures(kin, home).near_singular

    mujoco.mj_resetDataKeyframe(mj_model, mj_data, ids.home_key)
    mujoco.mj_forward(mj_model, mj_data)
    tool_z = mj_data.site_xmat[ids.tool_site].reshape(3, 3)[:, 2]
    np.testing.assert_allclose(tool_z, [0.0, 0.0, -1.0], atol=1e-12)
    tip, hole = mj_data.site_xpos[ids.tool_site], mj_data.site_xpos[ids.hole_entry_site]
    assert 0.1 < tip[2] - hole[2] < 0.3 and np.linalg.norm(tip[:2] - hole[:2]) < 0.01
    assert mj_data.ncon == 0


def test_gravity_compensated_arm_holds_home_for_ten_seconds(
    mj_model: mujoco.MjModel, mj_data: mujoco.MjData, ids: MujocoIds, kin: ArmKinematics
) -> None:
    mujoco.mj_resetDataKeyframe(mj_model, mj_data, ids.home_key)
    home = mj_data.qpos.copy()
    for _ in range(round(SIM_SECONDS / mj_model.opt.timestep)):
        mj_data.ctrl[ids.actuators] = kin.gravity(mj_data.qpos[ids.qpos])
        mujoco.mj_step(mj_model, mj_data)

    assert mj_data.time == pytest.approx(SIM_SECONDS)
    assert [w.number for w in mj_data.warning] == [0] * len(mj_data.warning)
    assert np.isfinite(mj_data.qpos).all() and np.isfinite(mj_data.qvel).all()
    assert np.isfinite(mj_data.sensordata).all()
    assert np.abs(mj_data.qpos - home).max() < HOME_DRIFT_TOLERANCE
    # At rest the wrist sensor carries exactly the weight of the peg.
    force = mj_data.sensordata[ids.wrist_force]
    assert np.linalg.norm(force) == pytest.approx(TOOL_MASS * GRAVITY, rel=1e-6)


def test_uncontrolled_arm_falls_without_warnings(
    mj_model: mujoco.MjModel, mj_data: mujoco.MjData, ids: MujocoIds
) -> None:
    """Zero torque from home: the arm collapses onto the table and the simulation stays clean."""
    mujoco.mj_resetDataKeyframe(mj_model, mj_data, ids.home_key)
    for _ in range(3000):
        mujoco.mj_step(mj_model, mj_data)
    assert [w.number for w in mj_data.warning] == [0] * len(mj_data.warning)
    assert np.isfinite(mj_data.qpos).all()
    assert any("table" in pair for pair in _contact_bodies(mj_model, mj_data))


def _contact_bodies(model: mujoco.MjModel, data: mujoco.MjData) -> list[tuple[str, str]]:
    names = []
    for contact in data.contact[: data.ncon]:
        bodies = (model.geom_bodyid[contact.geom1], model.geom_bodyid[contact.geom2])
        names.append(
            tuple(sorted(mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, b) for b in bodies))
        )
    return names


def _place_tool_tip(mj_model, mj_data, ids, kin: ArmKinematics, tip: np.ndarray) -> None:
    result = solve_ik(kin, pin.SE3(TOOL_DOWN, tip), kin.home_q)
    assert result.success, f"tool tip {tip} not reachable pointing down"
    mj_data.qpos[ids.qpos] = result.q
    mujoco.mj_forward(mj_model, mj_data)


def test_peg_touches_the_table(
    mj_model, mj_data: mujoco.MjData, ids: MujocoIds, kin: ArmKinematics
) -> None:
    mujoco.mj_forward(mj_model, mj_data)
    # 2 mm below the table top, well clear of the fixture.
    beside_fixture = mj_data.site_xpos[ids.hole_bottom_site] + np.array([-0.15, 0.10, -0.002])
    _place_tool_tip(mj_model, mj_data, ids, kin, beside_fixture)
    assert ("table", "tool") in _contact_bodies(mj_model, mj_data)


def test_peg_fits_in_the_hole_with_clearance(
    mj_model, mj_data: mujoco.MjData, ids: MujocoIds, kin: ArmKinematics
) -> None:
    """26 mm square hole, 20 mm peg: 3 mm of play on each side."""
    mujoco.mj_forward(mj_model, mj_data)
    just_above_bottom = mj_data.site_xpos[ids.hole_bottom_site] + np.array([0.0, 0.0, 0.001])
    for offset_xy, touches in (
        ((0.0, 0.0), False),
        ((0.002, 0.0), False),
        ((0.0, -0.002), False),
        ((0.005, 0.0), True),
    ):
        _place_tool_tip(
            mj_model, mj_data, ids, kin, just_above_bottom + np.array([*offset_xy, 0.0])
        )
        assert (("fixture", "tool") in _contact_bodies(mj_model, mj_data)) == touches, offset_xy
        assert ("table", "tool") not in _contact_bodies(mj_model, mj_data)


def test_links_never_collide_with_each_other(
    mj_model, mj_data: mujoco.MjData, ids: MujocoIds, kin: ArmKinematics
) -> None:
    rng = np.random.default_rng(5)
    for _ in range(200):
        mj_data.qpos[ids.qpos] = rng.uniform(kin.lower_limits, kin.upper_limits)
        mujoco.mj_forward(mj_model, mj_data)
        for pair in _contact_bodies(mj_model, mj_data):
            assert any(body in ENVIRONMENT_BODIES for body in pair), pair
