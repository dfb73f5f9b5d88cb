"""python -m services.foxglove: the slave station's live view, a Foxglove WebSocket server
(foxglove-sdk) streaming the arm's frames, joint states, the force arrow and both cameras (each
eye's JPEG, and both side by side as H.264 video), in the same channels as the MCAP recordings
(services.foxglove.live). Open it in Foxglove or Lichtblick: "Open connection" > "Foxglove
WebSocket" > ws://127.0.0.1:8765, with the layout docs/foxglove_layout.json.

It reads ProxyRobot, ForceSensor and StereoCamera as an observer, each stream only while a
viewer watches one of its topics. With --router it reads the station's observation from a Zenoh
router instead (services.foxglove.router_feeds): the view then runs anywhere behind a router,
without the per-eye JPEG images. It listens on loopback by default. The Foxglove protocol has
no client authentication, so beyond loopback it listens only when told so explicitly
(--allow-network or TELEROBOT_ALLOW_LIVE_VIEW_NETWORK=1): anyone who reaches the port then sees
the arm and the video (never moves it: the view is read-only). With the station's TLS
directory it serves wss:// with its own certificate (`make certs` issues foxglove.pem). A
browser page may watch only from the Foxglove app's origin, a desktop app's (file://) or one
given with --allowed-origin: any other page the user opens is refused.
"""

from __future__ import annotations

import argparse
import logging
import os
import ssl
import sys
from pathlib import Path

import foxglove
from foxglove import Context, StatusLevel

from services.foxglove.feeds import DEFAULT_VIDEO_KBIT, station_feeds
from services.foxglove.live import Demand, LiveChannels
from services.foxglove.origin_gate import DEFAULT_ORIGINS, OriginGate, loopback_certificate
from services.foxglove.router_feeds import ROUTER_FEEDS, router_feeds
from services.runtime.config import configure_logging
from services.runtime.process import stop_requested, wait_for_stop
from services.runtime.tls import station_channel_security
from wire.addresses import address_for, env_name, is_loopback
from wire.observation import STATION_ENV, join_or_exit_code
from wire.processes import dump_stacks_on_signal, say_ready
from wire.tls import TLS_DIR_ENV, open_channel

log = logging.getLogger("foxglove")

