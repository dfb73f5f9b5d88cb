"""Where each service serves its Prometheus metrics: a fixed port per service on loopback, so
Prometheus can scrape a station without reading its ready lines; a free port when the service's
own port is free (the tests run many stations at once); the flag or the variable over both; and
the table on the Operations page says the same."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from services.launcher import GRPC_CHILDREN
from services.runtime.config import (
    DEFAULT_METRICS_PORTS,
    FREE_METRICS_ADDRESS,
    METRICS_OFF,
    base_parser,
)
from services.runtime.process import check_metrics_address
from wire.addresses import DEFAULT_HOST, DEFAULT_PORTS, env_name

OPERATIONS = Path(__file__).resolve().parents[2] / "docs" / "operations.md"


@pytest.fixture(autouse=True)
def no_addresses_set(monkeypatch):
    for name in DEFAULT_PORTS:
        for setting in ("address", "metrics_address"):
            monkeypatch.delenv(env_name(name, setting), raising=False)


def metrics_address(service: str, *argv: str) -> str:
    return base_parser(service, "").parse_args(list(argv)).metrics_address


def test_every_grpc_service_has_a_fixed_metrics_port_on_loopback():
    assert set(DEFAULT_METRICS_PORTS) == set(GRPC_CHILDREN)
    for service in GRPC_CHILDREN:
        assert metrics_address(service) == f"{DEFAULT_HOST}:{DEFAULT_METRICS_PORTS[service]}"
    ports = list(DEFAULT_METRICS_PORTS.values())
    assert len(set(ports)) == len(ports)
    taken = {*DEFAULT_PORTS.values(), *range(50050, 50081), 8765, 9100}  # 9100: node_exporter
    assert not taken & set(ports)


def test_a_service_on_a_free_port_serves_its_metrics_on_a_free_port(monkeypatch):
    assert metrics_address("decision_server", "--address", "127.0.0.1:0") == FREE_METRICS_ADDRESS
    assert metrics_address("proxy_robot", "--address", "[::1]:0") == FREE_METRICS_ADDRESS
    monkeypatch.setenv(env_name("world", "address"), "127.0.0.1:0")  # as the tests' stations
    assert metrics_address("world") == FREE_METRICS_ADDRESS
    assert FREE_METRICS_ADDRESS == f"{DEFAULT_HOST}:0"


def test_the_flag_or_the_variable_says_where(monkeypatch):
    assert metrics_address("force_sensor", "--address", "127.0.0.1:0",
                           "--metrics-address", "127.0.0.1:9453") == "127.0.0.1:9453"
    assert metrics_address("force_sensor", "--metrics-address", METRICS_OFF) == METRICS_OFF
    monkeypatch.setenv(env_name("force_sensor", "metrics_address"), "127.0.0.1:19000")
    assert metrics_address("force_sensor", "--address", "127.0.0.1:0") == "127.0.0.1:19000"
    assert metrics_address("force_sensor", "--metrics-address", "[::1]:9") == "[::1]:9"


def test_a_service_beyond_loopback_keeps_its_metrics_on_loopback():
    chosen = metrics_address("decision_server", "--address", "0.0.0.0:50051", "--tls-dir", "x")
    assert chosen == f"{DEFAULT_HOST}:{DEFAULT_METRICS_PORTS['decision_server']}"
    check_metrics_address(chosen, allow_network=False)  # the loopback rule: no refusal


def test_the_operations_page_lists_each_default_port():
    text = OPERATIONS.read_text()
    rows = dict(re.findall(r"^\| `?(\w+)`? \| `?127\.0\.0\.1:(\d+)`? \|", text, re.MULTILINE))
    assert {name: int(port) for name, port in rows.items()
            if name in DEFAULT_METRICS_PORTS} == DEFAULT_METRICS_PORTS
