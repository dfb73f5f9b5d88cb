"""python -m services.web_console: the web console's gateway (see services/web_console)."""

from __future__ import annotations

import argparse
import asyncio
import logging
import os
import sys
from pathlib import Path

import grpc
import uvicorn

from services.runtime.config import PLAINTEXT_ENV, configure_logging
from services.runtime.process import watch_parent
from services.runtime.server import PlaintextRefused, check_plaintext
from services.web_console.app import ConsoleApp
from services.web_console.bridge import Upstream
from wire.addresses import address_for, env_name
from wire.processes import dump_stacks_on_signal, ready_line
from wire.stereo import LOW_LATENCY_OPTIONS
from wire.tls import KEEPALIVE_OPTIONS, TLS_DIR_ENV

log = logging.getLogger("web_console")

NAME = "web_console"
TOKEN_ADDRESS_ENV = env_name("decision_server", "token_address")
ALLOWED_HOSTS_ENV = env_name(NAME, "allowed_hosts")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m services.web_console",
                                     description=__doc__)
    parser.add_argument("--address", default=address_for(NAME),
                        help=f"host:port the console listens on (env {env_name(NAME, 'address')})")
    parser.add_argument("--decision-server", default=address_for("decision_server"),
                        help="the DecisionServer's address (env "
                             f"{env_name('decision_server', 'address')})")
    parser.add_argument("--token-address", default=os.environ.get(TOKEN_ADDRESS_ENV, ""),
                        help="with TLS: the DecisionServer's bearer-token port, where the "
                             f"browsers' tokens are forwarded (env {TOKEN_ADDRESS_ENV})")
    parser.add_argument("--tls-dir", default=os.environ.get(TLS_DIR_ENV, ""),
                        help=f"the station's TLS directory (env {TLS_DIR_ENV}): its ca.pem "
                             "verifies the token port")
    parser.add_argument("--allow-plaintext-network", action="store_true",
                        default=os.environ.get(PLAINTEXT_ENV) == "1",
                        help="listen beyond loopback without TLS (the console serves HTTP only)")
    parser.add_argument("--allowed-host", action="append", dest="allowed_hosts",
                        default=[h for h in os.environ.get(ALLOWED_HOSTS_ENV, "").split(",")
                                 if h],
                        help="a name browsers reach the console by, besides an IP address or "
                             "localhost (repeat for several; env "
                             f"{ALLOWED_HOSTS_ENV}, comma-separated): a request with any other "
                             "name in its Host header is refused, as a DNS-rebinding page's is")
    parser.add_argument("--log-level", default=os.environ.get("TELEROBOT_LOG_LEVEL", "INFO"))
    args = parser.parse_args(argv)
    configure_logging(NAME, args.log_level)
    dump_stacks_on_signal()
    try:
        # The console itself serves plain HTTP: beyond loopback only when told so explicitly.
        check_plaintext(args.address, False, args.allow_plaintext_network)
    except PlaintextRefused as refused:
        print(f"web_console: {refused}", file=sys.stderr)
        return 2
    return asyncio.run(_serve(args))


def _channels(args) -> tuple[Upstream, str]:
    """The channels to the DecisionServer and the page's auth mode ("none" or "token")."""
    options = list(KEEPALIVE_OPTIONS)
    if not args.tls_dir:
        return Upstream(grpc.aio.insecure_channel(args.decision_server, options=options),
                        grpc.aio.insecure_channel(args.decision_server,
                                                  options=[*options, *LOW_LATENCY_OPTIONS])), "none"
    if not args.token_address:
        refusal = (f"this TLS station's DecisionServer has no bearer-token port, so a browser "
                   f"cannot authenticate: set {TOKEN_ADDRESS_ENV} (for example "
                   f"127.0.0.1:50061) for the station")
        log.warning("%s", refusal)
        closed = grpc.aio.insecure_channel("127.0.0.1:9")  # never called
        return Upstream(closed, closed, refusal), "token"
    # Server authentication only: each call carries the browser's own token, so the
    # DecisionServer checks the browser's identity and role and audits it under that name.
    credentials = grpc.ssl_channel_credentials((Path(args.tls_dir) / "ca.pem").read_bytes())
    return Upstream(
        grpc.aio.secure_channel(args.token_address, credentials, options=options),
        grpc.aio.secure_channel(args.token_address, credentials,
                                options=[*options, *LOW_LATENCY_OPTIONS]),
        needs_token=True), "token"


async def _serve(args) -> int:
    upstream, auth = _channels(args)
    host, port = args.address.rsplit(":", 1)
    app = ConsoleApp(upstream, auth, args.allowed_hosts)
    config = uvicorn.Config(app, host=host.strip("[]"), port=int(port),
                            log_level="warning", access_log=False, lifespan="on",
                            ws_max_size=1 << 16, timeout_graceful_shutdown=2)
    server = uvicorn.Server(config)
    watch_parent(lambda: setattr(server, "should_exit", True))
    serving = asyncio.ensure_future(server.serve())
    while not server.started:
        if serving.done():
            return 1  # it could not bind; uvicorn logged why
        await asyncio.sleep(0.01)
    bound = server.servers[0].sockets[0].getsockname()
    address = f"{bound[0]}:{bound[1]}"
    log.info("serving the console on http://%s/ for the DecisionServer at %s", address,
             args.token_address if auth == "token" else args.decision_server)
    print(ready_line(NAME, address), flush=True)
    await serving
    await upstream.channel.close()
    await upstream.stereo_channel.close()
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
