"""Channels with the station's TLS: a client certificate, or a bearer token, or plaintext.

A client finds its credentials in the environment (or is given them):
- ``TELEROBOT_TLS_DIR``: a directory with the CA's ``ca.pem`` and client certificates as
  ``<identity>.pem`` and ``<identity>.key`` (``make certs`` writes one to var/pki). Unset:
  plaintext, which the services accept only on loopback.
- ``TELEROBOT_IDENTITY``: which certificate of the directory to present (default ``operator``;
  the station's services present their own).
- ``TELEROBOT_TOKEN``: a bearer token instead of a certificate (sent as ``authorization: Bearer
  ...``, only ever over TLS; only the DecisionServer's token port takes it).

Which server it is: every certificate of the station's CA names the hosts the station answers
on, so the host name alone only says "some server of this station". A service's certificate
also names the service (`server_name`: ``decision-server.telerobot.internal``), and a channel
opened for a service (``open_channel(..., service="decision_server")``) checks that name instead
of the host's, so no other certificate of the CA (the observer-role live view's, say) passes
for it.
"""

from __future__ import annotations

import os
import re
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import grpc

# Every channel pings its server four times a second and gives up on one that does not answer
# within 750 ms: a dead, hung or cut peer is noticed within a second (#14), not after TCP's
# minutes. 750 ms is above the longest round trip the project is tested across (400 ms and
# jitter), so a slow link is not taken for a dead one. The servers ping and allow pings at the
# same rate (services.runtime.server).
KEEPALIVE_INTERVAL_MS = 250
KEEPALIVE_TIMEOUT_MS = 750
KEEPALIVE_OPTIONS: tuple[tuple[str, int], ...] = (
    ("grpc.keepalive_time_ms", KEEPALIVE_INTERVAL_MS),
    ("grpc.keepalive_timeout_ms", KEEPALIVE_TIMEOUT_MS),
    # Recent grpc-core times a ping out by this, not by keepalive_timeout (default 60 s).
    ("grpc.http2.ping_timeout_ms", KEEPALIVE_TIMEOUT_MS),
    ("grpc.keepalive_permit_without_calls", 1),
    ("grpc.http2.max_pings_without_data", 0),
    # A lost connection is retried after 0.1 s, then at most a second apart (grpc-core's
    # default grows to 120 s), so a session resumes within a second of a cut's end. Not
    # grpc.min_reconnect_backoff_ms: grpc-core also takes it as the connect deadline (default
    # 20 s), and a TLS handshake across a slow link or a loaded machine takes more than 0.1 s.
    ("grpc.initial_reconnect_backoff_ms", 100),
    ("grpc.max_reconnect_backoff_ms", 1000),
)
TLS_DIR_ENV = "TELEROBOT_TLS_DIR"
IDENTITY_ENV = "TELEROBOT_IDENTITY"
TOKEN_ENV = "TELEROBOT_TOKEN"
DEFAULT_IDENTITY = "operator"
# The domain of the names services' certificates carry for clients to check. Never resolved,
# only compared (not .local, which mDNS resolves and discovery/ advertises hosts under).
SERVER_NAME_DOMAIN = "telerobot.internal"
TARGET_NAME_OPTION = "grpc.ssl_target_name_override"
_SERVICE_NAME = re.compile(r"[a-z0-9](?:[a-z0-9_]{0,61}[a-z0-9])?")


def server_name(service: str) -> str:
    """The name `service`'s certificate carries beside the host names, which a client dialing
    that service checks: "decision_server" -> "decision-server.telerobot.internal". A
    service's name has no '-' of its own, so no two services share a server name."""
    if not _SERVICE_NAME.fullmatch(service):
        raise ValueError(f"{service!r} cannot be a service's server name: lower-case letters, "
                         "digits and '_' (not at either end), at most 63")
    return f"{service.replace('_', '-')}.{SERVER_NAME_DOMAIN}"


