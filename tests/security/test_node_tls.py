"""The Node.js client (clients/node/client.js) against a real station with mutual TLS: it reads
over mTLS with the Python clients' environment (TELEROBOT_TLS_DIR, TELEROBOT_IDENTITY,
TELEROBOT_TOKEN) or the --tls-dir/--identity flags, and a plaintext client or certificates of
another CA fail the handshake cleanly (exit 1 with a JSON error, no stack trace)."""

from __future__ import annotations

import json
import os
import shutil
import signal
import subprocess
from dataclasses import dataclass
from pathlib import Path

import pytest

from services.runtime.children import refused_address
from services.runtime.process import token_port_name
from services.security import pki
from services.security.roles import Role
from services.security.tokens import TokenStore
from telerobot.v1 import proxy_robot_pb2, proxy_robot_pb2_grpc
from tests.processes import REPO, start_station, station_env
from wire.tls import IDENTITY_ENV, TLS_DIR_ENV, TOKEN_ENV, ChannelSecurity, open_channel

pytestmark = pytest.mark.e2e

SERVING = {"(server)": "SERVING", "telerobot.v1.ProxyRobot": "SERVING"}
ARM_UP = ("ROBOT_STATUS_CONNECTED", "ROBOT_STATUS_READY", "ROBOT_STATUS_MOVING")
CLIENT_ENV = (TLS_DIR_ENV, IDENTITY_ENV, TOKEN_ENV)
# The DecisionServer logs its token port (and, newer, reports it on a ready line).


@dataclass
class TlsStation:
    pki: Path  # the station's CA and certificates
    other_pki: Path  # a second CA the station does not trust
    decision_server: str
    proxy_robot: str
    token_address: str
    tokens: TokenStore


@pytest.fixture(scope="module")
def tls_station(tmp_path_factory):
    base = tmp_path_factory.mktemp("node_tls")
    pki.init(base / "pki")
    pki.init(base / "other_pki")
    tokens = base / "tokens.json"
    launcher = start_station(station_env(
        TELEROBOT_TLS_DIR=str(base / "pki"), TELEROBOT_AUDIT_DIR=str(base / "audit"),
        TELEROBOT_DECISION_SERVER_TOKEN_ADDRESS="127.0.0.1:0",
        TELEROBOT_TOKENS_FILE=str(tokens)))
    try:
        # Printed before the DecisionServer's own ready line, which start_station waited for.
        token_address = launcher.ready[token_port_name("decision_server")]
        station = TlsStation(base / "pki", base / "other_pki", launcher.ready["decision_server"],
                             launcher.ready["proxy_robot"], token_address, TokenStore(tokens))
        # Connect the arm (as admin: the inner port takes commands only from the station or an
        # admin), so that GetState answers with a state rather than FAILED_PRECONDITION.
        with open_channel(station.proxy_robot,
                          security=ChannelSecurity(station.pki, "admin")) as channel:
            proxy_robot_pb2_grpc.ProxyRobotStub(channel).Connect(
                proxy_robot_pb2.ConnectRequest(), timeout=10)
        yield station
    finally:
        launcher.stop(signal.SIGINT)


def _node(*args: str, **env: str) -> subprocess.CompletedProcess:
    """`node clients/node/client.js ARGS` with the client's credentials only from `env`."""
    clean = {k: v for k, v in os.environ.items() if k not in CLIENT_ENV}
    return subprocess.run(["node", "clients/node/client.js", *args], cwd=REPO,
                          env={**clean, **env}, capture_output=True, text=True, timeout=30)


def _reads(result: subprocess.CompletedProcess) -> dict:
    """The report of a client that read everything: health SERVING, status and state."""
    assert result.returncode == 0, result.stdout + result.stderr
    assert result.stderr == ""  # no warnings (e.g. Node's about an IP as TLS server name)
    report = json.loads(result.stdout)
    assert report["health"] == SERVING, report
    assert report["status"]["ok"], report["status"]
    assert report["status"]["reply"]["status"] in ARM_UP, report["status"]
    assert report["state"]["ok"], report["state"]
    assert len(report["state"]["reply"]["state"]["joint_positions_rad"]) == 6
    return report


