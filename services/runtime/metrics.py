"""Prometheus metrics of one service process, served over HTTP at /metrics.

Each process has a registry of its own (`ServiceMetrics`), never prometheus_client's global
one, so several servers in one process (the tests) keep separate counts. Nothing here knows
about gRPC: the interceptor (services.runtime.rpc) and the lanes (services.runtime.lanes) call
plain functions with names and seconds. Every recording function swallows its own errors (and
logs the first): a metric that fails never fails a call.

What is measured, and where:
- `telerobot_rpc_handled_total{method, code}`: every call, unary and streaming, counted once as
  it ends, with its status code name (OK, INVALID_ARGUMENT, ... ; CANCELLED for a stream the
  client left). Calls refused before their handler ran (a malformed request, a refused caller,
  a full lane) count too.
- `telerobot_rpc_duration_seconds{method}`: unary calls only, from the moment the interceptor
  receives the call (request bytes read) to the moment its response or status is handed back
  to gRPC: decoding, checks, the wait on the lane and the handler. Not the network, not the
  response's serialization. Buckets from 0.1 ms to 100 ms (and +Inf).
- `telerobot_lane_wait_seconds{lane}`: for each piece of lane work, from its submission to the
  moment a thread starts it; 0 for a call run at once on the thread that received it
  (`LaneExecutor.run_here`).
- `telerobot_lane_queued{lane}`, `..._running`, `..._threads` (gauges, read at scrape time),
  `telerobot_lane_rejected_total`, `..._borrowed_total`, `..._served_total`,
  `..._inline_total` (counters): the executor's own counters (services.runtime.lanes).
- `telerobot_open_streams`: streams open on the server (its ports together).
- `telerobot_stream_dropped_total{stream}`: messages a slow subscriber of a fanned-out stream
  lost (services.common.fanout), by stream name.
- `telerobot_stream_lag_seconds{stream}`: how long each message of a fanned-out stream waited
  in its subscriber's queue, from its publication to the moment the subscriber's stream took it
  to send (0 ms when the stream keeps up; it grows as a slow client's queue fills).
- `telerobot_command_age_seconds`: the DecisionServer's Teleoperate commands, their receive time
  minus the send time the operator stamped: the link's one-way delay and the wait before the
  server read the command. Across two hosts it includes their clocks' offset, so it is only
  as good as their time sync (a negative age, from a clock ahead of ours, counts as 0).
- `telerobot_events_total{event}`: named events a service counts itself (the DecisionServer's
  `lease_change`: a lease granted, released, lapsed or taken over).
- `telerobot_emergency_stop_latency_seconds`: the time an arriving EmergencyStop takes to latch
  its stop: the service's stop hook, run on gRPC's polling thread as the call arrives (ProxyRobot
  and the band: a word in shared memory; the DecisionServer: its stop sent to the band).
- values a service reads out at scrape time (`watch`): the world's 1 kHz loop
  (`telerobot_world_steps_total`, `..._overruns_total`, `..._dropped_steps_total`,
  `telerobot_world_worst_lateness_seconds`, `..._worst_step_seconds`).
- process_*: the process's CPU, memory and open files (prometheus_client's ProcessCollector).

The endpoint is prometheus_client's WSGI app on a server of our own: a connection is served by
one of at most MAX_HANDLERS threads, each of whose reads and writes gives up after
HANDLER_TIMEOUT_S, and a connection beyond them gets 503 at once (prometheus_client's own
server starts a thread per connection, which waits for ever on a client that sends nothing).
"""

from __future__ import annotations

import logging
import socket
import threading
from collections.abc import Callable, Iterable
from typing import Any
from wsgiref.simple_server import WSGIRequestHandler, WSGIServer, make_server

from prometheus_client import CollectorRegistry, Counter, Histogram, ProcessCollector
from prometheus_client.core import CounterMetricFamily, GaugeMetricFamily
from prometheus_client.exposition import make_wsgi_app

