"""Per-client stream settings (checked), resizing, and image encoding: JPEG, PNG, raw RGB8.

Each client picks its own encoding, JPEG quality, size (at most the source's) and rate; the
capture is shared. ``EncodeCache`` keeps the latest encoded pairs, so clients with the same
settings encode each pair once between them.

``decode_image`` is the client side (``wire.stereo``, re-exported here): bytes of a StereoPair
image back to an RGB8 array.
"""

from __future__ import annotations

import math
import threading
from collections import OrderedDict
from dataclasses import dataclass

import cv2
import numpy as np

from services.stereo_camera.source import SourceGeometry, StereoFrame
from telerobot.v1 import stereo_camera_pb2 as pb
from wire.errors import InvalidArgumentError
from wire.stereo import decode_image as decode_image  # re-exported: the client side

DEFAULT_JPEG_QUALITY = 90
PNG_COMPRESSION = 1  # zlib level: fast; PNG stays lossless at every level
ENCODINGS = {
    pb.IMAGE_ENCODING_RAW_RGB8: "raw",
    pb.IMAGE_ENCODING_JPEG: "jpeg",
    pb.IMAGE_ENCODING_PNG: "png",
}
VIDEO_ENCODINGS = {pb.IMAGE_ENCODING_H264: "h264"}  # streams only: one encoder per stream
# The bitrates an H.264 stream may ask for (max_kbit_per_s), and the ceiling when it asks none.
MIN_KBIT_PER_S, MAX_KBIT_PER_S, DEFAULT_MAX_KBIT_PER_S = 150, 50_000, 8_000
START_KBIT_PER_S = 1_500
TRANSFER_MODES = {
    pb.TRANSFER_MODE_SINGLE_BUFFER_SERIALIZED: "single",
    pb.TRANSFER_MODE_DOUBLE_BUFFER_CONCURRENT: "double",
}


@dataclass(frozen=True)
class ImageFormat:
    """What a client receives: the size of each eye and how it is encoded."""

    width_px: int
    height_px: int
    encoding: int  # ImageEncoding, never UNSPECIFIED
    jpeg_quality: int  # 1..100; used for JPEG only


@dataclass(frozen=True)
class StreamSettings:
    """A client's checked request; the size is resolved against the source by image_format()."""

    encoding: int
    jpeg_quality: int
    max_fps: float  # 0: the source's rate
    transfer_mode: int  # TransferMode, never UNSPECIFIED
    width_px: int = 0  # 0: the source's
    height_px: int = 0
    receipts: bool = False  # the client reports what it receives (pacing.py)
    max_kbit_per_s: int = DEFAULT_MAX_KBIT_PER_S  # H.264 only
    max_kbit_per_s_given: bool = False  # the client set it (else the default above)

    @property
    def video(self) -> bool:
        return self.encoding in VIDEO_ENCODINGS

    def image_format(self, geometry: SourceGeometry) -> ImageFormat:
        """The client's image format; InvalidArgumentError for a size past the source's, or odd
        for H.264. A source of odd size streams H.264 a pixel smaller."""
        width = self.width_px or geometry.width_px - geometry.width_px % 2 * self.video
        height = self.height_px or geometry.height_px - geometry.height_px % 2 * self.video
        if width > geometry.width_px or height > geometry.height_px:
            raise InvalidArgumentError(
                f"{width}x{height} is larger than the source's {geometry.width_px}x"
                f"{geometry.height_px}: ask for at most that (0 means the source's size)",
                reason="SIZE_TOO_LARGE")
        if self.video and (width % 2 or height % 2):
            raise InvalidArgumentError(
                f"H.264 needs an even width and height, not {width}x{height}",
                reason="ODD_SIZE")
        return ImageFormat(width, height, self.encoding, self.jpeg_quality)


def _check_encoding(encoding: int, default: int, quality: int, video: bool = False,
                    ) -> tuple[int, int]:
    if encoding == pb.IMAGE_ENCODING_UNSPECIFIED:
        encoding = default
    if encoding in VIDEO_ENCODINGS and not video:
        raise InvalidArgumentError(
            "IMAGE_ENCODING_H264 is for StreamPairs: a snapshot is one picture; use "
            "IMAGE_ENCODING_PNG, IMAGE_ENCODING_JPEG or IMAGE_ENCODING_RAW_RGB8",
            reason="BAD_ENCODING")
    if encoding not in ENCODINGS and encoding not in VIDEO_ENCODINGS:
        raise InvalidArgumentError(
            f"unknown image encoding {encoding}: use IMAGE_ENCODING_H264, IMAGE_ENCODING_JPEG, "
            "IMAGE_ENCODING_PNG or IMAGE_ENCODING_RAW_RGB8", reason="BAD_ENCODING")
    if encoding == pb.IMAGE_ENCODING_JPEG:
        if quality == 0:
            quality = DEFAULT_JPEG_QUALITY
        if not 1 <= quality <= 100:
            raise InvalidArgumentError(f"jpeg_quality {quality} is outside 1..100 (0 means "
                                       f"{DEFAULT_JPEG_QUALITY})", reason="BAD_JPEG_QUALITY")
    else:
        quality = DEFAULT_JPEG_QUALITY  # ignored for other encodings, as the proto says
    return encoding, quality


