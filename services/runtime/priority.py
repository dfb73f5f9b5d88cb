"""Real-time scheduling for a service's threads, where the host allows it.

A thread at SCHED_FIFO runs before every ordinary (CFS) thread on its core the moment it is
ready: co-tenant processes, rendering, a busy test runner no longer delay it, only real-time
threads of a higher priority. That is what ros2_control and libfranka do for their loops. It
needs CAP_SYS_NICE (root) and is asked for only where the kernel throttles real-time threads
(by default to 95 % of each second), so a runaway thread cannot lock a core. Where it is not
allowed, the log says so and the thread keeps its nice value.
"""

from __future__ import annotations

import logging
import os
import threading
from collections.abc import Callable
from typing import TypeVar

log = logging.getLogger(__name__)
T = TypeVar("T")

# SCHED_FIFO priorities (1-99, higher first): the world's physics thread (10) preempts the
# emergency-stop band (8), which preempts the services on the command path (5).
BAND_FIFO_PRIORITY = 8
COMMAND_PATH_FIFO_PRIORITY = 5

RT_RUNTIME_PATH = "/proc/sys/kernel/sched_rt_runtime_us"
RT_PERIOD_PATH = "/proc/sys/kernel/sched_rt_period_us"


def read_rt_throttling() -> tuple[int, int] | None:
    """(runtime, period) in µs of the kernel's real-time throttling: real-time threads may use
    `runtime` of every `period` (runtime -1: unlimited, throttling off); None if unknown."""
    try:
        with open(RT_RUNTIME_PATH) as runtime, open(RT_PERIOD_PATH) as period:
            return int(runtime.read()), int(period.read())
    except (OSError, ValueError):
        return None


def raise_thread_priority(fifo_priority: int, nice: int, *, system=os,
                          rt_throttling: Callable[[], tuple[int, int] | None] = read_rt_throttling,
                          thread_id: int | None = None, what: str = "physics thread",
                          inherited: bool = False) -> str:
    """Give the calling thread SCHED_FIFO at `fifo_priority` where the OS allows it and the
    kernel throttles real-time threads, else the nice value `nice`; returns what it got
    ("SCHED_FIFO 10", "nice -10" or "default"). `system` stands for the os module (tests pass a
    fake); `fifo_priority` 0 asks for the nice value only. With `inherited`, the threads and
    processes the calling thread starts later inherit SCHED_FIFO; without, they do not (Linux's
    SCHED_RESET_ON_FORK covers threads too). `what` names the thread in the log."""
    thread_id = threading.get_native_id() if thread_id is None else thread_id
    if fifo_priority > 0:
        throttling = rt_throttling()
        if not hasattr(system, "sched_setscheduler"):
            why_not = "this OS has no SCHED_FIFO"
        elif throttling is None:
            why_not = f"the kernel's real-time throttling is unknown ({RT_RUNTIME_PATH})"
        elif throttling[0] < 0:
            why_not = ("the kernel's real-time throttling is off (sched_rt_runtime_us -1), so a "
                       "runaway real-time thread could lock a core")
        else:
            policy = system.SCHED_FIFO
            if not inherited:
                policy |= getattr(system, "SCHED_RESET_ON_FORK", 0)
            try:
                system.sched_setscheduler(thread_id, policy, system.sched_param(fifo_priority))
            except OSError as exc:  # EPERM: no CAP_SYS_NICE, or no RT budget in the cgroup
                why_not = f"no privilege ({exc.strerror or exc})"
            else:
                log.info("%s at SCHED_FIFO priority %d (real-time threads are "
                         "throttled to %d µs of every %d µs)", what, fifo_priority, *throttling)
                return f"SCHED_FIFO {fifo_priority}"
        log.info("no SCHED_FIFO %d for the %s: %s; asking for nice %d instead",
                 fifo_priority, what, why_not, nice)
    try:
        system.setpriority(system.PRIO_PROCESS, thread_id, nice)
    except (PermissionError, AttributeError):
        log.info("no privilege to set nice %d on the %s; it runs at the default", nice, what)
        return "default"
    return f"nice {nice}"


# The nice value of a station's background work (the recordings' writer process): below every
# service, so that on a busy machine it waits, not the command path.
BACKGROUND_NICE = 10
# The nice value of the stereo camera, off the command path: on a shared machine its capture
# and encoding yield to the operator's own processes (whose threads are ordinary), as the
# recordings' writer does.
VIDEO_NICE = BACKGROUND_NICE


def nice_every_thread(nice: int, *, tasks_dir: str = "/proc/self/task", system=os) -> int:
    """Set the nice value `nice` on every thread of this process (Linux keeps it per thread,
    and a new thread takes its creator's, so the threads started later have it too); returns
    how many threads took it. Raising the value is always allowed; a thread that ended
    meanwhile is skipped."""
    count = 0
    for task in os.listdir(tasks_dir):
        try:
            system.setpriority(system.PRIO_PROCESS, int(task), nice)
        except ProcessLookupError:
            continue
        count += 1
    return count


def start_in_background(start: Callable[[], T], nice: int = BACKGROUND_NICE, *,
                        system=os) -> T:
    """`start()` run on a thread of its own that first leaves real-time scheduling for the
    ordinary one at nice `nice`, so the process `start` starts inherits that, never the
    caller's SCHED_FIFO (Linux keeps both per thread, and a child takes its parent thread's).
    Lowering is always allowed. Returns what `start` returns, or raises what it raised."""
    outcome: list = []

    def run() -> None:
        try:
            if hasattr(system, "sched_setscheduler"):
                system.sched_setscheduler(0, system.SCHED_OTHER, system.sched_param(0))
            try:
                system.setpriority(system.PRIO_PROCESS, threading.get_native_id(), nice)
            except PermissionError:
                pass  # already nicer than `nice`: going back up needs a privilege
            outcome.append((True, start()))
        except BaseException as error:  # noqa: BLE001 - re-raised in the caller's thread
            outcome.append((False, error))

    thread = threading.Thread(target=run, name="background-start")
    thread.start()
    thread.join()
    succeeded, value = outcome[0]
    if not succeeded:
        raise value
    return value
