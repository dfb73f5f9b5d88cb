"""Demonstrations end to end: `make teleop EPISODES=3` on a station started as it starts one
records three episodes at the DecisionServer (MCAP, with the stereo video); the export makes a
LeRobotDataset v3.0 of them, checked field by field against the layout lerobot 0.4-0.6 reads;
episode 0 of it replays on the arm to where the recording had the tool; then a DecisionServer
killed (SIGKILL) mid-episode leaves the earlier episodes whole, and the export names the last
one incomplete."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
from fractions import Fraction
from pathlib import Path

import av
import numpy as np
import pandas as pd
import pyarrow as pa
import pyarrow.parquet as pq
import pytest

from clients.python.decision_server import DecisionClient
from clients.teleop.export_lerobot import export
from clients.teleop.lerobot_dataset import ACTION_NAMES, state_names
from clients.teleop.replay_dataset import replay
from clients.teleop.stack import local_station
from services.launcher import STATION
from tests.conftest import wait_for
from tests.processes import REPO, unique_shm_name

pytestmark = pytest.mark.e2e

EPISODES = 3
FPS = 30
TASK = "insert the peg"


@pytest.fixture(scope="module")
def recorded(tmp_path_factory):
    """Three episodes by make teleop, then a fourth cut short by a SIGKILL of the
    DecisionServer; the recordings directory and make teleop's summary."""
    tmp = tmp_path_factory.mktemp("episodes")
    recordings = tmp / "recordings"
    env = {f"TELEROBOT_{name.upper()}_ADDRESS": "127.0.0.1:0" for name in STATION}
    shm = unique_shm_name()
    env.update(TELEROBOT_WORLD_SHM=shm, TELEROBOT_RECORDINGS_DIR=str(recordings))
    out = tmp / "run"
    with local_station(env=env) as addresses:
        result = subprocess.run(
            [sys.executable, "-m", "clients.teleop", "--address", addresses["decision_server"],
             "--out", str(out), "--calibration", str(tmp / "cameras.json"), "--modes",
             "feedback", "--episodes", str(EPISODES), "--task", TASK, "--no-video"],
            cwd=REPO, env={**os.environ, **env}, capture_output=True, text=True, timeout=600)
        assert result.returncode == 0, result.stdout[-3000:] + result.stderr[-3000:]
        before = tmp / "dataset-before"
        export([recordings], before, FPS, report=lambda line: None)
        with DecisionClient(addresses["decision_server"], default_timeout=10.0) as client:
            replayed = replay(client, before, 0)
            client.release_control()
        _kill_mid_episode(addresses["decision_server"], recordings, shm)
    return recordings, json.loads((out / "summary.json").read_text()), replayed


def _kill_mid_episode(address: str, recordings: Path, shm: str) -> None:
    with DecisionClient(address, default_timeout=10.0) as client:
        client.acquire_control("test", lease_duration_s=30.0)
        client.start_episode(TASK, name="killed")
        partial = recordings / "killed.mcap.partial"
        wait_for(lambda: partial.exists() and partial.stat().st_size > 64_000,  # samples, frames
                 timeout_s=30, what="the episode's file grown")
        os.kill(_decision_server_pid(shm), signal.SIGKILL)


def _decision_server_pid(shm: str) -> int:
    """The station's DecisionServer: the process running it with this station's world (not its
    recording writer, `-m services.decision_server.recording_writer`, which shares both)."""
    for entry in Path("/proc").iterdir():
        try:
            arguments = (entry / "cmdline").read_bytes().split(b"\0")
            environ = (entry / "environ").read_bytes()
        except (OSError, ValueError):
            continue
        if arguments[1:3] == [b"-m", b"services.decision_server"] and shm.encode() in environ:
            return int(entry.name)
    raise AssertionError("no DecisionServer process found")


@pytest.fixture(scope="module")
def dataset(recorded, tmp_path_factory):
    recordings = recorded[0]
    out = tmp_path_factory.mktemp("dataset") / "peg"
    lines: list[str] = []
    info = export([recordings], out, FPS, report=lines.append)
    return out, info, lines


def test_make_teleop_recorded_each_episode_with_its_outcome_and_video(recorded):
    recordings, summary, _ = recorded
    episodes = summary["episodes"]
    assert len(episodes) == EPISODES, summary
    runs = summary["runs"]
    for episode, run in zip(episodes, runs, strict=True):
        assert episode["task"] == TASK
        assert episode["outcome"] == ("SUCCEEDED" if run["success"] else "FAILED")
        assert episode["video_frames"] > 100 and episode["commands"] > 100, episode
        assert (recordings / f"{episode['name']}.mcap").exists()


