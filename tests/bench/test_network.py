"""bench.network without a station: the link each row sets, the rows a run makes, what a
failed run reports, latest.json's merge, the README block and the figure (no timing)."""

from __future__ import annotations

import json
import zlib
from types import SimpleNamespace

import pytest

from bench import network, readme, report

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def _row(mode, trip, success=True, peak=100.0, cut_s=0.0, error=None, connections=1,
         passivity=True, drift=0.001, swings=0):
    spec = network.RowSpec(mode, trip, cut_s, passivity)
    return {"name": spec.name, "mode": mode, "passivity": passivity, "round_trip_ms": trip,
            "seed": spec.seed, "drift_m": drift, "transparency_rms_n": 20.0,
            "oscillation_swings": swings,
            "energy": {"slave_dissipated_j": 0.5, "master_dissipated_j": 0.25}
            if mode == "feedback" and passivity else None,
            "cut_s": cut_s, "cut": {"at_s": network.CUT_AT_S, "mode": network.CUT_MODE,
                                    "happened": True} if cut_s else None,
            "success": success, "error": error, "duration_s": 12.5, "depth_m": 0.039,
            "peak_force_n": peak, "final_force_n": 4.9, "round_trip_p50_ms": trip + 7.0,
            "round_trip_p99_ms": trip + 20.0, "commands": 400, "acks": 600,
            "proxy": {"connections": connections}}


RESULT = {
    "rows": [_row("feedback", 0.0, peak=200.0), _row("compliance", 0.0, peak=30.0),
             _row("feedback", 183.0, peak=480.0), _row("compliance", 183.0, peak=12.0),
             _row("feedback", 183.0, success=False, peak=50.0, cut_s=3.0, connections=3,
                  error="UnavailableError: UNAVAILABLE in /telerobot.v1.DecisionServer/"
                        "Teleoperate: Stream removed (ping timeout)"),
             ],
    "round_trips_ms": [0.0, 183.0], "jitter_fraction": 0.1, "campus_rtt_ms": 183.0,
    "cut": {"s": 3.0, "at_s": 5.0, "mode": "stall", "round_trip_ms": 183.0},
    "papers": network.PAPERS, "elapsed_s": 300.0, "succeeded": 4, "runs": 5,
    "run": {"time": "2026-11-23T18:00:00+0000", "quick": False, "run_s": 310.0,
            "machine": {"cores": 2, "cpu_model": "AMD EPYC", "python": "3.11.7",
                        "load_avg_at_start": [1.5, 1, 1], "load_avg_at_end": [2.5, 1, 1]}},
}


def test_link_profiles_put_half_the_round_trip_each_way_with_ten_percent_jitter():
    up, down = network.link_profiles(200.0, seed=7)
    for profile in (up, down):
        assert profile.delay_s == pytest.approx(0.100)
        assert profile.jitter_s == pytest.approx(0.010)
        assert profile.bandwidth_bps == 0 and profile.stall_probability == 0
    assert (up.seed, down.seed) == (7, 8)
    still, _ = network.link_profiles(0.0, seed=1)
    assert still.delay_s == 0 and still.jitter_s == 0


def test_a_full_run_has_every_round_trip_in_both_modes_the_campus_link_and_cuts():
    specs = network.row_specs(quick=False)
    plain = {(s.mode, s.round_trip_ms) for s in specs if not s.cut_s}
    assert plain == {(mode, trip) for mode in network.MODES
                     for trip in (0, 100, 183, 200, 400)}
    # Feedback twice at every round trip: with TDPA and without it, next to each other.
    without = [s for s in specs if not s.passivity]
    assert {(s.mode, s.round_trip_ms) for s in without} == {
        ("feedback", trip) for trip in (0, 100, 183, 200, 400)}
    assert all(specs[specs.index(s) - 1] == network.RowSpec("feedback", s.round_trip_ms)
               for s in without)
    cuts = [s for s in specs if s.cut_s]
    assert {s.mode for s in cuts} == set(network.MODES)
    assert all(s.cut_s == 3.0 and s.round_trip_ms == network.CAMPUS_RTT_MS for s in cuts)
    quick = network.row_specs(quick=True)
    assert len(quick) < len(specs) and {s.mode for s in quick} == set(network.MODES)


def test_each_row_has_its_own_seed_the_same_in_every_run():
    specs = network.row_specs(quick=False)
    assert len({s.seed for s in specs}) == len(specs)
    assert network.RowSpec("feedback", 100.0).seed == zlib.crc32(b"feedback_100ms")
    assert network.RowSpec("compliance", 183.0, 3.0).name == "compliance_183ms_cut"
    assert network.RowSpec("feedback", 400.0, passivity=False).name == \
        "feedback_nopassivity_400ms"


