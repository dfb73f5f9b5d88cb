"""The live view's upstream streams: a Feed (services.common.feeds) each, open while a viewer
watches one of its topics. Read-only calls (role observer).

The video feed's stream takes receipts (services.common.video_receipts), which ask for a key
frame when the live view needs one (LiveChannels.take_keyframe_request); its bitrate adapts
below --video-kbit."""

from __future__ import annotations

import logging
from collections.abc import Callable

import grpc
from google.protobuf import duration_pb2

from services.common.feeds import Feed
from services.common.video_receipts import VideoReceipts
from services.foxglove.live import STATE, STEREO, VIDEO, WRENCH, LiveChannels
from telerobot.v1 import force_sensor_pb2 as fs_pb
from telerobot.v1 import force_sensor_pb2_grpc, proxy_robot_pb2_grpc, stereo_camera_pb2_grpc
from telerobot.v1 import proxy_robot_pb2 as pr_pb
from telerobot.v1 import stereo_camera_pb2 as sc_pb

log = logging.getLogger(__name__)

DEFAULT_VIDEO_KBIT = 1000  # 640x480 per eye, 10 fps (docs/services/live-view.md)


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

    receipts = VideoReceipts(camera, channels.take_keyframe_request)

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
