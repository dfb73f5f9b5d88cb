"""The console's ASGI application: the page and its assets, the Connect bridge, the
Teleoperate and receipts WebSockets, and /healthz for the launcher."""

from __future__ import annotations

import asyncio
import html
import ipaddress
import json
from collections.abc import Iterable
from pathlib import Path
from urllib.parse import urlsplit

from uvicorn.protocols.http.h11_impl import H11Protocol

from services.web_console import receipts, sockets, teleoperate
from services.web_console.bridge import BODY_MAX_BYTES, ConnectBridge, Upstream
from services.web_console.watch import SOCKET_REFUSALS, RouterWatch, watch_endpoints

STATIC_DIR = Path(__file__).resolve().parent / "static"
HEALTH_PATH = "/healthz"
CONTRACT_PREFIX = "/telerobot.v1."
# Teleoperate sockets open at once (uvicorn's connection limit does not count upgraded
# connections): one operator needs one; more get 1013, "try again later".
MAX_SOCKETS = 16
CLOSE_TRY_AGAIN_LATER = 1013
# A Connect request's body comes whole within this, or gets 408 (a client that sends its
# headers and then a byte now and then holds no connection for long).
BODY_TIMEOUT_S = 10.0
_TYPES = {".html": "text/html; charset=utf-8", ".js": "text/javascript; charset=utf-8",
          ".css": "text/css; charset=utf-8", ".map": "application/json", ".png": "image/png",
          ".svg": "image/svg+xml"}
# The page may load only its own assets and talk only to its own origin.
_SECURITY_HEADERS = [
    (b"content-security-policy",
     b"default-src 'self'; img-src 'self' blob: data:; connect-src 'self' ws: wss:; "
     b"style-src 'self'; script-src 'self'; frame-ancestors 'none'"),
    (b"x-content-type-options", b"nosniff"),
    (b"cache-control", b"no-cache"),
]

# The WebSockets: Teleoperate, and the video's receipts (receipts.py says why not Connect).
_SOCKETS = {teleoperate.PATH: teleoperate.serve, receipts.PATH: receipts.serve}


class TransportBoundProtocol(H11Protocol):
    """uvicorn's HTTP/1.1 protocol, holding nothing of a response beyond what the socket took.

    A server stream's messages go to the browser as the bridge reads them (bridge.py reads one
    message from the DecisionServer, sends it, then reads the next), and a send waits while the
    connection's write buffer is paused. asyncio lets that buffer hold 64 KiB before it pauses
    (seconds of low-bitrate video, minutes of arm states) for a browser or link that reads
    slowly; here it pauses as soon as the kernel's socket buffer is full, so the next message
    is read from the DecisionServer only once the client's transport has taken the last one.
    Over HTTPS the connection keeps asyncio's buffers: its TLS transport pauses at or above its
    mark (a TCP one above it), so a mark of 0 pauses every response for good, and one of 1
    stalled some WebSocket upgrades (tests/web_console/test_https.py).
    """

    def connection_made(self, transport) -> None:
        super().connection_made(transport)
        tls = transport.get_extra_info("sslcontext") is not None
        if not tls:
            transport.set_write_buffer_limits(high=0)


def _assets() -> dict[str, Path]:
    """URL path -> file: every file in static/ (only these are ever served), / the page."""
    files = {f"/{p.name}": p for p in STATIC_DIR.iterdir() if p.is_file()}
    if "/index.html" in files:
        files["/"] = files["/index.html"]
    return files


def same_origin(scope) -> bool:
    """Whether a WebSocket handshake comes from a page of this console (browsers always send
    Origin; a page elsewhere must not drive the arm through a user's loopback console)."""
    headers = dict(scope.get("headers") or ())
    origin, host = headers.get(b"origin"), headers.get(b"host")
    if origin is None or host is None:
        return False
    return urlsplit(origin.decode("latin-1")).netloc == host.decode("latin-1")


def foreign_origin(scope) -> bool:
    """Whether a request carries the Origin of another site (a browser sends Origin with every
    POST; a program such as buf curl sends none, and is not a page)."""
    headers = dict(scope.get("headers") or ())
    return b"origin" in headers and not same_origin(scope)


