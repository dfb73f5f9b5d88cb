"""The gRPC side of the runtime: lanes for every call, and domain errors as status codes.

`LaneInterceptor` wraps every method handler of a server:
- unary calls run on the lane the RPC declares in its proto (`default_lane`), or a lower one
  the client asks for in the `telerobot-lane` metadata key: a client may lower its call, never
  raise it above the declared lane (nor above the server's `client_lane_limit`), so no caller
  can crowd the high lane the lease holder's renewals run on;
- streaming calls keep their gRPC thread (a stream would pin a lane thread for its whole life)
  but count against caps on open streams (`CallSlots`): the server's (its ports together), and
  each caller's. A caller is the authenticated identity (certificate or token), or, for a
  caller without one, its peer's address; unary calls in flight are capped per caller too.
  On a station's inner port the station's own streams (the DecisionServer's forwards) have room
  of their own, and no per-caller cap. Over a cap: RESOURCE_EXHAUSTED with an ErrorInfo reason
  (STREAMS_EXHAUSTED, CALLER_STREAMS_EXHAUSTED, CALLER_CALLS_EXHAUSTED), counted in the audit
  log's refusals (when the server keeps one) and said in the log (at most once a minute);
- on a sync server (`read_first`) each unary call takes its slot before its request arrives:
  its handler is served as a client stream whose one message it reads itself, so a call that
  sends its headers and never its body holds one of its caller's slots, and a caller over its
  cap is refused at once instead of keeping a thread waiting for a body;
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
  fires only for a call that carries a valid token. A plaintext server may audit too (its
  `security` then authenticates nobody: services/runtime/auth.py);
- with `metrics` (services.runtime.metrics), every call is counted by method and status code
  as it ends, and a unary call's time in the server goes into a latency histogram. A metric
  that fails never fails the call.
"""

from __future__ import annotations

import contextlib
import logging
import threading
import time
from collections.abc import Callable, Iterable, Iterator
from concurrent.futures import CancelledError
from dataclasses import dataclass

import grpc
from google.protobuf.message import DecodeError, Message
from google.rpc import code_pb2, error_details_pb2, status_pb2
from grpc_status import rpc_status

from services.common.wakeup import Wakeup
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
from services.security.roles import Role
from wire.addresses import is_loopback
from wire.errors import TelerobotError
from wire.metadata import LANE_METADATA_KEY

log = logging.getLogger(__name__)

ERROR_DOMAIN = "telerobot.v1"

# Streams open on a server, its ports together (the DecisionServer's certificate and token
# ports share them), not counting the station's own on an inner port.
DEFAULT_MAX_STREAMS = 64
# What one caller may hold on a server at once: open streams, and unary calls in flight (from
# their headers to their answer, their time queued on a lane included). An operator's station
# opens a handful of streams (Teleoperate, events, state, wrench, images), a web console tab
# three; 32 calls is under the high lane's room (8 threads, 64 queued), so no caller alone
# fills it.
STREAMS_PER_CALLER = 16
CALLS_PER_CALLER = 32
# On an inner port (ProxyRobot, ForceSensor, StereoCamera), room for the station's own streams
# beside everyone else's DEFAULT_MAX_STREAMS: as many as the DecisionServer forwards at most
# (its DEFAULT_MAX_STREAMS, both ports together) plus its own follow and health streams, so the
# others' streams never refuse the station's.
STATION_OWN_STREAMS = 16
STATION_STREAMS = DEFAULT_MAX_STREAMS + STATION_OWN_STREAMS
# Calls refused for room are said in the log at most this often (their count since the last).
REFUSAL_WARNING_INTERVAL_S = 60.0


@dataclass(frozen=True)
class Holder:
    """Whose slots a call takes. `key` the caller's (None: no per-caller cap, as for the
    station on its inner port and for loopback in plaintext); `station`: the station's own room
    on an inner port; `name` says who in a refusal; `caller`: the authenticated caller, if
    any (for the audit of a refusal)."""

    key: str | None
    name: str
    station: bool = False
    caller: Caller | None = None


class SlotRefused(Exception):
    """No room for a call: `message` and the ErrorInfo `reason` of its RESOURCE_EXHAUSTED."""

    def __init__(self, message: str, reason: str):
        super().__init__(message)
        self.message, self.reason = message, reason