def test_the_export_names_the_killed_episode_and_keeps_the_others(dataset, recorded):
    _, info, lines = dataset
    incomplete = [line for line in lines if line.startswith("incomplete:")]
    assert len(incomplete) == 1 and "killed.mcap.partial" in incomplete[0], lines
    assert "never finished" in incomplete[0]
    succeeded = [e for e in recorded[1]["episodes"] if e["outcome"] == "SUCCEEDED"]
    assert info["total_episodes"] == len(succeeded) >= 2


def test_info_json_follows_v3(dataset):
    out, info, _ = dataset
    assert json.loads((out / "meta" / "info.json").read_text()) == info
    assert info["codebase_version"] == "v3.0" and info["fps"] == FPS
    assert info["robot_type"] == "puma560" and info["total_tasks"] == 1
    assert info["splits"] == {"train": f"0:{info['total_episodes']}"}
    assert info["data_path"] == "data/chunk-{chunk_index:03d}/file-{file_index:03d}.parquet"
    assert info["video_path"] == \
        "videos/{video_key}/chunk-{chunk_index:03d}/file-{file_index:03d}.mp4"
    assert (info["chunks_size"], info["data_files_size_in_mb"],
            info["video_files_size_in_mb"]) == (1000, 100, 200)
    features = info["features"]
    assert features["observation.state"] == {"dtype": "float32", "shape": [19],
                                             "names": state_names(6)}
    assert features["action"] == {"dtype": "float32", "shape": [6],
                                  "names": list(ACTION_NAMES)}
    for eye in ("left", "right"):
        video = features[f"observation.images.{eye}"]
        assert video["dtype"] == "video" and video["shape"] == [240, 320, 3]
        assert video["names"] == ["height", "width", "channels"]
        assert video["info"]["video.codec"] == "h264" and video["info"]["video.fps"] == FPS
        assert video["info"]["video.pix_fmt"] == "yuv420p"
    for name in ("frame_index", "episode_index", "index", "task_index"):
        assert features[name] == {"dtype": "int64", "shape": [1], "names": None}
    assert features["timestamp"] == {"dtype": "float32", "shape": [1], "names": None}


def test_the_data_and_the_episodes_line_up(dataset):
    out, info, _ = dataset
    data = pq.read_table(out / "data" / "chunk-000" / "file-000.parquet")
    assert data.schema.field("observation.state").type == pa.list_(pa.float32(), 19)
    assert data.schema.field("action").type == pa.list_(pa.float32(), 6)
    assert data.schema.field("timestamp").type == pa.float32()
    for name in ("frame_index", "episode_index", "index", "task_index"):
        assert data.schema.field(name).type == pa.int64()
    assert data.num_rows == info["total_frames"]
    assert data.column("index").to_pylist() == list(range(data.num_rows))
    episodes = pq.read_table(out / "meta" / "episodes" / "chunk-000" / "file-000.parquet")
    assert episodes.column("episode_index").to_pylist() == list(range(info["total_episodes"]))
    frame_index = np.array(data.column("frame_index"))
    episode_index = np.array(data.column("episode_index"))
    timestamps = np.array(data.column("timestamp"))
    start = 0
    for row in episodes.to_pylist():
        length = row["length"]
        assert (row["dataset_from_index"], row["dataset_to_index"]) == (start, start + length)
        assert row["tasks"] == [TASK] and (row["data/chunk_index"], row["data/file_index"]) \
            == (0, 0)
        assert (episode_index[start:start + length] == row["episode_index"]).all()
        assert (frame_index[start:start + length] == np.arange(length)).all()
        np.testing.assert_allclose(timestamps[start:start + length], np.arange(length) / FPS,
                                   atol=1e-6)
        for eye in ("left", "right"):
            key = f"videos/observation.images.{eye}"
            assert row[f"{key}/from_timestamp"] == pytest.approx(start / FPS)
            assert row[f"{key}/to_timestamp"] == pytest.approx((start + length) / FPS)
        start += length
    tasks = pd.read_parquet(out / "meta" / "tasks.parquet")
    assert tasks.index.name == "task" and list(tasks.index) == [TASK]
    assert tasks["task_index"].tolist() == [0]


