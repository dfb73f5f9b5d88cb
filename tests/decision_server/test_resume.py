"""Teleoperate sessions that outlive their stream (#14), in the core: a broken stream holds the
arm and leaves the session to be resumed; sequence numbers make a resend harmless. A fake slave
counts the moves and a fake clock runs the resume window; nothing sleeps."""

from __future__ import annotations

import threading

import numpy as np
import pytest

from services.decision_server.arbitration import ControlMode
from services.decision_server.sessions import (
    RESULTS_KEPT,
    MasterIncrement,
    SessionChanged,
)
from tests.conftest import wait_for
from wire.errors import AbortedError, NotFoundError, PermissionDeniedError

UP = np.array([0.0, 0.0, 0.001])


def commands(rig, *sequences: int, clutch=()) -> list[MasterIncrement]:
    return [MasterIncrement(UP, np.eye(3), s in clutch, rig.clock.time_ns(), s)
            for s in sequences]


def moves(rig) -> int:
    return sum(c.kind == "cartesian" for c in rig.slave.commands)


def holds(rig) -> int:
    return sum(c.kind == "hold" for c in rig.slave.commands)


def session_events(subscription) -> list[SessionChanged]:
    seen = []
    while (event := subscription.get(0)) is not None:
        if isinstance(event.payload, SessionChanged):
            seen.append(event.payload)
    return seen


@pytest.fixture
def session(rig):
    session = rig.core.open_session("alice", rig.lease.lease_id, None, 1.0)
    yield session
    session.close("the test ended")


def test_a_resent_command_gets_its_first_result_and_moves_nothing(rig, session):
    first = session.commands(commands(rig, 1, 2, 3))
    assert moves(rig) == 1  # one merged move
    again = session.commands(commands(rig, 2, 3, 4))
    assert again[:2] == first[1:]  # the same results, receive and apply times included
    assert again[2].outcome == "APPLIED"
    assert moves(rig) == 2  # only command 4 moved the arm
    counts = session.counts()
    assert (counts.processed, counts.applied, counts.resends, counts.last_sequence) == (4, 4, 2, 4)


def test_a_resend_within_one_batch_is_answered_too(rig, session):
    results = session.commands(commands(rig, 1, 2, 2))
    assert results[2] == results[1]
    assert session.counts().processed == 2


@pytest.mark.e2e
def test_a_resend_older_than_the_kept_results_is_a_duplicate(rig, session):
    session.commands(commands(rig, *range(1, RESULTS_KEPT + 2)))
    (late,) = session.commands(commands(rig, 1))
    assert late.outcome == "DUPLICATE" and "no longer kept" in late.detail


def test_sequence_zero_is_never_taken_for_a_resend(rig, session):
    session.commands(commands(rig, 0, 0))
    session.commands(commands(rig, 0))
    assert session.counts().processed == 3 and session.counts().resends == 0


def test_a_broken_stream_holds_the_arm_and_the_same_lease_resumes_the_session(rig, session):
    events = rig.core.events.subscribe(64)
    session.commands(commands(rig, 1, 2))
    session.end(session.stream, "the stream broke", resumable=True)
    assert session.detached and holds(rig) == 1
    resumed, stream = rig.core.resume_session(session.session_id, rig.lease.lease_id)
    assert resumed is session and stream == 2 and not session.detached
    assert [r.outcome for r in session.commands(commands(rig, 2, 3), stream)] == ["APPLIED"] * 2
    assert [(e.state, e.counts.processed) for e in session_events(events)] == [
        ("DETACHED", 2), ("RESUMED", 2)]
    assert session.counts().processed == 3


def test_a_resume_supersedes_a_stream_whose_break_went_unnoticed(rig, session):
    old = session.stream
    _, new = rig.core.resume_session(session.session_id, rig.lease.lease_id)
    with pytest.raises(AbortedError) as refused:
        session.commands(commands(rig, 1), old)
    assert refused.value.reason == "SUPERSEDED"
    session.end(old, "the old stream broke at last", resumable=True)  # changes nothing now
    assert not session.detached and holds(rig) == 0
    session.commands(commands(rig, 1), new)
    assert moves(rig) == 1


