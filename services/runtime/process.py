"""run_service: the life of one service process, from flags to a clean exit.

1. Parse flags (environment defaults), configure logging.
2. Build the service and bind its server; health says NOT_SERVING.
3. `start()` the service (for example, open the hardware link); then health says SERVING.
4. On SIGINT or SIGTERM: health says NOT_SERVING, new calls are refused, in-flight calls get
   `--grace-s` to finish, then `close()` releases the hardware. A second signal exits at once.
"""

from __future__ import annotations

import argparse
import logging
import os
import signal
import sys
import threading
from collections.abc import Callable, Sequence
from pathlib import Path

from grpc_health.v1 import health_pb2
from prometheus_client import disable_created_metrics

from services.runtime.config import (
    METRICS_OFF,
    base_parser,
    configure_logging,
    select_arm_from,
)
from services.runtime.metrics import ServiceMetrics
from services.runtime.priority import nice_every_thread, raise_thread_priority
from services.runtime.server import (
    PlaintextRefused,
    ServerSecurity,
    check_plaintext,
    create_server,
)
from services.runtime.service import Service
from services.runtime.thread_names import name_os_threads
from services.security.audit import AUDIT_DIR_ENV, AuditLog, audit_log_for
from services.security.tokens import TokenStore, tokens_file
from wire.addresses import env_name, is_loopback
from wire.errors import TelerobotError
from wire.processes import PARENT_PID_ENV, dump_stacks_on_signal, handle_signals, say_ready

log = logging.getLogger(__name__)

# A thread woken by the network waits for the GIL at most this long behind a busy one (Python's
# default is 5 ms, longer than a whole command budget). Every call crosses several threads.
GIL_SWITCH_INTERVAL_S = 0.001
_PARENT_POLL_S = 0.25  # how often a process checks that its parent (PARENT_PID_ENV) lives


def token_port_name(service: str) -> str:
    """The name on the ready line of a service's bearer-token port."""
    return f"{service}_tokens"


def metrics_port_name(service: str) -> str:
    """The name on the ready line of a service's Prometheus /metrics port."""
    return f"{service}_metrics"


