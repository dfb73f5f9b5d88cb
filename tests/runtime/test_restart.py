"""The restart policy: capped exponential back-off, a limit per window, failures forgotten."""

from pathlib import Path

from services.runtime.restart import RestartPolicy, RestartTracker
from services.runtime.supervisor_state import (
    RESTARTING,
    SUPERVISOR_STATE_ENV,
    ChildState,
    read_state,
    write_state,
)


def test_back_off_doubles_up_to_its_cap_then_gives_up():
    tracker = RestartTracker(RestartPolicy(first_delay_s=0.1, max_delay_s=0.3, max_failures=5,
                                           window_s=60))
    delays = [tracker.failed(now) for now in (0, 1, 2, 3)]
    assert delays == [0.1, 0.2, 0.3, 0.3]
    assert tracker.failed(4) is None  # the fifth within the window


def test_failures_older_than_the_window_are_forgotten():
    tracker = RestartTracker(RestartPolicy(first_delay_s=0.1, max_failures=3, window_s=10))
    assert tracker.failed(0) == 0.1
    assert tracker.failed(5) == 0.2
    assert tracker.failed(20) == 0.1  # both earlier ones are out of the window: a fresh start
    assert tracker.failed(21) == 0.2
    assert tracker.failed(22) is None


def test_the_state_file_round_trips_and_a_missing_one_is_empty(tmp_path, monkeypatch):
    path = tmp_path / "run" / "supervisor.json"
    state = {"force_sensor": ChildState(RESTARTING, 2, "was killed by signal 9 (SIGKILL)", 1.0)}
    write_state(path, state)
    assert read_state(path) == state
    monkeypatch.setenv(SUPERVISOR_STATE_ENV, str(path))
    assert read_state() == state
    assert read_state(Path(tmp_path / "none.json")) == {}
    path.write_text("{not json")
    assert read_state(path) == {}
