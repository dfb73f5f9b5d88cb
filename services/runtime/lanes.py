"""Priority lanes for request handling, after RT-CORBA thread-pool lanes (the Parma paper).

Each lane has its own bounded queue, `static_threads` threads that live as long as the pool,
and dynamic threads up to `max_threads` that retire when idle. An idle thread of a lower lane
may run work of a higher lane (borrowing); a higher lane's threads never run lower work, so a
saturated low lane cannot delay high-priority calls. Nothing here knows about gRPC; an RPC's
lane comes from its proto's `default_lane` option (`declared_lane`).

Thread priorities are set with per-thread nice values where the OS allows, each lane's an
offset from the process's own (the camera's process runs niced as a whole). In a real-time
process the medium and low lanes' work runs at the lowest real-time priority
(`scheduled_as`), so the GIL goes to the command path's threads first. The isolation that
matters most is structural: a high lane never waits behind a low queue.
"""

from __future__ import annotations

import contextlib
import enum
import functools
import logging
import os
import threading
import time
from collections import deque
from collections.abc import Callable, Iterator
from concurrent.futures import Future
from dataclasses import dataclass
from typing import Any

from telerobot.v1 import options_pb2
from wire.options import method_options

log = logging.getLogger(__name__)

# A dynamic thread with nothing to do for this long retires.
DYNAMIC_IDLE_TIMEOUT_S = 5.0


class Lane(enum.IntEnum):
    """Lanes, highest priority first (a smaller value is more urgent)."""

    EMERGENCY = 0
    HIGH = 1
    MEDIUM = 2
    LOW = 3

    @classmethod
    def parse(cls, text: str) -> Lane:
        """Lane from its name, any case ("high"); ValueError names the valid ones."""
        try:
            return cls[text.strip().upper()]
        except KeyError:
            names = ", ".join(lane.name.lower() for lane in cls)
            raise ValueError(f"unknown lane {text!r}; use one of {names}") from None


@dataclass(frozen=True)
class LaneConfig:
    """Sizing of one lane."""

    static_threads: int
    max_threads: int
    queue_capacity: int
    nice: int = 0
    # In a real-time process (services/runtime/priority.py), whether this lane's work keeps
    # the process's real-time priority. Work of a lane that does not runs at the lowest one
    # (ORDINARY_LANE_RT_PRIORITY), so it never keeps the command path's threads from a core,
    # nor from the GIL: Linux wakes a contended lock's waiters in priority order. (Not at
    # SCHED_OTHER: a GIL holder there waits behind every ordinary process for a core, and the
    # command path waits behind it for the GIL.)
    realtime: bool = False

    def __post_init__(self) -> None:
        if self.static_threads < 0 or self.max_threads < max(1, self.static_threads):
            raise ValueError("need 0 <= static_threads <= max_threads and max_threads >= 1")
        if self.queue_capacity < 0:
            raise ValueError("queue_capacity must be >= 0")


# The real-time priority the work of lanes that are not real-time runs at, in a real-time
# process: the lowest there is.
ORDINARY_LANE_RT_PRIORITY = 1

DEFAULT_LANES: dict[Lane, LaneConfig] = {
    Lane.EMERGENCY: LaneConfig(static_threads=1, max_threads=2, queue_capacity=16, nice=-5,
                               realtime=True),
    Lane.HIGH: LaneConfig(static_threads=2, max_threads=8, queue_capacity=64, nice=-2,
                          realtime=True),
    Lane.MEDIUM: LaneConfig(static_threads=1, max_threads=4, queue_capacity=64, nice=0),
    Lane.LOW: LaneConfig(static_threads=1, max_threads=4, queue_capacity=256, nice=2),
}


def capacity(lanes: dict[Lane, LaneConfig] | None = None) -> int:
    """How many calls the lanes hold at once, running and queued (DEFAULT_LANES when None):
    each holds a gRPC thread while it waits for its answer."""
    configs = DEFAULT_LANES if lanes is None else lanes
    return sum(config.max_threads + config.queue_capacity for config in configs.values())


_current = threading.local()


def current_lane() -> Lane | None:
    """The lane of the task this thread is running, None outside a lane executor."""
    return getattr(_current, "lane", None)


