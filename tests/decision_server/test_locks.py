"""The LockManager on a FakeClock: exclusive and collaborative control, the FIFO queue, wait
deadlines and lease expiry, with every time step taken by the test (clock.advance). Threads
that block in acquire(wait=True) are ordered by what the manager shows (its view) and by the
clock's count of blocked threads, never by sleeping."""

from __future__ import annotations

import threading

import pytest

from services.decision_server.arbitration import (
    DEFAULT_LEASE_S,
    MAX_WAITERS,
    ControlMode,
    ControlView,
    LockManager,
)
from tests.conftest import wait_for
from tests.fakes.clock import FakeClock
from wire.errors import (
    AbortedError,
    DeadlineExceededError,
    FailedPreconditionError,
    NotFoundError,
    PermissionDeniedError,
    ResourceExhaustedError,
    RpcCancelledError,
    TelerobotError,
)

EXCLUSIVE, COLLABORATIVE = ControlMode.EXCLUSIVE, ControlMode.COLLABORATIVE
TICK_S = 2.0 ** -20  # exact on the float grid near 1000 s: t0 + 5 - TICK + TICK == t0 + 5
HANG_GUARD_S = 10.0  # how long a test waits for a thread before failing; bounds no timing


@pytest.fixture
def clock() -> FakeClock:
    return FakeClock()


@pytest.fixture
def changes() -> list[tuple[ControlView, str]]:
    """Every (view, reason) the manager's on_change was told, in order."""
    return []


@pytest.fixture
def locks(clock, changes):
    manager = LockManager(lambda view, reason: changes.append((view, reason)), clock=clock)
    yield manager
    manager.close()


class Acquirer:
    """acquire(..., wait=True) on a thread of its own."""

    def __init__(self, locks: LockManager, operator_id: str, mode: ControlMode = EXCLUSIVE,
                 group: str = "", **options):
        self.outcome = None
        self._thread = threading.Thread(
            target=self._run, args=(locks, operator_id, mode, group, options), daemon=True,
            name=f"acquire-{operator_id}")
        self._thread.start()

    def _run(self, locks, operator_id, mode, group, options) -> None:
        try:
            self.outcome = locks.acquire(operator_id, mode, group, wait=True, **options)
        except TelerobotError as error:
            self.outcome = error

    def result(self):
        """The lease it got or the error it raised, once acquire has returned."""
        self._thread.join(HANG_GUARD_S)
        assert not self._thread.is_alive(), "acquire(wait=True) is still blocked"
        return self.outcome


def holders(locks: LockManager) -> list[str]:
    return [lease.operator_id for lease in locks.view().holders]


def queued(locks: LockManager) -> list[str]:
    return [operator for operator, *_ in locks.view().waiters]


def wait_until_queued(locks: LockManager, names: list[str]) -> None:
    wait_for(lambda: queued(locks) == names, HANG_GUARD_S, f"{names} queued")


def wait_until_blocked(clock: FakeClock, acquirers: int) -> None:
    """Until the lease reaper and `acquirers` waiting acquires are all blocked in clock.wait,
    their deadlines taken: then clock.advance past a deadline is sure to wake its thread."""
    wait_for(lambda: clock.waiters() == 1 + acquirers, HANG_GUARD_S,
             f"the reaper and {acquirers} acquire(s) blocked on the clock")


def told(changes: list[tuple[ControlView, str]], reason: str) -> ControlView:
    """The view on_change was given with `reason` (waiting for it: the reaper may tell it)."""
    return wait_for(lambda: next((view for view, said in changes if said == reason), None),
                    HANG_GUARD_S, f"on_change told {reason!r}")


