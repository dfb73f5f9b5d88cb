"""Refused calls in the audit log (issue #31): summarized per source in a file of their own, so
a flood of them never rotates a command out; and a Teleoperate stream on record as it starts.

The flood runs through the runtime's per-call security (services.runtime.auth.CallSecurity) as
the server's interceptor calls it, on a fake clock: ten minutes of it take seconds."""

from __future__ import annotations

import collections
import datetime
import json
import stat
import threading

import grpc
import pytest

from services.runtime.auth import CallSecurity
from services.runtime.server import ServerSecurity, binding, create_server
from services.security import audit
from services.security.audit import AuditLog
from services.security.caller import Caller
from services.security.pki import init
from services.security.roles import Role
from services.security.tokens import TokenStore
from telerobot.v1 import decision_server_pb2 as ds
from telerobot.v1 import decision_server_pb2_grpc
from tests.conftest import wait_for
from tests.fakes.clock import FakeClock
from wire.errors import TelerobotError
from wire.tls import ChannelSecurity

DS = "/telerobot.v1.DecisionServer/"
FLOOD_S = 600.0  # ten minutes
PER_S = 10  # each flooding source calls at 10 Hz
INTERVAL_S = 60.0


def lines(path) -> list[dict]:
    return [json.loads(line) for line in path.read_text().splitlines()] if path.exists() else []


def kept(path) -> list[dict]:
    """Every line of a rotated log, oldest first."""
    files = sorted(path.parent.glob(path.name + ".*"), key=lambda f: -int(f.suffix[1:]))
    return [entry for file in [*files, path] for entry in lines(file)]


def seconds(iso: str) -> float:
    return datetime.datetime.fromisoformat(iso).timestamp()


class Context:
    """What CallSecurity reads of a call's context: no client certificate (the token port),
    the call's metadata and its peer."""

    def __init__(self, peer: str, token: str | None = None):
        self._peer = peer
        self._metadata = (("authorization", f"Bearer {token}"),) if token else ()

    def auth_context(self) -> dict:
        return {}

    def invocation_metadata(self):
        return self._metadata

    def peer(self) -> str:
        return self._peer


@pytest.fixture
def clock():
    return FakeClock()


@pytest.fixture
def path(tmp_path):
    return tmp_path / "audit" / "decision_server.jsonl"


def test_a_ten_minute_flood_of_refusals_keeps_every_command(tmp_path, path, clock):
    """Two anonymous sources (one on a new connection each call) and an observer's token hammer
    the token port for ten minutes, while an operator teleoperates and commands once a
    second. The commands' log is small enough that the flood, written in full, would rotate
    every command out: every command stays, in full and in order; the refusals are one line in
    full and one summary per source per minute, in their own file, and the summaries count
    every refusal."""
    tokens = TokenStore(tmp_path / "tokens.json", clock=clock.time)
    operator = tokens.issue("alice", Role.OPERATOR, 3 * 3600)
    observer = tokens.issue("dashboard", Role.OBSERVER, 3 * 3600)
    # wall seconds exact on whole seconds, so an interval ends exactly a minute after it began
    log = AuditLog(path, max_bytes=500_000, backups=1, clock=lambda: clock.time_ns() / 1e9)
    security = CallSecurity(inner_port=False, tokens=tokens, audit=log)
    alice = Caller("alice", Role.OPERATOR)
    alice_at = Context("ipv4:10.0.0.2:5000", operator)
    refused = collections.defaultdict(collections.Counter)  # source -> method -> count
    commands = []

    def knock(method: str, context: Context, source: str) -> None:
        try:
            security.admit(method, context)
        except TelerobotError:
            refused[source][method] += 1
            return
        raise AssertionError(f"{source} was let in to {method}")

    start = clock.time()
    for step in range(round(FLOOD_S * PER_S)):
        anonymous = (DS + "AcquireControl", DS + "Teleoperate", DS + "EmergencyStop")[step % 3]
        knock(anonymous, Context(f"ipv4:10.0.0.66:{40000 + step % 500}"), "ipv4:10.0.0.66")
        knock(DS + "StartRecording", Context("ipv6:[2001:db8::7]:443", "forged"),
              "ipv6:[2001:db8::7]")
        if step % 5 == 0:
            knock(DS + "AcquireControl", Context("ipv4:10.0.0.9:7000", observer), "dashboard")
        if step % PER_S == 0:  # once a second: a Teleoperate stream starts, a command, it ends
            assert security.admit(DS + "Teleoperate", alice_at) == alice
            security.record(DS + "SetAssistance", alice, alice_at, "OK")
            security.record(DS + "Teleoperate", alice, alice_at, "OK")
            commands += [("Teleoperate", "STARTED"), ("SetAssistance", "OK"),
                         ("Teleoperate", "OK")]
        if step % (5 * PER_S) == 0:  # every 5 s a command of hers finds no room: a refusal
            security.record(DS + "RunAction", alice, alice_at, "RESOURCE_EXHAUSTED",
                            "the lane is saturated")
            refused["alice"][DS + "RunAction"] += 1
        clock.advance(1 / PER_S)
    log.close()

    written = kept(path)
    assert [(r["method"].rsplit("/", 1)[1], r["outcome"]) for r in written] == commands
    assert {(r["identity"], r["role"], r["peer"]) for r in written} == {
        ("alice", "operator", "ipv4:10.0.0.2:5000")}
    assert [seconds(r["time"]) for r in written] == sorted(seconds(r["time"]) for r in written)

    refusals = kept(path.with_name("decision_server.refusals.jsonl"))
    intervals = round(FLOOD_S / INTERVAL_S)
    # a minute of a source: the first refusal of each kind (method, outcome) in full, a summary
    assert len(refusals) == intervals * sum(len(methods) + 1 for methods in refused.values())
    for source, methods in refused.items():
        full = [r for r in refusals if "time" in r
                and (r["identity"] or r["peer"].rsplit(":", 1)[0]) == source]
        summaries = [r for r in refusals if r.get("source") == source]
        assert len(summaries) == intervals and len(full) == intervals * len(methods), source
        assert sum(s["count"] for s in summaries) == sum(methods.values()), source
        total = collections.Counter()
        for summary in summaries:
            total.update(summary["methods"])
            first, last = seconds(summary["first"]), seconds(summary["last"])
            assert last - first < INTERVAL_S
            assert sorted(r["method"] for r in full if first <= seconds(r["time"]) <= last) \
                == sorted(methods), source
        assert total == methods, source
        # each interval opens with the source's first refusal a minute after the one before
        opened = [seconds(s["first"]) - start for s in summaries]
        assert opened == pytest.approx([opened[0] + INTERVAL_S * n for n in range(intervals)],
                                       abs=0.1)
    anonymous = next(s for s in refusals if s.get("source") == "ipv4:10.0.0.66")
    assert anonymous["outcomes"] == {"UNAUTHENTICATED": anonymous["count"]}
    assert (anonymous["identity"], anonymous["role"]) == ("", "")
    assert len(anonymous["peers"]) == 8 and anonymous["detail"].startswith("no client cert")
    dashboard = next(s for s in refusals if s.get("source") == "dashboard")
    assert (dashboard["identity"], dashboard["role"]) == ("dashboard", "observer")
    assert dashboard["outcomes"] == {"PERMISSION_DENIED": dashboard["count"]}


