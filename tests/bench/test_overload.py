"""bench.overload's pure parts and soak_overload's goal: the strokes, the thirds of the run and
their percentiles, the waits of the commands applied on their own, the net motion against the
commands, the arm at rest, and each of the goal's bounds judged on rows given by hand."""

from __future__ import annotations

import pytest

from bench import goals, overload
from bench.overload import Command
from bench.plan import DEFAULT_GROUPS, GROUPS, Plan

MS = 1_000_000  # ns


def test_the_strokes_flip_every_swing_commands_and_cancel():
    signs = [overload.direction(i, 3) for i in range(12)]
    assert signs == [1, 1, 1, -1, -1, -1, 1, 1, 1, -1, -1, -1]
    assert sum(overload.direction(i) for i in range(2 * overload.SWING)) == 0


def test_a_command_falls_in_the_third_it_was_sent_in():
    first, duration = 1_000, 3_000
    assert [overload.third_of(first + t, first, duration) for t in (0, 999, 1000, 2999)] == [
        0, 0, 1, 2]
    assert overload.third_of(first - 5, first, duration) == 0  # before the start: the first
    assert overload.third_of(first + 4000, first, duration) == 2  # after the end: the last


def _command(sent_ms: float, wait_ms: float, queued_ms: float = 0.0,
             outcome: str = "APPLIED", merged: bool = False) -> Command:
    """Sent at `sent_ms`, received `queued_ms` later, applied `wait_ms` after that."""
    receive = int((sent_ms + queued_ms) * MS)
    return Command(int(sent_ms * MS), receive, receive + int(wait_ms * MS), outcome, merged)


def test_each_third_has_its_percentiles_of_both_latencies_over_the_commands_applied():
    # 300 ms of run: 100 commands a third; the last third waits 10x longer at the server.
    commands = [_command(t, 1.0 if t < 200 else 10.0, queued_ms=0.5) for t in range(300)]
    commands[5] = _command(5, 500.0, outcome="REJECTED")  # not applied: not in the latencies
    commands[150] = _command(150, 60.0, outcome="MERGED_LATE")  # applied: in them
    commands[151] = _command(151, 1.0, merged=True)
    thirds = overload.per_third(commands, 0, 0.3)
    assert [t["third"] for t in thirds] == [1, 2, 3]
    assert [t["t_s"] for t in thirds] == [0.0, 0.1, 0.2]
    assert [t["commands"] for t in thirds] == [100, 100, 100]
    assert [t["applied"] for t in thirds] == [99, 100, 100]
    assert thirds[0]["outcomes"] == {"APPLIED": 99, "REJECTED": 1}
    assert thirds[1]["outcomes"] == {"APPLIED": 99, "MERGED_LATE": 1}
    assert thirds[1]["client_merged"] == 1
    assert thirds[0]["received_p50_ms"] == pytest.approx(1.0)
    assert thirds[0]["received_max_ms"] == pytest.approx(1.0)  # the refused one left out
    assert thirds[0]["sent_p50_ms"] == pytest.approx(1.5)  # + the 0.5 ms before receipt
    assert thirds[0]["queued_p50_ms"] == pytest.approx(0.5)
    assert thirds[1]["received_max_ms"] == pytest.approx(60.0)
    assert thirds[2]["received_p99_ms"] == pytest.approx(10.0)
    assert thirds[2]["sent_p99_ms"] == pytest.approx(10.5)
    worst = overload.worst_vs_first(thirds, "received_p99_ms")
    assert worst["third"] in (2, 3) and worst["ratio"] > 2


def test_the_worst_third_against_the_first():
    thirds = [{"third": 1, "p": 2.0}, {"third": 2, "p": 3.0}, {"third": 3, "p": 2.5}]
    assert overload.worst_vs_first(thirds, "p") == {"ratio": 1.5, "third": 2, "first": 2.0,
                                                     "worst": 3.0}
    thirds[0]["p"] = None  # nothing applied in the first third: no ratio
    assert overload.worst_vs_first(thirds, "p")["ratio"] is None


