"""Per-subscriber quality of service for the wrench stream (the Parma paper's notification
service): each subscriber keeps every Nth sample, filters by change, and batches, on the
sampling thread, into its own bounded queue that drops the oldest batch when it is full."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from services.common.fanout import Subscription
from services.force_sensor.settings import exceeds
from services.runtime.errors import InvalidArgument

DEFAULT_QUEUE_CAPACITY = 64
MAX_BATCH_SIZE = 1000
MAX_QUEUE_CAPACITY = 10_000


@dataclass(frozen=True)
class WrenchReading:
    """One processed sample: contact wrench at the tool point, tool axes."""

    sequence: int
    sample_time_ns: int
    force_n: np.ndarray
    torque_nm: np.ndarray


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
        """Options from a request's fields, zeros meaning defaults; InvalidArgument if bad."""
        for name, value, limit in (("decimation", decimation, None),
                                   ("batch_size", batch_size, MAX_BATCH_SIZE),
                                   ("queue_capacity", queue_capacity, MAX_QUEUE_CAPACITY)):
            if value < 0 or (limit is not None and value > limit):
                raise InvalidArgument(f"{name} must be 0..{limit or 'any'}, got {value}",
                                      reason="BAD_STREAM_OPTION")
        for name, value in (("threshold_force_n", threshold_force_n),
                            ("threshold_torque_nm", threshold_torque_nm)):
            if not np.isfinite(value) or value < 0:
                raise InvalidArgument(f"{name} must be a finite number >= 0, got {value}",
                                      reason="BAD_STREAM_OPTION")
        return cls(decimation or 1, threshold_force_n, threshold_torque_nm, batch_size or 1,
                   queue_capacity or DEFAULT_QUEUE_CAPACITY)


class WrenchSubscription(Subscription[list[WrenchReading]]):
    """A subscriber's queue of batches; `offer_sample` runs on the sampling thread."""

    def __init__(self, fanout, options: StreamOptions):
        super().__init__(fanout, options.queue_capacity)
        self.options = options
        self._count = 0
        self._last_forwarded: WrenchReading | None = None
        self._batch: list[WrenchReading] = []

    def offer(self, item: WrenchReading) -> None:  # type: ignore[override]
        """Decimate, filter by change, batch; queue a batch once full."""
        self._count += 1
        if (self._count - 1) % self.options.decimation:
            return
        last = self._last_forwarded
        if last is not None and not exceeds(
                float(np.max(np.abs(item.force_n - last.force_n))),
                float(np.max(np.abs(item.torque_nm - last.torque_nm))),
                self.options.threshold_force_n, self.options.threshold_torque_nm):
            return
        self._last_forwarded = item
        self._batch.append(item)
        if len(self._batch) >= self.options.batch_size:
            batch, self._batch = self._batch, []
            super().offer(batch)
