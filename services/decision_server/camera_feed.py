"""CameraFeed: the stereo video an MCAP recording keeps; CameraSource: where it comes from
(recording_mcap.Sources.video), which the recordings' writer process opens (recording_writer).

While a recording runs, a thread of its own reads the camera's H.264 stream (both eyes side by
side, at the size and bitrate the DecisionServer was started with) and hands each pair, with
its stream's header, to the recording. A camera that is away, or goes
away, is asked again every RETRY_S until the recording stops: the recording goes on without
video meanwhile, and says how many frames it kept (Recording.video_frames).
"""

from __future__ import annotations

import logging
import threading
from collections.abc import Callable
from dataclasses import dataclass

import grpc

from services.runtime.tls import station_channel_security
from telerobot.v1 import stereo_camera_pb2 as pb
from telerobot.v1 import stereo_camera_pb2_grpc
from wire.stereo import LOW_LATENCY_OPTIONS
from wire.tls import open_channel

log = logging.getLogger(__name__)

RETRY_S = 0.5
STOP_TIMEOUT_S = 2.0


@dataclass(frozen=True)
class CameraSource:
    """The camera a recording's video comes from, as the DecisionServer reaches it (its TLS
    directory, presenting its own certificate), and the stream it asks for."""

    address: str
    tls_dir: str | None
    width_px: int
    height_px: int
    kbit_per_s: int

    def open(self) -> tuple[CameraFeed, grpc.Channel]:
        """A feed on a channel of its own (the caller closes it)."""
        security = station_channel_security(self.tls_dir or None, "decision_server")
        channel = open_channel(self.address, LOW_LATENCY_OPTIONS, security,
                               service="stereo_camera")
        stub = stereo_camera_pb2_grpc.StereoCameraStub(channel)
        return CameraFeed(stub, self.width_px, self.height_px, self.kbit_per_s), channel


class CameraFeed:
    """`feed(sink)` starts feeding sink(header, pair); the function it returns stops it."""

    def __init__(self, stub, width_px: int, height_px: int, kbit_per_s: int):
        self._stub = stub
        self._request = pb.StreamPairsRequest(
            encoding=pb.IMAGE_ENCODING_H264, width_px=width_px, height_px=height_px,
            max_kbit_per_s=kbit_per_s, receipts=False,
            transfer_mode=pb.TRANSFER_MODE_DOUBLE_BUFFER_CONCURRENT)

    def __call__(self, sink: Callable[[object, object], None]) -> Callable[[], None]:
        stopped = threading.Event()
        current: list[grpc.Future] = []

        def read() -> None:
            while not stopped.is_set():
                call = self._stub.StreamPairs(self._request)
                current[:] = [call]
                if stopped.is_set():  # stop() came before the call was there to cancel
                    call.cancel()
                header = None
                try:
                    for response in call:
                        if response.HasField("header"):
                            header = response.header
                        elif header is not None:
                            sink(header, response.pair)
                except grpc.RpcError as error:
                    if not stopped.is_set():
                        log.warning("the recording's video paused: %s %s", error.code().name,
                                    error.details())
                stopped.wait(RETRY_S)

        thread = threading.Thread(target=read, name="recording-video", daemon=True)
        thread.start()

        def stop() -> None:
            stopped.set()
            for call in current:
                call.cancel()
            thread.join(STOP_TIMEOUT_S)

        return stop
