"""Who is calling and whether they may: the runtime's side of the station's security.

With TLS on, every call but Health is authenticated and authorized before its handler runs:
- the caller is the verified client certificate's identity (CN) and role (OU), or, on a port
  that takes tokens, the identity a bearer token (`authorization: Bearer ...`) was issued to;
- the caller's role must reach the RPC's declared `min_role` (services.security.roles), else
  PERMISSION_DENIED naming the role needed; no credentials or a bad token: UNAUTHENTICATED;
- every command-class call (any RPC that needs the operator role or more, and EmergencyStop)
  is written to the audit log with its outcome; a command-class stream (Teleoperate) also as
  it starts (outcome STARTED), so a session that moves the arm is on record while it runs.
  The station's own calls on its inner ports (the DecisionServer's moves, up to 1 kHz) are
  summarized instead (see `summarizes`): per source, host and method, a minute's calls are
  one line, with the first of each outcome in full;
- a refused call (no credentials, a bad token, a role too low, no room: REFUSALS, and the
  calls the per-caller caps refuse before any of this: `refused_for_room`) is counted in the
  audit log's summary of refusals per source instead (services.security.audit), so a flood
  of them cannot rotate the commands' records out.

Without TLS (`authenticates` False) a server may still keep an audit log: nothing is checked
(every caller may call anything, as in plaintext), and command-class calls are recorded with an
empty identity, the role UNAUTHENTICATED_ROLE and the peer's address; on an inner port, where
the station's calls cannot be told from others', every caller's are summarized.
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
# The role of a call's record on a server without TLS: nobody was authenticated.
UNAUTHENTICATED_ROLE = "unauthenticated"


@dataclass
class CallSecurity:
    """A server's rules for its calls. `tokens`: the port takes bearer tokens (and only
    them: it asks for no certificate). `inner_port`: the station's inside (see roles).
    `authenticates`: False on a plaintext server, which checks nobody and only audits."""

    inner_port: bool
    tokens: TokenStore | None = None
    audit: AuditLog | None = None
    authenticates: bool = True

    def admit(self, method: str, context: grpc.ServicerContext) -> Caller | None:
        """The authenticated caller, allowed to call `method`; None for an open method
        (Health). Raises UnauthenticatedError or PermissionDeniedError; an audited method's refusal
        is counted in the audit log's refusals (with the identity, when it is known), and an
        audited stream's start is recorded. Without TLS: None, every call allowed."""
        if required_role(method, self.inner_port) is None:
            return None
        if not self.authenticates:
            if streams(method) and self.audited(method):
                self.record(method, None, context, STARTED)
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
        if streams(method) and self.audited(method):
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

    def summarizes(self, caller: Caller | None) -> bool:
        """Whether a command of `caller` is summarized instead of written in full: a call
        between the station's own services on an inner port (the DecisionServer's audit holds
        the operator's command behind it, and its moves reach ProxyRobot at up to 1 kHz), or,
        without TLS, any call on an inner port (the station's cannot be told from others').
        So a leaked station key still leaves a trace: its first call of each outcome a minute
        in full, the peers it came from, and its count."""
        return self.inner_port and (not self.authenticates or (
            caller is not None and caller.role is Role.STATION))

    def record(self, method: str, caller: Caller | None, context: grpc.ServicerContext,
               outcome: str, detail: str = "") -> None:
        """Audit how a call ended (or that a stream started): a refusal (REFUSALS, but not a
        stream's end) in the summary of refusals, the station's own on an inner port in the
        commands' summaries (`summarizes`), anything else in full."""
        if self.audit is None:
            return
        if outcome in REFUSALS and not streams(method):
            write = self.audit.refused
        elif self.summarizes(caller):
            write = self.audit.summarized
        else:
            write = self.audit.record
        write(identity=caller.identity if caller else "", role=self._role(caller),
              method=method, outcome=outcome, peer=context.peer(), detail=detail)

    def refused_for_room(self, method: str, caller: Caller | None,
                         context: grpc.ServicerContext, reason: str, message: str) -> None:
        """Count a call a cap refused (RESOURCE_EXHAUSTED `reason`, before it was authorized)
        in the summary of refusals, whatever its method: a flood of them is on record."""
        if self.audit is None:
            return
        self.audit.refused(identity=caller.identity if caller else "", role=self._role(caller),
                           method=method, outcome="RESOURCE_EXHAUSTED", peer=context.peer(),
                           detail=f"{reason}: {message}")

    def _role(self, caller: Caller | None) -> str:
        if caller is not None:
            return caller.role.label
        return "" if self.authenticates else UNAUTHENTICATED_ROLE


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
