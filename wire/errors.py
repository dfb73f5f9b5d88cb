"""The one error family of the project: servers raise these, clients catch them.

A domain module raises them without importing grpc, so it stays testable without a server; the
RPC layer sends each as its gRPC status code with a google.rpc.ErrorInfo (`reason`, a stable
UPPER_SNAKE_CASE tag), and the Python client turns every failed call back into the same class
(clients/python/errors.py). Each message should tell the caller what to do next.

Catch the subclass for the case you handle (`except FailedPreconditionError`) or the base class
and look at `code` (the grpc.StatusCode) or `reason`.
"""

from __future__ import annotations


class TelerobotError(Exception):
    """Base class. `reason`: the ErrorInfo tag, or None when the status carries none (errors made
    by gRPC itself). On a client, `domain` is the ErrorInfo's domain and `method` the full method
    name (/telerobot.v1.ProxyRobot/MoveJointsIncremental)."""

    status_name = "UNKNOWN"

    def __init__(self, message: str, reason: str | None = None, *, domain: str | None = None,
                 method: str | None = None):
        self.message = message
        self.reason = reason
        self.domain = domain
        self.method = method
        super().__init__(str(self))

    @property
    def code(self):
        """The grpc.StatusCode (grpc is imported only by a caller that asks for it)."""
        import grpc

        return grpc.StatusCode[self.status_name]

    def __str__(self) -> str:
        where = f" in {self.method}" if self.method else ""
        why = f" [{self.reason}]" if self.reason else ""
        return f"{self.status_name}{why}{where}: {self.message}"

    def __reduce__(self):  # picklable with its keyword-only fields
        return (_rebuild, (self.__class__, self.status_name, self.message, self.reason,
                           self.domain, self.method))


def _rebuild(cls, status_name, message, reason, domain, method):
    error = cls(message, reason, domain=domain, method=method)
    error.status_name = status_name
    return error


class InvalidArgumentError(TelerobotError):
    """Malformed input: NaN, wrong lengths, a non-rotation matrix, unknown enum values."""

    status_name = "INVALID_ARGUMENT"


class OutOfRangeError(TelerobotError):
    """Well-formed input past a limit: joint limits, workspace, increment caps."""

    status_name = "OUT_OF_RANGE"


class FailedPreconditionError(TelerobotError):
    """The system is not in a state to do this: not initialized, e-stopped, no lock held."""

    status_name = "FAILED_PRECONDITION"


class NotFoundError(TelerobotError):
    """A named thing (recording, lease, cobegin) does not exist."""

    status_name = "NOT_FOUND"


class AlreadyExistsError(TelerobotError):
    """A named thing already exists."""

    status_name = "ALREADY_EXISTS"


class AbortedError(TelerobotError):
    """A conflict the caller chose not to wait for, such as a held control lock."""

    status_name = "ABORTED"


class UnavailableError(TelerobotError):
    """A dependency (hardware link, another service) is down."""

    status_name = "UNAVAILABLE"


class ResourceExhaustedError(TelerobotError):
    """Overload: a queue or a cap is full."""

    status_name = "RESOURCE_EXHAUSTED"


class DeadlineExceededError(TelerobotError):
    """A wait inside the server (a barrier, a lock queue) ran out of time."""

    status_name = "DEADLINE_EXCEEDED"


class UnimplementedError(TelerobotError):
    """The contract exists but this build does not serve it yet."""

    status_name = "UNIMPLEMENTED"


class RpcCancelledError(TelerobotError):
    """The call was cancelled: the caller went away (not asyncio.CancelledError, hence the
    name)."""

    status_name = "CANCELLED"


class UnauthenticatedError(TelerobotError):
    """No identity the server can trust: a bad, expired or revoked token, or none."""

    status_name = "UNAUTHENTICATED"


class PermissionDeniedError(TelerobotError):
    """A known identity that may not do this: its role is too low, or the lease is another's."""

    status_name = "PERMISSION_DENIED"


class InternalError(TelerobotError):
    """A server bug or a transport failure."""

    status_name = "INTERNAL"


def error_for_status(status_name: str, message: str, reason: str | None = None, *,
                     domain: str | None = None, method: str | None = None) -> TelerobotError:
    """The error for a gRPC status name ("OUT_OF_RANGE"), so an error that came back from
    another service can be raised again without the domain importing grpc. A status without a
    class of its own (DATA_LOSS) gets the base class, with its name."""
    for cls in TelerobotError.__subclasses__():
        if cls.status_name == status_name:
            return cls(message, reason, domain=domain, method=method)
    error = TelerobotError.__new__(TelerobotError)
    error.status_name = status_name
    error.__init__(message, reason, domain=domain, method=method)
    return error
