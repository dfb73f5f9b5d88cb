"""Observation over Zenoh: keys and endpoints, the publisher (a real Zenoh router and client
sessions in this process, fake upstream streams) and the observer's counts. The station's own
router and publisher, end to end, are in tests/observation/test_station_observation.py."""

from __future__ import annotations

import itertools

import grpc
import pytest
import zenoh
from google.protobuf.timestamp_pb2 import Timestamp

from clients.observe import Observer
from services.observation.publisher import ObservationPublisher
from services.observation.status import StatusStream
from services.security import pki
from telerobot.v1 import decision_server_pb2 as ds_pb
from telerobot.v1 import force_sensor_pb2 as fs_pb
from tests.conftest import wait_for
from tests.fake_calls import FakeCall
from wire.observation import (
    BadEndpoint,
    SessionPlan,
    ZenohTls,
    checked_endpoint,
    client,
    decode,
    key,
    station_name,
    topic_of,
)

T0_NS = 1_700_000_000_000_000_000


def test_keys_name_the_station_and_the_topic():
    assert key("lab-3", "wrench") == "telerobot/lab-3/wrench"
    assert topic_of("telerobot/lab-3/wrench") == ("lab-3", "wrench")
    assert topic_of("telerobot/lab-3/other") is None
    assert topic_of("elsewhere/lab-3/wrench") is None
    with pytest.raises(KeyError, match="unknown topic"):
        key("lab-3", "commands")


@pytest.mark.parametrize("name", ["a/b", "*", "x" * 65, "lab 3"])
def test_a_station_name_that_is_no_key_chunk_is_refused(name):
    with pytest.raises(ValueError, match="station name"):
        station_name(name)


def test_the_station_name_defaults_to_its_variable_then_station(monkeypatch):
    monkeypatch.delenv("TELEROBOT_STATION", raising=False)
    assert station_name(None) == "station"
    monkeypatch.setenv("TELEROBOT_STATION", "lab-3")
    assert station_name(None) == "lab-3"


@pytest.mark.parametrize("endpoint", ["tcp/127.0.0.1:7447", "tcp/localhost:7447",
                                      "tcp/[::1]:7447", "tcp/127.0.0.1:0"])
def test_loopback_endpoints_are_taken(endpoint):
    assert checked_endpoint(endpoint) == endpoint


@pytest.mark.parametrize("endpoint, why", [
    ("tcp/10.0.0.2:7447", "beyond loopback"),
    ("tcp/0.0.0.0:7447", "beyond loopback"),
    ("tcp/robot.lab:7447", "beyond loopback"),
    ("udp/127.0.0.1:7447", "expected tcp/HOST:PORT"),
    ("127.0.0.1:7447", "expected tcp/HOST:PORT"),
    ("tcp/127.0.0.1", "expected tcp/HOST:PORT"),
])
def test_other_endpoints_are_refused_saying_why(endpoint, why):
    with pytest.raises(BadEndpoint, match=why):
        checked_endpoint(endpoint)
    with pytest.raises(BadEndpoint):
        SessionPlan("client", connect=(endpoint,)).config()


def stamp(ns: int) -> Timestamp:
    value = Timestamp()
    value.FromNanoseconds(ns)
    return value


def wrench_message(*sequences: int) -> fs_pb.StreamWrenchResponse:
    return fs_pb.StreamWrenchResponse(samples=[
        fs_pb.WrenchSample(sequence=s, sample_time=stamp(T0_NS + s * 1_000_000))
        for s in sequences])


class Streams:
    """Fake upstream streams, one FakeCall per open, by topic."""

    def __init__(self, *topics: str):
        self.calls: dict[str, list[FakeCall]] = {topic: [] for topic in topics}

    def opener(self, topic: str):
        def open_stream() -> FakeCall:
            self.calls[topic].append(FakeCall())
            return self.calls[topic][-1]
        return open_stream

    def all(self) -> dict:
        return {topic: self.opener(topic) for topic in self.calls}


