"""A development PKI (`make certs`): one CA, a certificate per service, one per identity.

    python -m services.security.pki [--dir var/pki] [--host NAME_OR_IP ...] [--force]
    python -m services.security.pki issue NAME --role operator [--host ...] [--dir var/pki]

What `init` (the default) writes into the directory:
- `ca.pem` and `ca.key`: the station's certificate authority, which may sign only end
  certificates (path length 0), never another CA;
- `<service>.pem` and `<service>.key` for every service of the station, role STATION: each is
  a server certificate (SANs: its own name, `decision-server.telerobot.internal` for instance,
  which a client dialing that service checks (wire/tls.py's `server_name`); then localhost,
  127.0.0.1, ::1, this host's name and every --host) and also a client certificate, which the
  DecisionServer presents on its inner links;
- `admin`, `operator` and `observer`: client certificates with those roles, and `launcher`
  (role STATION), which `make serve` presents to ask each service for its health;
- `web_console`: a server certificate only (no client identity), for the console's HTTPS.

An identity is the subject's common name (CN); its role is the subject's organizational unit
(OU). A real CA works the same way: issue certificates with those two fields, put its
certificate in `ca.pem` and each service's pair as `<service>.pem`/`.key` (see docs/security.md).
Keys are EC P-256 (fast handshakes), written with mode 0600. `init` reissues every service's and
identity's certificate and keeps the CA, so it also brings a directory made by an older version
up to date (the services' names).
"""

from __future__ import annotations

import argparse
import datetime
import functools
import ipaddress
import os
import socket
import sys
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path

from cryptography import x509
from cryptography.hazmat.primitives import hashes, serialization
from cryptography.hazmat.primitives.asymmetric import ec
from cryptography.x509.oid import ExtendedKeyUsageOID, NameOID

from services.security.roles import Role
from wire.files import replace_file
from wire.tls import server_name

DEFAULT_PKI_DIR = "var/pki"
# Every process of the station, and the identities a fresh station hands out.
STATION_SERVICES = ("world", "emergency_stop", "proxy_robot", "force_sensor", "stereo_camera",
                    "decision_server")
# Station processes with an observer's role: the live view (services.foxglove), the
# observation's publisher (services.observation) and the Zenoh router that carries it.
VIEWER_SERVICES = ("foxglove", "observation", "zenoh_router")
# Servers that are no client of the station: the web console's HTTPS (a server certificate
# only, so its key speaks for no identity at the gRPC ports).
WEB_SERVICES = ("web_console",)
CLIENT_IDENTITIES = {"admin": Role.ADMIN, "operator": Role.OPERATOR, "observer": Role.OBSERVER,
                     "launcher": Role.STATION}  # the launcher asks each service for its health
LOOPBACK_NAMES = ("localhost", "127.0.0.1", "::1")
CA_DAYS = 3650
LEAF_DAYS = 365


@dataclass(frozen=True)
class Identity:
    """Who a certificate speaks for."""

    name: str
    role: Role


class CertificateError(ValueError):
    """A certificate this station cannot take as an identity."""


def init(directory: Path, hosts: Iterable[str] = (), force: bool = False) -> list[Path]:
    """Write the CA, the services' and the identities' certificates; returns what it wrote.
    An existing CA is kept (and reused) unless `force`."""
    directory.mkdir(parents=True, exist_ok=True)
    written = []
    if force or not (directory / "ca.pem").exists():
        key = ec.generate_private_key(ec.SECP256R1())
        name = x509.Name([x509.NameAttribute(NameOID.COMMON_NAME, "telerobot development CA")])
        now = _now()
        cert = (x509.CertificateBuilder().subject_name(name).issuer_name(name)
                .public_key(key.public_key()).serial_number(x509.random_serial_number())
                .not_valid_before(now).not_valid_after(now + datetime.timedelta(days=CA_DAYS))
                .add_extension(x509.BasicConstraints(ca=True, path_length=0), critical=True)
                .add_extension(x509.KeyUsage(False, False, False, False, False, True, True,
                                             False, False), critical=True)
                .sign(key, hashes.SHA256()))
        written += _write_pair(directory, "ca", cert, key)
    server_names = [*LOOPBACK_NAMES, socket.gethostname(), *hosts]
    for service in STATION_SERVICES:
        written += issue(directory, service, Role.STATION, server_names)
    for service in VIEWER_SERVICES:
        written += issue(directory, service, Role.OBSERVER, server_names)
    for service in WEB_SERVICES:
        written += issue(directory, service, Role.OBSERVER, server_names, client=False)
    for identity, role in CLIENT_IDENTITIES.items():
        written += issue(directory, identity, role)
    return written