class LaneFull(Exception):
    """Raised by submit when the lane's queue is at capacity."""

    def __init__(self, lane: Lane, capacity: int):
        super().__init__(
            f"the {lane.name.lower()} lane is saturated ({capacity} calls waiting); "
            "retry after a short back-off"
        )
        self.lane = lane


class LaneExecutorClosed(Exception):
    """Raised by submit after shutdown began."""


@dataclass
class LaneCounters:
    """Live counters of one lane. `borrowed` counts its tasks run by lower lanes' threads."""

    queued: int = 0
    running: int = 0
    served: int = 0
    rejected: int = 0
    borrowed: int = 0
    threads: int = 0
    inline: int = 0  # served on the caller's thread (run_here)


@dataclass
class _Task:
    lane: Lane
    fn: Callable[[], Any]
    future: Future
    enqueued_ns: int


class _Worker:
    def __init__(self, lane: Lane, dynamic: bool, lock: threading.Lock):
        self.lane = lane
        self.dynamic = dynamic
        self.wake = threading.Condition(lock)
        self.reserved = False  # set by a submitter that handed this idle worker a task


class LaneExecutor:
    """Runs callables on priority lanes. `submit` returns a concurrent.futures.Future."""

    def __init__(self, lanes: dict[Lane, LaneConfig] | None = None, name: str = "lanes",
                 on_wait: Callable[[Lane, float], None] | None = None):
        self._config = dict(DEFAULT_LANES if lanes is None else lanes)
        missing = set(Lane) - set(self._config)
        if missing:
            raise ValueError(f"no config for lanes {sorted(m.name for m in missing)}")
        self._name = name
        # Called with each task's lane and how long it waited (s) before it started; 0 for a
        # run_here at once. Outside the lock; it must not raise (services.runtime.metrics).
        self.on_wait = on_wait
        self._lock = threading.Lock()
        self._queues: dict[Lane, deque[_Task]] = {lane: deque() for lane in Lane}
        self._idle: dict[Lane, list[_Worker]] = {lane: [] for lane in Lane}
        self._counters = {lane: LaneCounters() for lane in Lane}
        self._inline = {lane: 0 for lane in Lane}  # run_here calls running now
        self._threads: set[threading.Thread] = set()
        self._closed = False
        with self._lock:
            for lane in Lane:
                for _ in range(self._config[lane].static_threads):
                    self._spawn(lane, dynamic=False)

    # -- public -----------------------------------------------------------------------------

    def submit(self, lane: Lane, fn: Callable[[], Any]) -> Future:
        """Queue fn on lane; LaneFull when its queue is at capacity."""
        future: Future = Future()
        with self._lock:
            if self._closed:
                raise LaneExecutorClosed("the server is shutting down; retry on another instance")
            queue = self._queues[lane]
            counters = self._counters[lane]
            if (
                len(queue) >= self._config[lane].queue_capacity
                and not self._has_idle(lane)
                and counters.threads + self._inline[lane] >= self._config[lane].max_threads
            ):
                counters.rejected += 1
                raise LaneFull(lane, self._config[lane].queue_capacity)
            queue.append(_Task(lane, fn, future, time.monotonic_ns()))
            counters.queued += 1
            self._dispatch(lane)
        return future

    def run_here(self, lane: Lane, fn: Callable[[], Any]) -> Future:
        """Run fn on the calling thread, as `lane` work, when the lane has a free slot and
        nothing of its priority or higher is waiting; else queue it like submit(). Returns a
        done Future in the first case.

        A caller that would only block until a lane thread has run fn (a gRPC handler thread)
        saves two thread hand-overs this way, each a wait for the GIL. Priority is kept: fn
        never jumps a queued task of its own or a higher lane. Bounds are kept: runs here take
        only the slots the lane's threads leave free (max_threads - threads), so the lane
        never runs more than max_threads at once."""
        with self._lock:
            if self._closed:
                raise LaneExecutorClosed("the server is shutting down; retry on another instance")
            counters = self._counters[lane]
            free = self._config[lane].max_threads - counters.threads - self._inline[lane]
            inline = free > 0 and not self._queues_for(lane)
            if inline:
                self._inline[lane] += 1
                counters.running += 1
                counters.inline += 1
        if not inline:
            return self.submit(lane, fn)
        self._waited(lane, 0.0)
        future: Future = Future()
        future.set_running_or_notify_cancel()
        outer, _current.lane = getattr(_current, "lane", None), lane
        try:
            with scheduled_as(self._config[lane]):
                future.set_result(fn())
        except BaseException as exc:  # noqa: BLE001 - handed to the caller through the future
            future.set_exception(exc)
        finally:
            _current.lane = outer
            with self._lock:
                self._inline[lane] -= 1
                counters.running -= 1
                counters.served += 1
        return future

    def counters(self) -> dict[Lane, LaneCounters]:
        """A consistent copy of every lane's counters."""
        with self._lock:
            return {lane: LaneCounters(**vars(c)) for lane, c in self._counters.items()}

    def shutdown(self, wait: bool = True, timeout_s: float | None = None) -> None:
        """Cancel queued work, let running work finish, and stop every thread."""
        with self._lock:
            self._closed = True
            for lane, queue in self._queues.items():
                while queue:
                    task = queue.popleft()
                    self._counters[lane].queued -= 1
                    task.future.cancel()
            for workers in self._idle.values():
                for worker in workers:
                    worker.wake.notify()
            threads = list(self._threads)
        if wait:
            deadline = None if timeout_s is None else time.monotonic() + timeout_s
            for thread in threads:
                remaining = None if deadline is None else max(0.0, deadline - time.monotonic())
                thread.join(remaining)

    def _waited(self, lane: Lane, wait_s: float) -> None:
        """Report a task's wait to on_wait, if set (without the lock); never raises."""
        if self.on_wait is None:
            return
        try:
            self.on_wait(lane, wait_s)
        except Exception:  # noqa: BLE001 - a report never fails the task
            log.exception("reporting a lane wait failed")

    # -- internals (called with the lock held) ----------------------------------------------

    def _has_idle(self, lane: Lane) -> bool:
        return any(self._idle[candidate] for candidate in Lane if candidate >= lane)

    def _dispatch(self, lane: Lane) -> None:
        """Wake one idle worker that may run `lane` work: its own first, then a lower lane's."""
        for candidate in Lane:
            if candidate < lane or not self._idle[candidate]:
                continue
            worker = self._idle[candidate].pop()
            worker.reserved = True
            worker.wake.notify()
            return
        if self._counters[lane].threads + self._inline[lane] < self._config[lane].max_threads:
            self._spawn(lane, dynamic=True)

    def _spawn(self, lane: Lane, dynamic: bool) -> None:
        worker = _Worker(lane, dynamic, self._lock)
        kind = "dyn" if dynamic else "static"
        thread = threading.Thread(
            target=self._run_worker,
            args=(worker,),
            name=f"{self._name}-{lane.name.lower()}-{kind}",
            daemon=True,
        )
        self._counters[lane].threads += 1
        self._threads.add(thread)
        thread.start()

    def _next_task(self, lane: Lane) -> _Task | None:
        """The most urgent queued task this lane's thread may run: its own lane or higher."""
        for candidate in Lane:
            if candidate > lane:
                return None
            if self._queues[candidate]:
                return self._queues[candidate].popleft()
        return None

    # -- worker thread ----------------------------------------------------------------------

    def _run_worker(self, worker: _Worker) -> None:
        _set_thread_nice(self._config[worker.lane].nice)
        lock = self._lock
        lock.acquire()
        try:
            while True:
                task = self._next_task(worker.lane)
                if task is None:
                    if self._closed:
                        return
                    worker.reserved = False
                    self._idle[worker.lane].append(worker)
                    timeout = DYNAMIC_IDLE_TIMEOUT_S if worker.dynamic else None
                    worker.wake.wait(timeout)
                    if not worker.reserved and worker in self._idle[worker.lane]:
                        self._idle[worker.lane].remove(worker)
                        if worker.dynamic and not self._queues_for(worker.lane):
                            return
                    continue
                self._run_task(worker, task)
        finally:
            self._counters[worker.lane].threads -= 1
            self._threads.discard(threading.current_thread())
            lock.release()

    def _queues_for(self, lane: Lane) -> bool:
        return any(self._queues[candidate] for candidate in Lane if candidate <= lane)

    def _run_task(self, worker: _Worker, task: _Task) -> None:
        """Run one task with the lock released; counters are updated under the lock."""
        counters = self._counters[task.lane]
        counters.queued -= 1
        if not task.future.set_running_or_notify_cancel():
            return  # cancelled while queued (the client went away)
        counters.running += 1
        if worker.lane != task.lane:
            counters.borrowed += 1
        self._lock.release()
        self._waited(task.lane, (time.monotonic_ns() - task.enqueued_ns) / 1e9)
        _current.lane = task.lane
        try:
            with scheduled_as(self._config[task.lane]):
                result = task.fn()
        except BaseException as exc:  # noqa: BLE001 - handed to the caller through the future
            task.future.set_exception(exc)
        else:
            task.future.set_result(result)
        finally:
            _current.lane = None
            self._lock.acquire()
            counters.running -= 1
            counters.served += 1


