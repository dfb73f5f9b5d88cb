"""A stream handler in three threads, so that reading, acting and answering never wait on each
other. Nothing here knows about gRPC.

- `Inbox`: the messages are read on a thread of their own and taken in batches. A handler that
  reads one message, acts, and reads the next falls behind for good once the messages come
  faster than it acts: each waits behind all the earlier ones. Taking everything that arrived
  since it last looked, it can act once on the whole backlog (the DecisionServer composes a
  backlog of increments into one move).
- `Producer`: the acting runs on a thread of its own and its answers are yielded, in order, in
  the handler's thread (the one a server streams from). Writing an answer to the network
  (gRPC's sync server waits for each write to complete) then never delays the next action.
"""

from __future__ import annotations

import queue
import threading
from collections import deque
from collections.abc import Callable, Iterator
from typing import Generic, TypeVar

from wire.errors import ResourceExhaustedError

T = TypeVar("T")
M = TypeVar("M")


class Inbox(Generic[T]):
    """Reads `messages` on a daemon thread, stamping each with `stamp(message)` as it arrives.

    `take()` returns what has arrived (at least one, waiting for it), or an empty list once the
    messages ended; if reading raised, `take()` raises that exception, in the taker's thread.
    """

    def __init__(self, messages: Iterator[M], stamp: Callable[[M], T], name: str = "inbox"):
        self._messages = messages
        self._stamp = stamp
        self._items: deque[T] = deque()
        self._ready = threading.Condition()
        self._ended = False
        self._error: BaseException | None = None
        self._thread = threading.Thread(target=self._read, name=name, daemon=True)
        self._thread.start()

    def _read(self) -> None:
        try:
            for message in self._messages:
                item = self._stamp(message)
                with self._ready:
                    self._items.append(item)
                    self._ready.notify()
        except BaseException as error:  # noqa: BLE001 - handed to the taker, which raises it
            self._error = error
        finally:
            with self._ready:
                self._ended = True
                self._ready.notify()

    def put(self, item: T) -> None:
        """Hand the taker `item` as if it had arrived (a wake-up from another thread); nothing
        once the messages ended."""
        with self._ready:
            if not self._ended:
                self._items.append(item)
                self._ready.notify()

    def close(self) -> None:
        """No more batches: take() returns [] once what arrived was taken (the reader thread
        ends with the stream)."""
        with self._ready:
            self._ended = True
            self._items.clear()
            self._ready.notify_all()

    def take(self, limit: int | None = None) -> list[T]:
        """Everything that has arrived (at most `limit`), oldest first, waiting for at least
        one; [] once the messages ended and all were taken."""
        with self._ready:
            while not self._items and not self._ended:
                self._ready.wait()
            if not self._items and self._error is not None:
                raise self._error
            count = len(self._items) if limit is None else min(limit, len(self._items))
            return [self._items.popleft() for _ in range(count)]


def queued_now(pending: queue.SimpleQueue) -> list:
    """Everything in `pending` now, oldest first, without waiting: a writer thread that
    wakes once for many items (the audit log, the MCAP recorder) takes them this way."""
    items = []
    while True:
        try:
            items.append(pending.get_nowait())
        except queue.Empty:
            return items


_END = object()


class Producer(Generic[T]):
    """Runs `produce(emit)` on a daemon thread; iterating yields what it emits, in order, in the
    iterating thread, then raises what `produce` raised, if anything. Emitting never waits for
    the reader, but a reader that falls `max_pending` answers behind (a client that never
    reads: each write waits for it) ends the producing: emit raises ResourceExhaustedError,
    which the reader gets after what was pending. Stop its input (Inbox.close()) to end it."""

    def __init__(self, produce: Callable[[Callable[[T], None]], None], name: str = "producer",
                 max_pending: int = 4096):
        self._produce = produce
        self._max_pending = max_pending
        self._out: queue.SimpleQueue = queue.SimpleQueue()
        self._thread = threading.Thread(target=self._run, name=name, daemon=True)
        self._thread.start()

    def _emit(self, item: T) -> None:
        if self._out.qsize() >= self._max_pending:
            raise ResourceExhaustedError(
                f"{self._max_pending} answers wait to be read: a stream's reader must keep up "
                "with its answers", reason="ANSWERS_UNREAD")
        self._out.put(item)

    def _run(self) -> None:
        try:
            self._produce(self._emit)
        except BaseException as error:  # noqa: BLE001 - raised again in the iterating thread
            self._out.put(error)
        finally:
            self._out.put(_END)

    def __iter__(self) -> Iterator[T]:
        while (item := self._out.get()) is not _END:
            if isinstance(item, BaseException):
                raise item
            yield item
