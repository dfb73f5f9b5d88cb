"""The web console over HTTPS: with its certificate in the station's TLS directory it serves
HTTPS, so it may listen beyond loopback without --allow-plaintext-network, and a browser signs
in with a bearer token.

- A TLS station through the launcher, its console on 0.0.0.0: headless Chromium, trusting the
  development CA's certificates by their public keys, loads the page over HTTPS, signs in with
  an operator's token, takes the lock and drives the arm up; a Chromium that does not trust
  them gets a certificate error, and plain HTTP to the HTTPS port gets no answer.
- The Host and Origin checks (DNS rebinding) hold with https origins.
- In this process: a renewed certificate serves from the next connection on, a TLS handshake
  that does not come ends the connection, and HTTP beyond loopback is still refused without
  the console's certificate.
"""

from __future__ import annotations

import base64
import contextlib
import hashlib
import http.client
import json
import signal
import socket
import ssl
import threading
import time
import urllib.error
import urllib.request
from pathlib import Path

import pytest
from cryptography import x509
from cryptography.hazmat.primitives import serialization

from services.runtime.server import PlaintextRefused
from services.security.pki import LOOPBACK_NAMES, issue
from services.security.pki import init as init_pki
from services.security.roles import Role
from services.security.tokens import TokenStore
from services.web_console import teleoperate
from services.web_console.__main__ import ConsoleServer, check_listening, server_config
from services.web_console.https import RenewingCertificate, certificate_files
from telerobot.v1 import proxy_robot_pb2_grpc
from tests.conftest import starts_processes, wait_for
from tests.processes import start_station, station_env
from tests.web_console.conftest import CAMERA_SETTINGS, CHROMIUM, CHROMIUM_ARGS
from tests.web_console.test_limits import console
from wire.tls import ChannelSecurity, open_channel

_TIMEOUT_S = 10.0


def issue_console_certificate(pki: Path) -> None:
    """The console's certificate again, as `make certs` issues it: a server certificate of
    the station's CA for the loopback names, and no client identity."""
    issue(pki, "web_console", Role.OBSERVER, LOOPBACK_NAMES, client=False)


def verifying(pki: Path) -> ssl.SSLContext:
    """A client's context that trusts the station's CA alone and checks the host name."""
    return ssl.create_default_context(cafile=str(pki / "ca.pem"))


def request(url: str, pki: Path, body: bytes | None = None,
            headers: dict[str, str] | None = None) -> tuple[int, bytes]:
    sent = urllib.request.Request(url, data=body, method="POST" if body is not None else "GET",
                                  headers={"content-type": "application/json", **(headers or {})})
    try:
        with urllib.request.urlopen(sent, timeout=_TIMEOUT_S, context=verifying(pki)) as reply:
            return reply.status, reply.read()
    except urllib.error.HTTPError as error:
        return error.code, error.read()


def spki_hash(certificate_pem: Path) -> str:
    """Chromium's name for a public key: base64 of the SHA-256 of its SubjectPublicKeyInfo."""
    key = x509.load_pem_x509_certificate(certificate_pem.read_bytes()).public_key()
    der = key.public_bytes(serialization.Encoding.DER,
                           serialization.PublicFormat.SubjectPublicKeyInfo)
    return base64.b64encode(hashlib.sha256(der).digest()).decode()


def served_certificate(port: int, pki: Path) -> x509.Certificate:
    with socket.create_connection(("127.0.0.1", port), timeout=_TIMEOUT_S) as raw, \
            verifying(pki).wrap_socket(raw, server_hostname="127.0.0.1") as tls:
        return x509.load_der_x509_certificate(tls.getpeercert(binary_form=True))


# -- a TLS station, its console on every address ------------------------------------------

