"""The export's bad input, on episodes the DecisionServer's own recording store writes (a fake
clock and an arm that moves 1 mm a sample; no station, no video): a run without video exports
without images and says so; an unfinished or cut file is named incomplete; a recording that is
no episode is skipped; an existing output, or nothing to export, is refused; the arm's name
comes from the episodes; --append numbers new episodes on and leaves a dataset it cannot
extend as it was. And, on an episode made here, the first action of an arm that lags its
commands."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import numpy as np
import pandas as pd
import pinocchio as pin
import pyarrow.parquet as pq
import pytest

from clients.teleop.episode_file import Episode
from clients.teleop.export_lerobot import export, main
from clients.teleop.lerobot_dataset import on_grid
from services.decision_server.recording_mcap import Sources
from services.decision_server.recording_writer import on_a_thread
from services.decision_server.recordings import RecordingStore
from services.decision_server.slave import SlaveState
from tests.conftest import wait_for
from tests.fakes.clock import FakeClock

SAMPLES = 40


def _record(directory: Path, name: str, task: str = "lift", outcome: str = "SUCCEEDED",
            finish: bool = True, arm: str = "puma560", rise_m: float = 0.001) -> Path:
    """An episode of SAMPLES samples 10 ms apart, the tool rising 1 mm each, with a matching
    increment; the store's file (its partial one if not `finish`)."""
    clock = FakeClock()
    store = RecordingStore(directory, clock, on_a_thread)
    z = [0.0]
    sampled: list[float] = []  # the heights the recording's writer has taken

    def state():
        height = z[0]  # read once: the test's thread raises it meanwhile
        sampled.append(height)
        return SlaveState(pin.SE3(np.eye(3), np.array([0.4, 0.0, height])), "READY",
                          clock.time_ns(), joint_positions_rad=(0.1, 0.2, height, 0.0, 0.0, 0.0))

    store.start(name, "MCAP", Sources(state=state, arm_name=arm), task)
    for _ in range(SAMPLES):
        z[0] += rise_m
        store.add("BASE", np.array([0.0, 0.0, rise_m]), np.eye(3), np.array([0.4, 0.0, z[0]]))
        clock.advance(0.01)
        height = z[0]
        if task:  # an episode samples every 10 ms (another recording every 50)
            wait_for(lambda height=height: sampled and sampled[-1] == height, timeout_s=5,
                     what="the sample taken")
    if finish:
        store.stop(outcome)
        return directory / f"{name}.mcap"
    return directory / f"{name}.mcap.partial"


def test_an_episode_without_video_exports_without_images_and_says_so(tmp_path):
    _record(tmp_path / "runs", "ep0")
    lines: list[str] = []
    info = export([tmp_path / "runs"], tmp_path / "out", fps=50, report=lines.append)
    assert any("without images" in line for line in lines), lines
    assert info["video_path"] is None
    assert not any(key.startswith("observation.images") for key in info["features"])
    assert info["total_episodes"] == 1 and info["total_frames"] >= SAMPLES // 2
    assert not (tmp_path / "out" / "videos").exists()


