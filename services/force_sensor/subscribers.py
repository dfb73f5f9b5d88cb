"""Per-subscriber quality of service for the wrench stream (the Parma paper's notification
service): each subscriber keeps every Nth sample, filters by change, and batches, on the
sampling thread, into its own bounded queue that drops the oldest batch when it is full.

What many subscribers share is made once: when several subscribers complete a batch of the
same samples at the same tick (the operator at decimation 1 and every observer whose turn it
is, say), `WrenchFanout` hands them one `WrenchBatch`, whose message bytes are encoded once by
whichever stream needs them first and then fanned out as they are. Each subscriber's own
counters, change filter, queue and `dropped` stay its own, so sharing changes no one's samples.
"""

from __future__ import annotations

import os
import threading
import time
import weakref
from collections import deque
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass

import numpy as np

from services.common.fanout import Fanout
from services.common.wakeup import Wakeup
from services.force_sensor.settings import exceeds
from wire.errors import InvalidArgumentError

DEFAULT_QUEUE_CAPACITY = 64
MAX_BATCH_SIZE = 1000
MAX_QUEUE_CAPACITY = 10_000
STREAM_WAIT_S = 1.0  # get() without a timeout waits in turns of this


@dataclass(frozen=True)
class WrenchReading:
    """One processed sample: contact wrench at the tool point, tool axes."""

    sequence: int
    sample_time_ns: int
    force_n: np.ndarray
    torque_nm: np.ndarray


def changed_enough(reading: WrenchReading, last: WrenchReading | None, threshold_force_n: float,
                   threshold_torque_nm: float) -> bool:
    """The ThresholdValue test of `reading` against the `last` one let through (settings.exceeds);
    True with no last one, and with both thresholds zero without looking at the values."""
    if last is None or (threshold_force_n == 0 and threshold_torque_nm == 0):
        return True
    return exceeds(float(np.max(np.abs(reading.force_n - last.force_n))),
                   float(np.max(np.abs(reading.torque_nm - last.torque_nm))),
                   threshold_force_n, threshold_torque_nm)


@dataclass(frozen=True)
class StreamOptions:
    decimation: int = 1
    threshold_force_n: float = 0.0
    threshold_torque_nm: float = 0.0
    batch_size: int = 1
    queue_capacity: int = DEFAULT_QUEUE_CAPACITY

    @classmethod
    def from_request(cls, decimation: int, threshold_force_n: float, threshold_torque_nm: float,
                     batch_size: int, queue_capacity: int) -> StreamOptions:
        """Options from a request's fields, zeros meaning defaults; InvalidArgumentError if bad."""
        for name, value, limit in (("decimation", decimation, None),
                                   ("batch_size", batch_size, MAX_BATCH_SIZE),
                                   ("queue_capacity", queue_capacity, MAX_QUEUE_CAPACITY)):
            if value < 0 or (limit is not None and value > limit):
                raise InvalidArgumentError(f"{name} must be 0..{limit or 'any'}, got {value}",
                                           reason="BAD_STREAM_OPTION")
        for name, value in (("threshold_force_n", threshold_force_n),
                            ("threshold_torque_nm", threshold_torque_nm)):
            if not np.isfinite(value) or value < 0:
                raise InvalidArgumentError(f"{name} must be a finite number >= 0, got {value}",
                                           reason="BAD_STREAM_OPTION")
        return cls(decimation or 1, threshold_force_n, threshold_torque_nm, batch_size or 1,
                   queue_capacity or DEFAULT_QUEUE_CAPACITY)


class WrenchSelection:
    """Which samples a subscriber gets, and in which batches: every Nth sample, those that
    changed enough since the last one let through, `batch_size` at a time."""

    def __init__(self, options: StreamOptions):
        self._decimation = options.decimation
        self._batch_size = options.batch_size
        self._thresholds = (options.threshold_force_n, options.threshold_torque_nm)
        self._count = 0
        self._last_forwarded: WrenchReading | None = None
        self._batch: list[WrenchReading] = []

    def take(self, item: WrenchReading) -> tuple[WrenchReading, ...] | None:
        """Decimate, filter by change, batch: the readings of a batch this sample completes, or
        None."""
        self._count += 1
        if (self._count - 1) % self._decimation:
            return None
        if not changed_enough(item, self._last_forwarded, *self._thresholds):
            return None
        self._last_forwarded = item
        if self._batch_size == 1:
            return (item,)
        self._batch.append(item)
        if len(self._batch) < self._batch_size:
            return None
        readings, self._batch = tuple(self._batch), []
        return readings


class WrenchBatch:
    """The samples of one message, oldest first, shared by every subscriber that chose the
    same ones at the same tick, with the message's bytes once someone has encoded them."""

    __slots__ = ("readings", "_payload")

    def __init__(self, readings: tuple[WrenchReading, ...]):
        self.readings = readings
        self._payload: bytes | None = None

    def payload(self, encode: Callable[[Sequence[WrenchReading]], bytes]) -> bytes:
        """encode(readings), computed by the first caller and kept for the others. Two streams
        that ask at once may both encode (the same bytes); neither waits for the other."""
        payload = self._payload
        if payload is None:
            payload = self._payload = encode(self.readings)
        return payload

    def __iter__(self) -> Iterator[WrenchReading]:
        return iter(self.readings)

    def __len__(self) -> int:
        return len(self.readings)

    def __repr__(self) -> str:
        return f"WrenchBatch({[r.sequence for r in self.readings]})"


