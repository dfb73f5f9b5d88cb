"""The recording-on twins (issue #17): each `_mcap` row judged against its twin of the same run
(goals.py), compared with it (report.py, readme.py), and its MCAP file counted (recording.py)."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from bench import goals, readme, recording, report
from services.decision_server import recording_mcap
from services.decision_server.recordings import RecordedCommand
from telerobot.v1 import decision_server_pb2 as dpb
from telerobot.v1 import force_sensor_pb2, types_pb2


def _row(delivered_hz, p50_ms, p99_ms, **extra) -> dict:
    return {"rate_hz": 1000.0, "delivered_hz": delivered_hz, "p50_ms": p50_ms,
            "p99_ms": p99_ms, "max_ms": p99_ms, "dropped": 0, **extra}


def _complete(count: int) -> dict:
    return {"expected": count, "recorded": {"/robot/wrench": count, "/force/arrow": count},
            "error": None}


def test_the_goal_is_rate_and_cost_within_10_percent_of_the_twin_and_a_whole_recording():
    force, teleop = goals.goal_for("force_1000_mcap"), goals.goal_for("teleop_1000_mcap")
    assert (force.rate_vs, force.p50_vs, force.cpu_vs, force.p99_vs) == (
        ("force_1000", 0.9), ("force_1000", 1.1), None, None)
    assert force.text() == ("delivered >= 0.9 x force_1000, p50 <= 1.1 x force_1000 "
                            "(medians of interleaved pairs), recording complete")
    assert (teleop.rate_vs, teleop.p50_vs, teleop.cpu_vs, teleop.p99_vs) == (
        ("teleop_1000", 0.9), None, ("teleop_1000", 1.1), None)
    assert teleop.text() == ("delivered >= 0.9 x teleop_1000, server CPU/command <= 1.1 x "
                             "teleop_1000 (medians of interleaved pairs), recording complete")
    assert goals.dependents("force_1000") == ["force_1000_mcap"]
    assert goals.dependents("teleop_1000") == ["teleop_1000_tls", "teleop_1000_mcap",
                                              "teleop_1000_episode"]


def test_an_mcap_row_waits_for_its_twin_then_is_judged_on_rate_p50_and_its_file():
    results = {"force_1000_mcap": _row(990.0, 0.55, 9.0, recording=_complete(2500))}
    assert goals.verdict_text(goals.judge("force_1000_mcap", results, final=False)) == "PENDING"
    assert goals.judge("force_1000_mcap", results)["misses"] == [
        "force_1000 not measured in this run"]
    results["force_1000"] = _row(999.0, 0.5, 2.0)  # the p99 ratio (x4.5) is not judged
    assert goals.judge("force_1000_mcap", results)["pass"] is True
    results["force_1000_mcap"].update(delivered_hz=880.0, p50_ms=0.6)
    assert goals.judge("force_1000_mcap", results)["misses"] == [
        "880 Hz < 0.9 x 999.0", "p50 0.6 ms > 1.1 x 0.500"]


def test_teleop_s_cost_is_the_decision_server_s_cpu_per_command_not_its_queued_p50():
    cpu = goals.CPU_KEY
    results = {"teleop_1000": _row(995.0, 7.5, 60.0, **{cpu: 0.45}),
               "teleop_1000_mcap": _row(993.0, 73.0, 160.0, **{cpu: 0.48},
                                        recording=_complete(2014))}
    assert goals.judge("teleop_1000_mcap", results)["pass"] is True
    results["teleop_1000_mcap"][cpu] = 0.5
    assert goals.judge("teleop_1000_mcap", results)["misses"] == [
        "server CPU/command 0.5 ms > 1.1 x 0.450"]
    assert report.comparison(results["teleop_1000_mcap"], results["teleop_1000"])[
        "server_cpu"] == 1.11


def test_a_recording_that_lost_a_sample_or_failed_fails_the_row():
    results = {"force_1000": _row(999.0, 0.5, 2.0),
               "force_1000_mcap": _row(999.0, 0.5, 2.0, recording=_complete(2500))}
    results["force_1000_mcap"]["recording"]["recorded"]["/force/arrow"] = 2499
    assert goals.judge("force_1000_mcap", results)["misses"] == [
        "recording: /force/arrow 2499 of 2500"]
    results["force_1000_mcap"]["recording"] = {**_complete(10), "error": "disk full"}
    assert goals.judge("force_1000_mcap", results)["misses"] == ["recording: disk full"]
    del results["force_1000_mcap"]["recording"]
    assert goals.judge("force_1000_mcap", results)["misses"] == ["no recording checked"]


def test_an_mcap_row_is_compared_with_its_twin_in_the_table_and_the_readme():
    assert report.compared_with("teleop_1000_mcap") == [("recording_off", "teleop_1000")]
    results = {"teleop_1000": _row(995.0, 0.5, 4.0, server_cpu_ms_per_command=0.4),
               "teleop_1000_mcap": _row(990.0, 0.55, 6.0, mode="pipelined",
                                        server_cpu_ms_per_command=0.42, recording={
                   "format": "MCAP", "expected": 2020, "file_bytes": 900_000,
                   "recorded": {"applied acks": 2020}, "moves": 2001, "moves_saved": 2001})}
    report.add_ratios(results)
    assert results["teleop_1000_mcap"]["ratio_vs_recording_off"]["p50"] == 1.1
    text = report.table(results)
    assert "MCAP recording on / off" in text
    assert ("teleop_1000_mcap / teleop_1000: p50 x1.10, p99 x1.50, delivered x0.99, "
            "server_cpu x1.05") in text
    assert "MCAP of 2020: applied acks 2020; 2001 moves (StopRecording: 2001), 0.9 MB" in text
    document = {"quick": True, "machine": {}, **results}
    rows = {line.split("|")[1].strip().strip("`"): [c.strip() for c in line.split("|")[1:-1]]
            for line in readme.table(document).splitlines() if line.startswith("| `")}
    name, what, delivered, p50, p99, goal, result, baselines = rows["teleop_1000_mcap"]
    assert what.startswith("`teleop_1000` with the DecisionServer recording it as MCAP")
    assert goal == ("delivered ≥ 0.9 x teleop_1000, server CPU/command ≤ 1.1 x teleop_1000 "
                    "(medians of interleaved pairs), recording complete")
    assert baselines == ("recording off 995 Hz, 0.50 / 4.00 (p50 ×1.10, p99 ×1.50, "
                         "CPU/command ×1.05)")


def _pairs(ratios: list[float], cost: str = goals.CPU_KEY, lost: int | None = None
           ) -> list[tuple[dict, dict]]:
    """Interleaved legs (off, on): the on leg's cost at `ratios` x the off leg's 0.45; the
    on leg of pair `lost` (1-based) recorded one command short."""
    pairs = []
    for index, value in enumerate(ratios, 1):
        off = _row(995.0, 30.0, 200.0, **{cost: 0.45}, session_applied=2000)
        count = 2000 - (index == lost)
        on = _row(990.0, 60.0, 100.0, **{cost: round(0.45 * value, 6)}, session_applied=2000,
                  latencies_ms=[1.0], recording={**_complete(2000),
                                                 "recorded": {"applied acks": count}})
        pairs.append((off, on))
    return pairs


def test_interleaved_pairs_make_the_row_of_the_first_on_leg_with_ratios_and_medians():
    pairs = _pairs([1.04, 1.30, 1.02])
    row = report.interleaved(pairs)
    assert row["p50_ms"] == 60.0 and row["latencies_ms"] == [1.0]  # pair 1's on leg
    assert row["overhead_ratios"]["server_cpu"] == [1.04, 1.3, 1.02]
    assert row["overhead_ratios"]["delivered"] == [0.995] * 3
    assert row["overhead_median"] == {"delivered": 0.995, "p50": 2.0, "p99": 0.5,
                                      "server_cpu": 1.04}
    assert "subscriber_cpu" not in row["overhead_ratios"]  # neither leg has it
    assert row["overhead_pairs"][1] == {
        "off": {"delivered_hz": 995.0, "p50_ms": 30.0, "p99_ms": 200.0, "dropped": 0,
                goals.CPU_KEY: 0.45, "session_applied": 2000},
        "on": {"delivered_hz": 990.0, "p50_ms": 60.0, "p99_ms": 100.0, "dropped": 0,
               goals.CPU_KEY: 0.585, "session_applied": 2000}}
    assert len(row["recordings"]) == 3
    assert report.overhead_text({"overhead_median": {"server_cpu": 1.04},
                                 "overhead_ratios": {"server_cpu": [1.04, 1.3, None]}}) == (
        "server_cpu x1.04 (x1.04, x1.30, -)")


def test_an_interleaved_row_says_where_the_servers_cpu_moved_by_thread():
    """Each pair's on − off per thread name (0 where a leg had no such thread), the median
    over pairs, the largest change first; shown in the readme's row."""
    by_thread = goals.THREAD_CPU_KEY
    pairs = _pairs([1.0, 1.0, 1.0])
    for (off, on), engine, follow in zip(pairs, (10.0, 14.0, 9.0), (2.0, 6.0, 5.0),
                                         strict=True):
        off[by_thread] = {"event_engine": 80.0, "follow-proxy_ro": 30.0, "grpc": 60.0}
        on[by_thread] = {"event_engine": 80.0 + engine, "follow-proxy_ro": 30.0 + follow,
                         "grpc": 59.0, "recording-video": 3.0}
    pairs[2][1][by_thread].pop("recording-video")
    row = report.interleaved(pairs)
    assert row["thread_cpu_change"] == {"event_engine": 10.0, "follow-proxy_ro": 5.0,
                                        "recording-video": 3.0, "grpc": -1.0}
    assert row["overhead_pairs"][0]["on"][by_thread]["grpc"] == 59.0
    assert report.thread_cpu_text(row, shown=2) == (
        "event_engine +10.0, follow-proxy_ro +5.0 µs/command")
    results = {"teleop_1000": _row(995.0, 0.5, 4.0), "teleop_1000_mcap": row}
    line = next(line for line in readme.table({"quick": True, "machine": {}, **results})
                .splitlines() if line.startswith("| `teleop_1000_mcap`"))
    assert "the server's CPU by thread, on − off: event_engine +10.0, follow-proxy_ro +5.0, " \
           "recording-video +3.0, grpc -1.0 µs/command" in line
    assert report.thread_cpu_change(_pairs([1.0])) == {}  # legs not split by thread


