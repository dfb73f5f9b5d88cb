"""The calls the audit log used to miss (issue #31):

- the station's own moves on its inner ports (the DecisionServer's, up to 1 kHz as the station
  identity), so that a leaked service key moved the arm without a trace: now summarized per
  source, host and method a minute, the first of each outcome in full at once;
- a plaintext station's calls: with an audit directory, recorded with the peer's address as the
  caller (no identity, the role "unauthenticated").

The counting runs on a fake clock (an hour of moves takes a second); the rest through real
in-process servers, and one real process."""

from __future__ import annotations

import collections
import datetime
import json
import signal
from types import SimpleNamespace

import grpc
import pytest

from services.runtime.auth import UNAUTHENTICATED_ROLE, CallSecurity
from services.runtime.process import plaintext_audit_log
from services.runtime.server import ServerSecurity, binding, create_server
from services.security import audit
from services.security.audit import AuditLog
from services.security.caller import Caller
from services.security.pki import init
from services.security.roles import Role
from telerobot.v1 import decision_server_pb2 as ds
from telerobot.v1 import decision_server_pb2_grpc, proxy_robot_pb2_grpc
from telerobot.v1 import proxy_robot_pb2 as pr
from tests.conftest import wait_for
from tests.fakes.clock import FakeClock
from tests.processes import start_service, unique_shm_name
from wire.tls import ChannelSecurity

PR = "/telerobot.v1.ProxyRobot/"
DS = "/telerobot.v1.DecisionServer/"
INTERVAL_S = 60.0
STATION = {"identity": "decision_server", "role": "station"}
HERE = "ipv4:127.0.0.1:41000"  # the DecisionServer's connection to ProxyRobot


def lines(path) -> list[dict]:
    return [json.loads(line) for line in path.read_text().splitlines()] if path.exists() else []


def seconds(iso: str) -> float:
    return datetime.datetime.fromisoformat(iso).timestamp()


def full(records) -> list[dict]:
    return [r for r in records if "time" in r]


def summaries(records) -> list[dict]:
    return [r for r in records if "count" in r]


@pytest.fixture
def clock():
    return FakeClock()


@pytest.fixture
def path(tmp_path):
    return tmp_path / "audit" / "proxy_robot.jsonl"


def wall(clock: FakeClock):
    return lambda: clock.time_ns() / 1e9  # exact on whole seconds


# -- the counting, on a fake clock -------------------------------------------------------------

def test_station_moves_at_1khz_make_a_few_lines_a_minute(path, clock):
    """Three minutes of the DecisionServer's moves at 1 kHz, a Hold every 10 s and one refused
    move a minute: per minute and method, the first of each outcome in full and one summary
    that counts every call; 180,000 moves are 12 lines."""
    log = AuditLog(path, clock=wall(clock))
    start = clock.time_ns() / 1e9
    calls = collections.defaultdict(collections.Counter)  # method -> outcome -> count
    for step in range(180_000):  # one step a millisecond
        outcome = "FAILED_PRECONDITION" if step % 60_000 == 30_000 else "OK"
        log.summarized(method=PR + "MoveJointsIncremental", outcome=outcome, peer=HERE,
                       **STATION)
        calls[PR + "MoveJointsIncremental"][outcome] += 1
        if step % 10_000 == 0:
            log.summarized(method=PR + "Hold", outcome="OK", peer=HERE, **STATION)
            calls[PR + "Hold"]["OK"] += 1
        if step == 0:  # the first of each is on record at once, before its minute ends
            log.flush()
            assert [(r["method"], r["outcome"]) for r in lines(path)] == [
                (PR + "MoveJointsIncremental", "OK"), (PR + "Hold", "OK")]
        clock.advance(0.001)
    log.close()

    written = lines(path)
    assert len(written) == 3 * (2 + 1 + 1 + 1)  # a minute: moves 2 in full + 1, Hold 1 + 1
    for record in full(written):
        assert (record["identity"], record["role"], record["peer"]) == (
            "decision_server", "station", HERE)
    assert sorted((r["method"], r["outcome"]) for r in full(written)) == sorted(
        [(PR + "MoveJointsIncremental", "OK"), (PR + "MoveJointsIncremental",
                                                "FAILED_PRECONDITION"),
         (PR + "Hold", "OK")] * 3)
    counted = collections.defaultdict(collections.Counter)
    for summary in summaries(written):
        assert (summary["source"], summary["identity"], summary["role"]) == (
            "decision_server", "decision_server", "station")
        assert summary["peers"] == [HERE] and len(summary["methods"]) == 1
        method = next(iter(summary["methods"]))
        counted[method].update(summary["outcomes"])
        assert summary["count"] == sum(summary["outcomes"].values())
        first, last = seconds(summary["first"]), seconds(summary["last"])
        assert last - first < INTERVAL_S and (first - start) % INTERVAL_S == pytest.approx(0)
    assert counted == calls


