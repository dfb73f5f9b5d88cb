"""A minimal client of the Foxglove WebSocket protocol (foxglove.sdk.v1), as Foxglove or
Lichtblick speak it: it reads the server's info and advertised channels, subscribes by topic,
and decodes the binary message frames (opcode 1, subscription id u32, log time u64, payload;
little-endian) with each channel's protobuf class."""

from __future__ import annotations

import contextlib
import json
import struct
import time
from collections import defaultdict

from websockets.sync.client import connect

SUBPROTOCOL = "foxglove.sdk.v1"
MESSAGE_DATA = 0x01
_HEADER = struct.Struct("<BIQ")


class FoxgloveClient:
    def __init__(self, url: str, ssl=None):
        self._stack = contextlib.ExitStack()
        self.ws = self._stack.enter_context(connect(url, subprotocols=[SUBPROTOCOL], ssl=ssl,
                                                    open_timeout=10, max_size=None))
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
        self.ws.send(json.dumps({"op": "subscribe", "subscriptions": subscriptions}))

    def unsubscribe_all(self) -> None:
        self.ws.send(json.dumps({"op": "unsubscribe", "subscriptionIds": list(self._topics)}))
        self._topics.clear()

    def collect(self, until, timeout_s: float) -> None:
        """Read until `until(self.received)` holds; TimeoutError after `timeout_s`."""
        deadline = time.monotonic() + timeout_s
        while not until(self.received):
            self._read(deadline - time.monotonic())

    def _read(self, timeout_s: float) -> None:
        try:
            frame = self.ws.recv(timeout=max(timeout_s, 0.0))
        except TimeoutError:
            counts = {topic: len(got) for topic, got in self.received.items()}
            raise TimeoutError(f"received so far: {counts}") from None
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
        self._stack.close()

    def __enter__(self) -> FoxgloveClient:
        return self

    def __exit__(self, *exc) -> None:
        self.close()
