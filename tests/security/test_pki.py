"""The development PKI: what `make certs` writes, and identities read back from certificates."""

import stat
import subprocess
import sys

import pytest
from cryptography import x509

from services.security.pki import (
    CLIENT_IDENTITIES,
    STATION_SERVICES,
    CertificateError,
    identity_of,
    init,
    issue,
)
from services.security.roles import Role
from tests.processes import REPO


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


def test_service_certificates_name_every_address_they_answer_on(pki):
    cert = x509.load_pem_x509_certificate((pki / "decision_server.pem").read_bytes())
    names = cert.extensions.get_extension_for_class(x509.SubjectAlternativeName).value
    ips = {str(ip) for ip in names.get_values_for_type(x509.IPAddress)}
    assert {"127.0.0.1", "::1", "10.213.0.2"} <= ips
    assert {"localhost", "slave.example"} <= set(names.get_values_for_type(x509.DNSName))
    issuer = x509.load_pem_x509_certificate((pki / "ca.pem").read_bytes())
    cert.verify_directly_issued_by(issuer)


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