def test_a_leaked_station_key_used_from_elsewhere_is_on_record_at_once(path, clock):
    """Its calls have a summary of their own (another host), and its first move is written in
    full at once, naming its peer, while the station's own moves go on being counted."""
    log = AuditLog(path, clock=wall(clock))
    for _ in range(100):
        log.summarized(method=PR + "MoveJointsIncremental", outcome="OK", peer=HERE, **STATION)
        clock.advance(0.001)
    log.summarized(method=PR + "MoveJointsIncremental", outcome="OK",
                   peer="ipv4:10.0.0.66:50000", **STATION)
    log.flush()
    assert [r["peer"] for r in lines(path)] == [HERE, "ipv4:10.0.0.66:50000"]
    for _ in range(5):
        log.summarized(method=PR + "MoveJointsIncremental", outcome="OK",
                       peer="ipv4:10.0.0.66:50001", **STATION)
    log.close()
    by_peers = {tuple(s["peers"]): s["count"] for s in summaries(lines(path))}
    assert by_peers == {(HERE,): 100, ("ipv4:10.0.0.66:50000", "ipv4:10.0.0.66:50001"): 6}


def test_summarized_sources_beyond_the_limit_are_summed_as_one(path, clock):
    log = AuditLog(path, clock=wall(clock), max_sources=2)
    for n in range(5):
        for _ in range(3):
            log.summarized(identity="", role="", method=PR + "Hold", outcome="OK",
                           peer=f"ipv4:10.0.0.{n}:99")
    log.close()
    counts = {s["source"]: s["count"] for s in summaries(lines(path))}
    assert counts == {"ipv4:10.0.0.0": 3, "ipv4:10.0.0.1": 3, audit.OTHER_SOURCES: 9}
    assert len(full(lines(path))) == 3  # each of the two sources' first, and the others' first


def test_a_quiet_summary_is_written_when_its_minute_ends(path, clock):
    log = AuditLog(path, clock=wall(clock))
    for _ in range(3):
        log.summarized(method=PR + "Hold", outcome="OK", peer=HERE, **STATION)
    log.flush()
    assert len(lines(path)) == 1
    clock.advance(INTERVAL_S)
    summary = wait_for(lambda: summaries(lines(path)), what="the summary, by the clock alone")
    assert summary[0]["count"] == 3
    log.close()
    assert len(lines(path)) == 2


class Context:
    """What CallSecurity reads of a call's context (no certificate: the caller is given)."""

    def __init__(self, peer: str):
        self._peer = peer

    def auth_context(self) -> dict:
        return {}

    def invocation_metadata(self):
        return ()

    def peer(self) -> str:
        return self._peer


def test_the_runtime_summarizes_the_station_on_inner_ports_only(tmp_path, clock):
    """On an inner port the station's commands are summarized and everyone else's are in
    full; on the DecisionServer's port (the operator's door) every command is in full."""
    inner = AuditLog(tmp_path / "proxy_robot.jsonl", clock=wall(clock))
    door = AuditLog(tmp_path / "decision_server.jsonl", clock=wall(clock))
    station, admin = Caller("decision_server", Role.STATION), Caller("admin", Role.ADMIN)
    here = Context(HERE)
    for log, inner_port in ((inner, True), (door, False)):
        security = CallSecurity(inner_port=inner_port, audit=log)
        assert security.summarizes(station) is inner_port
        assert not security.summarizes(admin) and not security.summarizes(None)
        for _ in range(10):
            security.record(PR + "Hold", station, here, "OK")
        security.record(PR + "Hold", admin, here, "OK")
        log.close()
    assert [(r["identity"], r.get("count")) for r in lines(inner.path)] == [
        ("decision_server", None), ("admin", None), ("decision_server", 10)]
    assert [r["identity"] for r in lines(door.path)] == ["decision_server"] * 10 + ["admin"]