class WrenchSubscription:
    """A subscriber's filters and its queue of batches. `take` and `deliver` (or `offer`, both
    at once) run on the sampling thread; `get` on the subscriber's stream."""

    def __init__(self, fanout, options: StreamOptions):
        if options.queue_capacity < 1:
            raise ValueError("capacity must be at least 1")
        self.options = options
        self._fanout = fanout
        self._selection = WrenchSelection(options)
        self.take = self._selection.take  # bound once: it runs per sample per subscriber
        # (queued at, batch): the fanout's on_lag hears how long each batch waited.
        self._items: deque[tuple[float, WrenchBatch]] = deque(maxlen=options.queue_capacity)
        self._lock = threading.Lock()  # the queue and `dropped` change together
        # The stream waits for batches on an eventfd, which the sampling thread writes with the
        # GIL released (see `_wake`). Closed with the object, once nothing can write to it.
        self._wake_fd = os.eventfd(0, os.EFD_CLOEXEC | os.EFD_NONBLOCK)
        weakref.finalize(self, os.close, self._wake_fd)
        self._waiting = False  # the stream is armed (next_or_arm): write to wake it
        self.dropped = 0
        self.closed = False

    def deliver(self, batch: WrenchBatch) -> None:
        """Queue a batch, dropping (and counting) the oldest when full, and wake the stream."""
        with self._lock:
            full = len(self._items) == self._items.maxlen
            if full:
                self.dropped += 1  # deque drops the oldest on append
            self._items.append((self._fanout.clock(), batch))
        if self._waiting:
            self._wake()
        if full:
            self._fanout.note_dropped()

    def offer(self, item: WrenchReading) -> None:
        """take(item), and deliver what it completes in a batch of this subscriber's own."""
        readings = self.take(item)
        if readings is not None:
            self.deliver(WrenchBatch(readings))

    def get(self, timeout_s: float | None = None) -> WrenchBatch | None:
        """The oldest queued batch, waiting up to timeout_s on this thread; None on timeout or
        once closed."""
        deadline = None if timeout_s is None else time.monotonic() + timeout_s
        while True:
            batch = self.next_or_arm()
            if batch is not None or self.closed:
                self.disarm()
                return batch
            left_s = None if deadline is None else deadline - time.monotonic()
            if left_s is not None and left_s <= 0:
                self.disarm()
                return None
            self.wakeup(STREAM_WAIT_S if left_s is None else left_s).wait()
            self.disarm()

    def next_or_arm(self) -> WrenchBatch | None:
        """The oldest queued batch without waiting; None when there is none, and then a batch
        queued from now on writes the wakeup's fd, until disarm()."""
        # Armed before looking: a batch queued after the look then writes the eventfd.
        self._waiting = True
        batch = self._pop()
        if batch is not None:
            self._waiting = False
        return batch

    def wakeup(self, timeout_s: float) -> Wakeup:
        """What the stream waits on after next_or_arm() found nothing (services/common/wakeup)."""
        return Wakeup(self._wake_fd, timeout_s)

    def disarm(self) -> None:
        """Done waiting: batches queued from now on do not write the fd."""
        self._waiting = False

    def _pop(self) -> WrenchBatch | None:
        with self._lock:
            if not self._items:
                return None
            queued_at, batch = self._items.popleft()
        self._fanout.note_lag(queued_at)
        return batch

    def close(self) -> None:
        self._fanout._remove(self)
        self.closed = True
        self._wake()

    def _wake(self) -> None:
        """Wake the stream. os.eventfd_write releases the GIL for the system call, so when the
        woken thread takes this core (the kernel often runs a woken thread at once) it can also
        take the GIL, instead of waiting behind a sampling thread that holds the GIL while it is
        off the CPU: with a lock's release() that wait, on a loaded machine, was a third of the
        GIL's time (profile in core.py's docstring)."""
        os.eventfd_write(self._wake_fd, 1)

    def __enter__(self) -> WrenchSubscription:
        return self

    def __exit__(self, *exc) -> None:
        self.close()


class WrenchFanout(Fanout[WrenchBatch]):
    """Delivers every published reading to every open WrenchSubscription, the fastest first (the
    operator's 1 kHz stream is woken before 100 Hz observers, whatever the order they came in),
    with one shared WrenchBatch for all whose batches hold the same samples."""

    def subscribe(self, options: StreamOptions) -> WrenchSubscription:  # type: ignore[override]
        return self.attach(WrenchSubscription(self, options))

    def attach(self, subscription: WrenchSubscription) -> WrenchSubscription:
        with self._lock:  # a stable sort: equal decimations keep the order they came in
            self._subscriptions = tuple(sorted((*self._subscriptions, subscription),
                                               key=lambda s: s.options.decimation))
        return subscription

    def publish(self, reading: WrenchReading) -> None:  # type: ignore[override]
        shared: dict[tuple[int, ...], WrenchBatch] = {}
        for subscription in self._subscriptions:  # a snapshot: subscribe/close never block it
            readings = subscription.take(reading)
            if readings is None:
                continue
            key = tuple(map(id, readings))  # the readings are alive: their ids are theirs
            batch = shared.get(key)
            if batch is None:
                batch = shared[key] = WrenchBatch(readings)
            subscription.deliver(batch)