def stream_settings(request: pb.StreamPairsRequest) -> StreamSettings:
    """Checks a StreamPairsRequest (all but the size limit, which needs the source)."""
    encoding, quality = _check_encoding(request.encoding, pb.IMAGE_ENCODING_JPEG,
                                        request.jpeg_quality, video=True)
    max_kbit = request.max_kbit_per_s or DEFAULT_MAX_KBIT_PER_S
    if not MIN_KBIT_PER_S <= max_kbit <= MAX_KBIT_PER_S:
        raise InvalidArgumentError(
            f"max_kbit_per_s {request.max_kbit_per_s} is outside what the station encodes: "
            f"{MIN_KBIT_PER_S}..{MAX_KBIT_PER_S} kbit/s (0 means {DEFAULT_MAX_KBIT_PER_S})",
            reason="BAD_BITRATE")
    mode = request.transfer_mode or pb.TRANSFER_MODE_DOUBLE_BUFFER_CONCURRENT
    if mode not in TRANSFER_MODES:
        raise InvalidArgumentError(
            f"unknown transfer mode {mode}: use TRANSFER_MODE_SINGLE_BUFFER_SERIALIZED or "
            "TRANSFER_MODE_DOUBLE_BUFFER_CONCURRENT", reason="BAD_TRANSFER_MODE")
    max_fps = request.max_fps
    if not math.isfinite(max_fps) or max_fps < 0:
        raise InvalidArgumentError(f"max_fps must be a positive rate, or 0 for the source's rate; "
                                   f"got {max_fps}", reason="BAD_MAX_FPS")
    if request.width_px < 0 or request.height_px < 0:
        raise InvalidArgumentError(f"width_px and height_px must not be negative, got "
                                   f"{request.width_px}x{request.height_px} (0 means the source's)",
                                   reason="BAD_SIZE")
    return StreamSettings(encoding, quality, max_fps, mode, request.width_px, request.height_px,
                          request.receipts, max_kbit, bool(request.max_kbit_per_s))


def snapshot_settings(request: pb.GetSnapshotRequest) -> StreamSettings:
    """Checks a GetSnapshotRequest: the source's size, PNG unless asked otherwise."""
    encoding, quality = _check_encoding(request.encoding, pb.IMAGE_ENCODING_PNG,
                                        request.jpeg_quality)
    return StreamSettings(encoding, quality, 0.0, pb.TRANSFER_MODE_UNSPECIFIED)


# -- images --------------------------------------------------------------------------------------


def resize(image: np.ndarray, width_px: int, height_px: int) -> np.ndarray:
    """`image` at width_px x height_px (area averaging when shrinking, bilinear when enlarging
    a picture rendered small); itself if it fits."""
    if image.shape[1] == width_px and image.shape[0] == height_px:
        return image
    enlarging = width_px > image.shape[1] or height_px > image.shape[0]
    return cv2.resize(image, (width_px, height_px),
                      interpolation=cv2.INTER_LINEAR if enlarging else cv2.INTER_AREA)


def encode_image(image: np.ndarray, encoding: int, jpeg_quality: int = DEFAULT_JPEG_QUALITY,
                 ) -> bytes:
    """RGB8 (height, width, 3) to the bytes of a StereoPair image."""
    if encoding == pb.IMAGE_ENCODING_RAW_RGB8:
        return np.ascontiguousarray(image, dtype=np.uint8).tobytes()
    bgr = cv2.cvtColor(image, cv2.COLOR_RGB2BGR)
    if encoding == pb.IMAGE_ENCODING_JPEG:
        ok, data = cv2.imencode(".jpg", bgr, [cv2.IMWRITE_JPEG_QUALITY, int(jpeg_quality)])
    elif encoding == pb.IMAGE_ENCODING_PNG:
        ok, data = cv2.imencode(".png", bgr, [cv2.IMWRITE_PNG_COMPRESSION, PNG_COMPRESSION])
    else:
        raise InvalidArgumentError(f"unknown image encoding {encoding}", reason="BAD_ENCODING")
    if not ok:
        raise RuntimeError(f"OpenCV could not encode a {image.shape} image as {encoding}")
    return data.tobytes()


class EncodeCache:
    """The most recent encoded pairs, keyed by (sequence, format). Thread-safe; two clients
    that ask at the same moment may both encode (the second result is dropped)."""

    def __init__(self, capacity: int = 16):
        self._capacity = capacity
        self._lock = threading.Lock()
        self._entries: OrderedDict[tuple, tuple[bytes, bytes]] = OrderedDict()

    def encoded(self, frame: StereoFrame, image_format: ImageFormat) -> tuple[bytes, bytes]:
        """(left, right) bytes of `frame` in `image_format`."""
        key = (frame.sequence, image_format)
        with self._lock:
            hit = self._entries.get(key)
            if hit is not None:
                self._entries.move_to_end(key)
                return hit
        width, height = image_format.width_px, image_format.height_px
        result = tuple(encode_image(resize(image, width, height), image_format.encoding,
                                    image_format.jpeg_quality)
                       for image in (frame.left, frame.right))
        with self._lock:
            self._entries[key] = result
            while len(self._entries) > self._capacity:
                self._entries.popitem(last=False)
        return result
