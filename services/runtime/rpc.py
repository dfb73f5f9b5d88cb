"""The gRPC side of the runtime: lanes for every call, and domain errors as status codes.

`LaneInterceptor` wraps every method handler of a server:
- unary calls run on the lane the RPC declares in its proto (`default_lane`), or the lane the
  client asks for in the `telerobot-lane` metadata key, clamped to the server's limit;
- streaming calls keep their gRPC thread (a stream would pin a lane thread for its whole life)
  but count against a cap on open streams;
- requests are decoded and checked here (services/runtime/validation.py), so a malformed
  message, an unknown enum value or an over-long string gets INVALID_ARGUMENT naming the
  field, instead of grpcio's INTERNAL or a handler's UNKNOWN;
- `TelerobotError`s raised by servicers become their status code with a google.rpc.ErrorInfo;
- a response a servicer already serialized (`bytes`, such as one message fanned out to many
  streams) goes out as it is; every other response goes through the method's serializer;
- an emergency-lane call (EmergencyStop) calls the server's `on_emergency_call` hook the moment
  it arrives, on gRPC's polling thread, before its request is read or any thread picks it up:
  the service latches its stop there, so the stop never waits behind a busy pool or lane. The
  handler then runs as usual (with the reason) and answers. Stopping early is always safe;
- with TLS on (`security`), each call is authenticated and authorized before its request is
  decoded, runs as its caller (services.security.caller), and command-class calls are audited
  (services/runtime/auth.py). The early stop needs no check on a port that requires client
  certificates: the handshake already proved the caller is the station's. On a token port it
  fires only for a call that carries a valid token;
- with `metrics` (services.runtime.metrics), every call is counted by method and status code
  as it ends, and a unary call's time in the server goes into a latency histogram. A metric
  that fails never fails the call.
"""

from __future__ import annotations

import contextlib
import logging
import threading
import time
from collections.abc import Callable, Iterator
from concurrent.futures import CancelledError

import grpc
from google.protobuf.message import DecodeError, Message
from google.rpc import code_pb2, error_details_pb2, status_pb2
from grpc_status import rpc_status

from services.runtime.auth import CallSecurity
from services.runtime.lanes import (  # noqa: F401 - LANE_TO_PROTO re-exported
    LANE_TO_PROTO,
    Lane,
    LaneExecutor,
    LaneExecutorClosed,
    LaneFull,
    declared_lane,
)
from services.runtime.metrics import ServiceMetrics
from services.runtime.validation import check_request
from services.security.caller import Caller, acting_as
from wire.errors import TelerobotError
from wire.metadata import LANE_METADATA_KEY

log = logging.getLogger(__name__)

ERROR_DOMAIN = "telerobot.v1"

def error_status(code: grpc.StatusCode, message: str, reason: str) -> status_pb2.Status:
    """A google.rpc.Status carrying an ErrorInfo(reason, domain) detail."""
    info = error_details_pb2.ErrorInfo(reason=reason, domain=ERROR_DOMAIN)
    status = status_pb2.Status(code=getattr(code_pb2, code.name), message=message)
    status.details.add().Pack(info)
    return status


def abort(context: grpc.ServicerContext, code: grpc.StatusCode, message: str, reason: str):
    """End the call with `code`, `message` and an ErrorInfo detail. Never returns."""
    context.abort_with_status(rpc_status.to_status(error_status(code, message, reason)))


def abort_with_error(context: grpc.ServicerContext, error: TelerobotError):
    """End the call with the status code that matches a domain error."""
    abort(context, grpc.StatusCode[error.status_name], error.message,
          error.reason or error.status_name)


