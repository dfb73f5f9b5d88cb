"""The web console's watch-only mode (services/web_console/watch.py) without a browser: a real
Zenoh router in this process, a session of the test's own putting the station's messages under
its keys, and the console served by uvicorn, called over the Connect protocol (HTTP/1.1) and its
WebSockets. The page in Chromium against a whole station: tests/web_console/test_watch_page.py."""

from __future__ import annotations

import asyncio
import contextlib
import http.client
import json
import struct

import pytest
from websockets.sync.client import connect

from services.web_console.__main__ import main
from services.web_console.app import ConsoleApp
from services.web_console.watch import RouterWatch, TopicQueue, _pairs
from telerobot.v1 import decision_server_pb2 as ds_pb
from telerobot.v1 import force_sensor_pb2 as fs_pb
from telerobot.v1 import proxy_robot_pb2 as pr_pb
from telerobot.v1 import stereo_camera_pb2 as sc_pb
from telerobot.v1 import types_pb2
from tests.conftest import wait_for
from tests.observation.conftest import RELIABLY
from tests.observation.test_observation import T0_NS, stamp
from tests.web_console.test_limits import serving
from wire import convert
from wire.observation import RouterUnreachable, ZenohTls, client, join_router, key

STATION = "lab-3"


class FakeClock:
    def __init__(self):
        self.now = 100.0

    def __call__(self) -> float:
        return self.now


@pytest.fixture
def station(sessions):
    """The station's side: put(topic, message) once the console subscribes to the topic."""
    session = sessions()
    publishers = {}

    def put(topic: str, message) -> None:
        if topic not in publishers:
            publishers[topic] = session.declare_publisher(key(STATION, topic),
                                                          congestion_control=RELIABLY)
            wait_for(lambda: publishers[topic].matching_status.matching, timeout_s=10,
                     what=f"the console subscribed to {topic}")
        publishers[topic].put(message.SerializeToString())

    return put


@pytest.fixture
def console(router, sessions):
    """The watch-only console on a free port: (port, its RouterWatch's clock)."""
    clock = FakeClock()
    watch = RouterWatch(sessions(), STATION, router, clock=clock)
    with serving(ConsoleApp(watch, "none")) as (_, port):
        yield port, clock


def call(port: int, method: str, request) -> tuple[int, bytes]:
    """A unary Connect call in binary: (HTTP status, body)."""
    connection = http.client.HTTPConnection("127.0.0.1", port, timeout=10)
    try:
        connection.request("POST", f"/telerobot.v1.{method}", request.SerializeToString(),
                           {"content-type": "application/proto"})
        reply = connection.getresponse()
        return reply.status, reply.read()
    finally:
        connection.close()


class StreamEnded(Exception):
    def __init__(self, end: dict):
        super().__init__(f"the stream ended: {end}")
        self.end = end


@contextlib.contextmanager
def stream(port: int, method: str, request):
    """A server-streaming Connect call, sent: yields next_message(), which returns the next
    message's bytes, or raises StreamEnded with the stream's end message (its error)."""
    connection = http.client.HTTPConnection("127.0.0.1", port, timeout=10)
    body = request.SerializeToString()
    connection.request("POST", f"/telerobot.v1.{method}", struct.pack(">BI", 0, len(body)) + body,
                       {"content-type": "application/connect+proto"})
    replies = []  # the response's head comes with the first message: read then

    def next_message() -> bytes:
        if not replies:
            replies.append(connection.getresponse())
            assert replies[0].status == 200, replies[0].read()
        reply = replies[0]
        flags, length = struct.unpack(">BI", reply.read(5))
        data = reply.read(length)
        if flags & 0x02:
            raise StreamEnded(json.loads(data))
        return data

    try:
        yield next_message
    finally:
        connection.close()


def end_of(port: int, method: str, request) -> dict:
    """The end message of a stream that fails at once."""
    with stream(port, method, request) as next_message:
        with pytest.raises(StreamEnded) as ended:
            next_message()
    return ended.value.end


