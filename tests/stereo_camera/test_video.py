"""H.264 streams and their receipts, through a real in-process server: both eyes of one tick in
every frame, the window that holds a stream whose client does not report, key frames on
request, the encoder freed when the client goes, and bad input."""

from __future__ import annotations

import grpc
import pytest

from services.stereo_camera.encoding import MAX_KBIT_PER_S, MIN_KBIT_PER_S
from services.stereo_camera.pattern import PatternSource, read_tick
from telerobot.v1 import stereo_camera_pb2 as pb
from tests.conftest import wait_for
from tests.stereo_camera.conftest import error_code
from wire.video import H264Decoder

W, H = 320, 240
H264 = pb.IMAGE_ENCODING_H264


@pytest.fixture
def pattern(serve):
    return serve(PatternSource(W, H, fps=30))


def _stream(camera, timeout: float = 10, **request):
    return camera.stub.StreamPairs(pb.StreamPairsRequest(encoding=H264, **request),
                                   timeout=timeout)


def _report(camera, stream_id: str, pair: pb.StereoPair, received: int, **extra):
    return camera.stub.ReportReceipt(pb.ReportReceiptRequest(
        stream_id=stream_id, sequence=pair.sequence, received_bytes=received, **extra),
        timeout=5)


def test_every_frame_holds_both_eyes_of_one_capture_tick(pattern):
    call = _stream(pattern, receipts=True)
    header = next(call).header
    assert (header.encoding, header.width_px, header.height_px) == (H264, W, H)
    assert len(header.stream_id) == 16
    decoder, received = H264Decoder(), 0
    for index in range(20):
        pair = next(call).pair
        received += len(pair.video_frame)
        _report(pattern, header.stream_id, pair, received)
        assert not pair.left_image and not pair.right_image
        assert pair.keyframe == (index == 0)
        assert pair.target_kbit_per_s > 0
        left, right = decoder.decode(pair.video_frame)
        assert left.shape == right.shape == (H, W, 3)
        assert read_tick(left) == read_tick(right) == pair.sequence
    call.cancel()


@pytest.mark.e2e
def test_a_stream_whose_client_does_not_report_stops_at_its_window(pattern):
    """The first frames fill the window (the start rate times the assumed round trip); with no
    receipt nothing more is sent, and each receipt lets more go."""
    call = _stream(pattern, timeout=3, receipts=True)
    header = next(call).header
    held = []
    with pytest.raises(grpc.RpcError) as ended:
        for message in call:
            held.append(message.pair)
    assert ended.value.code() is grpc.StatusCode.DEADLINE_EXCEEDED
    assert 1 <= len(held) <= 10, "3 s at 30 fps would be 90 pairs"

    call = _stream(pattern, timeout=3, receipts=True)
    header = next(call).header
    received, flowing = 0, []
    with pytest.raises(grpc.RpcError):
        for message in call:
            received += len(message.pair.video_frame)
            _report(pattern, header.stream_id, message.pair, received)
            flowing.append(message.pair)
    assert len(flowing) >= 60, len(flowing)


def test_a_client_that_lost_its_reference_gets_a_key_frame(pattern):
    call = _stream(pattern, receipts=True)
    header = next(call).header
    received = 0
    for _ in range(5):
        pair = next(call).pair
        received += len(pair.video_frame)
        answer = _report(pattern, header.stream_id, pair, received)
    assert answer.target_kbit_per_s > 0 and answer.window_bytes > 0
    _report(pattern, header.stream_id, pair, received, want_keyframe=True)
    later = []
    for _ in range(5):
        later.append(next(call).pair)
        received += len(later[-1].video_frame)
        _report(pattern, header.stream_id, later[-1], received)
    assert any(pair.keyframe for pair in later)
    call.cancel()


def test_a_client_that_goes_frees_its_encoder_and_stream(pattern):
    servicer = pattern.servicer
    calls = [_stream(pattern, receipts=True), _stream(pattern)]
    for call in calls:
        next(call)
        next(call)
    assert servicer.open_encoders == 2 and len(servicer.streams) == 1
    for call in calls:
        call.cancel()
    wait_for(lambda: servicer.open_encoders == 0 and len(servicer.streams) == 0, 1.0,
             "the encoders freed within a second")


def test_without_receipts_the_stream_runs_at_the_bitrate_asked(pattern):
    call = _stream(pattern, max_kbit_per_s=400)
    assert next(call).header.stream_id == ""
    assert {next(call).pair.target_kbit_per_s for _ in range(3)} == {400}
    call.cancel()


BAD = {
    "odd width": (dict(width_px=W - 1), "ODD_SIZE"),
    "bitrate below the floor": (dict(max_kbit_per_s=MIN_KBIT_PER_S - 1), "BAD_BITRATE"),
    "bitrate above the ceiling": (dict(max_kbit_per_s=MAX_KBIT_PER_S + 1), "BAD_BITRATE"),
}


@pytest.mark.parametrize("fields, reason", BAD.values(), ids=BAD.keys())
def test_a_stream_the_station_cannot_give_is_an_invalid_argument(pattern, fields, reason):
    call = _stream(pattern, **fields)
    code, details = error_code(lambda: next(call))
    assert code is grpc.StatusCode.INVALID_ARGUMENT
    if reason == "BAD_BITRATE":
        assert f"{MIN_KBIT_PER_S}..{MAX_KBIT_PER_S}" in details  # what it can give
    else:
        assert f"{W - 1}x{H}" in details


def test_a_snapshot_cannot_be_video(pattern):
    code, details = error_code(lambda: pattern.snapshot(encoding=H264))
    assert code is grpc.StatusCode.INVALID_ARGUMENT
    assert "IMAGE_ENCODING_PNG" in details


@pytest.mark.parametrize("request_fields, code", [
    (dict(stream_id=""), grpc.StatusCode.INVALID_ARGUMENT),
    (dict(stream_id="0123456789abcdef", sequence=-1), grpc.StatusCode.INVALID_ARGUMENT),
    (dict(stream_id="0123456789abcdef"), grpc.StatusCode.NOT_FOUND),
], ids=["no id", "negative sequence", "no such stream"])
def test_bad_receipts(pattern, request_fields, code):
    got, _ = error_code(lambda: pattern.stub.ReportReceipt(
        pb.ReportReceiptRequest(**request_fields), timeout=5))
    assert got is code
