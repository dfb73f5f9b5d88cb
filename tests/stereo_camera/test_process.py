"""`python -m services.stereo_camera` as a real process: flags, errors, clean shutdown."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import threading
import uuid
from pathlib import Path

import grpc
import pytest

from services.runtime.lanes import DEFAULT_LANES
from services.runtime.priority import VIDEO_NICE
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


def thread_nice_values(pid: int) -> dict[int, int]:
    """The nice value of each thread of `pid`, by thread id (/proc/PID/task/TID/stat field
    19); the main thread's id is `pid`."""
    values = {}
    for task in Path(f"/proc/{pid}/task").iterdir():
        try:
            values[int(task.name)] = int((task / "stat").read_text().rsplit(")", 1)[1].split()[16])
        except FileNotFoundError:  # the thread ended meanwhile
            continue
    return values


def lane_values(base: int) -> set[int]:
    """The nice values a process's threads may have when its own is `base`: each lane's
    offset from it."""
    return {base + config.nice for config in DEFAULT_LANES.values()}


def _stream_one_pair(address: str) -> None:
    """An H.264 stream's first pair: the threads that capture and encode have started."""
    with open_channel(address) as channel:
        stub = stereo_camera_pb2_grpc.StereoCameraStub(channel)
        call = stub.StreamPairs(pb.StreamPairsRequest(encoding=pb.IMAGE_ENCODING_H264),
                                timeout=30)
        assert any(response.HasField("pair") for response in call)
        call.cancel()


def test_the_camera_yields_to_the_operator_every_thread_at_its_nice_value():
    running = start_service("stereo_camera", "--source", "pattern", "--width", "160",
                            "--height", "120", "--nice", str(VIDEO_NICE))  # the suite's is 0
    try:
        _stream_one_pair(running.address)
        values = list(thread_nice_values(running.pid).values())
        # The lanes keep their order from the process's value: the stream's (medium) and the
        # threads that capture and encode at VIDEO_NICE, the stop's and the high lane's above.
        assert set(values) <= lane_values(VIDEO_NICE), values
        assert values.count(VIDEO_NICE) >= len(values) - sum(
            config.static_threads for config in DEFAULT_LANES.values() if config.nice), values
        assert any(f"every thread at nice {VIDEO_NICE}" in line for line in running.lines)
    finally:
        running.stop()


def test_nice_zero_leaves_the_camera_at_the_value_it_was_started_with():
    inherited = os.getpriority(os.PRIO_PROCESS, threading.get_native_id())
    running = start_service("stereo_camera", "--source", "pattern", "--width", "160",
                            "--height", "120", "--nice", "0")
    try:
        _stream_one_pair(running.address)
        values = thread_nice_values(running.pid)
        assert values[running.pid] == inherited  # the main thread: the process's own
        assert set(values.values()) <= lane_values(inherited), values
        assert list(values.values()).count(inherited) > len(values) // 2, values
    finally:
        running.stop()
