"""A minimal client of the Foxglove WebSocket protocol (foxglove.sdk.v1), as Foxglove or
Lichtblick speak it: it reads the server's info and advertised channels, subscribes by topic,
and decodes the binary message frames (opcode 1, subscription id u32, log time u64, payload;
little-endian) with each channel's protobuf class.

It drives websockets' sans-I/O protocol from the caller's thread alone. The library's sync
client reads on a thread of its own while the caller writes, and on Python < 3.13 two threads
on one TLS socket race: a TLS 1.3 session ticket read during the handshake's write failed CI
with "[SSL] internal error"."""

from __future__ import annotations

import json
import socket
import struct
import time
from collections import defaultdict

from websockets.client import ClientProtocol
from websockets.frames import Frame, Opcode
from websockets.protocol import State
from websockets.uri import parse_uri

SUBPROTOCOL = "foxglove.sdk.v1"
MESSAGE_DATA = 0x01
_HEADER = struct.Struct("<BIQ")
_OPEN_TIMEOUT_S = 10.0


class FoxgloveClient:
    def __init__(self, url: str, ssl=None, origin: str | None = None):
        """Connects and shakes hands; InvalidHandshake if the server answers no upgrade.
        `origin`: the Origin header a browser's page would send (None: none, as a program)."""
        uri = parse_uri(url)
        self._protocol = ClientProtocol(uri, origin=origin, subprotocols=[SUBPROTOCOL],
                                        max_size=None)
        self._socket = socket.create_connection((uri.host, uri.port), timeout=_OPEN_TIMEOUT_S)
        self._inbox: list = []  # frames received and not yet read
        try:
            if uri.secure:
                self._socket = ssl.wrap_socket(self._socket, server_hostname=uri.host)
            self._protocol.send_request(self._protocol.connect())
            self._flush()
            deadline = time.monotonic() + _OPEN_TIMEOUT_S
            while self._protocol.state is State.CONNECTING:
                self._receive(deadline - time.monotonic())
            if self._protocol.handshake_exc is not None:
                raise self._protocol.handshake_exc
        except BaseException:
            self._socket.close()
            raise
        self.info: dict = {}
        self.channels: dict[str, dict] = {}  # topic -> the advertised channel
        self._topics: dict[int, str] = {}  # subscription id -> topic
        self.received: dict[str, list[tuple[int, bytes]]] = defaultdict(list)  # (log time, data)

    def wait_advertised(self, topics, timeout_s: float = 10.0) -> None:
        deadline = time.monotonic() + timeout_s
        while not set(topics) <= set(self.channels):
            self._read(deadline - time.monotonic())

    def subscribe(self, topics) -> None:
        subscriptions = []
        for topic in topics:
            subscription = len(self._topics) + 1
            self._topics[subscription] = topic
            subscriptions.append({"id": subscription, "channelId": self.channels[topic]["id"]})
        self._send_text({"op": "subscribe", "subscriptions": subscriptions})

    def unsubscribe_all(self) -> None:
        self._send_text({"op": "unsubscribe", "subscriptionIds": list(self._topics)})
        self._topics.clear()

    def collect(self, until, timeout_s: float) -> None:
        """Read until `until(self.received)` holds; TimeoutError after `timeout_s`."""
        deadline = time.monotonic() + timeout_s
        while not until(self.received):
            self._read(deadline - time.monotonic())

    def _read(self, timeout_s: float) -> None:
        deadline = time.monotonic() + timeout_s
        try:
            while not self._inbox:
                self._receive(deadline - time.monotonic())
        except TimeoutError:
            counts = {topic: len(got) for topic, got in self.received.items()}
            raise TimeoutError(f"received so far: {counts}") from None
        frame = self._inbox.pop(0)
        if isinstance(frame, str):
            message = json.loads(frame)
            if message["op"] == "serverInfo":
                self.info = message
            elif message["op"] == "advertise":
                self.channels.update({c["topic"]: c for c in message["channels"]})
            return
        opcode, subscription, log_time = _HEADER.unpack_from(frame)
        if opcode == MESSAGE_DATA and subscription in self._topics:
            self.received[self._topics[subscription]].append(
                (log_time, bytes(frame[_HEADER.size:])))

    def close(self) -> None:
        try:
            if self._protocol.state is State.OPEN:
                self._protocol.send_close()
                self._flush()
        except OSError:
            pass  # the server is gone already
        finally:
            self._socket.close()

    def _send_text(self, message: dict) -> None:
        self._protocol.send_text(json.dumps(message).encode())
        self._flush()

    def _flush(self) -> None:
        for data in self._protocol.data_to_send():
            if data:
                self._socket.sendall(data)

    def _receive(self, timeout_s: float) -> None:
        """One read from the socket into the protocol; data frames go to the inbox."""
        if timeout_s <= 0:
            raise TimeoutError
        self._socket.settimeout(timeout_s)
        data = self._socket.recv(65536)  # TimeoutError when nothing comes in time
        if data:
            self._protocol.receive_data(data)
        else:
            self._protocol.receive_eof()
        self._flush()  # pongs and close replies
        for event in self._protocol.events_received():  # the handshake's Response, then frames
            if not isinstance(event, Frame):
                continue
            if event.opcode is Opcode.TEXT:
                self._inbox.append(event.data.decode())
            elif event.opcode is Opcode.BINARY:
                self._inbox.append(event.data)
        if not data or self._protocol.state is State.CLOSED:
            if self._protocol.handshake_exc is not None:
                raise self._protocol.handshake_exc
            if not self._inbox:
                closed = self._protocol
                raise ConnectionError(f"the live view closed the connection "
                                      f"({closed.close_code}: {closed.close_reason})")

    def __enter__(self) -> FoxgloveClient:
        return self

    def __exit__(self, *exc) -> None:
        self.close()
