"""The gateway holds no more of a server stream than its client's transport: a browser that
stops reading leaves the messages in the sockets' buffers, not in the console (services/
web_console/app.py, TransportBoundProtocol), and the console reads the DecisionServer's stream
only as the browser's side takes them. No processes: the console's ASGI app on uvicorn in this
process, a fake upstream stream, and a raw HTTP/1.1 client."""

from __future__ import annotations

import asyncio
import fcntl
import logging
import socket
import struct
import termios
import threading
import time

import pytest
import uvicorn

from services.web_console.app import ConsoleApp, TransportBoundProtocol
from services.web_console.bridge import Upstream
from telerobot.v1 import stereo_camera_pb2 as pb
from tests.conftest import wait_for

IMAGE_BYTES = 8 * 1024
MESSAGE = pb.StreamPairsResponse(pair=pb.StereoPair(left_image=b"x" * IMAGE_BYTES))
WIRE_BYTES = 5 + MESSAGE.ByteSize()  # a Connect envelope around each message
CLIENT_RCVBUF = 16 * 1024


class _Stream:
    """An upstream server stream that always has a message (or, `quiet`, never one: events,
    or video paced to a reader that sends no receipts): it counts what the gateway takes."""

    def __init__(self, quiet: bool = False):
        self.quiet = quiet
        self.taken = 0
        self.cancelled = False

    def __aiter__(self):
        return self

    async def __anext__(self):
        if self.cancelled:
            raise StopAsyncIteration
        if self.quiet:
            await asyncio.Event().wait()  # until the gateway's task is cancelled
        self.taken += 1
        await asyncio.sleep(0)
        return MESSAGE

    def cancel(self):
        self.cancelled = True


class _Channel:
    """Enough of a grpc.aio.Channel for the bridge: every server stream is a _Stream."""

    def __init__(self):
        self.streams: list[_Stream] = []
        self.quiet = False  # the streams it opens

    def unary_unary(self, path, **_):
        async def call(request, **_):
            raise AssertionError(f"no unary call expected, got {path}")
        return call

    def unary_stream(self, path, **_):
        def call(request, **_):
            self.streams.append(_Stream(self.quiet))
            return self.streams[-1]
        return call


class _Recording(TransportBoundProtocol):
    transports: list = []

    def connection_made(self, transport) -> None:
        super().connection_made(transport)
        _Recording.transports.append(transport)


def _queued(sock, request: int) -> int:
    """Bytes in a socket's kernel queue: TIOCOUTQ unsent (or unacknowledged), FIONREAD unread."""
    return struct.unpack("i", fcntl.ioctl(sock.fileno(), request, b"\0\0\0\0"))[0]


@pytest.fixture
def console():
    """The console app on uvicorn (as __main__ runs it) on a thread: (address, channel)."""
    channel = _Channel()
    config = uvicorn.Config(ConsoleApp(Upstream(channel, channel), "none"), host="127.0.0.1",
                            port=0, http=_Recording, lifespan="on", log_level="warning")
    server = uvicorn.Server(config)
    loop = asyncio.new_event_loop()
    thread = threading.Thread(target=loop.run_until_complete, args=(server.serve(),),
                              daemon=True)
    thread.start()
    wait_for(lambda: server.started, timeout_s=10, what="uvicorn to start")
    host, port = server.servers[0].sockets[0].getsockname()[:2]
    channel.requests = server.server_state.tasks  # the requests being served
    yield f"{host}:{port}", channel
    server.should_exit = True
    thread.join(timeout=10)


def _open_stream(address: str) -> socket.socket:
    host, port = address.split(":")
    client = socket.socket()
    client.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, CLIENT_RCVBUF)  # a slow reader's
    client.connect((host, int(port)))
    body = pb.StreamPairsRequest(receipts=True).SerializeToString()
    envelope = struct.pack(">BI", 0, len(body)) + body
    client.sendall(b"POST /telerobot.v1.StereoCamera/StreamPairs HTTP/1.1\r\n"
                   b"Host: " + address.encode() + b"\r\n"
                   b"Content-Type: application/connect+proto\r\n"
                   b"Content-Length: " + str(len(envelope)).encode() + b"\r\n\r\n" + envelope)
    return client


def _steady(read) -> tuple:
    """`read()` once it has stopped changing for half a second."""
    last, since = read(), time.monotonic()
    while time.monotonic() - since < 0.5:
        time.sleep(0.05)
        now = read()
        if now != last:
            last, since = now, time.monotonic()
    return last


def test_a_client_that_stops_reading_leaves_the_backlog_in_the_sockets(console):
    address, channel = console
    client = _open_stream(address)
    try:
        first = client.recv(4096)  # the response's headers (and maybe a message): then nothing
        assert first.startswith(b"HTTP/1.1 200"), first[:200]
        wait_for(lambda: channel.streams, timeout_s=10, what="the upstream stream")
        stream = channel.streams[0]
        server_socket = _Recording.transports[-1].get_extra_info("socket")
        taken, in_kernel = _steady(lambda: (
            stream.taken,
            _queued(server_socket, termios.TIOCOUTQ) + _queued(client, termios.FIONREAD)))
        # Everything the gateway took from upstream is in the sockets (on loopback they take
        # megabytes) or read by the client, but for the message it holds for its next send
        # and what is left of the one before (asyncio's default would hold up to 64 KiB more).
        held = taken * WIRE_BYTES - in_kernel - len(first)
        print(f"taken {taken} messages of {WIRE_BYTES} bytes, {in_kernel} bytes in the "
              f"sockets, {held} bytes held by the gateway")
        assert held <= 2 * WIRE_BYTES, (taken, in_kernel, held)

        # Reading again, the stream moves on; the client leaving ends the upstream stream.
        client.settimeout(10)
        deadline = time.monotonic() + 30
        while stream.taken <= taken + 10:
            assert client.recv(1 << 20) and time.monotonic() < deadline, stream.taken
    finally:
        client.close()
    wait_for(lambda: stream.cancelled, timeout_s=10, what="the upstream stream cancelled")


def test_a_client_that_leaves_a_quiet_stream_ends_it_upstream(console, caplog):
    """A stream with nothing to send (connect-python looks for the client only between
    messages) still ends upstream when its client leaves, quietly: no camera renders for a
    closed tab, and the console's log has no error for it."""
    address, channel = console
    channel.quiet = True
    client = _open_stream(address)
    try:
        wait_for(lambda: channel.streams, timeout_s=10, what="the upstream stream")
    finally:
        client.close()
    wait_for(lambda: channel.streams[0].cancelled, timeout_s=10,
             what="the quiet upstream stream cancelled")
    wait_for(lambda: not channel.requests, timeout_s=10, what="the request's end")
    assert [r.getMessage() for r in caplog.records if r.levelno >= logging.ERROR] == []
