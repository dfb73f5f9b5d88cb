"""What one caller can take from a server (#31), over real in-process servers on port 0:

- a call runs on the lane its RPC declares or a lower one the client asks for, never a higher;
- streams are capped per caller (the authenticated identity, or the peer's address) as well as
  per server, a server's ports share one cap, and on an inner port the station's own streams
  have room of their own;
- a unary call takes one of its caller's slots from its headers on, so calls that send headers
  and never a body are refused once the caller holds its share, instead of each keeping a
  thread;
- a server accepts only as many calls as it has threads (RESOURCE_EXHAUSTED beyond), and one
  connection never takes all of them;
- a call refused for room is counted in the audit log's refusals and said in the log.

The servicers are fixtures; the interceptor, lanes, TLS and caps are the runtime's own."""

from __future__ import annotations

import json
import logging
import threading

import grpc
import pytest
from google.rpc import error_details_pb2
from grpc_health.v1 import health_pb2, health_pb2_grpc
from grpc_status import rpc_status

from services.runtime.lanes import current_lane
from services.runtime.rpc import (
    DEFAULT_MAX_STREAMS,
    STATION_OWN_STREAMS,
    CallSlots,
    Holder,
    RefusalWarnings,
    SlotRefused,
    peer_host,
)
from services.runtime.server import ServerSecurity, binding, create_server
from services.security.audit import AuditLog
from services.security.pki import init
from services.security.roles import Role
from services.security.tokens import TokenStore
from telerobot.v1 import (
    decision_server_pb2,
    decision_server_pb2_grpc,
    proxy_robot_pb2,
    proxy_robot_pb2_grpc,
)
from tests.conftest import wait_for
from tests.runtime.test_server import LANES
from wire.tls import ChannelSecurity

GET_STATUS = "/telerobot.v1.ProxyRobot/GetStatus"
GET_CONTROL_STATE = "/telerobot.v1.DecisionServer/GetControlState"
STREAM_EVENTS = "/telerobot.v1.DecisionServer/StreamEvents"
HEALTH_WATCH = "/grpc.health.v1.Health/Watch"


class Robot(proxy_robot_pb2_grpc.ProxyRobotServicer):
    """Each unary call answers with the lane it ran on; the event stream runs until the call
    ends."""

    def GetStatus(self, request, context):  # declared high
        return proxy_robot_pb2.GetStatusResponse(reason=current_lane().name.lower())

    def Connect(self, request, context):  # declared medium
        context.set_trailing_metadata([("lane", current_lane().name.lower())])
        return proxy_robot_pb2.ConnectResponse()

    def StreamRobotEvents(self, request, context):
        ended = threading.Event()
        context.add_callback(ended.set)
        while not ended.is_set():
            yield proxy_robot_pb2.StreamRobotEventsResponse(sequence=1)
            ended.wait(0.05)


class Decisions(decision_server_pb2_grpc.DecisionServerServicer):
    def ListRecordings(self, request, context):  # declared low
        return decision_server_pb2.ListRecordingsResponse(
            recordings=[decision_server_pb2.Recording(name=current_lane().name.lower())])

    def GetControlState(self, request, context):
        return decision_server_pb2.GetControlStateResponse()

    def StreamEvents(self, request, context):
        ended = threading.Event()
        context.add_callback(ended.set)
        while not ended.is_set():
            yield decision_server_pb2.StreamEventsResponse(sequence=1)
            ended.wait(0.05)


def bindings():
    return [binding(proxy_robot_pb2_grpc, "ProxyRobot", Robot()),
            binding(decision_server_pb2_grpc, "DecisionServer", Decisions())]


def reason_of(error: grpc.RpcError) -> str:
    status = rpc_status.from_call(error)
    info = error_details_pb2.ErrorInfo()
    assert status is not None and status.details[0].Unpack(info)
    return info.reason


@pytest.fixture(params=[False, True], ids=["sync", "aio"])
def aio(request):
    return request.param


@pytest.fixture(scope="module")
def pki(tmp_path_factory):
    directory = tmp_path_factory.mktemp("pki")
    init(directory)
    return directory


