"""bench/cpu.py: a busy process shows its CPU, an idle one none, and the machine's share is a
share."""

from __future__ import annotations

import subprocess
import sys

import pytest

from bench.cpu import CpuWindow, process_cpu_s
from tests.conftest import wait_for

pytestmark = pytest.mark.e2e  # it starts processes to watch


def _started(code: str) -> subprocess.Popen:
    """A Python child running `code` once it has said it got there (past its start-up)."""
    child = subprocess.Popen([sys.executable, "-c", f"print('ready', flush=True)\n{code}"],
                             stdout=subprocess.PIPE, text=True)
    assert child.stdout.readline() == "ready\n"
    return child


def test_a_spinning_process_takes_a_core_share_and_a_sleeping_one_none():
    spinning = _started("while True: pass")
    sleeping = _started("import time; time.sleep(60)")
    try:
        window = CpuWindow({"spinning": spinning.pid, "sleeping": sleeping.pid})
        used = process_cpu_s(spinning.pid)
        # The window: until the spinner has used a second of CPU, so it lasts a second at
        # least (CPU ticks are 10 ms: a second reads to about 1 %).
        wait_for(lambda: process_cpu_s(spinning.pid) - used >= 1.0, 30,
                 "a second of the spinner's CPU")
        cpu = window.stop()
    finally:
        for child in (spinning, sleeping):
            child.kill()
            child.communicate()  # reaped, its pipe closed
    assert cpu["cpu_pct"]["spinning"] > 30.0  # a whole core when it has one; shared on 2
    assert cpu["cpu_pct"]["sleeping"] <= 2.0
    assert 0.0 < cpu["machine_busy_pct"] <= 100.0


def test_a_process_gone_before_the_window_ends_is_left_out():
    gone = subprocess.Popen([sys.executable, "-c", "pass"])
    window = CpuWindow({"gone": gone.pid})
    gone.wait()
    assert window.stop()["cpu_pct"] == {}


def test_a_session_thread_that_ends_within_the_window_is_counted_under_its_kind():
    """ThreadCpuWatch: a thread started after the window opened and ended before it closed
    still counts (its last reading), under its name without the session id."""
    import os
    import threading
    import time

    from bench.cpu import ThreadCpuWatch, thread_kind

    assert thread_kind("teleop-in-d40be") == "teleop-in"
    assert thread_kind("event_engine") == "event_engine"
    burnt, finish = threading.Event(), threading.Event()

    def burn() -> None:
        start = time.thread_time()
        while time.thread_time() - start < 0.2:
            pass
        burnt.set()
        finish.wait(30)

    watch = ThreadCpuWatch(os.getpid())
    worker = threading.Thread(target=burn)
    worker.start()
    try:
        # The OS's name, as runtime.thread_names gives a session's threads theirs.
        with open(f"/proc/self/task/{worker.native_id}/comm", "w") as comm:
            comm.write("teleop-9f3c2a1b")
        assert burnt.wait(30)
        watch.sample()  # alive: its 0.2 s read
    finally:
        finish.set()
        worker.join()
    spent = watch.stop()  # it has ended
    assert spent["teleop"] >= 0.15, spent
