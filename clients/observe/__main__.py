"""python -m clients.observe: watch a station's observation through a Zenoh router.

Subscribes to telerobot/<station>/{wrench,state,events,status} (wire/observation.py; --topics
adds the video) through the router --router names and prints, each --every seconds, what each
topic delivered: samples per second, samples lost, and the lag from when a sample was taken (on
this host's clock). --events prints each event as it comes, --status the session's status each
time it changes; --json prints one JSON summary at the end instead.
Exits after --seconds, or on Ctrl-C; 1 if nothing arrived.
"""

from __future__ import annotations

import argparse
import json
import os
import signal
import sys
import threading
import time

from google.protobuf import json_format

from clients.observe import Observer
from wire.observation import (
    DEFAULT_TOPICS,
    TOPICS,
    BadEndpoint,
    RouterUnreachable,
    close_session,
    default_router,
    join_router,
)
from wire.processes import handle_signals
from wire.tls import IDENTITY_ENV, TLS_DIR_ENV


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="python -m clients.observe", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--router", default=None,
                        help="the router to subscribe through, tcp/HOST:PORT (loopback) or "
                             "tls/HOST:PORT (env TELEROBOT_ZENOH_ROUTER; default: the "
                             "station's own on this host)")
    parser.add_argument("--tls-dir", default=os.environ.get(TLS_DIR_ENV, ""),
                        help=f"a TLS directory of the station's PKI (env {TLS_DIR_ENV}): mutual "
                             "TLS with --identity's certificate")
    parser.add_argument("--identity", default=os.environ.get(IDENTITY_ENV, "observer"),
                        help=f"whose certificate to present (env {IDENTITY_ENV}; default "
                             "observer)")
    parser.add_argument("--station", default="*",
                        help="the station to watch (default: every station behind the router)")
    parser.add_argument("--topics", default=",".join(DEFAULT_TOPICS),
                        help=f"comma-separated, of {', '.join(TOPICS)} (default "
                             f"{','.join(DEFAULT_TOPICS)}: the video makes the cameras render)")
    parser.add_argument("--seconds", type=float, default=0.0,
                        help="stop after this long (default: until Ctrl-C)")
    parser.add_argument("--every", type=float, default=1.0, help="seconds between lines")
    parser.add_argument("--events", action="store_true", help="print each event as it comes")
    parser.add_argument("--status", action="store_true",
                        help="print the session's status (control, assistance, dependencies) "
                             "as JSON each time it changes")
    parser.add_argument("--json", action="store_true", help="one JSON summary at the end")
    return parser


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    topics = tuple(t for t in args.topics.split(",") if t)
    try:
        session = join_router(args.router or default_router(args.tls_dir), args.tls_dir,
                              args.identity)
    except BadEndpoint as error:
        print(f"observe: {error}", file=sys.stderr)
        return 2
    except RouterUnreachable as error:
        print(f"observe: {error}", file=sys.stderr)
        return 1

    shown_status: list[str] = [""]  # the last status printed, without its time

    def show_event(topic: str, message) -> None:
        if topic == "events" and args.events:
            print(json.dumps(json_format.MessageToDict(message)), flush=True)
        elif topic == "status" and args.status:
            status = json_format.MessageToDict(message)
            status.pop("statusTime", None)
            text = json.dumps(status)
            if text != shown_status[0]:
                shown_status[0] = text
                print(text, flush=True)

    try:
        observer = Observer(session, args.station, topics, on_message=show_event)
    except ValueError as error:
        session.close()
        print(f"observe: {error}", file=sys.stderr)
        return 2
    stop = threading.Event()
    handle_signals({signal.SIGINT: lambda _: stop.set(), signal.SIGTERM: lambda _: stop.set()})
    deadline = time.monotonic() + args.seconds if args.seconds > 0 else None
    try:
        while not stop.wait(args.every):
            if not args.json:
                print(_line(observer.summary()), flush=True)
            if deadline is not None and time.monotonic() >= deadline:
                break
    finally:
        summary = observer.summary()
        observer.close()
        close_session(session)
    if args.json:
        print(json.dumps(summary))
    return 0 if any(count["messages"] for count in summary.values()) else 1


def _line(summary: dict[str, dict]) -> str:
    return "; ".join(
        f"{topic} {c['samples_per_s']}/s, lost {c['lost']}, lag p50 {c['lag_p50_ms']} / "
        f"p99 {c['lag_p99_ms']} ms" for topic, c in summary.items())


if __name__ == "__main__":
    raise SystemExit(main())