def test_an_interleaved_row_is_judged_on_the_median_of_its_pairs_and_every_recording():
    twin = _row(995.0, 30.0, 200.0, **{goals.CPU_KEY: 0.9})  # pair 1's off leg, not judged on
    results = {"teleop_1000": twin,
               "teleop_1000_mcap": report.interleaved(_pairs([1.04, 1.30, 1.02]))}
    assert goals.judge("teleop_1000_mcap", results)["pass"] is True  # one pair's x1.30 is noise
    results["teleop_1000_mcap"] = report.interleaved(_pairs([1.12, 1.30, 1.02, 1.15, 1.2]))
    assert goals.judge("teleop_1000_mcap", results)["misses"] == [
        "server CPU/command median x1.15 > 1.1 (pairs x1.12, x1.30, x1.02, x1.15, x1.20)"]
    results["teleop_1000_mcap"] = report.interleaved(_pairs([1.0, 1.0, 1.0], lost=2))
    assert goals.judge("teleop_1000_mcap", results)["misses"] == [
        "pair 2: recording: applied acks 1999 of 2000"]
    slow = _pairs([1.0, 1.0, 1.0])
    for _, on in slow[:2]:
        on["delivered_hz"] = 850.0
    results["teleop_1000_mcap"] = report.interleaved(slow)
    assert goals.judge("teleop_1000_mcap", results)["misses"] == [
        "delivered median x0.85 < 0.9 (pairs x0.85, x0.85, x0.99)"]


