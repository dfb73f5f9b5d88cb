"""ObservationPublisher: each of the station's observed streams published once into Zenoh,
and followed only while someone subscribes.

Each topic (wire/observation.py) has a Zenoh publisher and a Feed (services.common.feeds) that
follows the service's own gRPC stream, as any observer would. The feed is open only while a
subscriber matches the topic anywhere behind the router (Zenoh's matching status), so a station
nobody watches serves no stream for it; however many subscribe, the service serves one.

A put never waits: congestion control drops what a slow link or subscriber cannot take
(CongestionControl.DROP), so a subscriber that falls behind loses samples, never the station's
time. The wrench's sequence numbers show each subscriber what it lost.
"""

from __future__ import annotations

import collections
import logging
import threading
from collections.abc import Callable, Iterator

import grpc
import zenoh
from google.protobuf import duration_pb2

from services.common.feeds import Feed
from services.observation.status import StatusStream
from services.observation.video import VideoStream
from telerobot.v1 import decision_server_pb2 as ds_pb
from telerobot.v1 import (
    decision_server_pb2_grpc,
    force_sensor_pb2_grpc,
    proxy_robot_pb2_grpc,
    stereo_camera_pb2_grpc,
)
from telerobot.v1 import force_sensor_pb2 as fs_pb
from telerobot.v1 import proxy_robot_pb2 as pr_pb
from wire.observation import STATE_PERIOD_S, TOPICS, WRENCH_BATCH, key

log = logging.getLogger(__name__)

# The wrench stream's queue at the sensor, in batches: a publisher that stalls for this long
# (0.5 s) loses the oldest, as any slow subscriber does.
WRENCH_QUEUE_BATCHES = 50

OpenStream = Callable[[], Iterator]


def station_streams(proxy_robot: grpc.Channel, force_sensor: grpc.Channel,
                    decision_server: grpc.Channel,
                    stereo_camera: grpc.Channel) -> dict[str, OpenStream]:
    """topic -> how to open the service stream it publishes (read-only calls, role observer;
    the video's receipts only report and ask for key frames)."""
    robot = proxy_robot_pb2_grpc.ProxyRobotStub(proxy_robot)
    sensor = force_sensor_pb2_grpc.ForceSensorStub(force_sensor)
    door = decision_server_pb2_grpc.DecisionServerStub(decision_server)
    camera = stereo_camera_pb2_grpc.StereoCameraStub(stereo_camera)
    period = duration_pb2.Duration()
    period.FromNanoseconds(int(STATE_PERIOD_S * 1e9))
    streams = {
        "wrench": lambda: sensor.StreamWrench(fs_pb.StreamWrenchRequest(
            batch_size=WRENCH_BATCH, queue_capacity=WRENCH_QUEUE_BATCHES)),
        "state": lambda: robot.StreamState(pr_pb.StreamStateRequest(period=period)),
        "events": lambda: door.StreamEvents(ds_pb.StreamEventsRequest()),
        "status": lambda: StatusStream(door),
        "video": lambda: VideoStream(camera),
    }
    assert streams.keys() == TOPICS.keys()
    return streams


class ObservationPublisher:
    """Publishes `streams` ({topic: open_stream}) under telerobot/<station>/<topic> on
    `session`. `on_status(topic, why)` hears why a feed's stream ended while subscribed, and
    (topic, None) once it flows again. `published` counts the messages put, per topic."""

    def __init__(self, session: zenoh.Session, station: str, streams: dict[str, OpenStream],
                 on_status: Callable[[str, str | None], None] = lambda topic, why: None):
        self.published: collections.Counter[str] = collections.Counter()
        self._lock = threading.Lock()
        self._publishers, self._feeds, self._listeners = {}, {}, []
        for topic, open_stream in streams.items():
            publisher = session.declare_publisher(
                key(station, topic), congestion_control=zenoh.CongestionControl.DROP)
            self._publishers[topic] = publisher
            self._feeds[topic] = Feed(topic, open_stream, self._putter(topic, publisher),
                                      on_status)

    def start(self) -> ObservationPublisher:
        for topic, feed in self._feeds.items():
            feed.start()
            publisher = self._publishers[topic]
            # Follow the stream while anyone subscribes: the listener hears each change, and
            # the status read after declaring it covers a subscriber that came before.
            self._listeners.append(publisher.declare_matching_listener(
                lambda status, feed=feed: feed.want(status.matching)))
            feed.want(publisher.matching_status.matching)
        return self

    def following(self) -> dict[str, bool]:
        """topic -> whether a subscriber matches it now (its stream is followed)."""
        return {topic: p.matching_status.matching for topic, p in self._publishers.items()}

    def close(self) -> None:
        for listener in self._listeners:
            listener.undeclare()
        for feed in self._feeds.values():
            feed.stop()
        for publisher in self._publishers.values():
            publisher.undeclare()

    def _putter(self, topic: str, publisher: zenoh.Publisher) -> Callable:
        def put(message) -> None:
            publisher.put(message.SerializeToString())
            with self._lock:
                self.published[topic] += 1
        return put
