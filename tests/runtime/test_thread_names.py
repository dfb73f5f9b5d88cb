"""A service's threads carry their Python names to the OS (top -H, ps -L, /proc)."""

from __future__ import annotations

from pathlib import Path

import pytest

from services.runtime.thread_names import OS_NAME_BYTES
from tests.processes import start_service

pytestmark = pytest.mark.e2e


def os_thread_names(pid: int) -> list[str]:
    names = []
    for task in Path(f"/proc/{pid}/task").iterdir():
        try:
            names.append((task / "comm").read_text().strip())
        except FileNotFoundError:  # the thread ended meanwhile
            continue
    return names


def test_each_thread_of_a_service_has_its_python_name_at_the_os():
    running = start_service("stereo_camera", "--source", "pattern", "--width", "160",
                            "--height", "120")
    try:
        names = os_thread_names(running.pid)
    finally:
        running.stop()
    # The lanes' handlers, the signal thread, the capture loop: each as Python names it, cut
    # to what Linux keeps.
    for python_name in ("rpc-high-static", "rpc-medium-static", "signals", "stereo-capture"):
        assert python_name[:OS_NAME_BYTES] in names, names