class HostCheck:
    """Which names a request's Host header may give: an IP address, `localhost`, or a name the
    operator allowed (--allowed-host). A page on a name of its own that DNS re-binds to this
    host (evil.example -> 127.0.0.1) reaches the console with its own name in Host, and is
    refused, with its Origin matching that Host or not."""

    def __init__(self, allowed: Iterable[str] = ()):
        self.allowed = frozenset({"localhost", *(name.lower() for name in allowed)})

    def refuses(self, scope) -> str | None:
        """None for an allowed Host; else the name it gave ("" when it gave none)."""
        host = dict(scope.get("headers") or ()).get(b"host", b"").decode("latin-1")
        name = urlsplit(f"//{host}").hostname or ""
        if name in self.allowed:
            return None
        try:
            ipaddress.ip_address(name)
            return None  # an address is not a name anyone can re-bind
        except ValueError:
            return name


class ConsoleApp:
    """Routes: /telerobot.v1.* (Connect), /ws/teleoperate and /ws/receipts (WebSockets),
    /healthz, assets. `upstream` is the DecisionServer's (Upstream), or a RouterWatch for a
    watch-only console."""

    def __init__(self, upstream: Upstream | RouterWatch, auth: str,
                 allowed_hosts: Iterable[str] = (),
                 max_body_bytes: int = BODY_MAX_BYTES, max_sockets: int = MAX_SOCKETS,
                 body_timeout_s: float = BODY_TIMEOUT_S):
        self.upstream = upstream
        self.max_body_bytes = max_body_bytes
        self.body_timeout_s = body_timeout_s
        self.max_sockets = max_sockets
        self.open_sockets = 0
        self.hosts = HostCheck(allowed_hosts)
        self.auth = auth  # "token" or "none": the page asks for a token only with "token"
        # A RouterWatch: the page watches through a router, and every command is refused.
        self.watch = upstream if isinstance(upstream, RouterWatch) else None
        self.bridge = (ConnectBridge(upstream, watch_endpoints) if self.watch
                       else ConnectBridge(upstream))
        self.assets = _assets()

    async def __call__(self, scope, receive, send) -> None:
        if scope["type"] == "lifespan":
            return await self._lifespan(receive, send)
        path = scope["path"]
        refused_host = self.hosts.refuses(scope)
        if scope["type"] == "websocket":
            serve = _SOCKETS.get(path)
            if serve is None or not same_origin(scope) or refused_host is not None:
                await receive()
                await send({"type": "websocket.close", "code": sockets.CLOSE_POLICY})
                return
            if self.open_sockets >= self.max_sockets:
                await receive()
                await send({"type": "websocket.close", "code": CLOSE_TRY_AGAIN_LATER})
                return
            if self.watch is not None:
                return await sockets.refuse(receive, send, *SOCKET_REFUSALS[path])
            self.open_sockets += 1
            try:
                return await serve(scope, receive, send, self.upstream)
            finally:
                self.open_sockets -= 1
        if refused_host is not None:
            return await _respond(send, 403, (
                f"this console does not answer to the name {refused_host!r}: a page served "
                "elsewhere may not reach it through a re-bound name; to use that name, start "
                "the console with --allowed-host\n").encode())
        if path.startswith(CONTRACT_PREFIX):
            if foreign_origin(scope):
                return await _respond(send, 403, b"a page of another site may not call the "
                                      b"station through this console\n")
            body = await _bounded_body(scope, receive, send, self.max_body_bytes,
                                       self.body_timeout_s)
            if body is None:
                return  # refused: too large or too slow
            return await _until_client_leaves(self.bridge, scope, body, receive, send)
        if scope["method"] not in ("GET", "HEAD"):
            return await _respond(send, 405, b"method not allowed\n",
                                  extra=[(b"allow", b"GET, HEAD")])
        if path == HEALTH_PATH:
            return await _respond(send, 200, b"SERVING\n")
        asset = self.assets.get(path)
        if asset is None:
            return await _respond(send, 404, b"not found\n")
        body = asset.read_bytes()
        if asset.name == "index.html":
            watching = self.watch.describe() if self.watch else ""
            body = (body.replace(b"{{AUTH}}", self.auth.encode())
                    .replace(b"{{WATCH}}", html.escape(watching).encode()))
        kind = _TYPES.get(asset.suffix, "application/octet-stream")
        await _respond(send, 200, b"" if scope["method"] == "HEAD" else body, kind,
                       length=len(body))

    async def _lifespan(self, receive, send) -> None:
        while True:
            message = await receive()
            if message["type"] == "lifespan.startup":
                if self.watch is not None:
                    self.watch.start()
                await send({"type": "lifespan.startup.complete"})
            elif message["type"] == "lifespan.shutdown":
                if self.watch is not None:
                    self.watch.close()
                await send({"type": "lifespan.shutdown.complete"})
                return


