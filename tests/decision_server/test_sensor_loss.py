"""Without its force sensor the arm does not move: a sensor that went down or hung holds the
arm and refuses Teleoperate's motion commands, with the reason in each ack; motion resumes once
it streams again. A sensor stopped on purpose, or never started, stops nothing."""

from __future__ import annotations

from services.decision_server.core import SENSOR_QUIET_NS
from telerobot.v1 import decision_server_pb2 as pb
from tests.conftest import wait_for
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


def _holds(slave) -> list[str]:
    return [c.detail for c in slave.commands if c.kind == "hold"]


def test_a_sensor_gone_quiet_holds_the_arm_before_the_next_command(fake_station):
    """A segment in flight would carry the arm on for up to 50 ms after the last command: the
    session's watchdog holds it as soon as the wrench is overdue, once per silence."""
    station, slave = fake_station
    operator = _streaming(station, slave)
    slave.sensor_hung = True
    slave.clock.advance(SENSOR_QUIET_NS / 1e9 - 0.001)
    slave.clock.advance(0.002)
    wait_for(lambda: _holds(slave), timeout_s=5, what="the watchdog holding the arm")
    # held at its deadline, never before it (the reason tells when it looked)
    assert "wrench is 31 ms old" in _holds(slave)[0], _holds(slave)
    slave.clock.advance(0.05)  # still silent, still under the operator's watchdog (0.5 s)
    assert operator.move(STEP).outcome == pb.COMMAND_OUTCOME_REJECTED  # asked: it is hung
    slave.clock.advance(0.05)
    assert operator.move(STEP).outcome == pb.COMMAND_OUTCOME_REJECTED
    holds = _holds(slave)
    assert len(holds) == 2 and "went silent" in holds[1], holds  # the watchdog's, then the loss
    slave.sensor_hung = False
    slave.step(0.001)
    assert operator.move(STEP).outcome == pb.COMMAND_OUTCOME_APPLIED
    operator.close()


def test_a_sensor_that_streams_only_changes_is_not_held_on_for_its_quiet(fake_station):
    """A change threshold makes silence normal: once the sensor said it has one, its quiet
    holds nothing (its loss is still found by asking it, at the next command)."""
    station, slave = fake_station
    slave.sensor_threshold_n = 2.0
    operator = _streaming(station, slave)
    slave.clock.advance(0.04)  # nothing changed enough: nothing streamed
    wait_for(lambda: _holds(slave), timeout_s=5, what="the first silence's hold")
    assert operator.move(STEP).outcome == pb.COMMAND_OUTCOME_APPLIED  # asked: it streams changes
    slave.clock.advance(0.2)
    assert operator.move(STEP).outcome == pb.COMMAND_OUTCOME_APPLIED
    assert len(_holds(slave)) == 1, _holds(slave)
    slave.sensor_hung = True
    slave.clock.advance(0.2)  # past the time it was known alive: asked again, no answer
    refused = operator.move(STEP)
    assert refused.outcome == pb.COMMAND_OUTCOME_REJECTED and "went silent" in refused.detail
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
