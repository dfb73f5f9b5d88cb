"""Helpers shared by the tests: real service processes on port 0, supervised by
services.runtime.children (each reports the port it bound on its ready line)."""

from __future__ import annotations

import os
import signal
import subprocess
import time
from dataclasses import dataclass
from pathlib import Path

import grpc
import pytest

# MuJoCo picks its GL backend at import: headless rendering needs EGL, set before any test
# module imports mujoco (make does it too, but a bare `pytest` should work the same).
os.environ.setdefault("MUJOCO_GL", "egl")

from services.runtime import children
from services.runtime.children import Child
from services.runtime.children import refused_address as refused_address  # for the tests

REPO = Path(__file__).resolve().parent.parent
BUF = REPO / "node_modules" / ".bin" / "buf"

# A started process: .process, .lines, .ready (name -> host:port), .wait_ready(names),
# .wait_line(text), .stop(sig), .describe(); see services.runtime.children.Child.
RunningProcess = Child
# refused_address() (imported above, for the tests too): host:port where connections are
# refused, for a dependency deliberately absent; held by this process and never listened on.
STOP_GRACE_S = 10.0  # a test's process gets this long to stop on SIGTERM before SIGKILL


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


def start_process(args: list[str], env: dict[str, str] | None = None,
                  name: str | None = None) -> Child:
    """Start `python <args>` from the repo root, every output line kept (stderr merged)."""
    if name is None:
        name = args[1].rsplit(".", 1)[-1] if args[:1] == ["-m"] else "python"
    return children.start(name, args, env=env, cwd=REPO, own_group=False, max_lines=None,
                          stop_grace_s=STOP_GRACE_S)


def start_service(name: str, *args: str, env: dict[str, str] | None = None) -> Child:
    """`python -m services.<name>` on 127.0.0.1:0 (plus `args`), once it printed its ready
    line; its address is `.address`."""
    running = start_process(["-m", f"services.{name}", "--address", "127.0.0.1:0", *args],
                            env, name)
    try:
        running.wait_ready(timeout_s=60.0)
    except children.ChildFailed:
        running.stop()
        raise
    return running


@pytest.fixture
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
def world():
    """One real world process for the tests that drive or read the simulated arm."""
    from tests.world.conftest import _cleanup, start_world  # tests/world imports this module

    running = start_world()
    yield running
    _cleanup(running)


@dataclass
class Backends:
    processes: list[Child]
    proxy_address: str
    sensor_address: str
    emergency_address: str


@pytest.fixture(scope="session")
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


# -- a whole station through the launcher (e2e) ---------------------------------------------

def station_env(**settings: str) -> dict[str, str]:
    """Every service on port 0 (the launcher reports the ports bound), a shared-memory segment
    of this station's own so stations never collide, and `settings` (TELEROBOT_* variables)."""
    from services.launcher import STATION
    from tests.world.conftest import unique_shm_name

    env = {f"TELEROBOT_{name.upper()}_ADDRESS": "127.0.0.1:0" for name in STATION}
    env["TELEROBOT_WORLD_SHM"] = unique_shm_name()
    env.update(settings)
    return env


def start_station(env: dict[str, str]) -> Child:
    """The real launcher, once it reported every service's address and said the station is
    up; `.ready` maps each service to its address."""
    from services.launcher import STATION, UP_LINE

    launcher = start_process(["-m", "services.launcher", "--grace-s", "1"], env=env)
    try:
        launcher.wait_ready(STATION, timeout_s=90)
        launcher.wait_line(UP_LINE, timeout_s=10)
    except Exception:
        launcher.stop(signal.SIGINT)
        raise
    return launcher


def pid_alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    # A zombie still answers kill(0); it is gone for our purposes once its parent reaped it.
    with open(f"/proc/{pid}/stat") as stat:
        return stat.read().split()[2] != "Z"


def child_pids(pid: int) -> list[int]:
    """The pids of a process's children now."""
    out = subprocess.run(["pgrep", "-P", str(pid)], capture_output=True, text=True).stdout
    return [int(p) for p in out.split()]


def service_pid(launcher: Child, name: str) -> int | None:
    """The pid of the launcher's child running services.<name> now (None between a death and
    its restart)."""
    for pid in child_pids(launcher.process.pid):
        try:
            with open(f"/proc/{pid}/cmdline") as cmdline:
                if f"services.{name}" in cmdline.read():
                    return pid
        except FileNotFoundError:
            continue
    return None


def health_serving(address: str) -> bool:
    """Whether the server at `address` (plaintext) says SERVING within a second."""
    from grpc_health.v1 import health_pb2, health_pb2_grpc

    try:
        with grpc.insecure_channel(address) as channel:
            reply = health_pb2_grpc.HealthStub(channel).Check(health_pb2.HealthCheckRequest(),
                                                              timeout=1)
        return reply.status == health_pb2.HealthCheckResponse.SERVING
    except grpc.RpcError:
        return False


def restarted(launcher: Child, name: str, old_pid: int) -> int | None:
    """The new pid of `name` once the launcher restarted it and it serves; None before."""
    pid = service_pid(launcher, name)
    if pid is None or pid == old_pid or not health_serving(launcher.ready[name]):
        return None
    return pid