log = logging.getLogger(__name__)

# Seconds: 0.1 ms to 100 ms, then +Inf.
LATENCY_BUCKETS_S = (0.0001, 0.0002, 0.0005, 0.001, 0.002, 0.005, 0.01, 0.02, 0.05, 0.1)
# Lane waits and stream lags: the same, and one more decade (a saturated lane waits long).
WAIT_BUCKETS_S = (0.0, *LATENCY_BUCKETS_S, 0.2, 0.5, 1.0)
# Command ages: a link can add hundreds of milliseconds, and a resumed session's resends seconds.
AGE_BUCKETS_S = (*LATENCY_BUCKETS_S, 0.2, 0.5, 1.0, 2.0, 5.0)

METRICS_PATH = "/metrics"
# The endpoint's bounds: connections served at once (Prometheus needs one), and how long one
# read or write on a connection may wait.
MAX_HANDLERS = 8
HANDLER_TIMEOUT_S = 5.0
_BUSY = (b"HTTP/1.1 503 Service Unavailable\r\nContent-Type: text/plain\r\n"
         b"Content-Length: 5\r\nConnection: close\r\n\r\nbusy\n")


class ServiceMetrics:
    """The metrics of one service process, on a registry of its own; `serve()` starts the
    HTTP endpoint."""

    def __init__(self, service: str = ""):
        self.service = service
        self.registry = CollectorRegistry(auto_describe=True)
        self._rpcs = Counter(
            "telerobot_rpc_handled", "RPCs handled, by method and status code, counted as "
            "each ends", ["method", "code"], registry=self.registry)
        self._latency = Histogram(
            "telerobot_rpc_duration_seconds", "Time a unary RPC spent in the server, from its "
            "request read to its response handed back to gRPC", ["method"],
            buckets=LATENCY_BUCKETS_S, registry=self.registry)
        self._lane_wait = Histogram(
            "telerobot_lane_wait_seconds", "Time lane work waited before a thread started it "
            "(0 when run at once)", ["lane"], buckets=WAIT_BUCKETS_S, registry=self.registry)
        self._dropped = Counter(
            "telerobot_stream_dropped", "Messages a slow subscriber of a fanned-out stream "
            "lost", ["stream"], registry=self.registry)
        self._lag = Histogram(
            "telerobot_stream_lag_seconds", "Time a fanned-out stream's message waited in its "
            "subscriber's queue before the stream took it", ["stream"], buckets=WAIT_BUCKETS_S,
            registry=self.registry)
        self._lag_of: dict[str, Any] = {}  # stream -> its child: observed at up to kHz rates
        self._command_age = Histogram(
            "telerobot_command_age_seconds", "A Teleoperate command's receive time minus its "
            "send time (includes the hosts' clock offset)", buckets=AGE_BUCKETS_S,
            registry=self.registry)
        self._events = Counter(
            "telerobot_events", "Events a service counts (world overruns, lease changes, "
            "emergency stops)", ["event"], registry=self.registry)
        self._stop_latency = Histogram(
            "telerobot_emergency_stop_latency_seconds", "From an EmergencyStop's arrival to "
            "its stop latched", buckets=LATENCY_BUCKETS_S, registry=self.registry)
        self._lanes = _LaneCollector()
        self.registry.register(self._lanes)
        try:
            ProcessCollector(registry=self.registry)
        except Exception:  # noqa: BLE001 - no /proc here: no process metrics, nothing else lost
            log.debug("no process metrics on this platform", exc_info=True)
        self._warned = False
        self._http: Any = None
        self._http_thread: threading.Thread | None = None

    # -- recording (never raises) -----------------------------------------------------------

    def rpc_done(self, method: str, code: str, duration_s: float | None) -> None:
        """One call ended with status `code`; `duration_s` for unary calls, None for streams."""
        try:
            self._rpcs.labels(method, code).inc()
            if duration_s is not None:
                self._latency.labels(method).observe(duration_s)
        except Exception:  # noqa: BLE001 - a metric never fails a call
            self._failed()

    def lane_waited(self, lane_name: str, wait_s: float) -> None:
        """A piece of work on `lane_name` waited `wait_s` before it started."""
        try:
            self._lane_wait.labels(lane_name).observe(wait_s)
        except Exception:  # noqa: BLE001
            self._failed()

    def dropped(self, stream: str, count: int = 1) -> None:
        """A subscriber of `stream` lost `count` messages."""
        try:
            if count > 0:
                self._dropped.labels(stream).inc(count)
        except Exception:  # noqa: BLE001
            self._failed()

    def stream_lagged(self, stream: str, lag_s: float) -> None:
        """A message of `stream` waited `lag_s` in its subscriber's queue."""
        try:
            child = self._lag_of.get(stream)
            if child is None:
                child = self._lag_of.setdefault(stream, self._lag.labels(stream))
            child.observe(lag_s)
        except Exception:  # noqa: BLE001
            self._failed()

    def command_aged(self, age_s: float) -> None:
        """A command arrived `age_s` after its send time (negative ages count as 0)."""
        try:
            self._command_age.observe(max(0.0, age_s))
        except Exception:  # noqa: BLE001
            self._failed()

    def event(self, name: str, count: int = 1) -> None:
        """Count `count` occurrences of the event `name`."""
        try:
            self._events.labels(name).inc(count)
        except Exception:  # noqa: BLE001
            self._failed()

    def emergency_stop_latched(self, latency_s: float) -> None:
        """An emergency stop was latched `latency_s` after its call arrived."""
        try:
            self._stop_latency.observe(latency_s)
        except Exception:  # noqa: BLE001
            self._failed()

    def watch(self, name: str, help_text: str, read: Callable[[], float],
              counter: bool = False) -> None:
        """Expose `read()` as the gauge (or, with `counter`, the counter) `name`, read at
        scrape time."""
        self._lanes.values.append((name, help_text, read, counter))

    def watch_lanes(self, counters: Callable[[], dict[Any, Any]],
                    open_streams: Callable[[], int] | None = None) -> None:
        """Read the lanes' counters (LaneExecutor.counters) and the open streams at scrape
        time."""
        self._lanes.counters = counters
        self._lanes.open_streams = open_streams

    def _failed(self) -> None:
        if not self._warned:
            self._warned = True
            log.exception("recording a metric failed; the call goes on (logged once)")

    # -- the HTTP endpoint ------------------------------------------------------------------

    def serve(self, address: str, max_handlers: int = MAX_HANDLERS,
              timeout_s: float = HANDLER_TIMEOUT_S) -> int:
        """Serve /metrics on host:port (port 0 picks a free one); returns the port bound.
        OSError if the address cannot be bound."""
        host, _, port = address.rpartition(":")
        host = host.strip("[]") or "127.0.0.1"
        family = socket.getaddrinfo(host, int(port), type=socket.SOCK_STREAM,
                                    flags=socket.AI_PASSIVE)[0][0]
        server_class = type("MetricsServer", (_BoundedServer,), {
            "address_family": family, "max_handlers": max_handlers,
            "handler_name": f"metrics-{self.service}-handler"})
        handler_class = type("MetricsHandler", (_QuietHandler,), {"timeout": timeout_s})
        self._http = make_server(host, int(port), make_wsgi_app(self.registry), server_class,
                                 handler_class)
        self._http_thread = threading.Thread(target=self._http.serve_forever,
                                             name=f"metrics-{self.service}", daemon=True)
        self._http_thread.start()
        return self._http.server_port

    def close(self) -> None:
        """Stop the HTTP endpoint, if serve() started it."""
        http, self._http = self._http, None
        if http is not None:
            http.shutdown()
            http.server_close()


