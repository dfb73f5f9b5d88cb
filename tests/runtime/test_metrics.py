"""Each server's Prometheus metrics, over a real in-process gRPC server on port 0 and a real
/metrics endpoint on another: counts by method and code, latency histograms, the lanes' queue
depth and waits. The servicers are fixtures; the interceptor, lanes and metrics are real. Every
count is checked against exactly the calls made: each call is counted before its answer leaves
the server, so no test waits for a count to appear."""

from __future__ import annotations

import json
import re
import threading
import urllib.request
from concurrent import futures
from pathlib import Path
from types import SimpleNamespace

import grpc
import pytest
from prometheus_client.parser import text_string_to_metric_families

from services.common.fanout import Fanout
from services.decision_server.__main__ import _LeaseChanges
from services.decision_server.core import ControlChanged, DecisionEvent
from services.runtime.lanes import Lane, LaneConfig
from services.runtime.metrics import LATENCY_BUCKETS_S, ServiceMetrics
from services.runtime.process import metrics_port_name
from services.runtime.server import binding, create_server
from services.world.service import WorldService
from telerobot.v1 import (
    decision_server_pb2,
    decision_server_pb2_grpc,
    proxy_robot_pb2,
    proxy_robot_pb2_grpc,
)
from tests.conftest import wait_for
from wire.errors import OutOfRangeError
from wire.processes import parse_ready_line

GET_STATUS = "/telerobot.v1.ProxyRobot/GetStatus"
MOVE = "/telerobot.v1.ProxyRobot/MoveJointsIncremental"
EVENTS = "/telerobot.v1.ProxyRobot/StreamRobotEvents"
STOP = "/telerobot.v1.ProxyRobot/EmergencyStop"
LIST = "/telerobot.v1.DecisionServer/ListRecordings"

LANES = {
    Lane.EMERGENCY: LaneConfig(static_threads=1, max_threads=1, queue_capacity=2),
    Lane.HIGH: LaneConfig(static_threads=1, max_threads=2, queue_capacity=4),  # room: inline
    Lane.MEDIUM: LaneConfig(static_threads=1, max_threads=2, queue_capacity=4),
    # One thread and no room to run inline: a second call queues behind a running one.
    Lane.LOW: LaneConfig(static_threads=1, max_threads=1, queue_capacity=4),
}


class Robot(proxy_robot_pb2_grpc.ProxyRobotServicer):
    def GetStatus(self, request, context):
        return proxy_robot_pb2.GetStatusResponse(reason="fine")

    def MoveJointsIncremental(self, request, context):
        raise OutOfRangeError("joint 2 would pass its limit", reason="JOINT_LIMIT")

    def EmergencyStop(self, request, context):
        raise RuntimeError("a bug in the handler")  # grpcio answers UNKNOWN

    def StreamRobotEvents(self, request, context):
        for sequence in range(3):
            yield proxy_robot_pb2.StreamRobotEventsResponse(sequence=sequence)


class Decisions(decision_server_pb2_grpc.DecisionServerServicer):
    """ListRecordings (low lane) holds its lane's one thread until released."""

    def __init__(self):
        self.release = threading.Event()

    def ListRecordings(self, request, context):
        self.release.wait(10)
        return decision_server_pb2.ListRecordingsResponse()


class Station:
    def __init__(self, on_emergency_call=None, aio=False):
        self.decisions = Decisions()
        self.metrics = ServiceMetrics("test")
        self.server, port = create_server(
            "127.0.0.1:0",
            [binding(proxy_robot_pb2_grpc, "ProxyRobot", Robot()),
             binding(decision_server_pb2_grpc, "DecisionServer", self.decisions)],
            lanes=LANES, metrics=self.metrics, on_emergency_call=on_emergency_call, aio=aio)
        self.server.start()
        self.metrics_port = self.metrics.serve("127.0.0.1:0")
        self.channel = grpc.insecure_channel(f"127.0.0.1:{port}")
        self.robot = proxy_robot_pb2_grpc.ProxyRobotStub(self.channel)
        self.decision = decision_server_pb2_grpc.DecisionServerStub(self.channel)

    def scrape(self) -> dict[tuple[str, frozenset], float]:
        """Every sample on /metrics: (sample name, its labels) -> value, parsed with
        prometheus_client's own parser."""
        url = f"http://127.0.0.1:{self.metrics_port}/metrics"
        with urllib.request.urlopen(url, timeout=5) as reply:
            assert reply.status == 200
            text = reply.read().decode()
        return {(sample.name, frozenset(sample.labels.items())): sample.value
                for family in text_string_to_metric_families(text)
                for sample in family.samples}

    def close(self):
        self.decisions.release.set()
        self.channel.close()
        self.server.stop(0)
        self.metrics.close()