def status(holder: str = "alice") -> ds_pb.SessionStatus:
    return ds_pb.SessionStatus(
        control=ds_pb.ControlState(holders=[ds_pb.ControlHolder(operator_id=holder)]),
        assistance=ds_pb.AssistanceConfig(scaling=ds_pb.Scaling(translation_scale=0.5)),
        dependencies=[ds_pb.Dependency(name="proxy_robot")])


def test_the_lock_assistance_and_dependencies_come_from_the_newest_status(console, station):
    port, clock = console
    station("status", status("alice"))
    wait_for(lambda: call(port, "DecisionServer/GetControlState",
                          ds_pb.GetControlStateRequest())[0] == 200, what="a status")
    code, body = call(port, "DecisionServer/GetControlState", ds_pb.GetControlStateRequest())
    assert [h.operator_id for h in ds_pb.GetControlStateResponse.FromString(body).state.holders
            ] == ["alice"]
    station("status", status("bob"))
    wait_for(lambda: ds_pb.GetControlStateResponse.FromString(call(
        port, "DecisionServer/GetControlState", ds_pb.GetControlStateRequest())[1]
    ).state.holders[0].operator_id == "bob", what="the newer status")
    code, body = call(port, "DecisionServer/GetAssistance", ds_pb.GetAssistanceRequest())
    assert ds_pb.GetAssistanceResponse.FromString(body).assistance.scaling.translation_scale == 0.5
    code, body = call(port, "DecisionServer/GetDependencies", ds_pb.GetDependenciesRequest())
    assert [d.name for d in ds_pb.GetDependenciesResponse.FromString(body).dependencies
            ] == ["proxy_robot"]
    clock.now += 3.5  # no status for longer than STATUS_STALE_S: the station may be gone
    code, body = call(port, "DecisionServer/GetControlState", ds_pb.GetControlStateRequest())
    assert code == 503 and json.loads(body)["code"] == "unavailable"
    assert "s old" in json.loads(body)["message"]


def test_a_status_call_before_any_status_is_unavailable(router, sessions):
    watch = RouterWatch(sessions(), STATION, router, status_wait_s=0.2)
    with serving(ConsoleApp(watch, "none")) as (_, port):
        code, body = call(port, "DecisionServer/GetControlState", ds_pb.GetControlStateRequest())
    assert code == 503 and "is the station publishing?" in json.loads(body)["message"]


def arm_state(ms: int) -> pr_pb.StreamStateResponse:
    return pr_pb.StreamStateResponse(state=types_pb2.RobotState(
        sample_time=stamp(T0_NS + ms * 1_000_000), joint_positions_rad=[ms / 1000]))


