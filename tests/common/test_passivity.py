"""TDPA on synthetic energy flows: a delayed channel into a stiff wall, no network, no clock."""

from __future__ import annotations

from collections import deque

import numpy as np
import pytest

from domain.passivity import (
    EnergyLedger,
    MasterPassivity,
    SlavePassivity,
    bound_force,
    bound_motion,
)

DOWN = np.array([0.0, 0.0, -1.0])
WALL_STIFFNESS_N_PER_M = 2e4


def wall_force(z_m: float) -> np.ndarray:
    """A wall at z = 0 pushing the tool up in proportion to how deep it is."""
    return np.array([0.0, 0.0, WALL_STIFFNESS_N_PER_M * max(-z_m, 0.0)])


FEEL_N = 8.0


def run_channel(delay_steps: int, passive: bool, steps: int = 400, speed_m: float = 2e-4,
                start_z_m: float = 0.004):
    """The master's hand steps down at `speed_m` per step, through a channel `delay_steps`
    late each way, onto a slave in front of the wall, until it feels FEEL_N; then it holds
    still (as make teleop's scripted operator does). Returns per-step records."""
    master, slave = MasterPassivity(), SlavePassivity()
    forward = deque([(np.zeros(3), 0.0)] * delay_steps)  # (hand step, master E_in)
    backward = deque([(np.zeros(3), 0.0)] * delay_steps)  # (force, slave E_in)
    z, records = start_z_m, []
    displayed = np.zeros(3)
    felt = False
    for _ in range(steps):
        hand_step = np.zeros(3) if felt else DOWN * speed_m
        if passive:
            shown = master.display(displayed, hand_step)
        else:
            shown = displayed
            master.ledger.add(-float(shown @ hand_step))
        felt = felt or shown[2] > FEEL_N
        forward.append((hand_step, master.ledger.energy_in_j))
        step, master_in = forward.popleft()
        force = wall_force(z)
        if passive:
            slave.heard(master_in)
            applied = slave.step(step, force).step_m
        else:
            applied = step
            slave.ledger.add(float(force @ applied))
        z += applied[2]
        backward.append((wall_force(z), slave.ledger.energy_in_j))
        displayed, slave_in = backward.popleft()
        master.heard(slave_in)
        records.append(dict(master_in=master.ledger.energy_in_j,
                            master_out=master.ledger.energy_out_j,
                            slave_in=slave.ledger.energy_in_j,
                            slave_out=slave.ledger.energy_out_j, sent_in=master_in,
                            force=float(wall_force(z)[2]), z=z))
    return records, master, slave


def test_a_delayed_channel_into_a_wall_makes_energy_without_the_controllers():
    records, _, _ = run_channel(delay_steps=20, passive=False)
    # The slave put far more energy into the wall than the master had put into the channel.
    deficit = max(r["slave_out"] - r["sent_in"] for r in records)
    assert deficit > 0.5  # joules, against 2.4 mJ the hand put in
    assert max(r["force"] for r in records) > 10 * FEEL_N


def test_without_the_controllers_the_peak_grows_with_the_delay():
    peaks = [max(r["force"] for r in run_channel(delay, passive=False)[0])
             for delay in (0, 5, 10, 20)]
    assert peaks == sorted(peaks) and peaks[-1] > 10 * peaks[0], peaks


@pytest.mark.parametrize("delay_steps", [0, 5, 10, 20])
def test_the_controllers_make_the_same_channel_passive_at_every_step(delay_steps):
    records, master, slave = run_channel(delay_steps=delay_steps, passive=True)
    for r in records:  # each side never put out more than the other had put in, as it knew
        assert r["slave_out"] <= r["sent_in"] + 1e-12
    assert master.ledger.energy_out_j <= master.slave_in_j + 1e-12
    if delay_steps:  # with no delay the channel is passive as it is
        assert slave.dissipated_j > 0.0 and slave.limited_steps > 0
    # The wall's force stays within a few times what the hand felt when it stopped.
    assert max(r["force"] for r in records) < 5 * FEEL_N


def test_the_peak_force_grows_far_less_with_the_delay():
    # Not flat: in the round trip before it feels the wall the hand still pays for a little
    # push (the small force it feels times its travel), and the slave may spend that.
    for delay in (5, 10, 20):
        off, on = (max(r["force"] for r in run_channel(delay, passive)[0])
                   for passive in (False, True))
        assert on < 0.5 * off, (delay, on, off)


