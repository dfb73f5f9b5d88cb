"""The lane executor on its own, without gRPC: bounds, borrowing, dynamic threads, and the
Parma experiment (no priority inversion with the low lane saturated)."""

from __future__ import annotations

import threading
import time

import pytest

from services.runtime.lanes import (
    DEFAULT_LANES,
    ORDINARY_LANE_RT_PRIORITY,
    Lane,
    LaneConfig,
    LaneExecutor,
    LaneFull,
    scheduled_as,
)

SMALL = {
    Lane.EMERGENCY: LaneConfig(static_threads=1, max_threads=1, queue_capacity=4),
    Lane.HIGH: LaneConfig(static_threads=1, max_threads=2, queue_capacity=4),
    Lane.MEDIUM: LaneConfig(static_threads=1, max_threads=1, queue_capacity=4),
    Lane.LOW: LaneConfig(static_threads=1, max_threads=2, queue_capacity=3),
}


@pytest.fixture
def executor():
    pool = LaneExecutor(SMALL, name="test")
    yield pool
    pool.shutdown(wait=True, timeout_s=5)


def blocker(release: threading.Event, started: threading.Semaphore | None = None):
    def run():
        if started:
            started.release()
        release.wait(10)
        return threading.current_thread().name
    return run


def test_runs_work_and_counts_it(executor):
    results = [executor.submit(Lane.MEDIUM, lambda i=i: i * i).result(5) for i in range(10)]
    assert results == [i * i for i in range(10)]
    counters = executor.counters()[Lane.MEDIUM]
    assert counters.served == 10 and counters.queued == 0 and counters.running == 0


def test_full_lane_rejects_and_counts(executor):
    release = threading.Event()
    started = threading.Semaphore(0)
    running = [executor.submit(Lane.LOW, blocker(release, started)) for _ in range(2)]
    for _ in range(2):
        assert started.acquire(timeout=5)
    queued = [executor.submit(Lane.LOW, lambda: "queued") for _ in range(3)]
    with pytest.raises(LaneFull, match="low lane is saturated"):
        executor.submit(Lane.LOW, lambda: "one too many")
    counters = executor.counters()[Lane.LOW]
    assert (counters.running, counters.queued, counters.rejected) == (2, 3, 1)
    release.set()
    assert [f.result(5) for f in queued] == ["queued"] * 3
    for f in running:
        f.result(5)


def test_dynamic_threads_grow_to_the_cap_and_no_further(executor):
    release = threading.Event()
    started = threading.Semaphore(0)
    futures = [executor.submit(Lane.HIGH, blocker(release, started)) for _ in range(2)]
    for _ in range(2):
        assert started.acquire(timeout=5)
    # HIGH is at its cap of 2 threads; EMERGENCY never lends to it, but the lower lanes
    # (MEDIUM, LOW) each have one idle static thread to lend.
    more = [executor.submit(Lane.HIGH, blocker(release, started)) for _ in range(2)]
    for _ in range(2):
        assert started.acquire(timeout=5)
    counters = executor.counters()
    assert counters[Lane.HIGH].threads == 2
    assert counters[Lane.HIGH].running == 4
    assert counters[Lane.HIGH].borrowed == 2
    release.set()
    names = {f.result(5) for f in futures + more}
    assert any("-medium-" in n for n in names) and any("-low-" in n for n in names)


def test_lower_lane_never_borrows_from_higher(executor):
    release = threading.Event()
    started = threading.Semaphore(0)
    low = [executor.submit(Lane.LOW, blocker(release, started)) for _ in range(2)]
    for _ in range(2):
        assert started.acquire(timeout=5)
    # Emergency, high and medium threads are idle, yet the next low call must wait.
    began = threading.Event()
    waiting = executor.submit(Lane.LOW,
                              lambda: (began.set(), threading.current_thread().name)[1])
    assert not began.wait(0.2)  # still not started 0.2 s on
    release.set()
    assert "-low-" in waiting.result(5)
    for f in low:
        f.result(5)