def issue(directory: Path, name: str, role: Role, server_names: Iterable[str] = (),
          days: int = LEAF_DAYS, client: bool = True) -> list[Path]:
    """Sign `<name>.pem`/`.key` with the directory's CA: a client certificate for identity
    `name` with `role` (unless not `client`), and also, when `server_names` are given, a
    server certificate for them and for `name`'s own server name (`server_name(name)`,
    first)."""
    ca_cert = x509.load_pem_x509_certificate((directory / "ca.pem").read_bytes())
    ca_key = serialization.load_pem_private_key((directory / "ca.key").read_bytes(), None)
    key = ec.generate_private_key(ec.SECP256R1())
    subject = x509.Name([x509.NameAttribute(NameOID.COMMON_NAME, name),
                         x509.NameAttribute(NameOID.ORGANIZATIONAL_UNIT_NAME, role.label)])
    usages = [ExtendedKeyUsageOID.CLIENT_AUTH] if client else []
    now = _now()
    builder = (x509.CertificateBuilder().subject_name(subject).issuer_name(ca_cert.subject)
               .public_key(key.public_key()).serial_number(x509.random_serial_number())
               .not_valid_before(now).not_valid_after(now + datetime.timedelta(days=days))
               .add_extension(x509.BasicConstraints(ca=False, path_length=None), critical=True))
    names = list(server_names)
    if names:  # its own name first: the one no other certificate carries
        names = list(dict.fromkeys([server_name(name), *names]))  # in order, without repeats
        usages.append(ExtendedKeyUsageOID.SERVER_AUTH)
        builder = builder.add_extension(
            x509.SubjectAlternativeName([_general_name(n) for n in names]), critical=False)
    builder = builder.add_extension(x509.ExtendedKeyUsage(usages), critical=False)
    return _write_pair(directory, name, builder.sign(ca_key, hashes.SHA256()), key)


@functools.lru_cache(maxsize=256)  # asked for every call; a peer's certificate is the same bytes
def identity_of(certificate_pem: bytes) -> Identity:
    """The identity a (verified) certificate speaks for: its CN, with the role in its OU."""
    try:
        cert = x509.load_pem_x509_certificate(certificate_pem)
    except ValueError as exc:
        raise CertificateError(f"not a PEM certificate: {exc}") from None
    names = cert.subject.get_attributes_for_oid(NameOID.COMMON_NAME)
    units = cert.subject.get_attributes_for_oid(NameOID.ORGANIZATIONAL_UNIT_NAME)
    if not names or not units:
        raise CertificateError("the certificate's subject needs a CN (the identity) and an OU "
                               "(its role: observer, operator, station or admin)")
    try:
        role = Role.parse(str(units[0].value))
    except ValueError as exc:
        raise CertificateError(f"the certificate's OU is not a role: {exc}") from None
    return Identity(str(names[0].value), role)


def _general_name(name: str) -> x509.GeneralName:
    try:
        return x509.IPAddress(ipaddress.ip_address(name))
    except ValueError:
        return x509.DNSName(name)


def _write_pair(directory: Path, name: str, cert: x509.Certificate,
                key: ec.EllipticCurvePrivateKey) -> list[Path]:
    """Write the key first (0600 from its creation, never readable by others), then the
    certificate, each by `replace_file`, so a server reloading them never reads half a file;
    then the directory is flushed, so the renames reach the disk too."""
    key_bytes = key.private_bytes(serialization.Encoding.PEM, serialization.PrivateFormat.PKCS8,
                                  serialization.NoEncryption())
    paths = [directory / f"{name}.key", directory / f"{name}.pem"]
    for path, data, mode in ((paths[0], key_bytes, 0o600),
                             (paths[1], cert.public_bytes(serialization.Encoding.PEM), 0o644)):
        replace_file(path, data, mode)
    directory_fd = os.open(directory, os.O_RDONLY | os.O_DIRECTORY)
    try:
        os.fsync(directory_fd)  # the renames themselves reach the disk
    finally:
        os.close(directory_fd)
    return paths


def _now() -> datetime.datetime:
    # A minute in the past: a peer whose clock is a little behind still accepts it.
    return datetime.datetime.now(datetime.UTC) - datetime.timedelta(minutes=1)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m services.security.pki",
                                     description=__doc__.split("\n\n")[0])
    parser.add_argument("--dir", type=Path, default=Path(DEFAULT_PKI_DIR),
                        help=f"where the files go (default {DEFAULT_PKI_DIR})")
    commands = parser.add_subparsers(dest="command")
    init_parser = commands.add_parser("init", help="the CA and every certificate (default)")
    issue_parser = commands.add_parser("issue", help="one more certificate from the CA")
    issue_parser.add_argument("name", help="the identity (the certificate's CN)")
    issue_parser.add_argument("--role", type=Role.parse, required=True,
                              help="observer, operator, station or admin")
    for sub in (parser, init_parser, issue_parser):
        sub.add_argument("--host", action="append", default=[],
                         help="another name or address the servers answer on (repeatable)")
    for sub in (parser, init_parser):
        sub.add_argument("--force", action="store_true", help="a new CA even if one exists")
    args = parser.parse_args(argv)
    if args.command == "issue":
        if not (args.dir / "ca.key").exists():
            parser.error(f"no CA in {args.dir}: run `make certs` first")
        try:
            written = issue(args.dir, args.name, args.role, args.host)
        except ValueError as exc:  # a server certificate for a name that cannot be one
            parser.error(str(exc))
    else:
        written = init(args.dir, args.host, args.force)
    for path in written:
        print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
