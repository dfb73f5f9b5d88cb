"""bench/estop_probe.py measures what it says: the Stop answer carries the time the interceptor
saw the call arrive, which is after it was sent and before it was answered, under a real load."""

from __future__ import annotations

import re

import pytest

from bench import estop_probe


def test_the_interceptor_notes_only_stops():
    seen = estop_probe._Seen()
    seen.stop_arrived(estop_probe.WORK)
    assert seen.at_ns == 0
    seen.stop_arrived(estop_probe.STOP)
    answered = estop_probe.Timestamp.FromString(seen.answer(b"", None))
    assert answered.ToNanoseconds() == seen.at_ns > 0


@pytest.mark.e2e  # a server and a load process
def test_the_floods_are_served_and_every_stop_is_seen_before_its_answer(capsys):
    assert estop_probe.main(["--trials", "5", "--kinds", "sync-flood", "aio-flood"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert [line.split()[0] for line in lines] == ["sync-flood", "aio-flood"]
    for line in lines:
        rate = float(re.search(r"under +([\d.]+) Work", line).group(1))
        seen_p50, seen_p99, answered_p50, answered_p99 = (
            float(v) for v in re.findall(r"p\d\d ([\d.]+)", line))
        assert rate > 100  # the load really ran beside the stops
        assert 0 < seen_p50 <= seen_p99
        assert seen_p50 < answered_p50 and seen_p99 <= answered_p99