def test_only_the_sessions_lease_may_resume_it(rig, session):
    session.end(session.stream, "the stream broke", resumable=True)
    with pytest.raises(NotFoundError):
        rig.core.resume_session("nosuchsession", rig.lease.lease_id)
    with pytest.raises(PermissionDeniedError):
        rig.core.resume_session(session.session_id, "someone-elses-lease")


def test_a_session_not_resumed_within_its_window_ends(rig, session):
    events = rig.core.events.subscribe(64)
    armed = rig.clock.waiters()
    session.end(session.stream, "the stream broke", resumable=True)
    wait_for(lambda: rig.clock.waiters() >= armed, what="the watchdog to wait for the window")
    rig.clock.advance(session.resume_window_s - 0.01)
    assert not session.closed
    rig.clock.advance(0.02)
    wait_for(lambda: session.closed, what="the session to end")
    with pytest.raises(NotFoundError):
        rig.core.resume_session(session.session_id, rig.lease.lease_id)
    assert [e.state for e in session_events(events)] == ["DETACHED", "CLOSED"]
    assert holds(rig) == 1  # held once, when the stream broke


def test_the_operators_own_close_ends_the_session_for_good(rig, session):
    session.end(session.stream, "the stream ended", resumable=False)
    assert session.closed
    with pytest.raises(NotFoundError):
        rig.core.resume_session(session.session_id, rig.lease.lease_id)


def test_a_detached_session_ends_with_its_lease(rig, session):
    session.end(session.stream, "the stream broke", resumable=True)
    rig.core.locks.release(rig.lease.lease_id)
    assert session.closed


def test_a_lapsed_lease_ends_its_detached_session(rig):
    rig.core.locks.release(rig.lease.lease_id)
    lease = rig.core.locks.acquire("bob", ControlMode.EXCLUSIVE, lease_s=0.5)
    session = rig.core.open_session("bob", lease.lease_id, None, 1.0)
    session.end(session.stream, "the stream broke", resumable=True)
    rig.clock.advance(0.6)  # the lease reaper, on the same clock, sees it lapse
    wait_for(lambda: session.closed, what="the session to end with its lease")
    with pytest.raises(NotFoundError):
        rig.core.resume_session(session.session_id, lease.lease_id)


def test_a_break_mid_batch_keeps_what_moved_and_leaves_the_rest_unreceived(rig, session):
    """The stream breaks while a batch is moving the arm: the move in flight lands before the
    hold; the batch's later moves do not happen, and they count as never received, so their
    resend after the resume moves the arm (once), and the landed one's resend does not."""
    entered, release = threading.Event(), threading.Event()
    move = rig.slave.move_cartesian

    def slow_move(*args):
        entered.set()
        release.wait(5)
        return move(*args)

    rig.slave.move_cartesian = slow_move
    stream = session.stream
    outcome: list[BaseException] = []

    def serve():  # 1 moves, 2 is a clutch (nothing to move), 3 would move: three groups
        try:
            session.commands(commands(rig, 1, 2, 3, clutch=(2,)), stream)
        except AbortedError as error:
            outcome.append(error)

    server = threading.Thread(target=serve)
    server.start()
    assert entered.wait(5)
    breaker = threading.Thread(target=session.end, args=(stream, "the stream broke", True))
    breaker.start()
    wait_for(lambda: session.detached, what="the session to detach")
    release.set()
    server.join(5), breaker.join(5)
    rig.slave.move_cartesian = move
    assert outcome and outcome[0].reason == "STREAM_BROKEN"
    assert [c.kind for c in rig.slave.commands] == ["cartesian", "hold"]
    assert session.counts().processed == 2  # 1 and 2; 3 was never received
    _, stream = rig.core.resume_session(session.session_id, rig.lease.lease_id)
    results = session.commands(commands(rig, 1, 2, 3, clutch=(2,)), stream)
    assert [r.outcome for r in results] == ["APPLIED", "INDEXED", "APPLIED"]
    assert moves(rig) == 2 and session.counts().resends == 2
