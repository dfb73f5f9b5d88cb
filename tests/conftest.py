"""The tests' shared fixtures, and the guard that keeps `pytest -m "not e2e"` process-free.

Every test not marked e2e runs in this process: it starts no process (subprocess, fork,
posix_spawn, multiprocessing, os.system), attaches no shared memory (so no world), and, in
the modules a folder names in its `modules_on_the_clock` fixture, reads no system time.
At collection, such a test that uses a fixture marked `@starts_processes` is refused (a
session fixture would start its world before any check at run time could refuse it); while it
is set up and runs, starting a process fails it. The helpers that start processes are in
tests/processes.py; the fakes that stand in for them in tests/fakes."""

from __future__ import annotations

import _posixsubprocess
import os
import subprocess
import sys
import time
from dataclasses import dataclass
from multiprocessing import process as multiprocessing_process
from multiprocessing import shared_memory

import pytest

# MuJoCo picks its GL backend at import: headless rendering needs EGL, set before any test
# module imports mujoco (make does it too, but a bare `pytest` should work the same).
os.environ.setdefault("MUJOCO_GL", "egl")
# The suite starts station after station on a shared 2-core machine, beside a browser and the
# cameras' rendering. With their command-path threads real-time (services/runtime/priority.py)
# they would take the cores from the test runner, the launchers and the cameras whenever they
# wake, which is what real-time is for on a station and not what a test of something else
# needs. So the suite's stations run them as ordinary threads; tests/runtime/test_realtime.py
# checks the real-time start, and `make bench` (soak_overload) measures what it buys.
COMMAND_PATH_SERVICES = ("decision_server", "proxy_robot", "force_sensor", "emergency_stop")
for _service in COMMAND_PATH_SERVICES:
    os.environ.setdefault(f"TELEROBOT_{_service.upper()}_RT_PRIORITY", "0")
# The camera's nice value (priority.VIDEO_NICE) would put it below the suite's command path,
# whose threads are ordinary here: the suite runs it beside them, at the default.
# tests/stereo_camera/test_process.py checks the niced start.
os.environ.setdefault("TELEROBOT_STEREO_CAMERA_NICE", "0")

from services.runtime import children  # noqa: E402
from services.runtime.children import Child  # noqa: E402
from services.runtime.process import GIL_SWITCH_INTERVAL_S  # noqa: E402
from tests.processes import (  # noqa: E402
    SHM_DIR,
    start_process,
    start_service,
    start_world,
    stop_world,
)

# The services a test runs in this process (in-process servers, the DecisionServer's force
# control, the Franka link's loop) switch the GIL as their own processes do
# (services/runtime/process.py), not at Python's 5 ms: a busy thread of the runner would
# otherwise hold them up to 5 ms at a time, longer than their control periods.
sys.setswitchinterval(GIL_SWITCH_INTERVAL_S)


def wait_for(predicate, timeout_s: float = 5.0, what: str = "condition"):
    """Poll `predicate` every 5 ms until it returns something true, and return that; fail the
    test after `timeout_s`, saying `what` (or what `what()` says then). It looks once more at
    the deadline: a machine that stalled this thread past it may have met the condition
    meanwhile."""
    deadline = time.monotonic() + timeout_s
    while True:
        past_deadline = time.monotonic() >= deadline
        value = predicate()
        if value:
            return value
        if past_deadline:
            break
        time.sleep(0.005)
    raise AssertionError(f"timed out waiting for {what() if callable(what) else what}")


# -- the guard: tests not marked e2e start no process ---------------------------------------

def starts_processes(fixture_function):
    """Mark a fixture function (under @pytest.fixture) as one that starts processes: a test
    not marked e2e that uses it, even through another fixture, is refused at collection."""
    fixture_function.starts_processes = True
    return fixture_function


def _process_fixtures(item) -> list[str]:
    """The fixtures `item` uses (directly or through others) that start processes."""
    definitions = getattr(getattr(item, "_fixtureinfo", None), "name2fixturedefs", {})
    return sorted(name for name, fixturedefs in definitions.items()
                  if fixturedefs and getattr(fixturedefs[-1].func, "starts_processes", False))


def pytest_collection_modifyitems(config, items) -> None:
    refused = [f"{item.nodeid} uses {used}" for item in items
               if not item.get_closest_marker("e2e") and (used := _process_fixtures(item))]
    if refused:
        raise pytest.UsageError("tests not marked e2e use fixtures that start processes: "
                                "mark them e2e or use the fakes (tests/fakes)\n  "
                                + "\n  ".join(refused))