def test_force_pairs_are_judged_on_the_p50_and_report_the_subscriber_s_cpu():
    cpu = goals.SUBSCRIBER_CPU_KEY
    pairs = []
    for p50, us in ((1.2, 40.0), (1.0, 45.0), (1.3, 41.0)):
        pairs.append((_row(999.0, 1.1, 3.0, **{cpu: 30.0}),
                      _row(998.0, p50, 3.0, **{cpu: us}, recording=_complete(2800))))
    results = {"force_1000": pairs[0][0], "force_1000_mcap": report.interleaved(pairs)}
    row = results["force_1000_mcap"]
    assert row["overhead_ratios"]["p50"] == [1.091, 0.909, 1.182]
    assert row["overhead_median"]["subscriber_cpu"] == 1.367  # reported, not judged
    assert goals.judge("force_1000_mcap", results)["pass"] is True
    assert report.comparison(pairs[0][1], pairs[0][0])["subscriber_cpu"] == 1.33
    report.add_ratios(results)
    text = report.table(results)
    assert ("force_1000_mcap, median of 3 interleaved pairs (on / off): delivered x1.00 "
            "(x1.00, x1.00, x1.00), p50 x1.09 (x1.09, x0.91, x1.18), p99 x1.00 (x1.00, x1.00, "
            "x1.00), subscriber_cpu x1.37 (x1.33, x1.50, x1.37)") in text
    assert "force_1000_mcap, pair 3: None of 2800: /robot/wrench 2800" in text
    assert "force_1000: subscriber CPU 30.0 µs/sample" in text
    document = {"quick": True, "machine": {}, **results}
    rows = {line.split("|")[1].strip().strip("`"): [c.strip() for c in line.split("|")[1:-1]]
            for line in readme.table(document).splitlines() if line.startswith("| `")}
    assert rows["force_1000_mcap"][-1] == (
        "recording off 999 Hz, 1.10 / 3.00 (p50 ×1.09, p99 ×1.00); medians of 3 interleaved "
        "pairs: delivered ×1.00 (×1.00 ×1.00 ×1.00), p50 ×1.09 (×1.09 ×0.91 ×1.18), "
        "p99 ×1.00 (×1.00 ×1.00 ×1.00), subscriber CPU/sample ×1.37 (×1.33 ×1.50 ×1.37)")


