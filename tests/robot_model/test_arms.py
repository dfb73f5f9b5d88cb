"""Every arm the project describes: its file reads, its cell works, and its kinematics match the
maker's own published tables (computed here, not read from the project)."""

from __future__ import annotations

import math
import shutil
from pathlib import Path

import mujoco
import numpy as np
import pinocchio as pin
import pytest

from domain.robot_model import ik
from domain.robot_model.description import (
    ArmDescriptionError,
    UnknownArmError,
    arm_description,
    available_arms,
    read_description,
)
from domain.robot_model.ik import solve_ik
from domain.robot_model.kinematics import ArmKinematics
from domain.robot_model.loader import load_mujoco_model, mujoco_ids
from domain.robot_model.singularity import singularity_measures

ARMS = ("fr3", "puma560", "ur5e")
TOOL_DOWN = np.diag([1.0, -1.0, -1.0])
RNG = np.random.default_rng(560)


def test_the_project_describes_three_arms() -> None:
    assert available_arms() == ARMS


def test_an_unknown_arm_lists_the_arms_there_are() -> None:
    message = "unknown arm 'kuka': the arms are fr3, puma560, ur5e"
    with pytest.raises(UnknownArmError, match=message):
        arm_description("kuka")


@pytest.fixture(params=ARMS)
def arm(request):
    return arm_description(request.param)


def test_the_description_is_what_the_file_declares(arm) -> None:
    model = mujoco.MjModel.from_xml_path(str(arm.arm_xml))
    joints = {"fr3": 7, "puma560": 6, "ur5e": 6}[arm.name]
    assert arm.joint_count == model.njnt == model.nu == joints
    assert arm.joint_names == tuple(model.joint(j).name for j in range(model.njnt))
    np.testing.assert_array_equal(arm.lower, model.jnt_range[:, 0])
    np.testing.assert_array_equal(arm.upper, model.jnt_range[:, 1])
    np.testing.assert_array_equal(arm.max_torque, model.actuator_ctrlrange[:, 1])
    assert (arm.max_velocity > 0).all() and (arm.lower < arm.home_q).all()
    # The tool point is the peg's tip, 100 mm along the flange's z axis, on every arm.
    np.testing.assert_allclose(arm.flange_T_tool[:3, 3], [0.0, 0.0, 0.1], atol=1e-12)
    np.testing.assert_allclose(arm.flange_T_tool[:3, :3], np.eye(3), atol=1e-12)


def test_home_is_a_ready_pose_above_the_hole(arm) -> None:
    kin = ArmKinematics(arm=arm)
    assert kin.within_limits(arm.home_q, tolerance=-math.radians(10))
    assert not singularity_measures(kin, arm.home_q).near_singular
    model = load_mujoco_model(arm.scene_xml)
    ids = mujoco_ids(model, arm)
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, ids.home_key)
    mujoco.mj_forward(model, data)
    np.testing.assert_allclose(data.site_xmat[ids.tool_site].reshape(3, 3)[:, 2], [0, 0, -1],
                               atol=1e-9)
    tip, hole = data.site_xpos[ids.tool_site], data.site_xpos[ids.hole_entry_site]
    assert 0.1 < tip[2] - hole[2] < 0.3 and np.linalg.norm(tip[:2] - hole[:2]) < 0.01
    assert data.ncon == 0


def test_gravity_compensation_holds_home_and_the_sensor_weighs_the_peg(arm) -> None:
    kin = ArmKinematics(arm=arm)
    model = load_mujoco_model(arm.scene_xml)
    ids = mujoco_ids(model, arm)
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, ids.home_key)
    for _ in range(5000):
        data.ctrl[ids.actuators] = kin.gravity(data.qpos[ids.qpos])
        mujoco.mj_step(model, data)
    assert [w.number for w in data.warning] == [0] * len(data.warning)
    assert np.abs(data.qpos[ids.qpos] - arm.home_q).max() < 1e-6
    assert np.linalg.norm(data.sensordata[ids.wrist_force]) == pytest.approx(0.1 * 9.81, rel=1e-6)


def test_the_peg_reaches_the_hole_floor_without_touching_the_walls(arm) -> None:
    kin = ArmKinematics(arm=arm)
    model = load_mujoco_model(arm.scene_xml)
    ids = mujoco_ids(model, arm)
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    bottom = data.site_xpos[ids.hole_bottom_site] + np.array([0.0, 0.0, 0.001])
    result = solve_ik(kin, pin.SE3(TOOL_DOWN, bottom), arm.home_q)
    assert result.success
    data.qpos[ids.qpos] = result.q
    mujoco.mj_forward(model, data)
    assert data.ncon == 0


# --- forward kinematics against the makers' tables ---------------------------------------------
def _rz(theta: float) -> np.ndarray:
    c, s = math.cos(theta), math.sin(theta)
    return np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1.0]])


def _rx(alpha: float) -> np.ndarray:
    c, s = math.cos(alpha), math.sin(alpha)
    return np.array([[1, 0, 0, 0], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, 1.0]])


def _t(x: float, y: float, z: float) -> np.ndarray:
    transform = np.eye(4)
    transform[:3, 3] = (x, y, z)
    return transform


def _fr3_flange(q: np.ndarray) -> np.ndarray:
    """Franka's modified-DH table (Craig): T_i = Rx(alpha_{i-1}) Tx(a_{i-1}) Rz(q_i) Tz(d_i),
    then the flange 0.107 m along z7."""
    a = (0.0, 0.0, 0.0, 0.0825, -0.0825, 0.0, 0.088)
    d = (0.333, 0.0, 0.316, 0.0, 0.384, 0.0, 0.0)
    alpha = (0.0, -math.pi / 2, math.pi / 2, math.pi / 2, -math.pi / 2, math.pi / 2, math.pi / 2)
    pose = np.eye(4)
    for i in range(7):
        pose = pose @ _rx(alpha[i]) @ _t(a[i], 0, 0) @ _rz(q[i]) @ _t(0, 0, d[i])
    return pose @ _t(0, 0, 0.107)


