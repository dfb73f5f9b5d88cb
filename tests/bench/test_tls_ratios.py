"""The TLS variants (issue #13): each `_tls` row compared with its plaintext twin of the same
run (report.py's ratios, goals.py's goal, readme.py's row), and the worker's credentials."""

from __future__ import annotations

from pathlib import Path

from bench import goals, readme, report, worker
from wire.tls import ChannelSecurity


def _row(delivered_hz, p50_ms, p99_ms, **extra) -> dict:
    return {"rate_hz": 1000.0, "delivered_hz": delivered_hz, "p50_ms": p50_ms,
            "p99_ms": p99_ms, "max_ms": p99_ms, "dropped": 0, **extra}


def test_a_tls_row_is_compared_with_its_plaintext_twin_and_nothing_else():
    assert report.compared_with("command_1000_tls") == [("plaintext", "command_1000")]
    assert report.compared_with("command_1000") == [("zmq", "command_1000_zmq"),
                                                    ("tcp", "command_1000_tcp")]
    assert report.compared_with("command_1000_zmq") == []
    assert report.plaintext_twin("teleop_1000") is None


def test_add_ratios_puts_p50_p99_rate_and_ack_ratios_on_the_tls_row():
    results = {
        "command_1000": _row(990.0, 2.0, 8.0, ack_p50_ms=1.0, ack_p99_ms=4.0),
        "command_1000_tls": _row(900.0, 2.5, 10.0, ack_p50_ms=1.5, ack_p99_ms=4.0),
        "teleop_1000_tls": _row(995.0, 12.0, 40.0),  # its twin did not run
    }
    ratios = report.add_ratios(results)
    expected = {"p50": 1.25, "p99": 1.25, "delivered": 0.91, "ack_p50": 1.5, "ack_p99": 1.0}
    assert results["command_1000_tls"]["ratio_vs_plaintext"] == expected
    assert ratios == {"command_1000_tls": {"plaintext": expected}}
    assert "ratio_vs_plaintext" not in results["teleop_1000_tls"]
    assert "ratio_vs_plaintext" not in results["command_1000"]
    table = report.table(results)
    assert "Mutual TLS / plaintext" in table
    assert "command_1000_tls / command_1000: p50 x1.25, p99 x1.25, delivered x0.91" in table


def test_the_tls_goal_is_p99_within_1_2_x_the_plaintext_twin_of_the_same_run():
    results = {"command_1000_tls": _row(990.0, 2.0, 9.0)}
    assert goals.goal_for("command_1000_tls").p99_vs == ("command_1000", 1.2)
    assert goals.goal_for("teleop_1000_tls").p99_vs == ("teleop_1000", 1.2)
    assert goals.judge("command_1000_tls", results)["misses"] == [
        "command_1000 not measured in this run"]
    results["command_1000"] = _row(995.0, 2.0, 8.0)
    assert goals.judge("command_1000_tls", results)["pass"] is True  # 9 <= 1.2 x 8
    results["command_1000"]["p99_ms"] = 7.0
    assert goals.judge("command_1000_tls", results)["misses"] == [
        "p99 9 ms > 1.2 x 7.000"]
    assert goals.dependents("command_1000") == ["command_1000_tls"]


def test_the_readme_row_shows_the_twin_and_the_p99_ratio():
    document = {"quick": True, "machine": {},
                "teleop_1000": _row(995.0, 12.0, 40.0, mode="pipelined"),
                "teleop_1000_tls": _row(990.0, 13.0, 50.0, mode="pipelined")}
    rows = {line.split("|")[1].strip().strip("`"): [c.strip() for c in line.split("|")[1:-1]]
            for line in readme.table(document).splitlines() if line.startswith("| `")}
    name, what, delivered, p50, p99, goal, result, baselines = rows["teleop_1000_tls"]
    assert what.startswith("`teleop_1000` with mutual TLS")
    assert goal == "p99 ≤ 1.2 x teleop_1000 (medians of interleaved pairs)"
    assert result.startswith("**FAIL**")  # no pairs: its own p99 over the twin's
    assert baselines == "plaintext 995 Hz, 12.0 / 40.0 (p99 ×1.25)"


def test_teleop_s_tls_row_is_judged_on_the_median_of_its_interleaved_pairs():
    """One pair's p99 moves by more than the bound by itself at 1 kHz on this machine: the
    row passes on the pairs' median, and the page shows each pair's ratio."""
    pairs = [(_row(990.0, 2.0, off), _row(990.0, 2.1, on))
             for off, on in ((4.0, 4.2), (4.0, 6.8), (5.0, 4.5), (4.0, 4.4))]
    results = {"teleop_1000": pairs[0][0], "teleop_1000_tls": report.interleaved(pairs)}
    assert results["teleop_1000_tls"]["overhead_median"]["p99"] == 1.075
    assert goals.judge("teleop_1000_tls", results)["pass"] is True
    results["teleop_1000_tls"]["overhead_median"]["p99"] = 1.25
    assert goals.judge("teleop_1000_tls", results)["misses"] == [
        "p99 median x1.25 > 1.2 (pairs x1.05, x1.70, x0.90, x1.10)"]
    row = [line for line in readme.table({"quick": True, "machine": {}, **results}).splitlines()
           if line.startswith("| `teleop_1000_tls`")][0]
    assert "medians of 4 interleaved pairs: delivered ×1.00" in row
    assert "p99 ×1.25 (×1.05 ×1.70 ×0.90 ×1.10)" in row


def test_a_worker_presents_the_identity_it_is_given_only_for_a_tls_station():
    assert worker._channel_security({"address": "x"}) == {}
    assert worker._channel_security({"tls_dir": "/pki", "identity": "admin"}) == {
        "security": ChannelSecurity(Path("/pki"), "admin")}
