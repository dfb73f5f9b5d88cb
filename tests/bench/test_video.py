"""bench.video without a station: the cells a run makes, the link each sets, the goals judged
on made-up figures, the tables, the fragment and the figure, and latest.json's merge (no
timing)."""

from __future__ import annotations

import json

import pytest

from bench import readme, report, video
from bench.plan import DEFAULT_GROUPS, GROUPS, Plan
from bench.run import report_text

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def _probe(fps=29.5, p50=40.0, p95=60.0, thirds=(60.0, 58.0, 61.0), kbit=900.0, codec="h264",
           target=1200):
    return {"fps": fps, "age_ms_p50": p50, "age_ms_p95": p95,
            "age_ms_p95_thirds": list(thirds), "kbit_per_s": kbit, "codec": codec,
            "target_kbit_per_s": target if codec == "h264" else 0, "frames": 300,
            "receipts": codec == "h264",
            "cpu": {"machine_busy_pct": 95.0, "window_s": 12.0,
                    "cpu_pct": {"stereo_camera": 70.0, "world": 33.0, "probe": 12.0}}}


def _record(trip, cap, h264=None, jpeg=None, long=False, seconds=10.0, load=1.5,
            console=False):
    cell = video.Cell(trip, cap, seconds, long, console)
    h264 = h264 if h264 is not None else _probe(p50=trip / 2 + 30, p95=trip / 2 + 50)
    record = {"name": cell.name, "round_trip_ms": trip, "one_way_delay_ms": cell.one_way_ms,
              "bottleneck_mbit": cap, "seconds": seconds, "skip_s": video.SKIP_S,
              "long": long, "console": console, "age_bound_ms": cell.age_bound_ms,
              cell.codecs[0]: h264, "load_avg_at_start": load}
    if console:
        h264.update(decoder="webcodecs", codec="h264 (avc1.42C01F)")
    elif not long:
        record["jpeg"] = jpeg if jpeg is not None else _probe(
            fps=12.0, p50=trip / 2 + 200, p95=trip / 2 + 400, kbit=6000.0, codec="jpeg")
        record["vs_jpeg"] = video.ratios(record["h264"], record["jpeg"])
    record["misses"] = video.judge(h264, cell)
    record["pass"] = not record["misses"]
    return record


RESULT = {
    "cells": [_record(0.0, None), _record(0.0, 2.0),
              _record(183.0, None),
              _record(183.0, 2.0, h264=_probe(fps=18.0, p50=150.0, p95=260.0,
                                              thirds=(200.0, 240.0, 300.0)))],
    "long": _record(183.0, 2.0, long=True, seconds=60.0, load=4.25),
    "console": [_record(183.0, 2.0, h264=_probe(fps=26.0, p50=140.0, p95=160.0,
                                                thirds=(150.0, 160.0, 158.0)), console=True)],
    "round_trips_ms": [0.0, 183.0], "bottlenecks_mbit": [None, 2.0],
    "camera": {"source": "sim", "width_px": 640, "height_px": 480, "fps": 30.0},
    "goals": {"min_fps": 25.0, "age_slack_ms": 80.0, "backlog_ms": 20.0},
    "skip_s": 2.0, "campus_rtt_ms": 183.0, "passed": 4, "judged": 5, "elapsed_s": 400.0,
    "rate_hz": None, "delivered_hz": None, "p50_ms": None, "p99_ms": None,
    "run": {"time": "2026-11-27T12:00:00+0000", "quick": False, "run_s": 410.0,
            "machine": {"cores": 2, "cpu_model": "AMD EPYC", "python": "3.11.7",
                        "load_avg_at_start": [0.5, 1, 1], "load_avg_at_end": [2.0, 1, 1]}},
}


# -- the cells and the link ---------------------------------------------------------------------