@pytest.fixture(scope="module")
@starts_processes
def https_station(tmp_path_factory):
    root = tmp_path_factory.mktemp("https-console")
    pki = root / "pki"
    init_pki(pki)  # the console's certificate among the others
    operator = TokenStore(root / "tokens.json").issue("web-operator", Role.OPERATOR, 3600)
    launcher = start_station(station_env(
        TELEROBOT_TLS_DIR=str(pki), TELEROBOT_TOKENS_FILE=str(root / "tokens.json"),
        TELEROBOT_DECISION_SERVER_TOKEN_ADDRESS="127.0.0.1:0",
        TELEROBOT_AUDIT_DIR=str(root / "audit"),
        TELEROBOT_RECORDINGS_DIR=str(root / "recordings"),
        TELEROBOT_WEB_CONSOLE_ADDRESS="0.0.0.0:0",  # beyond loopback, with no plaintext flag
        TELEROBOT_ALLOW_PLAINTEXT_NETWORK="0", **CAMERA_SETTINGS))
    port = int(launcher.ready["web_console"].rsplit(":", 1)[1])
    yield launcher, f"https://127.0.0.1:{port}", port, pki, operator
    launcher.stop(signal.SIGINT)


@pytest.mark.e2e
def test_the_console_serves_https_on_every_address_with_its_certificate(https_station):
    launcher, url, port, pki, _ = https_station
    assert launcher.ready["web_console"].startswith("0.0.0.0:")  # no plaintext flag needed
    status, page = request(url + "/", pki)
    assert status == 200 and b'content="token"' in page  # the page asks for a token
    subject = served_certificate(port, pki).subject
    assert subject.get_attributes_for_oid(x509.NameOID.COMMON_NAME)[0].value == "web_console"
    assert f"The web console: https://127.0.0.1:{port}/" in "\n".join(launcher.lines)


@pytest.mark.e2e
def test_plain_http_to_the_https_port_gets_no_answer(https_station):
    _, _, port, _, _ = https_station
    with pytest.raises(OSError):  # no response at all (http.client's RemoteDisconnected)
        urllib.request.urlopen(f"http://127.0.0.1:{port}/healthz", timeout=_TIMEOUT_S)
    with socket.create_connection(("127.0.0.1", port), timeout=_TIMEOUT_S) as raw:
        raw.sendall(b"GET /healthz HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n")
        answer = b""
        with contextlib.suppress(ConnectionResetError):
            while chunk := raw.recv(4096):
                answer += chunk
    assert not answer.startswith(b"HTTP/"), answer[:80]


@pytest.mark.e2e
def test_names_and_origins_are_checked_with_https_origins(https_station):
    _, url, port, pki, operator = https_station
    method = url + "/telerobot.v1.DecisionServer/GetControlState"
    token = {"authorization": f"Bearer {operator}"}
    assert request(method, pki, b"{}", {**token, "origin": url})[0] == 200  # its own page
    assert request(method, pki, b"{}", token)[0] == 200  # a program: no Origin
    status, reply = request(method, pki, b"{}",
                            {**token, "origin": f"https://evil.example:{port}"})
    assert status == 403, reply
    status, reply = request(method, pki, b"{}", {**token, "host": f"evil.localhost:{port}",
                                                 "origin": f"https://evil.localhost:{port}"})
    assert status == 403 and b"evil.localhost" in reply, reply

    protocols = f"{teleoperate.SUBPROTOCOL}, bearer.{operator}"
    status, headers = websocket_upgrade(port, pki, url, protocols)
    assert status == 101 and headers["sec-websocket-protocol"] == teleoperate.SUBPROTOCOL
    status, _ = websocket_upgrade(port, pki, f"https://evil.example:{port}", protocols)
    assert status == 403


