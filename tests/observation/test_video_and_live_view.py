"""The video topic and the live view from a router: a real Zenoh router and sessions in this
process, the observation publisher following a real in-process StereoCamera (the pattern
source) and fake wrench and state streams, and the Foxglove live view's router feeds behind a
real foxglove-sdk server with a client of the Foxglove protocol. Across two routers and a
delayed link, end to end: tests/observation/test_two_routers.py."""

from __future__ import annotations

import foxglove
import pytest
from foxglove_schemas_protobuf.CompressedVideo_pb2 import CompressedVideo

from clients.observe import Observer
from services.common.decimation import Decimation
from services.common.keyframes import KeyframePacing
from services.foxglove.live import FEED_TOPICS, STEREO, Demand, LiveChannels
from services.foxglove.router_feeds import RING_MESSAGES, ROUTER_FEEDS, router_feeds
from services.observation.publisher import ObservationPublisher
from services.observation.video import VideoStream
from services.stereo_camera.pattern import PatternSource
from telerobot.v1 import proxy_robot_pb2 as pr_pb
from telerobot.v1 import types_pb2
from tests.conftest import wait_for
from tests.foxglove.test_live_video import check_the_pictures
from tests.foxglove.ws_client import FoxgloveClient
from tests.observation.test_observation import T0_NS, Streams, stamp, wrench_message
from tests.stereo_camera.conftest import start_camera
from wire import foxglove as fx

W, H = 160, 120  # tests.foxglove.test_live_video's pattern, which check_the_pictures reads


class FakeClock:
    def __init__(self):
        self.now = 100.0

    def __call__(self) -> float:
        return self.now


def test_a_key_frame_is_asked_for_when_none_came_for_a_while_and_again_until_it_comes():
    clock = FakeClock()
    pacing = KeyframePacing(every_s=2.0, retry_s=0.5, clock=clock)
    clock.now += 1.9
    assert not pacing.due()
    clock.now += 0.1
    assert pacing.due() and not pacing.due()  # asked once
    clock.now += 0.4
    assert not pacing.due()
    clock.now += 0.1
    assert pacing.due()  # not come within retry_s: asked again
    pacing.keyframe()
    clock.now += 1.9
    assert not pacing.due()


def test_decimation_keeps_a_sample_per_period_of_sample_time():
    rate = Decimation.at_rate(50.0)  # 20 ms
    kept = [ms for ms in range(0, 100) if rate.keep(T0_NS + ms * 1_000_000)]
    assert kept == [0, 20, 40, 60, 80]
    assert rate.keep(T0_NS)  # time went back: a restarted stream starts over


@pytest.fixture
def camera():
    camera = start_camera(PatternSource(W, H, fps=30))
    yield camera
    camera.close()


def test_the_video_topic_puts_the_header_before_every_key_frame(sessions, camera):
    pacing = KeyframePacing(every_s=0.3)  # (the real clock: the camera's own pace)
    streams = {"video": lambda: VideoStream(camera.stub, pacing)}
    publisher = ObservationPublisher(sessions(), "lab-3", streams).start()
    messages = []
    observer = Observer(sessions(), "lab-3", ("video",),
                        on_message=lambda topic, message: messages.append(message))
    try:
        wait_for(lambda: sum(m.WhichOneof("content") == "pair" and m.pair.keyframe
                             for m in list(messages)) >= 3, timeout_s=30,
                 what="three key frames")
    finally:
        observer.close()
        publisher.close()
    kinds = ["header" if m.WhichOneof("content") == "header"
             else "key" if m.pair.keyframe else "delta" for m in messages]
    assert kinds[:2] == ["header", "key"], kinds[:5]
    for index, kind in enumerate(kinds):
        assert (kind == "key") == (index > 0 and kinds[index - 1] == "header"), kinds
    assert messages[0].header.width_px == W and messages[0].header.stream_id
    # Every key frame asked for by the pacing: there is no other way to get a second one.
    pairs = [CompressedVideo(data=m.pair.video_frame) for m in messages
             if m.WhichOneof("content") == "pair"]
    check_the_pictures(pairs)
    assert observer.counts["video"].samples == len(pairs)