def test_a_full_run_has_every_round_trip_through_every_bottleneck_then_the_long_run():
    cells = video.cells(quick=False)
    grid = [cell for cell in cells if not cell.long and not cell.console]
    assert {(c.round_trip_ms, c.bottleneck_mbit) for c in grid} == {
        (trip, cap) for trip in (0, 50, 183, 400) for cap in (None, 8, 4, 2)}
    assert len(grid) == 16 and all(c.seconds == 10.0 for c in grid)
    (long,) = [cell for cell in cells if cell.long]
    assert long == video.Cell(183.0, 2.0, 60.0, long=True) and cells.index(long) == 16
    assert long.codecs == ("h264",) and grid[0].codecs == ("h264", "jpeg")
    # Then the console's page in Chromium, on the campus route, open and through 2 Mbit/s.
    consoles = cells[17:]
    assert [(c.round_trip_ms, c.bottleneck_mbit) for c in consoles] == [(183.0, None),
                                                                       (183.0, 2.0)]
    assert all(c.console and c.codecs == ("console",) and c.seconds == 10.0 for c in consoles)
    assert len({c.name for c in cells}) == len(cells)
    assert grid[0].name == "0ms_open" and long.name == "183ms_2mbit_long"
    assert consoles[1].name == "183ms_2mbit_console"


def test_quick_runs_fewer_shorter_cells_and_the_lengths_can_be_set():
    quick = video.cells(quick=True)
    assert len(quick) < len(video.cells(quick=False))
    assert all(c.seconds < 10.0 for c in quick if not c.long)
    (long,) = [c for c in quick if c.long]
    assert long.seconds < 60.0 and [c.name for c in quick if c.console] == [
        "183ms_2mbit_console"]
    chosen = video.cells(quick=False, seconds=3.0, long_seconds=7.0)
    assert {c.seconds for c in chosen if not c.long} == {3.0}
    assert [c.seconds for c in chosen if c.long] == [7.0]
    assert video.step_count(Plan(quick=False)) == 1 + 17 + 2


def test_the_link_puts_half_the_round_trip_each_way_and_the_bottleneck_both_ways():
    up, down = video.link_profiles(video.Cell(183.0, 2.0, 10.0))
    for profile in (up, down):
        assert profile.delay_s == pytest.approx(0.0915)
        assert profile.bandwidth_bps == 2e6 and profile.jitter_s == 0
    open_up, _ = video.link_profiles(video.Cell(50.0, None, 10.0))
    assert open_up.bandwidth_bps == 0 and open_up.delay_s == pytest.approx(0.025)


# -- the goals ----------------------------------------------------------------------------------

def test_an_h264_run_meeting_every_goal_passes():
    cell = video.Cell(400.0, 2.0, 10.0)
    assert cell.age_bound_ms == 280.0
    assert video.judge(_probe(fps=25.0, p95=280.0, thirds=(270.0, 250.0, 290.0)), cell) == []


def test_each_goal_missed_says_by_how_much():
    cell = video.Cell(183.0, 2.0, 10.0)
    misses = video.judge(_probe(fps=17.3, p95=260.0, thirds=(200.0, 240.0, 221.0)), cell)
    assert misses == ["17.3 fps < 25", "age p95 260 ms > 171.5",
                      "backlog: last third's p95 221 ms > first's 200 + 20"]
    # A backlog that shrinks is no backlog; one within 20 ms is noise.
    assert video.judge(_probe(thirds=(100.0, 40.0, 30.0), p95=100.0),
                       video.Cell(50.0, None, 10.0)) == []
    assert video.judge(_probe(thirds=(40.0, 50.0, 60.0)), video.Cell(0.0, None, 10.0)) == []


def test_a_failed_or_empty_probe_fails_its_cell():
    cell = video.Cell(0.0, None, 10.0)
    assert video.judge({"status": "failed", "reason": "video worker took too long"}, cell) == [
        "failed: video worker took too long"]
    assert video.judge(None, cell) == ["failed: no result"]
    empty = {"fps": 0.0, "age_ms_p50": None, "age_ms_p95": None, "age_ms_p95_thirds": []}
    assert video.judge(empty, cell) == ["0.0 fps < 25", "age p95 – ms > 80",
                                        "backlog: too few frames for thirds"]


def test_ratios_are_h264_over_jpeg():
    versus = video.ratios(_probe(fps=30.0, p95=60.0), _probe(fps=12.0, p95=240.0))
    assert versus == {"age_p95": 0.25, "fps": 2.5}
    assert video.ratios(_probe(), {"status": "failed"}) == {"age_p95": None, "fps": None}


# -- the tables, the fragment and the figure ----------------------------------------------------

