"""The staleness bound: no command moves the arm on its own after waiting in the station past
the session's max_command_age. Late commands join the next fresh one's move (MERGED_LATE, no
motion lost); a backlog past the bounds is refused and the arm holds; a hold, the clutch or a
new stream overtakes a carry. Timed with the injectable clock, never with sleeps."""

from __future__ import annotations

import queue
import threading

import numpy as np
import pytest

from services.decision_server.sessions import MasterIncrement, WatchdogHold
from telerobot.v1 import decision_server_pb2 as pb
from tests.conftest import wait_for
from tests.decision_server.conftest import Rig
from wire import convert
from wire.errors import InvalidArgumentError

MAX_AGE_S = 0.05
UP = np.array([0.0, 0.0, 0.001])


def increment(rig: Rig, sequence: int, delta=UP, *, age_s: float = 0.0,
              clutch: bool = False) -> MasterIncrement:
    """A command with `sequence`, received `age_s` before the clock's now."""
    return MasterIncrement(np.asarray(delta, float), np.eye(3), clutch,
                           rig.clock.time_ns() - int(age_s * 1e9), sequence)


def outcomes(decided) -> list[tuple[int, str]]:
    return [(i.sequence, result.outcome) for i, result in decided]


def target(rig: Rig) -> np.ndarray:
    return rig.slave.kinematics.tool_pose(rig.slave.q_target).translation


def holds(rig: Rig) -> int:
    return sum(c.kind == "hold" for c in rig.slave.commands)


@pytest.fixture
def session(rig):
    session = rig.core.open_session("alice", rig.lease.lease_id, "BASE", 1.0,
                                    max_command_age_s=MAX_AGE_S)
    yield session
    session.close("done")


def test_a_late_command_waits_for_the_next_fresh_one_and_moves_with_it(rig, session):
    start = target(rig)
    assert session.decide([increment(rig, 1, age_s=0.06)]) == []  # late: not on its own
    assert rig.moves() == 0
    decided = session.decide([increment(rig, 2, [0.0, 0.002, 0.0])])
    assert outcomes(decided) == [(1, "MERGED_LATE"), (2, "APPLIED")]
    assert "waited 60 ms; applied with command 2" in decided[0][1].detail
    assert rig.moves() == 1
    np.testing.assert_allclose(target(rig) - start, [0.0, 0.002, 0.001], atol=1e-9)
    assert session.counts().applied == 2


def test_late_commands_in_a_batch_join_its_fresh_one_in_one_move(rig, session):
    start = target(rig)
    batch = [increment(rig, 1, age_s=0.09), increment(rig, 2, age_s=0.07),
             increment(rig, 3, age_s=0.01)]
    assert outcomes(session.decide(batch)) == [(1, "MERGED_LATE"), (2, "MERGED_LATE"),
                                              (3, "APPLIED")]
    assert rig.moves() == 1
    np.testing.assert_allclose(target(rig) - start, 3 * UP, atol=1e-9)


def test_a_command_within_the_age_is_applied_on_its_own(rig, session):
    assert outcomes(session.decide([increment(rig, 1, age_s=0.049)])) == [(1, "APPLIED")]
    assert rig.moves() == 1


def test_a_backlog_older_than_ten_ages_is_refused_and_the_arm_holds(rig, session):
    events = rig.core.events.subscribe(64)
    start = target(rig)
    decided = session.decide([increment(rig, 1, age_s=0.6), increment(rig, 2)])
    assert outcomes(decided) == [(1, "REJECTED"), (2, "REJECTED")]
    assert "backlog" in decided[0][1].detail and "600 ms" in decided[0][1].detail
    assert rig.moves() == 0 and holds(rig) == 1
    np.testing.assert_allclose(target(rig), start, atol=1e-9)
    hold = wait_for(lambda: next((e.payload for e in iter(lambda: events.get(0), None)
                                  if isinstance(e.payload, WatchdogHold)), None),
                    what="the hold event")
    assert "backlog" in hold.reason
    # The next fresh command moves the arm again, from where it held.
    assert outcomes(session.decide([increment(rig, 3)])) == [(3, "APPLIED")]


def test_a_late_carry_bigger_than_one_move_is_refused_and_the_arm_holds(rig, session):
    late = [increment(rig, i, [0.0, 0.0, 0.001], age_s=0.06) for i in range(1, 26)]
    decided = session.decide([*late, increment(rig, 26)])  # 26 mm in all, past 20 mm
    assert {outcome for _, outcome in outcomes(decided)} == {"REJECTED"}
    assert len(decided) == 26 and "26.0 mm" in decided[0][1].detail
    assert rig.moves() == 0 and holds(rig) == 1


