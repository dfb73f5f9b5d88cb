"""bench/probes/estop.py measures what it says: each stop is seen by the server after it was
sent and before it was answered, under a load the server really serves."""

from __future__ import annotations

import re

import pytest

from bench.probes import estop as estop_probe


def test_the_interceptor_notes_only_stops():
    seen = estop_probe._Seen()
    seen.noted("/telerobot.v1.ProxyRobot/GetState")
    assert seen.times_ns == []
    seen.noted(estop_probe.STOP)
    assert len(seen.times_ns) == 1 and seen.times_ns[0] > 0


@pytest.mark.e2e  # servers and loads in processes of their own
def test_every_stop_is_seen_before_its_answer_under_a_real_load(capsys):
    kinds = ["bare-paced", "aio-servicer", "stack-saturated", "aio-stack"]
    assert estop_probe.main(["--trials", "5", "--kinds", *kinds, "--tenant", "0.1"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert [line.split()[0] for line in lines] == kinds
    for line in lines:
        rate = float(re.search(r"under +([\d.]+) GetState", line).group(1))
        seen_p50, seen_p99, answered_p50, answered_p99 = (
            float(v) for v in re.findall(r"p\d\d ([\d.]+)", line))
        assert rate > 100  # the load really ran beside the stops
        assert "tenant 0.10" in line
        assert 0 < seen_p50 <= seen_p99
        assert seen_p50 < answered_p50 and seen_p99 <= answered_p99