def _ur5e_flange(q: np.ndarray) -> np.ndarray:
    """Universal Robots' standard-DH table: T_i = Rz(q_i) Tz(d_i) Tx(a_i) Rx(alpha_i)."""
    d = (0.1625, 0.0, 0.0, 0.1333, 0.0997, 0.0996)
    a = (0.0, -0.425, -0.3922, 0.0, 0.0, 0.0)
    alpha = (math.pi / 2, 0.0, 0.0, math.pi / 2, -math.pi / 2, 0.0)
    pose = np.eye(4)
    for i in range(6):
        pose = pose @ _rz(q[i]) @ _t(0, 0, d[i]) @ _t(a[i], 0, 0) @ _rx(alpha[i])
    return pose


@pytest.mark.parametrize(("name", "reference"), [("fr3", _fr3_flange), ("ur5e", _ur5e_flange)])
def test_the_flange_is_where_the_makers_table_puts_it(name, reference) -> None:
    arm = arm_description(name)
    kin = ArmKinematics(arm=arm)
    for _ in range(50):
        q = RNG.uniform(arm.lower, arm.upper)
        expected, reached = reference(q), kin.flange_pose(q).homogeneous
        assert np.linalg.norm(reached[:3, 3] - expected[:3, 3]) < 1e-4
        np.testing.assert_allclose(reached[:3, :3], expected[:3, :3], atol=1e-6)


# --- the redundant arm's spare joint ----------------------------------------------------------
def _drive_a_square(kin: ArmKinematics) -> np.ndarray:
    """Drive the tool 20 cm out and back around a square in 1 mm steps; the final joints."""
    q, pose = kin.home_q.copy(), kin.tool_pose(kin.home_q)
    for step, count in (((0, 1, 0), 200), ((1, 0, 0), 100), ((0, -1, 0), 200), ((-1, 0, 0), 100)):
        for _ in range(count):
            pose = pin.SE3(pose.rotation, pose.translation + 0.001 * np.array(step, float))
            result = solve_ik(kin, pose, q)
            assert result.success
            q = result.q
    return q


def test_the_fr3_elbow_comes_home_with_the_tool(monkeypatch) -> None:
    kin = ArmKinematics(arm=arm_description("fr3"))
    assert np.abs(_drive_a_square(kin) - kin.home_q).max() < 1e-3
    # Without the null-space posture task the same drive leaves the elbow elsewhere.
    monkeypatch.setattr(ik, "POSTURE_GAIN", 0.0)
    assert np.abs(_drive_a_square(kin) - kin.home_q).max() > 0.03


def test_a_joint_near_its_limit_is_pushed_back_in_the_null_space() -> None:
    arm = arm_description("fr3")
    kin = ArmKinematics(arm=arm)
    seed = arm.home_q.copy()
    seed[2] = arm.upper[2] - 0.05  # joint 3 nearly at its limit
    q, pose = seed, kin.tool_pose(seed)
    for _ in range(10):  # the tool tracked 1 mm at a time
        pose = pin.SE3(pose.rotation, pose.translation + np.array([0.0, 0.0, 0.001]))
        result = solve_ik(kin, pose, q)
        assert result.success
        q = result.q
    assert q[2] < seed[2] - 0.1


# --- broken files are refused, naming the element -------------------------------------------
@pytest.fixture
def fr3_copy(tmp_path: Path) -> Path:
    copy = tmp_path / "arm.xml"
    shutil.copy(arm_description("fr3").arm_xml, copy)
    return copy


@pytest.mark.parametrize(("old", "new", "message"), [
    ('<site name="tool_point"', '<site name="tip"', "no site named 'tool_point'"),
    ('<key name="home"', '<key name="ready"', "no key named 'home'"),
    ('name="fr3_joint4" type="hinge" axis="0 0 1" range="-3.0481 -0.1458"',
     'name="fr3_joint4" type="hinge" axis="0 0 1" range="-0.1458 -3.0481"',
     "joint 'fr3_joint4' has no limits"),
    ('<motor name="fr3_joint7_motor" joint="fr3_joint7" ctrlrange="-12 12" />', "",
     "joint 'fr3_joint7' has no motor"),
    ('data="2.62 2.62 2.62 2.62 5.26 4.18 5.26"', 'data="2.62 2.62"',
     "numeric 'max_joint_velocity' needs 7 positive values"),
])
def test_a_broken_description_names_what_is_wrong(fr3_copy: Path, old, new, message) -> None:
    text = fr3_copy.read_text()
    assert old in text
    fr3_copy.write_text(text.replace(old, new))
    with pytest.raises(ArmDescriptionError, match=message) as raised:
        read_description("fr3", fr3_copy, fr3_copy)
    assert str(fr3_copy) in str(raised.value)


def test_a_tool_behind_a_joint_from_the_flange_is_refused(fr3_copy: Path) -> None:
    lines = fr3_copy.read_text().splitlines()
    tool = next(line for line in lines if '<site name="tool_point"' in line)
    lines.remove(tool)
    link6 = next(i for i, line in enumerate(lines) if '<body name="fr3_link6"' in line)
    lines.insert(link6 + 1, tool)  # on link 6: joint 7 lies between it and the flange
    fr3_copy.write_text("\n".join(lines))
    with pytest.raises(ArmDescriptionError, match="site 'tool_point' is not rigid with site "
                                                  "'flange'"):
        read_description("fr3", fr3_copy, fr3_copy)
