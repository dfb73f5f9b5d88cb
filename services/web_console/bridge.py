"""Every unary and server-streaming RPC on the DecisionServer's port, served to browsers over
the Connect protocol and forwarded to the DecisionServer over gRPC.

The endpoints are built from the contracts' descriptors, not written per method: a method the
protos add is served on the next start. Requests are decoded and re-encoded by the protobuf
runtime (connect-python handles the Connect framing, its binary and JSON codecs, timeouts and
error bodies), so what reaches the DecisionServer is a well-formed message of the method's
type; the DecisionServer's own checks (validation, lease, role, audit) then apply as to any
client.
"""

from __future__ import annotations

import gzip
import logging
import zlib
from collections.abc import AsyncIterator, Callable, Iterable, Iterator, Mapping

import grpc
from connectrpc import _codec
from connectrpc.code import Code
from connectrpc.errors import ConnectError
from connectrpc.method import IdempotencyLevel, MethodInfo
from connectrpc.request import RequestContext
from connectrpc.server import ConnectASGIApplication, Endpoint
from google.protobuf import descriptor_pool, json_format, message_factory
from google.protobuf.descriptor import MethodDescriptor, ServiceDescriptor
from google.protobuf.message import DecodeError
from google.rpc import status_pb2

# Registers the contracts' descriptors in the default pool.
from telerobot.v1 import (  # noqa: F401
    decision_server_pb2,
    force_sensor_pb2,
    proxy_robot_pb2,
    stereo_camera_pb2,
)
from wire.metadata import LANE_METADATA_KEY, LEASE_METADATA_KEY

log = logging.getLogger(__name__)

# What the DecisionServer's port serves (it forwards ProxyRobot, ForceSensor and StereoCamera).
SERVICES = ("telerobot.v1.DecisionServer", "telerobot.v1.ProxyRobot",
            "telerobot.v1.ForceSensor", "telerobot.v1.StereoCamera")
# Browser headers that travel on as gRPC metadata: the lease, the lane, the bearer token.
FORWARDED_HEADERS = (LEASE_METADATA_KEY, LANE_METADATA_KEY, "authorization")
# A call without a Connect timeout gets this deadline (streams get none).
DEFAULT_UNARY_TIMEOUT_S = 30.0
# The largest request a browser may send, in bytes (a Teleoperate command is under 200): its
# message once decompressed, and its body as it comes (the body has room for the Connect
# envelope's 5 bytes and gzip's framing of an incompressible message).
READ_MAX_BYTES = 1 << 20
BODY_MAX_BYTES = READ_MAX_BYTES + 4096
_STATUS_DETAILS_KEY = "grpc-status-details-bin"


class Upstream:
    """Where calls go: the DecisionServer's channel, and one for the camera's pairs (see
    wire.stereo: a window of about one message, so a slow browser gets fresh pairs)."""

    def __init__(self, channel: grpc.aio.Channel, stereo_channel: grpc.aio.Channel,
                 refusal: str = "", needs_token: bool = False):
        self.channel = channel
        self.stereo_channel = stereo_channel
        self.needs_token = needs_token  # the DecisionServer's token port: every call needs one
        # Non-empty: every call is refused with UNAUTHENTICATED and this message (a TLS station
        # whose DecisionServer has no token port: a browser has no certificate to present).
        self.refusal = refusal

    def channel_for(self, service: str) -> grpc.aio.Channel:
        return self.stereo_channel if service == "telerobot.v1.StereoCamera" else self.channel


def forwarded_metadata(headers: Mapping[str, str] | Iterable[tuple[str, str]]
                       ) -> list[tuple[str, str]]:
    """The gRPC metadata a browser's request headers carry on (FORWARDED_HEADERS only)."""
    items = headers.items() if isinstance(headers, Mapping) else headers
    return [(key.lower(), value) for key, value in items
            if key.lower() in FORWARDED_HEADERS and value]


def connect_error(error: grpc.aio.AioRpcError) -> ConnectError:
    """The gRPC status as the Connect error of the same code, with its details
    (google.rpc.ErrorInfo and the like)."""
    code = Code[error.code().name] if error.code().name in Code.__members__ else Code.UNKNOWN
    details = []
    for key, value in error.trailing_metadata() or ():
        if key == _STATUS_DETAILS_KEY and isinstance(value, bytes):
            details = list(status_pb2.Status.FromString(value).details)
    return ConnectError(code, error.details() or "", details)


class _StrictCodec:
    """A codec whose undecodable input is the caller's error: INVALID_ARGUMENT (HTTP 400),
    as the Connect protocol says, where connect-python 0.9 answers UNKNOWN (HTTP 500)."""

    def __init__(self, inner):
        self._inner = inner

    def name(self) -> str:
        return self._inner.name()

    def encode(self, message) -> bytes:
        return self._inner.encode(message)

    def decode(self, data, message):
        try:
            return self._inner.decode(data, message)
        except (DecodeError, json_format.ParseError, UnicodeDecodeError, ValueError) as exc:
            raise ConnectError(Code.INVALID_ARGUMENT,
                               f"the request is not a {message.DESCRIPTOR.full_name}: {exc}"
                               ) from None


# connect-python keeps its codecs in one module-level registry and offers no way to pass
# others (its own TODO says so); wrap them there. pyproject pins connect-python below 0.10,
# and tests/web_console checks the 400s.
for _name, _inner in list(_codec._codecs.items()):
    if not isinstance(_inner, _StrictCodec):
        _codec._codecs[_name] = _StrictCodec(_inner)