class _BoundedServer(WSGIServer):
    """A thread per connection, at most `max_handlers` at once: a connection beyond them is
    answered 503 (if its socket takes the few bytes at once) and closed, by the accepting
    thread, which never waits on it."""

    max_handlers = MAX_HANDLERS
    handler_name = "metrics-handler"

    def server_activate(self) -> None:
        super().server_activate()
        self.slots = threading.BoundedSemaphore(self.max_handlers)

    def process_request(self, request, client_address) -> None:
        if not self.slots.acquire(blocking=False):
            try:
                request.send(_BUSY, socket.MSG_DONTWAIT)
            except OSError:
                pass
            self.shutdown_request(request)
            return
        handler = threading.Thread(target=self._handle, args=(request, client_address),
                                   name=self.handler_name, daemon=True)
        try:
            handler.start()
        except BaseException:
            self.slots.release()
            self.shutdown_request(request)
            raise

    def _handle(self, request, client_address) -> None:
        try:
            self.finish_request(request, client_address)
        except Exception:  # noqa: BLE001 - one connection's end, never the server's
            self.handle_error(request, client_address)
        finally:
            self.shutdown_request(request)
            self.slots.release()

    def handle_error(self, request, client_address) -> None:
        # A client that went quiet (the handler's timeout) or away: nothing to print.
        log.debug("metrics: a connection from %s ended in an error", client_address,
                  exc_info=True)


