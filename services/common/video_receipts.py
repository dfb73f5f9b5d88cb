"""VideoReceipts: the follower's side of a StereoCamera H.264 stream opened with receipts.

Each pair is reported (ReportReceipt, sent without waiting for its answer), which keeps the
frames in flight within the path, and a receipt asks for a key frame when the follower wants
one. The live view (services.foxglove) and the observation publisher (services.observation)
follow the camera's video this way.
"""

from __future__ import annotations

import threading
from collections.abc import Callable

from telerobot.v1 import stereo_camera_pb2 as sc_pb
from telerobot.v1 import stereo_camera_pb2_grpc

RECEIPT_TIMEOUT_S = 5.0


class VideoReceipts:
    """The stream's id from its header, then for each pair a ReportReceipt sent without
    waiting, with want_keyframe from `want_keyframe()`. A receipt that fails is not retried:
    the next one carries the bytes anyway."""

    def __init__(self, camera: stereo_camera_pb2_grpc.StereoCameraStub,
                 want_keyframe: Callable[[], bool]):
        self._camera = camera
        self._want_keyframe = want_keyframe
        self._stream_id = ""
        self._received_bytes = 0
        self._lock = threading.Lock()
        self._pending: set = set()  # the calls in flight (a future nobody holds is cancelled)

    def opened(self, header: sc_pb.StereoHeader) -> None:
        self._stream_id, self._received_bytes = header.stream_id, 0

    def received(self, pair: sc_pb.StereoPair) -> None:
        self._received_bytes += len(pair.video_frame) + len(pair.left_image) + \
            len(pair.right_image)
        if not self._stream_id:
            return
        future = self._camera.ReportReceipt.future(sc_pb.ReportReceiptRequest(
            stream_id=self._stream_id, sequence=pair.sequence,
            received_bytes=self._received_bytes,
            want_keyframe=self._want_keyframe()), timeout=RECEIPT_TIMEOUT_S)
        with self._lock:
            self._pending.add(future)
        future.add_done_callback(self._done)

    def _done(self, future) -> None:
        with self._lock:
            self._pending.discard(future)