def websocket_upgrade(port: int, pki: Path, origin: str, protocols: str
                      ) -> tuple[int, dict[str, str]]:
    """The console's answer to a WebSocket upgrade of /ws/teleoperate over TLS: its status and
    headers. (A raw request: websockets' sync client over TLS now and then never saw a 101 the
    console had sent, on a loaded machine.)"""
    key = base64.b64encode(b"sixteen byte key").decode()
    with socket.create_connection(("127.0.0.1", port), timeout=_TIMEOUT_S) as raw, \
            verifying(pki).wrap_socket(raw, server_hostname="127.0.0.1") as tls:
        tls.sendall((f"GET {teleoperate.PATH} HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n"
                     "Upgrade: websocket\r\nConnection: Upgrade\r\n"
                     f"Sec-WebSocket-Key: {key}\r\nSec-WebSocket-Version: 13\r\n"
                     f"Origin: {origin}\r\nSec-WebSocket-Protocol: {protocols}\r\n\r\n"
                     ).encode())
        head = b""
        while b"\r\n\r\n" not in head:
            chunk = tls.recv(4096)
            assert chunk, f"the console closed the connection after {head!r}"
            head += chunk
    status_line, *lines = head.split(b"\r\n\r\n")[0].decode("latin-1").split("\r\n")
    headers = dict(line.split(": ", 1) for line in lines)
    return int(status_line.split()[1]), {name.lower(): value for name, value in headers.items()}


@pytest.fixture
def chromium(playwright_driver, tmp_path):
    """Launches a Chromium with extra flags, on the session's one Playwright driver (a second
    sync driver in the same thread finds the first one's event loop running)."""
    def launch(*extra: str):
        return playwright_driver.chromium.launch_persistent_context(
            str(tmp_path / f"profile-{len(extra)}"), executable_path=CHROMIUM,
            args=[*CHROMIUM_ARGS, *extra], headless=True,
            viewport={"width": 1400, "height": 1000})
    return launch


@pytest.mark.e2e
@pytest.mark.slow
def test_chromium_signs_in_over_https_takes_the_lock_and_drives(https_station, chromium):
    from tests.web_console.test_browser import (
        DEADLINE_S,
        open_console,
        ready_arm,
        start_driving,
        take_lock,
        text,
        tool_z,
    )

    launcher, url, port, pki, operator = https_station
    untrusting = chromium()
    try:
        with pytest.raises(Exception, match="ERR_CERT_AUTHORITY_INVALID"):
            untrusting.new_page().goto(url + "/")  # the development CA is nobody's by default
    finally:
        untrusting.close()

    # Trust the station's CA and the console's certificate by their public keys (headless
    # Chromium reads no certificate store of ours).
    keys = ",".join(spki_hash(pki / name) for name in ("ca.pem", "web_console.pem"))
    browser = chromium(f"--ignore-certificate-errors-spki-list={keys}")
    try:
        page = open_console(browser, url + "/")
        assert page.evaluate("location.protocol") == "https:"
        with pytest.raises(Exception, match="ERR_EMPTY_RESPONSE|ERR_CONNECTION"):
            browser.new_page().goto(f"http://127.0.0.1:{port}/")  # no HTTP on the HTTPS port
        assert not page.locator("#auth").is_hidden()  # a TLS station's page asks for a token
        page.fill("#token", operator)
        page.click("#token-set")
        wait_for(lambda: text(page, "#message") == "token set", timeout_s=DEADLINE_S,
                 what="the token taken")
        take_lock(page)
        security = ChannelSecurity(pki, "observer")
        with open_channel(launcher.ready["proxy_robot"], security=security,
                          service="proxy_robot") as channel:
            robot = proxy_robot_pb2_grpc.ProxyRobotStub(channel)
            ready_arm(page, robot)  # Connect and Initialize through the page, with its token
            start_driving(page)  # the Teleoperate socket, over wss://
            start = tool_z(robot)
            page.keyboard.down("r")
            wait_for(lambda: tool_z(robot) > start + 0.005, timeout_s=DEADLINE_S,
                     what=f"the arm to rise; page says {text(page, '#message')!r}")
            page.keyboard.up("r")
        page.click("#lock-release")
        assert page.errors == []
    finally:
        browser.close()
    audit = [json.loads(line) for f in (pki.parent / "audit").glob("decision_server*.jsonl")
             for line in f.read_text().splitlines()]
    assert any(r.get("identity") == "web-operator" and r.get("method", "").endswith(
        "/Teleoperate") for r in audit), audit[-5:]


