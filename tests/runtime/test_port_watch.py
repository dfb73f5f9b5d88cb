"""PortWatch: a port that accepts, then not, then again, against a socket of this test's own."""

from __future__ import annotations

import socket

from services.runtime.port_watch import OK, PortWatch, accepts
from tests.conftest import wait_for


def _free_port() -> int:
    with socket.create_server(("127.0.0.1", 0)) as probe:
        return probe.getsockname()[1]


def test_a_port_that_listens_is_ok_and_one_that_does_not_says_why():
    with socket.create_server(("127.0.0.1", 0)) as server:
        address = f"127.0.0.1:{server.getsockname()[1]}"
        assert accepts(address) == OK
    answer = accepts(address)
    assert answer.startswith("UNAVAILABLE: ") and address in answer
    assert "refused" in answer.lower()


def test_the_watch_follows_the_port_going_and_coming_back():
    port = _free_port()
    address = f"127.0.0.1:{port}"
    server = socket.create_server(("127.0.0.1", port))
    watch = PortWatch(address, period_s=0.05).start()
    try:
        assert watch.answer() == OK  # the first answer is there once started
        server.close()
        wait_for(lambda: watch.answer() != OK, 5, "the port gone")
        server = socket.create_server(("127.0.0.1", port))
        wait_for(lambda: watch.answer() == OK, 5, "the port back")
    finally:
        watch.close()
        server.close()