def _refused(what: str):
    def refuse(*args, **kwargs):
        raise AssertionError(f"a test not marked e2e called {what}, which starts a process or "
                             "attaches shared memory (a world's): mark it e2e, or keep it in "
                             "this process")

    return refuse


def refuse_processes(monkeypatch: pytest.MonkeyPatch) -> None:
    """From here on (until `monkeypatch` undoes it), starting a process or attaching shared
    memory fails."""
    # Popen is also asyncio's subprocesses' and os.popen's.
    monkeypatch.setattr(subprocess.Popen, "__init__", _refused("subprocess.Popen"))
    # Below Popen: multiprocessing's spawn and forkserver start their processes here.
    monkeypatch.setattr(_posixsubprocess, "fork_exec", _refused("_posixsubprocess.fork_exec"))
    monkeypatch.setattr(multiprocessing_process.BaseProcess, "start",
                        _refused("multiprocessing's Process.start"))
    for name in ("fork", "forkpty", "posix_spawn", "posix_spawnp", "system"):  # os.spawn* fork
        monkeypatch.setattr(os, name, _refused(f"os.{name}"))
    monkeypatch.setattr(shared_memory.SharedMemory, "__init__", _attach_only_nothing)


_attach = shared_memory.SharedMemory.__init__
_refuse_shared_memory = _refused("multiprocessing's SharedMemory")


def _attach_only_nothing(self, name=None, create=False, size=0, **options):
    """Creating a segment (its resource tracker is a process) or attaching one that exists (a
    world's) fails the test; attaching one that does not exist fails as it would anyway, with
    FileNotFoundError (code that looks for a world and finds none may be tested in-process)."""
    if not create and name and not (SHM_DIR / name.lstrip("/")).exists():
        return _attach(self, name, create, size, **options)
    _refuse_shared_memory()


@pytest.hookimpl(wrapper=True)
def pytest_runtest_setup(item):
    """Refuse processes while a test not marked e2e is set up: its fixtures of every scope,
    a module's or session's first set up here too."""
    if item.get_closest_marker("e2e"):
        return (yield)
    with pytest.MonkeyPatch.context() as monkeypatch:
        refuse_processes(monkeypatch)
        return (yield)


@pytest.hookimpl(wrapper=True)
def pytest_runtest_call(item):
    """Refuse processes while a test not marked e2e runs."""
    if item.get_closest_marker("e2e"):
        return (yield)
    with pytest.MonkeyPatch.context() as monkeypatch:
        refuse_processes(monkeypatch)
        return (yield)


class _NoSystemTime:
    """Stands in for the `time` module inside a core: any reading of the real clock fails."""

    def __getattr__(self, name: str):
        raise AssertionError(f"the core read time.{name}: it must use its injected clock")


@pytest.fixture
def modules_on_the_clock() -> tuple:
    """Modules that must read no system time in tests not marked e2e (they take an injected
    clock); a folder's conftest names its own."""
    return ()


@pytest.fixture(autouse=True)
def _no_system_time(request, monkeypatch, modules_on_the_clock) -> None:
    """In tests not marked e2e, `modules_on_the_clock` read no system time."""
    if request.node.get_closest_marker("e2e"):
        return
    for module in modules_on_the_clock:
        monkeypatch.setattr(module, "time", _NoSystemTime(), raising=False)


# -- fixtures that start processes (e2e only) -----------------------------------------------

@pytest.fixture
@starts_processes
def service_process():
    """Factory: start `python -m services.<name>` on port 0 and wait until SERVING; returns
    its address."""
    started: list[Child] = []

    def start(name: str) -> str:
        started.append(start_service(name))
        return started[-1].address

    yield start
    children.stop_all(started)


@pytest.fixture(scope="session")
@starts_processes
def world():
    """One real world process for the tests that drive or read the simulated arm."""
    running = start_world()
    yield running
    stop_world(running)


@dataclass
class Backends:
    processes: list[Child]
    proxy_address: str
    sensor_address: str
    emergency_address: str


@pytest.fixture(scope="session")
@starts_processes
def backends(world):
    """Real ProxyRobot, ForceSensor and emergency-stop band processes on the shared world, for
    the tests that put a DecisionServer or a client in front of them."""
    env = {"TELEROBOT_WORLD_SHM": world.shm_name}
    names = ["proxy_robot", "force_sensor", "emergency_stop"]
    running = [start_process(["-m", f"services.{name}", "--address", "127.0.0.1:0"], env)
               for name in names]  # started together, waited for together
    try:
        addresses = [process.wait_ready(timeout_s=60.0) for process in running]
    except children.ChildFailed:
        children.stop_all(running)
        raise
    yield Backends(running, *addresses)
    children.stop_all(running)
