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
import threading
from collections.abc import Callable, Sequence
from typing import Protocol

from services.runtime.config import base_parser, configure_logging
from services.runtime.errors import TelerobotError
from services.runtime.server import ServiceBinding, create_server

log = logging.getLogger(__name__)

# What a process prints on stdout once it is SERVING; the launcher and tests wait for it.
READY_LINE_PREFIX = "TELEROBOT_READY"
# Set by a supervisor to its pid: the process then stops cleanly when that parent goes away,
# even if the parent was killed without a chance to stop it (no orphans).
PARENT_PID_ENV = "TELEROBOT_PARENT_PID"
_PARENT_POLL_S = 0.25


class Service(Protocol):
    """What a service process provides to the runtime."""

    def bindings(self) -> Sequence[ServiceBinding]:
        """Servicers to register on the server."""

    def start(self) -> None:
        """Become ready to serve (open hardware, start threads). Raise to abort start-up."""

    def close(self) -> None:
        """Release everything start() took. Called once, after the server stopped."""


def run_service(
    name: str,
    description: str,
    build: Callable[[argparse.Namespace], Service],
    argv: Sequence[str] | None = None,
    add_arguments: Callable[[argparse.ArgumentParser], None] | None = None,
) -> int:
    """Run the service `name` until SIGINT/SIGTERM; returns the process exit code."""
    parser = base_parser(name, description)
    if add_arguments:
        add_arguments(parser)
    args = parser.parse_args(argv)
    configure_logging(name, args.log_level)

    stop = threading.Event()
    _install_signal_handlers(stop)
    _stop_when_parent_exits(stop)

    service = build(args)
    server, port = create_server(
        args.address, service.bindings(), client_lane_limit=args.client_lane_limit,
        lanes=getattr(service, "lanes", None),  # a service may size its own lanes
    )
    server.start()
    try:
        service.start()
    except TelerobotError as error:  # an expected refusal, such as "already running"
        log.error("start-up failed: %s", error.message)
        server.stop(0)
        service.close()
        return 1
    except Exception:
        log.exception("start-up failed; stopping")
        server.stop(0)
        service.close()
        return 1
    server.set_serving()
    host = args.address.rsplit(":", 1)[0]
    log.info("serving %s on %s:%d", ", ".join(server.service_names) or "health only", host, port)
    print(f"{READY_LINE_PREFIX} {name} {host}:{port}", flush=True)

    stop.wait()
    log.info("stopping: draining calls for up to %.1f s", args.grace_s)
    server.stop(args.grace_s)
    service.close()
    log.info("stopped")
    return 0


def _install_signal_handlers(stop: threading.Event) -> None:
    def on_signal(signum, _frame):
        if stop.is_set():
            os._exit(128 + signum)  # second signal: the operator wants out now
        stop.set()

    signal.signal(signal.SIGINT, on_signal)
    signal.signal(signal.SIGTERM, on_signal)


def _stop_when_parent_exits(stop: threading.Event) -> None:
    parent = os.environ.get(PARENT_PID_ENV)
    if not parent:
        return

    def watch():
        while not stop.wait(_PARENT_POLL_S):
            if os.getppid() != int(parent):
                log.warning("parent %s is gone; stopping", parent)
                stop.set()

    threading.Thread(target=watch, name="parent-watch", daemon=True).start()