def test_two_operators_racing_have_exactly_one_winner(locks):
    start = threading.Barrier(8)
    winners, losers = [], []

    def race(name):
        start.wait(HANG_GUARD_S)
        try:
            winners.append(locks.acquire(name, EXCLUSIVE))
        except AbortedError as error:
            losers.append(error.message)

    threads = [threading.Thread(target=race, args=(f"op{i}",)) for i in range(8)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join(HANG_GUARD_S)
    assert len(winners) == 1 and len(losers) == 7
    assert all(f"'{winners[0].operator_id}' (EXCLUSIVE)" in message for message in losers)


def test_collaborative_control_is_shared_by_one_group(locks):
    a = locks.acquire("ann", COLLABORATIVE, "surgery")
    b = locks.acquire("bob", COLLABORATIVE, "surgery", group_secret=a.group_secret)
    assert set(holders(locks)) == {"ann", "bob"}
    with pytest.raises(AbortedError, match="COLLABORATIVE, group 'surgery'"):
        locks.acquire("cat", COLLABORATIVE, "other-group")
    with pytest.raises(AbortedError):
        locks.acquire("dan", EXCLUSIVE)
    assert locks.require(a.lease_id) and locks.require(b.lease_id)


def test_waiters_are_served_in_order(locks, changes):
    first = locks.acquire("first", COLLABORATIVE, "g")
    second = Acquirer(locks, "second")
    wait_until_queued(locks, ["second"])
    third = Acquirer(locks, "third")
    wait_until_queued(locks, ["second", "third"])
    # A newcomer may not overtake the queue, even one the group would admit.
    with pytest.raises(AbortedError, match="'first' \\(COLLABORATIVE, group 'g'\\)"):
        locks.acquire("newcomer", COLLABORATIVE, "g", group_secret=first.group_secret)

    locks.release(first.lease_id)
    assert second.result().operator_id == "second"
    assert holders(locks) == ["second"] and queued(locks) == ["third"]
    assert [lease.operator_id for lease in told(changes, "first released control").holders] \
        == ["second"]

    locks.release(second.result().lease_id)
    assert third.result().operator_id == "third"
    assert holders(locks) == ["third"] and queued(locks) == []


def test_a_wait_times_out_at_its_deadline(locks, clock, changes):
    locks.acquire("holder", EXCLUSIVE, lease_s=60)
    asked_at = clock.monotonic()
    waiter = Acquirer(locks, "waiter", wait_timeout_s=2.0)
    wait_until_queued(locks, ["waiter"])
    assert locks.view().waiters[0][3] == asked_at + 2.0  # the deadline, on the clock's scale
    wait_until_blocked(clock, 1)

    clock.advance(2.0 + TICK_S)
    error = waiter.result()
    assert isinstance(error, DeadlineExceededError) and "'holder'" in error.message
    assert queued(locks) == [] and holders(locks) == ["holder"]
    assert told(changes, "waiter gave up waiting").waiters == ()


def test_a_silent_holders_lease_expires_and_the_next_waiter_gets_control(locks, clock,
                                                                         changes):
    """Nobody calls after the deadline passes: the reaper notices and promotes the waiter."""
    locks.acquire("sleepy", EXCLUSIVE, lease_s=0.2)
    waiter = Acquirer(locks, "next", wait_timeout_s=2.0)
    wait_until_queued(locks, ["next"])
    wait_until_blocked(clock, 1)

    clock.advance(0.2 + TICK_S)
    lease = waiter.result()
    assert lease.operator_id == "next"
    assert lease.expires_at == clock.monotonic() + DEFAULT_LEASE_S  # granted now
    assert [h.operator_id for h in told(changes, "sleepy's lease expired").holders] == ["next"]


def test_a_lease_expires_just_after_its_deadline_not_before(locks, clock, changes):
    sleepy = locks.acquire("sleepy", EXCLUSIVE, lease_s=5.0)
    assert sleepy.expires_at == clock.monotonic() + 5.0
    waiter = Acquirer(locks, "next", wait_timeout_s=60)
    wait_until_queued(locks, ["next"])

    clock.advance(5.0 - TICK_S)
    assert holders(locks) == ["sleepy"] and queued(locks) == ["next"]
    clock.advance(TICK_S)  # exactly at the deadline: still valid
    assert clock.monotonic() == sleepy.expires_at
    assert holders(locks) == ["sleepy"] and queued(locks) == ["next"]
    assert not [reason for _, reason in changes if "expired" in reason]

    clock.advance(TICK_S)
    view = locks.view()
    assert [h.operator_id for h in view.holders] == ["next"] and view.waiters == ()
    assert waiter.result().lease_id == view.holders[0].lease_id
    assert [h.operator_id for h in told(changes, "sleepy's lease expired").holders] == ["next"]
    with pytest.raises(FailedPreconditionError, match="held by 'next'"):
        locks.require(sleepy.lease_id)


def test_use_renews_the_lease(locks, clock):
    lease = locks.acquire("busy", EXCLUSIVE, lease_s=1.0)
    for _ in range(6):
        clock.advance(0.75)
        assert locks.require(lease.lease_id).expires_at == clock.monotonic() + 1.0
    assert holders(locks) == ["busy"]  # 4.5 s on a 1 s lease
    clock.advance(1.0 + TICK_S)  # silent for longer than one lease
    with pytest.raises(FailedPreconditionError, match="needs the control lock: send the lease id"):
        locks.require(lease.lease_id)
    assert holders(locks) == []


def test_renew_moves_the_deadline(locks, clock, changes):
    lease = locks.acquire("op", EXCLUSIVE, lease_s=2.0)
    first_deadline = lease.expires_at
    clock.advance(1.5)
    assert locks.renew(lease.lease_id).expires_at == first_deadline + 1.5

    clock.advance(2.0)  # past the first deadline, exactly at the new one
    assert clock.monotonic() > first_deadline and holders(locks) == ["op"]
    clock.advance(TICK_S)
    assert holders(locks) == []
    told(changes, "op's lease expired")
    with pytest.raises(NotFoundError, match="acquire control again"):
        locks.renew(lease.lease_id)


def test_require_without_a_lease_explains(locks):
    with pytest.raises(FailedPreconditionError, match="telerobot-lease-id"):
        locks.require(None)


def test_on_change_is_told_with_the_lock_released(clock):
    """The callback may call back in (DecisionCore's takes its own locks): it must not
    deadlock, and it sees the state after the change."""
    seen = []
    manager = LockManager(lambda view, reason: seen.append((reason, manager.describe_holders())),
                          clock=clock)
    worker = threading.Thread(
        target=lambda: manager.release(manager.acquire("ann", EXCLUSIVE).lease_id), daemon=True)
    worker.start()
    worker.join(HANG_GUARD_S)
    manager.close()
    assert not worker.is_alive(), "on_change deadlocked calling back into the LockManager"
    assert seen == [("ann acquired EXCLUSIVE control", "'ann' (EXCLUSIVE)"),
                    ("ann released control", "nobody")]


class CallerGone:
    """Stands in for gRPC's context.add_callback: `leave()` runs what was registered, as the
    server does when the caller cancels or its connection drops."""

    def __init__(self):
        self.callbacks = []

    def __call__(self, callback) -> bool:
        self.callbacks.append(callback)
        return True

    def leave(self) -> None:
        for callback in self.callbacks:
            callback()


def test_a_waiter_that_goes_away_leaves_the_queue_at_once(locks, changes):
    holder = locks.acquire("holder", EXCLUSIVE)
    gone = CallerGone()
    waiter = Acquirer(locks, "waiter", on_caller_gone=gone)
    wait_until_queued(locks, ["waiter"])
    gone.leave()  # long before its wait (an hour by default) would end
    error = waiter.result()
    assert isinstance(error, RpcCancelledError) and error.reason == "CALLER_GONE"
    assert queued(locks) == [] and holders(locks) == ["holder"]
    locks.release(holder.lease_id)
    assert holders(locks) == []  # nobody was promoted for the caller that left


def test_each_operator_waits_once_and_the_queue_is_bounded(locks):
    locks.acquire("holder", EXCLUSIVE)
    gone = CallerGone()  # every waiter leaves at the end: none polls the clock after the test
    waiting = [Acquirer(locks, "ann", on_caller_gone=gone)]
    wait_until_queued(locks, ["ann"])
    with pytest.raises(AbortedError, match="already waits"):
        locks.acquire("ann", EXCLUSIVE, wait=True)
    for index in range(1, MAX_WAITERS):
        waiting.append(Acquirer(locks, f"op{index}", on_caller_gone=gone))
        wait_until_queued(locks, ["ann", *(f"op{i}" for i in range(1, index + 1))])
    with pytest.raises(ResourceExhaustedError, match="already wait for control"):
        locks.acquire("latecomer", EXCLUSIVE, wait=True)
    gone.leave()
    assert all(isinstance(w.result(), RpcCancelledError) for w in waiting)
    assert queued(locks) == []


def test_joining_a_group_takes_the_secret_its_first_holder_got(locks, changes):
    """Issue #31: anyone could join a collaborative lease by naming its group."""
    ann = locks.acquire("ann", COLLABORATIVE, "surgery")  # the first holder needs nothing
    assert len(ann.group_secret) >= 32
    gone = CallerGone()  # (a waiter queued by mistake leaves at the end)
    for presented in ("", "guess", ann.group_secret[:-1], ann.group_secret + "x"):
        with pytest.raises(PermissionDeniedError, match="group 'surgery' holds control") \
                as refused:
            locks.acquire("mallory", COLLABORATIVE, "surgery", group_secret=presented)
        assert refused.value.reason == "BAD_GROUP_SECRET"
        waiting = Acquirer(locks, "mallory", COLLABORATIVE, "surgery", group_secret=presented,
                           on_caller_gone=gone)  # wait=True: refused at once too, not queued
        try:
            assert isinstance(waiting.result(), PermissionDeniedError)
        finally:
            gone.leave()
    assert holders(locks) == ["ann"] and queued(locks) == []
    bob = locks.acquire("bob", COLLABORATIVE, "surgery", group_secret=ann.group_secret)
    assert bob.group_secret == ann.group_secret and holders(locks) == ["ann", "bob"]
    assert ann.group_secret not in repr(locks.view())  # nor in what on_change is told
    assert not any(ann.group_secret in repr(view) for view, _ in changes)

    locks.release(ann.lease_id)
    locks.release(bob.lease_id)  # the group ends with its last member, and its secret
    cat = locks.acquire("cat", COLLABORATIVE, "surgery", group_secret="whatever")
    assert cat.group_secret not in ("", ann.group_secret)
    with pytest.raises(PermissionDeniedError):
        locks.acquire("ann", COLLABORATIVE, "surgery", group_secret=ann.group_secret)


def test_a_waiter_the_group_does_not_admit_is_refused_when_its_turn_comes(locks):
    """Two queued for group g behind an exclusive holder: the first starts the group; the
    second would join it without its new secret, so it leaves the queue refused, and the
    waiter behind it moves up."""
    holder = locks.acquire("holder", EXCLUSIVE)
    first = Acquirer(locks, "first", COLLABORATIVE, "g")
    wait_until_queued(locks, ["first"])
    second = Acquirer(locks, "second", COLLABORATIVE, "g", group_secret="an old one")
    wait_until_queued(locks, ["first", "second"])
    third = Acquirer(locks, "third", EXCLUSIVE)
    wait_until_queued(locks, ["first", "second", "third"])

    locks.release(holder.lease_id)
    assert first.result().operator_id == "first" and first.result().group_secret
    refused = second.result()
    assert isinstance(refused, PermissionDeniedError)
    assert refused.reason == "BAD_GROUP_SECRET"
    assert holders(locks) == ["first"] and queued(locks) == ["third"]
    locks.release(first.result().lease_id)
    assert third.result().operator_id == "third"
