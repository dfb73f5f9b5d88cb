"""bench/profile.py's summary of py-spy's raw stacks (no py-spy run here)."""

from __future__ import annotations

from bench.profile import summarize

RAW = """\
Thread 1 (idle);run (threading.py:1);serve (services/a.py:10);move (services/b.py:20) 6
Thread 1 (idle);run (threading.py:1);serve (services/a.py:10) 2
Thread 2;run (threading.py:1);read (services/c.py:5);move (services/b.py:21) 2
"""


def test_shares_are_of_all_samples_inclusive_once_per_stack_and_self_on_top(tmp_path):
    path = tmp_path / "profile_x.txt"
    path.write_text(RAW)
    text = summarize(path)
    assert text.startswith("10 samples holding the GIL")
    inclusive, own = text.split("self:")
    assert "100.0%  run (threading.py)" in inclusive
    assert "80.0%  serve (a.py)" in inclusive and "80.0%  move (b.py)" in inclusive
    assert "80.0%  move (b.py)" in own and "20.0%  serve (a.py)" in own
    assert "read (c.py)" not in own


def test_an_empty_recording_says_so(tmp_path):
    path = tmp_path / "profile_x.txt"
    path.write_text("")
    assert summarize(path) == "no samples"
