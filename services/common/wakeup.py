"""Wakeup: what a response stream yields instead of blocking while it has nothing to send.

A stream whose producer wakes it through an eventfd (a ForceSensor subscription, written by
the sampling thread) yields `Wakeup(fd, timeout_s)`: "resume me once the fd is written, or after
timeout_s". Whoever drives the stream waits for it its own way and resets the fd:
- on grpcio's sync server, the stream's own thread blocks in `wait()`
  (services/runtime/rpc.py);
- on a grpc.aio server, the stream's coroutine awaits it on the event loop, which watches the
  fd for the stream's whole life, and pulls the stream's next message there too: a stream that
  waits only through Wakeups never blocks, so it costs no thread hand-over per message
  (services/runtime/aio_server.py).
"""

from __future__ import annotations

import os
import select
from dataclasses import dataclass


@dataclass(frozen=True, slots=True)
class Wakeup:
    """Resume the stream once the eventfd `fd` is written, or after `timeout_s`. There is
    always a timeout: a thread blocked here on the sync server sees that its client left only
    once it wakes."""

    fd: int
    timeout_s: float

    def wait(self) -> None:
        """Block this thread until the fd is written or the timeout passes, then reset it."""
        readable, _, _ = select.select([self.fd], [], [], self.timeout_s)
        if readable:
            reset_eventfd(self.fd)


def reset_eventfd(fd: int) -> None:
    """Back to zero (a non-blocking eventfd: nothing to do when nobody wrote it)."""
    try:
        os.eventfd_read(fd)
    except BlockingIOError:
        pass