def test_the_table_has_a_row_per_cell_and_the_long_run_with_the_jpeg_baseline_beside():
    rows = video.table_rows(RESULT)
    assert len(rows) == 6 and all(len(row) == len(video.HEADER) for row in rows)
    first = dict(zip(video.HEADER, rows[0], strict=True))
    assert first["round trip"] == "0 ms" and first["bottleneck"] == "none"
    assert first["H.264 fps"] == "29.5" and first["age p50 / p95 ms"] == "30 / 50"
    assert first["kbit/s (target)"] == "900 (1200)" and first["result"] == "PASS"
    assert first["JPEG fps"] == "12.0" and first["JPEG age p50 / p95 ms"] == "200 / 400"
    assert first["H.264 / JPEG"] == "age p95 ×0.12, fps ×2.46"
    missed = dict(zip(video.HEADER, rows[3], strict=True))
    assert missed["result"].startswith("FAIL: 18.0 fps < 25; age p95 260 ms > 171.5")
    assert missed["p95 by thirds ms"] == "200 → 240 → 300"
    long = dict(zip(video.HEADER, rows[4], strict=True))
    assert long["bottleneck"] == "2 Mbit/s, 60 s" and long["JPEG fps"] == "–"
    page = dict(zip(video.HEADER, rows[5], strict=True))
    assert page["bottleneck"] == "2 Mbit/s, the console in Chromium"
    assert page["H.264 fps"] == "26.0" and page["age p50 / p95 ms"] == "140 / 160"
    assert page["result"] == "PASS" and page["JPEG fps"] == "–"


def test_the_terminal_lines_and_the_bench_report_show_the_cells_and_the_cpu():
    lines = video.terminal_lines(RESULT)
    assert "4 of 5 H.264 runs passed" in lines[0]
    assert len([line for line in lines if line.startswith("    ")]) == 1 + 6 + 6
    assert any("183ms_2mbit_long: machine 95 %; stereo_camera 70, world 33, probe 12" in line
               for line in lines)
    text = report_text({"video": {**RESULT, "goal": "no goal", "pass": None}})
    assert "video: the stereo stream across the impairment link" in text


def test_the_fragment_has_the_run_the_table_the_misses_and_the_long_run():
    text = video.markdown(RESULT, "bench/results/latest.json")
    table = [line for line in text.splitlines() if line.startswith("| ")]
    assert table[0] == "| " + " | ".join(video.HEADER) + " |" and len(table) == 1 + 6
    assert "from `bench/results/latest.json`" in text and "load average 0.5 → 2.0" in text
    assert ("H.264 met every goal in 3 of 4 cells (missed in 183ms_2mbit); ≥ 25 fps in 3, the "
            "age's p95 bound in 3, no growing backlog in 3.") in text
    assert ("the machine was 95 % busy (both cores); share of one core: stereo_camera 70 %, "
            "world 33 %, probe 12 %; the camera's CPU per frame shown 24–39 ms") in text
    assert "Long run, 183 ms / 2 Mbit/s, 60 s: 29.5 fps" in text
    assert ": PASS (no growing backlog: the last third within 20 ms of the first)." in text
    assert "640×480 per eye" in text and "load average at the cells' starts 1.5–4.2" in text
    assert ("The console's page in headless Chromium (webcodecs, h264 (avc1.42C01F)), the link "
            "in front of the console, 183 ms / 2 Mbit/s: 26.0 fps, age p50 / p95 140 / 160 ms, "
            "p95 by thirds 150 → 160 → 158 ms: PASS.") in text


def test_goal_counts_count_each_goal_met_and_a_failed_probe_meets_none():
    records = [_record(0.0, None), _record(400.0, 2.0, h264={"status": "failed", "reason": "x"}),
               _record(50.0, 2.0, h264=_probe(fps=20.0, p95=70.0))]
    assert video.goal_counts(records) == (
        "H.264 met every goal in 1 of 3 cells (missed in 400ms_2mbit, 50ms_2mbit); ≥ 25 fps "
        "in 1, the age's p95 bound in 2, no growing backlog in 2.")
    assert "missed in" not in video.goal_counts(records[1:])  # all missed: no list