def serve(**settings):
    server, port = create_server("127.0.0.1:0", bindings(), lanes=LANES, **settings)
    server.start()
    return server, port


def tls_channel(pki, port: int, identity: str, **options) -> grpc.Channel:
    credentials = ChannelSecurity(pki, identity).credentials()
    return grpc.secure_channel(f"127.0.0.1:{port}", credentials,
                               options=[("grpc.ssl_target_name_override", "localhost"),
                                        *options.items()])


def open_streams(channel: grpc.Channel, count: int, decisions: bool = True) -> list:
    """`count` event streams, each past its first message (so each holds its slots)."""
    if decisions:
        stub = decision_server_pb2_grpc.DecisionServerStub(channel)
        streams = [stub.StreamEvents(decision_server_pb2.StreamEventsRequest(), timeout=30)
                   for _ in range(count)]
    else:
        stub = proxy_robot_pb2_grpc.ProxyRobotStub(channel)
        streams = [stub.StreamRobotEvents(proxy_robot_pb2.StreamRobotEventsRequest(),
                                          timeout=30) for _ in range(count)]
    for stream in streams:
        next(stream)
    return streams


def refused_stream(channel: grpc.Channel, decisions: bool = True) -> grpc.RpcError:
    with pytest.raises(grpc.RpcError) as error:
        open_streams(channel, 1, decisions)
    assert error.value.code() is grpc.StatusCode.RESOURCE_EXHAUSTED
    return error.value


# -- lanes ----------------------------------------------------------------------------------

def test_a_client_may_lower_its_call_but_never_raise_it_above_the_declared_lane(aio):
    server, port = serve(aio=aio)
    try:
        with grpc.insecure_channel(f"127.0.0.1:{port}") as channel:
            robot = proxy_robot_pb2_grpc.ProxyRobotStub(channel)
            decisions = decision_server_pb2_grpc.DecisionServerStub(channel)

            def listed_on(lane: str) -> str:
                reply = decisions.ListRecordings(decision_server_pb2.ListRecordingsRequest(),
                                                 metadata=[("telerobot-lane", lane)], timeout=5)
                return reply.recordings[0].name

            def connected_on(lane: str) -> str:
                _, call = robot.Connect.with_call(proxy_robot_pb2.ConnectRequest(),
                                                  metadata=[("telerobot-lane", lane)], timeout=5)
                return dict(call.trailing_metadata())["lane"]

            assert listed_on("high") == "low"  # ListRecordings declares the low lane
            assert listed_on("emergency") == "low"
            assert connected_on("high") == "medium"  # Connect declares the medium lane
            assert connected_on("low") == "low"  # lowering stays the client's choice
            assert robot.GetStatus(proxy_robot_pb2.GetStatusRequest(),
                                   metadata=[("telerobot-lane", "medium")],
                                   timeout=5).reason == "medium"
    finally:
        server.stop(0)


# -- streams per caller ---------------------------------------------------------------------

def test_one_identity_cannot_take_every_stream_and_the_ports_share_one_cap(pki, tmp_path, aio):
    tokens = TokenStore(tmp_path / "tokens.json")
    token = tokens.issue("dashboard", Role.OBSERVER, 600)
    security = ServerSecurity(pki, "decision_server", inner_port=False,
                              token_address="127.0.0.1:0", tokens=tokens)
    server, port = serve(security=security, max_streams=4, streams_per_caller=2, aio=aio)
    observer = tls_channel(pki, port, "observer")
    operator = tls_channel(pki, port, "operator")
    anonymous = grpc.secure_channel(
        f"127.0.0.1:{server.token_port}",
        grpc.composite_channel_credentials(
            grpc.ssl_channel_credentials((pki / "ca.pem").read_bytes()),
            grpc.access_token_call_credentials(token)),
        options=[("grpc.ssl_target_name_override", "localhost")])
    try:
        held = open_streams(observer, 2)
        error = refused_stream(observer)  # its own cap, though the server has room
        assert reason_of(error) == "CALLER_STREAMS_EXHAUSTED"
        assert "identity 'observer' already holds 2 streams" in error.details()
        held += open_streams(operator, 1)  # another identity is not refused
        held += open_streams(anonymous, 1)  # nor one on the token port: 4 open on the server
        assert server.interceptor.open_streams == 4
        error = refused_stream(anonymous)  # the two ports' streams count together
        assert reason_of(error) == "STREAMS_EXHAUSTED"
        assert "4 streams are open on this server" in error.details()
        held.pop(0).cancel()  # a slot given back is the observer's again
        wait_for(lambda: server.interceptor.open_streams == 3, what="the slot given back")
        held += open_streams(observer, 1)
        for stream in held:
            stream.cancel()
        wait_for(lambda: server.interceptor.open_streams == 0, what="every slot given back")
    finally:
        for channel in (observer, operator, anonymous):
            channel.close()
        server.stop(0)