def test_a_stream_is_followed_only_while_someone_subscribes_and_published_once(sessions):
    streams = Streams("wrench", "events")
    publisher = ObservationPublisher(sessions(), "lab-3", streams.all()).start()
    try:
        assert publisher.following() == {"wrench": False, "events": False}
        assert streams.calls == {"wrench": [], "events": []}  # nobody watches: no stream
        observers = [Observer(sessions(), "lab-3", ("wrench",)) for _ in range(2)]
        wait_for(lambda: len(streams.calls["wrench"]) == 1, what="the wrench stream opened")
        assert publisher.following() == {"wrench": True, "events": False}
        streams.calls["wrench"][0].items.put(wrench_message(1, 2, 3))
        wait_for(lambda: all(o.counts["wrench"].samples == 3 for o in observers),
                 what="both observers got the samples")
        assert len(streams.calls["wrench"]) == 1  # two subscribers, one upstream stream
        assert publisher.published["wrench"] == 1
        for observer in observers:
            observer.close()
        wait_for(lambda: streams.calls["wrench"][0].cancelled.is_set(),
                 what="the stream cancelled once nobody watches")
        assert streams.calls["events"] == []
    finally:
        publisher.close()


def test_the_observer_decodes_counts_lost_samples_and_measures_lag(sessions):
    clock = itertools.count(T0_NS + 10_000_000, 1_000_000)  # 10 ms after sample 0, then +1 ms
    streams = Streams("wrench", "events")
    publisher = ObservationPublisher(sessions(), "lab-3", streams.all()).start()
    seen = []
    observer = Observer(sessions(), "lab-3", ("wrench", "events"),
                        on_message=lambda topic, message: seen.append(topic),
                        clock_ns=lambda: next(clock))
    try:
        wait_for(lambda: streams.calls["wrench"] and streams.calls["events"],
                 what="both streams opened")
        wrench = streams.calls["wrench"][0]
        wrench.items.put(wrench_message(1, 2))
        wrench.items.put(wrench_message(6, 7))  # 3, 4 and 5 lost on the way
        wait_for(lambda: observer.counts["wrench"].samples == 4, what="the wrench arrived")
        streams.calls["events"][0].items.put(ds_pb.StreamEventsResponse(
            sequence=1, event_time=stamp(T0_NS)))
        wait_for(lambda: observer.counts["events"].messages == 1, what="the event arrived")
        summary = observer.summary()
        assert summary["wrench"]["messages"] == 2 and summary["wrench"]["lost"] == 3
        assert summary["events"]["lost"] == 0
        assert seen == ["wrench", "wrench", "events"]
        # Each message is stamped once on arrival, 1 ms apart from 10 ms after sample 0.
        assert observer.counts["wrench"].lags_ms == [9.0, 8.0, 5.0, 4.0]
        assert observer.counts["events"].lags_ms == [12.0]
    finally:
        observer.close()
        publisher.close()


def test_a_payload_that_is_no_message_is_counted_not_raised(sessions):
    observer = Observer(sessions(), "lab-3", ("wrench",))
    try:
        sessions().put("telerobot/lab-3/wrench", b"\xff\xff\xff")
        wait_for(lambda: observer.counts["wrench"].undecodable == 1, what="counted")
        assert observer.counts["wrench"].messages == 0
    finally:
        observer.close()


def test_an_observer_of_an_unknown_topic_is_refused(sessions):
    with pytest.raises(ValueError, match="unknown topics"):
        Observer(sessions(), "lab-3", ("commands",))


def test_the_payload_is_the_streams_own_message():
    message = wrench_message(5)
    assert decode("wrench", message.SerializeToString()) == message


# -- mutual TLS and the router's access rules ------------------------------------------------

