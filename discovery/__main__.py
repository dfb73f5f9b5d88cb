"""python -m discovery: find slave stations on the local network (`_telerobot._tcp`).

    python -m discovery list [--timeout 3]     # each station heard: name, addresses,
                                                        #   TLS, contract; exit 1 if none
    python -m discovery address [NAME]         # host:port of NAME's (or the only)
                                                        #   DecisionServer, for a client
    python -m discovery watch                  # "+ station" / "- name" until Ctrl-C
    python -m discovery advertise --address 10.0.0.2:50051 [--tls] [--token-port N]
                                                        # advertise a station started some
                                                        #   other way, until Ctrl-C

`make serve` advertises the station itself (see discovery/advertise.py).
"""

from __future__ import annotations

import argparse
import logging
import os
import signal
import sys
import threading

from discovery.advertise import ADVERTISE_ENV, STATION_NAME_ENV, plan
from discovery.browse import DEFAULT_TIMEOUT_S, Browser, browse, discovered_address
from discovery.station import SERVICE_TYPE, DiscoveryError, Station
from wire.processes import dump_stacks_on_signal

# The line `advertise` prints once the advertisement is out, before the name it got.
ADVERTISED_LINE = "advertised as"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m discovery", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--log-level", default=os.environ.get("TELEROBOT_LOG_LEVEL", "WARNING"))
    commands = parser.add_subparsers(dest="command", required=True)
    listing = commands.add_parser("list", help="print the stations heard within the timeout")
    address = commands.add_parser("address", help="print host:port of a station's "
                                  "DecisionServer")
    address.add_argument("name", nargs="?", help="the station's name (default: the only one)")
    for command in (listing, address):
        command.add_argument("--timeout", type=float, default=DEFAULT_TIMEOUT_S,
                             help=f"how long to listen, in seconds (default {DEFAULT_TIMEOUT_S})")
    commands.add_parser("watch", help="print stations as they come and go, until Ctrl-C")
    advertise = commands.add_parser("advertise", help="advertise a station until Ctrl-C")
    advertise.add_argument("--address", required=True,
                           help="host:port where its DecisionServer listens")
    advertise.add_argument("--tls", action="store_true", help="its ports require TLS")
    advertise.add_argument("--token-port", type=int, help="its bearer-token port")
    advertise.add_argument("--name", default=os.environ.get(STATION_NAME_ENV),
                           help=f"the station's name (env {STATION_NAME_ENV}; default "
                                "<host>:<port>)")
    advertise.add_argument("--mode", default=os.environ.get(ADVERTISE_ENV) or "1",
                           choices=["1", "0", "auto"],
                           help="1 (default): advertise even on loopback; auto: only beyond it")
    args = parser.parse_args(argv)
    dump_stacks_on_signal()
    logging.basicConfig(level=args.log_level.upper(),
                        format="%(asctime)s discovery[%(process)d] %(levelname)s: %(message)s")
    try:
        if args.command == "list":
            return _list(args.timeout)
        if args.command == "address":
            print(discovered_address(args.name, args.timeout), flush=True)
            return 0
        if args.command == "watch":
            return _watch()
        return _advertise(args)
    except DiscoveryError as exc:
        print(f"python -m discovery: {exc}", file=sys.stderr)
        return 1


def _list(timeout_s: float) -> int:
    stations = browse(timeout_s)
    if not stations:
        print(f"no slave station heard within {timeout_s:g} s ({SERVICE_TYPE})",
              file=sys.stderr)
        return 1
    for station in stations:
        print(station.describe(), flush=True)
    return 0


def _watch() -> int:
    stop = _stop_on_signals()

    def on_change(kind: str, station: Station) -> None:
        print(f"+ {station.describe()}" if kind == "+" else f"- {station.name}", flush=True)

    with Browser(on_change):
        print(f"watching for {SERVICE_TYPE}; Ctrl-C stops", flush=True)
        _wait(stop)
    return 0


def _advertise(args: argparse.Namespace) -> int:
    stop = _stop_on_signals()
    advertisement = plan(args.address, tls=args.tls, token_port=args.token_port,
                         mode=args.mode, name=args.name)
    if advertisement is None:
        print(f"not advertising {args.address}: loopback only (--mode 1 to advertise anyway)",
              file=sys.stderr)
        return 1
    with advertisement:
        print(f"{ADVERTISED_LINE} {advertisement.name}", flush=True)
        _wait(stop)
    print("withdrawn", flush=True)
    return 0


def _wait(stop: threading.Event) -> None:
    while not stop.wait(0.5):  # a bounded wait, so the signal handler always gets its turn
        pass


def _stop_on_signals() -> threading.Event:
    stop = threading.Event()
    for signum in (signal.SIGINT, signal.SIGTERM):
        signal.signal(signum, lambda *_: stop.set())
    return stop


if __name__ == "__main__":
    raise SystemExit(main())