class _QuietHandler(WSGIRequestHandler):
    """wsgiref's handler, whose reads and writes time out (`timeout`, set per server), and
    which logs no request."""

    def log_message(self, format, *args) -> None:  # noqa: A002 - the base class's name
        pass


class _LaneCollector:
    """The lanes' counters and the open streams, read when Prometheus scrapes."""

    def __init__(self):
        self.counters: Callable[[], dict[Any, Any]] | None = None
        self.open_streams: Callable[[], int] | None = None
        self.values: list[tuple[str, str, Callable[[], float], bool]] = []

    def describe(self) -> Iterable:
        return []  # read at collect time only: nothing to register up front

    def collect(self) -> Iterable:
        counters = self.counters
        if counters is not None:
            try:
                by_lane = counters()
            except Exception:  # noqa: BLE001 - a scrape without lanes, never an error
                log.exception("reading the lanes' counters failed")
                by_lane = {}
            gauges = {name: GaugeMetricFamily(f"telerobot_lane_{name}", help, labels=["lane"])
                      for name, help in _LANE_GAUGES.items()}
            totals = {name: CounterMetricFamily(f"telerobot_lane_{name}", help, labels=["lane"])
                      for name, help in _LANE_COUNTERS.items()}
            for lane, lane_counters in by_lane.items():
                label = [lane.name.lower()]
                for name, family in gauges.items():
                    family.add_metric(label, getattr(lane_counters, name))
                for name, family in totals.items():
                    family.add_metric(label, getattr(lane_counters, name))
            yield from gauges.values()
            yield from totals.values()
        if self.open_streams is not None:
            try:
                yield GaugeMetricFamily("telerobot_open_streams", "Streams open on the server",
                                        value=self.open_streams())
            except Exception:  # noqa: BLE001
                log.exception("reading the open streams failed")
        for name, help_text, read, counter in list(self.values):
            try:
                family = CounterMetricFamily if counter else GaugeMetricFamily
                yield family(name, help_text, value=read())
            except Exception:  # noqa: BLE001 - one value missing, never a failed scrape
                log.exception("reading %s failed", name)


_LANE_GAUGES = {
    "queued": "Calls waiting on the lane's queue",
    "running": "Calls of the lane running now",
    "threads": "The lane's threads",
}
_LANE_COUNTERS = {
    "served": "Calls of the lane served",
    "rejected": "Calls refused because the lane was full (RESOURCE_EXHAUSTED)",
    "borrowed": "Calls of the lane run by a lower lane's thread",
    "inline": "Calls of the lane run at once on the thread that received them",
}
