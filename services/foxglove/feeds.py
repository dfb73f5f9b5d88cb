"""The live view's upstream streams: a Feed (services.common.feeds) each, open while a viewer
watches one of its topics. Read-only calls (role observer).

The video feed's stream takes receipts: each pair is reported (ReportReceipt, sent without
waiting for its answer), which keeps the frames in flight within the path and lets a receipt
ask for a key frame when the live view needs one (LiveChannels.take_keyframe_request); its
bitrate adapts below --video-kbit."""

from __future__ import annotations

import logging
import threading
from collections.abc import Callable

import grpc
from google.protobuf import duration_pb2

from services.common.feeds import Feed
from services.foxglove.live import STATE, STEREO, VIDEO, WRENCH, LiveChannels
from telerobot.v1 import force_sensor_pb2 as fs_pb
from telerobot.v1 import force_sensor_pb2_grpc, proxy_robot_pb2_grpc, stereo_camera_pb2_grpc
from telerobot.v1 import proxy_robot_pb2 as pr_pb
from telerobot.v1 import stereo_camera_pb2 as sc_pb

log = logging.getLogger(__name__)

RECEIPT_TIMEOUT_S = 5.0
DEFAULT_VIDEO_KBIT = 1000  # 640x480 per eye, 10 fps (docs/services/live-view.md)


class VideoReceipts:
    """The video stream's side of receipts: the stream's id from its header, then for each
    pair a ReportReceipt sent without waiting (asking for a key frame when `channels` wants
    one). A receipt that fails is not retried: the next one carries the bytes anyway."""

    def __init__(self, camera: stereo_camera_pb2_grpc.StereoCameraStub, channels: LiveChannels):
        self._camera = camera
        self._channels = channels
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
            want_keyframe=self._channels.take_keyframe_request()), timeout=RECEIPT_TIMEOUT_S)
        with self._lock:
            self._pending.add(future)
        future.add_done_callback(self._done)

    def _done(self, future) -> None:
        with self._lock:
            self._pending.discard(future)


def station_feeds(channels: LiveChannels, proxy_robot: grpc.Channel, force_sensor: grpc.Channel,
                  stereo_camera: grpc.Channel, *, state_hz: float, wrench_hz: float,
                  stereo_fps: float, video_kbit: int = DEFAULT_VIDEO_KBIT,
                  sensor_hz: float = 1000.0,
                  on_status: Callable[[str, str | None], None] = lambda name, why: None,
                  ) -> dict[str, Feed]:
    """The four feeds of the live view (services.foxglove.live), not started; `on_status`
    as Feed's."""
    robot = proxy_robot_pb2_grpc.ProxyRobotStub(proxy_robot)
    sensor = force_sensor_pb2_grpc.ForceSensorStub(force_sensor)
    camera = stereo_camera_pb2_grpc.StereoCameraStub(stereo_camera)

    def open_state():
        if channels.cameras_unknown():  # the cameras' frames in /tf, before any video
            try:
                info = camera.GetStreamInfo(sc_pb.GetStreamInfoRequest(), timeout=2.0)
                channels.set_cameras(info.header)
            except grpc.RpcError as error:
                log.info("live view: no camera frames in /tf yet (%s)", error.code().name)
        period = duration_pb2.Duration()
        period.FromNanoseconds(int(1e9 / state_hz))
        return robot.StreamState(pr_pb.StreamStateRequest(period=period))

    def open_wrench():
        decimation = max(1, round(sensor_hz / wrench_hz))
        return sensor.StreamWrench(fs_pb.StreamWrenchRequest(decimation=decimation))

    def open_stereo():
        return camera.StreamPairs(sc_pb.StreamPairsRequest(
            encoding=sc_pb.IMAGE_ENCODING_JPEG, max_fps=stereo_fps))

    def open_video():
        return camera.StreamPairs(sc_pb.StreamPairsRequest(
            encoding=sc_pb.IMAGE_ENCODING_H264, max_fps=stereo_fps, receipts=True,
            max_kbit_per_s=video_kbit))

    receipts = VideoReceipts(camera, channels)

    def on_video(response: sc_pb.StreamPairsResponse) -> None:
        if response.WhichOneof("content") == "header":
            receipts.opened(response.header)
            channels.video_stream_opened()
        else:
            channels.stereo_video(response.pair)  # first: a key frame clears the request
            receipts.received(response.pair)  # that this receipt would otherwise repeat

    def on_wrench(response: fs_pb.StreamWrenchResponse) -> None:
        for sample in response.samples:
            channels.wrench(sample)

    def on_pairs(response: sc_pb.StreamPairsResponse) -> None:
        if response.WhichOneof("content") == "header":
            channels.set_cameras(response.header)
        else:
            channels.stereo_pair(response.pair)

    return {STATE: Feed(STATE, open_state, lambda response: channels.robot_state(response.state),
                        on_status),
            WRENCH: Feed(WRENCH, open_wrench, on_wrench, on_status),
            STEREO: Feed(STEREO, open_stereo, on_pairs, on_status),
            VIDEO: Feed(VIDEO, open_video, on_video, on_status)}
