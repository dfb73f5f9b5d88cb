"""bench.soak's pure parts and the soak's goal: the RSS slope after the warm-up, what counts as
steady growth, what counts as a loss, the events' classification. No station."""

from __future__ import annotations

import json

import pytest

from bench import goals, readme, soak
from bench.plan import DEFAULT_GROUPS, GROUPS, Plan
from telerobot.v1 import decision_server_pb2 as dpb


def _minutes(count: int, every_s: float = 5.0) -> list[float]:
    return [i * every_s for i in range(count)]


# -- the slope ------------------------------------------------------------------------------

def test_slope_is_the_least_squares_slope():
    assert soak.slope([0, 1, 2, 3], [1, 3, 5, 7]) == pytest.approx(2.0)
    assert soak.slope([0, 1, 2, 3], [5, 5, 5, 5]) == pytest.approx(0.0)
    # Noise around a line: the fit, not the end points.
    assert soak.slope([0, 1, 2, 3, 4], [0, 2, 1, 3, 3]) == pytest.approx(0.7)  # ends: 0.75
    assert soak.slope([1], [1]) is None
    assert soak.slope([2, 2], [1, 5]) is None


def test_a_steady_leak_shows_as_its_rate_in_mib_per_minute():
    times = _minutes(121)  # 10 minutes, every 5 s
    rss = [100.0 + 3.0 * t / 60.0 for t in times]  # 3 MiB/min
    trend = soak.rss_trend(times, rss)
    assert trend["slope_mib_min"] == pytest.approx(3.0)
    assert trend["late_slope_mib_min"] == pytest.approx(3.0)
    assert trend["window_min"] == pytest.approx(8.0)  # the first 20 % left out
    assert trend["growth_mib"] == pytest.approx(24.0)
    assert (trend["start_mib"], trend["end_mib"], trend["peak_mib"]) == (100.0, 130.0, 130.0)
    assert trend["samples"] == 97


def test_the_warm_up_is_left_out_of_the_fit():
    times = _minutes(121)
    # 50 MiB in the first minute (a renderer, pools filling), flat after.
    rss = [100.0 + min(t, 60.0) * 50.0 / 60.0 for t in times]
    trend = soak.rss_trend(times, rss)
    assert trend["slope_mib_min"] == pytest.approx(0.0)
    assert trend["start_mib"] == 100.0 and trend["end_mib"] == 150.0


def test_samples_of_a_process_gone_are_left_out():
    trend = soak.rss_trend([0, 10, 20, 30, 40, 50], [10, 10, None, 10, 10, 10])
    assert trend["slope_mib_min"] == pytest.approx(0.0) and trend["samples"] == 4
    empty = soak.rss_trend([0, 10], [None, None])
    assert empty["samples"] == 0 and empty["slope_mib_min"] is None


# -- steady growth ----------------------------------------------------------------------------

def _trend(rss, every_s: float = 5.0) -> dict:
    return soak.rss_trend(_minutes(len(rss), every_s), rss)


def test_growth_over_the_bound_all_along_fails():
    leak = _trend([100.0 + 2.5 * i * 5 / 60 for i in range(121)])  # 2.5 MiB/min
    assert goals.growing(leak, 2.0)
    misses = goals.rss_misses({"decision_server": leak, "world": _trend([50.0] * 121)}, 2.0)
    assert misses == ["decision_server RSS +2.50 MiB/min > 2 (late +2.50, +20.0 MiB)"]


def test_growth_under_the_bound_passes():
    slow = _trend([100.0 + 1.5 * i * 5 / 60 for i in range(121)])  # 1.5 MiB/min: 12 MiB
    assert not goals.growing(slow, 2.0)
    assert goals.rss_misses({"proxy_robot": slow}, 2.0) == []