def test_a_watchdog_hold_overtakes_a_carry(rig):
    armed = rig.clock.waiters()
    session = rig.core.open_session("alice", rig.lease.lease_id, "BASE", 0.1,
                                    max_command_age_s=MAX_AGE_S)
    try:
        assert session.decide([increment(rig, 1, age_s=0.06)]) == []
        wait_for(lambda: rig.clock.waiters() > armed, what="the watchdog to arm")
        rig.clock.advance(0.2)
        wait_for(lambda: holds(rig) == 1, what="the watchdog's hold")
        start = target(rig)
        decided = session.decide([increment(rig, 2)])
        assert outcomes(decided) == [(1, "REJECTED"), (2, "APPLIED")]
        assert "held before a fresh command" in decided[0][1].detail
        np.testing.assert_allclose(target(rig) - start, UP, atol=1e-5)  # 2 alone (IK from a hold)
    finally:
        session.close("done")


def test_a_carry_the_watchdog_overtook_while_its_batch_ran_is_refused_with_it(rig):
    """The watchdog holds the arm while a batch is being decided (a slow station), before the
    batch's late command is carried: nothing will overtake the carry after that, so it is
    refused in that batch's answer, not left unanswered until a fresh command comes."""
    armed = rig.clock.waiters()
    session = rig.core.open_session("alice", rig.lease.lease_id, "BASE", 0.1,
                                    max_command_age_s=MAX_AGE_S)
    health = rig.slave.health

    def slow_station():  # (asked as the batch is decided, before its commands are)
        rig.slave.health = health
        rig.clock.advance(0.2)
        wait_for(lambda: holds(rig) == 1, what="the watchdog's hold")
        return health()

    try:
        wait_for(lambda: rig.clock.waiters() > armed, what="the watchdog to arm")
        rig.slave.health = slow_station
        decided = session.decide([increment(rig, 1)])
        assert outcomes(decided) == [(1, "REJECTED")]
        assert "held before a fresh command" in decided[0][1].detail
        assert rig.moves() == 0
    finally:
        rig.slave.health = health
        session.close("done")


def test_the_clutch_overtakes_a_carry(rig, session):
    assert session.decide([increment(rig, 1, age_s=0.06)]) == []
    decided = session.decide([increment(rig, 2, clutch=True)])
    assert outcomes(decided) == [(1, "REJECTED"), (2, "INDEXED")]
    assert "indexing" in decided[0][1].detail
    assert rig.moves() == 0


def test_a_carry_dies_with_its_stream_unanswered_and_its_resend_is_processed(rig, session):
    assert session.decide([increment(rig, 1, age_s=0.06)]) == []
    session.end(1, "the stream broke", resumable=True)
    stream = session.resume()
    # Command 1 was never answered, so the master resends it; it is processed, once.
    decided = session.decide([increment(rig, 1), increment(rig, 2)], stream)
    assert outcomes(decided) == [(1, "APPLIED"), (2, "APPLIED")]


@pytest.mark.parametrize("age_s", [0.001, 2.0, -0.05])
def test_max_command_age_out_of_bounds_is_invalid_argument(rig, age_s):
    with pytest.raises(InvalidArgumentError) as error:
        rig.core.open_session("alice", rig.lease.lease_id, "BASE", 1.0, max_command_age_s=age_s)
    assert error.value.reason == "BAD_MAX_COMMAND_AGE"


def test_zero_max_command_age_means_fifty_ms(rig: Rig):
    session = rig.core.open_session("alice", rig.lease.lease_id, "BASE", 1.0)
    assert session.max_command_age_s == 0.05
    session.close("done")


# -- over the wire ------------------------------------------------------------------------------

class WireSession:
    """A Teleoperate stream to the fake station whose arm's first move waits for `release`,
    so that commands wait behind it; `send(n)` returns once command n arrived."""

    def __init__(self, fake_station, watchdog_s: float):
        self.station, self.slave = fake_station
        self.clock = self.station.core.clock
        self.arrived: list[float] = []
        self.station.servicer.on_command_age = self.arrived.append
        self.entered, self.release = threading.Event(), threading.Event()
        move = self.slave.move_cartesian

        def slow_first_move(*args):
            if not self.entered.is_set():
                self.entered.set()
                self.release.wait(10)
            return move(*args)

        self.slave.move_cartesian = slow_first_move
        lease, _ = self.station.acquire()
        self.requests: queue.Queue = queue.Queue()
        self.requests.put(pb.TeleoperateRequest(init=pb.TeleoperateInit(
            operator_id="tester", lease_id=lease, watchdog_timeout=convert.duration(watchdog_s),
            max_command_age=convert.duration(MAX_AGE_S))))
        self.replies = self.station.decisions.Teleoperate(iter(self.requests.get, None),
                                                          timeout=60)

    def send(self, sequence: int, receipt: pb.AckReceipt | None = None) -> None:
        self.requests.put(pb.TeleoperateRequest(command=pb.MasterCommand(
            sequence=sequence, send_time=convert.timestamp(self.clock.time_ns()),
            delta_position_m=convert.vector3_to_proto(UP), ack_receipt=receipt)))
        wait_for(lambda: len(self.arrived) >= sequence, what=f"command {sequence} to arrive")

    def carry_a_late_command(self) -> None:
        """Command 1 moves slowly; command 2 waits behind it past the age, and is carried."""
        next(self.replies)  # the Ready
        self.send(1)
        assert self.entered.wait(10)
        self.send(2)
        self.clock.advance(0.06)
        self.release.set()
        assert _outcomes([next(self.replies).ack]) == [(1, "COMMAND_OUTCOME_APPLIED")]
        (session,) = self.station.core._sessions.values()
        wait_for(lambda: session._late, what="command 2 carried, late")

    def close(self) -> None:
        self.release.set()
        self.requests.put(pb.TeleoperateRequest(end=pb.TeleoperateEnd()))
        self.requests.put(None)
        for _ in self.replies:
            pass


