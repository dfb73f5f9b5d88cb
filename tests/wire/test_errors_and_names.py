"""wire.errors, wire.metadata and wire.addresses: the names both sides must agree on."""

from __future__ import annotations

import pytest

import clients.python
from services.runtime.lanes import Lane
from wire import errors
from wire.addresses import DEFAULT_HOST, DEFAULT_PORTS, address_for, env_name
from wire.metadata import LANE_METADATA_KEY, LANES, LEASE_METADATA_KEY

STATUS_CLASSES = errors.TelerobotError.__subclasses__()


def test_the_clients_raise_the_errors_the_services_raise():
    assert clients.python.TelerobotError is errors.TelerobotError
    for cls in STATUS_CLASSES:
        assert getattr(clients.python, cls.__name__) is cls


@pytest.mark.parametrize("cls", STATUS_CLASSES, ids=lambda cls: cls.__name__)
def test_error_for_status_gives_the_class_of_each_status(cls):
    error = errors.error_for_status(cls.status_name, "try again", "SOME_REASON")
    assert type(error) is cls and error.message == "try again"
    assert error.reason == "SOME_REASON"
    assert str(error) == f"{cls.status_name} [SOME_REASON]: try again"
    assert errors.error_for_status(cls.status_name, "m").reason is None


def test_status_names_are_unique_and_an_unknown_one_is_kept():
    names = [cls.status_name for cls in STATUS_CLASSES]
    assert len(names) == len(set(names))
    error = errors.error_for_status("DATA_LOSS", "lost")
    assert type(error) is errors.TelerobotError and error.status_name == "DATA_LOSS"


def test_metadata_names_match_the_services():
    assert LANES == tuple(lane.name.lower() for lane in sorted(Lane))
    assert LANE_METADATA_KEY == "telerobot-lane"  # the names the protos' comments document
    assert LEASE_METADATA_KEY == "telerobot-lease-id"


def test_addresses_default_to_loopback_and_follow_the_environment(monkeypatch):
    assert env_name("proxy_robot", "address") == "TELEROBOT_PROXY_ROBOT_ADDRESS"
    monkeypatch.delenv("TELEROBOT_FORCE_SENSOR_ADDRESS", raising=False)
    assert address_for("force_sensor") == f"{DEFAULT_HOST}:{DEFAULT_PORTS['force_sensor']}"
    monkeypatch.setenv("TELEROBOT_FORCE_SENSOR_ADDRESS", "10.0.0.2:6000")
    assert address_for("force_sensor") == "10.0.0.2:6000"
    with pytest.raises(KeyError, match="known: world"):
        address_for("nonsense")
    assert len(set(DEFAULT_PORTS.values())) == len(DEFAULT_PORTS)