# -- in this process ------------------------------------------------------------------------

@pytest.fixture(scope="module")
def pki(tmp_path_factory) -> Path:
    directory = tmp_path_factory.mktemp("pki") / "pki"
    init_pki(directory)
    return directory


@contextlib.contextmanager
def serving_https(certificate: RenewingCertificate, handshake_timeout_s: float = 10.0):
    """The console (its upstream refusing every call) served over HTTPS by ConsoleServer on a
    thread of this process; yields its port."""
    server = ConsoleServer(server_config(console(), "127.0.0.1", 0, certificate=certificate),
                           handshake_timeout_s=handshake_timeout_s)
    thread = threading.Thread(target=server.run, name="console", daemon=True)
    thread.start()
    try:
        wait_for(lambda: server.started or not thread.is_alive(), 10, "the console serving")
        assert server.started, "the console did not start"
        yield server.servers[0].sockets[0].getsockname()[1]
    finally:
        server.should_exit = True
        thread.join(10)


def healthz(port: int, pki: Path) -> int:
    connection = http.client.HTTPSConnection("127.0.0.1", port, timeout=_TIMEOUT_S,
                                             context=verifying(pki))
    try:
        connection.request("GET", "/healthz")
        return connection.getresponse().status
    finally:
        connection.close()


def test_a_renewed_certificate_serves_from_the_next_connection(pki, tmp_path):
    files = certificate_files(pki)
    assert files is not None
    own = tmp_path / "pki"  # a copy of the CA: the console's pair is renewed in it
    own.mkdir()
    for name in ("ca.pem", "ca.key", "web_console.pem", "web_console.key"):
        (own / name).write_bytes((pki / name).read_bytes())
    with serving_https(RenewingCertificate(*certificate_files(own))) as port:
        first = served_certificate(port, own).serial_number
        assert healthz(port, own) == 200
        issue_console_certificate(own)  # renewed: a new key and certificate, each by rename
        renewed = served_certificate(port, own).serial_number
        assert renewed != first
        # A renewal half done (a new key beside the last certificate) is not taken.
        stray = tmp_path / "stray"
        stray.mkdir()
        for name in ("ca.pem", "ca.key"):
            (stray / name).write_bytes((own / name).read_bytes())
        issue_console_certificate(stray)
        (own / "web_console.key").write_bytes((stray / "web_console.key").read_bytes())
        assert served_certificate(port, own).serial_number == renewed
        assert healthz(port, own) == 200


def test_a_tls_handshake_that_does_not_come_ends_the_connection(pki):
    with serving_https(RenewingCertificate(*certificate_files(pki)),
                       handshake_timeout_s=0.3) as port, \
            socket.create_connection(("127.0.0.1", port), timeout=_TIMEOUT_S) as silent:
        started = time.monotonic()
        assert silent.recv(1) == b""  # closed by the console, before our timeout
        assert time.monotonic() - started < _TIMEOUT_S / 2
        assert healthz(port, pki) == 200  # and others are served


def test_http_beyond_loopback_is_refused_without_the_consoles_certificate(tmp_path):
    bare = tmp_path / "pki"  # the station's PKI without the console's certificate
    init_pki(bare)
    (bare / "web_console.pem").unlink()
    assert certificate_files(bare) is None
    with pytest.raises(PlaintextRefused, match="over plain HTTP") as refused:
        check_listening("0.0.0.0:50080", str(bare), https=False, allow_plaintext_network=False)
    assert f"pki --dir {bare} --host" in str(refused.value)  # how to get one
    with pytest.raises(PlaintextRefused, match="make certs"):
        check_listening("10.0.0.2:50080", "", https=False, allow_plaintext_network=False)
    check_listening("0.0.0.0:50080", str(bare), https=True, allow_plaintext_network=False)
    check_listening("127.0.0.1:50080", "", https=False, allow_plaintext_network=False)