def test_each_video_has_every_frame_at_its_timestamp(dataset):
    out, info, _ = dataset
    for eye in ("left", "right"):
        with av.open(str(out / "videos" / f"observation.images.{eye}" / "chunk-000" /
                          "file-000.mp4")) as container:
            stream = container.streams.video[0]
            assert stream.codec_context.name == "h264" and (stream.width, stream.height) == \
                (320, 240)
            times = [float(frame.pts * frame.time_base) for frame in container.decode(stream)]
        # frame i at i/fps (lerobot looks frames up within 1e-4 s): as many as the data rows
        assert len(times) == info["total_frames"]
        np.testing.assert_allclose(times, np.arange(len(times)) * float(Fraction(1, FPS)),
                                   atol=1e-4)


def test_the_stats_match_the_data(dataset):
    out, _, _ = dataset
    stats = json.loads((out / "meta" / "stats.json").read_text())
    data = pq.read_table(out / "data" / "chunk-000" / "file-000.parquet")
    for feature in ("observation.state", "action"):
        values = np.array(data.column(feature).to_pylist(), dtype=np.float64)
        np.testing.assert_allclose(stats[feature]["min"], values.min(0), atol=1e-6)
        np.testing.assert_allclose(stats[feature]["max"], values.max(0), atol=1e-6)
        np.testing.assert_allclose(stats[feature]["mean"], values.mean(0), atol=1e-6)
        np.testing.assert_allclose(stats[feature]["std"], values.std(0), atol=1e-5)
        assert stats[feature]["count"] == [len(values)]
        for quantile in ("q01", "q10", "q50", "q90", "q99"):
            assert len(stats[feature][quantile]) == values.shape[1]
    for eye in ("left", "right"):
        image = stats[f"observation.images.{eye}"]
        assert np.array(image["mean"]).shape == (3, 1, 1)
        assert 0 <= np.min(image["min"]) < np.min(image["mean"]) \
            <= np.max(image["mean"]) < np.max(image["max"]) <= 1  # fractions of 255


def test_the_actions_add_up_to_the_tool_path(dataset):
    """The actions (increments the station applied, per frame) follow the measured tool."""
    out, _, _ = dataset
    data = pq.read_table(out / "data" / "chunk-000" / "file-000.parquet")
    state = np.array(data.column("observation.state").to_pylist())
    action = np.array(data.column("action").to_pylist())
    episode = np.array(data.column("episode_index"))
    tool = slice(6, 9)
    for number in np.unique(episode):
        rows = np.flatnonzero(episode == number)
        moved = state[rows[-1], tool] - state[rows[0], tool]
        commanded = action[rows[:-1], :3].sum(0)
        # the task presses into the hole's floor: the arm stops short of a few commands
        assert np.linalg.norm(moved - commanded) < 0.01, (moved, commanded)


def test_episode_0_replays_to_where_the_recording_had_the_tool(recorded):
    replayed = recorded[2]
    assert replayed["frames"] > 100, replayed
    # The replay goes where the actions lead; the rest of the final error is the recording's
    # own motion that the actions do not hold.
    assert replayed["actions_error_mm"] <= 1.0, replayed
    assert replayed["final_error_mm"] <= 2.0, replayed


def test_appended_episodes_join_the_dataset_in_files_of_their_own(dataset, recorded,
                                                                   tmp_path):
    """The export of all episodes at once, and the first one exported then the rest appended,
    hold the same rows; the appended frames are in their own mp4s, from their own t = 0."""
    whole, info, _ = dataset
    recordings, summary, _ = recorded
    files = [recordings / f"{e['name']}.mcap" for e in summary["episodes"]
             if e["outcome"] == "SUCCEEDED"]
    grown = tmp_path / "grown"
    export(files[:1], grown, FPS, report=lambda line: None)
    assert export(files[1:], grown, FPS, append=True, report=lambda line: None) == info
    data = [pq.read_table(grown / "data" / "chunk-000" / f"file-00{i}.parquet")
            for i in (0, 1)]
    assert pa.concat_tables(data).equals(
        pq.read_table(whole / "data" / "chunk-000" / "file-000.parquet"))
    episodes = pd.read_parquet(grown / "meta" / "episodes" / "chunk-000" / "file-001.parquet")
    first_appended = data[0].num_rows
    assert episodes["dataset_from_index"].iloc[0] == first_appended
    for eye in ("left", "right"):
        key = f"videos/observation.images.{eye}"
        assert episodes[f"{key}/file_index"].tolist() == [1] * len(episodes)
        assert episodes[f"{key}/from_timestamp"].iloc[0] == 0.0
        with av.open(str(grown / key / "chunk-000" / "file-001.mp4")) as container:
            frames = sum(1 for _ in container.decode(video=0))
        assert frames == data[1].num_rows == episodes["length"].sum()
