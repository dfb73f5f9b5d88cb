"""create_server: a gRPC server with priority lanes, health and reflection."""

from __future__ import annotations

import logging
from collections.abc import Callable, Sequence
from concurrent import futures
from dataclasses import dataclass
from types import ModuleType

import grpc
from grpc_health.v1 import health, health_pb2, health_pb2_grpc
from grpc_reflection.v1alpha import reflection

from services.runtime.lanes import Lane, LaneConfig, LaneExecutor
from services.runtime.rpc import LaneInterceptor

log = logging.getLogger(__name__)

PACKAGE = "telerobot.v1"
_SERVING = health_pb2.HealthCheckResponse.SERVING
_NOT_SERVING = health_pb2.HealthCheckResponse.NOT_SERVING


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

    def __init__(self, server: grpc.Server, health_servicer: health.HealthServicer,
                 executor: LaneExecutor, interceptor: LaneInterceptor, service_names: list[str]):
        self.grpc_server = server
        self.health = health_servicer
        self.executor = executor
        self.interceptor = interceptor
        self.service_names = service_names

    def start(self) -> None:
        """Accept calls. Health stays NOT_SERVING until set_serving()."""
        self.grpc_server.start()

    def set_serving(self) -> None:
        """Report SERVING for the whole server and every service."""
        for name in ["", *self.service_names]:
            self.health.set(name, _SERVING)

    def stop(self, grace_s: float) -> None:
        """Report NOT_SERVING, refuse new calls, let in-flight ones finish within grace_s."""
        self.health.enter_graceful_shutdown()
        self.grpc_server.stop(grace_s).wait()
        self.executor.shutdown(wait=True, timeout_s=1.0)


def create_server(
    address: str,
    bindings: Sequence[ServiceBinding],
    *,
    lanes: dict[Lane, LaneConfig] | None = None,
    client_lane_limit: Lane = Lane.HIGH,
    max_streams: int = 64,
    on_emergency_call: Callable[[], None] | None = None,
) -> tuple[TelerobotServer, int]:
    """Build a server bound to `address` (port 0 picks one); returns it and the bound port.

    Every service is reported NOT_SERVING until `set_serving()`, and is listed by reflection.
    `on_emergency_call` runs as an emergency-lane call arrives (see services.runtime.rpc).
    """
    executor = LaneExecutor(lanes, name="rpc")
    interceptor = LaneInterceptor(executor, client_lane_limit, max_streams, on_emergency_call)
    lane_configs = lanes or {}
    capacity = sum(c.max_threads + c.queue_capacity for c in lane_configs.values()) or 512
    # gRPC threads only receive calls and wait on the lanes (or carry a stream), so there
    # must be one per call a lane can hold, plus the streams.
    pool = futures.ThreadPoolExecutor(max_workers=capacity + max_streams + 16,
                                      thread_name_prefix="grpc")
    server = grpc.server(
        pool,
        interceptors=[interceptor],
        # Two servers on one port would split calls between them silently: refuse instead.
        options=[("grpc.so_reuseport", 0)],
    )
    names = []
    for item in bindings:
        item.add_to_server(item.servicer, server)
        names.append(item.full_name)

    health_servicer = health.HealthServicer(experimental_non_blocking=True)
    health_pb2_grpc.add_HealthServicer_to_server(health_servicer, server)
    for name in ["", *names]:
        health_servicer.set(name, _NOT_SERVING)
    reflection.enable_server_reflection(
        [*names, health.SERVICE_NAME, reflection.SERVICE_NAME], server
    )
    try:
        port = server.add_insecure_port(address)
    except RuntimeError:
        port = 0
    if port == 0:
        executor.shutdown(wait=False)
        raise OSError(f"cannot listen on {address}: the port is in use or the host is not local")
    return TelerobotServer(server, health_servicer, executor, interceptor, names), port