def test_over_tls_only_the_station_publishes_and_observers_subscribe(pki_dir, tls_router):
    station = client(tls_router, ZenohTls(pki_dir, "observation"))
    observer = client(tls_router, ZenohTls(pki_dir, "observer"))
    try:
        counts = Observer(observer, "lab-3", ("wrench",)).counts["wrench"]
        watcher = Observer(station, "lab-3", ("events",)).counts["events"]
        publisher = station.declare_publisher(key("lab-3", "wrench"))
        wait_for(lambda: publisher.matching_status.matching, what="the observer subscribed")
        forged = ds_pb.StreamEventsResponse(sequence=1, event_time=stamp(T0_NS))
        observer.put(key("lab-3", "events"), forged.SerializeToString())  # refused
        publisher.put(wrench_message(1).SerializeToString())
        wait_for(lambda: counts.messages == 1, what="the station's sample delivered")
        publisher.put(wrench_message(2).SerializeToString())  # after the forged one
        wait_for(lambda: counts.messages == 2, what="the next sample")
        assert watcher.messages == 0  # the observer's put never got through the router
    finally:
        observer.close()
        station.close()


def test_a_tls_router_takes_no_plaintext_and_no_stranger(pki_dir, tls_router, tmp_path):
    port = tls_router.rsplit(":", 1)[1]
    with pytest.raises(zenoh.ZError):
        client(f"tcp/127.0.0.1:{port}")
    pki.init(tmp_path / "other")  # another CA: its certificates mean nothing here
    with pytest.raises(zenoh.ZError):
        client(tls_router, ZenohTls(tmp_path / "other", "observer"))


def test_tls_endpoints_need_a_tls_directory_and_its_files(pki_dir, tmp_path):
    with pytest.raises(BadEndpoint, match="give the station's TLS directory"):
        checked_endpoint("tls/10.0.0.2:7447")
    assert checked_endpoint("tls/10.0.0.2:7447", tls=True) == "tls/10.0.0.2:7447"
    with pytest.raises(BadEndpoint, match="make certs"):
        SessionPlan("client", connect=("tls/127.0.0.1:7447",),
                    tls=ZenohTls(tmp_path, "observer")).config()


# -- the session's status ---------------------------------------------------------------------

class FakeDoor:
    """A DecisionServer's read side: its events stream (a FakeCall) and its lock, which the
    test changes; counts the status reads (one GetControlState each)."""

    def __init__(self):
        self.events = FakeCall()
        self.holder = ""
        self.reads = 0
        self.down = False  # the DecisionServer not answering its reads

    def StreamEvents(self, request):
        return self.events

    def GetControlState(self, request, timeout):
        if self.down:
            raise FakeCall.Ended(grpc.StatusCode.UNAVAILABLE)
        self.reads += 1
        holders = [ds_pb.ControlHolder(operator_id=self.holder)] if self.holder else []
        return ds_pb.GetControlStateResponse(state=ds_pb.ControlState(holders=holders))

    def GetAssistance(self, request, timeout):
        return ds_pb.GetAssistanceResponse()

    def GetDependencies(self, request, timeout):
        return ds_pb.GetDependenciesResponse(dependencies=[ds_pb.Dependency(
            name="proxy_robot", state=ds_pb.DEPENDENCY_STATE_SERVING)])


def test_the_status_is_read_at_once_then_after_each_change_of_the_session():
    door = FakeDoor()
    statuses = iter(StatusStream(door, period_s=3600, clock_ns=lambda: T0_NS))
    first = next(statuses)
    assert first.status_time == stamp(T0_NS) and not first.control.holders
    assert [d.name for d in first.dependencies] == ["proxy_robot"]
    door.holder = "ada"
    door.events.items.put(ds_pb.StreamEventsResponse(
        control_changed=ds_pb.ControlChangedEvent()))
    second = next(statuses)  # read again after the lock's event, not an hour later
    assert [h.operator_id for h in second.control.holders] == ["ada"] and door.reads == 2
    door.events.items.put(grpc.StatusCode.UNAVAILABLE)
    with pytest.raises(grpc.RpcError):  # the events ended: the Feed reopens the stream
        next(statuses)


def test_a_status_read_that_fails_ends_the_stream_and_its_events():
    door = FakeDoor()
    door.down = True
    with pytest.raises(grpc.RpcError):
        next(iter(StatusStream(door, period_s=3600)))
    assert door.events.cancelled.is_set()
