"""Without its force sensor the arm does not move: a sensor that went down or hung holds the
arm and refuses Teleoperate's motion commands, with the reason in each ack; motion resumes once
it streams again. A sensor stopped on purpose, or never started, stops nothing."""

from __future__ import annotations

import threading
from concurrent.futures import ThreadPoolExecutor

import numpy as np

from services.decision_server.core import SENSOR_ALIVE_S, SENSOR_QUIET_NS
from services.decision_server.sessions import DEFAULT_MAX_COMMAND_AGE_S, WatchdogHold
from telerobot.v1 import decision_server_pb2 as pb
from tests.conftest import wait_for
from tests.decision_server.conftest import Operator
from wire.errors import UnavailableError

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
    events = station.core.events.subscribe(64)
    slave.sensor_hung = True  # no samples, and no answer when asked
    refused = operator.move(STEP)
    assert refused.outcome == pb.COMMAND_OUTCOME_REJECTED
    assert "force sensor went silent" in refused.detail and "holds" in refused.detail
    hold = wait_for(lambda: next((e.payload for e in iter(lambda: events.get(0), None)
                                  if isinstance(e.payload, WatchdogHold)), None),
                    what="the hold event")  # observers hear why the arm holds
    assert "force sensor went silent" in hold.reason
    # Held as the wrench was found stale (before the sensor was asked), and as it was lost.
    assert [reason.split(";")[0] for reason in _holds(slave)] == [
        "the force sensor's wrench went stale", refused.detail.split(";")[0]]
    assert operator.move(STEP).outcome == pb.COMMAND_OUTCOME_REJECTED
    assert len(_holds(slave)) == 2  # not again while it stays lost
    slave.sensor_hung = False
    slave.step(0.001)
    assert operator.move(STEP).outcome == pb.COMMAND_OUTCOME_APPLIED
    operator.close()


def _holds(slave) -> list[str]:
    return [c.detail for c in slave.commands if c.kind == "hold"]


def test_a_sensor_gone_quiet_between_commands_holds_the_arm_without_waiting_for_one(
        fake_station):
    """The segment the last command started would carry the arm on: the session's watchdog asks
    the sensor as soon as its wrench is SENSOR_QUIET_NS old, and holds the arm on no answer."""
    station, slave = fake_station
    operator = _streaming(station, slave)  # its watchdog: 0.5 s, far off
    slave.sensor_hung = True
    slave.clock.advance(SENSOR_QUIET_NS / 1e9 + 0.001)
    wait_for(lambda: len(_holds(slave)) == 2, timeout_s=5, what="the watchdog holding the arm")
    assert "went stale" in _holds(slave)[0] and "went silent" in _holds(slave)[1], _holds(slave)
    refused = operator.move(STEP)  # asked again: still no answer
    assert refused.outcome == pb.COMMAND_OUTCOME_REJECTED and "went silent" in refused.detail
    assert len(_holds(slave)) == 2, _holds(slave)
    slave.sensor_hung = False
    slave.step(0.001)
    assert operator.move(STEP).outcome == pb.COMMAND_OUTCOME_APPLIED
    operator.close()


def test_an_operator_gone_quiet_while_the_sensor_is_lost_is_still_held_for_it(fake_station):
    """The sensor's hold does not hide the operator's silence: the watchdog's own hold follows
    at its timeout, saying so (a frozen tab on a loaded machine, whose wrench went stale
    first, is still told apart from a lost sensor)."""
    station, slave = fake_station
    operator = _streaming(station, slave)  # its watchdog: 0.5 s
    events = station.core.events.subscribe(64)
    reasons: list[str] = []

    def hold_reasons() -> list[str]:
        reasons.extend(e.payload.reason for e in iter(lambda: events.get(0), None)
                       if isinstance(e.payload, WatchdogHold))
        return reasons

    slave.sensor_hung = True
    slave.clock.advance(SENSOR_QUIET_NS / 1e9 + 0.001)
    wait_for(lambda: any("went silent" in r for r in hold_reasons()), timeout_s=5,
             what="the sensor's hold")
    assert not any("watchdog timeout" in r for r in reasons)
    slave.clock.advance(0.5)  # the operator said nothing since its last command
    wait_for(lambda: any("watchdog timeout" in r for r in hold_reasons()), timeout_s=5,
             what=lambda: f"the watchdog's hold; holds so far: {reasons}")
    slave.sensor_hung = False
    slave.step(0.001)
    assert operator.move(STEP).outcome == pb.COMMAND_OUTCOME_APPLIED
    operator.close()