@contextlib.contextmanager
def scheduled_as(config: LaneConfig, system=os) -> Iterator[None]:
    """The block runs as `config`'s lane work: a real-time thread running the work of a lane
    that is not real-time runs it at ORDINARY_LANE_RT_PRIORITY (see LaneConfig.realtime) and
    takes its own priority back after. `system` stands for the os module (tests pass a
    fake)."""
    if config.realtime or not hasattr(system, "sched_getscheduler"):
        yield
        return
    policy = system.sched_getscheduler(0)
    if policy & ~getattr(system, "SCHED_RESET_ON_FORK", 0) not in (system.SCHED_FIFO,
                                                                   system.SCHED_RR):
        yield
        return
    param = system.sched_getparam(0)
    system.sched_setscheduler(0, policy, system.sched_param(ORDINARY_LANE_RT_PRIORITY))
    try:
        yield
    finally:
        try:
            system.sched_setscheduler(0, policy, param)
        except OSError as exc:  # the privilege went away meanwhile: the thread stays lower
            log.warning("%s could not take its real-time priority back after a lane's "
                        "ordinary work: %s", threading.current_thread().name, exc)


def _set_thread_nice(offset: int) -> None:
    """Set this thread's nice value (Linux: per thread) `offset` from the process's, which is
    its main thread's: a process niced as a whole (priority.nice_every_thread) keeps its lanes
    in the same order below the command path. Raising priority needs privilege."""
    if offset == 0 or not hasattr(os, "setpriority"):
        return
    nice = max(-20, min(19, os.getpriority(os.PRIO_PROCESS, os.getpid()) + offset))
    try:
        os.setpriority(os.PRIO_PROCESS, threading.get_native_id(), nice)
    except PermissionError:
        log.info("no privilege to set nice %d on %s; it runs at the default", nice,
                 threading.current_thread().name)


# Lanes for the runtime's own services, which carry no `default_lane` option.
_BUILTIN_LANES = {
    "/grpc.health.v1.Health/Check": Lane.HIGH,
    "/grpc.health.v1.Health/Watch": Lane.LOW,
}
_PROTO_LANES = {
    options_pb2.LANE_EMERGENCY: Lane.EMERGENCY,
    options_pb2.LANE_HIGH: Lane.HIGH,
    options_pb2.LANE_MEDIUM: Lane.MEDIUM,
    options_pb2.LANE_LOW: Lane.LOW,
}
LANE_TO_PROTO = {lane: value for value, lane in _PROTO_LANES.items()}


@functools.lru_cache(maxsize=1024)  # looked up for every call: cached (methods are few)
def declared_lane(method_path: str) -> Lane:
    """The lane an RPC declares in its proto ("/pkg.Service/Method"); MEDIUM when it has none."""
    if method_path in _BUILTIN_LANES:
        return _BUILTIN_LANES[method_path]
    options = method_options(method_path)
    if options is None:
        return Lane.MEDIUM
    return _PROTO_LANES.get(options.Extensions[options_pb2.default_lane], Lane.MEDIUM)
