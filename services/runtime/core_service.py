"""CoreService: a service process that serves some bindings and releases one core on stop."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

from services.common.fanout import Fanout
from services.runtime.metrics import ServiceMetrics
from services.runtime.server import ServiceBinding
from services.runtime.service import HealthReporter, Service
from services.security.audit import AuditLog


@dataclass
class CoreService(Service):
    """What run_service needs from a service whose domain object starts on demand (on Connect,
    on StartReading) and has one `close()` that releases its hardware."""

    served: Sequence[ServiceBinding]
    release: Callable[[], None]
    emergency_latch: Callable[[], None] | None = None  # Service.on_emergency_call
    # Usually nothing: the domain opens its hardware when a client asks, as the papers'
    # components do. A restarted ProxyRobot reattaches to the arm it left.
    on_start: Callable[[], None] | None = None
    # Streams fanned out to subscribers, by the name their drops are counted under.
    fanouts: dict[str, Fanout] = field(default_factory=dict)
    # Serve on grpc.aio (services/runtime/aio_server.py): an emergency stop's arrival then
    # does not queue behind a flood of other calls' events.
    aio_server: bool = False
    # Told the process's audit log (Service.keep_audit): ProxyRobot's local socket audits there.
    audit_to: Callable[[AuditLog | None], None] | None = None

    def configure(self, health: HealthReporter, metrics: ServiceMetrics | None) -> None:
        if metrics is None:
            return
        for name, fanout in self.fanouts.items():
            fanout.on_dropped = lambda name=name: metrics.dropped(name)
            fanout.on_lag = lambda lag_s, name=name: metrics.stream_lagged(name, lag_s)

    def bindings(self) -> Sequence[ServiceBinding]:
        return self.served

    def keep_audit(self, audit: AuditLog | None) -> None:
        if self.audit_to is not None:
            self.audit_to(audit)

    def start(self) -> None:
        if self.on_start is not None:
            self.on_start()

    def on_emergency_call(self) -> None:
        if self.emergency_latch is not None:
            self.emergency_latch()

    def close(self) -> None:
        self.release()
