"""StereoCamera clients: stream info, snapshots and synchronized pair streams.

A pair stream reports what it receives (``receipts=True``, the default): each pair it reads
is acknowledged with a ReportReceipt sent without waiting, so the sender keeps no more in flight
than the path carries and an H.264 stream's bitrate follows what arrives. The channel then
needs no small receive window. A stream opened with ``receipts=False`` is paced by the
transport alone: open its client with ``options=wire.stereo.LOW_LATENCY_OPTIONS`` so that a
slow reader gets the newest pair, not a backlog.

``encoding=IMAGE_ENCODING_H264``: both eyes come in one side-by-side video frame, decoded here
(PyAV, imported on first use) back into two eyes. A frame that does not decode is skipped and a
key frame asked for. Raw RGB8 frames decode with numpy alone; OpenCV is imported the first time
a JPEG or PNG frame is decoded.

Returns: the proto ``StereoHeader`` for stream info (it is a calibration record; the proto is
the clearest form), `StereoFrame` for pairs: header, the proto ``StereoPair`` (bytes, timing),
both eyes decoded to RGB8 arrays unless ``decode=False``, and when it arrived. A pair stream's
header arrives once, first; the stream yields only frames, each carrying it (``stream`` also
keeps it).
"""

from __future__ import annotations

import time
from collections.abc import Callable

from clients.python.base import _SKIP, AsyncClient, SyncClient
from clients.python.values import StereoFrame
from telerobot.v1 import stereo_camera_pb2 as pb
from telerobot.v1 import stereo_camera_pb2_grpc
from wire.stereo import decode_pair
from wire.video import H264Decoder, VideoDecodeError


def _frame(header: pb.StereoHeader, pair: pb.StereoPair, decode: bool) -> StereoFrame:
    left, right = decode_pair(header, pair) if decode else (None, None)
    return StereoFrame(header, pair, left, right, time.time_ns())


def pair_bytes(pair: pb.StereoPair) -> int:
    """The bytes a receipt counts for `pair`: its images or its video frame."""
    return len(pair.left_image) + len(pair.right_image) + len(pair.video_frame)


class _PairConverter:
    """Keeps the header of a pair stream, reports each pair's receipt, and turns each later
    message into a frame (decoding video in order)."""

    def __init__(self, decode: bool, report: Callable[[pb.ReportReceiptRequest], None] | None):
        self.decode = decode
        self.report = report
        self.header: pb.StereoHeader | None = None
        self.received_bytes = 0
        self._decoder: H264Decoder | None = None

    def __call__(self, message: pb.StreamPairsResponse):
        if message.WhichOneof("content") == "header":
            self.header = message.header
            if self.header.encoding == pb.IMAGE_ENCODING_H264 and self.decode:
                self._decoder = H264Decoder()
            return _SKIP
        pair = message.pair
        received_ns = time.time_ns()
        self.received_bytes += pair_bytes(pair)
        self._receipt(pair.sequence, want_keyframe=False)  # first: the path, not our decoding
        if self._decoder is None:
            return _frame(self.header, pair, self.decode)
        try:
            eyes = self._decoder.decode(pair.video_frame)
        except VideoDecodeError:
            eyes = None
        if eyes is None:  # nothing to show until a key frame comes
            self._receipt(pair.sequence, want_keyframe=True)
            return _SKIP
        return StereoFrame(self.header, pair, eyes[0], eyes[1], received_ns)

    def _receipt(self, sequence: int, want_keyframe: bool) -> None:
        if self.report is not None and self.header.stream_id:
            self.report(pb.ReportReceiptRequest(
                stream_id=self.header.stream_id, sequence=sequence,
                received_bytes=self.received_bytes, want_keyframe=want_keyframe))


class _StereoCameraMethods:
    """The StereoCamera calls; on the async client each returns an awaitable of the same value."""

    SERVICE = "telerobot.v1.StereoCamera"
    ADDRESS_NAME = "stereo_camera"
    STUB = stereo_camera_pb2_grpc.StereoCameraStub

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
                     receipts: bool = True, max_kbit_per_s: int = 0, decode: bool = True,
                     timeout: float | None = None, lane: str | None = None):
        """`StereoFrame`s until cancelled (`encoding` 0: JPEG; IMAGE_ENCODING_H264 for video).
        ``stream.header`` holds the header once the first frame has been read."""
        report = (lambda request: self._send_and_forget("ReportReceipt", request, lane)) \
            if receipts else None
        return self._server_stream("StreamPairs", pb.StreamPairsRequest(
            encoding=int(encoding), jpeg_quality=jpeg_quality, max_fps=max_fps,
            transfer_mode=int(transfer_mode), width_px=width_px, height_px=height_px,
            receipts=receipts, max_kbit_per_s=max_kbit_per_s),
            _PairConverter(decode, report), timeout, lane)

    def report_receipt(self, stream_id: str, sequence: int, received_bytes: int, *,
                       want_keyframe: bool = False, timeout: float | None = None,
                       lane: str | None = None) -> pb.ReportReceiptResponse:
        """Report a stream's receipt by hand (``stream_pairs`` does it for its own streams);
        answers the sender's target rate and window."""
        return self._unary("ReportReceipt", pb.ReportReceiptRequest(
            stream_id=stream_id, sequence=sequence, received_bytes=received_bytes,
            want_keyframe=want_keyframe), lambda r: r, timeout, lane)


class StereoCameraClient(_StereoCameraMethods, SyncClient):
    """Blocking StereoCamera client. ``with StereoCameraClient(address) as camera: ...``"""


class AsyncStereoCameraClient(_StereoCameraMethods, AsyncClient):
    """asyncio StereoCamera client: the same methods, awaited; streams are ``async for``."""