def test_the_station_has_room_of_its_own_on_an_inner_port(pki, aio):
    security = ServerSecurity(pki, "proxy_robot", inner_port=True)
    server, port = serve(security=security, max_streams=2, streams_per_caller=1,
                         station_streams=3, aio=aio)
    channels = {name: tls_channel(pki, port, name)
                for name in ("observer", "admin", "operator", "decision_server")}
    try:
        held = open_streams(channels["observer"], 1, decisions=False)
        held += open_streams(channels["admin"], 1, decisions=False)
        error = refused_stream(channels["operator"], decisions=False)  # the others' room: full
        assert reason_of(error) == "STREAMS_EXHAUSTED"
        # The DecisionServer forwards many callers' streams as itself: no per-caller cap, and
        # the others' streams do not take its room.
        held += open_streams(channels["decision_server"], 3, decisions=False)
        assert server.interceptor.open_streams == 5
        error = refused_stream(channels["decision_server"], decisions=False)
        assert "the station's 3 streams on this server are open" in error.details()
        for stream in held:
            stream.cancel()
        wait_for(lambda: server.interceptor.open_streams == 0, what="every slot given back")
    finally:
        for channel in channels.values():
            channel.close()
        server.stop(0)


def test_an_inner_port_has_room_for_every_stream_the_decision_server_may_forward(pki):
    door, _ = create_server("127.0.0.1:0", bindings(), security=ServerSecurity(
        pki, "decision_server", inner_port=False, token_address="127.0.0.1:0"))
    inner, _ = create_server("127.0.0.1:0", [], security=ServerSecurity(pki, "proxy_robot"))
    plain_door, _ = create_server("127.0.0.1:0", bindings())
    plain_inner, _ = create_server("127.0.0.1:0", [])
    try:
        # The DecisionServer's two ports share its cap; its own follow and health streams
        # come on top.
        assert door.interceptor.slots.max_streams == DEFAULT_MAX_STREAMS
        assert inner.interceptor.slots.station_streams >= (
            door.interceptor.slots.max_streams + STATION_OWN_STREAMS)
        # In plaintext the station is not told apart: its room is everyone's.
        assert plain_door.interceptor.slots.max_streams == DEFAULT_MAX_STREAMS
        assert plain_inner.interceptor.slots.max_streams >= (
            plain_door.interceptor.slots.max_streams + STATION_OWN_STREAMS
            + DEFAULT_MAX_STREAMS)
    finally:
        for server in (door, inner, plain_door, plain_inner):
            server.stop(0)


# -- unary calls per caller, and calls that never send their body ----------------------------

class Silent:
    """A request iterator that sends nothing until released: a call of headers only."""

    def __init__(self):
        self.release = threading.Event()

    def __call__(self):
        self.release.wait(30)
        return
        yield  # makes this a generator


def headers_only(channel: grpc.Channel, method: str, silent: Silent) -> grpc.Future:
    """A unary RPC called as a client stream whose one message never comes."""
    call = channel.stream_unary(method, request_serializer=None, response_deserializer=None)
    return call.future(silent(), timeout=30)