def test_parma_no_priority_inversion_with_low_lane_saturated(executor):
    """Parma's experiment: long low-priority calls fill the low lane (threads and queue);
    a high-priority call and an emergency call still start at once."""
    release = threading.Event()
    started = threading.Semaphore(0)
    low = [executor.submit(Lane.LOW, blocker(release, started)) for _ in range(2)]
    for _ in range(2):
        assert started.acquire(timeout=5)
    low += [executor.submit(Lane.LOW, blocker(release)) for _ in range(3)]  # queue full
    with pytest.raises(LaneFull):
        executor.submit(Lane.LOW, blocker(release))

    for lane in (Lane.HIGH, Lane.EMERGENCY):
        submitted = time.monotonic()
        started_at = executor.submit(lane, time.monotonic).result(timeout=2)
        # "At once": it did not wait for any low call (those wait for `release`, seconds away).
        assert started_at - submitted < 0.5
        assert not any(f.done() for f in low)
    release.set()
    for f in low:
        f.result(5)


def test_cancelled_work_is_skipped(executor):
    release = threading.Event()
    started = threading.Semaphore(0)
    busy = [executor.submit(Lane.LOW, blocker(release, started)) for _ in range(2)]
    for _ in range(2):
        assert started.acquire(timeout=5)
    ran = threading.Event()
    queued = executor.submit(Lane.LOW, ran.set)
    assert queued.cancel()
    release.set()
    for f in busy:
        f.result(5)
    executor.submit(Lane.LOW, lambda: None).result(5)
    assert not ran.is_set()


def test_shutdown_cancels_queued_work():
    pool = LaneExecutor(SMALL, name="test")
    release = threading.Event()
    started = threading.Semaphore(0)
    busy = [pool.submit(Lane.MEDIUM, blocker(release, started))]
    assert started.acquire(timeout=5)
    # MEDIUM's only thread is busy; LOW's idle thread lends itself, so fill it too before
    # the next call has to queue.
    busy.append(pool.submit(Lane.MEDIUM, blocker(release, started)))
    assert started.acquire(timeout=5)
    queued = pool.submit(Lane.MEDIUM, lambda: "never")
    threading.Timer(0.2, release.set).start()
    pool.shutdown(wait=True, timeout_s=5)
    assert queued.cancelled()
    assert all(f.result(1) for f in busy)


def test_bad_lane_names_are_refused():
    assert Lane.parse(" High ") is Lane.HIGH
    with pytest.raises(ValueError, match="use one of emergency, high, medium, low"):
        Lane.parse("urgent")


# -- run_here: on the caller's thread when the lane has room -------------------------------------

def test_run_here_runs_on_the_calling_thread_as_lane_work(executor):
    from services.runtime.lanes import current_lane

    here = threading.current_thread().name
    future = executor.run_here(Lane.HIGH, lambda: (threading.current_thread().name,
                                                   current_lane()))
    assert future.done() and future.result() == (here, Lane.HIGH)
    assert current_lane() is None  # the caller's thread is itself again
    counters = executor.counters()[Lane.HIGH]
    assert counters.inline == 1 and counters.served == 1 and counters.running == 0


def test_run_here_never_jumps_queued_work_of_its_lane_or_higher(executor):
    release = threading.Event()
    started = threading.Semaphore(0)
    # HIGH: one thread and one free slot (max 2). Fill both, then queue one more.
    busy = executor.submit(Lane.HIGH, blocker(release, started))
    assert started.acquire(timeout=5)
    inline_started = threading.Semaphore(0)
    caller = threading.Thread(target=lambda: executor.run_here(
        Lane.HIGH, blocker(release, inline_started)))
    caller.start()
    assert inline_started.acquire(timeout=5)  # ran on the caller's thread: the free slot
    queued = executor.submit(Lane.HIGH, lambda: "first in line")
    assert executor.counters()[Lane.HIGH].queued == 1
    later = executor.run_here(Lane.HIGH, lambda: "after it")  # no room: it queues behind
    assert not later.done()
    release.set()
    assert queued.result(5) == "first in line" and later.result(5) == "after it"
    caller.join(5)
    busy.result(5)


