"""Errors that domain code raises; the RPC layer maps each to a gRPC status code.

Domain modules import these instead of grpc, so they stay testable without a server.
Each message should tell the caller what to do next. They are defined in ``wire.errors`` (the
contracts' checks raise them too) and are the same classes here.
"""

from __future__ import annotations

from wire.errors import (
    Aborted,
    AlreadyExists,
    Cancelled,
    DeadlineExceeded,
    FailedPrecondition,
    InvalidArgument,
    NotFound,
    OutOfRange,
    PermissionDenied,
    ResourceExhausted,
    TelerobotError,
    Unauthenticated,
    Unavailable,
    Unimplemented,
    error_for_status,
)

__all__ = [
    "Aborted", "AlreadyExists", "Cancelled", "DeadlineExceeded", "FailedPrecondition",
    "InvalidArgument", "NotFound", "OutOfRange", "PermissionDenied", "ResourceExhausted",
    "TelerobotError", "Unauthenticated", "Unavailable", "Unimplemented", "error_for_status",
]