def test_a_failed_probe_shows_as_failed_in_the_table():
    record = _record(50.0, 4.0, h264={"status": "failed", "reason": "took too long"},
                     jpeg={"status": "failed", "reason": "x"})
    row = video.table_rows({"cells": [record]})[0]
    assert row[2] == "failed" and row[8] == "FAIL: failed: took too long" and row[9] == "failed"
    assert "failed" in video.cell_text(record)


def test_plot_writes_a_png_even_with_a_failed_probe(tmp_path):
    failed = _record(400.0, 2.0, h264={"status": "failed", "reason": "x"})
    path = video.plot({**RESULT, "cells": [*RESULT["cells"], failed]},
                      tmp_path / "sub" / "video.png")
    assert path.read_bytes().startswith(PNG_MAGIC)


# -- the plan, latest.json and bench.readme ----------------------------------------------------

def test_the_video_rows_run_with_the_network_group_or_alone_never_by_default():
    assert "video" in GROUPS and "video" not in DEFAULT_GROUPS
    assert not Plan(quick=False).wants("video")
    assert Plan(quick=False, only=("network",)).wants("video")
    alone = Plan(quick=False, only=("video",))
    assert alone.wants("video") and not alone.wants("network")


def _bench(tmp_path, only, results):
    from bench.run import Bench

    bench = Bench.__new__(Bench)  # no station: only what write() reads
    bench.plan, bench.out_dir, bench.shm = Plan(quick=True, only=only), tmp_path, "shm"
    bench.results, bench.raw, bench.elapsed_s, bench.load_at_start = results, {}, 1.0, [1, 1, 1]
    return bench


def test_a_video_run_alone_merges_its_row_and_a_run_without_it_keeps_it(tmp_path):
    latest = tmp_path / "latest.json"
    latest.write_text(json.dumps({"time": "full run", "closed_loop": {"p50_ms": 3.0},
                                  "network": {"rows": [], "run": {"time": "before"}}}))
    row = json.loads(json.dumps(RESULT))
    row.pop("run")
    _bench(tmp_path, ("video",), {"video": row, "world_loop": {"steps": 9}}).write()
    document = json.loads(latest.read_text())
    assert document["time"] == "full run" and document["closed_loop"] == {"p50_ms": 3.0}
    assert document["network"]["run"]["time"] == "before"
    assert document["video"]["run"]["world_loop"]["steps"] == 9
    assert "world_loop" not in document
    assert (tmp_path / video.PLOT_FILE).read_bytes().startswith(PNG_MAGIC)
    _bench(tmp_path, ("closed_loop",), {"closed_loop": {"p50_ms": 4.0}}).write()
    document = json.loads(latest.read_text())
    assert document["closed_loop"]["p50_ms"] == 4.0 and document["video"]["judged"] == 5
    assert report.previous_row(latest, video.NAME)["passed"] == 4


def test_readme_writes_the_fragment_and_the_figure_and_leaves_readme_alone(tmp_path):
    results = tmp_path / "latest.json"
    results.write_text(json.dumps({"time": "x", "video": RESULT,
                                   "world_loop": {"steps": 1, "overruns": 0}}))
    target = tmp_path / "README.md"
    target.write_text(f"{readme.BEGIN}\nold table\n{readme.END}\n")
    fragment, figure = tmp_path / "docs" / "video.md", tmp_path / "docs" / "video.png"
    assert readme.main(["--results", str(results), "--readme", str(target),
                        "--video-table", str(fragment), "--video-plot", str(figure)]) == 0
    assert target.read_text() == f"{readme.BEGIN}\nold table\n{readme.END}\n"
    assert fragment.read_text() == video.markdown(RESULT, str(results))
    assert figure.read_bytes().startswith(PNG_MAGIC)
    assert not readme.has_table({"video": RESULT, "world_loop": {}})
    assert "video" not in readme.table({"video": RESULT, "teleop_50": {"p50_ms": 1.0}})


def test_the_camera_cpu_per_frame_is_its_share_of_a_core_over_the_frame_rate():
    assert video.camera_ms_per_frame(_probe(fps=25.0)) == 28.0  # 70 % of a core / 25 fps
    assert video.camera_ms_per_frame({"status": "failed"}) is None
    assert video.camera_ms_per_frame({**_probe(), "fps": 0.0}) is None
    assert "camera 23.7 ms CPU/frame" in video.cpu_text(_probe())