def test_unfinished_cut_and_foreign_files_are_named_and_the_rest_exports(tmp_path):
    runs = tmp_path / "runs"
    _record(runs, "a-whole")
    cut = _record(runs, "b-cut")
    cut.write_bytes(cut.read_bytes()[: cut.stat().st_size // 2])
    _record(runs, "c-no-task", task="")
    _record(runs, "d-discarded", outcome="DISCARDED")
    _record(runs, "e-failed", outcome="FAILED")
    unfinished = _record(runs, "f-killed", finish=False)
    lines: list[str] = []
    info = export([runs], tmp_path / "out", report=lines.append)
    assert info["total_episodes"] == 1, lines  # a-whole
    said = "\n".join(lines)
    assert f"incomplete: {unfinished}" in said and "never finished" in said
    assert "incomplete: " + str(runs / "b-cut.mcap") in said
    assert "c-no-task.mcap: a recording without a task" in said
    assert "d-discarded.mcap ('lift') is marked DISCARDED" in said
    assert "e-failed.mcap ('lift') is marked FAILED" in said
    info = export([runs], tmp_path / "with-failed", include_failed=True, report=lambda _: None)
    assert info["total_episodes"] == 2


def test_an_existing_output_or_nothing_to_export_ends_with_status_2(tmp_path, capsys):
    runs = tmp_path / "runs"
    _record(runs, "ep0", outcome="DISCARDED")
    assert main([str(runs), "--out", str(tmp_path / "out")]) == 2
    assert "no episode to export" in capsys.readouterr().err
    (tmp_path / "exists").mkdir()
    assert main([str(runs), "--out", str(tmp_path / "exists")]) == 2
    assert "exists" in capsys.readouterr().err
    assert main([str(tmp_path / "missing"), "--out", str(tmp_path / "o")]) == 2
    assert "no such file" in capsys.readouterr().err


def test_the_actions_and_the_state_of_a_known_motion(tmp_path):
    """1 mm up every 10 ms: at 50 fps, each frame's action is 2 mm up and the state's z climbs
    2 mm a frame."""
    _record(tmp_path / "runs", "ep0")
    export([tmp_path / "runs"], tmp_path / "out", fps=50, report=lambda _: None)
    data = pq.read_table(tmp_path / "out" / "data" / "chunk-000" / "file-000.parquet")
    action = np.array(data.column("action").to_pylist())
    state = np.array(data.column("observation.state").to_pylist())
    np.testing.assert_allclose(action[:-1, 2], 0.002, atol=1e-6)
    np.testing.assert_allclose(action[:, [0, 1, 3, 4, 5]], 0.0, atol=1e-6)
    np.testing.assert_allclose(np.diff(state[:, 8]), 0.002, atol=1e-5)  # tool_z_m
    np.testing.assert_allclose(state[:, 2], state[:, 8], atol=1e-6)  # joint_3 follows it here
    info = json.loads((tmp_path / "out" / "meta" / "info.json").read_text())
    assert info["fps"] == 50
    shutil.rmtree(tmp_path / "out")


def test_the_first_action_carries_what_the_arm_had_still_to_make_of_earlier_commands():
    """An arm that lags its commands by 30 ms, and five 1 mm commands before the first frame
    (which waits for the first picture): the first action takes on the motion they had not yet
    made, so the actions lead from the first frame's state to where the commands did."""
    ms = 1_000_000
    state_ns = np.arange(0, 400 * ms, 10 * ms)
    increment_ns = np.arange(0, 300 * ms, 10 * ms)  # 1 mm up each, the first five before 50 ms
    targets = 0.001 * np.arange(1, len(increment_ns) + 1)
    heights = np.interp(state_ns - 30 * ms, increment_ns, targets, left=0.0)  # 30 ms behind
    count = len(state_ns)
    episode = Episode(
        Path("lagging.mcap"), "lagging", "lift", "SUCCEEDED", state_ns,
        np.zeros((count, 6)), np.column_stack([np.full(count, 0.4), np.zeros(count), heights]),
        np.repeat(np.eye(3)[None], count, 0), np.zeros(0, np.int64), np.zeros((0, 6)),
        increment_ns, ["BASE"] * len(increment_ns),
        np.tile([0.0, 0.0, 0.001], (len(increment_ns), 1)),
        np.repeat(np.eye(3)[None], len(increment_ns), 0),
        np.column_stack([np.full(len(targets), 0.4), np.zeros(len(targets)), targets]),
        video_ns=np.array([50 * ms, 390 * ms]), video_frames=[b"", b""], eye_size=(8, 8))
    frames = on_grid(episode, fps=50)
    assert frames.times_ns[0] == 50 * ms
    first_height = frames.state[0, 8]  # tool_z_m at 50 ms: 3 of the 5 mm commanded by then
    assert first_height == pytest.approx(0.003, abs=1e-6)
    # the 2 mm still to come, and the frame's own two commands (at 50 and 60 ms)
    assert frames.action[0, 2] == pytest.approx(0.002 + 0.002, abs=1e-6)
    np.testing.assert_allclose(first_height + frames.action[:-1, 2].sum(), targets[-1],
                               atol=1e-6)


def test_an_export_that_fails_leaves_no_half_dataset(tmp_path, monkeypatch):
    from clients.teleop import export_lerobot

    _record(tmp_path / "runs", "ep0")

    def fail(out, *args):
        (out / "meta").mkdir(parents=True)  # some of it written, then the disk fills
        raise OSError("No space left on device")

    monkeypatch.setattr(export_lerobot, "write_dataset", fail)
    with pytest.raises(OSError, match="No space left"):
        export([tmp_path / "runs"], tmp_path / "out", report=lambda _: None)
    assert not (tmp_path / "out").exists() and not (tmp_path / "out.partial").exists()


def test_the_robot_type_is_the_arm_the_episodes_name(tmp_path, capsys):
    _record(tmp_path / "fr3", "ep0", arm="fr3")
    info = export([tmp_path / "fr3"], tmp_path / "out", report=lambda _: None)
    assert info["robot_type"] == "fr3"
    _record(tmp_path / "fr3", "ep1", arm="puma560")
    with pytest.raises(ValueError, match="different arms.*ep0.mcap: fr3, ep1.mcap: puma560"):
        export([tmp_path / "fr3"], tmp_path / "mixed", report=lambda _: None)
    _record(tmp_path / "unnamed", "ep0", arm="")
    assert main([str(tmp_path / "unnamed"), "--out", str(tmp_path / "o")]) == 2
    assert "do not name their arm: give --robot-type" in capsys.readouterr().err
    assert main([str(tmp_path / "unnamed"), "--out", str(tmp_path / "o"),
                 "--robot-type", "my_arm"]) == 0
    assert json.loads((tmp_path / "o" / "meta" / "info.json").read_text())["robot_type"] == \
        "my_arm"


def _dataset(root: Path) -> dict:
    """Everything a reader sees of a dataset, its files concatenated in name order."""
    def tables(kind: str) -> pd.DataFrame:
        return pd.concat([pd.read_parquet(path) for path in
                          sorted((root / kind).glob("chunk-*/file-*.parquet"))],
                         ignore_index=True)

    return {"info": json.loads((root / "meta" / "info.json").read_text()),
            "stats": json.loads((root / "meta" / "stats.json").read_text()),
            "tasks": pd.read_parquet(root / "meta" / "tasks.parquet"),
            "data": tables("data"), "episodes": tables("meta/episodes")}


def test_append_numbers_the_new_episodes_on_as_one_export_would(tmp_path):
    runs = tmp_path / "runs"
    for name, task, rise in (("a", "lift", 0.001), ("b", "lift", 0.002), ("c", "lower", -0.001)):
        _record(runs, name, task=task, rise_m=rise)
    files = sorted(runs.iterdir())
    export(files, tmp_path / "whole", report=lambda _: None)
    export(files[:1], tmp_path / "grown", report=lambda _: None)
    lines: list[str] = []
    info = export(files[1:], tmp_path / "grown", append=True, report=lines.append)
    assert "3 episodes (2 appended)" in lines[-1]
    assert any(line.startswith("episode 1: b.mcap, 'lift'") for line in lines), lines
    whole, grown = _dataset(tmp_path / "whole"), _dataset(tmp_path / "grown")
    assert grown["info"] == whole["info"] == info
    assert (grown["tasks"].index.tolist(), grown["tasks"]["task_index"].tolist()) == \
        (["lift", "lower"], [0, 1])
    pd.testing.assert_frame_equal(grown["data"], whole["data"])
    assert sorted(p.name for p in (tmp_path / "grown" / "data" / "chunk-000").iterdir()) == \
        ["file-000.parquet", "file-001.parquet"]
    assert grown["episodes"]["data/file_index"].tolist() == [0, 1, 1]
    assert grown["episodes"]["meta/episodes/file_index"].tolist() == [0, 1, 1]
    same = [c for c in whole["episodes"].columns if "file_index" not in c and
            not c.startswith("stats/")]
    pd.testing.assert_frame_equal(grown["episodes"][same], whole["episodes"][same])
    for feature, stats in whole["stats"].items():
        for stat in ("min", "max", "mean", "std", "count"):  # exact; quantiles are estimates
            np.testing.assert_allclose(grown["stats"][feature][stat], stats[stat], atol=1e-9,
                                       err_msg=f"{feature} {stat}")
    assert not list(tmp_path.glob("grown.*"))  # no partial or replaced copy left


def test_an_append_that_does_not_fit_leaves_the_dataset_as_it_was(tmp_path, capsys):
    _record(tmp_path / "runs", "a")
    _record(tmp_path / "fr3", "b", arm="fr3")
    export([tmp_path / "runs"], tmp_path / "out", fps=50, report=lambda _: None)
    before = {p: p.read_bytes() for p in (tmp_path / "out").rglob("*") if p.is_file()}
    assert main([str(tmp_path / "fr3"), "--out", str(tmp_path / "out"), "--append",
                 "--fps", "30"]) == 2
    error = capsys.readouterr().err
    assert "do not fit" in error and "fps 30 (the dataset's: 50)" in error
    assert "robot_type 'fr3' (the dataset's: 'puma560')" in error
    assert main([str(tmp_path / "runs"), "--out", str(tmp_path / "nothing-here.json"),
                 "--append"]) == 0  # an append to nothing starts the dataset
    (tmp_path / "not-a-dataset").mkdir()
    assert main([str(tmp_path / "runs"), "--out", str(tmp_path / "not-a-dataset"),
                 "--append"]) == 2
    assert "not a LeRobot dataset to append to" in capsys.readouterr().err
    after = {p: p.read_bytes() for p in (tmp_path / "out").rglob("*") if p.is_file()}
    assert after == before and not list(tmp_path.glob("out.*"))


def test_an_append_skips_the_episode_files_the_dataset_holds(tmp_path, capsys):
    """Appending the recordings directory again adds only what was recorded since; a file
    given twice is exported once; an append with nothing new ends with status 2."""
    runs = tmp_path / "runs"
    _record(runs, "a")
    export([runs], tmp_path / "out", report=lambda _: None)
    _record(runs, "b", rise_m=0.002)
    lines: list[str] = []
    info = export([runs, runs / "b.mcap"], tmp_path / "out", append=True, report=lines.append)
    assert "skipped: a.mcap is already in the dataset, as episode 0" in lines
    assert "skipped: b.mcap is the same file as b.mcap" in lines
    assert info["total_episodes"] == 2
    sources = json.loads((tmp_path / "out" / "meta" / "telerobot_sources.json").read_text())
    assert [(s["episode_index"], s["file"]) for s in sources["episodes"]] == [
        (0, "a.mcap"), (1, "b.mcap")]
    before = {p: p.read_bytes() for p in (tmp_path / "out").rglob("*") if p.is_file()}
    assert main([str(runs), "--out", str(tmp_path / "out"), "--append"]) == 2
    assert "no new episode to export" in capsys.readouterr().err
    assert {p: p.read_bytes() for p in (tmp_path / "out").rglob("*") if p.is_file()} == before