def test_without_tls_the_runtime_records_the_caller_by_its_address(tmp_path, clock):
    """Nobody is checked (every call is let in, as no caller); command-class calls are on
    record with no identity and the role "unauthenticated": in full on the operator's door,
    summarized on an inner port (where the station cannot be told from anyone else)."""
    door = AuditLog(tmp_path / "decision_server.jsonl", clock=wall(clock))
    inner = AuditLog(tmp_path / "proxy_robot.jsonl", clock=wall(clock))
    security = CallSecurity(inner_port=False, audit=door, authenticates=False)
    browser = Context("ipv4:127.0.0.1:5000")
    assert security.admit(DS + "Teleoperate", browser) is None
    assert security.admit(DS + "DeleteRecording", browser) is None  # admin-level: let in
    security.record(DS + "Teleoperate", None, browser, "OK")
    inner_security = CallSecurity(inner_port=True, audit=inner, authenticates=False)
    for port in range(5):
        assert inner_security.admit(PR + "Hold", Context(f"ipv4:127.0.0.1:{port}")) is None
        inner_security.record(PR + "Hold", None, Context(f"ipv4:127.0.0.1:{port}"), "OK")
    door.close()
    inner.close()
    assert [(r["identity"], r["role"], r["method"], r["outcome"], r["peer"])
            for r in lines(door.path)] == [
        ("", UNAUTHENTICATED_ROLE, DS + "Teleoperate", "STARTED", "ipv4:127.0.0.1:5000"),
        ("", UNAUTHENTICATED_ROLE, DS + "Teleoperate", "OK", "ipv4:127.0.0.1:5000")]
    first, summary = lines(inner.path)
    assert (first["role"], first["peer"]) == (UNAUTHENTICATED_ROLE, "ipv4:127.0.0.1:0")
    assert (summary["source"], summary["role"], summary["count"]) == (
        "ipv4:127.0.0.1", UNAUTHENTICATED_ROLE, 5)


# -- through real servers ----------------------------------------------------------------------

class Robot(proxy_robot_pb2_grpc.ProxyRobotServicer):
    def Hold(self, request, context):
        return pr.HoldResponse()


class Teleoperating(decision_server_pb2_grpc.DecisionServerServicer):
    def Teleoperate(self, request_iterator, context):
        next(request_iterator)
        yield ds.TeleoperateResponse(ready=ds.TeleoperateReady())

    def GetControlState(self, request, context):
        return ds.GetControlStateResponse()


@pytest.mark.parametrize("aio", [False, True], ids=["sync", "aio"])
def test_the_station_key_moving_the_arm_on_an_inner_port_leaves_a_trace(tmp_path, aio):
    init(tmp_path / "pki")
    log = AuditLog(tmp_path / "audit" / "proxy_robot.jsonl")
    server, port = create_server(
        "127.0.0.1:0", [binding(proxy_robot_pb2_grpc, "ProxyRobot", Robot())],
        security=ServerSecurity(tmp_path / "pki", "proxy_robot", audit=log), aio=aio)
    server.start()
    try:
        for identity, calls in (("decision_server", 50), ("admin", 2)):
            credentials = ChannelSecurity(tmp_path / "pki", identity).credentials()
            with grpc.secure_channel(
                    f"127.0.0.1:{port}", credentials,
                    options=[("grpc.ssl_target_name_override", "localhost")]) as channel:
                robot = proxy_robot_pb2_grpc.ProxyRobotStub(channel)
                for _ in range(calls):
                    robot.Hold(pr.HoldRequest(), timeout=10)
        log.flush()
        assert sorted(r["identity"] for r in lines(log.path)) == [
            "admin", "admin", "decision_server"]
    finally:
        server.stop(0)
        log.close()
    (summary,) = summaries(lines(log.path))
    assert (summary["identity"], summary["role"], summary["count"]) == (
        "decision_server", "station", 50)
    assert summary["methods"] == {PR + "Hold": 50} and summary["outcomes"] == {"OK": 50}
    assert summary["peers"][0].startswith("ipv4:127.0.0.1:")