@pytest.fixture
def live_view(sessions):
    """A live view whose feeds read the router: its channels, feeds and server's URL."""
    context = foxglove.Context()
    channels = LiveChannels(context, feeds=ROUTER_FEEDS)
    feeds = router_feeds(channels, sessions(), "lab-3", state_hz=30, wrench_hz=50)
    demand = Demand(lambda feed, wanted: feeds[feed].want(wanted), channels.viewer_joined)
    server = foxglove.start_server(port=0, context=context, server_listener=demand)
    yield channels, feeds, f"ws://127.0.0.1:{server.port}"
    server.stop()
    for feed in feeds.values():
        feed.stop()
    channels.close()


def state_message(ms: int) -> pr_pb.StreamStateResponse:
    return pr_pb.StreamStateResponse(state=types_pb2.RobotState(
        sample_time=stamp(T0_NS + ms * 1_000_000), joint_positions_rad=[0.0] * 6))


def test_the_live_view_from_a_router_shows_the_arm_the_force_and_the_video(
        sessions, camera, live_view):
    channels, feeds, url = live_view
    fakes = Streams("wrench", "state")
    streams = {**fakes.all(), "video": lambda: VideoStream(camera.stub)}
    publisher = ObservationPublisher(sessions(), "lab-3", streams).start()
    topics = [t for feed in ROUTER_FEEDS for t in FEED_TOPICS[feed]]
    try:
        with FoxgloveClient(url) as client:
            client.wait_advertised(topics)
            assert not set(FEED_TOPICS[STEREO]) & set(client.channels)  # not in Zenoh
            assert fakes.calls == {"wrench": [], "state": []}  # nobody watches yet
            client.subscribe(topics)
            wait_for(lambda: fakes.calls["wrench"] and fakes.calls["state"],
                     what="the station's streams followed for the view")
            # 40 ms of the 1 kHz wrench and 80 ms of the 100 Hz state (no more messages than
            # the view's ring holds): the view keeps one sample per 20 ms (50 Hz) and one
            # state per 33 ms (30 Hz).
            fakes.calls["wrench"][0].items.put(wrench_message(*range(0, 20)))
            fakes.calls["wrench"][0].items.put(wrench_message(*range(20, 40)))
            assert RING_MESSAGES >= 8
            for ms in range(0, 80, 10):
                fakes.calls["state"][0].items.put(state_message(ms))
            client.collect(lambda got: len(got[fx.ROBOT_WRENCH]) == 2
                           and len(got[fx.JOINT_STATES]) == 2
                           and len(got[fx.STEREO_VIDEO]) >= 3, timeout_s=30)
            assert [stamp for stamp, _ in client.received[fx.ROBOT_WRENCH]] == [
                T0_NS, T0_NS + 20_000_000]
            assert [stamp for stamp, _ in client.received[fx.JOINT_STATES]] == [
                T0_NS + ms * 1_000_000 for ms in (0, 40)]
            video = [CompressedVideo.FromString(data)
                     for _, data in client.received[fx.STEREO_VIDEO]]
            assert fx.h264_is_keyframe(video[0].data)  # a viewer starts at a key frame
            check_the_pictures(video)
            assert not channels.cameras_unknown()  # the header came with the key frame
            client.unsubscribe_all()
            wait_for(lambda: fakes.calls["wrench"][0].cancelled.is_set()
                     and fakes.calls["state"][0].cancelled.is_set(),
                     what="the streams let go once the view stopped watching")
    finally:
        publisher.close()


@pytest.mark.parametrize("args, code, why", [
    (["--router", "tcp/10.0.0.2:7447"], 2, "beyond loopback"),
    (["--router", "tls/127.0.0.1:7447"], 2, "give the station's TLS directory"),
    (["--router", "tcp/127.0.0.1:7447", "--station", "a/b"], 2, "station name"),
    (["--router", "tcp/127.0.0.1:1"], 1, "does not answer"),
])
def test_a_live_view_given_a_router_it_cannot_use_says_why(args, code, why, capsys):
    from services.foxglove.__main__ import main

    assert main(["--address", "127.0.0.1:0", *args]) == code
    assert why in capsys.readouterr().err
