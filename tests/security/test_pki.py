"""The development PKI: what `make certs` writes, and identities read back from certificates."""

import asyncio
import stat
import subprocess
import sys

import grpc
import pytest
from cryptography import x509
from grpc_health.v1 import health_pb2, health_pb2_grpc

from services.runtime.server import ServerSecurity, create_server
from services.security.pki import (
    CLIENT_IDENTITIES,
    STATION_SERVICES,
    VIEWER_SERVICES,
    CertificateError,
    identity_of,
    init,
    issue,
)
from services.security.roles import Role
from tests.processes import REPO
from wire.tls import ChannelSecurity, open_channel, server_name


@pytest.fixture(scope="module")
def pki(tmp_path_factory):
    directory = tmp_path_factory.mktemp("pki")
    init(directory, hosts=["10.213.0.2", "slave.example"])
    return directory


def test_it_writes_a_ca_a_pair_per_service_and_per_identity_with_private_keys(pki):
    names = ["ca", *STATION_SERVICES, *CLIENT_IDENTITIES]
    for name in names:
        assert (pki / f"{name}.pem").exists()
        assert stat.S_IMODE((pki / f"{name}.key").stat().st_mode) == 0o600
    assert not list(pki.glob(".*.tmp"))


def test_identities_and_roles_come_from_cn_and_ou(pki):
    for name, role in CLIENT_IDENTITIES.items():
        identity = identity_of((pki / f"{name}.pem").read_bytes())
        assert (identity.name, identity.role) == (name, role)
    assert identity_of((pki / "proxy_robot.pem").read_bytes()).role is Role.STATION


def test_the_consoles_certificate_serves_https_and_is_no_client(pki):
    certificate = x509.load_pem_x509_certificate((pki / "web_console.pem").read_bytes())
    usages = certificate.extensions.get_extension_for_class(x509.ExtendedKeyUsage).value
    assert list(usages) == [x509.ExtendedKeyUsageOID.SERVER_AUTH]
    names = certificate.extensions.get_extension_for_class(x509.SubjectAlternativeName).value
    assert "127.0.0.1" in {str(ip) for ip in names.get_values_for_type(x509.IPAddress)}


def test_service_certificates_name_every_address_they_answer_on(pki):
    cert = x509.load_pem_x509_certificate((pki / "decision_server.pem").read_bytes())
    names = cert.extensions.get_extension_for_class(x509.SubjectAlternativeName).value
    ips = {str(ip) for ip in names.get_values_for_type(x509.IPAddress)}
    assert {"127.0.0.1", "::1", "10.213.0.2"} <= ips
    assert {"localhost", "slave.example"} <= set(names.get_values_for_type(x509.DNSName))
    issuer = x509.load_pem_x509_certificate((pki / "ca.pem").read_bytes())
    cert.verify_directly_issued_by(issuer)


def _dns_names(path) -> list[str]:
    cert = x509.load_pem_x509_certificate(path.read_bytes())
    names = cert.extensions.get_extension_for_class(x509.SubjectAlternativeName).value
    return names.get_values_for_type(x509.DNSName)


def test_each_service_certificate_names_its_own_service_and_no_other(pki):
    services = [*STATION_SERVICES, *VIEWER_SERVICES]
    assert server_name("decision_server") == "decision-server.telerobot.internal"
    for service in services:
        names = _dns_names(pki / f"{service}.pem")
        assert names[0] == server_name(service), service
        others = {server_name(other) for other in services if other != service}
        assert not others & set(names), service


def test_a_renewed_service_certificate_keeps_its_name_and_a_name_that_cannot_be_one_is_refused(
        tmp_path):
    init(tmp_path)
    issue(tmp_path, "proxy_robot", Role.STATION, ["localhost", "proxy-robot.telerobot.internal"])
    assert _dns_names(tmp_path / "proxy_robot.pem") == ["proxy-robot.telerobot.internal",
                                                        "localhost"]
    # "decision-server" would carry the DecisionServer's name: a service's name has no '-'.
    for name in ("decision-server", "Decision_Server", "_x", "x" * 64):
        with pytest.raises(ValueError, match="server name"):
            issue(tmp_path, name, Role.STATION, ["localhost"])
        assert not (tmp_path / f"{name}.pem").exists()
    issue(tmp_path, "ci-script", Role.OPERATOR)  # a client certificate takes any name


def _health(address: str, security: ChannelSecurity, service: str | None, aio: bool):
    """A health check through `open_channel`; raises grpc.RpcError (aio's too)."""
    request = health_pb2.HealthCheckRequest()
    if not aio:
        with open_channel(address, security=security, service=service) as channel:
            health_pb2_grpc.HealthStub(channel).Check(request, timeout=10)
        return

    async def check():
        async with open_channel(address, security=security, service=service,
                                aio=True) as channel:
            await health_pb2_grpc.HealthStub(channel).Check(request, timeout=10)

    asyncio.run(check())


