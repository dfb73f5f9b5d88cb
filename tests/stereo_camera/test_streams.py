"""StreamPairs, GetSnapshot and GetStreamInfo over a real server, with the pattern source: the
tick drawn in each eye tells which capture tick an image came from."""

from __future__ import annotations

import contextlib
import time
from collections.abc import Callable, Iterator

import cv2
import numpy as np
import pytest

from services.stereo_camera.capture import CaptureHub
from services.stereo_camera.client import decode_pair
from services.stereo_camera.pattern import PatternSource, pattern_image, read_tick
from services.stereo_camera.source import LEFT, RIGHT
from telerobot.v1 import stereo_camera_pb2 as pb
from tests.conftest import wait_for
from tests.stereo_camera.conftest import psnr

SINGLE = pb.TRANSFER_MODE_SINGLE_BUFFER_SERIALIZED
DOUBLE = pb.TRANSFER_MODE_DOUBLE_BUFFER_CONCURRENT
MODES = [pytest.param(SINGLE, id="single"), pytest.param(DOUBLE, id="double")]
W, H = 160, 120


@pytest.fixture
def pattern(serve):
    return serve(PatternSource(W, H, fps=100))


def _pairs(messages):
    return [message.pair for message in messages[1:]]


@contextlib.contextmanager
def metronome(fps: float) -> Iterator[Callable[[], int]]:
    """Another pattern source, kept capturing at `fps`: its tick count is the clock by which a
    test watches a hub that must stay idle (a busy machine slows both alike)."""
    hub = CaptureHub(PatternSource(W, H, fps=fps))
    hub.start()
    try:
        with hub.view(free_run=True):
            yield lambda: hub.stats.ticks
    finally:
        hub.close()


def idle_for(hub: CaptureHub, beats: Callable[[], int], count: int) -> Callable[[], bool]:
    """For wait_for: true once `hub` has started no tick while the metronome made `count`."""
    last = {"ticks": hub.stats.ticks, "beat": beats()}

    def idle() -> bool:
        ticks, beat = hub.stats.ticks, beats()
        if ticks != last["ticks"]:
            last.update(ticks=ticks, beat=beat)
            return False
        return beat - last["beat"] >= count
    return idle


@pytest.mark.parametrize("mode", MODES)
def test_header_once_then_pairs_whose_eyes_share_the_tick(pattern, mode):
    messages = pattern.stream(8, transfer_mode=mode, encoding=pb.IMAGE_ENCODING_JPEG)
    assert messages[0].WhichOneof("content") == "header"
    assert [m.WhichOneof("content") for m in messages[1:]] == ["pair"] * 8
    header = messages[0].header
    assert (header.width_px, header.height_px) == (W, H)
    assert header.encoding == pb.IMAGE_ENCODING_JPEG and header.transfer_mode == mode
    assert header.source == "pattern"
    sequences = []
    for pair in _pairs(messages):
        left, right = decode_pair(header, pair)
        assert read_tick(left) == read_tick(right) == pair.sequence
        assert pair.left_capture_time.ToNanoseconds() > 0
        assert pair.eye_skew.ToNanoseconds() == abs(
            pair.right_capture_time.ToNanoseconds() - pair.left_capture_time.ToNanoseconds())
        sequences.append(pair.sequence)
    assert sequences == sorted(set(sequences))  # strictly increasing


@pytest.mark.parametrize("mode", MODES)
@pytest.mark.parametrize("encoding", [pb.IMAGE_ENCODING_PNG, pb.IMAGE_ENCODING_RAW_RGB8],
                         ids=["png", "raw"])
def test_lossless_encodings_give_back_the_source_images_exactly(pattern, mode, encoding):
    messages = pattern.stream(3, transfer_mode=mode, encoding=encoding)
    header = messages[0].header
    for pair in _pairs(messages):
        left, right = decode_pair(header, pair)
        assert np.array_equal(left, pattern_image(pair.sequence, LEFT, W, H))
        assert np.array_equal(right, pattern_image(pair.sequence, RIGHT, W, H))