def run_service(
    name: str,
    description: str,
    build: Callable[[argparse.Namespace], Service],
    argv: Sequence[str] | None = None,
    add_arguments: Callable[[argparse.ArgumentParser], None] | None = None,
    switch_interval_s: float = GIL_SWITCH_INTERVAL_S,
    realtime_priority: int = 0,
    reads_arm: bool = True,
    nice: int = 0,
) -> int:
    """Run the service `name` until SIGINT/SIGTERM; returns the process exit code.
    `switch_interval_s` is the process's GIL switch interval (the world's is shorter).
    `realtime_priority` > 0: the service is on the command path, and every thread of its
    process runs at SCHED_FIFO at that priority where the host allows it (`--rt-priority`).
    `reads_arm`: the service loads the arm's model, so `--arm`'s file is checked before it
    starts; a service that does not (the emergency-stop band) checks only the name.
    `nice` > 0: the service is off the command path and yields to it, and every thread of its
    process runs at that nice value (`--nice`)."""
    parser = base_parser(name, description)
    if realtime_priority:
        add_realtime_argument(parser, name, realtime_priority)
    if nice:
        add_nice_argument(parser, name, nice)
    if add_arguments:
        add_arguments(parser)
    args = parser.parse_args(argv)
    configure_logging(name, args.log_level)
    if not select_arm_from(args, log, reads_arm):  # before anything loads a model
        return 2
    if realtime_priority:  # first: the threads started from now on inherit it
        if args.rt_priority:
            raise_thread_priority(args.rt_priority, 0, what=f"{name}'s threads",
                                  inherited=True)
        else:
            log.info("real-time scheduling off (--rt-priority 0)")
    if nice and args.nice:
        nice_every_thread(args.nice)
        log.info("every thread at nice %d: on a busy machine this service waits, not the "
                 "command path or the operator's processes", args.nice)
    dump_stacks_on_signal()
    name_os_threads()
    sys.setswitchinterval(switch_interval_s)

    stop = threading.Event()
    _install_signal_handlers(stop)
    watch_parent(stop.set, stop)

    try:  # before the service takes its hardware
        check_plaintext(args.address, bool(args.tls_dir), args.allow_plaintext_network)
        check_metrics_address(args.metrics_address, args.allow_metrics_network)
    except PlaintextRefused as error:
        log.error("not starting: %s", error)
        return 2
    metrics = None
    if args.metrics_address != METRICS_OFF:
        disable_created_metrics()  # no *_created series beside every counter (the process's)
        metrics = ServiceMetrics(name)
    service = build(args)
    security = server_security(args, name, inner_port=not service.operator_door)
    plaintext_audit = plaintext_audit_log(args, name)
    audit = security.audit if security else plaintext_audit
    try:
        server, port = create_server(
            args.address, service.bindings(), client_lane_limit=args.client_lane_limit,
            lanes=service.lanes, on_emergency_call=service.on_emergency_call,
            security=security, allow_plaintext_network=args.allow_plaintext_network,
            metrics=metrics,
            aio=service.aio_server,
            inner_port=not service.operator_door,
            audit=plaintext_audit,
        )
    except (PlaintextRefused, OSError, ValueError) as error:  # a port, or TLS files, refused
        log.error("not starting: %s", error)
        service.close()
        _close_audit(audit)
        return 2
    metrics_address = None
    if metrics is not None:
        try:
            metrics_host = args.metrics_address.rsplit(":", 1)[0]
            metrics_address = f"{metrics_host}:{metrics.serve(args.metrics_address)}"
        except (OSError, ValueError) as error:
            log.error("not starting: cannot serve metrics on %s: %s", args.metrics_address,
                      error)
            server.stop(0)
            service.close()
            _close_audit(audit)
            return 2
    service.configure(lambda service_name, serving: server.health.set(
        service_name, health_pb2.HealthCheckResponse.SERVING if serving
        else health_pb2.HealthCheckResponse.NOT_SERVING), metrics)
    service.keep_audit(audit)
    server.start()
    try:
        service.start()
    except TelerobotError as error:  # an expected refusal, such as "already running"
        log.error("start-up failed: %s", error.message)
        server.stop(0)
        service.close()
        _close_audit(audit)
        return 1
    except Exception:
        log.exception("start-up failed; stopping")
        server.stop(0)
        service.close()
        _close_audit(audit)
        return 1
    server.set_serving()
    host = args.address.rsplit(":", 1)[0]
    log.info("serving %s on %s:%d%s%s", ", ".join(server.service_names) or "health only",
             host, port, " with mutual TLS" if security else " in plaintext",
             " (grpc.aio)" if server.aio else "")
    if audit is not None:
        log.info("audit log: %s", audit.path)
    if server.token_port:
        token_address = f"{security.token_address.rsplit(':', 1)[0]}:{server.token_port}"
        log.info("bearer tokens from %s are taken on %s (TLS, no client certificate)",
                 security.tokens.path, token_address)
        # Before the service's own line: whoever waits for that one knows this one too.
        say_ready(token_port_name(name), token_address)
    if metrics_address:
        log.info("Prometheus metrics on http://%s/metrics", metrics_address)
        say_ready(metrics_port_name(name), metrics_address)
    say_ready(name, f"{host}:{port}")

    wait_for_stop(stop)
    log.info("stopping: draining calls for up to %.1f s", args.grace_s)
    server.stop(args.grace_s)
    service.close()
    if metrics is not None:
        metrics.close()
    _close_audit(audit)
    log.info("stopped")
    return 0


