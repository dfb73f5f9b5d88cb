"""StereoCamera tests: real in-process gRPC servers on port 0 serving real sources."""

from __future__ import annotations

import math
from collections.abc import Iterator
from dataclasses import dataclass

import grpc
import numpy as np
import pytest

import services.stereo_camera  # noqa: F401  (chooses MUJOCO_GL=egl before mujoco loads)
from services.runtime.server import TelerobotServer, binding, create_server
from services.stereo_camera.capture import CaptureHub
from services.stereo_camera.client import open_channel
from services.stereo_camera.servicer import StereoCameraServicer
from services.stereo_camera.source import StereoSource
from telerobot.v1 import stereo_camera_pb2 as pb
from telerobot.v1 import stereo_camera_pb2_grpc

RPC_TIMEOUT_S = 20.0


@dataclass
class Camera:
    """A served source: the client stub, and the hub behind it (for its counters)."""

    stub: stereo_camera_pb2_grpc.StereoCameraStub
    hub: CaptureHub
    server: TelerobotServer
    channel: grpc.Channel
    servicer: StereoCameraServicer
    address: str

    def stream(self, pairs: int, **request) -> list[pb.StreamPairsResponse]:
        """The first message and `pairs` more (all messages, in order), then cancel."""
        messages = []
        call = self.stub.StreamPairs(pb.StreamPairsRequest(**request), timeout=RPC_TIMEOUT_S)
        try:
            for message in call:
                messages.append(message)
                if len(messages) > pairs:
                    break
        finally:
            call.cancel()
        return messages

    def snapshot(self, **request) -> pb.GetSnapshotResponse:
        return self.stub.GetSnapshot(pb.GetSnapshotRequest(**request), timeout=RPC_TIMEOUT_S)

    def close(self) -> None:
        self.channel.close()
        self.server.stop(0)
        self.hub.close()


def start_camera(source: StereoSource, **hub_options) -> Camera:
    """Serve `source` from an in-process server on a free port; close() when done."""
    hub = CaptureHub(source, **hub_options)
    servicer = StereoCameraServicer(hub)
    server, port = create_server(
        "127.0.0.1:0", [binding(stereo_camera_pb2_grpc, "StereoCamera", servicer)])
    server.start()
    hub.start()
    address = f"127.0.0.1:{port}"
    channel = open_channel(address)
    return Camera(stereo_camera_pb2_grpc.StereoCameraStub(channel), hub, server, channel,
                  servicer, address)


@pytest.fixture
def serve() -> Iterator:
    """Factory: start_camera() for one test, closed after it."""
    started: list[Camera] = []

    def start(source: StereoSource, **hub_options) -> Camera:
        started.append(start_camera(source, **hub_options))
        return started[-1]

    yield start
    for camera in started:
        camera.close()


def psnr(a: np.ndarray, b: np.ndarray) -> float:
    mse = np.mean((a.astype(float) - b.astype(float)) ** 2)
    return math.inf if mse == 0 else 10 * math.log10(255.0**2 / mse)


def error_code(call) -> tuple[grpc.StatusCode, str]:
    """(code, details) of an RPC that must fail."""
    with pytest.raises(grpc.RpcError) as error:
        call()
    return error.value.code(), error.value.details()
