"""The C observer (clients/c, built by `make c-observer`): Zenoh's own C client, zenoh-pico,
with protoc-c's code of the protos, reading what the test puts under a station's keys through
a real router in this process, plaintext on loopback and over mutual TLS. Against the whole
station: test_station_observation.py."""

from __future__ import annotations

import json
import subprocess

import pytest

from services.security import pki
from telerobot.v1 import decision_server_pb2 as ds_pb
from telerobot.v1 import force_sensor_pb2 as fs_pb
from telerobot.v1 import proxy_robot_pb2 as pr_pb
from telerobot.v1 import stereo_camera_pb2 as sc_pb
from telerobot.v1 import types_pb2
from tests.conftest import wait_for
from tests.observation.conftest import RELIABLY
from tests.observation.test_observation import T0_NS, stamp
from tests.processes import REPO
from wire.observation import TOPICS, ZenohTls, client, key

pytestmark = pytest.mark.e2e

C_OBSERVER = REPO / "build" / "c-observer" / "telerobot-observe"
STATION = "lab-3"


def c_observer(*args: str) -> subprocess.Popen:
    return _start([], list(args))


def c_observer_in(namespace: str, args: list[str]) -> subprocess.Popen:
    """The C observer in a network namespace of the test's own."""
    return _start(["ip", "netns", "exec", namespace], args)


def _start(prefix: list[str], args: list[str]) -> subprocess.Popen:
    if not C_OBSERVER.exists():
        pytest.fail(f"{C_OBSERVER} is missing: `make test` builds it (`make c-observer`)")
    return subprocess.Popen([*prefix, str(C_OBSERVER), *args], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)


def lines_of(process: subprocess.Popen, code: int = 0) -> list[dict]:
    out, err = process.communicate(timeout=60)
    assert process.returncode == code, (out, err)
    return [json.loads(line) for line in out.splitlines()]


def test_it_decodes_every_topic_with_the_protos_as_the_schema(router, sessions):
    observer = c_observer("--router", router, "--station", STATION, "--topics",
                          ",".join(TOPICS), "--count", "6", "--seconds", "60")
    session = sessions()
    publishers = {topic: session.declare_publisher(key(STATION, topic),
                                                   congestion_control=RELIABLY)
                  for topic in TOPICS}
    wait_for(lambda: all(p.matching_status.matching for p in publishers.values()),
             timeout_s=30, what="the C observer subscribed to every topic")
    publishers["wrench"].put(fs_pb.StreamWrenchResponse(samples=[
        fs_pb.WrenchSample(sequence=s, sample_time=stamp(T0_NS + s * 1_000_000),
                           wrench=types_pb2.Wrench(force_n=types_pb2.Vector3(z=-s / 2)))
        for s in range(1, 11)]).SerializeToString())
    publishers["wrench"].put(b"\xff\xff\xff")  # no message of any type
    publishers["state"].put(pr_pb.StreamStateResponse(state=types_pb2.RobotState(
        sequence=88, status=types_pb2.ROBOT_STATUS_READY, joint_positions_rad=[0.5, -1.25],
        tool_pose=types_pb2.Pose(position_m=types_pb2.Vector3(x=0.6, y=-0.15, z=0.5)))
    ).SerializeToString())
    publishers["events"].put(ds_pb.StreamEventsResponse(
        sequence=12, control_changed=ds_pb.ControlChangedEvent()).SerializeToString())
    publishers["status"].put(ds_pb.SessionStatus(
        control=ds_pb.ControlState(holders=[ds_pb.ControlHolder(operator_id='ann "the" op')]),
        dependencies=[ds_pb.Dependency(name="proxy_robot",
                                       state=ds_pb.DEPENDENCY_STATE_SERVING)]
    ).SerializeToString())
    publishers["video"].put(sc_pb.StreamPairsResponse(header=sc_pb.StereoHeader(
        width_px=640, height_px=480)).SerializeToString())
    publishers["video"].put(sc_pb.StreamPairsResponse(pair=sc_pb.StereoPair(
        sequence=40, keyframe=True, video_frame=bytes(321))).SerializeToString())
    lines = lines_of(observer)
    by_topic = {line.get("topic"): line for line in lines if "topic" in line}
    wrench = by_topic["wrench"]
    assert (wrench["samples"], wrench["first"], wrench["last"]) == (10, 1, 10)
    assert wrench["force_n"] == [0, 0, -5]
    state = by_topic["state"]
    assert state["status"] == "ROBOT_STATUS_READY" and state["joints_rad"] == [0.5, -1.25]
    assert state["tool_m"] == [0.6, -0.15, 0.5]
    assert by_topic["events"] == {"topic": "events", "sequence": 12, "event": "control_changed"}
    assert by_topic["status"]["holders"] == ['ann "the" op']
    assert by_topic["status"]["dependencies"] == {"proxy_robot": "DEPENDENCY_STATE_SERVING"}
    video = [line for line in lines if line.get("topic") == "video"]
    assert video == [
        {"topic": "video", "content": "header", "width_px": 640, "height_px": 480},
        {"topic": "video", "content": "pair", "sequence": 40, "keyframe": True, "bytes": 321}]
    assert lines[-1]["summary"]["wrench"] == {"messages": 1, "undecodable": 1}


@pytest.mark.parametrize("args, why", [
    (["--router", "tcp/10.1.2.3:7447"], "must be tcp/ on loopback"),
    (["--router", "tls/127.0.0.1:7447"], "give the station's TLS directory"),
    (["--router", "tcp/127.0.0.1:7447", "--station", "a/b"], "station name"),
    (["--router", "tcp/127.0.0.1:7447", "--topics", "wrench,pictures"], "unknown topic"),
])
def test_bad_arguments_exit_2_saying_why(args, why):
    process = c_observer(*args)
    _, err = process.communicate(timeout=30)
    assert process.returncode == 2 and why in err, err


def test_a_router_that_does_not_answer_exits_1():
    process = c_observer("--router", "tcp/127.0.0.1:9", "--seconds", "1")
    _, err = process.communicate(timeout=60)
    assert process.returncode == 1 and "does not answer" in err, err


def test_over_tls_it_joins_as_the_observer_and_checks_the_router(pki_dir, tls_router, tmp_path):
    observer = c_observer("--router", tls_router, "--tls-dir", str(pki_dir), "--station",
                          STATION, "--topics", "status", "--count", "1", "--seconds", "60")
    station = client(tls_router, ZenohTls(pki_dir, "observation"))
    try:
        publisher = station.declare_publisher(key(STATION, "status"),
                                              congestion_control=RELIABLY)
        wait_for(lambda: publisher.matching_status.matching, timeout_s=30,
                 what="the C observer subscribed through the TLS router")
        publisher.put(ds_pb.SessionStatus(control=ds_pb.ControlState(
            holders=[ds_pb.ControlHolder(operator_id="tls-ann")])).SerializeToString())
        assert lines_of(observer)[0]["holders"] == ["tls-ann"]
    finally:
        station.close()
    # A certificate of another CA speaks for nobody here, and the router's is checked too.
    pki.init(tmp_path / "other")
    refused = c_observer("--router", tls_router, "--tls-dir", str(tmp_path / "other"),
                         "--seconds", "1")
    _, err = refused.communicate(timeout=60)
    assert refused.returncode == 1 and "does not answer" in err, err


def test_over_tls_the_certificates_must_be_there(tmp_path):
    process = c_observer("--router", "tls/127.0.0.1:7447", "--tls-dir", str(tmp_path))
    _, err = process.communicate(timeout=30)
    assert process.returncode == 2 and "ca.pem: `make certs` issues it" in err, err
