"""What a station's advertisement says and how an operator picks one: pure, no network."""

from __future__ import annotations

import pytest

from discovery.station import (
    CONTRACT,
    SERVICE_TYPE,
    DiscoveryError,
    Station,
    check_station_name,
    default_station_name,
    join_host_port,
    pick,
    should_advertise,
    split_host_port,
    station_from_record,
    txt_properties,
)


def station(name: str, contract: str = CONTRACT, **fields) -> Station:
    return Station(name=name, addresses=fields.pop("addresses", ("10.0.0.2",)),
                   port=fields.pop("port", 50051), tls=fields.pop("tls", True),
                   contract=contract, **fields)


def test_the_contract_is_the_protos_package_and_the_type_is_telerobot_tcp():
    assert CONTRACT == "telerobot.v1"
    assert SERVICE_TYPE == "_telerobot._tcp.local."


def test_txt_properties_read_back_into_the_same_station():
    properties = txt_properties("lab-slave", tls=True, token_port=50061, host="slave.example")
    assert properties == {"txtvers": "1", "contract": "telerobot.v1", "tls": "1",
                          "station": "lab-slave", "host": "slave.example",
                          "token_port": "50061"}
    found = station_from_record("lab-slave", ["fd00::2", "10.0.0.2"], 50051, properties)
    assert found == Station("lab-slave", ("10.0.0.2", "fd00::2"), 50051, True, "telerobot.v1",
                            50061, "slave.example")
    assert found.address == "10.0.0.2:50051"  # IPv4 first
    assert found.describe() == ("lab-slave  10.0.0.2:50051, [fd00::2]:50051  TLS  telerobot.v1"
                                "  tokens on port 50061")


def test_without_tls_or_a_token_port_the_properties_say_so():
    properties = txt_properties("s", tls=False, token_port=None, host="h")
    assert properties["tls"] == "0" and "token_port" not in properties
    found = station_from_record("s", ["10.0.0.2"], 50051, properties)
    assert not found.tls and found.token_port is None
    assert found.describe() == "s  10.0.0.2:50051  plaintext  telerobot.v1"


@pytest.mark.parametrize("properties", [
    {}, {"tls": "yes", "token_port": "x"}, {"token_port": "70000"}, {"token_port": "0"},
    {"contract": None, "tls": None},
])
def test_missing_or_malformed_properties_read_as_unknown_never_as_an_error(properties):
    found = station_from_record("s", ["10.0.0.2"], 50051, properties)
    assert (found.tls, found.token_port) == (False, None)
    assert found.contract == ""


def test_pick_the_only_station_or_one_by_name():
    only = station("lab-slave")
    assert pick([only]) is only
    assert pick([only], "lab-slave") is only
    other = station("other", addresses=("10.0.0.3",))
    assert pick([only, other], "other") is other


def test_pick_says_when_there_is_no_station():
    with pytest.raises(DiscoveryError, match="no slave station found.*--advertise.*5353"):
        pick([])
    with pytest.raises(DiscoveryError, match="no slave station found"):
        pick([], "lab-slave")


def test_pick_without_a_name_refuses_to_guess_between_several():
    with pytest.raises(DiscoveryError,
                       match=r"2 slave stations found \('a', 'b'\): name the one to use"):
        pick([station("b"), station("a")])


def test_pick_names_what_it_found_when_the_name_is_not_there():
    with pytest.raises(DiscoveryError,
                       match=r"no slave station called 'lab'\. Found: a  10\.0\.0\.2:50051"):
        pick([station("a")], "lab")


def test_pick_refuses_a_station_of_another_contract():
    with pytest.raises(DiscoveryError, match="'old' speaks telerobot.v0, this operator "
                                             "station telerobot.v1"):
        pick([station("old", "telerobot.v0")], "old")
    with pytest.raises(DiscoveryError, match="no slave station speaks telerobot.v1"):
        pick([station("old", "telerobot.v0")])
    # Without a name, one of another contract is no candidate, so the other is the only one.
    current = station("new")
    assert pick([station("old", "telerobot.v0"), current]) is current


def test_pick_refuses_two_responders_answering_for_one_name():
    with pytest.raises(DiscoveryError, match="2 slave stations answer as 'a'"):
        pick([station("a"), station("a", addresses=("10.0.0.9",))], "a")


def test_a_station_without_an_address_says_so():
    with pytest.raises(DiscoveryError, match="announced no address"):
        _ = station("a", addresses=()).address


@pytest.mark.parametrize("addresses, mode, expected", [
    (["127.0.0.1"], "auto", False),  # loopback only: meaningless to other hosts
    (["127.0.0.1", "::1"], "auto", False),
    (["127.0.0.1", "10.0.0.2"], "auto", True),
    (["10.0.0.2"], "auto", True),
    (["127.0.0.1"], "1", True),
    (["10.0.0.2"], "0", False),
    ([], "1", False),  # nothing to name
])
def test_should_advertise(addresses, mode, expected):
    assert should_advertise(addresses, mode) is expected


def test_an_unknown_advertise_mode_is_an_error():
    with pytest.raises(DiscoveryError, match="1, 0 or auto, not 'yes'"):
        should_advertise(["10.0.0.2"], "yes")


def test_the_default_name_is_the_short_host_name_and_the_port():
    assert default_station_name("slave.lab.example", 50051) == "slave:50051"
    assert default_station_name("", 50051) == "telerobot:50051"


@pytest.mark.parametrize("name", ["", "a.b", "x" * 64, "tab\there"])
def test_names_dns_sd_cannot_carry_are_refused(name):
    with pytest.raises(DiscoveryError, match="a station name"):
        check_station_name(name)


def test_host_port_with_ipv6_brackets():
    assert join_host_port("fd00::2", 50051) == "[fd00::2]:50051"
    assert split_host_port("[fd00::2]:50051") == ("fd00::2", 50051)
    assert split_host_port("0.0.0.0:0") == ("0.0.0.0", 0)
    with pytest.raises(DiscoveryError, match="expected host:port"):
        split_host_port("slave")
