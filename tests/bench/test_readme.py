"""bench.readme: the Performance page's table from a small latest.json, and the rewrite
between the markers of docs/performance.md."""

from __future__ import annotations

import json

import pytest

from bench import goals, readme

SAMPLE = {
    "time": "2026-11-23T12:00:00+0000", "quick": True, "run_s": 150.0, "world_shm": "x",
    "machine": {"cores": 2, "cpu_model": "AMD EPYC", "python": "3.11.7",
                "load_avg_at_start": [0.5, 1, 1], "load_avg_at_end": [2.5, 1, 1]},
    "teleop_1000": {"rate_hz": 1000.0, "delivered_hz": 995.2, "p50_ms": 0.81, "p99_ms": 1.7},
    "teleop_1000_zmq": {"rate_hz": 1000.0, "delivered_hz": 999.0, "p50_ms": 0.5,
                        "p99_ms": 1.2},
    "command_1000": {"rate_hz": 1000.0, "delivered_hz": 995.0, "p50_ms": 1.0, "p99_ms": 2.0},
    "command_1000_zmq": {"rate_hz": 1000.0, "delivered_hz": 999.0, "p50_ms": 0.5,
                         "p99_ms": 1.5},
    "estop_idle": {"rate_hz": None, "delivered_hz": 3.0, "p50_ms": 2.0, "p99_ms": 6.2},
    "teleop_500": {"rate_hz": 500.0, "delivered_hz": 500.0, "p50_ms": 0.9, "p99_ms": 1.2},
    "stereo_sim_double": {"status": "failed", "reason": "no GL", "rate_hz": None,
                          "delivered_hz": None, "p50_ms": None, "p99_ms": None},
    "world_loop": {"rate_hz": 1000.0, "delivered_hz": 999.0, "steps": 150000,
                   "overruns": 30, "overrun_pct": 0.02, "dropped_steps": 0},
    "ratios": {},
}


def _rows(block: str) -> dict[str, list[str]]:
    rows = {}
    for line in block.splitlines():
        if line.startswith("| `"):
            cells = [cell.strip() for cell in line.strip("|").split("|")]
            rows[cells[0].strip("`")] = cells
    return rows


@pytest.fixture
def document() -> dict:
    document = json.loads(json.dumps(SAMPLE))
    goals.add_goals(readme.scenarios(document))  # as the bench stores them
    return document


def test_one_row_per_project_scenario_in_run_order_with_its_goal_and_verdict(document):
    rows = _rows(readme.table(document))
    assert list(rows) == ["teleop_1000", "command_1000", "estop_idle", "teleop_500",
                          "stereo_sim_double", "world_loop"]  # baselines are not rows
    name, what, delivered, p50, p99, goal, result, baselines = rows["teleop_1000"]
    assert (delivered, p50, p99) == ("995 Hz", "0.81", "1.70")
    assert goal == "≥ 990 Hz, p99 ≤ 2 ms, p99 ≤ 1.5 x teleop_1000_zmq" and result == "**PASS**"
    assert baselines == "zmq 999 Hz, 0.50 / 1.20"
    assert rows["command_1000"][6] == "**PASS**"  # 2.0 <= 1.5 x 1.5 (its zmq baseline)
    assert rows["estop_idle"][2] == "–"  # trials, not a stream
    assert rows["estop_idle"][6] == "**FAIL**: p99 6.2 ms > 5"
    assert rows["teleop_500"][5:7] == ["–", "no goal"]
    assert rows["stereo_sim_double"][6].startswith("**FAIL**")
    assert "failed" in rows["stereo_sim_double"][6]
    assert rows["world_loop"][2] == "30 overruns in 150000 steps (0.02 %)"
    assert rows["world_loop"][6] == "**PASS**"


def test_the_header_names_the_run_and_the_machine(document):
    header = readme.table(document).splitlines()[0]
    assert "quick run of 150.0 s" in header and "2 cores (AMD EPYC" in header


def test_a_document_without_stored_verdicts_is_judged_by_the_goals():
    rows = _rows(readme.table(json.loads(json.dumps(SAMPLE))))
    assert rows["teleop_1000"][6] == "**PASS**"
    assert rows["estop_idle"][6].startswith("**FAIL**")


def test_rewrite_replaces_only_what_lies_between_the_markers():
    text = f"# T\n\nbefore\n{readme.BEGIN}\nold table\n{readme.END}\nafter\n"
    new = readme.rewrite(text, "| new |")
    assert new == f"# T\n\nbefore\n{readme.BEGIN}\n| new |\n{readme.END}\nafter\n"
    assert readme.rewrite(new, "| new |") == new
    with pytest.raises(ValueError):
        readme.rewrite("no markers here", "| new |")


def test_an_observers_row_says_where_the_cpu_went_while_it_was_measured(document):
    document["observers_32"] = {
        "rate_hz": 1000.0, "delivered_hz": 773.0, "p50_ms": 15.5, "p99_ms": 92.7,
        "cpu": {"machine_busy_pct": 95.4, "window_s": 2.0,
                "cpu_pct": {"force_sensor": 59.8, "world": 34.3, "operator": 44.1,
                            "observers 1": 12.7, "observers 2": 11.8}}}
    baselines = _rows(readme.table(document))["observers_32"][7]
    assert baselines == ("while measured: the machine 95 % busy; force sensor 60 %, "
                         "operator 44 %, world 34 %, observers 24 % of a core")


def test_the_tables_go_to_the_performance_page_between_its_markers():
    assert readme.PAGE == readme.REPO / "docs" / "performance.md"
    text = readme.PAGE.read_text()
    for begin, end in ((readme.BEGIN, readme.END), (readme.SOAK_BEGIN, readme.SOAK_END),
                       (readme.NETWORK_BEGIN, readme.NETWORK_END)):
        assert -1 < text.find(begin) < text.find(end)
    assert readme.BEGIN not in (readme.REPO / "README.md").read_text()


def test_main_rewrites_the_page_it_is_given(tmp_path, document):
    results = tmp_path / "latest.json"
    results.write_text(json.dumps(document))
    page = tmp_path / "performance.md"
    page.write_text(f"# Performance\n\n{readme.BEGIN}\nold table\n{readme.END}\nafter\n")
    for option in ("--page", "--readme"):  # --readme: another name of the same option
        assert readme.main(["--results", str(results), option, str(page)]) == 0
        text = page.read_text()
        assert "old table" not in text and "| `teleop_1000` |" in text
        assert text.startswith("# Performance\n") and text.endswith("\nafter\n")
