"""Keepalives: a peer that stops answering (a hung process, a cut link) is noticed in seconds
on both sides, not after TCP's minutes; its streams end with UNAVAILABLE (a Teleoperate session
then holds the arm). Four pings a second, 750 ms to answer: within a second (#14)."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time

import grpc
import pytest
from grpc_health.v1 import health_pb2, health_pb2_grpc

from services.runtime.server import create_server
from tests.conftest import wait_for
from tests.processes import REPO
from wire.tls import open_channel

pytestmark = pytest.mark.e2e

# The keepalives' own bound is 1 s (a ping every 250 ms, 750 ms to answer). This test checks the
# mechanism, with slack for a loaded machine: far under the minutes TCP alone would take.
NOTICED_WITHIN_S = 3.0

# Each child runs until the test kills it (signal.pause: no timer to outlast).
_SERVE = """
import signal
from services.runtime.server import create_server
server, port = create_server("127.0.0.1:0", [])
server.start(); server.set_serving()
print(port, flush=True)
signal.pause()
"""
_WATCH = """
import signal, sys
from grpc_health.v1 import health_pb2, health_pb2_grpc
from wire.tls import open_channel
stream = health_pb2_grpc.HealthStub(open_channel(sys.argv[1])).Watch(
    health_pb2.HealthCheckRequest())
next(stream)
print("watching", flush=True)
signal.pause()
"""


def _python(code: str, *args: str) -> subprocess.Popen:
    return subprocess.Popen([sys.executable, "-c", code, *args], cwd=REPO, text=True,
                            stdout=subprocess.PIPE, env={**os.environ, "PYTHONPATH": str(REPO)})


@pytest.fixture
def hung():
    """Processes the test stopped: continued and killed after it."""
    stopped: list[subprocess.Popen] = []
    yield stopped
    for process in stopped:
        os.kill(process.pid, signal.SIGCONT)
        process.kill()
        process.wait(10)


def test_a_client_notices_a_hung_server(hung):
    server = _python(_SERVE)
    hung.append(server)
    port = int(server.stdout.readline())
    with open_channel(f"127.0.0.1:{port}") as channel:
        stream = health_pb2_grpc.HealthStub(channel).Watch(health_pb2.HealthCheckRequest())
        assert next(stream).status == health_pb2.HealthCheckResponse.SERVING
        os.kill(server.pid, signal.SIGSTOP)
        started = time.monotonic()
        with pytest.raises(grpc.RpcError) as failure:
            next(stream)
    assert failure.value.code() == grpc.StatusCode.UNAVAILABLE
    assert time.monotonic() - started < NOTICED_WITHIN_S


def test_a_server_notices_a_hung_client(hung):
    server, port = create_server("127.0.0.1:0", [])
    server.start()
    server.set_serving()
    try:
        client = _python(_WATCH, f"127.0.0.1:{port}")
        hung.append(client)
        assert client.stdout.readline().strip() == "watching"
        assert server.interceptor.open_streams == 1
        os.kill(client.pid, signal.SIGSTOP)
        started = time.monotonic()
        wait_for(lambda: server.interceptor.open_streams == 0, timeout_s=NOTICED_WITHIN_S,
                 what="the server to end the hung client's stream")
        assert time.monotonic() - started < NOTICED_WITHIN_S
    finally:
        server.stop(0)
