"""bench/cpu.py: a busy process shows its CPU, an idle one none, and the machine's share is a
share."""

from __future__ import annotations

import subprocess
import sys
import time

import pytest

from bench.cpu import CpuWindow

pytestmark = pytest.mark.e2e  # it starts processes to watch


def test_a_spinning_process_takes_a_core_share_and_a_sleeping_one_none():
    spinning = subprocess.Popen([sys.executable, "-c", "while True: pass"])
    sleeping = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(60)"])
    try:
        time.sleep(0.3)  # both past their start-up
        window = CpuWindow({"spinning": spinning.pid, "sleeping": sleeping.pid})
        time.sleep(1.0)  # the window: CPU ticks are 10 ms, so a second reads to about 1 %
        cpu = window.stop()
    finally:
        spinning.kill()
        sleeping.kill()
    assert cpu["cpu_pct"]["spinning"] > 30.0  # a whole core when it has one; shared on 2
    assert cpu["cpu_pct"]["sleeping"] <= 2.0
    assert 0.0 < cpu["machine_busy_pct"] <= 100.0


def test_a_process_gone_before_the_window_ends_is_left_out():
    gone = subprocess.Popen([sys.executable, "-c", "pass"])
    window = CpuWindow({"gone": gone.pid})
    gone.wait()
    assert window.stop()["cpu_pct"] == {}