def test_the_wrench_recorder_writes_each_sample_and_its_arrow(tmp_path):
    recorder = recording.WrenchRecorder(tmp_path / "w.mcap")
    for sequence in range(1, 4):
        message = force_sensor_pb2.StreamWrenchResponse(samples=[force_sensor_pb2.WrenchSample(
            sequence=sequence, wrench=types_pb2.Wrench(force_n=types_pb2.Vector3(z=-2.0)))])
        message.samples[0].sample_time.FromNanoseconds(sequence * 1_000_000)
        recorder.write(message)
    checked = recorder.close()
    assert checked["expected"] == 3 and checked["error"] is None
    assert checked["recorded"] == {"/robot/wrench": 3, "/force/arrow": 3}
    assert goals.recording_misses(checked) == []


def test_a_teleop_recording_counts_merged_moves_in_commands(tmp_path):
    """Five 10 µm commands, two of them merged into one move: four increments, five commands;
    heartbeats' acks (sequence 0) and refused commands are not applied ones."""
    path = tmp_path / "t.mcap"
    file = recording_mcap.McapFile(path)
    for index, steps in enumerate((1, 2, 1, 1)):
        file.write(recording_mcap.INCREMENT, recording_mcap.increment_to_proto(RecordedCommand(
            0.001 * index, "BASE", np.array([0.0, -1e-5 * steps, 0.0]), np.eye(3),
            np.zeros(3), None)), 1_000_000 * (index + 1))
    for sequence, outcome in ((0, dpb.COMMAND_OUTCOME_APPLIED), (1, dpb.COMMAND_OUTCOME_APPLIED),
                              (2, dpb.COMMAND_OUTCOME_MODIFIED), (3, dpb.COMMAND_OUTCOME_REJECTED)):
        file.write(recording_mcap.ACK, dpb.CommandAck(sequence=sequence, outcome=outcome),
                   1_000_000 * (sequence + 1))
    file.finish({"name": "t"})
    checked = recording.teleop_check(path, applied=5, server_moves=4, step_m=1e-5)
    assert checked["recorded"] == {"increments (in commands)": 5, "applied acks": 2}
    assert (checked["moves"], checked["error"]) == (4, None)
    assert goals.recording_misses(checked) == ["recording: applied acks 2 of 5"]
    episode = {"recorded": {"applied acks": 5}, "expected": 5, "error": None,
               "video_frames": 0}  # an episode's, whole but without video
    assert goals.recording_misses(episode) == ["recording: no video frame"]
    assert goals.recording_misses({**episode, "video_frames": 60}) == []
    assert "StopRecording saved 5" in recording.teleop_check(path, 5, 5, 1e-5)["error"]
    assert recording.topic_counts(path) == {recording_mcap.INCREMENT: 4, recording_mcap.ACK: 4}


