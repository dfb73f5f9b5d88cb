"""The plain HTTP and unauthenticated ports stay on loopback unless told otherwise: the
metrics (read-only), and the Foxglove live view (no client authentication)."""

from __future__ import annotations

import http.client
import socket
import threading

import pytest

from services.foxglove.__main__ import main as live_view
from services.runtime.metrics import METRICS_PATH, ServiceMetrics
from services.runtime.process import check_metrics_address
from services.runtime.server import PlaintextRefused
from tests.conftest import wait_for


@pytest.mark.parametrize("address", ["0.0.0.0:9100", "10.0.0.2:9100", "[::]:9100"])
def test_metrics_beyond_loopback_are_refused_unless_allowed(address):
    with pytest.raises(PlaintextRefused, match="--allow-metrics-network"):
        check_metrics_address(address, allow_network=False)
    check_metrics_address(address, allow_network=True)  # allowed: a warning, no refusal
    check_metrics_address("127.0.0.1:0", allow_network=False)
    check_metrics_address("off", allow_network=False)


def test_the_live_view_beyond_loopback_is_refused_unless_allowed(capsys, monkeypatch):
    monkeypatch.delenv("TELEROBOT_ALLOW_LIVE_VIEW_NETWORK", raising=False)
    assert live_view(["--address", "0.0.0.0:0"]) == 2
    assert "--allow-network" in capsys.readouterr().err


# -- the metrics endpoint: plain HTTP that anyone on its host reaches, before any check --------

def _scrape(port: int) -> tuple[int, bytes]:
    connection = http.client.HTTPConnection("127.0.0.1", port, timeout=10)
    try:
        connection.request("GET", METRICS_PATH)
        reply = connection.getresponse()
        return reply.status, reply.read()
    finally:
        connection.close()


@pytest.fixture
def metrics(request):
    served = ServiceMetrics(request.node.name)
    yield served
    served.close()


def handlers(metrics: ServiceMetrics) -> int:
    """The endpoint's handler threads alive (they are named after the service)."""
    return sum(t.name == f"metrics-{metrics.service}-handler" for t in threading.enumerate())


def test_a_metrics_client_that_connects_and_never_sends_is_closed_after_the_timeout(metrics):
    port = metrics.serve("127.0.0.1:0", timeout_s=0.2)
    with socket.create_connection(("127.0.0.1", port)) as quiet:
        quiet.settimeout(10)
        assert quiet.recv(1) == b""  # the server closed it, having waited 0.2 s for a request
    assert _scrape(port)[0] == 200


def test_metrics_connections_beyond_the_handlers_get_503_and_take_no_thread(metrics):
    port = metrics.serve("127.0.0.1:0", max_handlers=2)
    quiet = [socket.create_connection(("127.0.0.1", port)) for _ in range(2)]
    flood: list[socket.socket] = []
    try:
        wait_for(lambda: handlers(metrics) == 2, 10, "a handler thread for each quiet client")
        flood = [socket.create_connection(("127.0.0.1", port)) for _ in range(20)]
        for extra in flood:
            extra.settimeout(10)
            reply = b""
            while chunk := extra.recv(1024):
                reply += chunk
            assert reply.startswith(b"HTTP/1.1 503 "), reply
        assert handlers(metrics) == 2
    finally:
        for sock in quiet + flood:
            sock.close()
    wait_for(lambda: handlers(metrics) == 0, 10, "the handlers gone")
    status, body = _scrape(port)
    assert status == 200 and b"# HELP" in body
