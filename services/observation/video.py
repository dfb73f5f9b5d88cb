"""The video topic's stream: the StereoCamera's H.264 stream, as observers behind a router need
it.

A viewer must start at a key frame, and needs the stream's header (the cameras' calibrations
and poses) to place the images. Observers join at any time and the publisher cannot tell when
(Zenoh's matching status says only whether any subscriber is there), so the stream asks the
camera for a key frame (in a receipt) once VIDEO_KEYFRAME_S has passed without one, and puts
the header again right before each key frame: a newcomer starts within VIDEO_KEYFRAME_S, at a
header and its key frame.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterator

from services.common.video_receipts import VideoReceipts
from telerobot.v1 import stereo_camera_pb2 as sc_pb
from telerobot.v1 import stereo_camera_pb2_grpc
from wire.observation import VIDEO_FPS, VIDEO_KBIT, VIDEO_KEYFRAME_S

KEYFRAME_RETRY_S = 0.5  # a key frame asked for and not come by then: asked for again


class KeyframePacing:
    """Whether the next receipt should ask for a key frame: none came for `every_s`, or one
    was asked for `retry_s` ago and has not come. `clock` is monotonic seconds."""

    def __init__(self, every_s: float = VIDEO_KEYFRAME_S, retry_s: float = KEYFRAME_RETRY_S,
                 clock: Callable[[], float] = time.monotonic):
        self._every_s, self._retry_s, self._clock = every_s, retry_s, clock
        self._last_keyframe_s = clock()
        self._asked_s: float | None = None

    def keyframe(self) -> None:
        """A key frame came."""
        self._last_keyframe_s, self._asked_s = self._clock(), None

    def due(self) -> bool:
        now = self._clock()
        if self._asked_s is not None:
            ask = now - self._asked_s >= self._retry_s
        else:
            ask = now - self._last_keyframe_s >= self._every_s
        if ask:
            self._asked_s = now
        return ask


class VideoStream:
    """One StreamPairs call (H.264, receipts) and the messages to publish from it: each pair,
    and before each key frame the stream's header. Cancellable, as Feed needs."""

    def __init__(self, camera: stereo_camera_pb2_grpc.StereoCameraStub,
                 pacing: KeyframePacing | None = None):
        self._pacing = pacing or KeyframePacing()
        self._receipts = VideoReceipts(camera, self._pacing.due)
        self._call = camera.StreamPairs(sc_pb.StreamPairsRequest(
            encoding=sc_pb.IMAGE_ENCODING_H264, max_fps=VIDEO_FPS, receipts=True,
            max_kbit_per_s=VIDEO_KBIT))

    def __iter__(self) -> Iterator[sc_pb.StreamPairsResponse]:
        header = None
        for response in self._call:
            if response.WhichOneof("content") == "header":
                header = response
                self._receipts.opened(response.header)
                continue  # put before the first pair, a key frame
            if response.pair.keyframe:
                self._pacing.keyframe()
                if header is not None:
                    yield header
            yield response
            self._receipts.received(response.pair)

    def cancel(self) -> None:
        self._call.cancel()
