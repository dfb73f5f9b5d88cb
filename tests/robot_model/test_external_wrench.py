"""The environment's wrench on the tool from joint torques, against MuJoCo's own contacts."""

from __future__ import annotations

import mujoco
import numpy as np
import pinocchio as pin
import pytest

from domain.robot_model.description import arm_description
from domain.robot_model.external_wrench import impedance_torques, wrench_at_frame
from domain.robot_model.ik import solve_ik
from domain.robot_model.kinematics import TOOL_FRAME, ArmKinematics
from domain.wrench_model import Payload, contact_wrench, wrist_reading
from services.world.sim import ArmSim

TOOL_DOWN = np.diag([1.0, -1.0, -1.0])


def settle(sim: ArmSim, target: np.ndarray, seconds: float = 2.5) -> None:
    sim.set_target(target)
    for _ in range(int(seconds / sim.period_s)):
        sim.step()


def peg_contacts(sim: ArmSim) -> tuple[np.ndarray, np.ndarray]:
    """(joint torques, total force in world axes) of MuJoCo's contacts on the peg: each
    contact force through MuJoCo's own point Jacobian (no Pinocchio)."""
    model, data = sim.model, sim.data
    peg = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_GEOM, "peg")
    torques, total = np.zeros(sim.arm.joint_count), np.zeros(3)
    wrench, jacobian = np.zeros(6), np.zeros((3, model.nv))
    for i in range(data.ncon):
        contact = data.contact[i]
        if peg not in (contact.geom1, contact.geom2):
            continue
        mujoco.mj_contactForce(model, data, i, wrench)
        force = contact.frame.reshape(3, 3).T @ wrench[:3]  # geom1 on geom2, world axes
        force = force if contact.geom2 == peg else -force
        mujoco.mj_jac(model, data, jacobian, None, contact.pos, model.geom_bodyid[peg])
        torques += jacobian[:, sim.ids.dofs].T @ force
        total += force
    return torques, total


# A spot on the table beside the fixture, that the arm reaches with the tool pointing down.
@pytest.mark.parametrize("name, beside_the_hole", [("fr3", [0.10, 0.10, 0.0]),
                                                   ("puma560", [-0.15, 0.10, 0.0])])
def test_a_push_on_the_table_comes_back_from_the_joints_as_the_contact_force(name,
                                                                             beside_the_hole):
    arm = arm_description(name)
    kinematics = ArmKinematics(arm=arm)
    sim = ArmSim(arm=arm)
    spot = sim.data.site_xpos[sim.ids.hole_bottom_site] + beside_the_hole
    above = solve_ik(kinematics, pin.SE3(TOOL_DOWN, spot + [0, 0, 0.03]), kinematics.home_q)
    below = solve_ik(kinematics, pin.SE3(TOOL_DOWN, spot - [0, 0, 0.002]), above.q)
    assert above.success and below.success
    settle(sim, above.q)
    settle(sim, below.q)

    torques, force_world = peg_contacts(sim)
    q = sim.joint_positions
    force, torque = wrench_at_frame(kinematics, q, TOOL_FRAME, torques)
    truth = kinematics.tool_pose(q).rotation.T @ force_world
    assert truth[2] < -10.0  # the table pushes the peg back up its own axis
    np.testing.assert_allclose(force, truth, rtol=0.02, atol=0.05)
    assert np.linalg.norm(torque) < 0.01 * np.linalg.norm(force)  # at the tip, on its axis


def test_a_joint_spring_pushed_off_its_setpoint_reads_the_push():
    stiffness = np.array([3000.0, 2000.0])
    # Pushed to +1 mrad and -2 mrad of the commanded angles: the push is K times that.
    np.testing.assert_allclose(
        impedance_torques(stiffness, [0.5, -0.2], [0.501, -0.202]), [3.0, -4.0])


def test_a_wrist_reading_of_an_estimated_push_gives_the_push_back():
    rng = np.random.default_rng(7)
    payload = Payload(0.1, np.array([0.0, 0.0, 0.05]))
    for _ in range(20):
        rotation = pin.SE3.Random().rotation
        force, torque = rng.normal(size=3) * 10, rng.normal(size=3)
        reading = wrist_reading(force, torque, rotation, payload)
        back = contact_wrench(*reading, rotation, pin.SE3.Identity(), payload)
        np.testing.assert_allclose(back.force_n, force, atol=1e-12)
        np.testing.assert_allclose(back.torque_nm, torque, atol=1e-12)
