"""The "custom protocol" baseline: a plain TCP socket, each message a 4-byte big-endian length
then the payload (struct framing), TCP_NODELAY on both ends.

A connection starts with one mode byte: ``C`` (commands: request frame, reply frame, ...) or
``F`` followed by a 4-byte decimation (the server then pushes one frame per wrench batch).
A reply frame starts with ``K`` (ok, payload follows) or ``E`` (error, UTF-8 message follows).
"""

from __future__ import annotations

import socket
import struct

LENGTH = struct.Struct("!I")
DECIMATION = struct.Struct("!i")
MODE_COMMANDS = b"C"
MODE_FORCE = b"F"
REPLY_OK = b"K"
REPLY_ERROR = b"E"
MAX_FRAME_BYTES = 1 << 20


def connect(address: str, timeout_s: float = 5.0) -> socket.socket:
    """A connected TCP socket to host:port with Nagle off."""
    host, port = address.rsplit(":", 1)
    sock = socket.create_connection((host, int(port)), timeout=timeout_s)
    sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
    return sock


def send_frame(sock: socket.socket, payload: bytes) -> None:
    sock.sendall(LENGTH.pack(len(payload)) + payload)


def recv_exact(sock: socket.socket, size: int) -> bytes:
    """Exactly `size` bytes; ConnectionError if the peer closed first."""
    chunks, left = [], size
    while left:
        chunk = sock.recv(left)
        if not chunk:
            raise ConnectionError("the peer closed the connection")
        chunks.append(chunk)
        left -= len(chunk)
    return b"".join(chunks)


def recv_frame(sock: socket.socket) -> bytes:
    (size,) = LENGTH.unpack(recv_exact(sock, LENGTH.size))
    if size > MAX_FRAME_BYTES:
        raise ConnectionError(f"a {size}-byte frame is past the {MAX_FRAME_BYTES}-byte limit")
    return recv_exact(sock, size)
