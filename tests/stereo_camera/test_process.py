"""`python -m services.stereo_camera` as a real process: flags, errors, clean shutdown."""

from __future__ import annotations

import signal
import subprocess
import sys
import uuid

import grpc
import pytest

from services.stereo_camera.client import open_channel
from telerobot.v1 import stereo_camera_pb2 as pb
from telerobot.v1 import stereo_camera_pb2_grpc
from tests.processes import REPO, start_service

pytestmark = pytest.mark.e2e


def test_the_sim_service_without_a_world_serves_headers_refuses_pairs_and_stops_cleanly():
    absent = f"telerobot_test_absent_{uuid.uuid4().hex[:8]}"
    running = start_service("stereo_camera", "--width", "160", "--height", "120",
                            "--shm-name", absent)
    try:
        with open_channel(running.address) as channel:
            stub = stereo_camera_pb2_grpc.StereoCameraStub(channel)
            header = stub.GetStreamInfo(pb.GetStreamInfoRequest(), timeout=10).header
            assert header.source == "sim" and (header.width_px, header.height_px) == (160, 120)
            assert header.baseline_m == pytest.approx(0.12)
            with pytest.raises(grpc.RpcError) as error:
                stub.GetSnapshot(pb.GetSnapshotRequest(), timeout=20)
            assert error.value.code() is grpc.StatusCode.UNAVAILABLE
            assert "no world is running" in error.value.details()
    finally:
        code = running.stop(signal.SIGTERM, grace_s=15)
    assert code == 0, running.describe()
    assert running.exited.wait(5)  # every line read
    assert any("stopped" in line for line in running.lines)


def test_a_device_source_without_devices_is_refused_at_start_saying_why():
    result = subprocess.run(
        [sys.executable, "-m", "services.stereo_camera", "--source", "device", "--address",
         "127.0.0.1:0"], cwd=REPO, capture_output=True, text=True, timeout=60)
    assert result.returncode != 0
    assert "--left and --right, or --side-by-side" in result.stderr
