"""A server's TLS: its certificate from the TLS directory, reloaded when the files change.

The credentials are grpcio's dynamic ones: before each new handshake grpcio asks whether the
certificate changed, and the answer is a stat of three files. A renewed certificate (written
by `python -m services.security.pki issue`, or by a real CA's tooling, each file replaced by
rename) is served from the next connection on, without a restart; connections already open
keep the one they shook hands with. A key and certificate that do not match yet (one file
replaced, the other not) are not taken: the old pair stays until both are new.
"""

from __future__ import annotations

import logging
import os
import threading
from pathlib import Path

import grpc
from cryptography import x509
from cryptography.hazmat.primitives import serialization

from wire.tls import ChannelSecurity

log = logging.getLogger(__name__)


def server_credentials(tls_dir: Path, name: str,
                       require_client_certificate: bool = True) -> grpc.ServerCredentials:
    """Credentials for the server `name` (`<name>.pem`/`.key` in `tls_dir`), trusting
    `ca.pem` for client certificates. With `require_client_certificate`, a client without a
    certificate from that CA fails the handshake; without it, none is asked for (the
    DecisionServer's token port, where callers present bearer tokens)."""
    files = _ServerFiles(tls_dir, name)
    config = files.load()
    if config is None:
        raise ValueError(f"the key {files.key} does not match the certificate {files.cert}")
    return grpc.dynamic_ssl_server_credentials(
        config, files.changed, require_client_authentication=require_client_certificate)


def station_channel_security(tls_dir: str | Path | None, name: str) -> ChannelSecurity:
    """How the service `name` calls the station's other services: with its own certificate
    (role STATION) when TLS is on, never with a token from the environment."""
    return ChannelSecurity(Path(tls_dir) if tls_dir else None, identity=name)


class _ServerFiles:
    def __init__(self, tls_dir: Path, name: str):
        self.cert = tls_dir / f"{name}.pem"
        self.key = tls_dir / f"{name}.key"
        self.ca = tls_dir / "ca.pem"
        self._stamp = None
        self._lock = threading.Lock()

    def load(self):
        """The files as a grpc certificate configuration; None while key and certificate do
        not match (a renewal half done)."""
        stamp = self._stat()
        cert, key, ca = (path.read_bytes() for path in (self.cert, self.key, self.ca))
        if not _pair_matches(cert, key):
            return None
        self._stamp = stamp
        return grpc.ssl_server_certificate_configuration([(key, cert)], root_certificates=ca)

    def changed(self):
        """grpcio's fetcher: a new configuration if the files changed, else None."""
        with self._lock:
            try:
                if self._stat() == self._stamp:
                    return None
                config = self.load()
            except (OSError, ValueError) as exc:
                log.warning("cannot reload the TLS certificate (%s); keeping the current one",
                            exc)
                return None
            if config is not None:
                log.info("TLS certificate %s reloaded", self.cert)
            return config

    def _stat(self):
        return tuple((s.st_mtime_ns, s.st_size, s.st_ino)
                     for s in (os.stat(p) for p in (self.cert, self.key, self.ca)))


def _pair_matches(cert_pem: bytes, key_pem: bytes) -> bool:
    cert = x509.load_pem_x509_certificate(cert_pem)
    key = serialization.load_pem_private_key(key_pem, None)
    public = serialization.PublicFormat.SubjectPublicKeyInfo
    encoding = serialization.Encoding.DER
    return (cert.public_key().public_bytes(encoding, public)
            == key.public_key().public_bytes(encoding, public))
