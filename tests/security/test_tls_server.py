"""One TLS server in process: the certificate it presents is renewed without a restart, and a
server without TLS listens only on loopback unless told otherwise, loudly."""

from __future__ import annotations

import logging
import os
import socket
import ssl

import grpc
import pytest
from cryptography import x509
from cryptography.hazmat.primitives import serialization
from cryptography.hazmat.primitives.asymmetric import ec
from grpc_health.v1 import health_pb2, health_pb2_grpc

from services.runtime.server import (
    PlaintextRefused,
    ServerSecurity,
    binding,
    create_server,
    is_loopback,
)
from services.security.pki import init, issue
from services.security.roles import Role
from services.security.tokens import TokenStore
from telerobot.v1 import proxy_robot_pb2, proxy_robot_pb2_grpc
from tests.conftest import wait_for
from wire.tls import ChannelSecurity, open_channel


@pytest.fixture
def pki(tmp_path):
    init(tmp_path)
    return tmp_path


@pytest.fixture(params=[False, True], ids=["sync", "aio"])
def tls_server(pki, request):
    server, port = create_server("127.0.0.1:0", [],
                                 security=ServerSecurity(pki, "proxy_robot", inner_port=True),
                                 aio=request.param)
    server.start()
    server.set_serving()
    yield port
    server.stop(0)


def served_serial(pki, port: int, identity: str = "operator") -> int:
    """The serial number of the certificate the server presents in a fresh handshake, made
    as a gRPC client would make it (h2, the CA's trust, a client certificate)."""
    context = ssl.create_default_context(cafile=str(pki / "ca.pem"))
    context.load_cert_chain(pki / f"{identity}.pem", pki / f"{identity}.key")
    context.set_alpn_protocols(["h2"])
    with socket.create_connection(("127.0.0.1", port), timeout=5) as raw, \
            context.wrap_socket(raw, server_hostname="localhost") as tls:
        return x509.load_der_x509_certificate(tls.getpeercert(binary_form=True)).serial_number


def test_a_renewed_certificate_is_served_without_a_restart(pki, tls_server):
    first = served_serial(pki, tls_server)
    issue(pki, "proxy_robot", Role.STATION, ["localhost", "127.0.0.1"])
    renewed = x509.load_pem_x509_certificate((pki / "proxy_robot.pem").read_bytes())
    assert renewed.serial_number != first
    wait_for(lambda: served_serial(pki, tls_server) == renewed.serial_number,
             what="the renewed certificate served")


def test_a_half_renewed_pair_is_not_taken(pki, tls_server):
    """A new key without its certificate yet (a renewal half done) leaves the old pair
    served; handshakes keep working."""
    first = served_serial(pki, tls_server)
    stray = ec.generate_private_key(ec.SECP256R1()).private_bytes(
        serialization.Encoding.PEM, serialization.PrivateFormat.PKCS8,
        serialization.NoEncryption())
    (pki / "proxy_robot.key.new").write_bytes(stray)
    os.replace(pki / "proxy_robot.key.new", pki / "proxy_robot.key")
    assert served_serial(pki, tls_server) == first


def test_a_client_certificate_from_another_ca_fails_the_handshake(pki, tls_server, tmp_path):
    init(tmp_path / "foreign")
    for client_pki in (pki, tmp_path / "foreign"):
        security = ChannelSecurity(client_pki, "admin")
        with open_channel(f"127.0.0.1:{tls_server}", security=security) as channel:
            try:
                health_pb2_grpc.HealthStub(channel).Check(health_pb2.HealthCheckRequest(),
                                                          timeout=5)
                code = grpc.StatusCode.OK
            except grpc.RpcError as error:
                code = error.code()
        expected = grpc.StatusCode.OK if client_pki == pki else grpc.StatusCode.UNAVAILABLE
        assert code == expected, client_pki


@pytest.mark.parametrize("address,loopback", [
    ("127.0.0.1:0", True), ("127.5.0.1:0", True), ("localhost:0", True), ("[::1]:0", True),
    ("0.0.0.0:0", False), ("[::]:0", False), ("10.213.7.2:0", False), (":0", False),
    ("myhost:0", False)])