NAME = "foxglove"
NETWORK_ENV = "TELEROBOT_ALLOW_LIVE_VIEW_NETWORK"
SERVER_NAME = "telerobot slave station"
ALLOWED_ORIGINS_ENV = env_name(NAME, "allowed_origins")


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="python -m services.foxglove", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--address", default=address_for(NAME),
                        help=f"host:port to listen on (env {env_name(NAME, 'address')})")
    for service in ("proxy_robot", "force_sensor", "stereo_camera"):
        parser.add_argument(f"--{service.replace('_', '-')}", default=address_for(service),
                            help=f"its address (env {env_name(service, 'address')})")
    parser.add_argument("--router", default=None,
                        help="watch through this Zenoh router, tcp/HOST:PORT (loopback) or "
                             "tls/HOST:PORT, instead of the services' own ports")
    parser.add_argument("--station", default=os.environ.get(STATION_ENV),
                        help=f"with --router: the station to watch (env {STATION_ENV}; "
                             "default station)")
    parser.add_argument("--tls-dir", default=os.environ.get(TLS_DIR_ENV, ""),
                        help=f"the station's TLS directory (env {TLS_DIR_ENV}): wss:// with "
                             "foxglove.pem, and the services (or the router) read with that "
                             "certificate")
    parser.add_argument("--allow-network", action="store_true",
                        default=os.environ.get(NETWORK_ENV) == "1",
                        help=f"listen beyond loopback (env {NETWORK_ENV}=1): viewers are not "
                             "authenticated")
    parser.add_argument("--allowed-origin", action="append", dest="allowed_origins",
                        default=[o for o in os.environ.get(ALLOWED_ORIGINS_ENV, "").split(",")
                                 if o],
                        help="a web origin whose pages may watch (e.g. http://localhost:8080), "
                             f"besides {' and '.join(DEFAULT_ORIGINS)} and programs that send "
                             "no Origin (repeat for several; env "
                             f"{ALLOWED_ORIGINS_ENV}, comma-separated): the WebSocket upgrade "
                             "of a page of any other origin is refused")
    parser.add_argument("--state-hz", type=float, default=30.0,
                        help="the arm's state rate (/tf, /joint_states)")
    parser.add_argument("--wrench-hz", type=float, default=50.0,
                        help="the force rate (/force/arrow), decimated from the sensor's 1 kHz")
    parser.add_argument("--stereo-fps", type=float, default=10.0,
                        help="the cameras' frame rate, at most (the JPEG images and the video)")
    parser.add_argument("--video-kbit", type=int, default=DEFAULT_VIDEO_KBIT,
                        help="the H.264 video's bitrate ceiling, kbit/s (/camera/stereo/video; "
                             "it adapts below it to what the camera's link delivers)")
    parser.add_argument("--log-level", default=os.environ.get("TELEROBOT_LOG_LEVEL", "INFO"))
    return parser


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    configure_logging(NAME, args.log_level)
    dump_stacks_on_signal()
    for option in ("state_hz", "wrench_hz", "stereo_fps", "video_kbit"):
        if not getattr(args, option) > 0:
            print(f"{NAME}: --{option.replace('_', '-')} must be > 0", file=sys.stderr)
            return 2
    host, _, port = args.address.rpartition(":")
    if not is_loopback(args.address) and not args.allow_network:
        print(f"{NAME}: refusing to listen on {args.address}: Foxglove viewers are not "
              f"authenticated, so anyone who reaches it would watch the arm and the cameras. "
              f"Listen on 127.0.0.1, or pass --allow-network ({NETWORK_ENV}=1)", file=sys.stderr)
        return 2
    tls = None
    if args.tls_dir:
        cert, key = (Path(args.tls_dir) / f"{NAME}.{ext}" for ext in ("pem", "key"))
        if not (cert.exists() and key.exists()):
            print(f"{NAME}: {cert} or {key} is missing: run `make certs` again (it issues the "
                  "live view's certificate)", file=sys.stderr)
            return 2
        tls = ssl.create_default_context(ssl.Purpose.CLIENT_AUTH)
        try:
            tls.load_cert_chain(cert, key)
        except ssl.SSLError as error:
            print(f"{NAME}: {cert} and {key} are no certificate and its key: {error}",
                  file=sys.stderr)
            return 2

    context = Context()
    viewers = _Viewers()
    upstream: list = []  # what the feeds read through, closed at the end
    if args.router:
        joined = join_or_exit_code(NAME, args.router, args.station, args.tls_dir, NAME)
        if isinstance(joined, int):
            return joined
        station, session = joined
        upstream.append(session)
        channels = LiveChannels(context, feeds=ROUTER_FEEDS)
        feeds = router_feeds(channels, session, station, state_hz=args.state_hz,
                             wrench_hz=args.wrench_hz)
    else:
        security = station_channel_security(args.tls_dir or None, NAME)
        # Over TLS each service's certificate must name that service (wire.tls).
        upstream += [open_channel(address, security=security, service=service)
                     for address, service in ((args.proxy_robot, "proxy_robot"),
                                              (args.force_sensor, "force_sensor"),
                                              (args.stereo_camera, "stereo_camera"))]
        channels = LiveChannels(context)
        feeds = station_feeds(channels, *upstream, state_hz=args.state_hz,
                              wrench_hz=args.wrench_hz, stereo_fps=args.stereo_fps,
                              video_kbit=args.video_kbit, on_status=viewers.show_feed_status)
    demand = Demand(lambda feed, wanted: feeds[feed].want(wanted), channels.viewer_joined)
    for feed in feeds.values():
        feed.start()
    stop = stop_requested()
    server = gate = None
    try:
        # The SDK's server on loopback, behind the gate that checks each viewer's Origin (the
        # SDK cannot), over TLS with a certificate only the gate trusts.
        inner_cert, inner_key = loopback_certificate()
        try:
            server = foxglove.start_server(name=SERVER_NAME, host="127.0.0.1", port=0,
                                           server_listener=demand, context=context,
                                           tls_cert=inner_cert, tls_key=inner_key)
            gate = OriginGate(server.port, inner_cert, [*DEFAULT_ORIGINS, *args.allowed_origins],
                              tls=tls)
            bound = gate.start(host.strip("[]"), int(port))
        except (RuntimeError, ValueError, OSError) as error:  # the port taken, a bad cert
            print(f"{NAME}: cannot serve on {args.address}: {error}", file=sys.stderr)
            return 1
        viewers.server = server
        address = f"{host}:{bound}"
        log.info("the live view serves %s://%s/ to viewers from %s or with no Origin",
                 "wss" if tls else "ws", address, ", ".join(sorted(gate.allowed)))
        say_ready(NAME, address)
        wait_for_stop(stop)
    finally:
        if gate is not None:
            gate.stop()
        if server is not None:
            server.stop()
        for feed in feeds.values():
            feed.stop()
        channels.close()
        for link in upstream:
            link.close()
    log.info("stopped; published %s", dict(channels.published))
    return 0


class _Viewers:
    """Tells the viewers (Foxglove's problems panel) why a feed stopped, e.g. the arm not
    connected yet, and clears it once the feed flows again."""

    def __init__(self):
        self.server: foxglove.WebSocketServer | None = None  # once it serves

    def show_feed_status(self, feed: str, why: str | None) -> None:
        if self.server is None:
            return
        status_id = f"feed-{feed}"
        if why is None:
            self.server.remove_status([status_id])
        else:
            self.server.publish_status(f"the {feed} feed stopped ({why}); retrying",
                                       StatusLevel.Warning, status_id)


if __name__ == "__main__":
    raise SystemExit(main())
