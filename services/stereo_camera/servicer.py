"""StereoCamera over gRPC: checks requests, takes pairs from the CaptureHub, encodes, sends.

A stream sends its header once (size, encoding, mode, per-eye calibration scaled to the
client's size, baseline, source, the stream's id), then pair data only: sequence, capture
times, eye skew and the two images, or for H.264 one side-by-side video frame (h264.py, an
encoder per stream). Which pair it takes next depends on its transfer mode (capture.py); max_fps
only spaces the requests out, so a paced client still gets the newest pair when its turn comes.

A stream whose client reports receipts is also paced to its path (pacing.py, receipts.py): a
tick is taken only when the window has room for its frame, and an H.264 stream's bitrate
follows the pacer's target. Ticks skipped that way are sequence gaps, never a queue.
"""

from __future__ import annotations

import contextlib
import logging
import threading
import time

from google.protobuf.duration_pb2 import Duration

from services.stereo_camera.capture import CaptureHub
from services.stereo_camera.encoding import (
    DEFAULT_JPEG_QUALITY,
    ENCODINGS,
    START_KBIT_PER_S,
    TRANSFER_MODES,
    VIDEO_ENCODINGS,
    EncodeCache,
    ImageFormat,
    StreamSettings,
    resize,
    snapshot_settings,
    stream_settings,
)
from services.stereo_camera.h264 import H264Encoder
from services.stereo_camera.pacing import RateLimits
from services.stereo_camera.receipts import PacedStream, PacedStreams
from services.stereo_camera.source import SourceGeometry, StereoFrame
from telerobot.v1 import stereo_camera_pb2 as pb
from telerobot.v1 import stereo_camera_pb2_grpc
from wire import convert
from wire.errors import DeadlineExceededError

log = logging.getLogger(__name__)

# How long a stream waits for a pair before it checks whether its client is still there.
STREAM_POLL_S = 0.1
OPEN_TIMEOUT_S = 10.0  # opening a camera may take a while
SNAPSHOT_TIMEOUT_S = 10.0  # when the client set no deadline
DEFAULT_ENCODING = pb.IMAGE_ENCODING_JPEG
DEFAULT_TRANSFER_MODE = pb.TRANSFER_MODE_DOUBLE_BUFFER_CONCURRENT
# An image stream's encoder ignores the pacer's target, which only sizes its window.
IMAGE_RATE_LIMITS = RateLimits(start_kbit=1_500, min_kbit=150, max_kbit=100_000)


def header_proto(geometry: SourceGeometry, image_format: ImageFormat,
                 transfer_mode: int, stream_id: str = "") -> pb.StereoHeader:
    calibration = geometry.calibration.for_size(image_format.width_px, image_format.height_px)
    left, right = calibration.eye_protos()
    return pb.StereoHeader(
        width_px=image_format.width_px, height_px=image_format.height_px,
        encoding=image_format.encoding, transfer_mode=transfer_mode, left=left, right=right,
        baseline_m=calibration.baseline_m, source=geometry.description, stream_id=stream_id)


def pair_proto(frame: StereoFrame, left_image: bytes = b"", right_image: bytes = b"",
               **video) -> pb.StereoPair:
    """`video`: video_frame, keyframe and target_kbit_per_s, for an H.264 stream."""
    skew = Duration()
    skew.FromNanoseconds(frame.eye_skew_ns)
    return pb.StereoPair(
        sequence=frame.sequence,
        left_capture_time=convert.timestamp(frame.left_time_ns),
        right_capture_time=convert.timestamp(frame.right_time_ns),
        left_image=left_image, right_image=right_image, eye_skew=skew,
        render_scale=frame.render_scale, **video)


class _VideoEncoding:
    """An H.264 stream's encoder, at its pacer's target rate (or a fixed one without)."""

    def __init__(self, image_format: ImageFormat, fps: float, settings: StreamSettings,
                 paced: PacedStream | None):
        self._format = image_format
        self._paced = paced
        self._fixed_kbit = settings.max_kbit_per_s if settings.max_kbit_per_s_given \
            else START_KBIT_PER_S
        kbit = paced.target_kbit if paced else self._fixed_kbit
        self._encoder = H264Encoder(image_format.width_px, image_format.height_px, fps, kbit)

    def pair(self, frame: StereoFrame) -> tuple[pb.StereoPair, int]:
        width, height = self._format.width_px, self._format.height_px
        kbit = self._paced.target_kbit if self._paced else self._fixed_kbit
        keyframe = self._paced.take_keyframe_request() if self._paced else False
        data, key = self._encoder.encode(resize(frame.left, width, height),
                                         resize(frame.right, width, height),
                                         kbit_per_s=kbit, keyframe=keyframe)
        return pair_proto(frame, video_frame=data, keyframe=key, target_kbit_per_s=kbit), \
            len(data)

    def close(self) -> None:
        self._encoder.close()