async def _bounded_body(scope, receive, send, limit: int, timeout_s: float):
    """Read a request's body, up to `limit` bytes within `timeout_s`, before the bridge sees
    it: a larger one (by its Content-Length, before a byte of it is read, or as it comes) is
    refused with 413 and a Connect resource_exhausted error, a slower one with 408 and
    deadline_exceeded, and the connection closed, so that no more of it is read. Returns a
    `receive` that gives the bridge the body read, then the client's own messages (a
    disconnect); None when refused."""
    length = dict(scope.get("headers") or ()).get(b"content-length", b"0")
    too_large = not length.isdigit() or int(length) > limit
    chunks: list[bytes] = []
    size = 0
    try:
        async with asyncio.timeout(timeout_s):
            while not too_large:
                message = await receive()
                if message["type"] != "http.request":
                    return _replay([message], receive)  # the client left: the bridge hears it
                chunks.append(message.get("body", b""))
                size += len(chunks[-1])
                too_large = size > limit
                if not message.get("more_body", False):
                    break
    except TimeoutError:
        await _refuse(send, 408, "deadline_exceeded",
                      f"the request's body did not come within {timeout_s:g} s")
        return None
    if too_large:
        await _refuse(send, 413, "resource_exhausted",
                      f"the request's body is larger than {limit} bytes")
        return None
    return _replay([{"type": "http.request", "body": b"".join(chunks), "more_body": False}],
                   receive)


async def _until_client_leaves(app, scope, body, receive, send) -> None:
    """Run `app` on a request whose body was read (`body` gives it again), and cancel it when
    the client leaves before its response ended. uvicorn hands a send to a gone client nothing
    and says nothing, and connect-python looks for the client only between a stream's messages:
    a quiet stream (events, or video paced to a reader that stopped sending receipts) would keep
    its upstream call, and the camera rendering for it, until the station stops."""
    ended = left = False

    async def tracked_send(message) -> None:
        nonlocal ended
        if message["type"] == "http.response.body" and not message.get("more_body", False):
            ended = True
        await send(message)

    call = asyncio.ensure_future(app(scope, body, tracked_send))

    async def watch() -> None:
        nonlocal left
        while (await receive())["type"] != "http.disconnect":
            pass
        if not ended:
            left = True
            call.cancel()

    watcher = asyncio.ensure_future(watch())
    try:
        await call
    except BaseException:
        # What the cancel made (connect-python raises it as a CANCELED ConnectError) has no one
        # to go to; anything else (the server stopping, a failure) goes on.
        if not left or not call.done():
            raise
    finally:
        watcher.cancel()


def _replay(messages: list, receive):
    """A `receive` that gives `messages`, then what `receive` gives."""
    pending = list(messages)

    async def replayed():
        return pending.pop(0) if pending else await receive()

    return replayed


async def _refuse(send, status: int, code: str, message: str) -> None:
    """A Connect error (its JSON body) on a connection that is closed after it: the rest of
    the request is never read."""
    await _respond(send, status, json.dumps({"code": code, "message": message}).encode(),
                   "application/json", extra=[(b"connection", b"close")])


async def _respond(send, status: int, body: bytes, kind: str = "text/plain; charset=utf-8",
                   extra=(), length: int | None = None) -> None:
    headers = [(b"content-type", kind.encode()),
               (b"content-length", str(len(body) if length is None else length).encode()),
               *_SECURITY_HEADERS, *extra]
    await send({"type": "http.response.start", "status": status, "headers": headers})
    await send({"type": "http.response.body", "body": body})
