"""For tests that promise to run in-process: no process, no world, no system time in the core.

A conftest calls `reject_process_fixtures` from its `pytest_collection_modifyitems` (a
session fixture that starts a world runs before any function fixture could refuse it) and
`refuse_processes` from an autouse fixture, for every test not marked e2e."""

from __future__ import annotations

import os
import subprocess
from multiprocessing import shared_memory
from pathlib import Path

import pytest

# Fixtures that start real processes (tests/conftest.py, tests/world/conftest.py).
PROCESS_FIXTURES = frozenset({"world", "world_factory", "shared_world", "backends",
                              "service_process"})


def reject_process_fixtures(items, folder: Path) -> None:
    """Refuse, at collection, a test under `folder` not marked e2e that uses a process fixture."""
    for item in items:
        if folder not in item.path.parents or item.get_closest_marker("e2e"):
            continue
        used = PROCESS_FIXTURES.intersection(getattr(item, "fixturenames", ()))
        if used:
            raise pytest.UsageError(f"{item.nodeid} uses {sorted(used)}, which start processes: "
                                    "mark it e2e or use the fakes (tests/fakes)")


class _NoSystemTime:
    """Stands in for the `time` module inside a core: any reading of the real clock fails."""

    def __getattr__(self, name: str):
        raise AssertionError(f"the core read time.{name}: it must use its injected clock")


def refuse_processes(monkeypatch, modules_on_the_clock=()) -> None:
    """From here on, starting a process or attaching shared memory (a world) fails the test,
    and so does reading the system time inside `modules_on_the_clock`."""

    def refuse(*args, **kwargs):
        raise AssertionError("a test not marked e2e tried to start a process or attach a "
                             "world's shared memory")

    monkeypatch.setattr(subprocess.Popen, "__init__", refuse)
    monkeypatch.setattr(os, "fork", refuse)
    monkeypatch.setattr(os, "posix_spawn", refuse)
    monkeypatch.setattr(shared_memory.SharedMemory, "__init__", refuse)
    for module in modules_on_the_clock:
        monkeypatch.setattr(module, "time", _NoSystemTime(), raising=False)
