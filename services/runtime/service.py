"""Service: the life of a service process, as run_service drives it.

As rclpy's lifecycle node, every stage is a method, each doing nothing unless a service
overrides it, so the runtime calls them all and a reader sees the whole contract here:

    bindings()            the servicers to register, once, before the server is made
    configure(health, metrics)
                          once the server exists, before start(): `health(name, serving)`
                          reports a health entry of the service's own, from any thread;
                          `metrics` is the process's ServiceMetrics, or None when metrics
                          are off
    keep_audit(audit)     then: the process's AuditLog (services/security/audit.py), or None
                          when it keeps none, for calls the service answers beside gRPC
    start()               become ready to serve (open hardware, start threads); raise to
                          abort start-up
    on_emergency_call()   an EmergencyStop call arrived: latch the stop now. It runs on gRPC's
                          polling thread or the aio server's loop, before the call is
                          dispatched, so it must not block
    close()               release everything start() took; called once, after the server
                          stopped (also after a failed start)

And three class attributes say how it is served: `lanes` (a dict of LaneConfig by Lane, or
None for the defaults), `aio_server` (serve on grpc.aio, services/runtime/aio_server.py), and
`operator_door` (the DecisionServer: the one port that takes operators' commands; the others
are the station's inner ports).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

from services.runtime.lanes import Lane, LaneConfig
from services.runtime.metrics import ServiceMetrics
from services.runtime.server import ServiceBinding
from services.security.audit import AuditLog

HealthReporter = Callable[[str, bool], None]


class Service:
    """Base class of every service process; see the module docstring."""

    lanes: dict[Lane, LaneConfig] | None = None
    aio_server: bool = False
    operator_door: bool = False

    def bindings(self) -> Sequence[ServiceBinding]:
        raise NotImplementedError(f"{type(self).__name__} serves nothing: define bindings()")

    def configure(self, health: HealthReporter, metrics: ServiceMetrics | None) -> None:
        """Once the server exists, before start()."""

    def keep_audit(self, audit: AuditLog | None) -> None:
        """Once the server exists, before start(): where calls answered beside gRPC are
        audited."""

    def start(self) -> None:
        """Become ready to serve."""

    def on_emergency_call(self) -> None:
        """Latch the stop as an EmergencyStop call arrives; must not block."""

    def close(self) -> None:
        """Release everything start() took."""
