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

from collections.abc import Iterator

from services.common.keyframes import KeyframePacing
from services.common.video_receipts import VideoReceipts
from telerobot.v1 import stereo_camera_pb2 as sc_pb
from telerobot.v1 import stereo_camera_pb2_grpc
from wire.observation import VIDEO_FPS, VIDEO_KBIT, VIDEO_KEYFRAME_S


class VideoStream:
    """One StreamPairs call (H.264, receipts) and the messages to publish from it: each pair,
    and before each key frame the stream's header. Cancellable, as Feed needs."""

    def __init__(self, camera: stereo_camera_pb2_grpc.StereoCameraStub,
                 pacing: KeyframePacing | None = None):
        self._pacing = pacing or KeyframePacing(VIDEO_KEYFRAME_S)
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
