"""python -m services.web_console: the web console's gateway (see services/web_console)."""

from __future__ import annotations

import argparse
import asyncio
import functools
import logging
import os
import sys
from pathlib import Path

import grpc
import uvicorn

from services.runtime.config import PLAINTEXT_ENV, configure_logging
from services.runtime.process import watch_parent
from services.runtime.server import PlaintextRefused
from services.web_console.app import ConsoleApp, TransportBoundProtocol
from services.web_console.bridge import Upstream
from services.web_console.https import RenewingCertificate, certificate_files, issue_command
from services.web_console.watch import RouterWatch
from wire.addresses import address_for, env_name, is_loopback
from wire.observation import DEFAULT_STATION, STATION_ENV, join_or_exit_code
from wire.processes import dump_stacks_on_signal, say_ready
from wire.stereo import LOW_LATENCY_OPTIONS
from wire.tls import IDENTITY_ENV, KEEPALIVE_OPTIONS, TLS_DIR_ENV, server_name_options

log = logging.getLogger("web_console")

NAME = "web_console"
TOKEN_ADDRESS_ENV = env_name("decision_server", "token_address")
ALLOWED_HOSTS_ENV = env_name(NAME, "allowed_hosts")
# What one client may hold of the console before it is authenticated, if ever:
MAX_CONNECTIONS = 64  # open at once; a request beyond them gets 503 (uvicorn's limit_concurrency)
HEAD_TIMEOUT_S = 10.0  # from a connection's opening (or its last response) to a whole request head
HANDSHAKE_TIMEOUT_S = 10.0  # over HTTPS, from a connection's opening to its TLS handshake's end
KEEP_ALIVE_S = 5  # an idle connection's life after a response
MAX_HEAD_BYTES = 16 * 1024  # a request line and headers; larger: 400, and closed


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
                             "verifies the token port, and with web_console.pem and "
                             "web_console.key in it the console serves HTTPS, on any address")
    parser.add_argument("--allow-plaintext-network", action="store_true",
                        default=os.environ.get(PLAINTEXT_ENV) == "1",
                        help="DANGEROUS: serve HTTP beyond loopback (without the console's "
                             "certificate in --tls-dir)")
    parser.add_argument("--allowed-host", action="append", dest="allowed_hosts",
                        default=[h for h in os.environ.get(ALLOWED_HOSTS_ENV, "").split(",")
                                 if h],
                        help="a name browsers reach the console by, besides an IP address or "
                             "localhost (repeat for several; env "
                             f"{ALLOWED_HOSTS_ENV}, comma-separated): a request with any other "
                             "name in its Host header is refused, as a DNS-rebinding page's is")
    parser.add_argument("--router", default=None,
                        help="watch only, through this Zenoh router: tcp/HOST:PORT (loopback) "
                             "or tls/HOST:PORT (with --tls-dir). The page shows the station's "
                             "observation and refuses every command")
    parser.add_argument("--station", default=None,
                        help=f"with --router: the station to watch (env {STATION_ENV}; "
                             f"default {DEFAULT_STATION})")
    parser.add_argument("--identity", default=os.environ.get(IDENTITY_ENV, "observer"),
                        help="with --router over TLS: the certificate presented to the router "
                             f"(<identity>.pem in --tls-dir; env {IDENTITY_ENV})")
    parser.add_argument("--allow-network", action="store_true",
                        help="with --router: serve browsers beyond loopback. A watch-only "
                             "console asks nobody for a token, so anyone who reaches its port "
                             "watches the arm and the cameras")
    parser.add_argument("--log-level", default=os.environ.get("TELEROBOT_LOG_LEVEL", "INFO"))
    args = parser.parse_args(argv)
    configure_logging(NAME, args.log_level)
    dump_stacks_on_signal()
    if args.router and not is_loopback(args.address) and not args.allow_network:
        print(f"{NAME}: refusing to watch on {args.address}: a watch-only console asks nobody "
              "for a token, so anyone who reaches it would watch the arm and the cameras. "
              "Listen on 127.0.0.1, or pass --allow-network", file=sys.stderr)
        return 2
    files = certificate_files(args.tls_dir)
    try:
        check_listening(args.address, args.tls_dir, files is not None,
                        args.allow_plaintext_network)
        certificate = RenewingCertificate(*files) if files else None
    except PlaintextRefused as refused:
        print(f"web_console: {refused}", file=sys.stderr)
        return 2
    except (OSError, ValueError) as error:  # ssl.SSLError is an OSError
        print(f"web_console: cannot serve HTTPS with {files[0]} and {files[1]}: {error}",
              file=sys.stderr)
        return 2
    if args.tls_dir and certificate is None:
        log.warning("serving HTTP, not HTTPS: the TLS directory has no %s.pem and .key (%s)",
                    NAME, issue_command(args.tls_dir))
    return asyncio.run(_serve(args, certificate))