@pytest.mark.parametrize("aio", [False, True], ids=["sync", "aio"])
def test_a_client_dialing_the_decision_server_refuses_the_live_views_certificate(pki, aio):
    """The live view's certificate (role observer, the same CA, the same host names) served
    where the DecisionServer should be: a client that asks for the DecisionServer fails the
    handshake; the DecisionServer's own certificate passes. Without the service, a host name
    is all that is checked, and the impostor passes."""
    def check(server_as: str, service: str | None) -> grpc.StatusCode:
        server, port = create_server("127.0.0.1:0", [], security=ServerSecurity(pki, server_as))
        server.start()
        server.set_serving()
        try:
            _health(f"127.0.0.1:{port}", ChannelSecurity(pki, "operator"), service, aio)
            return grpc.StatusCode.OK
        except grpc.RpcError as error:
            assert "Hostname Verification" in (error.details() or ""), error.details()
            return error.code()
        finally:
            server.stop(0)

    assert check("foxglove", "decision_server") == grpc.StatusCode.UNAVAILABLE
    assert check("proxy_robot", "decision_server") == grpc.StatusCode.UNAVAILABLE
    assert check("decision_server", "decision_server") == grpc.StatusCode.OK
    assert check("foxglove", None) == grpc.StatusCode.OK  # what the service's name adds


def test_the_ca_signs_only_end_certificates(pki):
    """The station's CA cannot delegate: path length 0, and it signs certificates and CRLs
    only. (docs/security.md: ca.pem must be a CA of the station's own.)"""
    ca = x509.load_pem_x509_certificate((pki / "ca.pem").read_bytes())
    constraints = ca.extensions.get_extension_for_class(x509.BasicConstraints)
    assert constraints.critical and constraints.value.ca and constraints.value.path_length == 0
    usage = ca.extensions.get_extension_for_class(x509.KeyUsage).value
    assert usage.key_cert_sign and usage.crl_sign and not usage.digital_signature
    for name in (*STATION_SERVICES, *CLIENT_IDENTITIES):
        leaf = x509.load_pem_x509_certificate((pki / f"{name}.pem").read_bytes())
        assert not leaf.extensions.get_extension_for_class(x509.BasicConstraints).value.ca


def test_init_keeps_an_existing_ca_so_issued_certificates_stay_valid(pki):
    before = (pki / "ca.pem").read_bytes()
    init(pki)
    assert (pki / "ca.pem").read_bytes() == before


def test_a_certificate_without_a_role_is_not_an_identity(pki, tmp_path):
    issue(pki, "someone", Role.OPERATOR)
    assert identity_of((pki / "someone.pem").read_bytes()).name == "someone"
    ca = (pki / "ca.pem").read_bytes()  # the CA's subject has a CN but no OU
    with pytest.raises(CertificateError, match="OU"):
        identity_of(ca)
    with pytest.raises(CertificateError, match="not a PEM"):
        identity_of(b"garbage")


@pytest.mark.e2e
def test_make_certs_command_line(tmp_path):
    result = subprocess.run(
        [sys.executable, "-m", "services.security.pki", "--dir", str(tmp_path), "--host",
         "10.0.0.9"], cwd=REPO, capture_output=True, text=True, timeout=60)
    assert result.returncode == 0, result.stderr
    assert (tmp_path / "operator.pem").exists()
    again = subprocess.run(
        [sys.executable, "-m", "services.security.pki", "--dir", str(tmp_path / "none"),
         "issue", "bob", "--role", "operator"], cwd=REPO, capture_output=True, text=True,
        timeout=60)
    assert again.returncode == 2 and "make certs" in again.stderr
    posing = subprocess.run(  # a server certificate named to pass for the DecisionServer
        [sys.executable, "-m", "services.security.pki", "--dir", str(tmp_path), "issue",
         "decision-server", "--role", "station", "--host", "localhost"], cwd=REPO,
        capture_output=True, text=True, timeout=60)
    assert posing.returncode == 2 and "server name" in posing.stderr, posing.stderr
    assert not (tmp_path / "decision-server.pem").exists()


def test_a_link_planted_in_the_directory_is_not_followed(tmp_path):
    """Keys go through new files of random names, created exclusively: a link planted where
    a fixed temporary name would be leads nowhere, and the key never lands outside."""
    directory = tmp_path / "pki"
    directory.mkdir()
    elsewhere = tmp_path / "attacker.txt"
    elsewhere.write_text("theirs\n")
    for name in (".ca.key.tmp", ".ca.pem.tmp", ".admin.key.tmp"):
        (directory / name).symlink_to(elsewhere)
    init(directory)
    assert elsewhere.read_text() == "theirs\n"
    assert stat.S_IMODE((directory / "ca.key").stat().st_mode) == 0o600
    assert not [p.name for p in directory.iterdir()
                if p.name.startswith(".") and not p.is_symlink()]  # no temporary left behind
