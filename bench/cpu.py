"""Where the machine's CPU went over a measured window: how busy all cores were (/proc/stat),
and each watched process's share of one core (/proc/<pid>/stat, user + system, every thread).

A scenario that misses its goal while the machine has no idle core left is limited by the
machine, not by the code under test; the bench clients run on the same cores as the station,
so their share is part of the answer."""

from __future__ import annotations

import os
import re
import time

_TICKS_PER_S = os.sysconf("SC_CLK_TCK")


def process_cpu_s(pid: int) -> float:
    """A process's CPU time so far (user + system, every thread), s; 10 ms ticks."""
    return _cpu_s(_stat_fields(pid))


def reaped_children_cpu_s(pid: int) -> float:
    """The CPU time so far of the children a process has waited for (user + system), s: the
    DecisionServer's recording writers, once each recording has stopped."""
    fields = _stat_fields(pid)
    return (int(fields[13]) + int(fields[14])) / _TICKS_PER_S


def thread_kind(name: str) -> str:
    """A thread's name without the session id a per-session thread carries ("teleop-in-
    d40be" -> "teleop-in"), so that the threads of two sessions compare."""
    return _SESSION_ID.sub("", name)


_SESSION_ID = re.compile(r"-[0-9a-f]{4,}$")


class ThreadCpuWatch:
    """A process's CPU time by thread name (thread_kind) over a window, a thread that starts
    or ends within it included: each thread counts what it had spent at its last reading
    (at the start, at each sample(), at stop()). A caller samples while the threads it wants
    are alive, at a moment that costs its measurement nothing: reading every thread's /proc
    file holds the caller's interpreter for about a millisecond."""

    def __init__(self, pid: int):
        self._pid = pid
        self._first = _task_cpu_s(pid)
        self._last = dict(self._first)

    def sample(self) -> None:
        """Read each thread's time now."""
        self._last.update(_task_cpu_s(self._pid))

    def stop(self) -> dict[str, float]:
        """{thread name: CPU s spent in the window}, the names that spent any."""
        self.sample()
        spent: dict[str, float] = {}
        for task, (name, cpu_s) in self._last.items():
            before = self._first.get(task, (name, 0.0))[1]
            if cpu_s > before:
                spent[name] = spent.get(name, 0.0) + cpu_s - before
        return spent


def _task_cpu_s(pid: int) -> dict[int, tuple[str, float]]:
    """{thread id: (thread_kind of its name, CPU s so far)} of a process's threads now."""
    tasks = {}
    try:
        entries = list(os.scandir(f"/proc/{pid}/task"))
    except (FileNotFoundError, ProcessLookupError):
        return tasks  # the process ended
    for task in entries:
        try:
            with open(f"{task.path}/stat") as stat:
                text = stat.read()
        except (FileNotFoundError, ProcessLookupError):
            continue  # the thread ended meanwhile
        name = thread_kind(text[text.index("(") + 1:text.rindex(")")])
        tasks[int(task.name)] = (name, _cpu_s(_fields(text)))
    return tasks


def _stat_fields(pid: int) -> list[str]:
    with open(f"/proc/{pid}/stat") as stat:
        return _fields(stat.read())


def _fields(stat: str) -> list[str]:
    """A /proc stat line's fields after the command (which may hold " "): state is [0]."""
    return stat.rsplit(")", 1)[1].split()


def _cpu_s(fields: list[str]) -> float:
    """User + system time of those fields, s."""
    return (int(fields[11]) + int(fields[12])) / _TICKS_PER_S


def machine_ticks() -> tuple[int, int]:
    """(busy, total) jiffies of all cores so far; idle and iowait are not busy."""
    with open("/proc/stat") as stat:
        values = [int(v) for v in stat.readline().split()[1:]]
    total = sum(values[:8])  # user nice system idle iowait irq softirq steal (guests are in user)
    return total - values[3] - values[4], total


class CpuWindow:
    """Started, then stopped: the machine's busy share and each process's CPU in between."""

    def __init__(self, pids: dict[str, int]):
        self._pids = dict(pids)
        self._started_at = time.monotonic()
        self._machine = machine_ticks()
        self._cpu = {name: _cpu_or_none(pid) for name, pid in self._pids.items()}

    def stop(self) -> dict:
        """{"machine_busy_pct": % of all cores, "cpu_pct": {name: % of one core}}; a process
        that exited meanwhile is left out."""
        elapsed = max(time.monotonic() - self._started_at, 1e-9)
        busy, total = machine_ticks()
        busy_then, total_then = self._machine
        shares = {}
        for name, pid in self._pids.items():
            now, then = _cpu_or_none(pid), self._cpu[name]
            if now is not None and then is not None:
                shares[name] = round(100.0 * (now - then) / elapsed, 1)
        return {"machine_busy_pct": round(100.0 * (busy - busy_then)
                                          / max(total - total_then, 1), 1),
                "window_s": round(elapsed, 3), "cpu_pct": shares}


def _cpu_or_none(pid: int) -> float | None:
    try:
        return process_cpu_s(pid)
    except (FileNotFoundError, ProcessLookupError):
        return None