def test_an_empty_third_has_no_percentiles():
    thirds = overload.per_third([_command(10, 1.0)], 0, 0.3)
    assert thirds[0]["applied"] == 1
    assert thirds[1]["applied"] == 0 and thirds[1]["sent_p99_ms"] is None


def test_the_waits_count_only_commands_applied_on_their_own():
    commands = [_command(0, 10.0), _command(1, 49.0, outcome="MODIFIED"),
                _command(2, 51.0), _command(3, 80.0, outcome="MERGED_LATE"),
                _command(4, 900.0, outcome="REJECTED")]
    waits = overload.waits_on_their_own(commands, 0.05)
    assert waits == {"max_wait_applied_ms": pytest.approx(51.0), "stale_applied": 1}
    assert overload.waits_on_their_own([], 0.05) == {"max_wait_applied_ms": None,
                                                     "stale_applied": 0}


def test_the_net_motion_is_compared_with_the_commands_in_mm():
    motion = overload.net_motion((0.0, 0.002, 0.0), (0.1, 0.2, 0.3), (0.1, 0.2023, 0.3004))
    assert motion["commanded_mm"] == [0.0, 2.0, 0.0]
    assert motion["measured_mm"] == pytest.approx([0.0, 2.3, 0.4])
    assert motion["error_mm"] == pytest.approx(0.5)
    assert overload.net_motion((0, 0, 0), None, (0, 0, 0))["error_mm"] is None


def test_the_arm_is_at_rest_when_its_tool_stays_put_and_no_joint_turns():
    still = [(0.5, 0.1, 0.3)] * 5
    assert overload.is_at_rest(still, [0.0] * 6)
    assert not overload.is_at_rest(still, [0.0, 0.01, 0, 0, 0, 0])  # a joint still turning
    creeping = [(0.5, 0.1 + i * 1e-6, 0.3) for i in range(5)]
    assert not overload.is_at_rest(creeping, [0.0] * 6)
    assert not overload.is_at_rest(still[:1], [0.0] * 6)  # one reading tells nothing


def test_at_rest_reads_until_the_arm_stops_and_keeps_the_session_alive(monkeypatch):
    monkeypatch.setattr(overload, "REST_PERIOD_S", 0.0)
    monkeypatch.setattr(overload, "HEARTBEAT_S", 0.0)
    positions = iter([(0, i * 1e-4, 0) for i in range(5)] + [(0, 5e-4, 0)] * 100)
    beats = []
    position, rested, _ = overload.at_rest(lambda: (next(positions), [0.0] * 6),
                                           lambda: beats.append(1))
    assert rested and position == [0, 5e-4, 0] and beats


def test_summarize_sums_the_increments_applied_and_splits_the_measured_stream():
    sends, acks = {}, {}
    for sequence in range(1, 21):  # 2 warm-up, 18 measured (6 a third), 1 tail
        phase = "warmup" if sequence <= 2 else "measured"
        sent_ns = (sequence - 3) * 10 * MS
        sends[sequence] = (sent_ns, 1e-5, phase)
        acks[sequence] = ("APPLIED", sent_ns + MS, sent_ns + 3 * MS, False)
    sends[21] = (200 * MS, 0.0, "tail")
    acks[21] = ("APPLIED", 201 * MS, 202 * MS, False)
    acks[7] = ("REJECTED", 41 * MS, 41 * MS, False)  # measured, not applied
    acks[10] = ("MERGED_LATE", 71 * MS, 140 * MS, False)  # applied, late (third 2)
    del acks[9]  # never acked
    row = overload.summarize(sends, acks, 0, 0.18, 0.05)
    assert row["commanded_y_m"] == pytest.approx(18 * 1e-5)  # 20 sent, 2 not applied
    assert row["not_applied_y_mm"] == pytest.approx(0.02)
    assert row["outcomes"] == {"APPLIED": 18, "REJECTED": 1, "MERGED_LATE": 1}
    assert (row["unacked"], row["unacked_measured"], row["rejected_measured"]) == (1, 1, 1)
    assert row["samples"] == 16  # measured and applied
    assert [t["commands"] for t in row["thirds"]] == [6, 5, 6]  # one unacked in the second
    assert row["received_p50_ms"] == pytest.approx(2.0)
    assert row["p50_ms"] == pytest.approx(3.0)  # sent -> applied
    assert row["stale_applied"] == 0 and row["max_wait_applied_ms"] == pytest.approx(2.0)
    assert row["worst_third"]["received_p99_ms"]["third"] == 2  # the late one's


