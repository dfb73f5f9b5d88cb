"""Without its force sensor the arm does not move: a sensor that went down or hung holds the
arm and refuses Teleoperate's motion commands, with the reason in each ack; motion resumes once
it streams again. A sensor stopped on purpose, or never started, stops nothing."""

from __future__ import annotations

from telerobot.v1 import decision_server_pb2 as pb
from tests.decision_server.conftest import Operator

STEP = (0, 0, 0.001)


def _streaming(station, slave):
    lease, _ = station.acquire()
    operator = Operator(station, lease)
    slave.step(0.001)  # a fresh wrench: the sensor streams
    assert operator.move(STEP).outcome == pb.COMMAND_OUTCOME_APPLIED
    return operator


def test_a_hung_sensor_holds_the_arm_until_it_streams_again(fake_station):
    station, slave = fake_station
    operator = _streaming(station, slave)
    slave.sensor_hung = True  # no samples, and no answer when asked
    refused = operator.move(STEP)
    assert refused.outcome == pb.COMMAND_OUTCOME_REJECTED
    assert "force sensor went silent" in refused.detail and "holds" in refused.detail
    holds = [c for c in slave.commands if c.kind == "hold"]
    assert len(holds) == 1  # held once, as the loss was noticed
    assert operator.move(STEP).outcome == pb.COMMAND_OUTCOME_REJECTED
    assert len([c for c in slave.commands if c.kind == "hold"]) == 1
    slave.sensor_hung = False
    slave.step(0.001)
    assert operator.move(STEP).outcome == pb.COMMAND_OUTCOME_APPLIED
    operator.close()


def test_a_sensor_process_that_is_down_holds_the_arm(fake_station):
    station, slave = fake_station
    operator = _streaming(station, slave)
    slave.dependency_health["force_sensor"] = "UNAVAILABLE: failed to connect"
    refused = operator.move(STEP)
    assert refused.outcome == pb.COMMAND_OUTCOME_REJECTED
    assert "force sensor is unavailable (UNAVAILABLE: failed to connect)" in refused.detail
    slave.dependency_health["force_sensor"] = "ok"
    assert operator.move(STEP).outcome == pb.COMMAND_OUTCOME_APPLIED
    operator.close()


def test_a_sensor_stopped_on_purpose_stops_nothing(fake_station):
    station, slave = fake_station
    operator = _streaming(station, slave)
    slave.sensor_reading = False  # StopReading: it answers that it does not read
    assert operator.move(STEP).outcome == pb.COMMAND_OUTCOME_APPLIED
    assert operator.move(STEP).outcome == pb.COMMAND_OUTCOME_APPLIED
    operator.close()
