"""bench.worldloop: the world loop's counters between two reads, as a percentage."""

from __future__ import annotations

from bench import worldloop


def test_delta_counts_between_two_reads_and_the_overrun_percentage():
    before = {"steps": 1000, "overruns": 10, "dropped_steps": 0}
    after = {"steps": 21000, "overruns": 30, "dropped_steps": 4}
    assert worldloop.delta(before, after) == {"steps": 20000, "overruns": 20,
                                              "dropped_steps": 4, "overrun_pct": 0.1}


def test_no_step_taken_has_no_percentage():
    same = {"steps": 5, "overruns": 1, "dropped_steps": 0}
    assert worldloop.delta(same, same)["overrun_pct"] is None
    assert worldloop.with_pct({"steps": 0, "overruns": 0, "dropped_steps": 0})[
        "overrun_pct"] is None
