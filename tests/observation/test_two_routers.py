"""Observers behind a second router, across a delayed link between two network namespaces:
the station (with mutual TLS) and its router on this host, a router on the observers' host
joined to it through the impairment proxy at the papers' 183 ms round trip, and 64 observers
behind that router. One copy of the station's stream crosses the link, every observer gets
every sample, and the median sample reaches them within the one-way delay plus 20 ms. The
Foxglove live view and the C observer, on the observers' side, watch the station through their
router.

The p95 of that lag is printed, not judged: here it is 106-118 ms, around issue #33's bound
of the one-way delay plus 20 ms (111.5 ms), and what moves it is this host's CPU, which the
station, two routers, the proxy and 64 Python subscribers share (docs/observers.md)."""

from __future__ import annotations

import itertools
import json
import re
import signal
import ssl
from dataclasses import dataclass
from pathlib import Path

import pytest
from foxglove_schemas_protobuf.CompressedVideo_pb2 import CompressedVideo
from foxglove_schemas_protobuf.FrameTransforms_pb2 import FrameTransforms
from foxglove_schemas_protobuf.SceneUpdate_pb2 import SceneUpdate

from services.runtime.children import Child
from services.security import pki
from telerobot.v1 import (
    force_sensor_pb2,
    force_sensor_pb2_grpc,
    proxy_robot_pb2,
    proxy_robot_pb2_grpc,
)
from tests.conftest import wait_for
from tests.foxglove.test_channels import world_poses
from tests.foxglove.test_live_video import decode
from tests.foxglove.ws_client import FoxgloveClient
from tests.netns import linked_namespaces, python_in_namespace, unavailable_reason
from tests.observation.observers_process import READY
from tests.observation.test_c_observer import c_observer_in, lines_of
from tests.processes import start_process, start_station, station_env
from wire import foxglove as fx
from wire.tls import ChannelSecurity, open_channel

pytestmark = [pytest.mark.e2e,
              pytest.mark.skipif(unavailable_reason() is not None,
                                 reason=unavailable_reason() or "")]

STATION_IP, OBSERVERS_IP = "10.213.33.1", "10.213.33.2"  # a private /30 of the test's own
STATION = "campus"
ONE_WAY_DELAY_MS = 91.5  # the papers' campus route: 183 ms round trip
OBSERVERS = 64
OBSERVE_S = 6.0


@dataclass
class Campus:
    """The station's side and the observers' side, joined by the delayed link."""

    tls_dir: Path
    station: Child
    link: Child
    remote: str  # the observers' namespace
    router_address: str  # the remote router's, in its namespace


@pytest.fixture(scope="module")
def campus(tmp_path_factory):
    tls_dir = tmp_path_factory.mktemp("pki")
    pki.init(tls_dir, hosts=[STATION_IP, OBSERVERS_IP])
    started = []
    try:
        with linked_namespaces(STATION_IP, OBSERVERS_IP, left_in_this_namespace=True) as (
                _, remote):
            station = start_station(station_env(TELEROBOT_TLS_DIR=str(tls_dir),
                                                TELEROBOT_STATION=STATION,
                                                TELEROBOT_ADVERTISE="0"))
            started.append(station)
            _start_reading(station.ready, tls_dir)
            link = start_process([
                "-m", "services.impairment", "--allow-network", "--listen", f"{STATION_IP}:0",
                "--target", station.ready["zenoh_router"], "--delay",
                f"{ONE_WAY_DELAY_MS}ms"], name="impairment")
            started.append(link)
            link_address = link.wait_ready("impairment", timeout_s=30)
            router = start_process(python_in_namespace(remote, [
                "-m", "services.zenoh_router", "--address", "127.0.0.1:0", "--tls-dir",
                str(tls_dir), "--connect", f"tls/{link_address}"]), name="remote_router")
            started.append(router)
            router_address = router.wait_ready("zenoh_router", timeout_s=30)
            yield Campus(tls_dir, station, link, remote, router_address)
    finally:
        codes = {child.name: child.stop(signal.SIGINT) for child in reversed(started)}
    # Each stopped by itself, none killed: the remote router too, whose Zenoh session's close
    # blocks while its link to the station's router goes through the slow link.
    assert set(codes.values()) == {0}, codes


