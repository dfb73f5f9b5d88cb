"""`make teleop`'s program end to end: against a station started the way it starts one
(clients.teleop.stack.local_station, every service on port 0), it runs the peg-in-hole task with
force feedback and then with compliance, and leaves its video, plots and summary. Once in
plaintext and once with mutual TLS on every link (TELEROBOT_TLS_DIR, as the README says), on the
PUMA 560; then on the FR3 and the UR5e (`make teleop ARM=…`), and on franka-sim through the
Franka driver (`DRIVER=franka-sim`, compliance mode)."""

from __future__ import annotations

import json
import os
import subprocess
import sys

import cv2
import pytest

from clients.teleop.stack import local_station
from services.launcher import GRPC_CHILDREN, HARDWARE_STATION, STATION
from services.runtime.priority import COMMAND_PATH_FIFO_PRIORITY
from services.runtime.process import metrics_port_name
from services.security import pki
from tests.conftest import COMMAND_PATH_SERVICES
from tests.processes import REPO, scrape_metrics, unique_shm_name
from wire.addresses import env_name

pytestmark = pytest.mark.e2e


# TLS and the arm are independent: one arm's run is also the TLS one (each run is ~40 s).
@pytest.mark.parametrize(("tls", "arm"), [(False, "puma560"), (False, "fr3"), (True, "ur5e")],
                         ids=["puma560", "fr3", "ur5e-tls"])
def test_teleop_finishes_the_peg_in_hole_and_leaves_its_artifacts(tmp_path, tls, arm):
    env = {f"TELEROBOT_{name.upper()}_ADDRESS": "127.0.0.1:0" for name in STATION}
    env["TELEROBOT_WORLD_SHM"] = unique_shm_name()
    env["TELEROBOT_ARM"] = arm
    if tls:
        pki.init(tmp_path / "pki")
        env.update(TELEROBOT_TLS_DIR=str(tmp_path / "pki"),
                   TELEROBOT_AUDIT_DIR=str(tmp_path / "audit"))
    out = tmp_path / "run"
    with local_station(env=env) as addresses:
        # local_station yields once the DecisionServer is up; the web console and the live view
        # come after it.
        services = {name for name in addresses if name in STATION}  # (and /metrics ports)
        assert set(GRPC_CHILDREN) <= services
        operator = addresses["decision_server"]
        result = subprocess.run(
            [sys.executable, "-m", "clients.teleop", "--address", operator, "--out", str(out),
             "--calibration", str(tmp_path / "cameras.json"), "--arm", arm],
            cwd=REPO, env={**os.environ, **env}, capture_output=True, text=True,
            timeout=400)
        assert result.returncode == 0, result.stdout[-3000:] + result.stderr[-3000:]
        if not tls and arm == "puma560":
            _check_the_station_metrics_moved(addresses)
    summary = json.loads((out / "summary.json").read_text())
    assert summary["station"] == f"found at {operator}"
    assert summary["arm"] == arm
    runs = {run["mode"]: run for run in summary["runs"]}
    assert list(runs) == ["feedback", "compliance"], runs
    assert all(run["success"] and run["depth_m"] > 0.035 for run in runs.values()), runs
    # With feedback the operator felt the floor (the force passed 8 N) and backed off; with
    # compliance the server's force loop met it more gently and held the 5 N asked.
    assert runs["feedback"]["peak_force_n"] > 8.0, runs
    assert runs["compliance"]["peak_force_n"] < runs["feedback"]["peak_force_n"], runs
    assert abs(runs["compliance"]["final_force_n"] - 5.0) < 1.0, runs
    assert summary["cameras_identified_now"] and (tmp_path / "cameras.json").exists()
    for name in ("force.png", "tool_path.png", "latency.png"):
        assert (out / name).stat().st_size > 10_000
    video = cv2.VideoCapture(str(out / "stereo.mp4"))
    frames = 0
    while video.read()[0]:
        frames += 1
    # Two ~15-20 s runs, rendered in software at 1–10 fps depending on the machine's load:
    # the file holds every frame the summary counts.
    assert frames == summary["video_frames"] >= 10, (frames, summary)
    assert "feedback" in result.stdout and "compliance" in result.stdout
    if tls:  # the operator drove as the identity of its certificate, and it is on record
        records = [json.loads(line) for line in
                   (tmp_path / "audit" / "decision_server.jsonl").read_text().splitlines()]
        driven = {(r["identity"], r["method"].rsplit("/", 1)[1], r["outcome"]) for r in records}
        assert {("operator", "AcquireControl", "OK"), ("operator", "Teleoperate", "OK")} \
            <= driven, driven