def test_which_addresses_are_loopback(address, loopback):
    assert is_loopback(address) is loopback


def test_plaintext_beyond_loopback_is_refused_unless_allowed_loudly(caplog):
    with pytest.raises(PlaintextRefused, match="make certs"):
        create_server("0.0.0.0:0", [])
    with caplog.at_level(logging.WARNING):
        server, port = create_server("0.0.0.0:0", [], allow_plaintext_network=True)
    try:
        assert port > 0
        assert any("PLAINTEXT beyond loopback" in r.getMessage() for r in caplog.records)
    finally:
        server.stop(0)


@pytest.mark.parametrize("aio", [False, True], ids=["sync", "aio"])
def test_the_early_stop_fires_only_for_callers_the_port_can_identify(pki, tmp_path, aio):
    """An EmergencyStop latches the stop as it arrives, before its handler runs (and so before
    the reply). On the mTLS port the handshake identified everyone; on the token port only a
    valid token does, so an anonymous or forged call must not latch anything."""
    tokens = TokenStore(tmp_path / "tokens.json")
    valid = tokens.issue("dashboard", Role.OBSERVER, 600)
    arrivals = []
    security = ServerSecurity(pki, "decision_server", inner_port=False,
                              token_address="127.0.0.1:0", tokens=tokens)
    unimplemented = proxy_robot_pb2_grpc.ProxyRobotServicer()  # the hook comes before it
    server, port = create_server(
        "127.0.0.1:0", [binding(proxy_robot_pb2_grpc, "ProxyRobot", unimplemented)],
        on_emergency_call=lambda: arrivals.append(1), security=security, aio=aio)
    server.start()
    ca = (pki / "ca.pem").read_bytes()

    def stop(port_, credentials) -> grpc.StatusCode:
        with grpc.secure_channel(f"127.0.0.1:{port_}", credentials) as channel:
            try:
                proxy_robot_pb2_grpc.ProxyRobotStub(channel).EmergencyStop(
                    proxy_robot_pb2.EmergencyStopRequest(), timeout=5)
            except grpc.RpcError as error:
                return error.code()
        return grpc.StatusCode.OK

    def with_token(token):
        return grpc.composite_channel_credentials(grpc.ssl_channel_credentials(ca),
                                                  grpc.access_token_call_credentials(token))

    try:
        assert stop(server.token_port, grpc.ssl_channel_credentials(ca)) \
            == grpc.StatusCode.UNAUTHENTICATED
        assert stop(server.token_port, with_token("trb_" + "A" * 43)) \
            == grpc.StatusCode.UNAUTHENTICATED
        assert arrivals == []
        assert stop(server.token_port, with_token(valid)) == grpc.StatusCode.UNIMPLEMENTED
        assert arrivals == [1]
        operator = ChannelSecurity(pki, "observer").credentials()
        assert stop(port, operator) == grpc.StatusCode.UNIMPLEMENTED
        assert arrivals == [1, 1]
    finally:
        server.stop(0)


def test_a_client_never_sends_a_token_in_plaintext():
    with pytest.raises(ValueError, match="only over TLS"):
        open_channel("127.0.0.1:1", security=ChannelSecurity(token="trb_secret"))


def test_a_server_on_every_address_is_reached_over_tls_at_its_wildcard_address(pki):
    """A station bound to 0.0.0.0 checks its services at the address they bound; no
    certificate names 0.0.0.0, so the client dials loopback instead (wire.tls.dialable)."""
    server, port = create_server("0.0.0.0:0", [],
                                 security=ServerSecurity(pki, "proxy_robot", inner_port=True))
    server.start()
    server.set_serving()
    try:
        with open_channel(f"0.0.0.0:{port}", security=ChannelSecurity(pki, "launcher")) as channel:
            reply = health_pb2_grpc.HealthStub(channel).Check(health_pb2.HealthCheckRequest(),
                                                              timeout=10)
        assert reply.status == health_pb2.HealthCheckResponse.SERVING
    finally:
        server.stop(0)