@pytest.fixture(params=[False, True], ids=["sync", "aio"])
def station(request):
    station = Station(aio=request.param)
    yield station
    station.close()


def value(samples, name, default=0.0, **labels) -> float:
    return samples.get((name, frozenset(labels.items())), default)


def calls(samples, method, code) -> float:
    return value(samples, "telerobot_rpc_handled_total", method=method, code=code)


def test_calls_are_counted_by_method_and_code(station):
    for _ in range(3):
        station.robot.GetStatus(proxy_robot_pb2.GetStatusRequest(), timeout=5)
    for _ in range(2):
        with pytest.raises(grpc.RpcError) as error:
            station.robot.MoveJointsIncremental(
                proxy_robot_pb2.MoveJointsIncrementalRequest(delta_joint_positions_rad=[0.1] * 6),
                timeout=5)
        assert error.value.code() is grpc.StatusCode.OUT_OF_RANGE
    # Refused by the interceptor before the handler runs: counted too.
    with pytest.raises(grpc.RpcError) as error:
        station.robot.GetStatus(proxy_robot_pb2.GetStatusRequest(),
                                metadata=[("telerobot-lane", "urgent")], timeout=5)
    assert error.value.code() is grpc.StatusCode.INVALID_ARGUMENT
    # A handler's bug: UNKNOWN, as without metrics.
    with pytest.raises(grpc.RpcError) as error:
        station.robot.EmergencyStop(proxy_robot_pb2.EmergencyStopRequest(), timeout=5)
    assert error.value.code() is grpc.StatusCode.UNKNOWN
    # A stream that ends on its own.
    assert len(list(station.robot.StreamRobotEvents(
        proxy_robot_pb2.StreamRobotEventsRequest(), timeout=5))) == 3

    samples = station.scrape()
    assert calls(samples, GET_STATUS, "OK") == 3
    assert calls(samples, GET_STATUS, "INVALID_ARGUMENT") == 1
    assert calls(samples, MOVE, "OUT_OF_RANGE") == 2
    assert calls(samples, STOP, "UNKNOWN") == 1
    assert calls(samples, EVENTS, "OK") == 1
    handled = {labels: count for (name, labels), count in samples.items()
               if name == "telerobot_rpc_handled_total"}
    assert sum(handled.values()) == 3 + 1 + 2 + 1 + 1  # nothing else (no scrape is a call)

    # Latency: one observation per unary call, whatever its code; none for the stream.
    histogram = "telerobot_rpc_duration_seconds"
    assert value(samples, f"{histogram}_count", method=GET_STATUS) == 4
    assert value(samples, f"{histogram}_count", method=MOVE) == 2
    assert value(samples, f"{histogram}_count", method=STOP) == 1
    assert (f"{histogram}_count", frozenset({("method", EVENTS)})) not in samples
    buckets = sorted(float(dict(labels)["le"]) for (name, labels) in samples
                     if name == f"{histogram}_bucket" and dict(labels)["method"] == GET_STATUS)
    assert buckets == [*LATENCY_BUCKETS_S, float("inf")]
    assert buckets[0] == 0.0001  # sub-millisecond
    assert value(samples, f"{histogram}_bucket", method=GET_STATUS, le="+Inf") == 4


