"""Summaries of measured latencies and rates, in the shape every scenario reports."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np


def percentiles_ms(latencies_ms: Sequence[float]) -> dict[str, float | None]:
    """p50, p99 and max of latencies in ms (None when there are none)."""
    values = np.asarray(latencies_ms, dtype=float)
    values = values[np.isfinite(values)]
    if values.size == 0:
        return {"p50_ms": None, "p99_ms": None, "max_ms": None}
    p50, p99 = np.percentile(values, [50, 99])
    return {"p50_ms": round(float(p50), 4), "p99_ms": round(float(p99), 4),
            "max_ms": round(float(values.max()), 4)}


def summary(latencies_ms: Sequence[float], rate_hz: float | None, delivered: int,
            window_s: float, dropped: int, **extra) -> dict:
    """The fields every scenario reports: rate_hz (offered), delivered_hz (`delivered` over
    `window_s`), p50/p99/max (ms), dropped, plus `extra`."""
    result = {
        "rate_hz": None if rate_hz is None else round(float(rate_hz), 3),
        "delivered_hz": round(delivered / window_s, 3) if window_s > 0 else None,
        **percentiles_ms(latencies_ms),
        "dropped": int(dropped),
        "samples": int(len(latencies_ms)),
    }
    result.update(extra)
    return result


def interarrival(arrivals_ns: Sequence[int], nominal_ms: float) -> dict[str, float | None]:
    """Inter-arrival times (ms): mean, standard deviation (the jitter), p99 and max."""
    times = np.asarray(arrivals_ns, dtype=np.int64)
    if times.size < 3:
        return {"interarrival_mean_ms": None, "jitter_ms": None, "interarrival_p99_ms": None,
                "interarrival_max_ms": None}
    gaps = np.diff(times) / 1e6
    return {
        "interarrival_nominal_ms": nominal_ms,
        "interarrival_mean_ms": round(float(gaps.mean()), 4),
        "jitter_ms": round(float(gaps.std()), 4),
        "interarrival_p99_ms": round(float(np.percentile(gaps, 99)), 4),
        "interarrival_max_ms": round(float(gaps.max()), 4),
    }


def ratio(numerator: float | None, denominator: float | None) -> float | None:
    """numerator / denominator, or None when either is missing or the denominator is 0."""
    if numerator is None or denominator is None or denominator <= 0:
        return None
    value = numerator / denominator
    return round(value, 2) if math.isfinite(value) else None