def test_a_passive_channel_is_left_untouched():
    # Free motion (no force at all), then a wall with the master paying ahead of the slave:
    # the master's E_in, already received, covers every step the slave takes.
    slave = SlavePassivity()
    slave.heard(10.0)
    steps = [DOWN * 2e-4] * 50
    forces = [np.zeros(3)] * 25 + [np.array([0.0, 0.0, 20.0])] * 25
    applied = [slave.step(step, force).step_m for step, force in zip(steps, forces, strict=True)]
    np.testing.assert_array_equal(np.array(applied), np.array(steps))
    assert slave.dissipated_j == 0.0 and slave.limited_steps == 0
    np.testing.assert_array_equal(slave.drift_m, np.zeros(3))
    assert slave.ledger.energy_out_j == pytest.approx(25 * 20.0 * 2e-4)

    master = MasterPassivity()
    master.heard(10.0)
    force = np.array([0.0, 0.0, 5.0])
    for _ in range(20):  # the hand backs off along the force it feels, energy covered
        np.testing.assert_array_equal(master.display(force, -DOWN * 1e-3), force)
    assert master.dissipated_j == 0.0


def test_motion_across_or_along_the_force_is_never_limited():
    force = np.array([0.0, 0.0, 30.0])  # the wall pushes up
    sideways = np.array([1e-3, 0.0, 0.0])
    up = np.array([0.0, 0.0, 1e-3])
    for step in (sideways, up):
        applied, dissipated = bound_motion(step, force, available_j=0.0)
        np.testing.assert_array_equal(applied, step)
        assert dissipated == 0.0
    # Into the wall with no energy: only the part across the wall is left.
    applied, dissipated = bound_motion(sideways + DOWN * 1e-3, force, available_j=0.0)
    np.testing.assert_allclose(applied, sideways, atol=1e-15)
    assert dissipated == pytest.approx(30.0 * 1e-3)
    # With some energy: exactly that much goes in.
    applied, _ = bound_motion(DOWN * 1e-3, force, available_j=0.01)
    assert -force @ applied == pytest.approx(0.01)


def test_the_master_controller_takes_out_the_force_the_slave_did_not_pay_for():
    force = np.array([0.0, 0.0, 40.0])
    retreat = np.array([0.0, 0.0, 5e-4])  # the hand moves along the force: it takes energy
    shown, dissipated = bound_force(force, retreat, available_j=0.0)
    np.testing.assert_allclose(shown, np.zeros(3), atol=1e-12)
    assert dissipated == pytest.approx(40.0 * 5e-4)
    shown, _ = bound_force(force, retreat, available_j=0.004)
    assert shown @ retreat == pytest.approx(0.004)
    pushing = -retreat  # against the force: the hand gives energy, shown in full
    np.testing.assert_array_equal(bound_force(force, pushing, 0.0)[0], force)


def test_the_drift_goes_back_in_free_motion_and_waits_for_energy_at_a_wall():
    slave = SlavePassivity(drift_return_m=1e-4)
    wall = np.array([0.0, 0.0, 50.0])
    for _ in range(10):  # pushing into the wall with nothing paid: blocked
        slave.step(DOWN * 2e-4, wall)
    np.testing.assert_allclose(slave.drift_m, DOWN * 2e-3)
    for _ in range(5):  # still at the wall, no energy: the drift stays
        slave.step(np.zeros(3), wall)
    np.testing.assert_allclose(slave.drift_m, DOWN * 2e-3)
    for _ in range(25):  # free: it goes back at 0.1 mm a step
        slave.step(np.zeros(3), np.zeros(3))
    np.testing.assert_allclose(slave.drift_m, np.zeros(3), atol=1e-15)


def test_news_of_the_other_side_never_goes_back_and_the_ledger_splits_energy():
    slave = SlavePassivity()
    slave.heard(2.0)
    slave.heard(1.0)  # a stale message, late
    assert slave.master_in_j == 2.0
    ledger = EnergyLedger()
    for energy in (0.5, -0.2, 0.1, -0.4):
        ledger.add(energy)
    assert (ledger.energy_in_j, ledger.energy_out_j) == pytest.approx((0.6, 0.6))