class LaneInterceptor(grpc.ServerInterceptor):
    """Dispatches every call of a server onto its priority lane; see the module docstring."""

    def __init__(self, executor: LaneExecutor, client_lane_limit: Lane = Lane.HIGH,
                 max_streams: int = 64, on_emergency_call: Callable[[], None] | None = None,
                 security: CallSecurity | None = None, metrics: ServiceMetrics | None = None):
        self._executor = executor
        self._metrics = metrics
        self._on_emergency_call = on_emergency_call
        self._security = security
        self._client_lane_limit = client_lane_limit
        self._max_streams = max_streams
        self._open_streams = 0
        self._streams_lock = threading.Lock()

    @property
    def open_streams(self) -> int:
        return self._open_streams

    def intercept_service(self, continuation, handler_call_details):
        handler = continuation(handler_call_details)
        if handler is None:
            return None  # unknown method: grpcio answers UNIMPLEMENTED
        method = handler_call_details.method
        metadata = handler_call_details.invocation_metadata
        if (self._on_emergency_call is not None and declared_lane(method) == Lane.EMERGENCY
                and self._may_stop_early(metadata)):
            started = time.perf_counter()
            self._emergency_arrived(method)
            if self._metrics is not None:
                self._metrics.emergency_stop_latched(time.perf_counter() - started)
        wrapped = self._wrap(handler, method, _requested_lane(metadata))
        if self._metrics is None:
            return wrapped
        return _measured(wrapped, method, self._metrics)

    def _may_stop_early(self, metadata) -> bool:
        security = self._security
        return security is None or security.tokens is None or security.token_is_valid(metadata)

    def _emergency_arrived(self, method: str) -> None:
        try:
            self._on_emergency_call()
        except Exception:  # noqa: BLE001 - the handler still runs and stops the arm
            log.exception("the early stop for %s failed; the call's handler stops the arm",
                          method)

    # -- wrapping ---------------------------------------------------------------------------

    def _lane_for(self, method: str, requested: str | None) -> Lane:
        if requested is None:
            return declared_lane(method)
        lane = Lane.parse(requested)  # ValueError for an unknown name
        return max(lane, self._client_lane_limit)  # clamp: never above the limit

    def _wrap(self, handler: grpc.RpcMethodHandler, method: str, requested: str | None):
        decode = handler.request_deserializer or (lambda raw: raw)
        encode = _passing_bytes(handler.response_serializer)
        # A stop is never refused for its words: an over-long reason is cut, not refused.
        emergency = declared_lane(method) == Lane.EMERGENCY
        security = self._security
        audited = security is not None and security.audited(method)

        def admit(context) -> Caller | None:
            if security is None:
                return None
            try:
                return security.admit(method, context)
            except TelerobotError as error:
                abort_with_error(context, error)

        def audit(caller: Caller | None, context):
            if not audited or security.station_internal(caller):
                return contextlib.nullcontext()
            return _audited_call(security, method, caller, context)

        def resolve_lane(context) -> Lane:
            try:
                return self._lane_for(method, requested)
            except ValueError as exc:
                abort(context, grpc.StatusCode.INVALID_ARGUMENT,
                      f"bad {LANE_METADATA_KEY} metadata: {exc}", "BAD_LANE")

        if handler.unary_unary:
            behavior = handler.unary_unary

            def unary_unary(raw, context):
                lane = resolve_lane(context)
                caller = admit(context)
                request = _decode_or_abort(decode, raw, context, emergency)
                with audit(caller, context):
                    return self._run_on_lane(lane, behavior, request, context, caller)

            return grpc.unary_unary_rpc_method_handler(unary_unary, None, encode)

        if handler.unary_stream:
            behavior = handler.unary_stream

            def unary_stream(raw, context):
                resolve_lane(context)
                caller = admit(context)
                request = _decode_or_abort(decode, raw, context)
                with audit(caller, context):
                    yield from self._run_stream(behavior, request, context, caller)

            return grpc.unary_stream_rpc_method_handler(unary_stream, None, encode)

        if handler.stream_unary:
            behavior = handler.stream_unary

            def stream_unary(raw_iterator, context):
                resolve_lane(context)
                caller = admit(context)
                with self._stream_slot(context), audit(caller, context):
                    return _call(behavior, _decoded(raw_iterator, decode, context), context,
                                 caller)

            return grpc.stream_unary_rpc_method_handler(stream_unary, None, encode)

        behavior = handler.stream_stream

        def stream_stream(raw_iterator, context):
            resolve_lane(context)
            caller = admit(context)
            with audit(caller, context):
                yield from self._run_stream(behavior, _decoded(raw_iterator, decode, context),
                                            context, caller)

        return grpc.stream_stream_rpc_method_handler(stream_stream, None, encode)

    def _run_on_lane(self, lane: Lane, behavior: Callable, request, context,
                     caller: Caller | None = None):
        try:
            # On this gRPC thread when the lane has room (no hand-over to a lane thread and
            # back); queued on the lane otherwise.
            future = self._executor.run_here(
                lane, lambda: _call(behavior, request, context, caller))
        except LaneFull as exc:
            abort(context, grpc.StatusCode.RESOURCE_EXHAUSTED, str(exc), "LANE_SATURATED")
        except LaneExecutorClosed as exc:
            abort(context, grpc.StatusCode.UNAVAILABLE, str(exc), "SHUTTING_DOWN")
        context.add_callback(future.cancel)  # drop it from the queue if the client leaves
        try:
            return future.result()
        except CancelledError:
            abort(context, grpc.StatusCode.CANCELLED, "the call was cancelled before it ran",
                  "CANCELLED")

    def _run_stream(self, behavior: Callable, request, context,
                    caller: Caller | None = None) -> Iterator:
        with self._stream_slot(context), acting_as(caller):
            try:
                yield from behavior(request, context)
            except TelerobotError as error:
                abort_with_error(context, error)

    @contextlib.contextmanager
    def _stream_slot(self, context):
        """Hold one of the server's stream slots for the life of a stream."""
        with self._streams_lock:
            if self._open_streams >= self._max_streams:
                abort(context, grpc.StatusCode.RESOURCE_EXHAUSTED,
                      f"{self._max_streams} streams are open on this server; close one or "
                      "retry later", "STREAMS_EXHAUSTED")
            self._open_streams += 1
        try:
            yield
        finally:
            with self._streams_lock:
                self._open_streams -= 1