def _refused(result: subprocess.CompletedProcess, address: str) -> str:
    """The error of a client that could not get through: exit 1, one JSON line, no trace."""
    assert result.returncode == 1, result.stdout + result.stderr
    assert "    at " not in result.stdout + result.stderr  # no JavaScript stack trace
    report = json.loads(result.stdout)
    assert sorted(report) == ["address", "error"] and report["address"] == address, report
    return report["error"]


@pytest.mark.parametrize("identity", ["observer", "operator"])
@pytest.mark.parametrize("service", ["decision_server", "proxy_robot"])
def test_node_client_reads_over_mutual_tls(tls_station, service, identity):
    address = getattr(tls_station, service)
    report = _reads(_node(address, TELEROBOT_TLS_DIR=str(tls_station.pki),
                          TELEROBOT_IDENTITY=identity))
    assert report["address"] == address


def test_node_client_identity_defaults_to_operator(tls_station):
    _reads(_node(tls_station.decision_server, TELEROBOT_TLS_DIR=str(tls_station.pki)))


def test_flags_override_the_environment(tls_station):
    # The environment names a directory of the wrong CA and an identity that has no
    # certificate; the flags win.
    _reads(_node(tls_station.proxy_robot, "--tls-dir", str(tls_station.pki),
                 "--identity", "observer", TELEROBOT_TLS_DIR=str(tls_station.other_pki),
                 TELEROBOT_IDENTITY="nobody"))


def test_a_bearer_token_over_tls_on_the_token_port(tls_station):
    token = tls_station.tokens.issue("node-observer", Role.OBSERVER, ttl_s=600)
    _reads(_node(tls_station.token_address, TELEROBOT_TLS_DIR=str(tls_station.pki),
                 TELEROBOT_TOKEN=token))


def test_a_bearer_token_on_the_mutual_tls_port_fails_the_handshake(tls_station):
    # With a token the client presents no certificate, which the main port requires.
    token = tls_station.tokens.issue("node-observer", Role.OBSERVER, ttl_s=600)
    address = tls_station.decision_server
    error = _refused(_node(address, TELEROBOT_TLS_DIR=str(tls_station.pki),
                           TELEROBOT_TOKEN=token), address)
    assert "TLS handshake failed" in error


def test_plaintext_against_the_tls_station_fails_cleanly(tls_station):
    address = tls_station.decision_server
    error = _refused(_node(address), address)
    assert f"cannot reach {address}" in error and TLS_DIR_ENV in error


def test_another_ca_fails_the_handshake(tls_station):
    # Its ca.pem does not sign the station's server certificate: the client refuses.
    address = tls_station.decision_server
    error = _refused(_node(address, TELEROBOT_TLS_DIR=str(tls_station.other_pki)), address)
    assert "TLS handshake failed" in error and "certificate" in error


def test_a_client_certificate_of_another_ca_fails_the_handshake(tls_station, tmp_path):
    # The client trusts the station's CA but presents a certificate another CA signed: the
    # server refuses it.
    shutil.copy(tls_station.pki / "ca.pem", tmp_path / "ca.pem")
    for suffix in (".pem", ".key"):
        shutil.copy(tls_station.other_pki / f"operator{suffix}", tmp_path / f"operator{suffix}")
    address = tls_station.proxy_robot
    error = _refused(_node(address, TELEROBOT_TLS_DIR=str(tmp_path)), address)
    assert "TLS handshake failed" in error


def test_a_missing_certificate_is_reported_not_thrown(tls_station):
    address = tls_station.decision_server
    error = _refused(_node(address, "--identity", "nobody",
                           TELEROBOT_TLS_DIR=str(tls_station.pki)), address)
    assert "nobody.key" in error and "make certs" in error


def test_an_unreachable_server_over_tls(tls_station):
    address = refused_address()
    error = _refused(_node(address, TELEROBOT_TLS_DIR=str(tls_station.pki)), address)
    assert f"cannot reach {address}" in error
