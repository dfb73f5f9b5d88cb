"""Helpers shared by the tests: real service processes on free loopback ports."""

from __future__ import annotations

import os
import signal
import socket
import subprocess
import sys
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path

import pytest

# MuJoCo picks its GL backend at import: headless rendering needs EGL, set before any test
# module imports mujoco (make does it too, but a bare `pytest` should work the same).
os.environ.setdefault("MUJOCO_GL", "egl")

from services.runtime.process import READY_LINE_PREFIX

REPO = Path(__file__).resolve().parent.parent
BUF = REPO / "node_modules" / ".bin" / "buf"


def wait_for(predicate, timeout_s: float = 5.0, what: str = "condition"):
    """Poll `predicate` every 5 ms until it returns something true, and return that; fail the
    test after `timeout_s`."""
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        value = predicate()
        if value:
            return value
        time.sleep(0.005)
    raise AssertionError(f"timed out waiting for {what}")


def free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return sock.getsockname()[1]


@dataclass
class RunningProcess:
    """A real service (or launcher) process with its output collected."""

    process: subprocess.Popen
    lines: list[str] = field(default_factory=list)
    ready: dict[str, str] = field(default_factory=dict)  # service name -> host:port

    def wait_ready(self, names: list[str], timeout_s: float = 60.0) -> None:
        deadline = time.monotonic() + timeout_s
        while time.monotonic() < deadline:
            if all(name in self.ready for name in names):
                return
            if self.process.poll() is not None:
                break
            time.sleep(0.02)
        output = "\n".join(self.lines[-40:])
        raise AssertionError(f"{names} not ready (exit {self.process.poll()}):\n{output}")

    def stop(self, sig: int = signal.SIGTERM, timeout_s: float = 10.0) -> int:
        if self.process.poll() is None:
            self.process.send_signal(sig)
        return self.process.wait(timeout_s)


def start_process(args: list[str], env: dict[str, str] | None = None) -> RunningProcess:
    """Start `python <args>` from the repo root, merging stderr into the collected lines."""
    process = subprocess.Popen(
        [sys.executable, *args], cwd=REPO, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
        text=True, env={**os.environ, "PYTHONUNBUFFERED": "1", **(env or {})},
    )
    running = RunningProcess(process)

    def pump():
        for line in process.stdout:
            line = line.rstrip("\n")
            running.lines.append(line)
            if line.startswith(READY_LINE_PREFIX):
                _, name, address = line.split()
                running.ready[name] = address

    threading.Thread(target=pump, daemon=True).start()
    return running


@pytest.fixture
def service_process():
    """Factory: start `python -m services.<name>` on a free port and wait until SERVING."""
    started: list[RunningProcess] = []

    def start(name: str) -> str:
        running = start_process(["-m", f"services.{name}", "--address", f"127.0.0.1:{free_port()}"])
        started.append(running)
        running.wait_ready([name])
        return running.ready[name]

    yield start
    for running in started:
        if running.process.poll() is None:
            running.stop()


@pytest.fixture(scope="session")
def world():
    """One real world process for the tests that drive or read the simulated arm."""
    from tests.world.conftest import _cleanup, start_world  # tests/world imports this module

    running = start_world()
    yield running
    _cleanup(running)


@dataclass
class Backends:
    processes: list[RunningProcess]
    proxy_address: str
    sensor_address: str
    emergency_address: str


@pytest.fixture(scope="session")
def backends(world):
    """Real ProxyRobot, ForceSensor and emergency-stop band processes on the shared world, for
    the tests that put a DecisionServer or a client in front of them."""
    env = {"TELEROBOT_WORLD_SHM": world.shm_name}
    names = ["proxy_robot", "force_sensor", "emergency_stop"]
    running = [start_process(["-m", f"services.{name}", "--address",
                              f"127.0.0.1:{free_port()}"], env) for name in names]
    for process, name in zip(running, names, strict=True):
        process.wait_ready([name])
    yield Backends(running, *(process.ready[name]
                              for process, name in zip(running, names, strict=True)))
    for process in running:
        process.stop()