class CallSlots:
    """A server's open streams and unary calls in flight, by caller; its ports share one.

    A stream takes one of `max_streams` (or, for the station on an inner port, one of
    `station_streams` when that is not 0) and one of its caller's `streams_per_caller`; a unary
    call one of its caller's `calls_per_caller` (the server's bound on calls is gRPC's
    `maximum_concurrent_rpcs`, services/runtime/server.py). A holder without a key has no
    per-caller cap."""

    def __init__(self, max_streams: int = DEFAULT_MAX_STREAMS,
                 streams_per_caller: int = STREAMS_PER_CALLER,
                 calls_per_caller: int = CALLS_PER_CALLER, station_streams: int = 0):
        if min(max_streams, streams_per_caller, calls_per_caller) < 1 or station_streams < 0:
            raise ValueError("stream and call caps must be >= 1 (station_streams >= 0)")
        self.max_streams = max_streams
        self.streams_per_caller = streams_per_caller
        self.calls_per_caller = calls_per_caller
        self.station_streams = station_streams
        self._lock = threading.Lock()
        self._streams = 0  # everyone's but the station's own room
        self._station = 0
        self._calls = 0
        self._held: dict[str, list[int]] = {}  # key -> [streams, calls]; gone at [0, 0]

    @property
    def open_streams(self) -> int:
        return self._streams + self._station

    @property
    def calls_in_flight(self) -> int:
        """Unary calls between their headers and their answer, every caller's."""
        return self._calls

    def held_by(self, key: str) -> tuple[int, int]:
        """(streams, unary calls) the caller `key` holds now."""
        with self._lock:
            streams, calls = self._held.get(key, (0, 0))
        return streams, calls

    def take(self, holder: Holder, stream: bool) -> None:
        """Take a stream's or a unary call's slot for `holder`; SlotRefused when the caller
        or the server has no room. Give it back with give()."""
        station_room = stream and holder.station and self.station_streams > 0
        with self._lock:
            held = self._held.get(holder.key) if holder.key is not None else None
            if holder.key is not None:
                cap = self.streams_per_caller if stream else self.calls_per_caller
                if held is not None and held[0 if stream else 1] >= cap:
                    raise SlotRefused(*_caller_refusal(holder.name, cap, stream))
            if station_room and self._station >= self.station_streams:
                raise SlotRefused(
                    f"the station's {self.station_streams} streams on this server are open; "
                    "close one or retry later", "STREAMS_EXHAUSTED")
            if stream and not station_room and self._streams >= self.max_streams:
                raise SlotRefused(f"{self.max_streams} streams are open on this server; close "
                                  "one or retry later", "STREAMS_EXHAUSTED")
            if station_room:
                self._station += 1
            elif stream:
                self._streams += 1
            else:
                self._calls += 1
            if holder.key is not None:
                if held is None:
                    held = self._held[holder.key] = [0, 0]
                held[0 if stream else 1] += 1

    def give(self, holder: Holder, stream: bool) -> None:
        with self._lock:
            if stream and holder.station and self.station_streams > 0:
                self._station -= 1
            elif stream:
                self._streams -= 1
            else:
                self._calls -= 1
            if holder.key is not None:
                held = self._held[holder.key]
                held[0 if stream else 1] -= 1
                if held == [0, 0]:
                    del self._held[holder.key]


def _caller_refusal(name: str, cap: int, stream: bool) -> tuple[str, str]:
    if stream:
        return (f"{name} already holds {cap} streams on this server, as many as one caller "
                "may: close one before opening another", "CALLER_STREAMS_EXHAUSTED")
    return (f"{name} already has {cap} calls in flight on this server, as many as one caller "
            "may: wait for one to end", "CALLER_CALLS_EXHAUSTED")


class RefusalWarnings:
    """Says in the log that calls are refused for room: the first at once, then at most once
    per `interval_s`, with how many were refused since the last warning (a flood must not
    flood the log too)."""

    def __init__(self, interval_s: float = REFUSAL_WARNING_INTERVAL_S,
                 clock: Callable[[], float] = time.monotonic):
        self._interval_s = interval_s
        self._clock = clock
        self._lock = threading.Lock()
        self._unsaid = 0
        self._next = -float("inf")

    def refused(self, method: str, who: str, reason: str) -> None:
        with self._lock:
            self._unsaid += 1
            now = self._clock()
            if now < self._next:
                return
            count, self._unsaid, self._next = self._unsaid, 0, now + self._interval_s
        log.warning("refused %d call(s) for room since the last warning, the latest %s from %s "
                    "(%s); the audit log's refusals count them by caller", count, method, who,
                    reason)