def test_a_step_that_levels_off_is_not_steady_growth():
    # Flat, +20 MiB at minute 4 (after the warm-up), flat again: the whole window's slope is
    # over the bound, its second half's is zero.
    rss = [100.0 if i * 5 < 240 else 120.0 for i in range(121)]
    trend = _trend(rss)
    assert trend["slope_mib_min"] > 2.0 and trend["late_slope_mib_min"] == pytest.approx(0)
    assert not goals.growing(trend, 2.0)


def test_a_short_soak_does_not_judge_a_few_mib():
    # One minute: 3 MiB/min over 48 s is 2.4 MiB, within what allocators move by.
    short = _trend([100.0 + 3.0 * i * 2 / 60 for i in range(31)], every_s=2.0)
    assert short["slope_mib_min"] == pytest.approx(3.0) and short["growth_mib"] < 4.0
    assert not goals.growing(short, 2.0)
    fast = _trend([100.0 + 10.0 * i * 2 / 60 for i in range(31)], every_s=2.0)
    assert goals.growing(fast, 2.0)


def test_no_samples_fail_the_memory_goal():
    assert goals.rss_misses({}, 2.0) == ["no RSS sampled"]
    assert goals.rss_misses({"world": _trend([1.0])}, 2.0) == ["world: too few RSS samples"]


# -- loss -------------------------------------------------------------------------------------

def _row(**changes) -> dict:
    flat = _trend([100.0] * 121)
    row = {"rate_hz": 500.0, "delivered_hz": 499.0, "p50_ms": 10.0, "p99_ms": 40.0,
           "teleop": {"sent": 300000, "unacked": 0, "ack_gaps": 0, "refused": 0, "unsent": 0,
                      "late_skipped": 12},
           "events": {"watchdog_trips": 0, "watchdog_holds": 1, "leases_lost": 0,
                      "control_changes": 2, "sequence_gaps": 0, "errors": [],
                      "ended_early": False},
           "observers": {"observer_delivered_hz_mean": 99.0, "errors": []},
           "stereo": {"delivered_hz": 29.0, "errors": 0, "pairs": 17000},
           "rss": {name: dict(flat) for name in soak.STATION}, "exited": []}
    for key, value in changes.items():
        if isinstance(value, dict) and isinstance(row.get(key), dict):
            row[key] = {**row[key], **value}
        else:
            row[key] = value
    return row


def test_a_clean_soak_passes():
    judged = goals.judge("soak", {"soak": _row()})
    assert judged == {"goal": "RSS growth <= 2 MiB/min per process, no loss", "pass": True,
                      "misses": []}


@pytest.mark.parametrize(("changes", "miss"), [
    ({"teleop": {"unacked": 3}}, "3 commands unacked"),
    ({"teleop": {"refused": 2}}, "2 commands refused"),
    ({"teleop": {"unsent": 9000}}, "9000 commands unsent (the stream ended early)"),
    ({"teleop": {"status": "failed", "reason": "teleop failed: boom"}},
     "Teleoperate failed: teleop failed: boom"),
    ({"events": {"watchdog_trips": 1}}, "1 watchdog trips"),
    ({"events": {"leases_lost": 1}}, "1 leases lost"),
    ({"events": {"sequence_gaps": 4}}, "4 events not received (the counts may be short)"),
    ({"events": {"status": "failed", "reason": "events failed"}},
     "events not followed: events failed"),
    ({"exited": ["proxy_robot"]}, "exited during the soak: proxy_robot"),
    ({"observers": {"errors": ["observer 2: UNAVAILABLE"]}}, "observers: 1 streams failed"),
    ({"stereo": {"errors": 2}}, "stereo: 2 streams failed"),
    ({"stereo": {"status": "pending", "reason": "no GL"}}, "stereo pending: no GL"),
])
def test_each_loss_fails_the_soak_and_says_what(changes, miss):
    judged = goals.judge("soak", {"soak": _row(**changes)})
    assert judged["pass"] is False and judged["misses"] == [miss]


