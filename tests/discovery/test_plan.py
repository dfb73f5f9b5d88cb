"""Which addresses a station's advertisement names, and when there is none: no packet sent."""

from __future__ import annotations

import pytest

from discovery.advertise import STATION_NAME_ENV, plan
from discovery.interfaces import host_addresses, listen_addresses
from discovery.station import DiscoveryError


def test_an_address_is_itself_a_wildcard_is_every_address_of_its_family():
    assert listen_addresses("10.0.0.2") == ["10.0.0.2"]
    assert listen_addresses("[::1]") == ["::1"]
    every = host_addresses()
    assert "127.0.0.1" in every
    assert listen_addresses("0.0.0.0") == [a for a in every if ":" not in a]
    assert listen_addresses("::") == every
    assert not any(a.lower().startswith("fe80:") for a in every)  # no link-local


def test_a_name_is_what_it_resolves_to():
    assert "127.0.0.1" in listen_addresses("localhost")
    assert listen_addresses("no-such-station.invalid") == []


def test_a_station_on_loopback_is_advertised_only_when_asked(monkeypatch):
    monkeypatch.delenv(STATION_NAME_ENV, raising=False)
    assert plan("127.0.0.1:50051", tls=False) is None
    assert plan("localhost:50051", tls=False) is None
    forced = plan("127.0.0.1:50051", tls=False, mode="1", host_name="slave.example")
    assert forced.addresses == ["127.0.0.1"] and forced.interfaces == ["127.0.0.1"]
    assert forced.name == "slave:50051"
    assert forced.info.port == 50051
    assert forced.info.server == "slave.local."


def test_the_advertisement_names_the_listening_addresses_but_not_loopback():
    advertisement = plan("0.0.0.0:50051", tls=True, token_port=50061, mode="1",
                         name="lab-slave", host_name="slave.example")
    expected = [a for a in listen_addresses("0.0.0.0") if a != "127.0.0.1"] or ["127.0.0.1"]
    assert advertisement.addresses == expected
    assert advertisement.info.decoded_properties == {
        "txtvers": "1", "contract": "telerobot.v1", "tls": "1", "station": "lab-slave",
        "host": "slave.example", "token_port": "50061"}
    assert plan("0.0.0.0:50051", tls=True, mode="0") is None


def test_the_name_comes_from_the_environment_unless_given(monkeypatch):
    monkeypatch.setenv(STATION_NAME_ENV, "bench-2")
    assert plan("127.0.0.1:50051", tls=False, mode="1").name == "bench-2"
    assert plan("127.0.0.1:50051", tls=False, mode="1", name="x").name == "x"
    monkeypatch.setenv(STATION_NAME_ENV, "bad.name")
    with pytest.raises(DiscoveryError, match="no dots"):
        plan("127.0.0.1:50051", tls=False, mode="1")


def test_an_ipv6_only_station_cannot_be_advertised_over_ipv4_mdns():
    with pytest.raises(DiscoveryError, match="needs an IPv4 address"):
        plan("[::1]:50051", tls=False, mode="1")