def test_headers_only_calls_are_refused_past_the_callers_share(pki):
    """On the sync server, whose handler reads the request and so sees the call at its
    headers (a grpc.aio server reads a request on its loop, holding no thread, before its
    handler runs)."""
    security = ServerSecurity(pki, "decision_server", inner_port=False)
    server, port = serve(security=security, calls_per_caller=2)
    observer = tls_channel(pki, port, "observer")
    operator = tls_channel(pki, port, "operator")
    silent = Silent()
    try:
        held = [headers_only(observer, GET_CONTROL_STATE, silent) for _ in range(2)]
        slots = server.interceptor.slots
        wait_for(lambda: slots.held_by("identity observer") == (0, 2),
                 what="the two calls holding the observer's share")
        third = headers_only(observer, GET_CONTROL_STATE, silent)
        error = third.exception(timeout=20)  # refused at its headers, without a body
        assert error is not None and error.code() is grpc.StatusCode.RESOURCE_EXHAUSTED
        assert reason_of(error) == "CALLER_CALLS_EXHAUSTED"
        assert "identity 'observer' already has 2 calls in flight" in error.details()
        stub = decision_server_pb2_grpc.DecisionServerStub(operator)
        stub.GetControlState(decision_server_pb2.GetControlStateRequest(), timeout=10)
        for call in held:
            call.cancel()
        wait_for(lambda: slots.held_by("identity observer") == (0, 0),
                 what="the observer's share given back")
        decision_server_pb2_grpc.DecisionServerStub(observer).GetControlState(
            decision_server_pb2.GetControlStateRequest(), timeout=10)
    finally:
        silent.release.set()
        observer.close()
        operator.close()
        server.stop(0)


def test_unary_calls_in_flight_are_capped_per_caller(pki, aio):
    """On either server, calls with their body count while they wait on a lane."""
    security = ServerSecurity(pki, "decision_server", inner_port=False)
    blocker = threading.Event()

    class Slow(Decisions):
        def GetControlState(self, request, context):
            blocker.wait(20)
            return decision_server_pb2.GetControlStateResponse()

    server, port = create_server(
        "127.0.0.1:0", [binding(decision_server_pb2_grpc, "DecisionServer", Slow())],
        security=security, calls_per_caller=2, aio=aio)
    server.start()
    observer = tls_channel(pki, port, "observer")
    try:
        stub = decision_server_pb2_grpc.DecisionServerStub(observer)
        request = decision_server_pb2.GetControlStateRequest()
        held = [stub.GetControlState.future(request, timeout=30) for _ in range(2)]
        slots = server.interceptor.slots
        wait_for(lambda: slots.held_by("identity observer") == (0, 2),
                 what="two calls in the servicer")
        with pytest.raises(grpc.RpcError) as error:
            stub.GetControlState(request, timeout=10)
        assert error.value.code() is grpc.StatusCode.RESOURCE_EXHAUSTED
        assert reason_of(error.value) == "CALLER_CALLS_EXHAUSTED"
        blocker.set()
        for call in held:
            call.result(timeout=10)
        wait_for(lambda: slots.held_by("identity observer") == (0, 0), what="the share back")
    finally:
        blocker.set()
        observer.close()
        server.stop(0)


# -- the server's bound, and a connection's -------------------------------------------------