def test_the_pairs_are_four_quick_and_six_full_each_leg_the_quick_length():
    from bench.plan import Plan

    quick, full = Plan(quick=True), Plan(quick=False)
    assert (quick.overhead_pairs, full.overhead_pairs) == (4, 6)
    assert (full.overhead_teleop_leg_s, full.overhead_force_leg_s) == (quick.command_s,
                                                                       quick.force_s)


def test_when_the_teleop_streams_fail_their_recording_twin_is_a_failed_row_too():
    """teleop_1000_mcap repeats teleop_1000: with no teleop_1000 it has nothing to compare
    with, and it must show as failed, not vanish from the table."""
    from types import SimpleNamespace

    from bench.groups import decision
    from bench.plan import Plan
    from bench.run import Bench
    from services.runtime.children import ChildFailed

    def worker_fails(*args, **kwargs):
        raise ChildFailed("decision_server exited (code 1)")

    bench = Bench.__new__(Bench)  # no station: the failure path only
    bench.plan, bench.results = Plan(quick=True, only=("decision",)), {}
    bench.progress = SimpleNamespace(step=lambda *a: None, done=lambda *a: None)
    bench.driver = SimpleNamespace(arm_ready=lambda: None)
    bench.pid = lambda name: None
    bench.rate_worker = worker_fails
    decision._teleop(bench, "127.0.0.1:1")
    for name in ("teleop_50", "teleop_1000", "teleop_1000_lockstep", "teleop_1000_mcap"):
        assert bench.results[name]["status"] == "failed", name
    assert "decision_server exited" in bench.results["teleop_1000_mcap"]["reason"]


@pytest.mark.parametrize("reuse_twin", [True, False])
def test_the_pairs_run_in_balanced_order_and_the_legs_go_out_and_back_in_turn(reuse_twin):
    """off, on, then on, off...: as many pairs record first as second; each leg's sign is the
    opposite of the one before it, the twin's own run (+1) included when it is pair 1's off."""
    from types import SimpleNamespace

    from bench.plan import Plan
    from bench.run import Bench

    bench = Bench.__new__(Bench)
    bench.plan, bench.results = Plan(quick=True), {"teleop_1000": _row(995.0, 1.5, 4.0)}
    bench.progress = SimpleNamespace(step=lambda *a: None, done=lambda *a: None,
                                     note=lambda *a: None)
    bench.record = bench.results.__setitem__
    bench.headline = lambda name: ""
    legs = []

    def leg(role):
        def run(index, sign):
            legs.append((role, index, sign))
            return _row(995.0, 1.5, 4.0)
        return run

    bench.mcap_twin("teleop_1000", "a test", leg("off"), leg("on"), suffix="x",
                    reuse_twin=reuse_twin)
    roles = [role for role, _, _ in legs]
    expected = ["off", "on", "on", "off", "off", "on", "on", "off"]
    assert roles == (expected[1:] if reuse_twin else expected)
    assert [index for _, index, _ in legs] == ([0, 1, 1, 2, 2, 3, 3] if reuse_twin
                                               else [0, 0, 1, 1, 2, 2, 3, 3])
    signs = [sign for _, _, sign in legs]
    assert signs[0] == (-1.0 if reuse_twin else 1.0)
    assert all(a == -b for a, b in itertools.pairwise(signs))
    assert len(bench.results["teleop_1000_x"]["overhead_pairs"]) == 4


def test_pairs_of_identical_legs_make_a_row_of_ratios_without_recordings():
    """teleop_1000_aa: the same leg twice, nothing recorded: the ratios are the run's noise,
    and the row carries no recordings to be checked or listed."""
    leg = _row(995.0, 1.5, 4.0, **{goals.CPU_KEY: 0.65})
    row = report.interleaved([(leg, _row(995.0, 1.5, 6.0, **{goals.CPU_KEY: 0.65}))] * 3)
    assert row["overhead_median"]["p99"] == 1.5
    assert "recordings" not in row
    assert goals.goal_for("teleop_1000_aa") is None  # a diagnostic