def _target_position(slave) -> np.ndarray:
    with slave._lock:
        return slave.kinematics.tool_pose(slave.q_target).translation.copy()


def test_a_quiet_sensor_that_answers_stops_the_arm_only_while_it_is_asked(fake_station):
    """A sensor that reads but streams nothing new (a change threshold) is asked and answers;
    the arm stopped while it was asked (the first time only), then finishes the segment the
    stop cut, so no motion is lost. It is asked again SENSOR_ALIVE_S later, and the arm goes
    on meanwhile."""
    station, slave = fake_station
    operator = _streaming(station, slave)  # the arm on its way to the first STEP
    commanded = _target_position(slave)
    slave.sensor_is_reading_calls = 0
    slave.clock.advance(SENSOR_QUIET_NS / 1e9 + 0.001)  # quiet, but alive
    wait_for(lambda: [c.kind for c in slave.commands][-2:] == ["hold", "cartesian"],
             timeout_s=5, what="the stop while asking, then the rest of the segment")
    assert "asking the sensor" in _holds(slave)[0] and slave.sensor_is_reading_calls == 1
    np.testing.assert_allclose(_target_position(slave), commanded, atol=1e-6)
    assert operator.move(STEP).outcome == pb.COMMAND_OUTCOME_APPLIED
    assert len(_holds(slave)) == 1
    slave.clock.advance(SENSOR_ALIVE_S + 0.001)  # still quiet: asked again, without a stop
    wait_for(lambda: slave.sensor_is_reading_calls == 2, timeout_s=5, what="asked again")
    assert operator.move(STEP).outcome == pb.COMMAND_OUTCOME_APPLIED
    assert len(_holds(slave)) == 1, _holds(slave)
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


def test_a_command_that_comes_while_the_watchdog_asks_the_sensor_is_still_watched(fake_station):
    """The sensor is lost, and the watchdog asks it again; a command comes meanwhile and waits
    for the question past its age, so it is carried, and the sensor then answers it. The
    watchdog must still watch that command's silence: its hold answers the carry, which would
    otherwise wait for a command the operator never sends (it waits for this one's ack)."""
    station, slave = fake_station
    operator = _streaming(station, slave)  # its watchdog: 0.5 s
    (session,) = station.core._sessions.values()
    slave.sensor_hung = True
    assert operator.move(STEP).outcome == pb.COMMAND_OUTCOME_REJECTED  # lost
    asked, release, taken = threading.Event(), threading.Event(), threading.Event()

    def probe(timeout_s: float) -> bool:  # the watchdog's question: no answer; others: alive
        if threading.current_thread().name.startswith("watchdog-"):
            asked.set()
            release.wait(10)
            raise UnavailableError("no answer within 40 ms", reason="SENSOR_SILENT")
        return True

    snapshot = station.core.snapshot

    def after_the_watchdog_asks():  # (the command's batch reads it just before its own check)
        taken.set()
        assert asked.wait(10)
        return snapshot()

    slave.sensor_is_reading, station.core.snapshot = probe, after_the_watchdog_asks
    with ThreadPoolExecutor(1) as pool:
        ack = pool.submit(operator.move, STEP)
        assert taken.wait(10)
        assert asked.wait(10)  # the command woke the watchdog, which asks the sensor
        slave.clock.advance(DEFAULT_MAX_COMMAND_AGE_S + 0.01)  # it waits past its age
        release.set()
        wait_for(lambda: session._late or ack.done(), what="the command carried")
        slave.clock.advance(0.6)  # past the watchdog's timeout
        refused = ack.result(timeout=10)
    assert refused.outcome == pb.COMMAND_OUTCOME_REJECTED
    assert "held before a fresh command came" in refused.detail
    operator.close()
