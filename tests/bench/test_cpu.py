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
