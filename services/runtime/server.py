"""create_server: a gRPC server with priority lanes, health, reflection and, optionally, TLS.

Security (see docs/security.md):
- without TLS a server listens only on loopback; a non-loopback address is refused unless the
  caller explicitly allows plaintext there (`--allow-plaintext-network`), and then it warns;
- with TLS (`ServerSecurity`) its port requires a client certificate from the station's CA,
  and every call is authorized by role (services/runtime/auth.py);
- the audit log (services.security.audit) is TLS's (`ServerSecurity.audit`), or, without TLS,
  `audit`: a plaintext server checks nobody, but records its command-class calls with the
  peer's address as the caller (services/runtime/auth.py);
- a server with a `token_address` also listens there with TLS but without client
  certificates, for callers with bearer tokens. That port is a second grpc.Server on the same
  servicers and lanes, so that its interceptor knows every caller on it came without a
  certificate (gRPC tells an interceptor nothing about the port a call came in on).

Room (see services/runtime/rpc.py's CallSlots): a server's ports share one count of streams
and calls by caller. Each grpc.Server accepts at most as many calls as its thread pool has
threads (`maximum_concurrent_rpcs`, sized from its lanes' capacity and its streams: one thread
per call a lane can hold, per stream, and a few spare), so a flood of calls is answered
RESOURCE_EXHAUSTED at once instead of queueing for a thread; and one connection may carry all
but CONNECTION_RESERVE of them (`grpc.max_concurrent_streams`), so the calls of one
connection, however many, always leave room for the others'. A client's calls past that wait
on the client; gRPC narrows the share of a connection that keeps resetting streams (its
"overload protection", against rapid resets), and refuses its streams past it with
REFUSED_STREAM (UNAVAILABLE on the client).
"""

from __future__ import annotations

import logging
from collections.abc import Callable, Sequence
from concurrent import futures
from dataclasses import dataclass
from pathlib import Path
from types import ModuleType
from typing import TYPE_CHECKING

import grpc
from grpc_health.v1 import health, health_pb2, health_pb2_grpc
from grpc_reflection.v1alpha import reflection, reflection_pb2_grpc

from services.runtime.aio_server import AioLaneInterceptor, AioServerHandle, EventLoopThread
from services.runtime.auth import CallSecurity
from services.runtime.lanes import Lane, LaneConfig, LaneExecutor, capacity
from services.runtime.metrics import ServiceMetrics
from services.runtime.rpc import (
    CALLS_PER_CALLER,
    DEFAULT_MAX_STREAMS,
    STATION_STREAMS,
    STREAMS_PER_CALLER,
    CallSlots,
    LaneInterceptor,
)
from services.runtime.tls import server_credentials
from wire.addresses import is_loopback
from wire.tls import KEEPALIVE_INTERVAL_MS, KEEPALIVE_TIMEOUT_MS

if TYPE_CHECKING:
    from services.security.audit import AuditLog
    from services.security.tokens import TokenStore

log = logging.getLogger(__name__)

PACKAGE = "telerobot.v1"
_SERVING = health_pb2.HealthCheckResponse.SERVING
_NOT_SERVING = health_pb2.HealthCheckResponse.NOT_SERVING


@dataclass(frozen=True)
class ServerSecurity:
    """TLS for a server: it presents `<name>.pem` from `tls_dir` and requires client
    certificates signed by its `ca.pem`. `inner_port`: one of the station's inner services,
    which take commands only from the station (services.security.roles)."""

    tls_dir: Path
    name: str
    inner_port: bool = True
    token_address: str | None = None  # also listen here for bearer-token callers
    tokens: TokenStore | None = None
    audit: AuditLog | None = None