def test_what_is_reported_but_not_judged():
    # Late ticks are the client's own; dropped wrench samples and skipped stereo pairs are
    # latest-wins streams doing their job; the latency has goals elsewhere.
    row = _row(teleop={"late_skipped": 5000}, p99_ms=900.0,
               observers={"observer_sequence_gaps": 40, "observer_server_dropped": 40},
               stereo={"dropped": 12})
    assert goals.judge("soak", {"soak": row})["pass"] is True


def test_a_soak_that_did_not_run_fails():
    judged = goals.judge("soak", {"soak": {"status": "failed", "reason": "no DecisionServer"}})
    assert judged["pass"] is False and "no DecisionServer" in judged["misses"][0]


# -- events -----------------------------------------------------------------------------------

def _event(sequence: int, **event) -> dpb.StreamEventsResponse:
    return dpb.StreamEventsResponse(sequence=sequence, **event)


def test_the_event_book_tells_lease_losses_and_watchdog_trips_apart():
    book = soak.EventBook()
    book.add(_event(1, control_changed=dpb.ControlChangedEvent(
        reason="bench acquired EXCLUSIVE control")))
    book.add(_event(2, watchdog_hold=dpb.WatchdogHoldEvent(
        reason="watchdog timeout: no command or heartbeat")))
    book.add(_event(5, control_changed=dpb.ControlChangedEvent(reason="bench's lease expired")))
    book.add(_event(6, watchdog_hold=dpb.WatchdogHoldEvent(reason="the stream ended")))
    result = book.result()
    assert (result["control_changes"], result["leases_lost"]) == (2, 1)
    assert (result["watchdog_holds"], result["watchdog_trips"]) == (2, 1)
    assert result["sequence_gaps"] == 2  # 3 and 4 never came
    assert [c["reason"] for c in result["control"]] == ["bench acquired EXCLUSIVE control",
                                                        "bench's lease expired"]


# -- the plan, and README's block ---------------------------------------------------------------

def test_the_soak_runs_only_when_asked_for():
    assert "soak" in GROUPS and "soak" not in DEFAULT_GROUPS
    assert not Plan(quick=False).wants("soak") and Plan(quick=False).wants("command")
    plan = Plan(quick=False, only=("soak",))
    assert plan.wants("soak") and not plan.wants("command")
    assert plan.soak_s == 600.0 and Plan(quick=True).soak_s == 60.0
    assert Plan(quick=True, soak_minutes=2.5).soak_s == 150.0


def test_readme_writes_the_soak_block_and_leaves_the_table():
    document = {"time": "2026-11-23T12:00:00+0000", "quick": False, "run_s": 640.0,
                "machine": {"cores": 2, "cpu_model": "AMD EPYC", "python": "3.11.7",
                            "load_avg_at_start": [1.0, 1, 1], "load_avg_at_end": [3.0, 1, 1]},
                "soak": _row(minutes=10.0, watchdog_s=1.0, sample_s=5.0,
                             warmup_fraction=0.2),
                "world_loop": {"steps": 600000, "overruns": 60, "overrun_pct": 0.01},
                "ratios": {}}
    goals.add_goals(readme.scenarios(document))
    assert readme.has_soak(document) and not readme.has_table(document)
    block = readme.soak_block(json.loads(json.dumps(document)))
    assert "a soak of 10 min" in block and "**Result: PASS**" in block
    assert "| `decision_server` | 100.0 → 100.0 | +0.00 | +0.00 |" in block
    text = (f"{readme.BEGIN}\nold table\n{readme.END}\n{readme.SOAK_BEGIN}\nold soak\n"
            f"{readme.SOAK_END}\n")
    new = readme.rewrite(text, block, readme.SOAK_BEGIN, readme.SOAK_END)
    assert "old table" in new and "old soak" not in new and block in new


def test_wrench_sequence_gaps_count_the_samples_missing_for_a_subscriber():
    from bench.force import sequence_gaps

    assert sequence_gaps(None, 50, 10) == 0
    assert sequence_gaps(40, 50, 10) == 0  # every 10th sample is this subscriber's
    assert sequence_gaps(40, 70, 10) == 2