def test_a_run_ended_by_an_error_reports_its_trace_up_to_it_and_the_error():
    trace = SimpleNamespace(force_n=[[0, 0, -1.0], [0, 0, -7.5], [0, 0, -3.0]],
                            round_trip_ms=[10.0, 12.0, 200.0])
    peg = SimpleNamespace(mode="feedback", trace=trace, _commands=3, _acks=[1, 2, 3])
    out = network._partial(peg, 6.2, RuntimeError("stream removed"))
    assert out["success"] is False
    assert out["peak_force_n"] == 7.5 and out["final_force_n"] == 3.0
    assert out["round_trip_p50_ms"] == 12.0
    assert out["error"] == "RuntimeError: stream removed"
    empty = network._partial(SimpleNamespace(mode="compliance", trace=SimpleNamespace(
        force_n=[], round_trip_ms=[]), _commands=0, _acks=[]), 0.1, ValueError("x"))
    assert empty["peak_force_n"] is None and empty["round_trip_p99_ms"] is None


def test_merge_replaces_only_the_network_row(tmp_path):
    latest = tmp_path / "latest.json"
    assert not report.merge_row(latest, network.NAME, RESULT)  # nothing to merge into
    latest.write_text(json.dumps({"time": "earlier", "teleop_50": {"p50_ms": 1.0},
                                  "network": {"rows": [], "run": {"time": "old"}}}))
    assert report.merge_row(latest, network.NAME, RESULT)
    document = json.loads(latest.read_text())
    assert document["time"] == "earlier" and document["teleop_50"] == {"p50_ms": 1.0}
    assert document["network"]["run"]["time"] == RESULT["run"]["time"]
    assert report.previous_row(latest, network.NAME)["runs"] == 5
    latest.write_text(json.dumps({"network": {"status": "failed"}}))  # no run of its own
    assert report.previous_row(latest, network.NAME) is None


def test_the_terminal_table_has_a_line_per_run():
    lines = network.terminal_lines(RESULT)
    assert len(lines) == 2 + len(RESULT["rows"])  # title, header
    assert "183 ms (campus)" in lines[4] and "480.0" in lines[4]
    assert "NO" in lines[-1] and "3 connections" in lines[-1]


def test_readme_block_shows_every_run_the_figure_and_the_campus_comparison():
    document = {"time": "x", "network": RESULT}
    block = readme.network_block(document, "bench/results/latest.json", "docs/net.png")
    table = [line for line in block.splitlines() if line.startswith("| ")]
    assert table[0].startswith("| mode | round trip set | cut |")
    assert len(table) == 1 + len(RESULT["rows"])
    assert ("| feedback, TDPA | 183 ms (campus) | – | 190.0 / 203.0 | yes | 12.5 | 480.0 | 4.9 "
            "| 1.0 | 20.0 | 0 | 500 / 250 |") in block
    assert "- 183 ms: FAIL (peak 480.0 N > 300.0 N)" in block  # #15's verdict
    assert "3 s at 5 s (stall)" in table[-1] and "| NO |" in table[-1]
    assert "ping timeout" in table[-1]
    assert "![Peak force against the link's round trip, per mode](docs/net.png)" in block
    assert "480.0 N, with compliance at the server 12.0 N (40× less)" in block
    assert "load average 1.5 → 2.5" in block and "4 of 5 runs succeeded" in block


def test_readme_main_rewrites_the_network_block_and_draws_its_figure(tmp_path):
    results = tmp_path / "latest.json"
    results.write_text(json.dumps({"time": "x", "network": RESULT,
                                   "world_loop": {"steps": 1, "overruns": 0}}))
    text = (f"intro\n{readme.BEGIN}\nold table\n{readme.END}\n"
            f"{readme.NETWORK_BEGIN}\nold network\n{readme.NETWORK_END}\nend\n")
    target = tmp_path / "README.md"
    target.write_text(text)
    figure = tmp_path / "docs" / "net.png"
    assert readme.main(["--results", str(results), "--readme", str(target),
                        "--network-plot", str(figure)]) == 0
    written = target.read_text()
    assert "old table" in written  # no table scenarios: the Performance table stays
    assert "old network" not in written and "](docs/net.png)" in written
    assert figure.read_bytes().startswith(PNG_MAGIC)
    assert not readme.has_table({"network": RESULT, "world_loop": {}})


