"""The live view's core: the station's feeds published on Foxglove channels, and which feeds
the viewers want. No grpc here (services.foxglove.feeds reads the services; __main__ serves).

Four feeds, each an upstream stream that runs only while a viewer watches one of its topics,
so an idle live view costs the station nothing (the cameras render only for subscribers):

- ``state`` (ProxyRobot.StreamState): /tf (the arm's frames from Pinocchio, and the cameras'),
  /joint_states and our own /robot/state;
- ``wrench`` (ForceSensor.StreamWrench): /force/arrow and our own /robot/wrench (tool axes);
- ``stereo`` (StereoCamera.StreamPairs, JPEG): each eye's /camera/…/image and
  /camera/…/calibration;
- ``video`` (StereoCamera.StreamPairs, H.264, with receipts): /camera/stereo/video, both eyes
  side by side in one CompressedVideo frame per pair, as the camera encoded it.

A video viewer must start at a key frame, and the camera sends one only when a stream opens or
its client asks (a receipt's want_keyframe). The SDK sends a channel's messages to all its
subscribers alike (its Python Client has no sink id to log to one viewer), so when a viewer
subscribes to the video mid-stream, the channel holds back every frame, for everyone, until
the key frame the feed then asks for: the newcomer's first frame is that key frame, and the
others miss about one frame. Reopening the upstream stream would also start with a key frame,
but costs a new stream (header, encoder, pacing from scratch) and a longer gap for everyone.
The SDK adds a subscription just before it tells the listener, so a frame sent in that instant
could still reach a newcomer ahead of its key frame; Foxglove's and Lichtblick's players skip
to the first key frame anyway. The feed also asks for a key frame every KEYFRAME_REFRESH_S, so
that a viewer whose WebSocket dropped a frame (the SDK drops a slow client's oldest messages)
or whose decoder failed recovers in bounded time.

Each channel's schema is the message's protobuf file descriptors, as in the MCAP recordings, so
Foxglove, Lichtblick or any client of the Foxglove WebSocket protocol decodes it as it comes.
Log times are the sample's own time (sample or capture time, ns since the epoch).

"""

from __future__ import annotations

import logging
import threading
import time
from collections import Counter
from collections.abc import Callable

from foxglove import Channel, Context, Schema
from mcap_protobuf.schema import build_file_descriptor_set

from services.common.keyframes import KEYFRAME_RETRY_S, KeyframePacing
from telerobot.v1 import force_sensor_pb2 as fs_pb
from telerobot.v1 import stereo_camera_pb2 as sc_pb
from telerobot.v1 import types_pb2
from wire import foxglove as fox

log = logging.getLogger(__name__)

STATE, WRENCH, STEREO, VIDEO = "state", "wrench", "stereo", "video"
FEED_TOPICS: dict[str, tuple[str, ...]] = {
    STATE: (fox.TF, fox.JOINT_STATES, fox.ROBOT_STATE),
    WRENCH: (fox.FORCE_ARROW, fox.ROBOT_WRENCH),
    STEREO: (fox.LEFT_IMAGE, fox.RIGHT_IMAGE, fox.LEFT_CALIBRATION, fox.RIGHT_CALIBRATION),
    VIDEO: (fox.STEREO_VIDEO,),
}
KEYFRAME_REFRESH_S = 4.0  # the video's longest run without a key frame
LIVE_TOPICS: dict[str, type] = {**fox.FOXGLOVE_TOPICS, fox.ROBOT_STATE: types_pb2.RobotState,
                                fox.ROBOT_WRENCH: types_pb2.Wrench}
_FEED_OF_TOPIC = {topic: feed for feed, topics in FEED_TOPICS.items() for topic in topics}


def protobuf_schema(message_class: type) -> Schema:
    """A Foxglove schema for a protobuf message class: its name and file descriptors."""
    descriptors = build_file_descriptor_set(message_class).SerializeToString()
    return Schema(name=message_class.DESCRIPTOR.full_name, encoding="protobuf", data=descriptors)


class Demand:
    """Which feeds the viewers want: a feed is wanted while any client subscribes to any of its
    topics. `on_change(feed, wanted)` is called when that flips (from the server's thread),
    under the lock, so two flips are never told in the wrong order; it must not block.
    `on_join(topic)`, if given, hears every new subscription to one of the feeds' topics (after
    the flip it may cause), so that the video can start a newcomer at a key frame."""

    def __init__(self, on_change: Callable[[str, bool], None],
                 on_join: Callable[[str], None] | None = None):
        self._on_change = on_change
        self._on_join = on_join
        self._lock = threading.Lock()
        self._subscribers: dict[str, set[tuple[int, str]]] = {feed: set() for feed in FEED_TOPICS}

    def subscribed(self, client_id: int, topic: str) -> None:
        self._update(client_id, topic, add=True)

    def unsubscribed(self, client_id: int, topic: str) -> None:
        self._update(client_id, topic, add=False)

    def wanted(self, feed: str) -> bool:
        with self._lock:
            return bool(self._subscribers[feed])

    def _update(self, client_id: int, topic: str, add: bool) -> None:
        feed = _FEED_OF_TOPIC.get(topic)
        if feed is None:
            return
        with self._lock:
            watchers = self._subscribers[feed]
            before = bool(watchers)
            joined = add and (client_id, topic) not in watchers
            (watchers.add if add else watchers.discard)((client_id, topic))
            if before != bool(watchers):
                self._on_change(feed, not before)
            if joined and self._on_join is not None:
                self._on_join(topic)

    # The foxglove.websocket.ServerListener protocol (the SDK calls these on its own thread).
    def on_subscribe(self, client, channel) -> None:
        self.subscribed(client.id, channel.topic)

    def on_unsubscribe(self, client, channel) -> None:
        self.unsubscribed(client.id, channel.topic)