class BoundedGzip:
    """gzip for the Connect bridge that stops decompressing past `limit` bytes: a request whose
    message would be larger gets RESOURCE_EXHAUSTED after at most `limit` + 1 bytes were
    produced, not after the whole of it (connect-python's own gzip inflates a message whole
    before comparing it with read_max_bytes: a megabyte of zeros inflates to a gigabyte)."""

    def __init__(self, limit: int = READ_MAX_BYTES):
        self.limit = limit

    def name(self) -> str:
        return "gzip"

    def compress(self, data) -> bytes:
        return gzip.compress(data, compresslevel=6)

    def decompress(self, data) -> bytes:
        out = bytearray()
        rest = bytes(data)
        while rest:  # one gzip member after another, as gzip.decompress reads them
            member = zlib.decompressobj(wbits=16 + zlib.MAX_WBITS)
            try:
                out += member.decompress(rest, self.limit + 1 - len(out))
            except zlib.error as error:
                raise ConnectError(Code.INVALID_ARGUMENT, f"the request is not valid gzip: "
                                   f"{error}") from None
            if len(out) > self.limit:
                raise ConnectError(Code.RESOURCE_EXHAUSTED, "the request's message is larger "
                                   f"than {self.limit} bytes once decompressed")
            if not member.eof:
                raise ConnectError(Code.INVALID_ARGUMENT, "the request's gzip data is cut short")
            rest = member.unused_data.lstrip(b"\0")  # gzip allows zeros between members
        return bytes(out)


def _timeout_s(ctx: RequestContext) -> float:
    timeout_ms = ctx.timeout_ms()
    return timeout_ms / 1000.0 if timeout_ms is not None else DEFAULT_UNARY_TIMEOUT_S


def served_methods() -> Iterator[tuple[ServiceDescriptor, MethodDescriptor]]:
    """Every unary and server-streaming method of SERVICES (client and bidirectional streams
    are not Connect-over-HTTP/1.1 material: Teleoperate has its WebSocket)."""
    pool = descriptor_pool.Default()
    for name in SERVICES:
        service = pool.FindServiceByName(name)
        for method in service.methods:
            if not method.client_streaming:
                yield service, method


def method_info(service: ServiceDescriptor, method: MethodDescriptor) -> tuple[str, MethodInfo]:
    """The method's path ("/telerobot.v1.Service/Method") and what connect-python needs of it."""
    info = MethodInfo(name=method.name, service_name=service.full_name,
                      input=message_factory.GetMessageClass(method.input_type),
                      output=message_factory.GetMessageClass(method.output_type),
                      idempotency_level=IdempotencyLevel.UNKNOWN)
    return f"/{service.full_name}/{method.name}", info


def _endpoint(upstream: Upstream, service: ServiceDescriptor, method: MethodDescriptor):
    path, info = method_info(service, method)
    request_cls, response_cls = info.input, info.output
    channel = upstream.channel_for(service.full_name)

    def refuse_if_closed():
        if upstream.refusal:
            raise ConnectError(Code.UNAUTHENTICATED, upstream.refusal)

    if method.server_streaming:
        call_stream = channel.unary_stream(path, request_serializer=request_cls.SerializeToString,
                                           response_deserializer=response_cls.FromString)

        async def server_stream(request, ctx: RequestContext) -> AsyncIterator:
            refuse_if_closed()
            timeout_ms = ctx.timeout_ms()
            call = call_stream(request, metadata=forwarded_metadata(ctx.request_headers()),
                               timeout=timeout_ms / 1000.0 if timeout_ms else None)
            try:
                async for response in call:
                    yield response
            except grpc.aio.AioRpcError as error:
                raise connect_error(error) from None
            finally:
                call.cancel()  # the browser left: end the upstream stream at once

        return path, Endpoint.server_stream(method=info, function=server_stream)

    call_unary = channel.unary_unary(path, request_serializer=request_cls.SerializeToString,
                                     response_deserializer=response_cls.FromString)

    async def unary(request, ctx: RequestContext):
        refuse_if_closed()
        try:
            return await call_unary(request, metadata=forwarded_metadata(ctx.request_headers()),
                                    timeout=_timeout_s(ctx))
        except grpc.aio.AioRpcError as error:
            raise connect_error(error) from None

    return path, Endpoint.unary(method=info, function=unary)


def endpoints(upstream: Upstream) -> dict[str, Endpoint]:
    """Path -> endpoint for every served method, forwarded to the DecisionServer."""
    return dict(_endpoint(upstream, service, method) for service, method in served_methods())


class ConnectBridge(ConnectASGIApplication):
    """The ASGI application serving `endpoints_of(upstream)` over the Connect protocol: the
    DecisionServer's methods (`endpoints`), or the observation through a router's
    (services.web_console.watch)."""

    def __init__(self, upstream, endpoints_of: Callable[..., dict[str, Endpoint]] = endpoints):
        super().__init__(service=upstream, endpoints=endpoints_of, read_max_bytes=READ_MAX_BYTES,
                         compressions=[BoundedGzip(READ_MAX_BYTES)])

    @property
    def path(self) -> str:
        return "/telerobot.v1."  # informational: the router sends every /telerobot.v1.* here
