"""bench.goals: each scenario's goal and its PASS/FAIL, judged on results given by hand."""

from __future__ import annotations

from bench import goals


def _result(delivered_hz=None, p50_ms=None, p99_ms=None, **extra) -> dict:
    return {"rate_hz": 1000.0, "delivered_hz": delivered_hz, "p50_ms": p50_ms,
            "p99_ms": p99_ms, "max_ms": p99_ms, "dropped": 0, **extra}


def test_teleop_1000_passes_only_with_rate_latency_and_latency_against_zmq():
    zmq = {"teleop_1000_zmq": _result(999.0, 0.5, 1.5)}
    fast = {"teleop_1000": _result(995.0, 0.8, 1.9), **zmq}
    slow = {"teleop_1000": _result(980.0, 0.8, 1.9), **zmq}
    late = {"teleop_1000": _result(995.0, 0.8, 2.1), **zmq}
    behind = {"teleop_1000": _result(995.0, 0.8, 1.9),
              "teleop_1000_zmq": _result(999.0, 0.5, 1.2)}
    assert goals.judge("teleop_1000", fast)["pass"] is True
    assert goals.judge("teleop_1000", slow)["misses"] == ["980 Hz < 990"]
    assert goals.judge("teleop_1000", late)["misses"] == ["p99 2.1 ms > 2"]
    assert goals.judge("teleop_1000", behind)["misses"] == [
        "p99 1.9 ms > 1.5 x 1.200"]


def test_every_estop_scenario_has_the_5_ms_goal():
    for name in ("estop_idle", "estop_under_load", "estop_under_load_proxy", "estop_ds_idle",
                 "estop_ds_busywork"):
        assert goals.goal_for(name).p99_ms == 5.0, name


def test_baselines_and_unlisted_scenarios_have_no_goal():
    results = {"command_1000_zmq": _result(999.0, 0.5, 1.0), "command_50": _result(50, 1, 2)}
    for name in results:
        judged = goals.judge(name, results)
        assert (judged["goal"], judged["pass"]) == (goals.NO_GOAL, None)
        assert goals.verdict_text(judged) == "no goal"


def test_a_goal_relative_to_a_baseline_waits_for_it_then_is_judged_against_it():
    results = {"command_1000": _result(995.0, 1.0, 3.0)}
    assert goals.verdict_text(goals.judge("command_1000", results, final=False)) == "PENDING"
    assert goals.judge("command_1000", results)["misses"] == [
        "command_1000_zmq not measured in this run"]
    results["command_1000_zmq"] = _result(999.0, 0.5, 2.5)
    assert goals.judge("command_1000", results)["pass"] is True  # 3.0 <= 1.5 x 2.5
    results["command_1000_zmq"]["p99_ms"] = 1.0
    assert goals.judge("command_1000", results)["pass"] is False
    assert goals.dependents("command_1000_zmq") == ["command_1000"]


def test_a_failed_scenario_with_a_goal_fails_it():
    results = {"closed_loop": {"status": "failed", "reason": "the worker died"}}
    judged = goals.judge("closed_loop", results)
    assert judged["pass"] is False and "the worker died" in judged["misses"][0]


def test_world_loop_goal_is_on_the_overrun_percentage():
    assert goals.judge("world_loop", {"world_loop": {"overrun_pct": 0.05}})["pass"] is True
    assert goals.judge("world_loop", {"world_loop": {"overrun_pct": 0.5}})["pass"] is False


def test_add_goals_stores_goal_pass_and_misses_on_every_scenario():
    results = {"closed_loop": _result(None, 12.0, 30.0), "stereo_sim_double":
               _result(18.0, 40.0, 60.0), "teleop_500": _result(500.0, 1.0, 1.5)}
    goals.add_goals(results)
    assert results["closed_loop"]["pass"] is False
    assert results["closed_loop"]["goal_misses"] == ["p99 30 ms > 25"]
    assert results["stereo_sim_double"]["goal"] == ">= 17 fps"
    assert results["stereo_sim_double"]["pass"] is True
    assert results["teleop_500"]["goal"] == "no goal"


def test_bench_readme_lists_the_goals_as_the_code_has_them():
    from pathlib import Path

    text = (Path(goals.__file__).parent / "README.md").read_text()
    block = text.split("<!-- goals:begin -->")[1].split("<!-- goals:end -->")[0]
    rows = [[cell.strip().strip("`") for cell in line.strip("|").split("|")]
            for line in block.strip().splitlines()[2:]]
    assert rows == [[pattern, goal.text(), goal.source] for pattern, goal in goals.GOALS]
