"""python -m services.launcher (`make serve`): start the slave station, one process per service.

It starts every service in turn, each once the one before answers its health check with
SERVING (dependencies first), prints the
addresses, and supervises them. On Ctrl-C or SIGTERM it stops them all (SIGTERM, then SIGKILL
after a deadline) and exits. If a child dies on its own, the launcher says which and how, shows
its last log lines, and stops the whole station: a slave station with a part missing is not safe
to operate, and a supervisor above (systemd, a shell loop) can restart the group cleanly.

Children run in their own process group, so a terminal's Ctrl-C reaches only the launcher, which
then drains each child once; each child also stops by itself if the launcher is killed.
"""

from __future__ import annotations

import argparse
import collections
import logging
import os
import signal
import subprocess
import sys
import threading
import time
from dataclasses import dataclass, field

import grpc
from grpc_health.v1 import health_pb2, health_pb2_grpc

from services.runtime.config import DEFAULT_GRACE_S, address_for, configure_logging, env_name
from services.runtime.process import PARENT_PID_ENV, READY_LINE_PREFIX

log = logging.getLogger("launcher")

# Start order: dependencies first (the world stands in for the hardware). Stop order is the
# reverse, so the hardware goes last.
STATION = ["world", "emergency_stop", "proxy_robot", "force_sensor", "stereo_camera",
           "decision_server"]
STARTUP_TIMEOUT_S = 60.0
# The banner's first line: whoever starts a launcher (`make teleop`, the tests) waits for it.
UP_LINE = "Slave station is up"
_LOG_TAIL_LINES = 20


@dataclass
class Child:
    """One supervised service process."""

    name: str
    address: str
    process: subprocess.Popen
    ready: threading.Event = field(default_factory=threading.Event)
    log_tail: collections.deque = field(
        default_factory=lambda: collections.deque(maxlen=_LOG_TAIL_LINES))

    def describe_exit(self) -> str:
        code = self.process.returncode
        how = f"was killed by signal {-code}" if code < 0 else f"exited with code {code}"
        tail = "\n    ".join(self.log_tail) or "(no output)"
        return f"{self.name} ({self.address}) {how}; its last lines:\n    {tail}"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m services.launcher", description=__doc__)
    parser.add_argument("--grace-s", type=float, default=DEFAULT_GRACE_S,
                        help="how long each service may drain in-flight calls on stop")
    parser.add_argument("--log-level", default=os.environ.get("TELEROBOT_LOG_LEVEL", "INFO"))
    args = parser.parse_args(argv)
    configure_logging("launcher", args.log_level)

    stop = threading.Event()
    stop_reason: list[str] = []

    def on_signal(signum, _frame):
        stop_reason.append(signal.Signals(signum).name)
        stop.set()

    signal.signal(signal.SIGINT, on_signal)
    signal.signal(signal.SIGTERM, on_signal)

    children: list[Child] = []
    try:
        # One at a time: a service starts once the ones it depends on answer, so its first
        # calls to them do not fail and leave its channels backing off.
        for name in STATION:
            children.append(_start(name, args))
            failed = _wait_until_serving(children[-1:], stop)
            if failed:
                log.error("start-up failed: %s", failed)
                return 1
        if stop.is_set():
            return 0
        _print_banner(children)
        dead = _supervise(children, stop)
        if dead is not None:
            log.error("%s\nstopping the whole station (see the launcher's docstring for why)",
                      dead.describe_exit())
            return 1
        log.info("%s received; stopping the station", stop_reason[0] if stop_reason else "stop")
        return 0
    finally:
        _stop_all(children, args.grace_s)


def _start(name: str, args) -> Child:
    env = dict(os.environ, **{PARENT_PID_ENV: str(os.getpid()),
                              "TELEROBOT_GRACE_S": str(args.grace_s),
                              "PYTHONUNBUFFERED": "1"})
    process = subprocess.Popen(
        [sys.executable, "-m", f"services.{name}"],
        stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env,
        process_group=0,
    )
    child = Child(name, address_for(name), process)
    threading.Thread(target=_pump_output, args=(child,), name=f"out-{name}", daemon=True).start()
    return child


def _pump_output(child: Child) -> None:
    """Forward a child's output, keep its tail, and notice its ready line."""
    for line in child.process.stdout:
        line = line.rstrip("\n")
        if line.startswith(READY_LINE_PREFIX):
            child.ready.set()
            continue
        child.log_tail.append(line)
        print(line, file=sys.stderr, flush=True)


def _wait_until_serving(children: list[Child], stop: threading.Event) -> str | None:
    """None once every child answers SERVING; else why not."""
    deadline = time.monotonic() + STARTUP_TIMEOUT_S
    pending = list(children)
    while pending and not stop.is_set():
        for child in list(pending):
            if child.process.poll() is not None:
                return child.describe_exit()
            if child.ready.is_set() and _is_serving(child.address):
                log.info("%s is serving on %s", child.name, child.address)
                pending.remove(child)
        if time.monotonic() > deadline:
            names = ", ".join(c.name for c in pending)
            return f"{names} not serving after {STARTUP_TIMEOUT_S:.0f} s"
        stop.wait(0.05)
    return None


def _is_serving(address: str) -> bool:
    try:
        with grpc.insecure_channel(address) as channel:
            reply = health_pb2_grpc.HealthStub(channel).Check(
                health_pb2.HealthCheckRequest(service=""), timeout=1.0)
        return reply.status == health_pb2.HealthCheckResponse.SERVING
    except grpc.RpcError:
        return False


def _supervise(children: list[Child], stop: threading.Event) -> Child | None:
    """Wait for a stop request (None) or the first child that dies (that child)."""
    while not stop.wait(0.1):
        for child in children:
            if child.process.poll() is not None:
                child.ready.clear()
                return child
    return None


def _stop_all(children: list[Child], grace_s: float) -> None:
    """SIGTERM every live child (reverse start order), SIGKILL what outlives the deadline."""
    for child in reversed(children):
        if child.process.poll() is None:
            child.process.send_signal(signal.SIGTERM)
    deadline = time.monotonic() + grace_s + 1.5
    for child in reversed(children):
        try:
            child.process.wait(max(0.0, deadline - time.monotonic()))
        except subprocess.TimeoutExpired:
            log.warning("%s did not stop in time; killing it", child.name)
            child.process.kill()
            child.process.wait()


def _print_banner(children: list[Child]) -> None:
    operator = address_for("decision_server")
    width = max(len(c.name) for c in children)
    lines = ["", f"{UP_LINE}. Ctrl-C stops it.", ""]
    lines += [f"  {c.name:<{width}}  {c.address}  (pid {c.process.pid})" for c in children]
    lines += [
        "",
        f"The operator's address is {operator} (set {env_name('decision_server', 'address')} "
        "to move it). Try:",
        f"  grpcurl -plaintext {operator} list",
        f"  grpcurl -plaintext {operator} grpc.health.v1.Health/Check",
        "or, without grpcurl:",
        f"  npx buf curl --protocol grpc --http2-prior-knowledge --list-methods http://{operator}",
        "",
    ]
    print("\n".join(lines), flush=True)


if __name__ == "__main__":
    raise SystemExit(main())
