"""python -m services.observation: the station's observation, published once into Zenoh.

It reads ForceSensor (every wrench sample), ProxyRobot (the arm's state at 100 Hz), the
DecisionServer (its events) and the StereoCamera (its H.264 video) as an observer, each stream
only while someone subscribes to its topic, and publishes them through the station's router
(services.zenoh_router, or the one --router names) under telerobot/<station>/...
(wire/observation.py). Subscribers anywhere behind the router get them: `python -m
clients.observe`, Zenoh's clients in any language with the protos as the schema. Commands stay
on gRPC.

The router going away stops nothing at the station: the puts are dropped meanwhile, this
process says so once, and Zenoh reconnects when the router is back.
"""

from __future__ import annotations

import argparse
import logging
import os
import sys
import threading

import zenoh

from services.observation.publisher import ObservationPublisher, station_streams
from services.runtime.config import configure_logging
from services.runtime.process import stop_requested, wait_for_stop
from services.runtime.tls import station_channel_security
from wire.addresses import address_for, env_name
from wire.observation import (
    STATION_ENV,
    BadEndpoint,
    ZenohTls,
    checked_endpoint,
    client,
    close_session,
    default_router,
    station_name,
    tls_from,
)
from wire.processes import dump_stacks_on_signal, say_ready
from wire.tls import TLS_DIR_ENV, open_channel

log = logging.getLogger("observation")

NAME = "observation"
RETRY_S = 1.0  # a router that is not there yet is asked again this often
UPSTREAM = ("proxy_robot", "force_sensor", "decision_server", "stereo_camera")


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="python -m services.observation", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--router", default=None,
                        help="the Zenoh router to publish through, tcp/HOST:PORT or "
                             "tls/HOST:PORT (env TELEROBOT_ZENOH_ROUTER; default: the "
                             f"station's own, {env_name('zenoh_router', 'address')})")
    parser.add_argument("--station", default=os.environ.get(STATION_ENV),
                        help=f"the station's name in the keys (env {STATION_ENV}; default "
                             "station)")
    for service in UPSTREAM:
        parser.add_argument(f"--{service.replace('_', '-')}", default=address_for(service),
                            help=f"its address (env {env_name(service, 'address')})")
    parser.add_argument("--tls-dir", default=os.environ.get(TLS_DIR_ENV, ""),
                        help=f"the station's TLS directory (env {TLS_DIR_ENV}): the services are "
                             f"read, and the router joined over mutual TLS, with {NAME}.pem")
    parser.add_argument("--log-level", default=os.environ.get("TELEROBOT_LOG_LEVEL", "INFO"))
    return parser


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    configure_logging(NAME, args.log_level)
    dump_stacks_on_signal()
    try:
        station = station_name(args.station)
        router = checked_endpoint(args.router or default_router(args.tls_dir),
                                  tls=bool(args.tls_dir))
        tls = tls_from(args.tls_dir, NAME)
        if tls is not None:
            tls.files()  # there, before waiting for a router
    except (ValueError, BadEndpoint) as error:
        print(f"{NAME}: {error}", file=sys.stderr)
        return 2
    stop = stop_requested()
    session = _join(router, tls, stop)
    if session is None:
        return 0
    security = station_channel_security(args.tls_dir or None, NAME)
    channels = [open_channel(getattr(args, service), security=security, service=service)
                for service in UPSTREAM]
    publisher = ObservationPublisher(session, station, station_streams(*channels),
                                     on_status=_say_status).start()
    try:
        log.info("publishing telerobot/%s/... through %s while anyone subscribes", station,
                 router)
        say_ready(NAME, router.split("/", 1)[1])
        wait_for_stop(stop)
    finally:
        publisher.close()
        close_session(session)
        for channel in channels:
            channel.close()
    log.info("stopped; published %s", dict(publisher.published))
    return 0


def _join(router: str, tls: ZenohTls | None, stop: threading.Event) -> zenoh.Session | None:
    """A client session through `router`, asking again every RETRY_S until it answers; None
    if a stop came first."""
    said = False
    while not stop.is_set():
        try:
            return client(router, tls)
        except zenoh.ZError as error:
            if not said:
                log.warning("the router %s does not answer (%s); asking again every %.0f s",
                            router, error, RETRY_S)
                said = True
        stop.wait(RETRY_S)
    return None


def _say_status(topic: str, why: str | None) -> None:
    if why is None:
        log.info("the %s stream flows again", topic)


if __name__ == "__main__":
    raise SystemExit(main())
