"""The one exception family the clients raise for a failed call: `TelerobotRpcError`.

Every failed RPC, sync or async, unary or stream, becomes a `TelerobotRpcError` (or the subclass
for its status code) carrying:

- ``code``: the ``grpc.StatusCode``;
- ``message``: the server's message (it says what to do next);
- ``reason`` and ``domain``: the ``google.rpc.ErrorInfo`` detail the telerobot servers attach
  (domain ``telerobot.v1``, a stable UPPER_SNAKE_CASE reason such as ``NO_CONTROL``), or None
  when the status carries none (errors made by gRPC itself, or calls forwarded through the
  DecisionServer, whose forwarding keeps the code and message but not the backend's reason);
- ``method``: the full method name, ``/telerobot.v1.ProxyRobot/MoveJointsIncremental``.

Catch the subclass for the case you handle (``except FailedPreconditionError``) or the base
class and look at ``code``/``reason``. A few errors are made on the client side and say so in
their message: a Teleoperate ack that did not come within its timeout, a channel that did not
connect in ``wait_for_ready``; they use the status code gRPC itself would use
(DEADLINE_EXCEEDED, UNAVAILABLE) and have no reason.
"""

from __future__ import annotations

import grpc
from google.rpc import error_details_pb2, status_pb2

STATUS_DETAILS_KEY = "grpc-status-details-bin"


class TelerobotRpcError(Exception):
    """A call failed: status code, the server's message and the ErrorInfo reason if any."""

    def __init__(self, code: grpc.StatusCode, message: str, *, reason: str | None = None,
                 domain: str | None = None, method: str | None = None):
        self.code = code
        self.message = message
        self.reason = reason
        self.domain = domain
        self.method = method
        super().__init__(str(self))

    def __str__(self) -> str:
        where = f" in {self.method}" if self.method else ""
        why = f" [{self.reason}]" if self.reason else ""
        return f"{self.code.name}{why}{where}: {self.message}"

    def __reduce__(self):  # picklable with its keyword-only fields
        return (_rebuild, (self.__class__, self.code, self.message, self.reason, self.domain,
                           self.method))


def _rebuild(cls, code, message, reason, domain, method):
    return cls(code, message, reason=reason, domain=domain, method=method)


class InvalidArgumentError(TelerobotRpcError):
    """Malformed input: NaN, wrong lengths, a non-rotation matrix, bad metadata. Fix the call."""


class OutOfRangeError(TelerobotRpcError):
    """Past a joint or workspace limit or an increment cap. Nothing moved."""


class FailedPreconditionError(TelerobotRpcError):
    """Wrong state: not initialized, e-stopped, or no control lock held."""


class NotFoundError(TelerobotRpcError):
    """An unknown or expired lease, recording or cobegin."""


class AlreadyExistsError(TelerobotRpcError):
    """A name already in use (a recording)."""


class AbortedError(TelerobotRpcError):
    """A conflict: the lock is held by someone else, or was lost mid-stream."""


class UnavailableError(TelerobotRpcError):
    """The server or one of its dependencies is down, or shutting down."""


class ResourceExhaustedError(TelerobotRpcError):
    """A lane queue or a stream cap is full: back off, then call again."""


class DeadlineExceededError(TelerobotRpcError):
    """The call's deadline (the `timeout`) passed, or a wait inside the server ran out."""


class UnimplementedError(TelerobotRpcError):
    """An unknown method, or a contract whose behaviour is not built yet."""


class RpcCancelledError(TelerobotRpcError):
    """The call was cancelled (not asyncio.CancelledError, hence the name)."""


class PermissionDeniedError(TelerobotRpcError):
    """Not allowed: the identity's role is too low (the message names the role needed), or
    the lease is another identity's."""


class UnauthenticatedError(TelerobotRpcError):
    """No identity the server trusts: a bad, expired or revoked token, or none."""


class InternalError(TelerobotRpcError):
    """A server bug or a transport failure."""


_BY_CODE: dict[grpc.StatusCode, type[TelerobotRpcError]] = {
    grpc.StatusCode.INVALID_ARGUMENT: InvalidArgumentError,
    grpc.StatusCode.OUT_OF_RANGE: OutOfRangeError,
    grpc.StatusCode.FAILED_PRECONDITION: FailedPreconditionError,
    grpc.StatusCode.NOT_FOUND: NotFoundError,
    grpc.StatusCode.ALREADY_EXISTS: AlreadyExistsError,
    grpc.StatusCode.ABORTED: AbortedError,
    grpc.StatusCode.UNAVAILABLE: UnavailableError,
    grpc.StatusCode.RESOURCE_EXHAUSTED: ResourceExhaustedError,
    grpc.StatusCode.DEADLINE_EXCEEDED: DeadlineExceededError,
    grpc.StatusCode.UNIMPLEMENTED: UnimplementedError,
    grpc.StatusCode.CANCELLED: RpcCancelledError,
    grpc.StatusCode.PERMISSION_DENIED: PermissionDeniedError,
    grpc.StatusCode.UNAUTHENTICATED: UnauthenticatedError,
    grpc.StatusCode.INTERNAL: InternalError,
}


def error_for_code(code: grpc.StatusCode, message: str, *, reason: str | None = None,
                   domain: str | None = None, method: str | None = None) -> TelerobotRpcError:
    """The `TelerobotRpcError` subclass for `code` (the base class for codes without one)."""
    cls = _BY_CODE.get(code, TelerobotRpcError)
    return cls(code, message, reason=reason, domain=domain, method=method)


def _error_info(trailing_metadata) -> error_details_pb2.ErrorInfo | None:
    for key, value in trailing_metadata or ():
        if key != STATUS_DETAILS_KEY:
            continue
        try:
            status = status_pb2.Status.FromString(value)
        except Exception:  # a malformed detail must not hide the error itself
            return None
        for detail in status.details:
            if detail.Is(error_details_pb2.ErrorInfo.DESCRIPTOR):
                info = error_details_pb2.ErrorInfo()
                detail.Unpack(info)
                return info
    return None


def from_rpc_error(error: grpc.RpcError, method: str | None = None) -> TelerobotRpcError:
    """The typed error for a failed call (a sync ``grpc.RpcError`` or a ``grpc.aio.AioRpcError``),
    with the ErrorInfo reason and domain read from the status details in its trailers."""
    code = error.code() if callable(getattr(error, "code", None)) else grpc.StatusCode.UNKNOWN
    details = error.details() if callable(getattr(error, "details", None)) else None
    trailers = (error.trailing_metadata()
                if callable(getattr(error, "trailing_metadata", None)) else None)
    info = _error_info(trailers)
    return error_for_code(code or grpc.StatusCode.UNKNOWN, details or str(code),
                          reason=info.reason if info else None,
                          domain=info.domain if info else None, method=method)
