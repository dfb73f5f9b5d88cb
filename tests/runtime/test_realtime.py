"""A service on the command path runs every thread of its process at SCHED_FIFO when asked and
allowed (this machine: root, real-time throttling on), and none with --rt-priority 0. The rest
of the suite runs its stations with it off (tests/conftest.py)."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from tests.processes import start_service, unique_shm_name

pytestmark = pytest.mark.e2e

SCHED_FIFO = 1


def thread_policies(pid: int) -> list[tuple[int, int]]:
    """(policy, real-time priority) of each thread of `pid` (/proc/PID/task/TID/stat fields
    41 and 40)."""
    policies = []
    for task in Path(f"/proc/{pid}/task").iterdir():
        fields = (task / "stat").read_text().rsplit(")", 1)[1].split()
        policies.append((int(fields[38]), int(fields[37])))
    return policies


@pytest.mark.skipif(os.geteuid() != 0, reason="SCHED_FIFO needs CAP_SYS_NICE")
def test_the_band_runs_its_threads_at_sched_fifo_when_asked():
    band = start_service("emergency_stop", "--shm-name", unique_shm_name(),
                         env={"TELEROBOT_EMERGENCY_STOP_RT_PRIORITY": "8"})
    try:
        policies = thread_policies(band.pid)
        fifo = [p for p in policies if p == (SCHED_FIFO, 8)]
        # Every thread started after start-up inherits it (gRPC's among them); at most the
        # one an import started before is ordinary.
        assert len(fifo) >= len(policies) - 1 and len(fifo) > 5, policies
        assert any("threads at SCHED_FIFO priority 8" in line for line in band.lines)
    finally:
        band.stop()


def test_rt_priority_zero_leaves_every_thread_ordinary():
    band = start_service("emergency_stop", "--shm-name", unique_shm_name(), "--rt-priority", "0")
    try:
        assert {policy for policy, _ in thread_policies(band.pid)} == {0}
        assert any("real-time scheduling off" in line for line in band.lines)
    finally:
        band.stop()
