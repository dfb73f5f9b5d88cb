"""The live view refuses viewers from pages of other origins: any page in the user's browser
can open a WebSocket to 127.0.0.1:8765, and the browser tells the server only the page's
Origin. The SDK's server checks none, so the gate in front of it does (services.foxglove.live,
OriginGate); the SDK's server behind it speaks only TLS with a certificate no browser trusts.

In-process: a real SDK server behind a real gate, and a client of the Foxglove protocol that
sends the Origin a page would. The last test runs `python -m services.foxglove` itself."""

from __future__ import annotations

import socket
import ssl

import foxglove
import pytest
from websockets.exceptions import InvalidHandshake, InvalidStatus

from services.foxglove.live import LiveChannels
from services.foxglove.origin_gate import DEFAULT_ORIGINS, OriginGate, loopback_certificate
from tests.conftest import wait_for
from tests.foxglove.ws_client import FoxgloveClient
from tests.processes import refused_address, start_service
from wire import foxglove as fx

EXTRA_ORIGIN = "http://localhost:8080"  # one the operator allowed (--allowed-origin)
REFUSED = ["http://evil.localhost:8765", "https://evil.example", "null",
           "https://app.foxglove.dev.evil.example", "http://127.0.0.1:8080",
           "http://app.foxglove.dev"]
ALLOWED = [None, "https://app.foxglove.dev", "file://", "HTTPS://APP.FOXGLOVE.DEV/",
           EXTRA_ORIGIN]


class Gated:
    """An SDK server on loopback with the certificate the gate alone trusts, and its gate."""

    def __init__(self, tls: ssl.SSLContext | None = None, **limits):
        self.context = foxglove.Context()
        self.channels = LiveChannels(self.context)
        self.certificate, key = loopback_certificate()
        self.server = foxglove.start_server(name="gated", port=0, context=self.context,
                                            tls_cert=self.certificate, tls_key=key)
        self.gate = OriginGate(self.server.port, self.certificate,
                               [*DEFAULT_ORIGINS, EXTRA_ORIGIN], tls=tls, **limits)
        self.port = self.gate.start("127.0.0.1", 0)
        self.url = f"{'wss' if tls else 'ws'}://127.0.0.1:{self.port}"

    def close(self) -> None:
        self.gate.stop()
        self.server.stop()
        self.channels.close()


@pytest.fixture
def gated():
    served = Gated()
    yield served
    served.close()


@pytest.mark.parametrize("origin", ALLOWED)
def test_a_program_the_foxglove_app_and_the_allowed_origins_watch(gated, origin):
    with FoxgloveClient(gated.url, origin=origin) as client:
        client.wait_advertised([fx.JOINT_STATES])
        assert client.info["name"] == "gated"


@pytest.mark.parametrize("origin", REFUSED)
def test_a_page_of_another_origin_is_refused(gated, origin):
    with pytest.raises(InvalidStatus) as refused:
        FoxgloveClient(gated.url, origin=origin).close()
    assert refused.value.response.status_code == 403
    assert gated.gate.refused[origin] == 1


def test_two_origins_in_one_request_are_refused(gated):
    with socket.create_connection(("127.0.0.1", gated.port), timeout=10) as sock:
        sock.sendall(b"GET / HTTP/1.1\r\nHost: 127.0.0.1\r\nUpgrade: websocket\r\n"
                     b"Connection: Upgrade\r\nSec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\n"
                     b"Sec-WebSocket-Version: 13\r\nSec-WebSocket-Protocol: foxglove.sdk.v1\r\n"
                     b"Origin: https://app.foxglove.dev\r\nOrigin: https://evil.example\r\n\r\n")
        assert sock.recv(12) == b"HTTP/1.1 403"


def test_the_server_behind_the_gate_takes_no_plain_websocket_and_no_untrusted_tls(gated):
    """What a page that found the inner port could try: ws:// (no TLS), or wss:// with a
    browser's trust, which does not include the gate's certificate."""
    inner = f"127.0.0.1:{gated.server.port}"
    with pytest.raises((InvalidHandshake, ConnectionError)):
        FoxgloveClient(f"ws://{inner}").close()
    with pytest.raises(ssl.SSLCertVerificationError):
        FoxgloveClient(f"wss://{inner}", ssl=ssl.create_default_context()).close()
    # The gate's own trust does shake hands with it.
    trusting = ssl.create_default_context(cadata=gated.certificate.decode())
    with FoxgloveClient(f"wss://{inner}", ssl=trusting) as client:
        client.wait_advertised([fx.JOINT_STATES])


def test_with_the_tls_directory_the_gate_serves_wss_and_checks_origins_the_same(tmp_path):
    """The live view's own certificate (foxglove.pem in the TLS directory) is the gate's."""
    certificate, key = loopback_certificate()  # stands in for foxglove.pem and its key
    (tmp_path / "foxglove.pem").write_bytes(certificate)
    (tmp_path / "foxglove.key").write_bytes(key)
    tls = ssl.create_default_context(ssl.Purpose.CLIENT_AUTH)
    tls.load_cert_chain(tmp_path / "foxglove.pem", tmp_path / "foxglove.key")
    served = Gated(tls=tls)
    try:
        trusting = ssl.create_default_context(cadata=certificate.decode())
        with FoxgloveClient(served.url, ssl=trusting, origin="https://app.foxglove.dev") as c:
            c.wait_advertised([fx.JOINT_STATES])
        with pytest.raises(InvalidStatus) as refused:
            FoxgloveClient(served.url, ssl=trusting, origin="https://evil.example").close()
        assert refused.value.response.status_code == 403
        with pytest.raises(InvalidHandshake):  # plain ws:// gets no WebSocket upgrade
            FoxgloveClient(f"ws://127.0.0.1:{served.port}").close()
    finally:
        served.close()


def test_a_connection_that_sends_no_upgrade_is_closed_after_the_head_timeout():
    served = Gated(head_timeout_s=0.2)
    try:
        with socket.create_connection(("127.0.0.1", served.port)) as quiet:
            quiet.settimeout(10)
            assert quiet.recv(1) == b""
    finally:
        served.close()


def test_connections_beyond_the_viewers_limit_get_503():
    served = Gated(max_viewers=2)
    try:
        quiet = [socket.create_connection(("127.0.0.1", served.port)) for _ in range(2)]
        try:
            wait_for(lambda: len(served.gate._connections) == 2, 10, "two connections held")
            with pytest.raises(InvalidStatus) as refused:
                FoxgloveClient(served.url).close()
            assert refused.value.response.status_code == 503
        finally:
            for sock in quiet:
                sock.close()
        wait_for(lambda: not served.gate._connections, 10, "the quiet connections gone")
        FoxgloveClient(served.url).close()
    finally:
        served.close()


@pytest.mark.e2e
def test_the_live_view_process_refuses_other_origins_and_serves_programs():
    absent = refused_address()
    live = start_service("foxglove", "--proxy-robot", absent, "--force-sensor", absent,
                         "--stereo-camera", absent, "--allowed-origin", EXTRA_ORIGIN)
    try:
        url = f"ws://{live.address}"
        with pytest.raises(InvalidStatus) as refused:
            FoxgloveClient(url, origin="http://evil.localhost:8765").close()
        assert refused.value.response.status_code == 403
        for origin in (None, "https://app.foxglove.dev", EXTRA_ORIGIN):
            with FoxgloveClient(url, origin=origin) as client:
                client.wait_advertised([fx.JOINT_STATES])
    finally:
        live.stop()