def test_a_server_refuses_calls_beyond_its_threads_and_one_connection_leaves_room():
    """Plaintext on loopback (no per-caller cap): headers-only calls pile up to the bounds."""
    server, port = serve(max_streams=2, station_streams=0)
    pool = 20 + 2 + 16  # the lanes' threads and queues, the streams, the spare threads
    per_connection = pool - pool // 4
    silent = Silent()
    local = [("grpc.use_local_subchannel_pool", 1)]  # a connection of each channel's own
    flooding, other, third = (grpc.insecure_channel(f"127.0.0.1:{port}", options=local)
                              for _ in range(3))
    slots = server.interceptor.slots
    try:
        flood = [headers_only(flooding, GET_STATUS, silent) for _ in range(pool)]
        wait_for(lambda: slots.calls_in_flight == per_connection,
                 what="one connection's share of calls in the server")
        # The rest of that connection's calls wait on the client: the others still get in.
        robot = proxy_robot_pb2_grpc.ProxyRobotStub(other)
        assert robot.GetStatus(proxy_robot_pb2.GetStatusRequest(), timeout=10).reason == "high"
        assert slots.calls_in_flight == per_connection
        flood += [headers_only(other, GET_STATUS, silent)
                  for _ in range(pool - per_connection)]
        wait_for(lambda: slots.calls_in_flight == pool, what="every thread of the server held")
        with pytest.raises(grpc.RpcError) as error:  # one more is refused, not queued
            proxy_robot_pb2_grpc.ProxyRobotStub(third).GetStatus(
                proxy_robot_pb2.GetStatusRequest(), timeout=10)
        assert error.value.code() is grpc.StatusCode.RESOURCE_EXHAUSTED
        for call in flood:
            call.cancel()
        wait_for(lambda: slots.calls_in_flight == 0, what="every call gone")
        assert robot.GetStatus(proxy_robot_pb2.GetStatusRequest(), timeout=10).reason == "high"
    finally:
        silent.release.set()
        for channel in (flooding, other, third):
            channel.close()
        server.stop(0)


# -- the counting itself ---------------------------------------------------------------------

def test_call_slots_count_by_caller_and_forget_callers_that_hold_nothing():
    slots = CallSlots(max_streams=3, streams_per_caller=2, calls_per_caller=1,
                      station_streams=1)
    alice, bob = Holder("identity alice", "alice"), Holder("identity bob", "bob")
    station, local = Holder(None, "station", station=True), Holder(None, "127.0.0.1")
    slots.take(alice, stream=True)
    slots.take(alice, stream=True)
    with pytest.raises(SlotRefused) as refused:
        slots.take(alice, stream=True)
    assert refused.value.reason == "CALLER_STREAMS_EXHAUSTED"
    slots.take(alice, stream=False)  # calls are counted apart from streams
    with pytest.raises(SlotRefused) as refused:
        slots.take(alice, stream=False)
    assert refused.value.reason == "CALLER_CALLS_EXHAUSTED"
    slots.take(local, stream=True)  # no per-caller cap, the server's
    with pytest.raises(SlotRefused) as refused:
        slots.take(bob, stream=True)
    assert refused.value.reason == "STREAMS_EXHAUSTED"
    slots.take(station, stream=True)  # its own room
    with pytest.raises(SlotRefused):
        slots.take(station, stream=True)
    assert (slots.open_streams, slots.calls_in_flight) == (4, 1)
    for holder, stream in ((alice, True), (alice, True), (alice, False), (local, True),
                           (station, True)):
        slots.give(holder, stream)
    assert (slots.open_streams, slots.calls_in_flight) == (0, 0)
    assert slots._held == {}  # noqa: SLF001 - no caller is remembered once it holds nothing


@pytest.mark.parametrize("peer,host", [("ipv4:127.0.0.1:5000", "127.0.0.1"),
                                       ("ipv6:[::1]:5000", "::1"),
                                       ("ipv4:10.0.0.2:41000", "10.0.0.2"),
                                       ("unix:/tmp/socket", "unix:/tmp/socket")])
def test_a_peer_is_its_host_whatever_its_port(peer, host):
    assert peer_host(peer) == host


# -- refusals for room are on record -----------------------------------------------------------