def test_run_here_keeps_the_lane_within_max_threads(executor):
    """HIGH has max 2: with a call running here and one on the lane's own thread, a third gets
    no new HIGH thread; it runs on an idle lower lane's thread (borrowing), as before. Which of
    the two submitted calls borrows is not fixed: HIGH's static thread may not be waiting yet
    when the first comes, and an idle lower thread then takes it."""
    release = threading.Event()
    running = threading.Semaphore(0)
    inline = threading.Thread(target=lambda: executor.run_here(Lane.HIGH,
                                                                blocker(release, running)))
    inline.start()
    assert running.acquire(timeout=5)
    on_thread = executor.submit(Lane.HIGH, blocker(release, running))
    assert running.acquire(timeout=5)
    third = executor.submit(Lane.HIGH, blocker(release, running))
    assert running.acquire(timeout=5)
    counters = executor.counters()[Lane.HIGH]
    assert counters.threads == 1 and counters.borrowed == 1
    release.set()
    lanes = sorted(name.split("-")[1] for name in (on_thread.result(5), third.result(5)))
    assert lanes in (["high", "medium"], ["high", "low"])
    inline.join(5)


class FakeScheduler:
    """The os module's scheduling calls, for one thread: its policy and priority."""

    SCHED_OTHER, SCHED_FIFO, SCHED_RR, SCHED_RESET_ON_FORK = 0, 1, 2, 0x40000000

    def __init__(self, policy: int, priority: int = 0):
        self.policy, self.priority = policy, priority
        self.refuse_real_time = False

    @staticmethod
    def sched_param(priority: int) -> int:
        return priority

    def sched_getscheduler(self, _pid: int) -> int:
        return self.policy

    def sched_getparam(self, _pid: int) -> int:
        return self.priority

    def sched_setscheduler(self, _pid: int, policy: int, priority: int) -> None:
        if self.refuse_real_time and priority > self.priority:
            raise PermissionError(1, "Operation not permitted")
        self.policy, self.priority = policy, priority


def test_ordinary_lane_work_runs_at_the_lowest_real_time_priority_then_goes_back():
    fifo = FakeScheduler.SCHED_FIFO | FakeScheduler.SCHED_RESET_ON_FORK
    system = FakeScheduler(fifo, 5)
    low = LaneConfig(static_threads=1, max_threads=1, queue_capacity=1, nice=2)
    with scheduled_as(low, system):
        assert (system.policy, system.priority) == (fifo, ORDINARY_LANE_RT_PRIORITY)
    assert (system.policy, system.priority) == (fifo, 5)


def test_real_time_lane_work_and_ordinary_threads_keep_their_scheduling():
    high = LaneConfig(static_threads=1, max_threads=1, queue_capacity=1, realtime=True)
    low = LaneConfig(static_threads=1, max_threads=1, queue_capacity=1, nice=2)
    real_time = FakeScheduler(FakeScheduler.SCHED_FIFO, 5)
    with scheduled_as(high, real_time):
        assert (real_time.policy, real_time.priority) == (FakeScheduler.SCHED_FIFO, 5)
    ordinary = FakeScheduler(FakeScheduler.SCHED_OTHER)
    with scheduled_as(low, ordinary):
        assert (ordinary.policy, ordinary.priority) == (FakeScheduler.SCHED_OTHER, 0)


def test_a_thread_refused_its_priority_back_goes_on_at_the_lower_one(caplog):
    system = FakeScheduler(FakeScheduler.SCHED_FIFO, 5)
    low = LaneConfig(static_threads=1, max_threads=1, queue_capacity=1)
    with scheduled_as(low, system):
        system.refuse_real_time = True  # the privilege went away meanwhile
    assert (system.policy, system.priority) == (FakeScheduler.SCHED_FIFO,
                                                ORDINARY_LANE_RT_PRIORITY)
    assert "could not take its real-time priority back" in caplog.text


def test_the_default_lanes_that_keep_real_time_are_the_emergency_and_high_ones():
    assert [lane for lane, config in DEFAULT_LANES.items() if config.realtime] == [
        Lane.EMERGENCY, Lane.HIGH]
