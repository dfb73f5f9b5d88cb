"""Errors that domain code raises; the RPC layer maps each to a gRPC status code.

Domain modules import these instead of grpc (through ``services.runtime.errors``, which
re-exports them), so they stay testable without a server; ``wire``'s own checks raise them too.
Each message should tell the caller what to do next.
"""

from __future__ import annotations


class TelerobotError(Exception):
    """Base class. `reason` is a stable UPPER_SNAKE_CASE tag sent as google.rpc.ErrorInfo."""

    status_name = "UNKNOWN"

    def __init__(self, message: str, reason: str | None = None):
        super().__init__(message)
        self.message = message
        self.reason = reason or self.status_name


class InvalidArgument(TelerobotError):
    """Malformed input: NaN, wrong lengths, a non-rotation matrix, unknown enum values."""

    status_name = "INVALID_ARGUMENT"


class OutOfRange(TelerobotError):
    """Well-formed input past a limit: joint limits, workspace, increment caps."""

    status_name = "OUT_OF_RANGE"


class FailedPrecondition(TelerobotError):
    """The system is not in a state to do this: not initialized, e-stopped, no lock held."""

    status_name = "FAILED_PRECONDITION"


class NotFound(TelerobotError):
    """A named thing (recording, lease, cobegin) does not exist."""

    status_name = "NOT_FOUND"


class AlreadyExists(TelerobotError):
    """A named thing already exists."""

    status_name = "ALREADY_EXISTS"


class Aborted(TelerobotError):
    """A conflict the caller chose not to wait for, such as a held control lock."""

    status_name = "ABORTED"


class Unavailable(TelerobotError):
    """A dependency (hardware link, another service) is down."""

    status_name = "UNAVAILABLE"


class ResourceExhausted(TelerobotError):
    """Overload: a queue or a cap is full."""

    status_name = "RESOURCE_EXHAUSTED"


class DeadlineExceeded(TelerobotError):
    """A wait inside the server (a barrier, a lock queue) ran out of time."""

    status_name = "DEADLINE_EXCEEDED"


class Unimplemented(TelerobotError):
    """The contract exists but this build does not serve it yet."""

    status_name = "UNIMPLEMENTED"


class Cancelled(TelerobotError):
    """The caller went away."""

    status_name = "CANCELLED"


class Unauthenticated(TelerobotError):
    """No identity the server can trust: a bad, expired or revoked token, or none."""

    status_name = "UNAUTHENTICATED"


class PermissionDenied(TelerobotError):
    """A known identity that may not do this: its role is too low, or the lease is another's."""

    status_name = "PERMISSION_DENIED"


def error_for_status(status_name: str, message: str, reason: str | None = None) -> TelerobotError:
    """The domain error for a gRPC status name ("OUT_OF_RANGE"), so an error that came back from
    another service can be raised again without the domain importing grpc."""
    for cls in TelerobotError.__subclasses__():
        if cls.status_name == status_name:
            return cls(message, reason)
    error = TelerobotError(message, reason)
    error.status_name = status_name
    return error