def test_one_copy_crosses_to_a_remote_router_and_its_64_observers_keep_up(campus):
    down_before = _bytes_down(campus.link)
    observers = start_process(python_in_namespace(campus.remote, [
        "-m", "tests.observation.observers_process", "--router",
        f"tls/{campus.router_address}", "--tls-dir", str(campus.tls_dir), "--station", STATION,
        "--count", str(OBSERVERS), "--seconds", str(OBSERVE_S)]), name="observers")
    try:
        observers.wait_line(READY, timeout_s=90)
        assert observers.wait(OBSERVE_S + 60) == 0, observers.describe()
    finally:
        observers.stop(signal.SIGINT)
    result = json.loads(observers.lines[-1])
    carried = _bytes_down(campus.link) - down_before
    each = result["observers"]
    assert len(each) == OBSERVERS and all(o["messages"] > 0 for o in each)
    most = max(o["bytes"] for o in each)
    print(f"the link carried {carried} B; an observer got {most} B; lag p50 "
          f"{result['lag_p50_ms']:.1f} ms, p95 {result['lag_p95_ms']:.1f} ms")
    # One copy: the station -> remote router direction carried about what one observer got
    # (with Zenoh's framing), not 64 times it.
    assert most <= carried < 2 * most, (carried, most)
    assert sum(o["lost"] for o in each) == 0
    assert result["lag_p50_ms"] <= ONE_WAY_DELAY_MS + 20, result["lag_p50_ms"]


def test_the_foxglove_live_view_works_from_the_remote_router(campus):
    """The live view on the observers' side, watching through their router: a Foxglove client
    gets the arm's frames, the force and the video, which starts at a key frame and decodes."""
    _connect(campus.station.ready, campus.tls_dir)
    view = start_process(python_in_namespace(campus.remote, [
        "-m", "services.foxglove", "--router", f"tls/{campus.router_address}", "--station",
        STATION, "--tls-dir", str(campus.tls_dir), "--address", f"{OBSERVERS_IP}:0",
        "--allow-network"]), name="remote_live_view")
    try:
        address = view.wait_ready("foxglove", timeout_s=30)
        trust = ssl.create_default_context(cafile=str(campus.tls_dir / "ca.pem"))
        topics = [fx.TF, fx.JOINT_STATES, fx.FORCE_ARROW, fx.STEREO_VIDEO]
        with FoxgloveClient(f"wss://{address}", ssl=trust) as client:
            client.wait_advertised(topics)
            assert fx.LEFT_IMAGE not in client.channels  # the per-eye JPEG stays home
            client.subscribe(topics)
            client.collect(lambda got: all(len(got[t]) >= 3 for t in topics), timeout_s=60)
    finally:
        view.stop(signal.SIGINT)
    video = [CompressedVideo.FromString(data) for _, data in client.received[fx.STEREO_VIDEO]]
    assert fx.h264_is_keyframe(video[0].data)
    pictures = decode(video)
    assert pictures[0].ndim == 3 and pictures[0].std() > 0
    arrow = SceneUpdate.FromString(client.received[fx.FORCE_ARROW][-1][1])
    assert arrow.entities[0].frame_id == fx.TOOL_FRAME
    # Once the video's header came, the cameras' frames join the arm's in /tf.
    frames = [world_poses(FrameTransforms.FromString(data))
              for _, data in client.received[fx.TF]]
    assert fx.TOOL_FRAME in frames[0]
    assert {fx.LEFT_CAMERA_FRAME, fx.RIGHT_CAMERA_FRAME} <= set(frames[-1])


def test_the_c_observer_follows_the_station_from_the_remote_router(campus):
    """Zenoh's C client on the observers' side, over mutual TLS as the observer: the arm and
    the sensor's samples, in order, through their router."""
    _connect(campus.station.ready, campus.tls_dir)
    lines = lines_of(c_observer_in(campus.remote, [
        "--router", f"tls/{campus.router_address}", "--tls-dir", str(campus.tls_dir),
        "--station", STATION, "--topics", "wrench,state", "--seconds", "4"]))
    wrench = [line for line in lines if line.get("topic") == "wrench"]
    assert len(wrench) >= 20 and all(b["first"] > a["last"]
                                     for a, b in itertools.pairwise(wrench))
    assert any(line.get("topic") == "state" and len(line["joints_rad"]) == 6 for line in lines)


def _connect(ready: dict[str, str], tls_dir) -> None:
    with open_channel(ready["proxy_robot"], security=ChannelSecurity(tls_dir, "admin"),
                      service="proxy_robot") as channel:
        proxy_robot_pb2_grpc.ProxyRobotStub(channel).Connect(proxy_robot_pb2.ConnectRequest(),
                                                             timeout=10)


def _start_reading(ready: dict[str, str], tls_dir) -> None:
    with open_channel(ready["force_sensor"], security=ChannelSecurity(tls_dir, "admin"),
                      service="force_sensor") as channel:
        force_sensor_pb2_grpc.ForceSensorStub(channel).StartReading(
            force_sensor_pb2.StartReadingRequest(), timeout=10)


def _bytes_down(link) -> int:
    """The bytes the impairment proxy has carried from its target (the station's router) to its
    client (the remote router), from the stats it prints on SIGUSR2."""
    told = sum(line.startswith("stats:") for line in link.lines)
    link.send_signal(signal.SIGUSR2)
    wait_for(lambda: sum(line.startswith("stats:") for line in link.lines) > told, 10,
             "the link's stats")
    line = [line for line in link.lines if line.startswith("stats:")][-1]
    return int(re.search(r"bytes=\{'up': \d+, 'down': (\d+)\}", line).group(1))
