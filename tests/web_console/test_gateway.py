"""The console's gateway without a browser: the Connect protocol's status codes for bad input,
the contracts' errors carried through, and the Teleoperate and receipts WebSockets' rules."""

from __future__ import annotations

import json
import urllib.error
import urllib.request

import pytest
from websockets.exceptions import ConnectionClosed, InvalidStatus
from websockets.sync.client import connect

from telerobot.v1 import decision_server_pb2 as ds
from telerobot.v1 import types_pb2
from telerobot.v1.stereo_camera_pb2 import ReportReceiptRequest

pytestmark = pytest.mark.e2e


def post(url: str, body: bytes, content_type: str = "application/json",
         headers: dict[str, str] | None = None) -> tuple[int, bytes]:
    request = urllib.request.Request(url, data=body, method="POST",
                                     headers={"content-type": content_type, **(headers or {})})
    try:
        with urllib.request.urlopen(request, timeout=10) as reply:
            return reply.status, reply.read()
    except urllib.error.HTTPError as error:
        return error.code, error.read()


def get(url: str) -> tuple[int, bytes]:
    try:
        with urllib.request.urlopen(url, timeout=10) as reply:
            return reply.status, reply.read()
    except urllib.error.HTTPError as error:
        return error.code, error.read()


def test_page_assets_and_health(console_url):
    status, page = get(console_url + "/")
    assert status == 200 and b'src="/app.js"' in page
    assert b"{{AUTH}}" not in page and b'content="none"' in page  # plaintext station: no token
    assert get(console_url + "/app.js")[0] == 200
    assert get(console_url + "/healthz") == (200, b"SERVING\n")
    assert get(console_url + "/../pyproject.toml")[0] == 404
    assert get(console_url + "/nothing-here")[0] == 404
    assert post(console_url + "/", b"")[0] == 405


def test_unary_calls_in_json_and_binary(console_url):
    status, body = post(console_url + "/telerobot.v1.DecisionServer/GetControlState", b"{}")
    assert status == 200 and "state" in json.loads(body)
    status, body = post(console_url + "/telerobot.v1.DecisionServer/GetDependencies",
                        ds.GetDependenciesRequest().SerializeToString(), "application/proto")
    assert status == 200
    names = {d.name for d in ds.GetDependenciesResponse.FromString(body).dependencies}
    assert {"proxy_robot", "force_sensor", "stereo_camera"} <= names


@pytest.mark.parametrize("path, body, content_type, http_status, code", [
    # Undecodable input is the caller's error.
    ("DecisionServer/AcquireControl", b'{"operator_id": ', "application/json", 400,
     "invalid_argument"),
    ("DecisionServer/AcquireControl", b"\xff\xff\xff", "application/proto", 400,
     "invalid_argument"),
    ("DecisionServer/AcquireControl", b'{"no_such_field": 1}', "application/json", 400,
     "invalid_argument"),
    # The DecisionServer's own checks, carried through with its status and message.
    ("DecisionServer/AcquireControl", b'{"operator_id": "x", "mode": 7}', "application/json",
     400, "invalid_argument"),
    ("ProxyRobot/MoveJointsIncremental", b'{"delta_joint_positions_rad": [0.01,0,0,0,0,0]}',
     "application/json", 400, "failed_precondition"),  # no lease
])
def test_bad_calls_get_the_right_status(console_url, path, body, content_type, http_status,
                                        code):
    status, reply = post(f"{console_url}/telerobot.v1.{path}", body, content_type)
    assert status == http_status, reply
    error = json.loads(reply)
    assert error["code"] == code and error["message"]


def test_unknown_methods_and_media_types(console_url):
    assert post(console_url + "/telerobot.v1.DecisionServer/NoSuchMethod", b"{}")[0] == 404
    assert post(console_url + "/telerobot.v1.DecisionServer/GetControlState", b"{}",
                "text/plain")[0] == 415


def test_the_lock_error_names_its_reason(console_url):
    # A move without the lock: FAILED_PRECONDITION with the contracts' ErrorInfo detail.
    status, reply = post(console_url + "/telerobot.v1.ProxyRobot/MoveJointsIncremental",
                         b'{"delta_joint_positions_rad": [0.01,0,0,0,0,0]}')
    details = json.loads(reply).get("details", [])
    assert status == 400 and any(d["type"] == "google.rpc.ErrorInfo" for d in details)


def ws_url(console_url: str) -> str:
    return console_url.replace("http://", "ws://") + "/ws/teleoperate"


def test_teleoperate_socket_refuses_other_origins(console_url):
    with pytest.raises(InvalidStatus) as refused:
        connect(ws_url(console_url), origin="http://evil.example",
                subprotocols=["telerobot.v1.teleoperate"], open_timeout=10)
    assert refused.value.response.status_code == 403
    with pytest.raises(InvalidStatus):  # the contract's subprotocol is required
        connect(ws_url(console_url), origin=console_url, open_timeout=10)


def test_teleoperate_socket_rules(console_url):
    origin = console_url
    with connect(ws_url(console_url), origin=origin, subprotocols=["telerobot.v1.teleoperate"],
                 open_timeout=10) as socket:
        assert socket.subprotocol == "telerobot.v1.teleoperate"
        socket.send("not a protobuf message")
        with pytest.raises(ConnectionClosed):
            socket.recv(timeout=10)
        assert socket.close_code == 1003
    # An init without a lease: the DecisionServer ends the stream, FAILED_PRECONDITION (9).
    init = ds.TeleoperateRequest(init=ds.TeleoperateInit(
        operator_id="nobody", lease_id="no-such-lease", mapping=types_pb2.REFERENCE_FRAME_BASE))
    with connect(ws_url(console_url), origin=origin, subprotocols=["telerobot.v1.teleoperate"],
                 open_timeout=10) as socket:
        socket.send(init.SerializeToString())
        with pytest.raises(ConnectionClosed):
            while True:
                socket.recv(timeout=10)
        assert socket.close_code == 4000 + 9, (socket.close_code, socket.close_reason)
        assert socket.close_reason


def receipts_url(console_url: str) -> str:
    return console_url.replace("http://", "ws://") + "/ws/receipts"


def test_receipts_socket_rules(console_url):
    with pytest.raises(InvalidStatus) as refused:
        connect(receipts_url(console_url), origin="http://evil.example",
                subprotocols=["telerobot.v1.receipts"], open_timeout=10)
    assert refused.value.response.status_code == 403
    with pytest.raises(InvalidStatus):  # its subprotocol is required
        connect(receipts_url(console_url), origin=console_url, open_timeout=10)
    with connect(receipts_url(console_url), origin=console_url,
                 subprotocols=["telerobot.v1.receipts"], open_timeout=10) as socket:
        assert socket.subprotocol == "telerobot.v1.receipts"
        # A receipt for a stream that has ended (NOT_FOUND upstream) is dropped, and the
        # socket stays open for the next: fire and forget, nothing comes back.
        socket.send(ReportReceiptRequest(stream_id="ended", sequence=1,
                                         received_bytes=10).SerializeToString())
        with pytest.raises(TimeoutError):
            socket.recv(timeout=1)
        socket.send("not a receipt")
        with pytest.raises(ConnectionClosed):
            socket.recv(timeout=10)
        assert socket.close_code == 1003
