"""The console's watch-only mode (--router): the page served anywhere behind a Zenoh router, from
the station's observation (wire/observation.py) instead of its DecisionServer. However many
browsers watch, the station publishes each stream once.

The page calls the same methods as ever; those the observation carries are answered from it:

    ProxyRobot.StreamState        telerobot/<station>/state, thinned to the request's period
                                  by sample time
    ForceSensor.StreamWrench      telerobot/<station>/wrench, with the request's decimation,
                                  change filter and batches (services.force_sensor.subscribers)
    StereoCamera.StreamPairs      telerobot/<station>/video: H.264 only, from the next header
                                  and its key frame, without receipts (nobody paces the station)
    DecisionServer.StreamEvents   telerobot/<station>/events
    DecisionServer.GetControlState, GetAssistance, GetDependencies
                                  the newest telerobot/<station>/status

Every other method is refused: one that commands (its declared role is above observer) with
PERMISSION_DENIED, a read the observation does not carry with UNIMPLEMENTED, each saying where to
go instead. The WebSockets are refused the same way (Teleoperate: PERMISSION_DENIED; receipts:
UNIMPLEMENTED).

A stream of the state, the wrench or the video that carried nothing for SILENCE_S ends with
UNAVAILABLE, so the page says the station went quiet instead of showing its last message as
live; the events may be quiet for any time.

Each stream has a queue of its own that keeps the newest messages: a browser that reads slower
than the station publishes loses the oldest (counted: the wrench's dropped_count, the events'
sequence gaps, a log line at the stream's end), never the router's or the station's time. Video
that lost a message waits for the next key frame, which comes within VIDEO_KEYFRAME_S.
"""

from __future__ import annotations

import asyncio
import logging
import time
from collections import deque
from collections.abc import AsyncIterator, Callable

import grpc
import zenoh
from connectrpc.code import Code
from connectrpc.errors import ConnectError
from connectrpc.request import RequestContext
from connectrpc.server import Endpoint
from google.protobuf.message import DecodeError

from services.common.decimation import Decimation
from services.force_sensor.servicer import reading_to_proto
from services.force_sensor.subscribers import (
    DEFAULT_QUEUE_CAPACITY,
    StreamOptions,
    WrenchReading,
    WrenchSelection,
)
from services.security.roles import Role, declared_role
from services.web_console import receipts, teleoperate
from services.web_console.bridge import method_info, served_methods
from telerobot.v1 import decision_server_pb2 as ds_pb
from telerobot.v1 import force_sensor_pb2 as fs_pb
from telerobot.v1 import stereo_camera_pb2 as sc_pb
from wire import convert
from wire.errors import TelerobotError
from wire.observation import STATUS_PERIOD_S, decode, key

log = logging.getLogger(__name__)

# Messages each stream's queue keeps: 0.16 s of the state at 100 Hz, 0.8 s of the video.
STATE_QUEUE = 16
EVENTS_QUEUE = 256
VIDEO_QUEUE = 8
# How long a status call waits for the station's first status, and how old the newest may be
# before the station counts as gone: two of its periods, then one more for the link.
STATUS_WAIT_S = 2 * STATUS_PERIOD_S
STATUS_STALE_S = 3 * STATUS_PERIOD_S
# A stream of the state, the wrench or the video (100, 100 and 10 messages a second, a key frame
# every 2 s) that carried nothing for this long ends with UNAVAILABLE: the page then says the
# station stopped publishing it (or the link is down), instead of showing the last as live.
SILENCE_S = 3.0