@pytest.mark.parametrize("aio", [False, True], ids=["sync", "aio"])
def test_a_plaintext_server_keeps_an_audit_log(tmp_path, aio):
    door_log = AuditLog(tmp_path / "audit" / "decision_server.jsonl")
    inner_log = AuditLog(tmp_path / "audit" / "proxy_robot.jsonl")
    door, door_port = create_server(
        "127.0.0.1:0", [binding(decision_server_pb2_grpc, "DecisionServer", Teleoperating())],
        audit=door_log, aio=aio)
    inner, inner_port = create_server(
        "127.0.0.1:0", [binding(proxy_robot_pb2_grpc, "ProxyRobot", Robot())], audit=inner_log,
        aio=aio)
    for server in (door, inner):
        server.start()
    try:
        with grpc.insecure_channel(f"127.0.0.1:{door_port}") as channel:
            stub = decision_server_pb2_grpc.DecisionServerStub(channel)
            stub.GetControlState(ds.GetControlStateRequest(), timeout=10)  # a read: not audited
            stream = stub.Teleoperate(iter([ds.TeleoperateRequest(init=ds.TeleoperateInit())]),
                                      timeout=10)
            assert [reply.HasField("ready") for reply in stream] == [True]
        with grpc.insecure_channel(f"127.0.0.1:{inner_port}") as channel:
            robot = proxy_robot_pb2_grpc.ProxyRobotStub(channel)
            for _ in range(20):
                robot.Hold(pr.HoldRequest(), timeout=10)
        wait_for(lambda: door_log.flush() or len(lines(door_log.path)) == 2,
                 what="the stream's end")
    finally:
        for server in (door, inner):
            server.stop(0)
        door_log.close()
        inner_log.close()
    started, ended = lines(door_log.path)
    assert [(r["identity"], r["role"], r["method"], r["outcome"]) for r in (started, ended)] == [
        ("", UNAUTHENTICATED_ROLE, DS + "Teleoperate", "STARTED"),
        ("", UNAUTHENTICATED_ROLE, DS + "Teleoperate", "OK")]
    assert started["peer"].startswith("ipv4:127.0.0.1:")
    first, summary = lines(inner_log.path)
    assert (first["method"], first["role"]) == (PR + "Hold", UNAUTHENTICATED_ROLE)
    assert (summary["source"], summary["count"]) == ("ipv4:127.0.0.1", 20)


def test_with_tls_the_audit_log_is_the_securitys(tmp_path):
    init(tmp_path / "pki")
    log = AuditLog(tmp_path / "audit.jsonl")
    try:
        with pytest.raises(ValueError, match="security.audit"):
            create_server("127.0.0.1:0", [], audit=log,
                          security=ServerSecurity(tmp_path / "pki", "proxy_robot"))
    finally:
        log.close()


def test_a_plaintext_service_audits_when_it_has_an_audit_directory(tmp_path, monkeypatch):
    plaintext, tls = SimpleNamespace(tls_dir=""), SimpleNamespace(tls_dir=str(tmp_path))
    monkeypatch.delenv(audit.AUDIT_DIR_ENV, raising=False)
    assert plaintext_audit_log(plaintext, "proxy_robot") is None  # not into the cwd's var/
    monkeypatch.setenv(audit.AUDIT_DIR_ENV, str(tmp_path / "audit"))
    log = plaintext_audit_log(plaintext, "proxy_robot")
    try:
        assert log is not None and log.path == tmp_path / "audit" / "proxy_robot.jsonl"
    finally:
        log.close()
    assert plaintext_audit_log(tls, "proxy_robot") is None  # TLS's comes with its security


@pytest.mark.e2e
def test_a_plaintext_band_records_its_stops(tmp_path):
    """The emergency-stop band, a real process in plaintext with TELEROBOT_AUDIT_DIR (and no
    arm behind it: each stop ends UNAVAILABLE, and is on record all the same)."""
    directory = tmp_path / "audit"
    band = start_service("emergency_stop", "--shm-name", unique_shm_name(), "--rt-priority", "0",
                         env={audit.AUDIT_DIR_ENV: str(directory)})
    path = directory / "emergency_stop.jsonl"
    try:
        with grpc.insecure_channel(band.address) as channel:
            robot = proxy_robot_pb2_grpc.ProxyRobotStub(channel)
            outcomes = []
            for _ in range(3):
                try:
                    robot.EmergencyStop(pr.EmergencyStopRequest(reason="test"), timeout=10)
                    outcomes.append("OK")
                except grpc.RpcError as error:
                    outcomes.append(error.code().name)
        first = wait_for(lambda: lines(path), what="the first stop in the band's audit log")[0]
    finally:
        band.stop(signal.SIGTERM)
    assert (first["identity"], first["role"], first["method"]) == (
        "", UNAUTHENTICATED_ROLE, PR + "EmergencyStop")
    assert first["peer"].startswith("ipv4:127.0.0.1:") and first["outcome"] == outcomes[0]
    summary = lines(path)[-1]
    assert (summary["source"], summary["count"]) == ("ipv4:127.0.0.1", 3)