def peer_host(peer: str) -> str:
    """The host of a gRPC peer string ("ipv4:127.0.0.1:5000", "ipv6:[::1]:5000"), without
    its port: a caller that opens many connections is still one address."""
    kind, _, address = peer.partition(":")
    if kind == "unix" or not address:
        return peer
    if address.startswith("["):
        return address[1:].partition("]")[0]
    return address.rpartition(":")[0] or address


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
                 max_streams: int = DEFAULT_MAX_STREAMS,
                 on_emergency_call: Callable[[], None] | None = None,
                 security: CallSecurity | None = None, metrics: ServiceMetrics | None = None,
                 slots: CallSlots | None = None, read_first: bool = False,
                 waits_on_loop: bool = False):
        """`slots`: the server's streams and calls by caller, shared by its ports (a new one
        of `max_streams` when None). `read_first`: each unary call takes its slot before its
        request is read (the sync server; a grpc.aio server reads it on its loop first).
        `waits_on_loop`: a stream's Wakeups (services/common/wakeup.py) pass up to the server's
        event loop (grpc.aio); otherwise the stream's thread waits for them here."""
        self._executor = executor
        self._metrics = metrics
        self._on_emergency_call = on_emergency_call
        self._security = security
        self._client_lane_limit = client_lane_limit
        self.slots = slots if slots is not None else CallSlots(max_streams)
        self._read_first = read_first
        self._waits_here = not waits_on_loop
        self.refusal_warnings = RefusalWarnings()

    @property
    def open_streams(self) -> int:
        """Streams open on the server (every port that shares its slots)."""
        return self.slots.open_streams

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
        unary = not handler.request_streaming and not handler.response_streaming
        return _measured(wrapped, method, self._metrics, timed=unary)

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
        declared = declared_lane(method)
        if requested is None:
            return declared
        lane = Lane.parse(requested)  # ValueError for an unknown name
        # Lowering is the client's to choose; raising is not: never above the RPC's declared
        # lane, nor above the server's limit.
        return max(lane, self._client_lane_limit, declared)

    def _holder(self, context) -> Holder:
        """Whose slots the call takes: its authenticated identity, else its peer's address."""
        security = self._security
        peer = context.peer() or ""
        if security is not None and security.authenticates:
            try:
                caller = security.authenticate(context)
            except TelerobotError:  # refused later, by admit(), where the method needs it
                host = peer_host(peer)
                return Holder(f"peer {host}", f"unauthenticated callers from {host}")
            if security.inner_port and caller.role is Role.STATION:
                # The DecisionServer (and the launcher): bounded by its own caps at its door.
                return Holder(None, f"the station ({caller.identity})", station=True,
                              caller=caller)
            return Holder(f"identity {caller.identity}", f"identity {caller.identity!r}",
                          caller=caller)
        host = peer_host(peer)
        if peer.startswith("unix:") or is_loopback(f"{host}:0"):
            # Plaintext on loopback: every process of the host is one address (the station's
            # own services too), and any of them may command the arm anyway.
            return Holder(None, host)
        return Holder(f"peer {host}", f"peer {host}")

    @contextlib.contextmanager
    def _slot(self, context, method: str, stream: bool) -> Iterator[None]:
        """Hold the call's slot for the `with` block; RESOURCE_EXHAUSTED when there is no
        room, counted in the audit log's refusals and said in the log."""
        holder = self._holder(context)
        try:
            self.slots.take(holder, stream)
        except SlotRefused as refused:
            self._refused_for_room(method, holder, context, refused)
            abort(context, grpc.StatusCode.RESOURCE_EXHAUSTED, refused.message, refused.reason)
        try:
            yield
        finally:
            self.slots.give(holder, stream)

    def _refused_for_room(self, method: str, holder: Holder, context,
                          refused: SlotRefused) -> None:
        try:  # a failed audit or warning never changes the answer
            if self._security is not None:
                self._security.refused_for_room(method, holder.caller, context, refused.reason,
                                                refused.message)
            self.refusal_warnings.refused(method, holder.name, refused.reason)
        except Exception:  # noqa: BLE001
            log.exception("cannot record a refusal of %s", method)

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
            if not audited:
                return contextlib.nullcontext()
            return _audited_call(security, method, caller, context)

        def resolve_lane(context) -> Lane:
            try:
                return self._lane_for(method, requested)
            except ValueError as exc:
                abort(context, grpc.StatusCode.INVALID_ARGUMENT,
                      f"bad {LANE_METADATA_KEY} metadata: {exc}", "BAD_LANE")

        # On a sync server the handler reads a unary call's request itself (see read_first).
        reads_first = self._read_first

        def first(raw, context):
            return _only_request(raw, context, method) if reads_first else raw

        def call_slot(context):
            # A stop is never refused for room either.
            return (contextlib.nullcontext() if emergency
                    else self._slot(context, method, stream=False))

        if handler.unary_unary:
            behavior = handler.unary_unary

            def unary_unary(raw, context):
                with call_slot(context):
                    raw = first(raw, context)
                    lane = resolve_lane(context)
                    caller = admit(context)
                    request = _decode_or_abort(decode, raw, context, emergency)
                    with audit(caller, context):
                        return self._run_on_lane(lane, behavior, request, context, caller)

            if reads_first:
                return grpc.stream_unary_rpc_method_handler(unary_unary, None, encode)
            return grpc.unary_unary_rpc_method_handler(unary_unary, None, encode)

        if handler.unary_stream:
            behavior = handler.unary_stream

            def unary_stream(raw, context):
                with self._slot(context, method, stream=True):
                    raw = first(raw, context)
                    resolve_lane(context)
                    caller = admit(context)
                    request = _decode_or_abort(decode, raw, context)
                    with audit(caller, context):
                        yield from _streamed(behavior, request, context, caller,
                                             self._waits_here)

            if reads_first:
                return grpc.stream_stream_rpc_method_handler(unary_stream, None, encode)
            return grpc.unary_stream_rpc_method_handler(unary_stream, None, encode)

        if handler.stream_unary:
            behavior = handler.stream_unary

            def stream_unary(raw_iterator, context):
                with self._slot(context, method, stream=True):
                    resolve_lane(context)
                    caller = admit(context)
                    with audit(caller, context):
                        return _call(behavior, _decoded(raw_iterator, decode, context),
                                     context, caller)

            return grpc.stream_unary_rpc_method_handler(stream_unary, None, encode)

        behavior = handler.stream_stream

        def stream_stream(raw_iterator, context):
            with self._slot(context, method, stream=True):
                resolve_lane(context)
                caller = admit(context)
                with audit(caller, context):
                    yield from _streamed(behavior, _decoded(raw_iterator, decode, context),
                                         context, caller, self._waits_here)

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