class RouterWatch:
    """The station's observation through a router, for the console's endpoints: a queue per
    stream, and the newest status, followed for the console's whole life (one small message a
    second)."""

    def __init__(self, session: zenoh.Session, station: str, router: str,
                 clock: Callable[[], float] = time.monotonic,
                 status_wait_s: float = STATUS_WAIT_S, silence_s: float = SILENCE_S):
        self.session = session
        self.station = station
        self.router = router
        self.silence_s = silence_s
        self._clock = clock
        self._status_wait_s = status_wait_s
        self._status: tuple[float, ds_pb.SessionStatus] | None = None
        self._status_subscriber: zenoh.Subscriber | None = None
        self._status_changed: asyncio.Event | None = None
        self._loop: asyncio.AbstractEventLoop | None = None

    def start(self) -> RouterWatch:
        """Follow the status from now on; call on the loop that serves the console."""
        self._loop = asyncio.get_running_loop()
        self._status_changed = asyncio.Event()
        self._status_subscriber = self.session.declare_subscriber(
            key(self.station, "status"), self._on_status)
        return self

    def close(self) -> None:
        if self._status_subscriber is not None:
            self._status_subscriber.undeclare()
            self._status_subscriber = None

    def describe(self) -> str:
        return f"station {self.station!r} through the router {self.router}"

    def queue(self, topic: str, capacity: int, steady: bool) -> TopicQueue:
        """A queue of `topic`; a `steady` one (published at a rate) fails after silence_s
        without a message."""
        return TopicQueue(self.session, key(self.station, topic), topic, capacity,
                          self.describe(), self.silence_s if steady else None)

    async def status(self) -> ds_pb.SessionStatus:
        """The newest status, waiting up to STATUS_WAIT_S for a first one; UNAVAILABLE when none
        came, or when the newest is older than STATUS_STALE_S (the station or the link is
        gone, and what it said may no longer hold)."""
        if self._status is None:
            try:
                async with asyncio.timeout(self._status_wait_s):
                    await self._status_changed.wait()
            except TimeoutError:
                raise ConnectError(Code.UNAVAILABLE, f"no status from {self.describe()} within "
                                   f"{self._status_wait_s:g} s: is the station publishing?"
                                   ) from None
        received, status = self._status
        age = self._clock() - received
        if age > STATUS_STALE_S:
            raise ConnectError(Code.UNAVAILABLE, f"the newest status from {self.describe()} is "
                               f"{age:.1f} s old: the station or the link is down")
        return status

    def _on_status(self, sample: zenoh.Sample) -> None:  # (a Zenoh thread)
        try:
            status = decode("status", sample.payload.to_bytes())
        except DecodeError as error:
            log.warning("a status from %s left out: %s", self.describe(), error)
            return
        _call_soon(self._loop, self._set_status, status)

    def _set_status(self, status: ds_pb.SessionStatus) -> None:
        self._status = (self._clock(), status)
        self._status_changed.set()


def _call_soon(loop: asyncio.AbstractEventLoop | None, callback, *args) -> None:
    """callback(*args) on `loop`, from a Zenoh thread; nothing once the loop has closed."""
    if loop is None:
        return
    try:
        loop.call_soon_threadsafe(callback, *args)
    except RuntimeError:
        pass  # the console stopped


class TopicQueue:
    """One stream's subscription to a topic: the newest `capacity` payloads, the oldest dropped
    (and counted) when the stream reads slower than the station publishes. Zenoh's thread only
    hands each payload to the loop, so it never waits for a browser."""

    def __init__(self, session: zenoh.Session, key_expr: str, topic: str, capacity: int,
                 source: str = "", silence_s: float | None = None):
        self.topic = topic
        self.source = source  # what it reads, for the errors it raises
        self.silence_s = silence_s
        self.dropped = 0
        self._items: deque[bytes] = deque(maxlen=capacity)
        self._arrived = asyncio.Event()
        self._loop = asyncio.get_running_loop()
        self._subscriber = session.declare_subscriber(key_expr, self._on_sample)

    def close(self) -> None:
        self._subscriber.undeclare()

    def _on_sample(self, sample: zenoh.Sample) -> None:  # (a Zenoh thread)
        _call_soon(self._loop, self._put, sample.payload.to_bytes())

    def _put(self, payload: bytes) -> None:
        if len(self._items) == self._items.maxlen:
            self.dropped += 1  # (the deque drops the oldest)
        self._items.append(payload)
        self._arrived.set()

    async def messages(self) -> AsyncIterator:
        """The decoded messages, oldest first, until the stream is cancelled; one that does not
        decode is logged and skipped. UNAVAILABLE once nothing came for `silence_s`."""
        while True:
            while not self._items:
                self._arrived.clear()
                try:
                    async with asyncio.timeout(self.silence_s):
                        await self._arrived.wait()
                except TimeoutError:
                    raise ConnectError(
                        Code.UNAVAILABLE, f"no {self.topic} from the {self.source} for "
                        f"{self.silence_s:g} s: the station stopped publishing it, or the link "
                        "is down") from None
            try:
                yield decode(self.topic, self._items.popleft())
            except DecodeError as error:
                log.warning("a %s message left out: %s", self.topic, error)


def _queued(watch: RouterWatch, topic: str, capacity: int, stream, steady: bool = True):
    """A server-stream function: `stream(request, queue)` over a queue of `topic` (`steady`:
    see RouterWatch.queue), which is closed (and its drops logged) when the browser leaves."""

    async def serve(request, ctx: RequestContext) -> AsyncIterator:
        queue = watch.queue(topic, capacity, steady)
        try:
            async for response in stream(request, queue):
                yield response
        finally:
            queue.close()
            if queue.dropped:
                log.info("a browser's %s stream read too slowly: %d messages dropped",
                         topic, queue.dropped)

    return serve


async def _state(request, queue: TopicQueue) -> AsyncIterator:
    period_s = convert.seconds(request.period)
    if period_s < 0:
        raise ConnectError(Code.INVALID_ARGUMENT, f"period must be >= 0, got {period_s} s")
    kept = Decimation(int(period_s * 1e9))
    async for response in queue.messages():
        if kept.keep(convert.time_ns(response.state.sample_time)):
            yield response


