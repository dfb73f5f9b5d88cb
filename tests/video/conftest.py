"""Video tests: a real StereoCamera and DecisionServer in front of it, reached through the
impairment link (services.impairment) as an operator across a network would."""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

import pytest

from services.runtime import children
from tests.processes import start_service


@dataclass
class VideoStation:
    camera_address: str  # the StereoCamera's own port
    decision_address: str  # the operator's one address


@pytest.fixture(scope="module")
def video_station(world, backends, tmp_path_factory) -> Iterator[VideoStation]:
    """A pattern camera (640x480 per eye, 30 fps: an image x264 works at) behind a
    DecisionServer process on the shared world's arm and band, with a sensor of its own."""
    started = []
    try:
        started.append(start_service("stereo_camera", "--source", "pattern", "--width", "640",
                                     "--height", "480", "--fps", "30"))
        started.append(start_service("force_sensor",
                                     env={"TELEROBOT_WORLD_SHM": world.shm_name}))
        started.append(start_service(
            "decision_server", "--proxy-robot-address", backends.proxy_address,
            "--force-sensor-address", started[1].address,
            "--stereo-camera-address", started[0].address,
            "--emergency-stop-address", backends.emergency_address,
            "--recordings-dir", str(tmp_path_factory.mktemp("recordings"))))
        yield VideoStation(started[0].address, started[2].address)
    finally:
        children.stop_all(started)