def _streamed(behavior: Callable, request, context, caller: Caller | None = None,
              waits_here: bool = True) -> Iterator:
    """A streaming handler's responses, produced as `caller`, domain errors as status codes;
    with `waits_here`, the Wakeups it yields are waited for on this thread."""
    with acting_as(caller):
        try:
            responses = behavior(request, context)
            yield from _waiting_here(responses) if waits_here else responses
        except TelerobotError as error:
            abort_with_error(context, error)


def _waiting_here(responses: Iterable) -> Iterator:
    """`responses` without their Wakeups: each is waited for on the stream's own thread."""
    responses = iter(responses)
    try:
        for response in responses:
            if type(response) is Wakeup:
                response.wait()
            else:
                yield response
    finally:
        close = getattr(responses, "close", None)
        if close is not None:  # the client left: the handler's finally blocks run now
            close()


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


def _measured(handler: grpc.RpcMethodHandler, method: str, metrics: ServiceMetrics,
              timed: bool | None = None) -> grpc.RpcMethodHandler:
    """`handler` with each call counted by its status code as it ends, and a unary call's
    time in the server observed (`timed`: whether the RPC is unary, which a sync server's
    handler no longer says: it reads its request itself)."""

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
            except grpc.RpcError:  # the call broke under a read of its request
                settle(context, started, unary, code="CANCELLED")
                raise
            except BaseException:
                settle(context, started, unary, default="UNKNOWN")
                raise
            settle(context, started, unary)
            return response
        return call

    if timed is None:
        timed = not handler.request_streaming and not handler.response_streaming
    if handler.unary_unary:
        return handler._replace(unary_unary=answered_once(handler.unary_unary, timed))
    if handler.stream_unary:
        return handler._replace(stream_unary=answered_once(handler.stream_unary, timed))

    streaming = handler.unary_stream or handler.stream_stream

    def streamed(request, context):
        started = time.perf_counter()
        try:
            yield from streaming(request, context)
        except (GeneratorExit, grpc.RpcError):  # the client left
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


def _only_request(raw_iterator: Iterator[bytes], context, method: str) -> bytes:
    """A unary call's one request, read from its stream of requests (grpc.RpcError if the
    call ends meanwhile); none is what grpcio answers to it: UNIMPLEMENTED."""
    raw = next(raw_iterator, None)
    if raw is None:
        abort(context, grpc.StatusCode.UNIMPLEMENTED,
              f'"{method}" requires exactly one request message.', "NO_REQUEST")
    return raw


def _decoded(raw_iterator: Iterator[bytes], decode: Callable, context) -> Iterator:
    for raw in raw_iterator:
        yield _decode_or_abort(decode, raw, context)
