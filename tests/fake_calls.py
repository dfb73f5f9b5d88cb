"""FakeCall: the client side of a gRPC server stream, for code that follows streams (Feed)."""

from __future__ import annotations

import queue
import threading

import grpc


class FakeCall:
    """A server stream's client side: yields what the test puts in, ends with an RpcError the
    test raises, and is cancelled as grpc's is."""

    class Ended(grpc.RpcError):
        def __init__(self, code: grpc.StatusCode):
            self._code = code

        def code(self):
            return self._code

        def details(self):
            return self._code.name.lower()

    def __init__(self):
        self.items: queue.Queue = queue.Queue()
        self.cancelled = threading.Event()

    def __iter__(self):
        while True:
            item = self.items.get()
            if isinstance(item, grpc.StatusCode):
                raise FakeCall.Ended(item)
            yield item

    def cancel(self):
        self.cancelled.set()
        self.items.put(grpc.StatusCode.CANCELLED)
