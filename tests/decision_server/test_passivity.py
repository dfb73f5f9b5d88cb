"""TDPA's slave port in the DecisionServer (#15): a session that asks for it cannot push into
the environment with more energy than the master has put into the channel. On the fake slave
(its table a spring, 1e4 N/m) and a fake clock; the servicer through a real in-process server."""

from __future__ import annotations

import grpc
import numpy as np
import pytest

from services.decision_server.sessions import MasterIncrement
from telerobot.v1 import decision_server_pb2 as pb
from telerobot.v1 import types_pb2
from wire import convert

DOWN = np.array([0.0, 0.0, -1.0])
STEP_M = 5e-4
SERVO_PERIOD_S = 0.001


def push_down(rig, session, commands: int, master_energy_in_j: float | None):
    """`commands` steps of 0.5 mm down, 20 ms apart, each carrying the master's E_in."""
    results = []
    for _ in range(commands):
        sequence = session.last_sequence + 1
        results += session.commands([MasterIncrement(
            DOWN * STEP_M, np.eye(3), False, rig.clock.time_ns(), sequence, master_energy_in_j)])
        rig.slave.step(SERVO_PERIOD_S, 20)
    return results


def depth_m(rig) -> float:
    return rig.slave.floor_z - rig.slave.tool_pose().translation[2]


def floor_just_below(rig) -> None:
    rig.slave.floor_z = rig.slave.tool_pose().translation[2] - 0.001  # 1 mm below the tip
    rig.slave.step(SERVO_PERIOD_S)  # a first wrench sample: no contact


def test_without_passivity_the_slave_goes_as_deep_as_it_is_sent(rig):
    floor_just_below(rig)
    session = rig.core.open_session("alice", rig.lease.lease_id, "BASE", 1.0)
    results = push_down(rig, session, 20, master_energy_in_j=None)
    assert {r.outcome for r in results} == {"APPLIED"}
    assert depth_m(rig) == pytest.approx(0.009, abs=5e-4)  # 10 mm sent, 1 mm of it free
    assert session.passivity is None


def test_with_tdpa_the_slave_stops_where_the_master_has_paid_for_nothing(rig):
    floor_just_below(rig)
    session = rig.core.open_session("alice", rig.lease.lease_id, "BASE", 1.0, passivity=True)
    results = push_down(rig, session, 20, master_energy_in_j=0.0)
    # Free motion costs nothing; the step that reaches the floor lands (the force before it
    # was zero); every later one is taken out.
    assert results[0].outcome == "APPLIED" and results[-1].outcome == "MODIFIED"
    assert depth_m(rig) < STEP_M + 1e-4
    passivity = session.passivity
    assert passivity.ledger.energy_out_j <= passivity.master_in_j + 1e-12
    assert passivity.dissipated_j > 0.0
    # What was taken out is the drift: the slave is short of the master by about 9 mm.
    assert passivity.drift_m[2] == pytest.approx(-(0.010 - 0.001 - depth_m(rig)), abs=5e-4)


def test_the_energy_the_master_put_in_is_what_the_slave_may_spend(rig):
    floor_just_below(rig)
    session = rig.core.open_session("alice", rig.lease.lease_id, "BASE", 1.0, passivity=True)
    push_down(rig, session, 20, master_energy_in_j=0.02)
    passivity = session.passivity
    assert passivity.ledger.energy_out_j == pytest.approx(0.02, rel=1e-9)  # all of it, no more
    assert depth_m(rig) > STEP_M + 1e-4  # deeper than with nothing paid


def test_the_drift_comes_back_once_the_tool_is_free(rig):
    floor_just_below(rig)
    session = rig.core.open_session("alice", rig.lease.lease_id, "BASE", 1.0, passivity=True)
    push_down(rig, session, 10, master_energy_in_j=0.0)
    drift = session.passivity.drift_m.copy()
    assert drift[2] < -0.003
    rig.slave.floor_z -= 0.05  # the table gives way (say, the peg finds the hole)
    rig.slave.step(SERVO_PERIOD_S)
    for _ in range(40):  # the master holds still; the slave catches up in free motion
        session.commands([MasterIncrement(np.zeros(3), np.eye(3), False, rig.clock.time_ns(),
                                          session.last_sequence + 1, 0.0)])
        rig.slave.step(SERVO_PERIOD_S, 20)
    np.testing.assert_allclose(session.passivity.drift_m, np.zeros(3), atol=1e-12)


def init(lease: str, **fields) -> pb.TeleoperateRequest:
    return pb.TeleoperateRequest(init=pb.TeleoperateInit(
        operator_id="tester", lease_id=lease, mapping=types_pb2.REFERENCE_FRAME_BASE,
        watchdog_timeout=convert.duration(1.0), **fields))


def down(sequence: int, energy_in_j: float) -> pb.TeleoperateRequest:
    return pb.TeleoperateRequest(command=pb.MasterCommand(
        sequence=sequence, delta_position_m=types_pb2.Vector3(z=-STEP_M),
        master_energy=pb.PortEnergy(energy_in_j=energy_in_j)))


def test_acks_carry_the_slave_port_and_the_drift(fake_station):
    station, slave = fake_station
    slave.floor_z = slave.tool_pose().translation[2] - 0.0002
    slave.step(SERVO_PERIOD_S)
    lease, _ = station.acquire()
    messages = [init(lease, passivity=pb.PASSIVITY_TDPA)]
    messages += [down(sequence, 0.0) for sequence in range(1, 6)]
    messages.append(pb.TeleoperateRequest(heartbeat=pb.Heartbeat(
        master_energy=pb.PortEnergy(energy_in_j=0.0))))
    replies = list(station.decisions.Teleoperate(iter(messages), timeout=30))
    assert replies[0].ready.passivity == pb.PASSIVITY_TDPA
    acks = [r.ack for r in replies[1:]]
    assert all(a.HasField("slave_energy") for a in acks)  # the heartbeat's too
    assert acks[-1].outcome == pb.COMMAND_OUTCOME_HEARTBEAT
    # The fake arm is not stepped here, so the tool never reaches the floor 0.2 mm down: no
    # force, nothing dissipated, no drift: a passive flow is left as it is.
    assert {a.outcome for a in acks[:-1]} == {pb.COMMAND_OUTCOME_APPLIED}
    assert acks[-1].slave_energy.dissipated_j == 0.0
    assert acks[-1].passivity_drift_m == types_pb2.Vector3()


def test_a_session_without_passivity_says_off_and_sends_no_energy(fake_station):
    station, _ = fake_station
    lease, _ = station.acquire()
    replies = list(station.decisions.Teleoperate(iter([init(lease), down(1, 0.0)]), timeout=30))
    assert replies[0].ready.passivity == pb.PASSIVITY_OFF
    assert not replies[1].ack.HasField("slave_energy")


@pytest.mark.parametrize("energy", [float("nan"), -1.0, float("inf")])
def test_a_bad_energy_is_invalid_argument(fake_station, energy):
    station, _ = fake_station
    lease, _ = station.acquire()
    with pytest.raises(grpc.RpcError) as error:
        list(station.decisions.Teleoperate(iter([init(lease, passivity=pb.PASSIVITY_TDPA),
                                                 down(1, energy)]), timeout=30))
    assert error.value.code() is grpc.StatusCode.INVALID_ARGUMENT
    assert "master_energy" in error.value.details()
