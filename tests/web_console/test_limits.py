"""What one client may take of the console before anyone knows who it is: the console served by
real uvicorn on a thread of this process, its configuration the one `python -m
services.web_console` runs, its upstream one whose every call is refused (a reply naming that
refusal shows a request reached the station's side).

- A gzip bomb (a small body that inflates to 128 MiB) is refused with resource_exhausted,
  having inflated no more than the limit: measured by tracemalloc's peak, in this process.
- A body larger than the limit is refused by its Content-Length before it is read, or as it
  comes; one that does not come is refused after the body timeout.
- A connection that sends no request head, or half of one, is closed after the head timeout.
- Requests beyond the connection limit get 503; Teleoperate sockets beyond theirs get 1013."""

from __future__ import annotations

import asyncio
import concurrent.futures
import contextlib
import functools
import gzip
import http.client
import json
import socket
import struct
import threading
import tracemalloc

import pytest
import uvicorn

from services.web_console import teleoperate
from services.web_console.__main__ import MAX_CONNECTIONS, server_config
from services.web_console.app import CLOSE_TRY_AGAIN_LATER, ConsoleApp
from services.web_console.bridge import BODY_MAX_BYTES, READ_MAX_BYTES, Upstream
from tests.conftest import wait_for
from tests.web_console.test_rebinding import REACHED, NoChannel

UNARY = "/telerobot.v1.DecisionServer/GetControlState"
STREAM = "/telerobot.v1.ProxyRobot/StreamState"
BOMB_BYTES = 128 << 20  # what the bomb inflates to
_REPLY_TIMEOUT_S = 10.0


