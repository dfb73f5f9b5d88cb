"""The live view's feeds from a Zenoh router (--router), instead of the station's services: the
view then runs anywhere behind a router, beside a remote team's own router for instance, and
the station serves each stream once however many views watch.

Each feed subscribes to its topic of the station's observation (wire/observation.py) while a
viewer watches one of its Foxglove topics, and reads it on a thread of its own through a ring of
the newest messages, so a slow view skips messages instead of queueing them:

- ``state``: telerobot/<station>/state (100 Hz), kept at --state-hz of sample time;
- ``wrench``: telerobot/<station>/wrench (every 1 kHz sample), kept at --wrench-hz;
- ``video``: telerobot/<station>/video: its header sets the cameras (their frames join /tf),
  its pairs go to /camera/stereo/video. A newcomer starts at the next key frame, which the
  publisher sends at least every VIDEO_KEYFRAME_S (services/observation/video.py).

The per-eye JPEG images are not published into Zenoh: a view from a router has no ``stereo``
feed, and does not advertise its topics.
"""

from __future__ import annotations

import logging
import threading
from collections.abc import Callable

import zenoh
from google.protobuf.message import DecodeError

from services.common.decimation import Decimation
from services.foxglove.live import STATE, VIDEO, WRENCH, LiveChannels
from wire.observation import decode, key

log = logging.getLogger(__name__)

RING_MESSAGES = 8  # per feed: 80 ms of the wrench, 0.8 s of the video
ROUTER_FEEDS = (STATE, WRENCH, VIDEO)


class RouterFeed:
    """One topic of the station's observation, subscribed to while wanted. `handle(message)`
    takes each decoded message on the feed's reader thread; one it cannot decode or show is
    logged (once per kind) and skipped."""

    def __init__(self, name: str, session: zenoh.Session, station: str, topic: str,
                 handle: Callable):
        self.name = name
        self._session = session
        self._key = key(station, topic)
        self._topic = topic
        self._handle = handle
        self._lock = threading.Lock()
        self._subscriber: zenoh.Subscriber | None = None
        self._told: set[str] = set()  # the kinds of failure logged already

    def start(self) -> RouterFeed:
        return self

    def want(self, wanted: bool) -> None:
        with self._lock:
            subscriber = self._subscriber
            if wanted and subscriber is None:
                self._subscriber = self._session.declare_subscriber(
                    self._key, zenoh.handlers.RingChannel(RING_MESSAGES))
                threading.Thread(target=self._read, args=(self._subscriber,), daemon=True,
                                 name=f"router-{self.name}").start()
            elif not wanted and subscriber is not None:
                self._subscriber = None
                subscriber.undeclare()  # (its reader ends with it)

    def stop(self) -> None:
        self.want(False)

    def _read(self, subscriber: zenoh.Subscriber) -> None:
        for sample in subscriber:  # until undeclared
            try:
                message = decode(self._topic, sample.payload.to_bytes())
                self._handle(message)
            except (DecodeError, ValueError) as error:
                kind = type(error).__name__
                if kind not in self._told:
                    self._told.add(kind)
                    log.warning("live view: a %s message from %s left out (%s: %s)",
                                self.name, self._key, kind, error)


def router_feeds(channels: LiveChannels, session: zenoh.Session, station: str, *,
                 state_hz: float, wrench_hz: float) -> dict[str, RouterFeed]:
    """The live view's feeds (ROUTER_FEEDS) from `station`'s observation on `session`."""
    state_rate, wrench_rate = Decimation.at_rate(state_hz), Decimation.at_rate(wrench_hz)

    def on_state(response) -> None:
        if state_rate.keep(response.state.sample_time.ToNanoseconds()):
            channels.robot_state(response.state)

    def on_wrench(response) -> None:
        for sample in response.samples:
            if wrench_rate.keep(sample.sample_time.ToNanoseconds()):
                channels.wrench(sample)

    def on_video(response) -> None:
        if response.WhichOneof("content") == "header":
            channels.set_cameras(response.header)
        else:
            channels.stereo_video(response.pair)

    return {STATE: RouterFeed(STATE, session, station, "state", on_state),
            WRENCH: RouterFeed(WRENCH, session, station, "wrench", on_wrench),
            VIDEO: RouterFeed(VIDEO, session, station, "video", on_video)}
