"""StereoCamera clients: stream info, snapshots and synchronized pair streams.

Channels opened by these clients use the camera's ``LOW_LATENCY_OPTIONS`` (see
``wire/stereo.py``): a slow reader gets the newest pair, not a backlog. Raw RGB8 frames decode
with numpy alone; OpenCV is imported the first time a JPEG or PNG frame is decoded.

Returns: the proto ``StereoHeader`` for stream info (it is a calibration record; the proto is
the clearest form), `StereoFrame` for pairs: header, the proto ``StereoPair`` (bytes, timing) and
both eyes decoded to RGB8 arrays unless ``decode=False``. A pair stream's header arrives once,
first; the stream yields only frames, each carrying it (``stream`` also keeps it).
"""

from __future__ import annotations

from clients.python.base import _SKIP, AsyncClient, SyncClient
from clients.python.values import StereoFrame
from telerobot.v1 import stereo_camera_pb2 as pb
from telerobot.v1 import stereo_camera_pb2_grpc
from wire.stereo import LOW_LATENCY_OPTIONS, decode_pair


def _frame(header: pb.StereoHeader, pair: pb.StereoPair, decode: bool) -> StereoFrame:
    left, right = decode_pair(header, pair) if decode else (None, None)
    return StereoFrame(header, pair, left, right)


class _PairConverter:
    """Keeps the header of a pair stream and turns each later message into a frame."""

    def __init__(self, decode: bool):
        self.decode = decode
        self.header: pb.StereoHeader | None = None

    def __call__(self, message: pb.StreamPairsResponse):
        if message.WhichOneof("content") == "header":
            self.header = message.header
            return _SKIP
        return _frame(self.header, message.pair, self.decode)


class _StereoCameraMethods:
    """The StereoCamera calls; on the async client each returns an awaitable of the same value."""

    SERVICE = "telerobot.v1.StereoCamera"
    ADDRESS_NAME = "stereo_camera"
    STUB = stereo_camera_pb2_grpc.StereoCameraStub
    EXTRA_OPTIONS = LOW_LATENCY_OPTIONS

    def get_stream_info(self, *, timeout: float | None = None, lane: str | None = None
                        ) -> pb.StereoHeader:
        """What a default stream carries: size, encoding, per-eye calibration, baseline."""
        return self._unary("GetStreamInfo", pb.GetStreamInfoRequest(), lambda r: r.header,
                           timeout, lane)

    def get_snapshot(self, encoding: int = 0, jpeg_quality: int = 0, *, decode: bool = True,
                     timeout: float | None = None, lane: str | None = None) -> StereoFrame:
        """The newest pair (`encoding` an ImageEncoding; 0: PNG, lossless)."""
        return self._unary("GetSnapshot", pb.GetSnapshotRequest(
            encoding=int(encoding), jpeg_quality=jpeg_quality),
            lambda r: _frame(r.header, r.pair, decode), timeout, lane)

    def stream_pairs(self, encoding: int = 0, *, jpeg_quality: int = 0, max_fps: float = 0.0,
                     transfer_mode: int = 0, width_px: int = 0, height_px: int = 0,
                     decode: bool = True, timeout: float | None = None,
                     lane: str | None = None):
        """`StereoFrame`s until cancelled (`encoding` 0: JPEG). ``stream.header`` holds the
        header once the first frame has been read."""
        return self._server_stream("StreamPairs", pb.StreamPairsRequest(
            encoding=int(encoding), jpeg_quality=jpeg_quality, max_fps=max_fps,
            transfer_mode=int(transfer_mode), width_px=width_px, height_px=height_px),
            _PairConverter(decode), timeout, lane)


class StereoCameraClient(_StereoCameraMethods, SyncClient):
    """Blocking StereoCamera client. ``with StereoCameraClient(address) as camera: ...``"""


class AsyncStereoCameraClient(_StereoCameraMethods, AsyncClient):
    """asyncio StereoCamera client: the same methods, awaited; streams are ``async for``."""