# The server pings each client as the clients ping it (wire.tls.KEEPALIVE_OPTIONS), so a dead,
# hung or cut client is noticed within a second and its streams end (a Teleoperate session
# then holds the arm and waits to be resumed), and it takes the clients' pings at that rate
# instead of answering them with GOAWAY "too_many_pings".
SERVER_KEEPALIVE_OPTIONS = (
    ("grpc.keepalive_time_ms", KEEPALIVE_INTERVAL_MS),
    ("grpc.keepalive_timeout_ms", KEEPALIVE_TIMEOUT_MS),
    ("grpc.http2.ping_timeout_ms", KEEPALIVE_TIMEOUT_MS),  # see wire.tls.KEEPALIVE_OPTIONS
    ("grpc.keepalive_permit_without_calls", 1),
    ("grpc.http2.min_recv_ping_interval_without_data_ms", KEEPALIVE_INTERVAL_MS // 2),
    ("grpc.http2.max_ping_strikes", 0),
)


# Threads beyond the lanes' and the streams' (calls being refused, Health, reflection).
SPARE_THREADS = 16
# However many calls one connection carries, this many of a server's stay for the others
# (a quarter of them on a small server).
CONNECTION_RESERVE = 32


class PlaintextRefused(ValueError):
    """A server asked to listen without TLS beyond loopback."""


@dataclass(frozen=True)
class ServiceBinding:
    """One servicer and how to add it to a server."""

    full_name: str
    servicer: object
    add_to_server: Callable[[object, grpc.Server], None]


def binding(grpc_module: ModuleType, service: str, servicer: object) -> ServiceBinding:
    """Binding for `service` (e.g. "ProxyRobot") from its generated *_pb2_grpc module."""
    add = getattr(grpc_module, f"add_{service}Servicer_to_server")
    return ServiceBinding(f"{PACKAGE}.{service}", servicer, add)


class TelerobotServer:
    """A started-or-not gRPC server with its lanes and health status."""

    def __init__(self, servers: list[grpc.Server], health_servicer: health.HealthServicer,
                 executor: LaneExecutor, interceptor: LaneInterceptor, service_names: list[str],
                 token_port: int | None = None, metrics: ServiceMetrics | None = None,
                 aio: bool = False, after_stop: Callable[[], None] | None = None):
        self.grpc_servers = servers  # the main port's, then the token port's if any
        self.aio = aio  # grpc.aio servers (services/runtime/aio_server.py)
        self._after_stop = after_stop  # closes an aio server's loop and pool
        self.health = health_servicer
        self.executor = executor
        self.interceptor = interceptor
        self.service_names = service_names
        self.token_port = token_port
        self.metrics = metrics

    def start(self) -> None:
        """Accept calls. Health stays NOT_SERVING until set_serving()."""
        for server in self.grpc_servers:
            server.start()

    def set_serving(self) -> None:
        """Report SERVING for the whole server and every service."""
        for name in ["", *self.service_names]:
            self.health.set(name, _SERVING)

    def stop(self, grace_s: float) -> None:
        """Report NOT_SERVING, refuse new calls, let in-flight ones finish within grace_s."""
        self.health.enter_graceful_shutdown()
        stopped = [server.stop(grace_s) for server in self.grpc_servers]
        for event in stopped:
            event.wait()
        self.executor.shutdown(wait=True, timeout_s=1.0)
        if self._after_stop is not None:
            self._after_stop()


def create_server(
    address: str,
    bindings: Sequence[ServiceBinding],
    *,
    lanes: dict[Lane, LaneConfig] | None = None,
    client_lane_limit: Lane = Lane.HIGH,
    max_streams: int = DEFAULT_MAX_STREAMS,
    streams_per_caller: int = STREAMS_PER_CALLER,
    calls_per_caller: int = CALLS_PER_CALLER,
    station_streams: int | None = None,
    inner_port: bool | None = None,
    on_emergency_call: Callable[[], None] | None = None,
    security: ServerSecurity | None = None,
    allow_plaintext_network: bool = False,
    metrics: ServiceMetrics | None = None,
    aio: bool = False,
    audit: AuditLog | None = None,
) -> tuple[TelerobotServer, int]:
    """Build a server bound to `address` (port 0 picks one); returns it and the bound port.

    Every service is reported NOT_SERVING until `set_serving()`, and is listed by reflection.
    `on_emergency_call` runs as an emergency-lane call arrives (see services.runtime.rpc).
    Without `security`, a non-loopback `address` raises PlaintextRefused unless
    `allow_plaintext_network`. With `metrics`, calls and lanes are measured there (serving
    them over HTTP is the caller's: `metrics.serve(address)`). With `aio`, calls arrive on a
    grpc.aio server's event loop instead of grpcio's sync polling thread, and the same
    servicers and interceptor run on a thread pool (services/runtime/aio_server.py).
    `audit`: the audit log of a server without TLS (with TLS it is `security.audit`).

    Streams: `max_streams` open on the server (its ports together), `streams_per_caller` and
    `calls_per_caller` (unary calls in flight) for each caller (services/runtime/rpc.py). An
    inner port (`inner_port`; None: what `security` says, or, in plaintext, every server but
    the DecisionServer's) also keeps `station_streams` (None: STATION_STREAMS) for the
    station's own; in plaintext, where the station cannot be told from the others, they are
    added to `max_streams` for everyone.
    """
    check_plaintext(address, security is not None, allow_plaintext_network)
    if security is not None and audit is not None:
        raise ValueError("with TLS, the audit log is security.audit")
    executor = LaneExecutor(
        lanes, name="rpc",
        on_wait=(lambda lane, wait_s: metrics.lane_waited(lane.name.lower(), wait_s))
        if metrics is not None else None)
    names = [item.full_name for item in bindings]
    if inner_port is None:
        inner_port = (security.inner_port if security is not None
                      else f"{PACKAGE}.DecisionServer" not in names)
    if station_streams is None:
        station_streams = STATION_STREAMS if inner_port else 0
    if security is None:  # nobody is known to be the station: one room for all
        max_streams, station_streams = max_streams + station_streams, 0
    slots = CallSlots(max_streams, streams_per_caller, calls_per_caller, station_streams)
    health_servicer = health.HealthServicer(experimental_non_blocking=True)
    for name in ["", *names]:
        health_servicer.set(name, _NOT_SERVING)

    # gRPC threads only receive calls and wait on the lanes (or carry a stream), so there
    # must be one per call a lane can hold, plus the streams; a call beyond that is refused.
    pool_size = capacity(lanes) + max_streams + station_streams + SPARE_THREADS
    per_connection = pool_size - min(CONNECTION_RESERVE, pool_size // 4)
    aio_loop = aio_pool = None
    if aio:  # one loop for the servers, one pool for their handlers (the token port's too)
        aio_loop = EventLoopThread()
        servers_count = 2 if security is not None and security.token_address else 1
        aio_pool = futures.ThreadPoolExecutor(max_workers=pool_size * servers_count,
                                              thread_name_prefix="grpc")

    def build(call_security: CallSecurity | None):
        interceptor = LaneInterceptor(executor, client_lane_limit, max_streams,
                                      on_emergency_call, call_security, metrics, slots,
                                      read_first=aio_loop is None,
                                      waits_on_loop=aio_loop is not None)
        # Two servers on one port would split calls between them silently: refuse instead.
        options = [("grpc.so_reuseport", 0), *SERVER_KEEPALIVE_OPTIONS,
                   ("grpc.max_concurrent_streams", per_connection)]
        if aio_loop is None:
            server = grpc.server(
                futures.ThreadPoolExecutor(max_workers=pool_size, thread_name_prefix="grpc"),
                interceptors=[interceptor], options=options,
                maximum_concurrent_rpcs=pool_size)
            grpc_server = server
        else:
            async def aio_server():  # made on its loop, which it keeps
                return grpc.aio.server(interceptors=[AioLaneInterceptor(interceptor, aio_pool)],
                                       options=options, maximum_concurrent_rpcs=pool_size)

            server = AioServerHandle(aio_loop.run(aio_server()), aio_loop)
            grpc_server = server.server
        for item in bindings:
            item.add_to_server(item.servicer, grpc_server)
        health_pb2_grpc.add_HealthServicer_to_server(health_servicer, grpc_server)
        # The sync reflection servicer on either kind: the interceptor wraps sync handlers.
        reflection_pb2_grpc.add_ServerReflectionServicer_to_server(reflection.ReflectionServicer(
            [*names, health.SERVICE_NAME, reflection.SERVICE_NAME]), grpc_server)
        return server, interceptor

    if security is not None:
        main_security = CallSecurity(security.inner_port, None, security.audit)
    elif audit is not None:  # plaintext: nobody is checked, command-class calls are recorded
        main_security = CallSecurity(inner_port, None, audit, authenticates=False)
    else:
        main_security = None
    server, interceptor = build(main_security)
    servers = [server]
    try:
        credentials = (server_credentials(security.tls_dir, security.name)
                       if security else None)
        port = _bind(server, address, credentials)
        token_port = None
        if security is not None and security.token_address:
            token_server, _ = build(
                CallSecurity(security.inner_port, security.tokens, security.audit))
            servers.append(token_server)
            token_port = _bind(token_server, security.token_address, server_credentials(
                security.tls_dir, security.name, require_client_certificate=False))
    except BaseException:
        executor.shutdown(wait=False)
        if aio_loop is not None:
            _close_aio(aio_loop, aio_pool)
        raise
    if metrics is not None:
        metrics.watch_lanes(executor.counters, lambda: slots.open_streams)
    after_stop = (lambda: _close_aio(aio_loop, aio_pool)) if aio_loop is not None else None
    return TelerobotServer(servers, health_servicer, executor, interceptor, names,
                           token_port, metrics, aio, after_stop), port


def _close_aio(loop: EventLoopThread, pool: futures.ThreadPoolExecutor | None) -> None:
    if pool is not None:
        pool.shutdown(wait=False, cancel_futures=True)
    loop.close()


def check_plaintext(address: str, tls: bool, allow_plaintext_network: bool) -> None:
    """PlaintextRefused for a server without TLS on a non-loopback address, unless allowed
    explicitly (then a loud warning)."""
    if tls or is_loopback(address):
        return
    if not allow_plaintext_network:
        raise PlaintextRefused(
            f"refusing to listen on {address} without TLS: anyone on that network could take "
            "the lock and move the arm. Run `make certs` and set TELEROBOT_TLS_DIR (or "
            "--tls-dir), listen on 127.0.0.1, or pass --allow-plaintext-network")
    log.warning("PLAINTEXT beyond loopback on %s: no authentication, no encryption. Anyone "
                "who reaches this port can command the arm.", address)


def _bind(server: grpc.Server, address: str, credentials) -> int:
    try:
        port = (server.add_secure_port(address, credentials) if credentials
                else server.add_insecure_port(address))
    except RuntimeError:
        port = 0
    if port == 0:
        raise OSError(f"cannot listen on {address}: the port is in use or the host is not local")
    return port