def _call(behavior: Callable, request, context, caller: Caller | None = None):
    """Run a handler as `caller`, turning domain errors into status codes."""
    try:
        if caller is None:
            return behavior(request, context)
        with acting_as(caller):
            return behavior(request, context)
    except TelerobotError as error:
        abort_with_error(context, error)


@contextlib.contextmanager
def _audited_call(security: CallSecurity, method: str, caller: Caller | None, context):
    """Record a command-class call in the audit log with how it ended."""
    try:
        yield
    except GeneratorExit:  # the client left a stream
        security.record(method, caller, context, "CANCELLED")
        raise
    except BaseException:  # an abort (its code is set) or the call cancelled under it
        code = context.code()
        security.record(method, caller, context, code.name if code else "CANCELLED",
                        context.details() or "")
        raise
    code = context.code()
    security.record(method, caller, context, code.name if code else "OK")


def _measured(handler: grpc.RpcMethodHandler, method: str, metrics: ServiceMetrics
              ) -> grpc.RpcMethodHandler:
    """`handler` with each call counted by its status code as it ends, and a unary call's
    time in the server observed."""

    def outcome(context, default: str) -> str:
        try:
            code = context.code()
            return default if code is None else code.name
        except Exception:  # noqa: BLE001 - a metric never fails a call
            return default

    def settle(context, started: float, unary: bool, code: str | None = None,
               default: str = "OK") -> None:
        metrics.rpc_done(method, code or outcome(context, default),
                         time.perf_counter() - started if unary else None)

    def answered_once(behavior, unary: bool):
        """A call answered with one response: a unary call (timed) or a client stream."""
        def call(request, context):
            started = time.perf_counter()
            try:
                response = behavior(request, context)
            except BaseException:
                settle(context, started, unary, default="UNKNOWN")
                raise
            settle(context, started, unary)
            return response
        return call

    if handler.unary_unary:
        return handler._replace(unary_unary=answered_once(handler.unary_unary, True))
    if handler.stream_unary:
        return handler._replace(stream_unary=answered_once(handler.stream_unary, False))

    streaming = handler.unary_stream or handler.stream_stream

    def streamed(request, context):
        started = time.perf_counter()
        try:
            yield from streaming(request, context)
        except GeneratorExit:  # the client left
            settle(context, started, False, code="CANCELLED")
            raise
        except BaseException:
            settle(context, started, False, default="UNKNOWN")
            raise
        settle(context, started, False)

    if handler.unary_stream:
        return handler._replace(unary_stream=streamed)
    return handler._replace(stream_stream=streamed)


def _passing_bytes(serialize: Callable | None) -> Callable | None:
    """The method's response serializer, except that bytes pass through unchanged."""
    if serialize is None:
        return None

    def serialize_unless_bytes(response):
        if type(response) is bytes:
            return response
        return serialize(response)

    return serialize_unless_bytes


def _requested_lane(metadata) -> str | None:
    for key, value in metadata or ():
        if key == LANE_METADATA_KEY:
            return value
    return None


def _decode_or_abort(decode: Callable, raw: bytes, context, emergency: bool = False):
    try:
        request = decode(raw)
    except (DecodeError, ValueError, TypeError) as exc:
        abort(context, grpc.StatusCode.INVALID_ARGUMENT,
              f"the request is not a valid message for this method: {exc}", "MALFORMED_REQUEST")
    if isinstance(request, Message):
        try:
            check_request(request, cut_long_strings=emergency)
        except TelerobotError as error:
            abort_with_error(context, error)
    return request


def _decoded(raw_iterator: Iterator[bytes], decode: Callable, context) -> Iterator:
    for raw in raw_iterator:
        yield _decode_or_abort(decode, raw, context)