def test_counts_move_by_exactly_the_calls_made(station):
    station.robot.GetStatus(proxy_robot_pb2.GetStatusRequest(), timeout=5)
    before = station.scrape()
    for _ in range(5):
        station.robot.GetStatus(proxy_robot_pb2.GetStatusRequest(), timeout=5)
    after = station.scrape()
    assert calls(after, GET_STATUS, "OK") - calls(before, GET_STATUS, "OK") == 5
    count = "telerobot_rpc_duration_seconds_count"
    assert (value(after, count, method=GET_STATUS)
            - value(before, count, method=GET_STATUS)) == 5
    # Every GetStatus ran at once on the thread that received it (the high lane had room).
    wait = "telerobot_lane_wait_seconds"
    assert value(after, f"{wait}_count", lane="high") == 6
    assert value(after, f"{wait}_bucket", lane="high", le="0.0") == 6
    assert value(after, "telerobot_lane_inline_total", lane="high") == 6
    assert value(after, "telerobot_lane_served_total", lane="high") == 6


def test_lane_queue_depth_and_waits(station):
    pool = futures.ThreadPoolExecutor(2)
    request = decision_server_pb2.ListRecordingsRequest()
    try:
        first = pool.submit(station.decision.ListRecordings, request, timeout=10)
        wait_for(lambda: station.server.executor.counters()[Lane.LOW].running == 1,
                 what="the first call running")
        second = pool.submit(station.decision.ListRecordings, request, timeout=10)
        wait_for(lambda: station.server.executor.counters()[Lane.LOW].queued == 1,
                 what="the second call queued")
        during = station.scrape()
        station.decisions.release.set()
        first.result(timeout=10)
        second.result(timeout=10)
    finally:
        station.decisions.release.set()
        pool.shutdown()
    assert value(during, "telerobot_lane_queued", lane="low") == 1
    assert value(during, "telerobot_lane_running", lane="low") == 1
    assert value(during, "telerobot_lane_threads", lane="low") == 1
    assert value(during, "telerobot_lane_queued", lane="high", default=None) == 0
    assert value(during, "telerobot_lane_wait_seconds_count", lane="low") == 1  # the first

    after = station.scrape()
    assert value(after, "telerobot_lane_queued", lane="low") == 0
    assert value(after, "telerobot_lane_served_total", lane="low") == 2
    # Both were handed to the lane's thread (none ran inline): two waits, none zero.
    assert value(after, "telerobot_lane_wait_seconds_count", lane="low") == 2
    assert value(after, "telerobot_lane_wait_seconds_bucket", lane="low", le="0.0") == 0
    assert calls(after, LIST, "OK") == 2


def test_servers_in_one_process_keep_separate_counts():
    one, two = Station(), Station()
    try:
        one.robot.GetStatus(proxy_robot_pb2.GetStatusRequest(), timeout=5)
        two.robot.GetStatus(proxy_robot_pb2.GetStatusRequest(), timeout=5)
        two.robot.GetStatus(proxy_robot_pb2.GetStatusRequest(), timeout=5)
        assert calls(one.scrape(), GET_STATUS, "OK") == 1
        assert calls(two.scrape(), GET_STATUS, "OK") == 2
    finally:
        one.close()
        two.close()


def test_a_failing_metric_never_fails_a_call(station, monkeypatch):
    def broken(*_args, **_kwargs):
        raise RuntimeError("the metrics are broken")

    monkeypatch.setattr(station.metrics._rpcs, "labels", broken)
    monkeypatch.setattr(station.metrics._lane_wait, "labels", broken)
    reply = station.robot.GetStatus(proxy_robot_pb2.GetStatusRequest(), timeout=5)
    assert reply.reason == "fine"
    with pytest.raises(grpc.RpcError) as error:
        station.robot.MoveJointsIncremental(
            proxy_robot_pb2.MoveJointsIncrementalRequest(delta_joint_positions_rad=[0.1] * 6),
            timeout=5)
    assert error.value.code() is grpc.StatusCode.OUT_OF_RANGE  # not UNKNOWN
    station.scrape()  # still answers


def test_the_metrics_ready_line():
    name, address = parse_ready_line(f"TELEROBOT_READY {metrics_port_name('world')} "
                                     "127.0.0.1:9100")
    assert (name, address) == ("world_metrics", "127.0.0.1:9100")