# -- the goal --------------------------------------------------------------------------------

def _third(index: int, sent: float, received: float) -> dict:
    return {"third": index, "sent_p99_ms": sent, "received_p99_ms": received}


def _row(**changes) -> dict:
    row = {"rate_hz": 500.0, "delivered_hz": 500.0, "p50_ms": 2.0, "p99_ms": 8.0,
           "received_p99_ms": 4.0,
           "thirds": [_third(1, 8.0, 4.0), _third(2, 9.0, 5.0), _third(3, 15.9, 7.9)],
           "motion": {"error_mm": 0.01}, "stale_applied": 0, "max_command_age_ms": 50.0,
           "max_wait_applied_ms": 12.0}
    row.update(changes)
    return row


def test_a_row_within_every_bound_passes():
    judged = goals.judge(overload.NAME, {overload.NAME: _row()})
    assert judged["pass"] is True, judged["misses"]
    assert "received -> applied p99 <= 10 ms" in judged["goal"]


@pytest.mark.parametrize("changes, miss", [
    ({"p99_ms": 120.0}, "p99 120 ms > 100"),
    ({"received_p99_ms": 12.0}, "received -> applied p99 12 ms > 10"),
    ({"thirds": [_third(1, 8.0, 4.0), _third(2, 9.0, 9.0), _third(3, 9.0, 4.0)]},
     "received -> applied p99 of third 2 9 ms > 2 x the first's 4"),
    ({"thirds": [_third(1, 8.0, 4.0), _third(2, 9.0, 4.0), _third(3, 17.0, 4.0)]},
     "sent -> applied p99 of third 3 17 ms > 2 x the first's 8"),
    ({"thirds": [_third(1, None, None), _third(2, 9.0, 4.0), _third(3, 9.0, 4.0)]},
     "sent -> applied p99: third 2 9 ms, the first - ms"),
    ({"thirds": []}, "no thirds measured"),
    ({"motion": {"error_mm": 0.7}}, "motion 0.7 mm off the commands applied > 0.5"),
    ({"motion": {"error_mm": None}}, "motion not measured"),
    ({"stale_applied": 3, "max_wait_applied_ms": 61.0},
     "3 applied on their own past max_command_age (50 ms; longest 61 ms)"),
])
def test_each_bound_fails_the_row_and_says_what(changes, miss):
    judged = goals.judge(overload.NAME, {overload.NAME: _row(**changes)})
    assert judged["pass"] is False
    assert miss in judged["misses"]


def test_a_row_that_did_not_run_fails():
    judged = goals.judge(overload.NAME, {overload.NAME: {"status": "failed",
                                                         "reason": "no DecisionServer"}})
    assert judged["pass"] is False and "no DecisionServer" in judged["misses"][0]


def test_other_rows_are_not_judged_by_the_overload_bounds():
    assert goals.overload_misses({}, goals.goal_for("teleop_1000")) == []


def test_soak_overload_runs_in_make_bench_quick_or_not():
    assert overload.NAME in GROUPS and overload.NAME in DEFAULT_GROUPS
    assert Plan(quick=True).wants(overload.NAME) and Plan(quick=False).wants(overload.NAME)
    assert not Plan(quick=True, only=("soak",)).wants(overload.NAME)
    assert Plan(quick=True).overload_s == 15.0 and Plan(quick=False).overload_s == 45.0