def add_realtime_argument(parser: argparse.ArgumentParser, name: str, default: int) -> None:
    parser.add_argument(
        "--rt-priority", type=int, default=int(os.environ.get(env_name(name, "rt_priority"),
                                                              default)),
        choices=range(0, 100), metavar="0-99",
        help=f"SCHED_FIFO priority of every thread of this process where the OS allows it "
             f"(default {default}, below the world's physics thread); 0 turns it off "
             f"(env {env_name(name, 'rt_priority')})")


def add_nice_argument(parser: argparse.ArgumentParser, name: str, default: int) -> None:
    parser.add_argument(
        "--nice", type=int, default=int(os.environ.get(env_name(name, "nice"), default)),
        choices=range(0, 20), metavar="0-19",
        help=f"nice value of every thread of this process (default {default}: below the "
             f"operator's processes on a shared machine); 0 leaves it as the process was started "
             f"(env {env_name(name, 'nice')})")


def check_metrics_address(address: str, allow_network: bool) -> None:
    """PlaintextRefused for metrics beyond loopback unless allowed (then a warning): they are
    plain HTTP, read by anyone who reaches the port."""
    if address == METRICS_OFF or is_loopback(address):
        return
    if not allow_network:
        raise PlaintextRefused(
            f"refusing to serve metrics on {address}: they are plain HTTP without "
            "authentication. Serve them on 127.0.0.1 (and let Prometheus reach them through "
            "a tunnel or a local agent), or pass --allow-metrics-network")
    log.warning("metrics on %s: plain HTTP, readable by anyone who reaches the port", address)


def server_security(args: argparse.Namespace, name: str, inner_port: bool
                    ) -> ServerSecurity | None:
    """TLS for the service `name` when --tls-dir (TELEROBOT_TLS_DIR) is set; None otherwise."""
    if not args.tls_dir:
        return None
    token_address = args.token_address or None
    return ServerSecurity(
        Path(args.tls_dir), name, inner_port, token_address,
        tokens=TokenStore(tokens_file()) if token_address else None,
        audit=audit_log_for(name))


def plaintext_audit_log(args: argparse.Namespace, name: str) -> AuditLog | None:
    """The audit log of the service `name` without TLS: kept when TELEROBOT_AUDIT_DIR names
    a directory (with TLS one is always kept, in var/audit by default). Nobody is
    authenticated, so its records name the caller by its address."""
    if args.tls_dir or not os.environ.get(AUDIT_DIR_ENV):
        return None
    return audit_log_for(name)


def _close_audit(audit: AuditLog | None) -> None:
    if audit is not None:
        audit.close()


def stop_requested() -> threading.Event:
    """An event set on SIGINT or SIGTERM, or when the supervising parent (PARENT_PID_ENV) goes
    away: a process without a gRPC server of its own waits on it (wait_for_stop)."""
    stop = threading.Event()
    _install_signal_handlers(stop)
    watch_parent(stop.set, stop)
    return stop


def wait_for_stop(stop: threading.Event) -> None:
    """Block the main thread until `stop` is set (a signal's handler runs on a thread of its
    own: handle_signals)."""
    stop.wait()


def _install_signal_handlers(stop: threading.Event) -> None:
    def on_signal(signum: int) -> None:
        if stop.is_set():
            os._exit(128 + signum)  # second signal: the operator wants out now
        stop.set()

    handle_signals({signal.SIGINT: on_signal, signal.SIGTERM: on_signal})


def watch_parent(on_gone: Callable[[], None], stop: threading.Event | None = None) -> bool:
    """If a supervisor set PARENT_PID_ENV, call `on_gone` (once, on a daemon thread) when that
    parent goes away, checking every 0.25 s until `stop` is set. Returns whether it watches."""
    parent = os.environ.get(PARENT_PID_ENV)
    if not parent:
        return False
    stop = stop or threading.Event()

    def watch():
        while not stop.wait(_PARENT_POLL_S):
            if os.getppid() != int(parent):
                log.warning("parent %s is gone; stopping", parent)
                on_gone()
                return

    threading.Thread(target=watch, name="parent-watch", daemon=True).start()
    return True