def check_listening(address: str, tls_dir: str, https: bool, allow_plaintext_network: bool
                    ) -> None:
    """PlaintextRefused for HTTP beyond loopback unless allowed (then a warning). Over HTTPS
    the console may listen anywhere: browsers sign in with tokens (a TLS station's console
    forwards only to the token port, and refuses every call without one)."""
    if https or is_loopback(address):
        return
    if not allow_plaintext_network:
        how = (f"issue the console's certificate into {tls_dir} ({issue_command(tls_dir)})"
               if tls_dir else "run the station with TLS (`make certs`, TELEROBOT_TLS_DIR) and "
               "the console's certificate in that directory")
        raise PlaintextRefused(
            f"refusing to serve the console on {address} over plain HTTP: anyone on that "
            f"network could take the lock and move the arm. To serve HTTPS, {how}; or listen "
            "on 127.0.0.1, or pass --allow-plaintext-network")
    log.warning("PLAINTEXT beyond loopback on %s: the console serves HTTP. Anyone who reaches "
                "this port can command the arm.", address)


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
    # The token port's certificate must be the DecisionServer's (wire.tls).
    options = [*options, *server_name_options("decision_server")]
    return Upstream(
        grpc.aio.secure_channel(args.token_address, credentials, options=options),
        grpc.aio.secure_channel(args.token_address, credentials,
                                options=[*options, *LOW_LATENCY_OPTIONS]),
        needs_token=True), "token"


async def _serve(args, certificate: RenewingCertificate | None) -> int:
    if args.router:
        joined = join_or_exit_code(NAME, args.router, args.station, args.tls_dir, args.identity)
        if isinstance(joined, int):
            return joined
        watch = RouterWatch(joined[1], joined[0], args.router)
        try:
            return await _serve_app(args, certificate, ConsoleApp(watch, "none",
                                                                  args.allowed_hosts))
        finally:
            watch.session.close()
    upstream, auth = _channels(args)
    try:
        return await _serve_app(args, certificate, ConsoleApp(upstream, auth, args.allowed_hosts))
    finally:
        await upstream.channel.close()
        await upstream.stereo_channel.close()


async def _serve_app(args, certificate: RenewingCertificate | None, app: ConsoleApp) -> int:
    host, port = args.address.rsplit(":", 1)
    server = ConsoleServer(server_config(app, host.strip("[]"), int(port),
                                         certificate=certificate))
    watch_parent(lambda: setattr(server, "should_exit", True))
    serving = asyncio.ensure_future(server.serve())
    while not server.started:
        if serving.done():
            return 1  # it could not bind; uvicorn logged why
        await asyncio.sleep(0.01)
    bound = server.servers[0].sockets[0].getsockname()
    address = f"{bound[0]}:{bound[1]}"
    upstream = args.token_address if args.tls_dir else args.decision_server
    log.info("serving the console on %s://%s/ for %s", "https" if certificate else "http",
             address, f"watching, the {app.watch.describe()}" if app.watch else
             f"the DecisionServer at {upstream}")
    say_ready(NAME, address)
    await serving
    return 0