def _total(samples, name: str, **labels) -> float:
    wanted = set(labels.items())
    return sum(value for (sample, sample_labels), value in samples.items()
               if sample == name and wanted <= sample_labels)


def _check_the_station_metrics_moved(addresses: dict[str, str]) -> None:
    """After a session, each service's /metrics parses and its counters moved with the
    session's traffic: calls, the commands' ages, the streams' lags, the world's steps."""
    grpc_services = set(GRPC_CHILDREN)
    scraped = {name: scrape_metrics(addresses[metrics_port_name(name)]) for name in grpc_services}
    for name, samples in scraped.items():
        if name != "world":  # the world serves shared memory, no gRPC calls
            assert _total(samples, "telerobot_rpc_handled_total") > 0, name
    decisions = scraped["decision_server"]
    assert _total(decisions, "telerobot_rpc_handled_total", code="OK",
                  method="/telerobot.v1.DecisionServer/AcquireControl") >= 1
    # Every command of both runs was aged on arrival (the task sends hundreds).
    assert _total(decisions, "telerobot_command_age_seconds_count") > 100
    assert _total(decisions, "telerobot_events_total", event="lease_change") >= 1
    # The DecisionServer read the wrench and the arm's states through fanned-out streams.
    assert _total(scraped["force_sensor"], "telerobot_stream_lag_seconds_count",
                  stream="wrench") > 100
    assert _total(scraped["proxy_robot"], "telerobot_stream_lag_seconds_count") > 0
    assert _total(scraped["world"], "telerobot_world_steps_total") > 1000


def test_teleop_inserts_the_peg_on_a_franka_under_compliance(tmp_path):
    """`make teleop ARM=fr3 DRIVER=franka-sim`: the whole station on ProxyRobot's Franka driver,
    franka-sim as the robot (libfranka's protocol, from its home pose after the driver brings
    it there), the force sensor on the Franka's own estimate of the push (its joint-impedance
    spring). Compliance mode: feedback mode also runs, and passes most runs, but the spring
    reads the servo's tracking error as a push while the arm moves, and now and then that stops
    the scripted operator short of the floor (docs/arms.md).

    The station's command paths run in real time, as a Franka station is deployed (the suite
    runs other stations' as ordinary threads, tests/conftest.py): at ordinary priority on a
    loaded machine the force loop's wrench samples come stale and it stops short of the 5 N
    (CI read 1.6 N; beside two busy loops 1.6 N at ordinary priority, 5.0 N in real time)."""
    env = {f"TELEROBOT_{name.upper()}_ADDRESS": "127.0.0.1:0" for name in HARDWARE_STATION}
    env.update(TELEROBOT_WORLD_SHM=unique_shm_name(), TELEROBOT_ARM="fr3",
               TELEROBOT_PROXY_ROBOT_DRIVER="franka-sim")
    env.update({env_name(name, "rt_priority"): str(COMMAND_PATH_FIFO_PRIORITY)
                for name in COMMAND_PATH_SERVICES})
    out = tmp_path / "run"
    with local_station(env=env) as addresses:
        # Up once the DecisionServer is: every service it depends on, which start before it.
        door = HARDWARE_STATION.index("decision_server")
        assert set(HARDWARE_STATION[:door + 1]) <= set(addresses)
        assert "world" not in addresses  # the Franka is the hardware; ProxyRobot mirrors it
        result = subprocess.run(
            [sys.executable, "-m", "clients.teleop", "--address", addresses["decision_server"],
             "--out", str(out), "--calibration", str(tmp_path / "cameras.json"), "--arm", "fr3",
             "--modes", "compliance"],
            cwd=REPO, env={**os.environ, **env}, capture_output=True, text=True, timeout=400)
        assert result.returncode == 0, result.stdout[-3000:] + result.stderr[-3000:]
    summary = json.loads((out / "summary.json").read_text())
    (run,) = summary["runs"]
    assert summary["arm"] == "fr3" and run["mode"] == "compliance", summary
    assert run["success"] and run["depth_m"] > 0.035, run
    assert abs(run["final_force_n"] - 5.0) < 1.0, run
    assert summary["video_frames"] >= 10, summary  # the cameras render the mirrored Franka
