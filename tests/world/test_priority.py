"""The physics thread's priority choice: SCHED_FIFO where allowed and throttled, else nice, else
the default; a background process's start, below it; and a whole process's nice value. The os
calls are faked: nothing here changes a real thread's scheduling."""

from __future__ import annotations

import errno
import logging
import os
import threading

import pytest

from services.runtime.priority import (
    nice_every_thread,
    raise_thread_priority,
    start_in_background,
)

THROTTLED = (950_000, 1_000_000)  # Linux's default: 95 % of every second
THREAD = 4242


class NiceOnlyOs:
    """The os calls raise_thread_priority makes on an OS without SCHED_FIFO (macOS), recording
    them; `refuse` names the calls that fail with EPERM."""

    SCHED_FIFO = 1
    SCHED_RESET_ON_FORK = 0x40000000
    PRIO_PROCESS = 0
    sched_param = os.sched_param

    def __init__(self, *refuse: str):
        self.refuse = set(refuse)
        self.calls: list[tuple] = []

    def _call(self, name: str, *args) -> None:
        self.calls.append((name, *args))
        if name in self.refuse:
            raise PermissionError(errno.EPERM, "Operation not permitted")

    def setpriority(self, which, tid, nice) -> None:
        self._call("setpriority", which, tid, nice)


class FakeOs(NiceOnlyOs):
    """Linux's calls."""

    def sched_setscheduler(self, tid, policy, param) -> None:
        self._call("sched_setscheduler", tid, policy, param.sched_priority)


def _raise(system, fifo=10, nice=-10, throttling=THROTTLED) -> str:
    return raise_thread_priority(fifo, nice, system=system, rt_throttling=lambda: throttling,
                                 thread_id=THREAD)


def test_sched_fifo_where_allowed(caplog) -> None:
    system = FakeOs()
    with caplog.at_level(logging.INFO, "services.runtime.priority"):
        assert _raise(system, fifo=15) == "SCHED_FIFO 15"
    assert system.calls == [("sched_setscheduler", THREAD,
                             FakeOs.SCHED_FIFO | FakeOs.SCHED_RESET_ON_FORK, 15)]
    assert "SCHED_FIFO priority 15" in caplog.text and "950000 µs of every 1000000" in caplog.text


def test_without_the_privilege_it_falls_back_to_nice(caplog) -> None:
    system = FakeOs("sched_setscheduler")
    with caplog.at_level(logging.INFO, "services.runtime.priority"):
        assert _raise(system) == "nice -10"
    assert [call[0] for call in system.calls] == ["sched_setscheduler", "setpriority"]
    assert system.calls[-1] == ("setpriority", FakeOs.PRIO_PROCESS, THREAD, -10)
    assert "no SCHED_FIFO 10" in caplog.text and "no privilege" in caplog.text


def test_without_any_privilege_it_runs_at_the_default(caplog) -> None:
    system = FakeOs("sched_setscheduler", "setpriority")
    with caplog.at_level(logging.INFO, "services.runtime.priority"):
        assert _raise(system) == "default"
    assert "no privilege to set nice -10" in caplog.text


@pytest.mark.parametrize("throttling, why", [
    ((-1, 1_000_000), "throttling is off"),
    (None, "throttling is unknown"),
])
def test_no_sched_fifo_unless_the_kernel_throttles_it(caplog, throttling, why) -> None:
    system = FakeOs()
    with caplog.at_level(logging.INFO, "services.runtime.priority"):
        assert _raise(system, throttling=throttling) == "nice -10"
    assert [call[0] for call in system.calls] == ["setpriority"]  # never asked for SCHED_FIFO
    assert why in caplog.text


def test_no_sched_fifo_on_an_os_without_it() -> None:
    system = NiceOnlyOs()
    assert _raise(system) == "nice -10"
    assert [call[0] for call in system.calls] == ["setpriority"]


def test_priority_zero_asks_for_the_nice_value_only() -> None:
    system = FakeOs()
    assert _raise(system, fifo=0) == "nice -10"
    assert [call[0] for call in system.calls] == ["setpriority"]


def test_a_process_wide_priority_is_inherited_by_later_threads() -> None:
    """Linux's SCHED_RESET_ON_FORK covers new threads too: a service asking for all of its
    threads leaves it out."""
    system = FakeOs()
    assert raise_thread_priority(5, 0, system=system, rt_throttling=lambda: THROTTLED,
                                 thread_id=THREAD, inherited=True) == "SCHED_FIFO 5"
    assert system.calls == [("sched_setscheduler", THREAD, FakeOs.SCHED_FIFO, 5)]


def test_a_background_process_is_started_from_a_thread_at_ordinary_scheduling() -> None:
    """start_in_background lowers a thread of its own, never the caller's, before `start`
    runs there (a process started then inherits that thread's scheduling)."""
    system = FakeOs()
    system.SCHED_OTHER = 0
    started_on = []

    def start() -> str:
        started_on.append(threading.get_native_id())
        return "started"

    assert start_in_background(start, 10, system=system) == "started"
    [thread] = started_on
    assert thread != threading.get_native_id()
    assert system.calls == [("sched_setscheduler", 0, 0, 0),
                            ("setpriority", FakeOs.PRIO_PROCESS, thread, 10)]


def test_a_background_start_that_fails_raises_in_the_caller() -> None:
    system = FakeOs("setpriority")  # already nicer: going back up is refused, and that is fine
    system.SCHED_OTHER = 0

    def start():
        raise FileNotFoundError("no such interpreter")

    with pytest.raises(FileNotFoundError, match="no such interpreter"):
        start_in_background(start, 10, system=system)


def test_nice_every_thread_sets_each_thread_of_the_process_and_skips_one_that_ended(tmp_path):
    for task in ("101", "102", "103"):
        (tmp_path / task).mkdir()

    class EndedOs(NiceOnlyOs):
        def setpriority(self, which, tid, nice) -> None:
            super().setpriority(which, tid, nice)
            if tid == 102:
                raise ProcessLookupError(errno.ESRCH, "No such process")

    system = EndedOs()
    assert nice_every_thread(5, tasks_dir=str(tmp_path), system=system) == 2
    assert sorted(system.calls) == [("setpriority", 0, tid, 5) for tid in (101, 102, 103)]