def test_a_summary_is_written_when_its_interval_ends_with_no_refusal_after_it(path, clock):
    log = AuditLog(path, clock=clock.time)
    refusals = path.with_name("decision_server.refusals.jsonl")
    for n in range(3):
        log.refused(identity="", role="", method=DS + "AcquireControl",
                    outcome="UNAUTHENTICATED", peer=f"ipv4:10.0.0.66:{4000 + n}", detail="no")
        clock.advance(1.0)
    log.flush()
    assert [r["peer"] for r in lines(refusals)] == ["ipv4:10.0.0.66:4000"]
    clock.advance(INTERVAL_S)
    summary = wait_for(lambda: lines(refusals)[1:], what="the summary, by the clock alone")[0]
    assert summary["count"] == 3 and summary["peers"] == [f"ipv4:10.0.0.66:{4000 + n}"
                                                          for n in range(3)]
    assert seconds(summary["last"]) - seconds(summary["first"]) == pytest.approx(2.0)
    log.close()
    assert len(lines(refusals)) == 2 and not lines(path)


def test_close_writes_the_open_summaries_and_refusals_all_in_full_have_none(path, clock):
    log = AuditLog(path, clock=clock.time)
    for peer, method in [("ipv4:10.0.0.66:1", "Reset"), ("ipv4:10.0.0.66:2", "Reset"),
                         ("ipv4:10.0.0.77:1", "Reset"), ("ipv4:10.0.0.88:1", "Reset"),
                         ("ipv4:10.0.0.88:1", "Hold")]:
        log.refused(identity="", role="", method=DS + method, outcome="UNAUTHENTICATED",
                    peer=peer)
    log.close()
    written = lines(log.refusals_path)
    assert [r.get("peer") for r in written] == [
        "ipv4:10.0.0.66:1", "ipv4:10.0.0.77:1", "ipv4:10.0.0.88:1", "ipv4:10.0.0.88:1", None]
    assert (written[-1]["source"], written[-1]["count"]) == ("ipv4:10.0.0.66", 2)


def test_sources_beyond_the_limit_are_summed_as_one(path, clock):
    log = AuditLog(path, clock=clock.time, max_sources=2)
    for n in range(6):
        for _ in range(2):
            log.refused(identity="", role="", method=DS + "Reset",
                        outcome="UNAUTHENTICATED", peer=f"ipv4:10.0.{n}.1:99")
    log.close()
    summaries = {r["source"]: r["count"] for r in lines(log.refusals_path) if "source" in r}
    assert summaries == {"ipv4:10.0.0.1": 2, "ipv4:10.0.1.1": 2, audit.OTHER_SOURCES: 8}


