"""Client tests: the real world, ProxyRobot and ForceSensor processes with an in-process
DecisionServer in front (the DecisionServer tests' fixtures), and an in-process StereoCamera
serving the synthetic pattern."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from services.runtime.server import binding, create_server
from services.stereo_camera.capture import CaptureHub
from services.stereo_camera.pattern import PatternSource
from services.stereo_camera.servicer import StereoCameraServicer
from telerobot.v1 import stereo_camera_pb2_grpc
from tests.decision_server.conftest import fake_station, station  # noqa: F401  (fixtures)

CAMERA_WIDTH_PX, CAMERA_HEIGHT_PX = 96, 72


@pytest.fixture
def camera_address() -> Iterator[str]:
    """host:port of a StereoCamera serving a small synthetic pattern."""
    hub = CaptureHub(PatternSource(CAMERA_WIDTH_PX, CAMERA_HEIGHT_PX, fps=60))
    server, port = create_server(
        "127.0.0.1:0",
        [binding(stereo_camera_pb2_grpc, "StereoCamera", StereoCameraServicer(hub))])
    server.start()
    hub.start()
    yield f"127.0.0.1:{port}"
    server.stop(0)
    hub.close()
