"""StereoCamera over gRPC: checks requests, takes pairs from the CaptureHub, encodes, sends.

A stream sends its header once (size, encoding, mode, per-eye calibration scaled to the
client's size, baseline, source), then pair data only: sequence, capture times, eye skew and
the two images. Which pair it takes next depends on its transfer mode (capture.py); max_fps
only spaces the requests out, so a paced client still gets the newest pair when its turn comes.
"""

from __future__ import annotations

import logging
import time

from google.protobuf.duration_pb2 import Duration

from services.common import convert
from services.runtime.errors import DeadlineExceeded
from services.stereo_camera.capture import CaptureHub
from services.stereo_camera.encoding import (
    DEFAULT_JPEG_QUALITY,
    ENCODINGS,
    TRANSFER_MODES,
    EncodeCache,
    ImageFormat,
    snapshot_settings,
    stream_settings,
)
from services.stereo_camera.source import SourceGeometry, StereoFrame
from telerobot.v1 import stereo_camera_pb2 as pb
from telerobot.v1 import stereo_camera_pb2_grpc

log = logging.getLogger(__name__)

# How long a stream waits for a pair before it checks whether its client is still there.
STREAM_POLL_S = 0.1
OPEN_TIMEOUT_S = 10.0  # opening a camera may take a while
SNAPSHOT_TIMEOUT_S = 10.0  # when the client set no deadline
DEFAULT_ENCODING = pb.IMAGE_ENCODING_JPEG
DEFAULT_TRANSFER_MODE = pb.TRANSFER_MODE_DOUBLE_BUFFER_CONCURRENT


def header_proto(geometry: SourceGeometry, image_format: ImageFormat,
                 transfer_mode: int) -> pb.StereoHeader:
    calibration = geometry.calibration.for_size(image_format.width_px, image_format.height_px)
    left, right = calibration.eye_protos()
    return pb.StereoHeader(
        width_px=image_format.width_px, height_px=image_format.height_px,
        encoding=image_format.encoding, transfer_mode=transfer_mode, left=left, right=right,
        baseline_m=calibration.baseline_m, source=geometry.description)


def pair_proto(frame: StereoFrame, left_image: bytes, right_image: bytes) -> pb.StereoPair:
    skew = Duration()
    skew.FromNanoseconds(frame.eye_skew_ns)
    return pb.StereoPair(
        sequence=frame.sequence,
        left_capture_time=convert.timestamp(frame.left_time_ns),
        right_capture_time=convert.timestamp(frame.right_time_ns),
        left_image=left_image, right_image=right_image, eye_skew=skew)


class StereoCameraServicer(stereo_camera_pb2_grpc.StereoCameraServicer):
    """The StereoCamera contract on top of a CaptureHub (started and closed by its owner)."""

    def __init__(self, hub: CaptureHub, cache: EncodeCache | None = None):
        self._hub = hub
        self._cache = cache or EncodeCache()

    def GetStreamInfo(self, request, context):
        geometry = self._hub.geometry(OPEN_TIMEOUT_S)
        image_format = ImageFormat(geometry.width_px, geometry.height_px, DEFAULT_ENCODING,
                                   DEFAULT_JPEG_QUALITY)
        return pb.GetStreamInfoResponse(
            header=header_proto(geometry, image_format, DEFAULT_TRANSFER_MODE))

    def StreamPairs(self, request, context):
        settings = stream_settings(request)  # InvalidArgument before touching the source
        geometry = self._hub.geometry(OPEN_TIMEOUT_S)
        image_format = settings.image_format(geometry)
        single = settings.transfer_mode == pb.TRANSFER_MODE_SINGLE_BUFFER_SERIALIZED
        log.debug("stream opened: %dx%d %s, %s buffer, max %.1f fps", image_format.width_px,
                  image_format.height_px, ENCODINGS[image_format.encoding],
                  TRANSFER_MODES[settings.transfer_mode], settings.max_fps)
        yield pb.StreamPairsResponse(
            header=header_proto(geometry, image_format, settings.transfer_mode))
        period_s = 1.0 / settings.max_fps if settings.max_fps > 0 else 0.0
        next_due = None  # when the next pair may be taken: one period after the previous
        with self._hub.view(free_run=not single) as view:
            while context.is_active():
                wait = 0.0 if next_due is None else next_due - time.monotonic()
                if wait > 0:
                    time.sleep(min(wait, STREAM_POLL_S))
                    continue
                frame = view.fresh(STREAM_POLL_S) if single else view.next(STREAM_POLL_S)
                if frame is None:
                    continue
                now = time.monotonic()
                next_due = now + period_s if next_due is None else max(next_due + period_s, now)
                left, right = self._cache.encoded(frame, image_format)
                yield pb.StreamPairsResponse(pair=pair_proto(frame, left, right))

    def GetSnapshot(self, request, context):
        settings = snapshot_settings(request)
        geometry = self._hub.geometry(OPEN_TIMEOUT_S)
        image_format = settings.image_format(geometry)
        timeout_s = SNAPSHOT_TIMEOUT_S
        remaining = context.time_remaining()
        if remaining is not None:
            timeout_s = min(timeout_s, max(0.0, remaining))
        frame = self._hub.snapshot(timeout_s)
        if frame is None:
            raise DeadlineExceeded(f"no pair came from {geometry.description} within "
                                   f"{timeout_s:.1f} s: the source is slow or stuck",
                                   reason="NO_PAIR")
        left, right = self._cache.encoded(frame, image_format)
        return pb.GetSnapshotResponse(
            header=header_proto(geometry, image_format, settings.transfer_mode),
            pair=pair_proto(frame, left, right))