def test_jpeg_is_close_to_the_source_and_quality_matters(pattern):
    sizes = {}
    for quality in (95, 40):
        messages = pattern.stream(2, encoding=pb.IMAGE_ENCODING_JPEG, jpeg_quality=quality)
        header = messages[0].header
        pair = messages[-1].pair
        left, right = decode_pair(header, pair)
        assert psnr(left, pattern_image(pair.sequence, LEFT, W, H)) > (30 if quality > 90 else 25)
        assert psnr(right, pattern_image(pair.sequence, RIGHT, W, H)) > 25
        sizes[quality] = len(pair.left_image)
    assert sizes[40] < sizes[95]


def test_a_client_may_ask_for_a_smaller_size(pattern):
    messages = pattern.stream(2, encoding=pb.IMAGE_ENCODING_PNG, width_px=80, height_px=60)
    header = messages[0].header
    assert (header.width_px, header.height_px) == (80, 60)
    pair = messages[-1].pair
    left, right = decode_pair(header, pair)
    expected = cv2.resize(pattern_image(pair.sequence, LEFT, W, H), (80, 60),
                          interpolation=cv2.INTER_AREA)
    assert np.array_equal(left, expected)
    assert read_tick(left) == read_tick(right) == pair.sequence


def test_a_single_buffer_client_alone_triggers_each_capture(serve):
    camera = serve(PatternSource(W, H, fps=200, cost_ms=5))
    messages = camera.stream(8, transfer_mode=SINGLE, encoding=pb.IMAGE_ENCODING_RAW_RGB8)
    sequences = [pair.sequence for pair in _pairs(messages)]
    # capture, send, capture the next: no tick is captured while a pair is being sent
    assert sequences == list(range(sequences[0], sequences[0] + 8))
    with metronome(200) as beats:  # 0.2 s of ticks at the source's rate
        wait_for(idle_for(camera.hub, beats, 40), 10.0, "the source to stop capturing")
    assert camera.hub.stats.ticks <= sequences[-1] + 1  # and nothing runs ahead


def test_a_slow_client_gets_the_newest_pair_and_sees_the_gaps(serve):
    # The channel keeps about one pair in flight (client.LOW_LATENCY_OPTIONS): the server
    # holds nothing back either, so each read gets the pair that was newest when it was sent.
    camera = serve(PatternSource(W, H, fps=50))
    call = camera.stub.StreamPairs(pb.StreamPairsRequest(encoding=pb.IMAGE_ENCODING_RAW_RGB8),
                                   timeout=20)
    try:
        next(call)  # header
        received = []
        for _ in range(8):
            pair = next(call).pair
            ticks = camera.hub.stats.ticks
            received.append((pair.sequence, ticks - pair.sequence))  # its age, in ticks
            left = np.frombuffer(pair.left_image, np.uint8).reshape(H, W, 3)
            assert read_tick(left) == pair.sequence
            # A slow client: it reads again once the source has made 12 pairs (0.24 s).
            wait_for(lambda since=ticks: camera.hub.stats.ticks >= since + 12, 10.0,
                     "12 more ticks")
    finally:
        call.cancel()
    sequences = [sequence for sequence, _ in received]
    gaps = np.diff(sequences)
    assert (gaps >= 1).all()
    assert np.median(gaps) >= 4, sequences  # the pairs it could not take are skipped
    # No backlog: with one, each read would be a pair older than the one before by 12 ticks.
    ages = [age for _, age in received[2:]]
    assert max(ages) < 50, received  # 1 s at 50 fps