class LiveChannels:
    """The live view's channels in a Foxglove context, and what the feeds hand them. Each feed
    calls its own methods from one thread; a message is converted and serialized only when its
    channel has a subscriber."""

    def __init__(self, context: Context, clock: Callable[[], float] = time.monotonic,
                 feeds: tuple[str, ...] = tuple(FEED_TOPICS)):
        """Advertises the topics of `feeds` (of FEED_TOPICS): a feed the view cannot follow
        shows no topic."""
        advertised = {topic for feed in feeds for topic in FEED_TOPICS[feed]}
        self._channels = {topic: Channel(topic, schema=protobuf_schema(message_class),
                                         message_encoding="protobuf", context=context)
                          for topic, message_class in LIVE_TOPICS.items()
                          if topic in advertised}
        self._arm = fox.ArmTransforms()  # the state feed's thread only
        self._header: sc_pb.StereoHeader | None = None
        self._lock = threading.Lock()
        self.published: Counter[str] = Counter()
        self.skipped: Counter[str] = Counter()  # messages with no Foxglove form (said once)
        # The video's key frames (under _lock): held back until one comes, after a newcomer.
        self._video_held = False  # frames are held back until the next key frame
        self._keyframes = KeyframePacing(KEYFRAME_REFRESH_S, KEYFRAME_RETRY_S, clock)
        self.held_back = 0  # video frames held back waiting for a key frame

    def cameras_unknown(self) -> bool:
        return self._header is None

    def set_cameras(self, header: sc_pb.StereoHeader) -> None:
        """The cameras' calibration: their frames go into /tf from now on."""
        self._header = header
        self._arm.set_cameras(header)

    def robot_state(self, state: types_pb2.RobotState) -> None:
        stamp = state.sample_time.ToNanoseconds()
        self._publish(fox.ROBOT_STATE, lambda: state, stamp)
        self._publish(fox.JOINT_STATES, lambda: fox.joint_states(state), stamp)
        self._publish(fox.TF, lambda: self._arm.state_transforms(state), stamp)

    def wrench(self, sample: fs_pb.WrenchSample) -> None:
        stamp = sample.sample_time.ToNanoseconds()
        self._publish(fox.ROBOT_WRENCH, lambda: sample.wrench, stamp)
        self._publish(fox.FORCE_ARROW, lambda: fox.force_arrow(sample.wrench, stamp), stamp)

    def stereo_pair(self, pair: sc_pb.StereoPair) -> None:
        """A pair from the stream whose header set_cameras() was given (none yet: skipped)."""
        stamp, header = pair.left_capture_time.ToNanoseconds(), self._header
        if header is None:
            return
        for topic, convert in (
                (fox.LEFT_IMAGE, lambda: fox.camera_images(pair)[0]),
                (fox.RIGHT_IMAGE, lambda: fox.camera_images(pair)[1]),
                (fox.LEFT_CALIBRATION, lambda: fox.camera_calibrations(header, stamp)[0]),
                (fox.RIGHT_CALIBRATION, lambda: fox.camera_calibrations(header, stamp)[1])):
            self._publish(topic, convert, stamp)

    def viewer_joined(self, topic: str) -> None:
        """A viewer subscribed to `topic` (Demand's on_join): a video newcomer gets nothing
        until the next key frame, which is asked for."""
        if topic != fox.STEREO_VIDEO:
            return
        with self._lock:
            self._video_held = True
            self._keyframes.ask()

    def stereo_video(self, pair: sc_pb.StereoPair) -> None:
        """A pair of the H.264 stream: its access unit on /camera/stereo/video, unless frames
        are held back for a newcomer and this is not a key frame."""
        with self._lock:
            if pair.keyframe:
                self._video_held = False
                self._keyframes.keyframe()
            elif self._video_held:
                self.held_back += 1
                return
        self._publish(fox.STEREO_VIDEO, lambda: fox.stereo_video(pair),
                      pair.left_capture_time.ToNanoseconds())

    def video_stream_opened(self) -> None:
        """A new upstream video stream: its first frame is a key frame, no need to ask."""
        with self._lock:
            self._keyframes.keyframe()

    def take_keyframe_request(self) -> bool:
        """Whether the video feed's next receipt should ask for a key frame: a newcomer waits
        for one (asked again every KEYFRAME_RETRY_S until it comes), or none came for
        KEYFRAME_REFRESH_S."""
        with self._lock:
            return self._keyframes.due()

    def _publish(self, topic: str, convert, stamp_ns: int) -> None:
        channel = self._channels[topic]
        if not channel.has_sinks():
            return
        message = self._converted(topic, convert)
        if message is None:
            return
        channel.log(message.SerializeToString(), log_time=int(stamp_ns))
        with self._lock:
            self.published[topic] += 1

    def _converted(self, topic: str, convert):
        try:
            return convert()
        except ValueError as error:
            with self._lock:
                if not self.skipped[topic]:
                    log.warning("live view: %s left out (%s)", topic, error)
                self.skipped[topic] += 1
            return None

    def close(self) -> None:
        for channel in self._channels.values():
            channel.close()
