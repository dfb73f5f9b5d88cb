"""Plain helpers (no fixtures) for the tests that start real processes: services on port 0
supervised by services.runtime.children (each reports the port it bound on its ready line),
worlds on segments of their own, whole stations through the launcher.

Only tests marked e2e may use them: tests/conftest.py refuses any other test that starts a
process. The fixtures built on them live in tests/conftest.py and tests/world/conftest.py."""

from __future__ import annotations

import os
import signal
import subprocess
import urllib.request
import uuid
from dataclasses import dataclass
from pathlib import Path

import grpc
from prometheus_client.parser import text_string_to_metric_families

from services.runtime import children
from services.runtime.children import Child
from services.runtime.children import refused_address as refused_address  # for the tests
from services.world.shm_layout import SHM_NAME_ENV

REPO = Path(__file__).resolve().parent.parent
BUF = REPO / "node_modules" / ".bin" / "buf"
SHM_DIR = Path("/dev/shm")  # where Linux keeps POSIX shared memory

# A started process: .process, .lines, .ready (name -> host:port), .wait_ready(names),
# .wait_line(text), .stop(sig), .describe(); see services.runtime.children.Child.
RunningProcess = Child
# refused_address() (imported above, for the tests too): host:port where connections are
# refused, for a dependency deliberately absent; held by this process and never listened on.
STOP_GRACE_S = 10.0  # a test's process gets this long to stop on SIGTERM before SIGKILL


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


# -- worlds: `python -m services.world` on segments of their own ----------------------------

def unique_shm_name() -> str:
    return f"telerobot_test_{uuid.uuid4().hex[:12]}"


def segment_exists(name: str) -> bool:
    return (SHM_DIR / name).exists()


@dataclass
class World:
    """A running world process and the segment it publishes on."""

    running: RunningProcess
    shm_name: str

    @property
    def pid(self) -> int:
        return self.running.process.pid

    def output(self) -> str:
        return "\n".join(self.running.lines[-40:])


def start_world(shm_name: str | None = None) -> World:
    """Start a world on a fresh segment and wait for its ready line."""
    name = shm_name or unique_shm_name()
    running = start_process(["-m", "services.world", "--address", "127.0.0.1:0"],
                            env={SHM_NAME_ENV: name})
    running.wait_ready(["world"], timeout_s=60.0)
    return World(running, name)


def stop_world(world: World) -> None:
    """Stop a world (if it still runs) and remove its segment."""
    if world.running.process.poll() is None:
        world.running.stop()
    # Only after a kill: never leave segments behind (the killed world's resource tracker may
    # be removing it at the same moment).
    (SHM_DIR / world.shm_name).unlink(missing_ok=True)


# -- a whole station through the launcher ---------------------------------------------------

def station_env(**settings: str) -> dict[str, str]:
    """Every service on port 0 (the launcher reports the ports bound), a shared-memory segment
    of this station's own so stations never collide, and `settings` (TELEROBOT_* variables)."""
    from services.launcher import STATION

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


def scrape_metrics(address: str) -> dict[tuple[str, frozenset], float]:
    """Every sample of a service's /metrics at `address`, parsed by prometheus_client's own
    parser: (sample name, its labels) -> value."""
    with urllib.request.urlopen(f"http://{address}/metrics", timeout=10) as reply:
        text = reply.read().decode()
    return {(sample.name, frozenset(sample.labels.items())): sample.value
            for family in text_string_to_metric_families(text) for sample in family.samples}
