"""The live view's H.264 feed: a real in-process StereoCamera (the pattern source) streaming to
the video feed (receipts, key frames on demand), a real foxglove-sdk WebSocket server in this
process and clients of the Foxglove protocol; what they receive is decoded with PyAV."""

from __future__ import annotations

import time

import av
import foxglove
import numpy as np
import pytest
from foxglove_schemas_protobuf.CompressedVideo_pb2 import CompressedVideo

from services.foxglove import live
from services.foxglove.feeds import station_feeds
from services.foxglove.live import Demand, LiveChannels
from services.stereo_camera.pattern import PatternSource, pattern_image, read_tick
from services.stereo_camera.source import LEFT, RIGHT
from telerobot.v1 import stereo_camera_pb2 as sc_pb
from tests.conftest import wait_for
from tests.foxglove.ws_client import FoxgloveClient
from tests.stereo_camera.conftest import psnr, start_camera
from wire import foxglove as fx

W, H = 160, 120
FPS = 10.0


@pytest.fixture
def station():
    """A camera, and a live view of it: its server, channels and feeds (the video feed opens
    its stream only when a viewer subscribes)."""
    camera = start_camera(PatternSource(W, H, fps=30))
    context = foxglove.Context()
    channels = LiveChannels(context)
    # Only the camera is served: the state and wrench feeds are never wanted here.
    feeds = station_feeds(channels, camera.channel, camera.channel, camera.channel,
                          state_hz=30, wrench_hz=50, stereo_fps=FPS, video_kbit=800)
    for feed in feeds.values():
        feed.start()
    demand = Demand(lambda feed, wanted: feeds[feed].want(wanted), channels.viewer_joined)
    server = foxglove.start_server(port=0, context=context, server_listener=demand)
    yield camera, channels, feeds, f"ws://127.0.0.1:{server.port}"
    server.stop()
    for feed in feeds.values():
        feed.stop()
    channels.close()
    camera.close()


def videos(client: FoxgloveClient) -> list[CompressedVideo]:
    return [CompressedVideo.FromString(data) for _, data in client.received[fx.STEREO_VIDEO]]


def decode(frames: list[CompressedVideo]) -> list[np.ndarray]:
    """The frames in order, from the first (which must be a key frame), one picture each."""
    decoder = av.CodecContext.create("h264", "r")
    pictures = []
    for frame in frames:
        (picture,) = decoder.decode(av.Packet(frame.data))
        pictures.append(picture.to_ndarray(format="rgb24"))
    return pictures


def capturing(camera, for_s: float = 0.4) -> bool:
    """Whether the camera captures pairs (for some stream) now."""
    before = camera.hub.stats.ticks
    time.sleep(for_s)
    return camera.hub.stats.ticks > before


def check_the_pictures(frames: list[CompressedVideo]) -> None:
    """Each frame decodes, in order, to both eyes side by side, close to the pattern's tick it
    shows (the pattern draws its tick; read back from the left eye)."""
    for picture in decode(frames):
        assert picture.shape == (H, 2 * W, 3)
        tick = read_tick(picture[:, :W])
        assert psnr(picture[:, :W], pattern_image(tick, LEFT, W, H)) > 28
        assert psnr(picture[:, W:], pattern_image(tick, RIGHT, W, H)) > 28


def test_the_video_is_advertised_and_a_viewer_starts_at_a_key_frame_that_decodes(station):
    camera, channels, _, url = station
    with FoxgloveClient(url) as client:
        client.wait_advertised([fx.STEREO_VIDEO])
        advertised = client.channels[fx.STEREO_VIDEO]
        assert (advertised["encoding"], advertised["schemaName"]) == (
            "protobuf", "foxglove.CompressedVideo")
        assert not capturing(camera)  # nobody watches: no stream, no capture
        client.subscribe([fx.STEREO_VIDEO])
        client.collect(lambda got: len(got[fx.STEREO_VIDEO]) >= 8, timeout_s=20)
        client.unsubscribe_all()
        # The viewer left: the feed's stream closes, and the camera stops capturing.
        wait_for(lambda: not capturing(camera), timeout_s=10, what="the stream closed")
    frames = videos(client)
    assert {(f.format, f.frame_id) for f in frames} == {("h264", fx.STEREO_CAMERA_FRAME)}
    assert fx.h264_is_keyframe(frames[0].data)
    assert not any(fx.h264_is_keyframe(f.data) for f in frames[1:])  # no key frame unasked
    stamps = [stamp for stamp, _ in client.received[fx.STEREO_VIDEO]]
    assert stamps == [f.timestamp.ToNanoseconds() for f in frames] == sorted(stamps)
    check_the_pictures(frames)
    assert channels.held_back == 0 and channels.published[fx.STEREO_VIDEO] >= 8


def test_a_viewer_who_joins_mid_stream_starts_at_a_key_frame_and_the_others_go_on(station):
    _, channels, _, url = station
    with FoxgloveClient(url) as first, FoxgloveClient(url) as second:
        first.wait_advertised([fx.STEREO_VIDEO])
        first.subscribe([fx.STEREO_VIDEO])
        first.collect(lambda got: len(got[fx.STEREO_VIDEO]) >= 5, timeout_s=20)
        second.wait_advertised([fx.STEREO_VIDEO])
        second.subscribe([fx.STEREO_VIDEO])
        second.collect(lambda got: len(got[fx.STEREO_VIDEO]) >= 5, timeout_s=20)
        seen = {data for _, data in second.received[fx.STEREO_VIDEO]}
        first.collect(lambda got: seen <= {data for _, data in got[fx.STEREO_VIDEO]},
                      timeout_s=20)
    late, early = videos(second), videos(first)
    assert fx.h264_is_keyframe(late[0].data)  # the key frame asked for the newcomer
    check_the_pictures(late)
    # The first viewer got that key frame too, and every frame it got decodes in order: the
    # frames held back for the newcomer were held back for all (at most a few).
    keys = [i for i, f in enumerate(early) if fx.h264_is_keyframe(f.data)]
    assert keys[0] == 0 and early[keys[1]].data == late[0].data
    check_the_pictures(early)
    assert channels.held_back <= 3


def test_key_frames_are_asked_for_a_newcomer_until_one_comes_and_every_few_seconds():
    now = [100.0]
    channels = LiveChannels(foxglove.Context(), clock=lambda: now[0])
    delta = sc_pb.StereoPair(video_frame=b"delta", keyframe=False)
    key = sc_pb.StereoPair(video_frame=b"key", keyframe=True)
    try:
        channels.video_stream_opened()  # its first frame is a key frame: nothing to ask
        assert not channels.take_keyframe_request()
        channels.stereo_video(key)
        channels.viewer_joined(fx.TF)  # not the video: nothing to do
        assert not channels.take_keyframe_request()
        channels.viewer_joined(fx.STEREO_VIDEO)
        assert channels.take_keyframe_request() and not channels.take_keyframe_request()
        channels.stereo_video(delta)  # held back until the key frame
        assert channels.held_back == 1
        now[0] += live.KEYFRAME_RETRY_S  # none came: asked again
        assert channels.take_keyframe_request() and not channels.take_keyframe_request()
        channels.stereo_video(key)
        channels.stereo_video(delta)  # flows again
        assert channels.held_back == 1 and not channels.take_keyframe_request()
        now[0] += live.KEYFRAME_REFRESH_S  # the longest run without one
        assert channels.take_keyframe_request() and not channels.take_keyframe_request()
        channels.stereo_video(delta)  # a refresh holds nothing back
        assert channels.held_back == 1
    finally:
        channels.close()