def test_plot_writes_a_png_even_with_failed_and_missing_runs(tmp_path):
    rows = [*RESULT["rows"], {**_row("compliance", 183.0, cut_s=3.0), "peak_force_n": None,
                              "success": False}]
    path = network.plot({**RESULT, "rows": rows}, tmp_path / "sub" / "peak.png")
    assert path.read_bytes().startswith(PNG_MAGIC)


def _bench(tmp_path, only, results):
    from bench.plan import Plan
    from bench.run import Bench

    bench = Bench.__new__(Bench)  # no station: only what write() reads
    bench.plan, bench.out_dir, bench.shm = Plan(quick=True, only=only), tmp_path, "shm"
    bench.results, bench.raw, bench.elapsed_s, bench.load_at_start = results, {}, 1.0, [1, 1, 1]
    return bench


def test_a_network_run_alone_merges_its_row_and_a_run_without_it_keeps_it(tmp_path):
    latest = tmp_path / "latest.json"
    latest.write_text(json.dumps({"time": "full run", "closed_loop": {"p50_ms": 3.0}}))
    row = json.loads(json.dumps(RESULT))
    row.pop("run")
    _bench(tmp_path, ("network",), {"network": row, "world_loop": {"steps": 9}}).write()
    document = json.loads(latest.read_text())
    assert document["time"] == "full run" and document["closed_loop"] == {"p50_ms": 3.0}
    assert document["network"]["run"]["world_loop"]["steps"] == 9
    assert "world_loop" not in document  # that run's loop stays with its row
    assert (tmp_path / network.PLOT_FILE).read_bytes().startswith(PNG_MAGIC)
    _bench(tmp_path, ("closed_loop",), {"closed_loop": {"p50_ms": 4.0}}).write()
    document = json.loads(latest.read_text())
    assert document["closed_loop"]["p50_ms"] == 4.0 and document["network"]["runs"] == 5


def test_the_campus_comparison_claims_no_ratio_when_a_run_failed():
    rows = [_row("feedback", 183.0, peak=480.0), _row("compliance", 183.0, success=False,
                                                       peak=1.0)]
    text = network.campus_comparison({**RESULT, "rows": rows})
    assert "×" not in text and "the compliance run failed" in text
    assert "No complete pair" in network.campus_comparison({**RESULT, "rows": rows[:1]})


def test_the_passivity_verdict_judges_the_tdpa_runs_against_their_loopback_peak():
    result = {"rows": [
        _row("feedback", 0.0, peak=120.0), _row("feedback", 0.0, peak=250.0, passivity=False),
        _row("feedback", 100.0, peak=170.0), _row("feedback", 100.0, peak=480.0, passivity=False),
        _row("feedback", 400.0, peak=190.0, drift=0.007, swings=5),
        _row("feedback", 400.0, peak=580.0, passivity=False),
        _row("compliance", 400.0, peak=12.0)]}
    lines = network.passivity_verdict(result)
    assert len(lines) == 3
    assert lines[0].startswith("0 ms: PASS") and lines[1].startswith("100 ms: PASS")
    assert "without passivity 480.0 N peak" in lines[1]
    assert lines[2].startswith("400 ms: FAIL")
    for miss in ("peak 190.0 N > 180.0 N", "5 swings", "drift 7.0 mm"):
        assert miss in lines[2]
    assert network.passivity_verdict({"rows": [result["rows"][1]]})[0].startswith("No feedback")


def test_tdpa_rows_are_made_of_five_runs_judged_on_the_median_peak():
    assert network.RowSpec("feedback", 100.0).repeats == network.TDPA_REPEATS == 5
    assert network.RowSpec("feedback", 100.0, passivity=False).repeats == 1
    assert network.RowSpec("feedback", 183.0, 3.0).repeats == 1  # a cut runs once
    assert network.RowSpec("compliance", 100.0).repeats == 1
    runs = [{"success": True, "peak_force_n": 240.0, "drift_m": 0.001},
            {"success": True, "peak_force_n": 130.0, "drift_m": 0.002},
            {"success": True, "peak_force_n": 180.0, "drift_m": 0.003}]
    middle = network.median_run(runs)
    assert middle["peak_force_n"] == 180.0 and middle["drift_m"] == 0.003  # one run's figures
    assert middle["peaks_n"] == [240.0, 130.0, 180.0] and middle["success"]
    failed = network.median_run([*runs[:2], {"success": False, "peak_force_n": None,
                                             "error": "UnavailableError: gone"}])
    assert failed["success"] is False and failed["error"] == "UnavailableError: gone"
    assert failed["peak_force_n"] == 130.0  # the median of the peaks there are
    assert network.median_run(runs[:1]) is runs[0]
