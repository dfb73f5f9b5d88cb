"""A whole station with mutual TLS on loopback: who may call what, through every door.

One real station (the launcher, every service in its own process) runs with a development PKI
of the test's own, a bearer-token port on the DecisionServer, and an audit log in a temporary
directory. Each identity calls a representative RPC of every service, on the DecisionServer's
port and on each service's own (inner) port, and gets the code its role earns.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import time

import grpc
import pytest
from grpc_health.v1 import health_pb2, health_pb2_grpc

from services.runtime.process import token_port_name
from services.security.pki import init, issue
from services.security.roles import Role
from services.security.tokens import TokenStore
from telerobot.v1 import decision_server_pb2 as ds
from telerobot.v1 import (
    decision_server_pb2_grpc,
    force_sensor_pb2_grpc,
    proxy_robot_pb2_grpc,
    stereo_camera_pb2_grpc,
    types_pb2,
)
from telerobot.v1 import force_sensor_pb2 as fs
from telerobot.v1 import proxy_robot_pb2 as pr
from telerobot.v1 import stereo_camera_pb2 as sc
from tests.conftest import wait_for
from tests.processes import BUF, REPO, start_station, station_env
from wire.metadata import LEASE_METADATA_KEY
from wire.tls import ChannelSecurity, open_channel

pytestmark = pytest.mark.e2e

DENIED = {grpc.StatusCode.PERMISSION_DENIED, grpc.StatusCode.UNAUTHENTICATED}
# The identities of the station's PKI, and their roles.
IDENTITIES = {"observer": Role.OBSERVER, "operator": Role.OPERATOR,
              "decision_server": Role.STATION, "admin": Role.ADMIN}
STUBS = {"DecisionServer": decision_server_pb2_grpc.DecisionServerStub,
         "ProxyRobot": proxy_robot_pb2_grpc.ProxyRobotStub,
         "ForceSensor": force_sensor_pb2_grpc.ForceSensorStub,
         "StereoCamera": stereo_camera_pb2_grpc.StereoCameraStub}
# (port, service, method, request, least role there). The inner ports ask the STATION role for
# what the DecisionServer's port asks the OPERATOR or ADMIN role.
MATRIX = [
    ("decision_server", "DecisionServer", "GetControlState", ds.GetControlStateRequest(),
     Role.OBSERVER),
    ("decision_server", "DecisionServer", "RenewControl", ds.RenewControlRequest(lease_id="x"),
     Role.OPERATOR),
    ("decision_server", "DecisionServer", "DeleteRecording",
     ds.DeleteRecordingRequest(name="none"), Role.ADMIN),
    ("decision_server", "ProxyRobot", "GetState", pr.GetStateRequest(), Role.OBSERVER),
    ("decision_server", "ProxyRobot", "Hold", pr.HoldRequest(), Role.OPERATOR),
    ("proxy_robot", "ProxyRobot", "GetStatus", pr.GetStatusRequest(), Role.OBSERVER),
    ("proxy_robot", "ProxyRobot", "Hold", pr.HoldRequest(), Role.STATION),
    ("proxy_robot", "ProxyRobot", "SetToolFrame", pr.SetToolFrameRequest(), Role.STATION),
    ("force_sensor", "ForceSensor", "GetSensorConfig", fs.GetSensorConfigRequest(),
     Role.OBSERVER),
    ("force_sensor", "ForceSensor", "StopReading", fs.StopReadingRequest(), Role.STATION),
    ("force_sensor", "ForceSensor", "SetSensorConfig", fs.SetSensorConfigRequest(),
     Role.STATION),
    ("stereo_camera", "StereoCamera", "GetStreamInfo", sc.GetStreamInfoRequest(),
     Role.OBSERVER),
    ("emergency_stop", "ProxyRobot", "GetStatus", pr.GetStatusRequest(), Role.OBSERVER),
]


@pytest.fixture(scope="module")
def pki(tmp_path_factory):
    directory = tmp_path_factory.mktemp("pki")
    init(directory)
    issue(directory, "operator2", Role.OPERATOR)  # a second operator, to steal a lease
    return directory


@pytest.fixture(scope="module")
def tokens(tmp_path_factory):
    path = tmp_path_factory.mktemp("tokens") / "tokens.json"
    store = TokenStore(path)
    an_hour_ago = TokenStore(path, clock=lambda: time.time() - 3600)
    return {"path": path,
            "operator": store.issue("script", Role.OPERATOR, 600),
            "observer": store.issue("dashboard", Role.OBSERVER, 600),
            "expired": an_hour_ago.issue("old-script", Role.OPERATOR, 60)}


@pytest.fixture(scope="module")
def station(pki, tokens, tmp_path_factory):
    audit = tmp_path_factory.mktemp("audit")
    env = station_env(TELEROBOT_TLS_DIR=str(pki), TELEROBOT_AUDIT_DIR=str(audit),
                      TELEROBOT_TOKENS_FILE=str(tokens["path"]),
                      TELEROBOT_DECISION_SERVER_TOKEN_ADDRESS="127.0.0.1:0")
    launcher = start_station(env)
    try:
        # The arm ready, so that a stop has something to stop (an admin may go to the inner
        # port directly).
        address = dict(launcher.ready)
        with open_channel(address["proxy_robot"], security=ChannelSecurity(pki, "admin")) as ch:
            robot = proxy_robot_pb2_grpc.ProxyRobotStub(ch)
            robot.Connect(pr.ConnectRequest(), timeout=30)
            robot.Initialize(pr.InitializeRequest(), timeout=30)
        yield {"address": address, "audit": audit}
    finally:
        launcher.stop(signal.SIGINT)


def _channel(station, port: str, pki, identity: str = "operator", **security):
    return open_channel(station["address"][port],
                        security=ChannelSecurity(pki, identity, **security))


def _code(call, request, metadata=()) -> tuple[grpc.StatusCode, str]:
    try:
        call(request, timeout=10, metadata=metadata)
    except grpc.RpcError as error:
        return error.code(), error.details() or ""
    return grpc.StatusCode.OK, ""


@pytest.mark.parametrize("identity", IDENTITIES)
@pytest.mark.parametrize("port,service,method,request_,needed", MATRIX,
                         ids=[f"{m[0]}-{m[2]}" for m in MATRIX])
def test_each_role_gets_the_code_it_earns(station, pki, identity, port, service, method,
                                          request_, needed):
    with _channel(station, port, pki, identity) as channel:
        code, details = _code(getattr(STUBS[service](channel), method), request_)
    if IDENTITIES[identity] >= needed:
        assert code not in DENIED, (code, details)
    else:
        assert code == grpc.StatusCode.PERMISSION_DENIED, (code, details)
        assert f"needs the {needed.label} role" in details
        assert f"this identity is {IDENTITIES[identity].label}" in details


def test_a_certificate_from_another_ca_or_none_fails_the_handshake(station, pki, tmp_path):
    init(tmp_path / "foreign")
    address = station["address"]["decision_server"]
    attempts = {
        "foreign CA": ChannelSecurity(tmp_path / "foreign", "admin"),
        "no certificate": ChannelSecurity(pki, token="trb_not-a-client-certificate"),
        "plaintext": ChannelSecurity(),
    }
    for what, security in attempts.items():
        with open_channel(address, security=security) as channel:
            stub = health_pb2_grpc.HealthStub(channel)
            code, details = _code(stub.Check, health_pb2.HealthCheckRequest())
        assert code == grpc.StatusCode.UNAVAILABLE, (what, code, details)


def test_a_client_naming_the_service_it_dials_reaches_that_service_only(station, pki, tokens):
    """Every certificate of the station names the same hosts; each also names its service,
    and a client that asks for a service (open_channel's `service`) takes no other's."""
    ports = ("decision_server", "proxy_robot", "force_sensor", "stereo_camera", "emergency_stop")
    for port in ports:
        for service in ports:
            with open_channel(station["address"][port], security=ChannelSecurity(pki, "observer"),
                              service=service) as channel:
                code, details = _code(health_pb2_grpc.HealthStub(channel).Check,
                                      health_pb2.HealthCheckRequest())
            assert (code == grpc.StatusCode.OK) == (service == port), (port, service, details)
    # The token port presents the DecisionServer's certificate too.
    token_port = station["address"][token_port_name("decision_server")]
    with open_channel(token_port, security=ChannelSecurity(pki, token=tokens["observer"]),
                      service="decision_server") as channel:
        stub = decision_server_pb2_grpc.DecisionServerStub(channel)
        assert _code(stub.GetControlState, ds.GetControlStateRequest())[0] == grpc.StatusCode.OK


def test_a_lease_belongs_to_the_identity_that_took_it(station, pki):
    with _channel(station, "decision_server", pki, "operator") as mine, \
            _channel(station, "decision_server", pki, "operator2") as thief, \
            _channel(station, "decision_server", pki, "admin") as admin:
        owner = decision_server_pb2_grpc.DecisionServerStub(mine)
        granted = owner.AcquireControl(
            ds.AcquireControlRequest(operator_id="claims-to-be-admin",
                                     mode=ds.CONTROL_MODE_EXCLUSIVE), timeout=10)
        lease = granted.lease_id
        assert granted.operator_id == "operator"
        state = owner.GetControlState(ds.GetControlStateRequest(), timeout=10)
        assert [h.operator_id for h in state.state.holders] == ["operator"]  # not what it claimed

        stolen = ((LEASE_METADATA_KEY, lease),)
        robot = proxy_robot_pb2_grpc.ProxyRobotStub(thief)
        code, details = _code(robot.Hold, pr.HoldRequest(), stolen)
        assert code == grpc.StatusCode.PERMISSION_DENIED and "belongs to 'operator'" in details
        other = decision_server_pb2_grpc.DecisionServerStub(thief)
        for method, request in (("RenewControl", ds.RenewControlRequest(lease_id=lease)),
                                ("ReleaseControl", ds.ReleaseControlRequest(lease_id=lease))):
            code, _ = _code(getattr(other, method), request)
            assert code == grpc.StatusCode.PERMISSION_DENIED, method
        assert _code(owner.RenewControl, ds.RenewControlRequest(lease_id=lease))[0] \
            == grpc.StatusCode.OK
        # An admin may take it away.
        revoked = decision_server_pb2_grpc.DecisionServerStub(admin).ReleaseControl(
            ds.ReleaseControlRequest(lease_id=lease), timeout=10)
        assert not revoked.state.holders


def test_the_token_port_takes_valid_tokens_only(station, pki, tokens):
    address = station["address"][token_port_name("decision_server")]

    def call(token, method, request):
        with open_channel(address, security=ChannelSecurity(pki, token=token)) as channel:
            return _code(getattr(decision_server_pb2_grpc.DecisionServerStub(channel), method),
                         request)

    assert call(tokens["operator"], "GetControlState", ds.GetControlStateRequest())[0] \
        == grpc.StatusCode.OK
    assert call(tokens["operator"], "RenewControl", ds.RenewControlRequest(lease_id="x"))[0] \
        == grpc.StatusCode.NOT_FOUND  # authorized; the lease does not exist
    code, details = call(tokens["observer"], "RenewControl", ds.RenewControlRequest())
    assert code == grpc.StatusCode.PERMISSION_DENIED and "needs the operator role" in details
    code, details = call(tokens["expired"], "GetControlState", ds.GetControlStateRequest())
    assert code == grpc.StatusCode.UNAUTHENTICATED and "expired" in details
    forged = "trb_" + "A" * 43
    assert call(forged, "GetControlState", ds.GetControlStateRequest())[0] \
        == grpc.StatusCode.UNAUTHENTICATED
    # Without any token: health answers (open to all); nothing else does.
    bare = grpc.secure_channel(address, grpc.ssl_channel_credentials((pki / "ca.pem")
                                                                     .read_bytes()))
    with bare:
        health = health_pb2_grpc.HealthStub(bare).Check(health_pb2.HealthCheckRequest(),
                                                         timeout=10)
        assert health.status == health_pb2.HealthCheckResponse.SERVING
        code, _ = _code(decision_server_pb2_grpc.DecisionServerStub(bare).GetControlState,
                        ds.GetControlStateRequest())
        assert code == grpc.StatusCode.UNAUTHENTICATED


def test_an_unauthenticated_stop_on_the_token_port_does_not_stop_the_arm(station, pki):
    """The early stop (on gRPC's polling thread, before any handler) must not fire for a
    caller the token port cannot identify."""
    address = station["address"][token_port_name("decision_server")]
    bare = grpc.secure_channel(address, grpc.ssl_channel_credentials((pki / "ca.pem")
                                                                     .read_bytes()))
    with bare:
        code, _ = _code(proxy_robot_pb2_grpc.ProxyRobotStub(bare).EmergencyStop,
                        pr.EmergencyStopRequest(reason="anonymous"))
    assert code == grpc.StatusCode.UNAUTHENTICATED
    with _channel(station, "proxy_robot", pki, "observer") as channel:
        status = proxy_robot_pb2_grpc.ProxyRobotStub(channel).GetStatus(
            pr.GetStatusRequest(), timeout=10)
    assert status.status == types_pb2.ROBOT_STATUS_READY, status


def _audit(directory, service: str) -> list[dict]:
    """Every line of a service's audit log: its commands, then its refusals (summarized per
    source; each source's first refusal of a kind in a minute is written in full at once)."""
    return [json.loads(line) for name in (f"{service}.jsonl", f"{service}.refusals.jsonl")
            if (directory / name).exists()
            for line in (directory / name).read_text().splitlines()]


def test_command_calls_are_audited_with_identity_and_outcome(station, pki):
    with _channel(station, "decision_server", pki, "observer") as channel:
        stub = decision_server_pb2_grpc.DecisionServerStub(channel)
        _code(stub.AcquireControl, ds.AcquireControlRequest(
            operator_id="x", mode=ds.CONTROL_MODE_EXCLUSIVE))
        _code(stub.GetControlState, ds.GetControlStateRequest())  # a read: not audited

    def refused_acquire():
        records = _audit(station["audit"], "decision_server")
        return next((r for r in records if r.get("identity") == "observer"
                     and r.get("method", "").endswith("/AcquireControl")), None) and records

    records = wait_for(refused_acquire, what="the refused AcquireControl in the audit log")
    refused = next(r for r in records if r.get("identity") == "observer"
                   and r.get("method", "").endswith("/AcquireControl"))
    assert refused["outcome"] == "PERMISSION_DENIED" and refused["role"] == "observer"
    assert refused["time"].endswith("+00:00") and refused["peer"].startswith("ipv")
    assert not any(r.get("method", "").endswith("/GetControlState") for r in records)


def test_an_admin_sets_the_tool_frame_through_the_decision_server(station, pki):
    """The DecisionServer checks the admin role at its door and forwards the call to the inner
    ports as the station."""
    with _channel(station, "decision_server", pki, "admin") as channel:
        door = decision_server_pb2_grpc.DecisionServerStub(channel)
        lease = door.AcquireControl(ds.AcquireControlRequest(
            mode=ds.CONTROL_MODE_EXCLUSIVE), timeout=10).lease_id
        try:
            robot = proxy_robot_pb2_grpc.ProxyRobotStub(channel)
            frame = robot.GetToolFrame(pr.GetToolFrameRequest(), timeout=10).flange_to_tool
            frame.position_m.z += 0.01
            reply = robot.SetToolFrame(pr.SetToolFrameRequest(flange_to_tool=frame),
                                       timeout=10, metadata=((LEASE_METADATA_KEY, lease),))
            assert abs(reply.flange_to_tool.position_m.z - frame.position_m.z) < 1e-9
            frame.position_m.z -= 0.01
            robot.SetToolFrame(pr.SetToolFrameRequest(flange_to_tool=frame), timeout=10,
                               metadata=((LEASE_METADATA_KEY, lease),))
        finally:
            door.ReleaseControl(ds.ReleaseControlRequest(lease_id=lease), timeout=10)


def test_inner_ports_audit_everyone_and_summarize_the_station(station, pki):
    """The DecisionServer's moves reach ProxyRobot at up to 1 kHz as the station's identity:
    those are summarized there, a line a minute per method, the first of each outcome in full
    at once (so a leaked station key leaves a trace). An admin's command, and every refusal,
    are in full."""
    for identity in IDENTITIES:
        with _channel(station, "proxy_robot", pki, identity) as channel:
            _code(proxy_robot_pb2_grpc.ProxyRobotStub(channel).Hold, pr.HoldRequest())

    def holds():  # records are written by the audit log's own thread, just after the reply
        found = {(r["identity"], r["role"], r["outcome"])
                 for r in _audit(station["audit"], "proxy_robot")
                 if r.get("method", "").endswith("/Hold")}
        wanted = {("admin", "admin", "OK"), ("decision_server", "station", "OK")}
        return found if wanted <= found else None

    holds = wait_for(holds, what="the admin's and the station's Holds in ProxyRobot's audit log")
    assert {("observer", "observer", "PERMISSION_DENIED"),
            ("operator", "operator", "PERMISSION_DENIED")} <= holds


def test_the_readmes_buf_curl_calls_work_over_tls(station, pki, tokens):
    """The Security section's calls: a client certificate on the DecisionServer's port, and a
    bearer token on its token port (reflection needs the token too: --reflect-header)."""
    def buf_curl(*args: str) -> subprocess.CompletedProcess:
        return subprocess.run([str(BUF), "curl", "--protocol", "grpc", "--cacert",
                               str(pki / "ca.pem"), *args], cwd=REPO, capture_output=True,
                              text=True, timeout=60)

    operator = station["address"]["decision_server"]
    listed = buf_curl("--cert", str(pki / "operator.pem"), "--key", str(pki / "operator.key"),
                      "--list-methods", f"https://{operator}")
    assert listed.returncode == 0, listed.stderr
    assert "telerobot.v1.DecisionServer/Teleoperate" in listed.stdout
    token_port = station["address"][token_port_name("decision_server")]
    state = buf_curl("-H", f"authorization: Bearer {tokens['operator']}", "--reflect-header",
                     "*", "-d", "{}",
                     f"https://{token_port}/telerobot.v1.DecisionServer/GetControlState")
    assert state.returncode == 0, state.stderr
    assert "state" in json.loads(state.stdout)


def test_anyone_identified_may_stop_the_arm_and_the_stop_is_audited(station, pki):
    """Last in this module: it leaves the arm e-stopped."""
    with _channel(station, "decision_server", pki, "observer") as channel:
        reply = proxy_robot_pb2_grpc.ProxyRobotStub(channel).EmergencyStop(
            pr.EmergencyStopRequest(reason="observer saw smoke"), timeout=10)
    assert reply.status == types_pb2.ROBOT_STATUS_ESTOPPED
    path = station["audit"] / "decision_server.jsonl"
    wait_for(lambda: path.exists() and any(
        json.loads(line)["method"].endswith("/EmergencyStop")
        and json.loads(line)["identity"] == "observer" for line in path.read_text().splitlines()),
        what="the stop in the audit log")


def test_the_live_view_serves_wss_and_reads_the_station_as_an_observer(station, pki):
    """The live view under TLS: wss:// with its own certificate (the station's CA), reading
    ProxyRobot with the observer certificate `make certs` issued it."""
    import ssl

    from websockets.exceptions import InvalidHandshake

    from tests.foxglove.ws_client import FoxgloveClient
    from wire import foxglove as fx

    context = ssl.create_default_context(cafile=str(pki / "ca.pem"))
    with FoxgloveClient(f"wss://{station['address']['foxglove']}", ssl=context) as client:
        client.wait_advertised([fx.JOINT_STATES])
        client.subscribe([fx.JOINT_STATES])
        client.collect(lambda got: len(got[fx.JOINT_STATES]) >= 2, timeout_s=30)
    with pytest.raises(InvalidHandshake):  # plain ws:// gets no WebSocket upgrade
        FoxgloveClient(f"ws://{station['address']['foxglove']}").close()


def test_the_decision_servers_moves_on_the_local_socket_are_audited(station, pki):
    """On a TLS station too the DecisionServer moves the arm over ProxyRobot's local socket
    (wire/local_call.py); ProxyRobot's audit log summarizes those moves as the station's, the
    caller named by the user id the socket's peer credentials give."""
    from telerobot.v1 import types_pb2

    with _channel(station, "proxy_robot", pki, "admin") as channel:  # a test before stopped it
        robot = proxy_robot_pb2_grpc.ProxyRobotStub(channel)
        if robot.Reset(pr.ResetRequest(), timeout=10).status != types_pb2.ROBOT_STATUS_READY:
            robot.Initialize(pr.InitializeRequest(), timeout=30)
    with _channel(station, "decision_server", pki, "operator") as channel:
        door = decision_server_pb2_grpc.DecisionServerStub(channel)
        lease = door.AcquireControl(ds.AcquireControlRequest(
            mode=ds.CONTROL_MODE_EXCLUSIVE), timeout=10).lease_id
        metadata = ((LEASE_METADATA_KEY, lease),)
        try:
            increments = [ds.RecordedIncrement(
                offset={"nanos": k * 10_000_000}, frame=types_pb2.REFERENCE_FRAME_BASE,
                delta_position_m=types_pb2.Vector3(z=0.0001 * (-1) ** k)) for k in range(4)]
            request = ds.StartReplayRequest(name="local-moves", speed=1.0,
                                            increments=increments)
            # Taken once the DecisionServer's state stream has the reset arm READY.
            wait_for(lambda: _code(door.StartReplay, request, metadata)[0] == grpc.StatusCode.OK,
                     what="the replay started on the reset arm")

            def local_moves():
                return [r for r in _audit(station["audit"], "proxy_robot")
                        if r.get("method", "").endswith("/MoveCartesianIncremental")
                        and r.get("peer", "").startswith("unix:")] or None

            records = wait_for(local_moves, what="the replay's moves in ProxyRobot's audit log")
        finally:
            door.ReleaseControl(ds.ReleaseControlRequest(lease_id=lease), timeout=10)
    assert {(r["identity"], r["role"], r["outcome"]) for r in records} == {
        (f"uid {os.getuid()}", "station", "OK")}
