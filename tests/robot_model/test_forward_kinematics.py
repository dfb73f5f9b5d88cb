"""MuJoCo, Pinocchio and an independent standard-DH implementation agree on every frame."""

from __future__ import annotations

import math

import mujoco
import numpy as np
import pinocchio as pin
import pytest

from domain.robot_model.kinematics import ArmKinematics, JacobianFrame
from domain.robot_model.loader import MujocoIds

# Written out independently of domain.robot_model.puma560 on purpose (Corke mdl_puma560,
# standard DH, base height 0.6718 m): rows are (d, a, alpha).
DH_ROWS = (
    (0.6718, 0.0, math.pi / 2),
    (0.0, 0.4318, 0.0),
    (0.15005, 0.0203, -math.pi / 2),
    (0.4318, 0.0, math.pi / 2),
    (0.0, 0.0, -math.pi / 2),
    (0.0, 0.0, 0.0),
)
LIMITS_DEG = ((-160, 160), (-45, 225), (-225, 45), (-110, 170), (-100, 100), (-266, 266))
TOOL_LENGTH = 0.1  # m, flange to peg tip along flange z

NUM_SAMPLES = 200
POSITION_TOLERANCE = 1e-9  # m
ROTATION_TOLERANCE = 1e-9  # max |element| difference of rotation matrices
LINK_BODIES = ("link1", "link2", "link3", "link4", "link5", "link6")


def dh_matrix(theta: float, d: float, a: float, alpha: float) -> np.ndarray:
    """Rz(theta) Tz(d) Tx(a) Rx(alpha)."""
    ct, st, ca, sa = math.cos(theta), math.sin(theta), math.cos(alpha), math.sin(alpha)
    return np.array(
        [
            [ct, -st * ca, st * sa, a * ct],
            [st, ct * ca, -ct * sa, a * st],
            [0, sa, ca, d],
            [0, 0, 0, 1.0],
        ]
    )


def rot_z(theta: float) -> np.ndarray:
    return dh_matrix(theta, 0.0, 0.0, 0.0)


def dh_frames(q: np.ndarray) -> list[np.ndarray]:
    """World poses of DH frames 0..6."""
    frames = [np.eye(4)]
    for theta, (d, a, alpha) in zip(q, DH_ROWS, strict=True):
        frames.append(frames[-1] @ dh_matrix(theta, d, a, alpha))
    return frames


def random_configurations(count: int, seed: int) -> np.ndarray:
    lower, upper = np.radians(LIMITS_DEG).T
    return np.random.default_rng(seed).uniform(lower, upper, size=(count, 6))


def assert_pose_close(actual: np.ndarray, expected: np.ndarray, what: str) -> None:
    position = np.abs(actual[:3, 3] - expected[:3, 3]).max()
    rotation = np.abs(actual[:3, :3] - expected[:3, :3]).max()
    assert position < POSITION_TOLERANCE, f"{what}: position differs by {position:.3g} m"
    assert rotation < ROTATION_TOLERANCE, f"{what}: rotation differs by {rotation:.3g}"


def mujoco_pose(pos: np.ndarray, xmat: np.ndarray) -> np.ndarray:
    pose = np.eye(4)
    pose[:3, :3] = xmat.reshape(3, 3)
    pose[:3, 3] = pos
    return pose


def test_model_limits_match_independent_table(kin: ArmKinematics) -> None:
    lower, upper = np.radians(LIMITS_DEG).T
    np.testing.assert_allclose(kin.lower_limits, lower, atol=1e-12)
    np.testing.assert_allclose(kin.upper_limits, upper, atol=1e-12)