def server_name_options(service: str) -> tuple[tuple[str, str], ...]:
    """Channel options that make a TLS channel accept only `service`'s certificate: gRPC
    checks `server_name(service)` instead of the target's host (for a channel made without
    `open_channel`)."""
    return ((TARGET_NAME_OPTION, server_name(service)),)


@dataclass(frozen=True)
class ChannelSecurity:
    """How a channel authenticates; the default is plaintext."""

    tls_dir: Path | None = None
    identity: str = DEFAULT_IDENTITY  # the client certificate presented, unless a token is
    token: str | None = None

    @classmethod
    def from_env(cls, identity: str | None = None) -> ChannelSecurity:
        """From the environment; `identity` (a service's own) wins over TELEROBOT_IDENTITY."""
        tls_dir = os.environ.get(TLS_DIR_ENV) or None
        return cls(Path(tls_dir) if tls_dir else None,
                   identity or os.environ.get(IDENTITY_ENV) or DEFAULT_IDENTITY,
                   os.environ.get(TOKEN_ENV) or None)

    @property
    def secure(self) -> bool:
        return self.tls_dir is not None

    def credentials(self) -> grpc.ChannelCredentials:
        """TLS credentials: the CA, and the identity's certificate or the token."""
        if self.tls_dir is None:
            raise ValueError("no TLS directory: set TELEROBOT_TLS_DIR (make certs writes "
                             "var/pki) or use a plaintext channel on loopback")
        root = _read(self.tls_dir / "ca.pem")
        if self.token:
            return grpc.composite_channel_credentials(
                grpc.ssl_channel_credentials(root), grpc.access_token_call_credentials(self.token))
        return grpc.ssl_channel_credentials(root, _read(self.tls_dir / f"{self.identity}.key"),
                                            _read(self.tls_dir / f"{self.identity}.pem"))


def open_channel(target: str, options: Sequence[tuple[str, object]] = (),
                 security: ChannelSecurity | None = None, aio: bool = False,
                 service: str | None = None):
    """A channel to `target`: TLS when `security` (default: from the environment) has a TLS
    directory, plaintext otherwise; with KEEPALIVE_OPTIONS (before `options`, which may
    override them). `aio` makes a grpc.aio channel.

    `service` (a name of wire.addresses' DEFAULT_PORTS, e.g. "decision_server"): over TLS the
    server's certificate must name it (`server_name`), whatever host `target` names, so another
    certificate of the station's CA cannot pose as it; the handshake fails otherwise
    (UNAVAILABLE, "Hostname Verification Check failed": a PKI made before service names, which
    `make certs` reissues). None checks only that the certificate names the target's host."""
    security = security or ChannelSecurity.from_env()
    target = dialable(target)
    expected = server_name_options(service) if service is not None else ()  # a bad name fails
    options = [*KEEPALIVE_OPTIONS, *(expected if security.secure else ()), *options]
    grpc_module = grpc.aio if aio else grpc
    if security.token and not security.secure:
        raise ValueError("a bearer token is sent only over TLS: set TELEROBOT_TLS_DIR to a "
                         "directory holding the station's ca.pem")
    if not security.secure:
        return grpc_module.insecure_channel(target, options=list(options))
    return grpc_module.secure_channel(target, security.credentials(), options=list(options))


def dialable(target: str) -> str:
    """`target`, with a wildcard host (a server's "listen on every address": 0.0.0.0, [::])
    turned into loopback. Connecting to 0.0.0.0 happens to reach this host, but no certificate
    names it, so over TLS the station's own checks of a service bound so would fail."""
    host, sep, port = target.rpartition(":")
    wildcard = {"0.0.0.0": "127.0.0.1", "[::]": "[::1]"}
    return f"{wildcard[host]}:{port}" if sep and host in wildcard else target


def _read(path: Path) -> bytes:
    try:
        return path.read_bytes()
    except OSError as exc:
        raise FileNotFoundError(f"cannot read {path}: {exc.strerror}; `make certs` writes the "
                                "development certificates, or see docs/security.md for "
                                "a real CA") from None
