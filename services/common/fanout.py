"""One publisher, many subscribers, each with its own bounded queue that drops its oldest.

A slow subscriber never slows the publisher or any other subscriber: its queue overflows, the
oldest items go, and `dropped` says how many (and the fanout's `on_dropped`, if set, hears of
each: the service's metrics). The fanout's `on_lag`, if set, hears how long each item waited in
a queue before its subscriber took it (the stream's lag). Nothing here knows about gRPC.
"""

from __future__ import annotations

import logging
import threading
import time
from collections import deque
from collections.abc import Callable
from typing import Generic, TypeVar

T = TypeVar("T")

log = logging.getLogger(__name__)


class Subscription(Generic[T]):
    """A subscriber's queue. Read with get(); close() when done."""

    def __init__(self, fanout: Fanout[T], capacity: int):
        if capacity < 1:
            raise ValueError("capacity must be at least 1")
        self._fanout = fanout
        self._items: deque[tuple[float, T]] = deque(maxlen=capacity)  # (queued at, item)
        self._ready = threading.Condition()
        self.dropped = 0
        self.closed = False

    def offer(self, item: T) -> None:
        with self._ready:
            full = len(self._items) == self._items.maxlen
            if full:
                self.dropped += 1  # deque drops the oldest on append
            self._items.append((self._fanout.clock(), item))
            self._ready.notify()
        if full:
            self._fanout.note_dropped()

    def get(self, timeout_s: float | None = None) -> T | None:
        """The oldest queued item, waiting up to timeout_s; None on timeout or once closed."""
        with self._ready:
            if not self._items and not self.closed:
                self._ready.wait(timeout_s)
            if not self._items:
                return None
            queued_at, item = self._items.popleft()
        self._fanout.note_lag(queued_at)
        return item

    def close(self) -> None:
        self._fanout._remove(self)
        with self._ready:
            self.closed = True
            self._ready.notify_all()

    def __enter__(self) -> Subscription[T]:
        return self

    def __exit__(self, *exc) -> None:
        self.close()


class Fanout(Generic[T]):
    """Delivers every published item to every open subscription."""

    def __init__(self, clock: Callable[[], float] = time.monotonic) -> None:
        self.clock = clock  # seconds, for the lag: time.monotonic, or a test's fake clock
        self._lock = threading.Lock()
        self._subscriptions: tuple[Subscription[T], ...] = ()
        # Called (on the publisher's thread) each time a subscriber's queue drops an item.
        self.on_dropped: Callable[[], None] | None = None
        # Called (on the subscriber's thread) with the seconds each item waited in its queue.
        self.on_lag: Callable[[float], None] | None = None

    def note_dropped(self) -> None:
        """A subscriber dropped an item: tell on_dropped, if set. Never raises."""
        on_dropped = self.on_dropped
        if on_dropped is None:
            return
        try:
            on_dropped()
        except Exception:  # noqa: BLE001 - a report never fails the publisher
            log.exception("reporting a dropped item failed")

    def note_lag(self, queued_at: float) -> None:
        """A subscriber took an item queued at `queued_at` (by `clock`): tell on_lag, if set,
        how long it waited. Never raises."""
        on_lag = self.on_lag
        if on_lag is None:
            return
        try:
            on_lag(self.clock() - queued_at)
        except Exception:  # noqa: BLE001 - a report never fails the subscriber
            log.exception("reporting a stream's lag failed")

    def subscribe(self, capacity: int = 64) -> Subscription[T]:
        return self.attach(Subscription(self, capacity))

    def attach(self, subscription: Subscription[T]) -> Subscription[T]:
        """Start delivering to a subscription made here (a Subscription subclass that filters
        in its offer(), for example)."""
        with self._lock:
            self._subscriptions = (*self._subscriptions, subscription)
        return subscription

    def publish(self, item: T) -> None:
        for subscription in self._subscriptions:  # a snapshot: subscribe/close never block this
            subscription.offer(item)

    def close_all(self) -> None:
        for subscription in self._subscriptions:
            subscription.close()

    @property
    def subscriber_count(self) -> int:
        return len(self._subscriptions)

    def _remove(self, subscription: Subscription[T]) -> None:
        with self._lock:
            self._subscriptions = tuple(s for s in self._subscriptions if s is not subscription)
