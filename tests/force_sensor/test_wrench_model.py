"""The contact wrench at the tool, against MuJoCo's own contact forces in the simulated arm."""

from __future__ import annotations

import mujoco
import numpy as np
import pinocchio as pin
import pytest

from domain.robot_model import puma560
from domain.robot_model.ik import solve_ik
from domain.robot_model.kinematics import ArmKinematics
from domain.wrench_model import ContactWrench, contact_wrench
from services.force_sensor.core import default_payload
from services.world.sim import ArmSim

TOOL_DOWN = np.diag([1.0, -1.0, -1.0])


@pytest.fixture(scope="module")
def kinematics() -> ArmKinematics:
    return ArmKinematics()


def measured(sim: ArmSim, kinematics: ArmKinematics, bias=None) -> ContactWrench:
    raw = sim.wrench_sample()
    q = sim.joint_positions
    sensor = kinematics.frame_pose(q, puma560.FT_SITE)
    sensor_to_tool = sensor.actInv(kinematics.tool_pose(q))
    return contact_wrench(raw.force_n, raw.torque_nm, sensor.rotation, sensor_to_tool,
                          default_payload(), bias)


def settle(sim: ArmSim, target: np.ndarray, seconds: float = 2.5) -> None:
    sim.set_target(target)
    for _ in range(int(seconds / sim.period_s)):
        sim.step()


def peg_contact_force_world(sim: ArmSim) -> np.ndarray:
    """Sum of MuJoCo's contact forces on the peg, in world axes (the independent truth)."""
    model, data = sim.model, sim.data
    peg = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_GEOM, "peg")
    total = np.zeros(3)
    wrench = np.zeros(6)
    for i in range(data.ncon):
        contact = data.contact[i]
        if peg not in (contact.geom1, contact.geom2):
            continue
        mujoco.mj_contactForce(model, data, i, wrench)
        # In the contact frame (rows of `frame`), the force geom1 applies to geom2.
        force_world = contact.frame.reshape(3, 3).T @ wrench[:3]
        total += force_world if contact.geom2 == peg else -force_world
    return total


@pytest.mark.parametrize("joints", [
    puma560.HOME_Q,
    puma560.HOME_Q + np.array([0.3, -0.2, 0.25, 0.5, 0.4, -0.6]),
    puma560.HOME_Q + np.array([-0.5, 0.3, -0.4, -1.2, 0.6, 2.0]),
])
def test_no_contact_reads_zero_in_any_orientation(kinematics, joints):
    """The tool's weight is removed wherever the sensor points (no tare)."""
    sim = ArmSim()
    settle(sim, joints)
    wrench = measured(sim, kinematics)
    assert np.linalg.norm(wrench.force_n) < 5e-3  # N, against a 0.98 N tool weight
    assert np.linalg.norm(wrench.torque_nm) < 5e-4  # N·m


def test_pressing_on_the_table_pushes_along_minus_tool_z_as_much_as_the_contact(kinematics):
    sim = ArmSim()
    spot = sim.data.site_xpos[sim.ids.hole_bottom_site] + np.array([-0.15, 0.10, 0.0])
    above = solve_ik(kinematics, pin.SE3(TOOL_DOWN, spot + [0, 0, 0.03]), kinematics.home_q)
    below = solve_ik(kinematics, pin.SE3(TOOL_DOWN, spot - [0, 0, 0.002]), above.q)
    assert above.success and below.success
    settle(sim, above.q)
    free = measured(sim, kinematics)
    assert np.linalg.norm(free.force_n) < 5e-3
    settle(sim, below.q)

    wrench = measured(sim, kinematics)
    tool = kinematics.tool_pose(sim.joint_positions)
    truth_tool = tool.rotation.T @ peg_contact_force_world(sim)
    assert truth_tool[2] < -10.0  # the table pushes the peg back up its own axis
    np.testing.assert_allclose(wrench.force_n, truth_tool, rtol=0.02, atol=0.05)
    assert wrench.force_n[2] < 0 and abs(wrench.force_n[2]) > 0.99 * np.linalg.norm(
        wrench.force_n)
    # The contact is at the tip: little moment about the tool point (peg radius 10 mm).
    assert np.linalg.norm(wrench.torque_nm) < 0.01 * np.linalg.norm(wrench.force_n)


def test_bias_is_subtracted(kinematics):
    sim = ArmSim()
    settle(sim, puma560.HOME_Q, 0.5)
    bias = ContactWrench(np.array([1.0, 0, 0]), np.array([0, 0.5, 0]))
    wrench = measured(sim, kinematics, bias)
    np.testing.assert_allclose(wrench.force_n, [-1.0, 0, 0], atol=5e-3)
    np.testing.assert_allclose(wrench.torque_nm, [0, -0.5, 0], atol=5e-4)