class StereoCameraServicer(stereo_camera_pb2_grpc.StereoCameraServicer):
    """The StereoCamera contract on top of a CaptureHub (started and closed by its owner)."""

    def __init__(self, hub: CaptureHub, cache: EncodeCache | None = None,
                 streams: PacedStreams | None = None):
        self._hub = hub
        self._cache = cache or EncodeCache()
        self.streams = streams or PacedStreams()
        self._encoders_lock = threading.Lock()
        self._open_encoders = 0

    @property
    def open_encoders(self) -> int:
        """H.264 encoders held by open streams (one each)."""
        with self._encoders_lock:
            return self._open_encoders

    def _count_encoders(self, change: int) -> None:
        with self._encoders_lock:
            self._open_encoders += change

    def GetStreamInfo(self, request, context):
        geometry = self._hub.geometry(OPEN_TIMEOUT_S)
        image_format = ImageFormat(geometry.width_px, geometry.height_px, DEFAULT_ENCODING,
                                   DEFAULT_JPEG_QUALITY)
        return pb.GetStreamInfoResponse(
            header=header_proto(geometry, image_format, DEFAULT_TRANSFER_MODE))

    def StreamPairs(self, request, context):
        settings = stream_settings(request)  # InvalidArgumentError before touching the source
        geometry = self._hub.geometry(OPEN_TIMEOUT_S)
        image_format = settings.image_format(geometry)
        single = settings.transfer_mode == pb.TRANSFER_MODE_SINGLE_BUFFER_SERIALIZED
        fps = min(settings.max_fps or geometry.rate_hz, geometry.rate_hz or settings.max_fps)
        log.debug("stream opened: %dx%d %s, %s buffer, max %.1f fps, receipts %s",
                  image_format.width_px, image_format.height_px,
                  {**ENCODINGS, **VIDEO_ENCODINGS}[image_format.encoding],
                  TRANSFER_MODES[settings.transfer_mode], settings.max_fps, settings.receipts)
        with contextlib.ExitStack() as stack:
            paced = None
            if settings.receipts:
                limits = RateLimits(min(START_KBIT_PER_S, settings.max_kbit_per_s),
                                    max_kbit=settings.max_kbit_per_s) if settings.video \
                    else IMAGE_RATE_LIMITS
                paced = stack.enter_context(self.streams.open(limits))
            video = None
            if settings.video:
                video = _VideoEncoding(image_format, fps, settings, paced)
                self._count_encoders(1)
                stack.callback(self._count_encoders, -1)
                stack.callback(video.close)  # frees the encoder when the client goes
            yield pb.StreamPairsResponse(header=header_proto(
                geometry, image_format, settings.transfer_mode,
                paced.stream_id if paced else ""))
            view = stack.enter_context(self._hub.view(free_run=not single))
            yield from self._pairs(view, single, settings, image_format, paced, video, context)

    def _pairs(self, view, single: bool, settings: StreamSettings, image_format: ImageFormat,
               paced: PacedStream | None, video: _VideoEncoding | None, context):
        period_s = 1.0 / settings.max_fps if settings.max_fps > 0 else 0.0
        next_due = None  # when the next pair may be taken: one period after the previous
        while context.is_active():
            wait = 0.0 if next_due is None else next_due - time.monotonic()
            if wait > 0:
                time.sleep(min(wait, STREAM_POLL_S))
                continue
            if paced is not None and not paced.wait_for_room(STREAM_POLL_S):
                continue  # the path is full: the ticks meanwhile are skipped, not queued
            frame = view.fresh(STREAM_POLL_S) if single else view.next(STREAM_POLL_S)
            if frame is None or (paced is not None and not paced.admit()):
                continue
            now = time.monotonic()
            next_due = now + period_s if next_due is None else max(next_due + period_s, now)
            if video is not None:
                pair, size = video.pair(frame)
            else:
                left, right = self._cache.encoded(frame, image_format)
                pair, size = pair_proto(frame, left, right), len(left) + len(right)
            if paced is not None:
                paced.sent(frame.sequence, size)  # before the send: its receipt may beat it
            yield pb.StreamPairsResponse(pair=pair)

    def ReportReceipt(self, request, context):
        target_kbit, window = self.streams.report(request.stream_id, request.sequence,
                                                  request.received_bytes, request.want_keyframe)
        return pb.ReportReceiptResponse(target_kbit_per_s=target_kbit, window_bytes=window)

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
            raise DeadlineExceededError(f"no pair came from {geometry.description} within "
                                        f"{timeout_s:.1f} s: the source is slow or stuck",
                                        reason="NO_PAIR")
        left, right = self._cache.encoded(frame, image_format)
        return pb.GetSnapshotResponse(
            header=header_proto(geometry, image_format, settings.transfer_mode),
            pair=pair_proto(frame, left, right))
