"""Bad requests get INVALID_ARGUMENT; a source that cannot be opened gets FAILED_PRECONDITION
naming the device or file."""

from __future__ import annotations

import grpc
import pytest
from google.rpc import error_details_pb2
from grpc_status import rpc_status

from services.stereo_camera.pattern import PatternSource
from services.stereo_camera.video import DEVICE, FILE, VideoSource
from telerobot.v1 import stereo_camera_pb2 as pb
from tests.stereo_camera.conftest import error_code

W, H = 96, 72
JPEG = pb.IMAGE_ENCODING_JPEG

BAD_STREAMS = {
    "unknown encoding": dict(encoding=99),
    "unknown transfer mode": dict(transfer_mode=7),
    "wider than the source": dict(width_px=W + 1),
    "taller than the source": dict(height_px=H + 1),
    "negative size": dict(width_px=-8),
    "negative fps": dict(max_fps=-1.0),
    "NaN fps": dict(max_fps=float("nan")),
    "jpeg quality above 100": dict(encoding=JPEG, jpeg_quality=101),
    "jpeg quality below 1": dict(encoding=JPEG, jpeg_quality=-3),
}


@pytest.fixture
def pattern(serve):
    return serve(PatternSource(W, H))


def _open_stream(camera, **request):
    call = camera.stub.StreamPairs(pb.StreamPairsRequest(**request), timeout=10)
    return lambda: next(call)


@pytest.mark.parametrize("request_fields", BAD_STREAMS.values(), ids=BAD_STREAMS.keys())
def test_bad_stream_requests_are_invalid_arguments(pattern, request_fields):
    code, details = error_code(_open_stream(pattern, **request_fields))
    assert code is grpc.StatusCode.INVALID_ARGUMENT, details


def test_the_error_says_what_to_do_and_carries_a_reason(pattern):
    call = pattern.stub.StreamPairs(pb.StreamPairsRequest(width_px=4 * W), timeout=10)
    with pytest.raises(grpc.RpcError) as error:
        next(call)
    assert f"{W}x{H}" in error.value.details()  # the largest size it may ask for
    status = rpc_status.from_call(error.value)
    info = error_details_pb2.ErrorInfo()
    status.details[0].Unpack(info)
    assert (info.reason, info.domain) == ("SIZE_TOO_LARGE", "telerobot.v1")


def test_zero_means_the_defaults_and_quality_is_ignored_outside_jpeg(pattern):
    header = next(iter(pattern.stub.StreamPairs(pb.StreamPairsRequest(), timeout=10))).header
    assert (header.width_px, header.height_px, header.encoding) == (W, H, JPEG)
    png = pattern.stub.StreamPairs(pb.StreamPairsRequest(
        encoding=pb.IMAGE_ENCODING_PNG, jpeg_quality=500), timeout=10)
    assert next(png).header.encoding == pb.IMAGE_ENCODING_PNG
    png.cancel()


@pytest.mark.parametrize("request_fields", [dict(encoding=42), dict(encoding=JPEG,
                                                                    jpeg_quality=200)],
                         ids=["unknown encoding", "jpeg quality"])
def test_bad_snapshot_requests_are_invalid_arguments(pattern, request_fields):
    code, _ = error_code(lambda: pattern.snapshot(**request_fields))
    assert code is grpc.StatusCode.INVALID_ARGUMENT


def test_a_device_that_cannot_be_opened_is_a_failed_precondition_naming_it(serve):
    camera = serve(VideoSource(DEVICE, "/dev/video97", "/dev/video98"), retry_after_s=0.05)
    calls = {
        "stream": _open_stream(camera),
        "info": lambda: camera.stub.GetStreamInfo(pb.GetStreamInfoRequest(), timeout=10),
        "snapshot": lambda: camera.snapshot(),
    }
    for name, call in calls.items():
        code, details = error_code(call)
        assert code is grpc.StatusCode.FAILED_PRECONDITION, (name, details)
        assert "/dev/video97" in details, details
    # bad arguments are still refused as such, before the source is touched
    code, _ = error_code(_open_stream(camera, encoding=99))
    assert code is grpc.StatusCode.INVALID_ARGUMENT


def test_a_missing_recording_is_a_failed_precondition_naming_it(serve, tmp_path):
    missing = tmp_path / "no_such_recording.avi"
    camera = serve(VideoSource(FILE, str(missing), side_by_side=True))
    code, details = error_code(_open_stream(camera))
    assert code is grpc.StatusCode.FAILED_PRECONDITION
    assert str(missing) in details
