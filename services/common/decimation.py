"""Thinning a stream by its own sample times, for readers that want fewer samples than the
station publishes (the live view and the watch-only console, reading through a router)."""

from __future__ import annotations


class Decimation:
    """Keeps a sample when `period_ns` of sample time has passed since the last one kept (or
    time went back: a restarted stream). A period of 0 keeps every sample."""

    def __init__(self, period_ns: int):
        self._period_ns = period_ns
        self._last_ns: int | None = None

    @classmethod
    def at_rate(cls, rate_hz: float) -> Decimation:
        return cls(int(1e9 / rate_hz))

    def keep(self, stamp_ns: int) -> bool:
        if self._last_ns is not None and 0 <= stamp_ns - self._last_ns < self._period_ns:
            return False
        self._last_ns = stamp_ns
        return True
