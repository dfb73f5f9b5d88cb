"""python -m services.zenoh_router: the station's Zenoh router, which observers subscribe
through (docs/observers.md).

It listens on --address: plaintext on loopback, or with the station's TLS directory (--tls-dir)
mutual TLS anywhere, where only the station's publisher and other routers may put into its keys
(wire/observation.py ACCESS_CONTROL); plaintext beyond loopback is refused. It may join other
routers with --connect, so that a router near a remote team relays the station's streams to
its own subscribers: one copy crosses the link between routers, however many subscribe behind
it. It carries observation only (wire/observation.py): commands stay on gRPC. Once it listens
it prints its ready line with the address it bound (a port 0 picks a free one).
"""

from __future__ import annotations

import argparse
import json
import logging
import os
import sys
from pathlib import Path

import zenoh

from services.runtime.config import configure_logging
from services.runtime.process import stop_requested, wait_for_stop
from wire.addresses import address_for, env_name
from wire.observation import (
    BadEndpoint,
    SessionPlan,
    ZenohTls,
    close_session,
    endpoint_for,
)
from wire.processes import dump_stacks_on_signal, say_ready
from wire.tls import TLS_DIR_ENV

log = logging.getLogger("zenoh_router")

NAME = "zenoh_router"
CONNECT_ENV = env_name(NAME, "connect")
LOOKUP_TIMEOUT_S = 5.0
# Zenoh's default is 1,000 sessions: a class or a remote team behind one router may be more.
DEFAULT_MAX_SESSIONS = 4096


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="python -m services.zenoh_router", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--address", default=address_for(NAME),
                        help=f"host:port to listen on (env {env_name(NAME, 'address')})")
    parser.add_argument("--connect", action="append",
                        default=[e for e in os.environ.get(CONNECT_ENV, "").split(",") if e],
                        help="another router to join, tls/HOST:PORT, or tcp/HOST:PORT on loopback "
                             "(repeat for several; env "
                             f"{CONNECT_ENV}, comma-separated)")
    parser.add_argument("--tls-dir", default=os.environ.get(TLS_DIR_ENV, ""),
                        help=f"the station's TLS directory (env {TLS_DIR_ENV}): mutual TLS with "
                             f"{NAME}.pem, and the access rules")
    parser.add_argument("--max-sessions", type=int, default=DEFAULT_MAX_SESSIONS,
                        help="the most sessions (subscribers' and routers') it takes at once")
    parser.add_argument("--log-level", default=os.environ.get("TELEROBOT_LOG_LEVEL", "INFO"))
    return parser


def listening_on(session: zenoh.Session) -> list[str]:
    """The endpoints the router bound, from its admin space (a port 0 made real)."""
    for reply in session.get(f"@/{session.zid()}/router", timeout=LOOKUP_TIMEOUT_S):
        if reply.ok is not None:
            return json.loads(reply.ok.payload.to_string())["locators"]
    return []


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    configure_logging(NAME, args.log_level)
    if args.max_sessions < 1:
        print(f"{NAME}: --max-sessions must be at least 1", file=sys.stderr)
        return 2
    dump_stacks_on_signal()
    tls = ZenohTls(Path(args.tls_dir), NAME) if args.tls_dir else None
    plan = SessionPlan("router", listen=(endpoint_for(args.address, tls=bool(tls)),),
                       connect=tuple(args.connect), tls=tls)
    try:
        config = plan.config()
        config.insert_json5("adminspace/enabled", "true")  # (read by listening_on)
        config.insert_json5("transport/unicast/max_sessions", str(args.max_sessions))
        session = zenoh.open(config)
    except BadEndpoint as error:
        print(f"{NAME}: {error}", file=sys.stderr)
        return 2
    except zenoh.ZError as error:  # the port taken, an endpoint Zenoh cannot parse
        print(f"{NAME}: cannot listen on {args.address}: {error}", file=sys.stderr)
        return 1
    stop = stop_requested()
    try:
        bound = listening_on(session)
        if not bound:
            print(f"{NAME}: listening on {args.address}, but its address is unknown",
                  file=sys.stderr)
            return 1
        address = bound[0].split("/", 1)[1]
        log.info("routing on %s%s", bound[0],
                 f", joined to {', '.join(args.connect)}" if args.connect else "")
        say_ready(NAME, address)
        wait_for_stop(stop)
    finally:
        close_session(session)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