def test_the_state_is_thinned_to_the_requested_period_of_sample_time(console, station):
    port, _ = console
    request = pr_pb.StreamStateRequest(period=convert.duration(0.05))
    with stream(port, "ProxyRobot/StreamState", request) as next_message:
        for ms in range(0, 120, 10):  # 100 Hz, as the station publishes it
            station("state", arm_state(ms))
        kept = [convert.time_ns(pr_pb.StreamStateResponse.FromString(next_message())
                                .state.sample_time) for _ in range(3)]
    assert [(t - T0_NS) // 1_000_000 for t in kept] == [0, 50, 100]
    assert end_of(port, "ProxyRobot/StreamState", pr_pb.StreamStateRequest(
        period=convert.duration(-1.0)))["error"]["code"] == "invalid_argument"


def wrench_message(*sequences: int) -> fs_pb.StreamWrenchResponse:
    return fs_pb.StreamWrenchResponse(samples=[fs_pb.WrenchSample(
        sequence=s, sample_time=stamp(T0_NS + s * 1_000_000),
        wrench=types_pb2.Wrench(force_n=types_pb2.Vector3(z=float(s)))) for s in sequences])


def test_the_wrench_keeps_the_requested_decimation_and_batches(console, station):
    port, _ = console
    request = fs_pb.StreamWrenchRequest(decimation=2, batch_size=3)
    with stream(port, "ForceSensor/StreamWrench", request) as next_message:
        station("wrench", wrench_message(*range(1, 11)))  # the station's batches of ten
        station("wrench", wrench_message(*range(11, 21)))
        batches = [fs_pb.StreamWrenchResponse.FromString(next_message()) for _ in range(3)]
    assert [[s.sequence for s in b.samples] for b in batches] == [
        [1, 3, 5], [7, 9, 11], [13, 15, 17]]
    assert batches[2].samples[1].wrench.force_n.z == 15.0
    assert all(b.dropped_count == 0 for b in batches)
    assert end_of(port, "ForceSensor/StreamWrench", fs_pb.StreamWrenchRequest(
        decimation=-1))["error"]["code"] == "invalid_argument"


def pair(sequence: int, keyframe: bool = False) -> sc_pb.StreamPairsResponse:
    return sc_pb.StreamPairsResponse(pair=sc_pb.StereoPair(
        sequence=sequence, keyframe=keyframe, video_frame=b"\0\0\0\1" + bytes([sequence])))


HEADER = sc_pb.StreamPairsResponse(header=sc_pb.StereoHeader(stream_id="video-1"))


def test_the_video_starts_at_a_header_and_takes_h264_only(console, station):
    port, _ = console
    request = sc_pb.StreamPairsRequest(encoding=sc_pb.IMAGE_ENCODING_H264, receipts=True)
    with stream(port, "StereoCamera/StreamPairs", request) as next_message:
        station("video", pair(1))  # mid-stream: nothing decodes from here
        station("video", HEADER)
        station("video", pair(2, keyframe=True))
        station("video", pair(3))
        got = [sc_pb.StreamPairsResponse.FromString(next_message()) for _ in range(3)]
    assert got[0].header.stream_id == "video-1"
    assert [(m.pair.sequence, m.pair.keyframe) for m in got[1:]] == [(2, True), (3, False)]
    refused = end_of(port, "StereoCamera/StreamPairs", sc_pb.StreamPairsRequest(
        encoding=sc_pb.IMAGE_ENCODING_JPEG))["error"]
    assert refused["code"] == "unimplemented" and "H.264" in refused["message"]


def test_a_stream_the_station_stopped_publishing_ends_saying_so(router, sessions, station):
    watch = RouterWatch(sessions(), STATION, router, silence_s=0.5)
    with serving(ConsoleApp(watch, "none")) as (_, port):
        with stream(port, "ProxyRobot/StreamState", pr_pb.StreamStateRequest()) as next_message:
            station("state", arm_state(0))
            next_message()
            with pytest.raises(StreamEnded) as ended:  # nothing more: the station went quiet
                next_message()
    error = ended.value.end["error"]
    assert error["code"] == "unavailable" and "no state from the station 'lab-3'" in (
        error["message"])


def test_the_events_pass_as_the_station_raised_them(console, station):
    port, _ = console
    with stream(port, "DecisionServer/StreamEvents", ds_pb.StreamEventsRequest()) as next_message:
        station("events", ds_pb.StreamEventsResponse(sequence=41, event_time=stamp(T0_NS)))
        assert ds_pb.StreamEventsResponse.FromString(next_message()).sequence == 41


def test_a_lost_video_frame_skips_to_the_next_header(router, sessions, station):
    """A browser that reads slower than the station puts loses the oldest frames; the frames
    after a loss do not decode, so the stream resumes at the next header and its key frame."""
    async def scenario() -> list[tuple[str, int]]:
        queue = TopicQueue(sessions(), key(STATION, "video"), "video", capacity=3)
        pairs = aiter(_pairs(sc_pb.StreamPairsRequest(encoding=sc_pb.IMAGE_ENCODING_H264), queue))
        got = []

        async def take(count: int) -> None:
            for _ in range(count):
                message = await anext(pairs)
                got.append((message.WhichOneof("content"), message.pair.sequence))

        try:
            station("video", HEADER)
            station("video", pair(1, keyframe=True))
            await take(2)
            for sequence in (2, 3, 4, 5):  # read too slowly: pair 2 is lost
                station("video", pair(sequence))
            await asyncio.to_thread(wait_for, lambda: queue.dropped == 1, 10, "pair 2 dropped")
            station("video", HEADER)
            station("video", pair(6, keyframe=True))
            await take(2)
            return got
        finally:
            await pairs.aclose()
            queue.close()

    assert asyncio.run(scenario()) == [("header", 0), ("pair", 1), ("header", 0), ("pair", 6)]


def test_commands_and_reads_the_router_does_not_carry_are_refused(console):
    port, _ = console
    code, body = call(port, "DecisionServer/AcquireControl",
                      ds_pb.AcquireControlRequest(operator_id="mallory"))
    assert code == 403 and json.loads(body)["code"] == "permission_denied"
    assert "only watches" in json.loads(body)["message"]
    code, body = call(port, "ProxyRobot/GetArmInfo", pr_pb.GetArmInfoRequest())
    assert code == 501 and json.loads(body)["code"] == "unimplemented"
    with connect(f"ws://127.0.0.1:{port}/ws/teleoperate", origin=f"http://127.0.0.1:{port}",
                 subprotocols=["telerobot.v1.teleoperate"]) as socket:
        with pytest.raises(Exception) as closed:
            socket.recv(timeout=10)
    assert closed.value.rcvd.code == 4000 + 7  # PERMISSION_DENIED
    connection = http.client.HTTPConnection("127.0.0.1", port, timeout=10)
    connection.request("GET", "/")
    page = connection.getresponse().read()
    assert f"station &#x27;{STATION}&#x27; through the router tcp/127.0.0.1".encode() in page


def test_over_tls_the_console_watches_as_an_observer(pki_dir, tls_router):
    station = client(tls_router, ZenohTls(pki_dir, "observation"))
    watch = RouterWatch(join_router(tls_router, str(pki_dir), "observer"), STATION, tls_router)
    try:
        with serving(ConsoleApp(watch, "none")) as (_, port):
            publisher = station.declare_publisher(key(STATION, "status"),
                                                  congestion_control=RELIABLY)
            wait_for(lambda: publisher.matching_status.matching, timeout_s=10,
                     what="the console subscribed to the status")
            publisher.put(status("tls-ann").SerializeToString())
            code, body = call(port, "DecisionServer/GetControlState",
                              ds_pb.GetControlStateRequest())
        assert code == 200, body
        assert ds_pb.GetControlStateResponse.FromString(body).state.holders[0].operator_id == (
            "tls-ann")
    finally:
        watch.session.close()
        station.close()
    # The console's HTTPS certificate is a server's only: it speaks for nobody at a router.
    with pytest.raises(RouterUnreachable):
        join_router(tls_router, str(pki_dir), "web_console").close()


@pytest.mark.parametrize("args, code, says", [
    (["--router", "tcp/10.1.2.3:7447"], 2, "plaintext beyond loopback"),
    (["--router", "tls/127.0.0.1:7447"], 2, "give the station's TLS directory"),
    (["--router", "tcp/127.0.0.1:7447", "--station", "a/b"], 2, "station name"),
    (["--router", "tcp/127.0.0.1:9"], 1, "does not answer"),
])
def test_bad_router_arguments_say_why(args, code, says, capsys):
    assert main(["--address", "127.0.0.1:0", *args]) == code
    assert says in capsys.readouterr().err


def test_a_watch_only_console_beyond_loopback_needs_allow_network(capsys):
    assert main(["--address", "0.0.0.0:0", "--router", "tcp/127.0.0.1:9"]) == 2
    assert "anyone who reaches it would watch" in capsys.readouterr().err
    # Allowed, it still needs HTTPS (or --allow-plaintext-network) beyond loopback.
    assert main(["--address", "0.0.0.0:0", "--router", "tcp/127.0.0.1:9",
                 "--allow-network"]) == 2
    assert "over plain HTTP" in capsys.readouterr().err