def test_a_source_has_at_most_a_few_kinds_in_full(path, clock):
    log = AuditLog(path, clock=clock.time)
    for n in range(3 * audit.MAX_KINDS):
        log.refused(identity="mallory", role="observer", method=f"{DS}Method{n % 12}",
                    outcome="PERMISSION_DENIED", peer="ipv4:10.0.0.5:99")
    log.close()
    written = lines(log.refusals_path)
    assert [r["method"] for r in written[:-1]] == [
        f"{DS}Method{n}" for n in range(audit.MAX_KINDS)]
    assert written[-1]["count"] == 3 * audit.MAX_KINDS and len(written[-1]["methods"]) == 12


def test_the_refusals_file_is_private_rotated_and_only_made_when_needed(path, clock):
    log = AuditLog(path, max_bytes=2000, backups=2, clock=clock.time, summary_interval_s=1.0)
    log.record(identity="alice", role="operator", method=DS + "Reset", outcome="OK")
    log.flush()
    assert not log.refusals_path.exists()
    for n in range(200):
        log.refused(identity="", role="", method=DS + "Reset", outcome="UNAUTHENTICATED",
                    peer="ipv4:10.0.0.66:1", detail=f"refusal {n}")
        clock.advance(1.0)  # each refusal opens an interval: each is in full
    log.close()
    refusals = log.refusals_path
    files = sorted(file.name for file in refusals.parent.glob(refusals.name + "*"))
    assert files == [refusals.name, refusals.name + ".1", refusals.name + ".2"]
    for name in files:
        file = refusals.parent / name
        assert stat.S_IMODE(file.stat().st_mode) == 0o600 and file.stat().st_size <= 2000
    assert kept(refusals)[-1]["detail"] == "refusal 199"
    assert [r["method"] for r in lines(path)] == [DS + "Reset"]


# -- through a real server: the interceptor, TLS and the token port -----------------------------

class Teleoperating(decision_server_pb2_grpc.DecisionServerServicer):
    """Teleoperate answers ready and holds the stream until `let_go`."""

    def __init__(self):
        self.let_go = threading.Event()

    def Teleoperate(self, request_iterator, context):
        next(request_iterator)
        yield ds.TeleoperateResponse(ready=ds.TeleoperateReady())
        self.let_go.wait(10)


@pytest.mark.parametrize("aio", [False, True], ids=["sync", "aio"])
def test_teleoperate_is_on_record_as_it_starts_and_refusals_go_to_their_file(tmp_path, aio):
    init(tmp_path / "pki")
    tokens = TokenStore(tmp_path / "tokens.json")
    log = AuditLog(tmp_path / "audit" / "decision_server.jsonl")
    servicer = Teleoperating()
    security = ServerSecurity(tmp_path / "pki", "decision_server", inner_port=False,
                              token_address="127.0.0.1:0", tokens=tokens, audit=log)
    server, port = create_server(
        "127.0.0.1:0", [binding(decision_server_pb2_grpc, "DecisionServer", servicer)],
        security=security, aio=aio)
    server.start()
    ca = (tmp_path / "pki" / "ca.pem").read_bytes()
    try:
        with grpc.secure_channel(f"127.0.0.1:{server.token_port}",
                                 grpc.ssl_channel_credentials(ca)) as anonymous:
            stub = decision_server_pb2_grpc.DecisionServerStub(anonymous)
            for _ in range(3):
                with pytest.raises(grpc.RpcError) as error:
                    stub.AcquireControl(ds.AcquireControlRequest(), timeout=10)
                assert error.value.code() == grpc.StatusCode.UNAUTHENTICATED
        credentials = ChannelSecurity(tmp_path / "pki", "operator").credentials()
        with grpc.secure_channel(f"127.0.0.1:{port}", credentials) as channel:
            stream = decision_server_pb2_grpc.DecisionServerStub(channel).Teleoperate(
                iter([ds.TeleoperateRequest(init=ds.TeleoperateInit())]), timeout=20)
            assert next(stream).HasField("ready")
            log.flush()
            assert [(r["identity"], r["method"], r["outcome"]) for r in lines(log.path)] == [
                ("operator", DS + "Teleoperate", "STARTED")]
            servicer.let_go.set()
            assert list(stream) == []
        wait_for(lambda: log.flush() or len(lines(log.path)) == 2, what="the stream's end")
        assert lines(log.path)[1]["outcome"] == "OK"
    finally:
        server.stop(0)
        log.close()
    refusals = lines(log.refusals_path)
    assert [r.get("outcome") for r in refusals] == ["UNAUTHENTICATED", None]
    assert refusals[1]["count"] == 3 and refusals[1]["methods"] == {DS + "AcquireControl": 3}