def test_a_serialized_client_beside_a_free_running_one_waits_for_a_new_capture(serve):
    camera = serve(PatternSource(W, H, fps=100))
    fast = camera.stub.StreamPairs(pb.StreamPairsRequest(
        transfer_mode=DOUBLE, encoding=pb.IMAGE_ENCODING_RAW_RGB8), timeout=20)
    try:
        next(fast)
        next(fast)  # the capture thread now runs free
        messages = camera.stream(6, transfer_mode=SINGLE, encoding=pb.IMAGE_ENCODING_PNG,
                                 max_fps=10)
    finally:
        fast.cancel()
    header = messages[0].header
    sequences = []
    for pair in _pairs(messages):
        left, right = decode_pair(header, pair)
        assert read_tick(left) == read_tick(right) == pair.sequence
        sequences.append(pair.sequence)
    assert min(np.diff(sequences)) >= 2  # at 10 of 100 fps, it skips the ticks in between


def test_max_fps_spaces_the_pairs(pattern):
    messages = pattern.stream(5, max_fps=10, encoding=pb.IMAGE_ENCODING_RAW_RGB8)
    times = [pair.left_capture_time.ToNanoseconds() / 1e9 for pair in _pairs(messages)]
    # Never faster than asked (a slow machine makes it slower, never faster). The pairs come
    # from a source at 100 fps, so each may be up to one source tick (10 ms) early.
    assert times[-1] - times[0] > 4 * 0.1 - 0.02


def test_snapshot_is_the_newest_pair_in_png_with_its_header(pattern):
    before = time.time_ns()
    reply = pattern.snapshot()
    assert reply.header.encoding == pb.IMAGE_ENCODING_PNG
    assert (reply.header.width_px, reply.header.height_px) == (W, H)
    assert reply.pair.left_capture_time.ToNanoseconds() >= before  # captured for this call
    left, right = decode_pair(reply.header, reply.pair)
    assert np.array_equal(left, pattern_image(reply.pair.sequence, LEFT, W, H))
    assert np.array_equal(right, pattern_image(reply.pair.sequence, RIGHT, W, H))
    jpeg = pattern.snapshot(encoding=pb.IMAGE_ENCODING_JPEG, jpeg_quality=80)
    assert jpeg.header.encoding == pb.IMAGE_ENCODING_JPEG
    assert jpeg.pair.sequence > reply.pair.sequence


def test_stream_info_describes_the_default_stream(pattern):
    header = pattern.stub.GetStreamInfo(pb.GetStreamInfoRequest(), timeout=10).header
    assert (header.width_px, header.height_px) == (W, H)
    assert header.encoding == pb.IMAGE_ENCODING_JPEG
    assert header.transfer_mode == DOUBLE
    assert header.source == "pattern"
    assert header.left.fx_px == 0 and not header.left.projection  # the pattern: unknown


def test_many_clients_share_one_capture(serve):
    camera = serve(PatternSource(W, H, fps=10))
    calls = [camera.stub.StreamPairs(pb.StreamPairsRequest(
        encoding=pb.IMAGE_ENCODING_PNG, width_px=W // (index + 1), height_px=H // (index + 1)),
        timeout=20) for index in range(3)]
    try:
        headers = [next(call).header for call in calls]
        seen = [[], [], []]
        for _ in range(3):
            for call, pairs in zip(calls, seen, strict=True):
                pairs.append(next(call).pair)
    finally:
        for call in calls:
            call.cancel()
    for header, pairs in zip(headers, seen, strict=True):
        for pair in pairs:
            left, right = decode_pair(header, pair)  # each client in its own size
            assert left.shape == (header.height_px, header.width_px, 3)
            assert read_tick(left) == read_tick(right) == pair.sequence
    sequences = [{pair.sequence for pair in pairs} for pairs in seen]
    assert sequences[0] & sequences[1] & sequences[2]  # the same captures...
    assert camera.hub.stats.ticks < 9  # ...fewer of them than the 9 pairs delivered


def test_the_source_idles_without_clients(pattern):
    pattern.stream(2)
    # Once the stream's end reaches the server, no tick for 0.3 s of the source's 100 fps.
    with metronome(100) as beats:
        wait_for(idle_for(pattern.hub, beats, 30), 10.0, "the source to stop capturing")