def test_refusals_for_room_are_counted_in_the_audit_logs_refusals(pki, tmp_path, aio, caplog):
    """Refused before authorization, by the caller's caps: each caller's refusals counted in
    its summary (the first of each method in full), whatever the method (a flood of reads or
    of Health watches too), and said in the log."""
    tokens = TokenStore(tmp_path / "tokens.json")
    log = AuditLog(tmp_path / "audit" / "decision_server.jsonl")
    blocker = threading.Event()

    class Slow(Decisions):
        def GetControlState(self, request, context):
            blocker.wait(20)
            return decision_server_pb2.GetControlStateResponse()

    security = ServerSecurity(pki, "decision_server", inner_port=False,
                              token_address="127.0.0.1:0", tokens=tokens, audit=log)
    server, port = create_server(
        "127.0.0.1:0", [binding(decision_server_pb2_grpc, "DecisionServer", Slow())],
        lanes=LANES, security=security, streams_per_caller=1, calls_per_caller=1, aio=aio)
    server.start()
    observer = tls_channel(pki, port, "observer")
    anonymous = grpc.secure_channel(
        f"127.0.0.1:{server.token_port}",
        grpc.ssl_channel_credentials((pki / "ca.pem").read_bytes()),
        options=[("grpc.ssl_target_name_override", "localhost")])
    caplog.set_level(logging.WARNING, logger="services.runtime.rpc")
    try:
        held = open_streams(observer, 1)
        for _ in range(2):
            assert reason_of(refused_stream(observer)) == "CALLER_STREAMS_EXHAUSTED"
        stub = decision_server_pb2_grpc.DecisionServerStub(observer)
        request = decision_server_pb2.GetControlStateRequest()
        slow = stub.GetControlState.future(request, timeout=30)
        wait_for(lambda: server.interceptor.slots.held_by("identity observer") == (1, 1),
                 what="the observer's call in the servicer")
        with pytest.raises(grpc.RpcError) as error:
            stub.GetControlState(request, timeout=10)
        assert reason_of(error.value) == "CALLER_CALLS_EXHAUSTED"
        health = health_pb2_grpc.HealthStub(anonymous)  # needs nothing, holds a slot
        watches = [health.Watch(health_pb2.HealthCheckRequest(), timeout=30)]
        next(watches[0])
        for _ in range(2):
            with pytest.raises(grpc.RpcError) as error:
                next(health.Watch(health_pb2.HealthCheckRequest(), timeout=30))
            assert reason_of(error.value) == "CALLER_STREAMS_EXHAUSTED"
        blocker.set()
        slow.result(timeout=10)
        for stream in held + watches:
            stream.cancel()
    finally:
        blocker.set()
        observer.close()
        anonymous.close()
        server.stop(0)
        log.close()
    assert not log.path.exists() or log.path.read_text() == ""  # no command: reads only
    refusals = [json.loads(line) for line in log.refusals_path.read_text().splitlines()]
    in_full = {(r["identity"], r["method"], r["detail"].split(":")[0]) for r in refusals
               if "time" in r}
    assert in_full == {("observer", STREAM_EVENTS, "CALLER_STREAMS_EXHAUSTED"),
                       ("observer", GET_CONTROL_STATE, "CALLER_CALLS_EXHAUSTED"),
                       ("", HEALTH_WATCH, "CALLER_STREAMS_EXHAUSTED")}
    assert all(r["outcome"] == "RESOURCE_EXHAUSTED" for r in refusals if "time" in r)
    counted = {r["source"]: (r["count"], r["methods"]) for r in refusals if "count" in r}
    assert counted == {"observer": (3, {STREAM_EVENTS: 2, GET_CONTROL_STATE: 1}),
                       "ipv4:127.0.0.1": (2, {HEALTH_WATCH: 2})}
    warned = [r.getMessage() for r in caplog.records if "for room" in r.getMessage()]
    assert warned and "CALLER_STREAMS_EXHAUSTED" in warned[0]


def test_refusals_for_room_are_said_in_the_log_at_most_once_a_minute(caplog):
    now = [100.0]
    warnings = RefusalWarnings(interval_s=60.0, clock=lambda: now[0])
    caplog.set_level(logging.WARNING, logger="services.runtime.rpc")
    for step in range(600):  # ten refusals a second for a minute
        warnings.refused(GET_STATUS, "identity 'flood'", "CALLER_CALLS_EXHAUSTED")
        now[0] = 100.0 + (step + 1) / 10
    said = [r.getMessage() for r in caplog.records]
    assert len(said) == 1 and said[0].startswith("refused 1 call(s)")
    warnings.refused(GET_STATUS, "identity 'flood'", "CALLER_CALLS_EXHAUSTED")
    assert len(caplog.records) == 2
    assert caplog.records[1].getMessage().startswith("refused 600 call(s)")