async def _wrench(request, queue: TopicQueue) -> AsyncIterator:
    try:
        selection = WrenchSelection(StreamOptions.from_request(
            request.decimation, request.threshold_force_n, request.threshold_torque_nm,
            request.batch_size, request.queue_capacity))
    except TelerobotError as error:
        raise ConnectError(Code[error.status_name], error.message) from None
    async for response in queue.messages():
        for sample in response.samples:
            readings = selection.take(_reading(sample))
            if readings is not None:
                yield fs_pb.StreamWrenchResponse(samples=[reading_to_proto(r) for r in readings],
                                                 dropped_count=queue.dropped)


def _reading(sample: fs_pb.WrenchSample) -> WrenchReading:
    return WrenchReading(sample.sequence, convert.time_ns(sample.sample_time),
                         convert.vector3_value(sample.wrench.force_n),
                         convert.vector3_value(sample.wrench.torque_nm))


async def _pairs(request, queue: TopicQueue) -> AsyncIterator:
    if request.encoding != sc_pb.IMAGE_ENCODING_H264:
        raise ConnectError(Code.UNIMPLEMENTED, "watching through a router, the video is the "
                           "station's H.264 stream only: ask for encoding IMAGE_ENCODING_H264")
    dropped_seen, started = 0, False
    async for response in queue.messages():
        if queue.dropped != dropped_seen:  # a frame lost: nothing decodes until a key frame
            dropped_seen, started = queue.dropped, False
        if response.WhichOneof("content") == "header":
            started = True  # (the publisher puts one right before each key frame)
        if started:
            yield response


async def _events(request, queue: TopicQueue) -> AsyncIterator:
    async for response in queue.messages():
        yield response


def _status_reply(watch: RouterWatch, reply: Callable[[ds_pb.SessionStatus], object]):
    async def unary(request, ctx: RequestContext):
        return reply(await watch.status())

    return unary


def _refusal(path: str, watch: RouterWatch):
    role = declared_role(path)
    if role is not None and role > Role.OBSERVER:
        code, why = Code.PERMISSION_DENIED, (
            f"this console only watches ({watch.describe()}): {path} commands the station, "
            "which only its own console or DecisionServer takes")
    else:
        code, why = Code.UNIMPLEMENTED, (
            f"this console only watches ({watch.describe()}), and the router does not carry "
            f"{path}: ask the station's own console or DecisionServer")

    async def refuse(request, ctx: RequestContext):
        raise ConnectError(code, why)

    return refuse


def _refusing_stream(path: str, watch: RouterWatch):
    refuse = _refusal(path, watch)

    async def stream(request, ctx: RequestContext) -> AsyncIterator:
        await refuse(request, ctx)
        yield  # (never reached: an async generator)

    return stream


def watch_endpoints(watch: RouterWatch) -> dict[str, Endpoint]:
    """Path -> endpoint for every method the console serves (bridge.served_methods): from the
    observation where it carries the answer, refused otherwise."""
    streams = {
        "/telerobot.v1.ProxyRobot/StreamState": _queued(watch, "state", STATE_QUEUE, _state),
        "/telerobot.v1.ForceSensor/StreamWrench": _queued(
            watch, "wrench", DEFAULT_QUEUE_CAPACITY, _wrench),
        "/telerobot.v1.StereoCamera/StreamPairs": _queued(watch, "video", VIDEO_QUEUE, _pairs),
        "/telerobot.v1.DecisionServer/StreamEvents": _queued(watch, "events", EVENTS_QUEUE,
                                                             _events, steady=False),
    }
    unaries = {
        "/telerobot.v1.DecisionServer/GetControlState": _status_reply(
            watch, lambda s: ds_pb.GetControlStateResponse(state=s.control)),
        "/telerobot.v1.DecisionServer/GetAssistance": _status_reply(
            watch, lambda s: ds_pb.GetAssistanceResponse(assistance=s.assistance)),
        "/telerobot.v1.DecisionServer/GetDependencies": _status_reply(
            watch, lambda s: ds_pb.GetDependenciesResponse(dependencies=s.dependencies)),
    }
    served = {}
    for service, method in served_methods():
        path, info = method_info(service, method)
        if method.server_streaming:
            served[path] = Endpoint.server_stream(
                method=info, function=streams.get(path) or _refusing_stream(path, watch))
        else:
            served[path] = Endpoint.unary(
                method=info, function=unaries.get(path) or _refusal(path, watch))
    return served


# The WebSockets' refusals: driving commands the arm; receipts pace a station that this
# console does not reach.
SOCKET_REFUSALS = {
    teleoperate.PATH: (grpc.StatusCode.PERMISSION_DENIED, "this console only watches: drive "
                       "from the station's own console"),
    receipts.PATH: (grpc.StatusCode.UNIMPLEMENTED, "this console only watches: the router's "
                    "video takes no receipts"),
}
