"""Who is calling and whether they may: the runtime's side of the station's security.

With TLS on, every call but Health is authenticated and authorized before its handler runs:
- the caller is the verified client certificate's identity (CN) and role (OU), or, on a port
  that takes tokens, the identity a bearer token (`authorization: Bearer ...`) was issued to;
- the caller's role must reach the RPC's declared `min_role` (services.security.roles), else
  PERMISSION_DENIED naming the role needed; no credentials or a bad token: UNAUTHENTICATED;
- every command-class call (any RPC that needs the operator role or more, and EmergencyStop)
  is written to the audit log with its outcome, except the station's own calls on its inner
  ports (see `station_internal`); a command-class stream (Teleoperate) also as it starts
  (outcome STARTED), so a session that moves the arm is on record while it runs;
- a refused call (no credentials, a bad token, a role too low, no room: REFUSALS) is counted in
  the audit log's summary of refusals per source instead (services.security.audit), so a
  flood of them cannot rotate the commands' records out.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from typing import TYPE_CHECKING

import grpc
from google.protobuf import descriptor_pool

from services.runtime.lanes import Lane, declared_lane
from services.security.caller import Caller
from services.security.pki import CertificateError, identity_of
from services.security.roles import Role, check_role, declared_role, required_role
from wire.errors import TelerobotError, UnauthenticatedError

if TYPE_CHECKING:
    from services.security.audit import AuditLog
    from services.security.tokens import TokenStore

_BEARER = "bearer "
# The outcomes of a call refused for who is calling or for room: it changed nothing. A unary
# call that ends so is a refusal (summarized); a stream's end is always a command record, as
# its start was.
REFUSALS = frozenset({"UNAUTHENTICATED", "PERMISSION_DENIED", "RESOURCE_EXHAUSTED"})
STARTED = "STARTED"


@dataclass
class CallSecurity:
    """A server's rules for its calls. `tokens`: the port takes bearer tokens (and only
    them: it asks for no certificate). `inner_port`: the station's inside (see roles)."""

    inner_port: bool
    tokens: TokenStore | None = None
    audit: AuditLog | None = None

    def admit(self, method: str, context: grpc.ServicerContext) -> Caller | None:
        """The authenticated caller, allowed to call `method`; None for an open method
        (Health). Raises UnauthenticatedError or PermissionDeniedError; an audited method's refusal
        is counted in the audit log's refusals (with the identity, when it is known), and an
        audited stream's start is recorded."""
        if required_role(method, self.inner_port) is None:
            return None
        caller = None
        try:
            caller = self.authenticate(context)
            check_role(caller.role, method, self.inner_port)
        except TelerobotError as error:
            if self.audited(method) and self.audit is not None:
                self.audit.refused(identity=caller.identity if caller else "",
                                   role=caller.role.label if caller else "", method=method,
                                   outcome=error.status_name, peer=context.peer(),
                                   detail=error.message)
            raise
        if streams(method) and self.audited(method) and not self.station_internal(caller):
            self.record(method, caller, context, STARTED)  # its end is recorded as it ends
        return caller

    def authenticate(self, context: grpc.ServicerContext) -> Caller:
        certificate = context.auth_context().get("x509_pem_cert")
        if certificate:
            try:
                identity = identity_of(certificate[0])
            except CertificateError as exc:
                raise UnauthenticatedError(str(exc), "CERTIFICATE_WITHOUT_ROLE") from None
            return Caller(identity.name, identity.role)
        token = bearer_token(context.invocation_metadata())
        if token is None or self.tokens is None:
            raise UnauthenticatedError(
                "no client certificate and no bearer token: present a certificate from the "
                "station's CA, or a token (authorization: Bearer ...) on the token port",
                "NO_CREDENTIALS")
        grant = self.tokens.verify(token)
        return Caller(grant.identity, grant.role)

    def token_is_valid(self, metadata) -> bool:
        """Whether call metadata carries a token this port would take (checked before the
        call's context exists, for the early stop)."""
        token = bearer_token(metadata)
        if token is None or self.tokens is None:
            return False
        try:
            self.tokens.verify(token)
        except UnauthenticatedError:
            return False
        return True

    def audited(self, method: str) -> bool:
        """Whether `method` is command-class: it changes the arm, the lock or the settings."""
        role = declared_role(method)
        return self.audit is not None and (
            declared_lane(method) == Lane.EMERGENCY or (role is not None and role >= Role.OPERATOR))

    def station_internal(self, caller: Caller | None) -> bool:
        """A call between the station's own services: not audited on the inner ports. The
        DecisionServer's audit already holds the operator's command behind it, and its moves
        reach ProxyRobot at up to 1 kHz. (Refusals are audited whoever asked.)"""
        return self.inner_port and caller is not None and caller.role is Role.STATION

    def record(self, method: str, caller: Caller | None, context: grpc.ServicerContext,
               outcome: str, detail: str = "") -> None:
        """Audit how a call ended (or that a stream started): a refusal (REFUSALS, but not a
        stream's end) in the summary of refusals, anything else in full."""
        if self.audit is None:
            return
        write = (self.audit.refused if outcome in REFUSALS and not streams(method)
                 else self.audit.record)
        write(identity=caller.identity if caller else "",
              role=caller.role.label if caller else "", method=method, outcome=outcome,
              peer=context.peer(), detail=detail)


@functools.lru_cache(maxsize=1024)  # looked up for every call: cached (methods are few)
def streams(method_path: str) -> bool:
    """Whether "/pkg.Service/Method" streams its requests or its responses (from the loaded
    protos; False for a method they do not define)."""
    service, _, method = method_path.lstrip("/").partition("/")
    try:
        found = descriptor_pool.Default().FindMethodByName(f"{service}.{method}")
    except KeyError:
        return False
    return bool(found.client_streaming or found.server_streaming)


def bearer_token(metadata) -> str | None:
    for key, value in metadata or ():
        if key == "authorization" and value[:len(_BEARER)].lower() == _BEARER:
            return value[len(_BEARER):].strip()
    return None
