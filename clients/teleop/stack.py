"""Find the slave station, or start one: `make teleop` works on a fresh clone."""

from __future__ import annotations

import collections
import contextlib
import os
import signal
import subprocess
import sys
import threading
from collections.abc import Iterator

import grpc
from grpc_health.v1 import health_pb2, health_pb2_grpc

from services.launcher import UP_LINE

STARTUP_TIMEOUT_S = 90.0


def serving(address: str, timeout_s: float = 1.0) -> bool:
    try:
        with grpc.insecure_channel(address) as channel:
            reply = health_pb2_grpc.HealthStub(channel).Check(
                health_pb2.HealthCheckRequest(), timeout=timeout_s)
        return reply.status == health_pb2.HealthCheckResponse.SERVING
    except grpc.RpcError:
        return False


@contextlib.contextmanager
def station_at(address: str, log=print) -> Iterator[bool]:
    """Yield once a station answers at `address`; start a local one (and stop it after) if
    nothing does. Yields whether it started one."""
    if serving(address):
        yield False
        return
    log(f"nothing answers at {address}: starting a local slave station")
    launcher = subprocess.Popen(
        [sys.executable, "-m", "services.launcher"], stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT, text=True, process_group=0,
        env={**os.environ, "PYTHONUNBUFFERED": "1"})
    lines: collections.deque[str] = collections.deque(maxlen=40)
    up = threading.Event()

    def drain() -> None:  # keep reading, or the station blocks on a full pipe
        for line in launcher.stdout:
            lines.append(line.rstrip())
            if UP_LINE in line:
                up.set()

    threading.Thread(target=drain, name="station-log", daemon=True).start()
    try:
        up.wait(STARTUP_TIMEOUT_S)
        if not serving(address, 5.0):
            raise RuntimeError("the local station did not come up:\n" + "\n".join(lines))
        yield True
    finally:
        if launcher.poll() is None:
            launcher.send_signal(signal.SIGINT)
            try:
                launcher.wait(10)
            except subprocess.TimeoutExpired:
                launcher.kill()