def server_config(app, host: str, port: int, *, max_connections: int = MAX_CONNECTIONS,
                  head_timeout_s: float = HEAD_TIMEOUT_S,
                  certificate: RenewingCertificate | None = None) -> uvicorn.Config:
    """uvicorn's configuration of the console, with its limits on unauthenticated clients;
    HTTPS with `certificate`."""
    protocol = type("HeadTimeoutH11", (HeadTimeoutH11,), {"head_timeout_s": head_timeout_s})
    tls = {} if certificate is None else {
        "ssl_context_factory": lambda _config, _default: certificate.context}
    return uvicorn.Config(app, host=host, port=port, log_level="warning", access_log=False,
                          lifespan="on", http=protocol, ws_max_size=1 << 16,
                          limit_concurrency=max_connections, timeout_keep_alive=KEEP_ALIVE_S,
                          h11_max_incomplete_event_size=MAX_HEAD_BYTES,
                          timeout_graceful_shutdown=2, **tls)


class ConsoleServer(uvicorn.Server):
    """uvicorn's server, whose TLS handshakes must end within `handshake_timeout_s` of the
    connection: uvicorn gives asyncio no handshake timeout, so its default (60 s) would apply,
    and a connection is counted against the connection limit, and its head timed, only once
    its handshake is done."""

    def __init__(self, config: uvicorn.Config, handshake_timeout_s: float = HANDSHAKE_TIMEOUT_S):
        super().__init__(config)
        self.handshake_timeout_s = handshake_timeout_s

    async def startup(self, sockets=None) -> None:
        if not self.config.is_ssl:
            return await super().startup(sockets)
        # uvicorn creates its listeners with loop.create_server, here while startup runs: they
        # get the timeout through it (an attribute of this loop that shadows the method, and
        # goes after).
        loop = asyncio.get_running_loop()
        loop.create_server = functools.partial(loop.create_server,
                                               ssl_handshake_timeout=self.handshake_timeout_s)
        try:
            await super().startup(sockets)
        finally:
            del loop.create_server


class HeadTimeoutH11(TransportBoundProtocol):
    """uvicorn's HTTP/1.1 protocol, which also closes a connection whose request head has not
    come whole within `head_timeout_s` of the connection's opening or of its last response.
    uvicorn has no such timeout: its keep-alive timer starts only after a response and stops at
    the next byte, so a client that connects and sends nothing, or a byte a second, holds its
    connection (and a slot of limit_concurrency) for ever."""

    head_timeout_s = HEAD_TIMEOUT_S

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self._head_timer: asyncio.TimerHandle | None = None

    def connection_made(self, transport) -> None:
        super().connection_made(transport)
        self._await_head()

    def handle_events(self) -> None:
        super().handle_events()
        if self._in_request():
            self._stop_head_timer()

    def on_response_complete(self) -> None:
        super().on_response_complete()
        if not self._in_request():
            self._await_head()

    def handle_websocket_upgrade(self, event) -> None:
        self._stop_head_timer()  # the connection is the WebSocket protocol's from now on
        super().handle_websocket_upgrade(event)

    def connection_lost(self, exc) -> None:
        self._stop_head_timer()
        super().connection_lost(exc)

    def _in_request(self) -> bool:
        return self.cycle is not None and not self.cycle.response_complete

    def _await_head(self) -> None:
        self._stop_head_timer()
        if not self.transport.is_closing():
            self._head_timer = self.loop.call_later(self.head_timeout_s, self._head_timed_out)

    def _stop_head_timer(self) -> None:
        if self._head_timer is not None:
            self._head_timer.cancel()
            self._head_timer = None

    def _head_timed_out(self) -> None:
        self._head_timer = None
        if not self._in_request() and self.transport.get_protocol() is self:
            self.transport.close()


if __name__ == "__main__":
    raise SystemExit(main())