def test_forward_kinematics_agree(
    mj_model: mujoco.MjModel, mj_data: mujoco.MjData, ids: MujocoIds, kin: ArmKinematics
) -> None:
    tip = np.eye(4)
    tip[2, 3] = TOOL_LENGTH
    body_ids = [mujoco.mj_name2id(mj_model, mujoco.mjtObj.mjOBJ_BODY, name) for name in LINK_BODIES]
    for q in random_configurations(NUM_SAMPLES, seed=1):
        frames = dh_frames(q)
        mj_data.qpos[ids.qpos] = q
        mujoco.mj_kinematics(mj_model, mj_data)

        # Body link_i is DH frame i-1 turned by q_i about its z axis (the hinge).
        for i, body in enumerate(body_ids, start=1):
            expected = frames[i - 1] @ rot_z(q[i - 1])
            assert_pose_close(
                mujoco_pose(mj_data.xpos[body], mj_data.xmat[body]),
                expected,
                f"mujoco {LINK_BODIES[i - 1]}",
            )
            assert_pose_close(
                kin.frame_pose(q, LINK_BODIES[i - 1]).homogeneous,
                expected,
                f"pinocchio {LINK_BODIES[i - 1]}",
            )

        flange, tool = frames[6], frames[6] @ tip
        site = ids.flange_site
        assert_pose_close(
            mujoco_pose(mj_data.site_xpos[site], mj_data.site_xmat[site]), flange, "mujoco flange"
        )
        site = ids.tool_site
        assert_pose_close(
            mujoco_pose(mj_data.site_xpos[site], mj_data.site_xmat[site]), tool, "mujoco tool_point"
        )
        assert_pose_close(kin.flange_pose(q).homogeneous, flange, "pinocchio flange")
        assert_pose_close(kin.tool_pose(q).homogeneous, tool, "pinocchio tool")


def test_tool_jacobians_match_mujoco(
    mj_model: mujoco.MjModel, mj_data: mujoco.MjData, ids: MujocoIds, kin: ArmKinematics
) -> None:
    jacp, jacr = np.zeros((3, mj_model.nv)), np.zeros((3, mj_model.nv))
    for q in random_configurations(50, seed=2):
        mj_data.qpos[ids.qpos] = q
        mujoco.mj_kinematics(mj_model, mj_data)
        mujoco.mj_comPos(mj_model, mj_data)
        mujoco.mj_jacSite(mj_model, mj_data, jacp, jacr, ids.tool_site)
        world = np.vstack([jacp[:, ids.dofs], jacr[:, ids.dofs]])
        np.testing.assert_allclose(kin.tool_jacobian(q, JacobianFrame.WORLD), world, atol=1e-12)

        rotation = mj_data.site_xmat[ids.tool_site].reshape(3, 3)
        local = np.vstack([rotation.T @ world[:3], rotation.T @ world[3:]])
        np.testing.assert_allclose(kin.tool_jacobian(q, JacobianFrame.LOCAL), local, atol=1e-12)
        np.testing.assert_allclose(kin.frame_jacobian(q, "tool_point"), world, atol=1e-12)


def test_jacobian_is_the_derivative_of_the_tool_position(kin: ArmKinematics) -> None:
    q = random_configurations(1, seed=3)[0]
    step = 1e-7
    numeric = np.empty((3, 6))
    for j in range(6):
        dq = np.zeros(6)
        dq[j] = step
        numeric[:, j] = (kin.tool_pose(q + dq).translation - kin.tool_pose(q - dq).translation) / (
            2 * step
        )
    np.testing.assert_allclose(kin.tool_jacobian(q)[:3], numeric, atol=1e-7)


def test_tool_transform_is_settable(kin: ArmKinematics) -> None:
    q = random_configurations(1, seed=4)[0]
    default = kin.flange_T_tool
    np.testing.assert_allclose(default.rotation, np.eye(3), atol=1e-15)
    np.testing.assert_allclose(default.translation, [0.0, 0.0, TOOL_LENGTH], atol=1e-15)

    offset = pin.SE3(pin.rpy.rpyToMatrix(0.1, -0.2, 0.3), np.array([0.01, -0.02, 0.15]))
    kin.flange_T_tool = offset
    np.testing.assert_allclose(kin.flange_T_tool.homogeneous, offset.homogeneous, atol=1e-15)
    np.testing.assert_allclose(
        kin.tool_pose(q).homogeneous, (kin.flange_pose(q) * offset).homogeneous, atol=1e-12
    )


def test_unknown_frame_names_raise(kin: ArmKinematics) -> None:
    with pytest.raises(KeyError):
        kin.frame_pose(np.zeros(6), "no_such_frame")
