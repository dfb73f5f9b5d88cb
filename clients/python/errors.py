"""Every failed call, sync or async, unary or stream, becomes an error of the project's one
family (wire/errors.py): the class for its status code, carrying

- ``code``: the ``grpc.StatusCode``;
- ``message``: the server's message (it says what to do next);
- ``reason`` and ``domain``: the ``google.rpc.ErrorInfo`` detail the telerobot servers attach
  (domain ``telerobot.v1``, a stable UPPER_SNAKE_CASE reason such as ``NO_CONTROL``), or None
  when the status carries none (errors made by gRPC itself, or calls forwarded through the
  DecisionServer, whose forwarding keeps the code and message but not the backend's reason);
- ``method``: the full method name, ``/telerobot.v1.ProxyRobot/MoveJointsIncremental``.

A few errors are made on the client side and say so in their message: a Teleoperate ack that
did not come within its timeout, a channel that did not connect in ``wait_for_ready``; they use
the status code gRPC itself would use (DEADLINE_EXCEEDED, UNAVAILABLE) and have no reason.
"""

from __future__ import annotations

import grpc
from google.rpc import error_details_pb2, status_pb2

from wire.errors import TelerobotError, error_for_status

STATUS_DETAILS_KEY = "grpc-status-details-bin"


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


def from_rpc_error(error: grpc.RpcError, method: str | None = None) -> TelerobotError:
    """The typed error for a failed call (a sync ``grpc.RpcError`` or a ``grpc.aio.AioRpcError``),
    with the ErrorInfo reason and domain read from the status details in its trailers."""
    code = error.code() if callable(getattr(error, "code", None)) else grpc.StatusCode.UNKNOWN
    details = error.details() if callable(getattr(error, "details", None)) else None
    trailers = (error.trailing_metadata()
                if callable(getattr(error, "trailing_metadata", None)) else None)
    info = _error_info(trailers)
    code = code or grpc.StatusCode.UNKNOWN
    return error_for_status(code.name, details or str(code), info.reason if info else None,
                            domain=info.domain if info else None, method=method)