def test_emergency_stop_latency_is_observed_per_stop():
    stops = []
    station = Station(on_emergency_call=lambda: stops.append("latched"))
    try:
        for _ in range(2):
            with pytest.raises(grpc.RpcError):  # the fixture's handler fails; the stop latched
                station.robot.EmergencyStop(proxy_robot_pb2.EmergencyStopRequest(), timeout=5)
        station.robot.GetStatus(proxy_robot_pb2.GetStatusRequest(), timeout=5)  # no stop
        samples = station.scrape()
    finally:
        station.close()
    assert stops == ["latched", "latched"]
    latency = "telerobot_emergency_stop_latency_seconds"
    assert value(samples, f"{latency}_count") == 2
    assert value(samples, f"{latency}_bucket", le="0.0001", default=None) is not None
    assert calls(samples, STOP, "UNKNOWN") == 2


def test_stream_drops_watched_values_and_lease_changes(station):
    fanout: Fanout[int] = Fanout()
    fanout.on_dropped = lambda: station.metrics.dropped("robot_states")
    slow = fanout.subscribe(capacity=1)
    for item in range(4):
        fanout.publish(item)
    assert slow.dropped == 3

    steps = [0]
    station.metrics.watch("telerobot_world_steps", "Physics steps run", lambda: steps[0],
                          counter=True)
    station.metrics.watch("telerobot_world_worst_lateness_seconds", "Largest lateness",
                          lambda: 0.0015)
    station.metrics.watch("telerobot_broken", "A reading that fails", lambda: 1 / 0)
    steps[0] = 1000

    events: Fanout[DecisionEvent] = Fanout()
    events.attach(_LeaseChanges(events, station.metrics))
    events.publish(DecisionEvent(1, 0, ControlChanged(None, "granted")))
    events.publish(DecisionEvent(2, 0, "something else"))
    events.publish(DecisionEvent(3, 0, ControlChanged(None, "released")))

    samples = station.scrape()  # the failing reading is left out, the rest is served
    assert value(samples, "telerobot_stream_dropped_total", stream="robot_states") == 3
    assert value(samples, "telerobot_world_steps_total") == 1000
    assert value(samples, "telerobot_world_worst_lateness_seconds") == 0.0015
    assert ("telerobot_broken", frozenset()) not in samples
    assert value(samples, "telerobot_events_total", event="lease_change") == 2


def test_stream_lags_and_command_ages_are_histograms(station):
    fanout: Fanout[int] = Fanout()
    fanout.on_lag = lambda lag_s: station.metrics.stream_lagged("robot_states", lag_s)
    subscription = fanout.subscribe()
    for item in range(3):
        fanout.publish(item)
    assert [subscription.get(0) for _ in range(3)] == [0, 1, 2]
    station.metrics.command_aged(0.150)  # a command across a 300 ms round trip
    station.metrics.command_aged(-0.002)  # the operator's clock is ahead: counted as 0

    samples = station.scrape()
    lag = "telerobot_stream_lag_seconds"
    assert value(samples, f"{lag}_count", stream="robot_states") == 3
    assert value(samples, f"{lag}_bucket", stream="robot_states", le="1.0") == 3
    age = "telerobot_command_age_seconds"
    assert value(samples, f"{age}_count") == 2
    assert value(samples, f"{age}_bucket", le="0.0001") == 1
    assert value(samples, f"{age}_bucket", le="0.2") == 2
    assert value(samples, f"{age}_sum") == pytest.approx(0.150)


def test_the_grafana_dashboard_asks_only_for_metrics_a_service_serves(station):
    dashboard = json.loads((Path(__file__).parents[2] / "docs/grafana_dashboard.json")
                           .read_text())
    WorldService.configure(SimpleNamespace(loop=None), lambda *_: None, station.metrics)
    url = f"http://127.0.0.1:{station.metrics_port}/metrics"
    with urllib.request.urlopen(url, timeout=5) as reply:
        families = {family.name for family in text_string_to_metric_families(reply.read()
                                                                               .decode())}
    exprs = [target["expr"] for panel in dashboard["panels"] for target in panel["targets"]]
    asked = {re.sub(r"_(bucket|count|sum|total)$", "", name)
             for expr in exprs for name in re.findall(r"\b(?:telerobot|process)_\w+", expr)}
    assert asked and asked <= families, sorted(asked - families)
