"""Whether a TCP port accepts connections: the health of a dependency that speaks no gRPC (the
station's Zenoh router), for the launcher's start-up check and the DecisionServer's
dependencies.

A connection is opened and closed at once; a Zenoh router takes that without a log line.
"""

from __future__ import annotations

import socket
import threading

from wire.tls import dialable

OK = "ok"
CONNECT_TIMEOUT_S = 1.0
WATCH_PERIOD_S = 0.5


def accepts(address: str, timeout_s: float = CONNECT_TIMEOUT_S) -> str:
    """"ok" if `address` (host:port) accepts a TCP connection within `timeout_s`, else why
    not ("UNAVAILABLE: ...")."""
    host, _, port = dialable(address).rpartition(":")
    try:
        with socket.create_connection((host.strip("[]"), int(port)), timeout=timeout_s):
            return OK
    except OSError as error:
        return f"UNAVAILABLE: {address} accepts no connection ({error.strerror or error})"


class PortWatch:
    """`accepts(address)`, asked every `period_s` on a thread of its own, so that reading the
    answer never waits on the network."""

    def __init__(self, address: str, period_s: float = WATCH_PERIOD_S):
        self.address = address
        self._period_s = period_s
        self._answer = "UNAVAILABLE: not asked yet"
        self._asked = threading.Event()
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, name=f"port-watch-{address}",
                                        daemon=True)

    def start(self, wait_s: float = CONNECT_TIMEOUT_S) -> PortWatch:
        """Start asking, and wait up to `wait_s` for the first answer."""
        self._thread.start()
        self._asked.wait(wait_s)
        return self

    def answer(self) -> str:
        return self._answer

    def _run(self) -> None:
        while True:
            self._answer = accepts(self.address)
            self._asked.set()
            if self._stop.wait(self._period_s):
                return

    def close(self) -> None:
        self._stop.set()
        self._thread.join(timeout=CONNECT_TIMEOUT_S + 1.0)