@functools.cache
def gzip_bomb(size: int = BOMB_BYTES) -> bytes:
    """`size` zero bytes as gzip, about a thousandth of that: members of 16 MiB each, one after
    another (as gzip allows), so that making it takes no gigabyte of work."""
    member = gzip.compress(bytes(16 << 20), compresslevel=9)
    return member * (size // (16 << 20))


def console(**limits) -> ConsoleApp:
    return ConsoleApp(Upstream(NoChannel(), NoChannel(), refusal=REACHED), "none", **limits)


@contextlib.contextmanager
def serving(app: ConsoleApp, **limits):
    """The app served by uvicorn as the console's __main__ configures it; yields the server
    (uvicorn.Server) and its port."""
    server = uvicorn.Server(server_config(app, "127.0.0.1", 0, **limits))
    thread = threading.Thread(target=server.run, name="console", daemon=True)
    thread.start()
    try:
        wait_for(lambda: server.started or not thread.is_alive(), 10, "the console serving")
        assert server.started, "the console did not start"
        yield server, server.servers[0].sockets[0].getsockname()[1]
    finally:
        server.should_exit = True
        thread.join(10)


def post(port: int, path: str, body: bytes, headers: dict[str, str]) -> tuple[int, bytes]:
    connection = http.client.HTTPConnection("127.0.0.1", port, timeout=_REPLY_TIMEOUT_S)
    try:
        connection.request("POST", path, body, headers)
        reply = connection.getresponse()
        return reply.status, reply.read()
    finally:
        connection.close()


def envelope(flags: int, message: bytes) -> bytes:
    """One message of a Connect stream: flags (1: compressed), length, message."""
    return struct.pack(">BI", flags, len(message)) + message


def unary_request(body: bytes, encoding: str = "gzip") -> tuple[str, bytes, dict]:
    return UNARY, body, {"content-type": "application/json", "content-encoding": encoding}


def stream_request(body: bytes, encoding: str = "gzip") -> tuple[str, bytes, dict]:
    return STREAM, envelope(1, body), {"content-type": "application/connect+json",
                                       "connect-content-encoding": encoding}


def connect_code(body: bytes) -> str:
    """The Connect error code of a reply: a unary call's JSON error, or a stream's end
    message."""
    if body[:1] == b"{":
        return json.loads(body)["code"]
    flags, length = struct.unpack(">BI", body[:5])
    assert flags & 0x02, body[:80]  # the end-of-stream message
    return json.loads(body[5:5 + length])["error"]["code"]


@pytest.mark.parametrize("request_of", [unary_request, stream_request], ids=["unary", "stream"])
def test_a_gzip_bomb_is_refused_having_inflated_no_more_than_the_limit(request_of):
    bomb = gzip_bomb()
    assert len(bomb) < BODY_MAX_BYTES < BOMB_BYTES // 100  # small as it comes, huge inflated
    with serving(console()) as (_, port):
        # A small gzip body gets through to the station's side: gzip is still read.
        status, body = post(port, *request_of(gzip.compress(b"{}")))
        assert REACHED.encode() in body, (status, body)

        tracemalloc.start()
        try:
            status, body = post(port, *request_of(bomb))
            _, peak = tracemalloc.get_traced_memory()
        finally:
            tracemalloc.stop()
    assert connect_code(body) == "resource_exhausted", (status, body)
    assert REACHED.encode() not in body
    # The body, the message inflated up to the limit and a copy or two: nowhere near 128 MiB.
    assert peak < 8 * READ_MAX_BYTES, f"the console allocated {peak / 2**20:.0f} MiB"


def read_reply(sock: socket.socket) -> bytes:
    """Everything the console sends until it closes the connection (or the test's timeout)."""
    sock.settimeout(_REPLY_TIMEOUT_S)
    data = b""
    while chunk := sock.recv(65536):
        data += chunk
    return data


def test_a_body_larger_than_the_limit_is_refused_by_its_length_before_it_is_read():
    with serving(console()) as (_, port), socket.create_connection(("127.0.0.1", port)) as sock:
        sock.sendall(f"POST {UNARY} HTTP/1.1\r\nHost: 127.0.0.1\r\n"
                     f"Content-Type: application/json\r\nContent-Length: {1 << 30}\r\n\r\n"
                     .encode())
        reply = read_reply(sock)  # not a byte of the gigabyte sent: answered, and closed
    assert reply.startswith(b"HTTP/1.1 413 "), reply[:200]
    assert b'"resource_exhausted"' in reply


def test_a_chunked_body_is_refused_once_past_the_limit_without_its_end():
    chunk = b"x" * 65536
    with serving(console()) as (_, port), socket.create_connection(("127.0.0.1", port)) as sock:
        sock.sendall(f"POST {UNARY} HTTP/1.1\r\nHost: 127.0.0.1\r\n"
                     "Content-Type: application/json\r\nTransfer-Encoding: chunked\r\n\r\n"
                     .encode())
        sent = 0
        while sent <= BODY_MAX_BYTES:  # just past the limit, and no last chunk
            piece = chunk[:BODY_MAX_BYTES + 1 - sent]
            sock.sendall(b"%x\r\n%s\r\n" % (len(piece), piece))
            sent += len(piece)
        reply = read_reply(sock)
    assert reply.startswith(b"HTTP/1.1 413 "), reply[:200]


def test_a_body_that_does_not_come_is_refused_after_the_body_timeout():
    with serving(console(body_timeout_s=0.2)) as (_, port), \
            socket.create_connection(("127.0.0.1", port)) as sock:
        sock.sendall(f"POST {UNARY} HTTP/1.1\r\nHost: 127.0.0.1\r\n"
                     "Content-Type: application/json\r\nContent-Length: 100\r\n\r\n{".encode())
        reply = read_reply(sock)
    assert reply.startswith(b"HTTP/1.1 408 "), reply[:200]
    assert b'"deadline_exceeded"' in reply


@pytest.mark.parametrize("sent", [b"", b"GET /healthz HTTP/1.1\r\nHost: 127.0.0.1\r\n"],
                         ids=["nothing", "half a head"])
def test_a_connection_without_a_whole_request_head_is_closed_after_the_head_timeout(sent):
    with serving(console(), head_timeout_s=0.2) as (_, port), \
            socket.create_connection(("127.0.0.1", port)) as sock:
        sock.sendall(sent)
        assert read_reply(sock) == b""  # closed, with nothing to say


def test_a_kept_alive_connection_that_starts_a_head_and_stops_is_closed():
    """uvicorn's keep-alive timer stops at the next request's first byte; the head timeout
    starts again after each response."""
    with serving(console(), head_timeout_s=0.2) as (_, port), \
            socket.create_connection(("127.0.0.1", port)) as sock:
        sock.settimeout(_REPLY_TIMEOUT_S)
        sock.sendall(b"GET /healthz HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n")
        reply = b""
        while not reply.endswith(b"SERVING\n"):
            reply += sock.recv(65536)
        assert reply.startswith(b"HTTP/1.1 200 "), reply
        sock.sendall(b"GET /heal")  # after the response: the keep-alive timer stops here
        assert read_reply(sock) == b""


def health(port: int) -> int:
    connection = http.client.HTTPConnection("127.0.0.1", port, timeout=_REPLY_TIMEOUT_S)
    try:
        connection.request("GET", "/healthz")
        return connection.getresponse().status
    finally:
        connection.close()


def test_requests_beyond_the_connection_limit_get_503():
    with serving(console()) as (server, port):
        idle = [socket.create_connection(("127.0.0.1", port)) for _ in range(MAX_CONNECTIONS)]
        try:
            wait_for(lambda: len(server.server_state.connections) >= MAX_CONNECTIONS, 10,
                     "the console holding every idle connection")
            assert health(port) == 503
        finally:
            for sock in idle:
                sock.close()
        wait_for(lambda: not server.server_state.connections, 10, "the idle connections gone")
        assert health(port) == 200


def test_a_teleoperate_socket_beyond_the_limit_is_closed_try_again_later():
    app = console(max_sockets=2)
    app.open_sockets = 2  # two sessions open
    headers = [(b"host", b"127.0.0.1:50080"), (b"origin", b"http://127.0.0.1:50080")]
    scope = {"type": "websocket", "path": teleoperate.PATH, "headers": headers,
             "subprotocols": [teleoperate.SUBPROTOCOL]}
    sent = []

    async def receive():
        return {"type": "websocket.connect"}

    async def send(message):
        sent.append(message)

    with concurrent.futures.ThreadPoolExecutor(1) as thread:
        thread.submit(asyncio.run, app(scope, receive, send)).result()
    assert sent == [{"type": "websocket.close", "code": CLOSE_TRY_AGAIN_LATER}]
