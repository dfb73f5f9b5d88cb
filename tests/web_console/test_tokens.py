"""A TLS station with the DecisionServer's bearer-token port: the console forwards each
browser's token, so the DecisionServer's own roles and audit apply (an observer watches, an
operator drives), and the console itself decides nothing."""

from __future__ import annotations

import json
import signal

import pytest
from websockets.exceptions import ConnectionClosed
from websockets.sync.client import connect

from services.security.pki import init as init_pki
from services.security.roles import Role
from services.security.tokens import TokenStore
from telerobot.v1 import decision_server_pb2 as ds
from telerobot.v1.stereo_camera_pb2 import ReportReceiptRequest
from tests.processes import start_station, station_env
from tests.web_console.conftest import CAMERA_SETTINGS
from tests.web_console.test_gateway import get, post

pytestmark = [pytest.mark.e2e, pytest.mark.slow]


@pytest.fixture(scope="module")
def tls_console(tmp_path_factory):
    root = tmp_path_factory.mktemp("tls-console")
    init_pki(root / "pki")
    (root / "pki" / "web_console.pem").unlink()  # this console serves plain HTTP on loopback
    store = TokenStore(root / "tokens.json")
    tokens = {role: store.issue(f"web-{role.name.lower()}", role, 3600)
              for role in (Role.OBSERVER, Role.OPERATOR)}
    launcher = start_station(station_env(
        TELEROBOT_TLS_DIR=str(root / "pki"), TELEROBOT_TOKENS_FILE=str(root / "tokens.json"),
        TELEROBOT_DECISION_SERVER_TOKEN_ADDRESS="127.0.0.1:0",
        TELEROBOT_AUDIT_DIR=str(root / "audit"), **CAMERA_SETTINGS))
    yield f"http://{launcher.ready['web_console']}", tokens, root / "audit"
    launcher.stop(signal.SIGINT)


def call(url: str, method: str, body: dict, token: str | None = None,
         lease: str | None = None) -> tuple[int, dict]:
    headers = {"authorization": f"Bearer {token}"} if token else {}
    if lease:
        headers["telerobot-lease-id"] = lease
    status, reply = post(f"{url}/telerobot.v1.{method}", json.dumps(body).encode(),
                         headers=headers)
    return status, json.loads(reply)


def test_the_page_asks_for_a_token(tls_console):
    url, _, _ = tls_console
    status, page = get(url + "/")
    assert status == 200 and b'content="token"' in page


def test_no_token_or_a_forged_one_is_unauthenticated(tls_console):
    url, _, _ = tls_console
    for token in (None, "trb_forged"):
        status, error = call(url, "DecisionServer/GetControlState", {}, token)
        assert (status, error["code"]) == (401, "unauthenticated"), error


def test_an_observer_watches_but_does_not_drive(tls_console):
    url, tokens, _ = tls_console
    observer = tokens[Role.OBSERVER]
    status, state = call(url, "DecisionServer/GetControlState", {}, observer)
    assert status == 200, state
    status, error = call(url, "DecisionServer/AcquireControl",
                         {"operator_id": "x", "mode": "CONTROL_MODE_EXCLUSIVE"}, observer)
    assert (status, error["code"]) == (403, "permission_denied")
    assert "operator" in error["message"]  # names the role it needs


def test_an_operator_drives_as_its_token_identity(tls_console):
    url, tokens, audit = tls_console
    operator = tokens[Role.OPERATOR]
    status, lease = call(url, "DecisionServer/AcquireControl",
                         {"operator_id": "claimed-name", "mode": "CONTROL_MODE_EXCLUSIVE"},
                         operator)
    assert status == 200, lease
    assert lease["operatorId"] == "web-operator"  # the token's identity, not the claim
    for method in ("ProxyRobot/Connect", "ProxyRobot/Initialize"):  # with the lease header
        status, reply = call(url, method, {}, operator, lease["leaseId"])
        assert status == 200, reply
    # The Teleoperate socket carries the token as a subprotocol and the lease in its init.
    init = ds.TeleoperateRequest(init=ds.TeleoperateInit(operator_id="claimed-name",
                                                         lease_id=lease["leaseId"]))
    with connect(url.replace("http://", "ws://") + "/ws/teleoperate", origin=url,
                 subprotocols=["telerobot.v1.teleoperate", f"bearer.{operator}"],
                 open_timeout=10) as socket:
        socket.send(init.SerializeToString())
        ready = ds.TeleoperateResponse.FromString(socket.recv(timeout=10))
        assert ready.HasField("ready")
    # The socket closed: the stream ended. The DecisionServer audited it under the token's name.
    lines = [json.loads(line) for f in audit.glob("decision_server*.jsonl")
             for line in f.read_text().splitlines()]
    assert any(r.get("identity") == "web-operator" and "AcquireControl" in r.get("method", "")
               for r in lines), lines[-5:]
    status, _ = call(url, "DecisionServer/ReleaseControl", {"lease_id": lease["leaseId"]},
                     operator)
    assert status == 200


def test_the_socket_without_a_token_is_refused(tls_console):
    url, _, _ = tls_console
    with connect(url.replace("http://", "ws://") + "/ws/teleoperate", origin=url,
                 subprotocols=["telerobot.v1.teleoperate"], open_timeout=10) as socket:
        with pytest.raises(ConnectionClosed):
            socket.recv(timeout=10)
        assert socket.close_code == 4000 + 16, socket.close_reason  # UNAUTHENTICATED
        assert "token" in socket.close_reason


def test_the_receipts_socket_forwards_the_token(tls_console):
    url, tokens, _ = tls_console
    receipts = url.replace("http://", "ws://") + "/ws/receipts"
    receipt = ReportReceiptRequest(stream_id="ended", sequence=1, received_bytes=1)
    with connect(receipts, origin=url, subprotocols=["telerobot.v1.receipts"],
                 open_timeout=10) as socket:  # no token: refused at once
        with pytest.raises(ConnectionClosed):
            socket.recv(timeout=10)
        assert socket.close_code == 4000 + 16, socket.close_reason
    with connect(receipts, origin=url, subprotocols=["telerobot.v1.receipts", "bearer.trb_forged"],
                 open_timeout=10) as socket:  # the DecisionServer refuses a forged one
        socket.send(receipt.SerializeToString())
        with pytest.raises(ConnectionClosed):
            socket.recv(timeout=10)
        assert socket.close_code == 4000 + 16, socket.close_reason
    with connect(receipts, origin=url,
                 subprotocols=["telerobot.v1.receipts", f"bearer.{tokens[Role.OBSERVER]}"],
                 open_timeout=10) as socket:  # an observer's: NOT_FOUND, dropped, still open
        socket.send(receipt.SerializeToString())
        with pytest.raises(TimeoutError):
            socket.recv(timeout=1)