def _outcomes(acks) -> list[tuple[int, str]]:
    return [(a.sequence, pb.CommandOutcome.Name(a.outcome)) for a in acks]


def test_over_the_wire_a_late_command_is_acked_merged_late_with_the_fresh_one(fake_station):
    """Command 2 arrives while command 1's move is slow and waits past the age; command 3
    comes fresh: 2 and 3 are one move, 2's ack MERGED_LATE, in order, and the Ready says the
    bound. A receipt for 3's ack then gives an offset estimate on the next ack."""
    wire = WireSession(fake_station, watchdog_s=1.0)
    slave, clock, send, replies = wire.slave, wire.clock, wire.send, wire.replies
    try:
        ready = next(replies).ready
        assert convert.seconds(ready.max_command_age) == pytest.approx(MAX_AGE_S)
        send(1)
        assert wire.entered.wait(10)
        send(2)
        clock.advance(0.06)  # 2 waits behind the slow move
        send(3)
        wire.release.set()
        acks = [next(replies).ack for _ in range(3)]
        assert _outcomes(acks) == [
            (1, "COMMAND_OUTCOME_APPLIED"), (2, "COMMAND_OUTCOME_MERGED_LATE"),
            (3, "COMMAND_OUTCOME_APPLIED")]
        assert not acks[2].HasField("clock_offset")  # no receipt yet
        moves = [c for c in slave.commands if c.kind == "cartesian"]
        assert len(moves) == 2
        np.testing.assert_allclose(moves[1].detail[1], 2 * UP, atol=1e-12)

        clock.advance(0.004)  # 3's ack reaches the master 4 ms after it was sent
        send(4, pb.AckReceipt(sequence=3, receive_time=convert.timestamp(clock.time_ns())))
        fourth = next(replies).ack
        # The master's clock here is the server's: the estimate is 0 within its bound.
        offset = fourth.clock_offset.ToNanoseconds()
        error = fourth.clock_offset_error.ToNanoseconds()
        assert fourth.HasField("clock_offset") and abs(offset) <= error <= 2_000_000
    finally:
        wire.close()


def test_over_the_wire_a_late_command_with_none_after_it_is_answered_when_the_arm_holds(
        fake_station):
    """A client that waits for each ack sends nothing after a late command: the watchdog's
    hold overtakes it, and its ack (REJECTED) comes then, not with a command that never
    comes."""
    wire = WireSession(fake_station, watchdog_s=0.1)
    try:
        wire.carry_a_late_command()
        wire.clock.advance(0.2)  # past the watchdog: it holds the arm
        late = next(wire.replies).ack
        assert _outcomes([late]) == [(2, "COMMAND_OUTCOME_REJECTED")]
        assert "held before a fresh command came" in late.detail
        assert len([c for c in wire.slave.commands if c.kind == "cartesian"]) == 1
    finally:
        wire.close()


def test_over_the_wire_the_operators_end_answers_the_carry(fake_station):
    """The operator ends the session while a late command is carried: no fresh command will
    come, so the carry is refused before the stream ends; every command sent is answered."""
    wire = WireSession(fake_station, watchdog_s=1.0)
    try:
        wire.carry_a_late_command()
        wire.requests.put(pb.TeleoperateRequest(end=pb.TeleoperateEnd()))
        wire.requests.put(None)
        rest = [reply.ack for reply in wire.replies]
        assert _outcomes(rest) == [(2, "COMMAND_OUTCOME_REJECTED")]
        assert "ended the session before a fresh command came" in rest[0].detail
        assert len([c for c in wire.slave.commands if c.kind == "cartesian"]) == 1
    finally:
        wire.release.set()
