"""clients.teleop.stack.station_at without processes: it uses a station that answers and starts
one (local_station) only when none does."""

from __future__ import annotations

import contextlib

import pytest

from clients.teleop import stack


@pytest.fixture
def started(monkeypatch):
    """Replaces local_station: records the operator address asked for, starts nothing."""
    calls: list[str | None] = []
    up: set[str] = set()

    @contextlib.contextmanager
    def fake_local_station(operator_address=None, env=None):
        calls.append(operator_address)
        up.add(operator_address)
        yield {"decision_server": operator_address}

    monkeypatch.setattr(stack, "local_station", fake_local_station)
    monkeypatch.setattr(stack, "serving", lambda address, timeout_s=1.0: address in up)
    return calls, up


def test_a_station_that_answers_is_used_as_it_is(started):
    calls, up = started
    up.add("127.0.0.1:7001")
    with stack.station_at("127.0.0.1:7001", log=lambda _: None) as local:
        assert local is False
    assert calls == []


def test_without_a_station_one_is_started_at_the_address_asked(started):
    calls, _ = started
    said: list[str] = []
    with stack.station_at("127.0.0.1:7002", log=said.append) as local:
        assert local is True
    assert calls == ["127.0.0.1:7002"]
    assert said == ["nothing answers at 127.0.0.1:7002: starting a local slave station"]


def test_a_started_station_that_does_not_answer_there_is_an_error(started, monkeypatch):
    monkeypatch.setattr(stack, "serving", lambda address, timeout_s=1.0: False)
    with pytest.raises(RuntimeError, match="nothing answers at 127.0.0.1:7003"):
        with stack.station_at("127.0.0.1:7003", log=lambda _: None):
            pass
