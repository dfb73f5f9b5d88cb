"""Zenoh subscribers for the observers_zenoh rows (bench/groups/observers_zenoh.py): `count`
client sessions in this process, each its own connection to the router and its own
subscriber to the station's wrench (so the router sends each one its copy), counted by
clients.observe.Observer from the moment all are receiving."""

from __future__ import annotations

import threading
import time
from collections.abc import Callable

import numpy as np
import zenoh

from clients.observe import Observer, TopicCount
from wire.observation import client

FIRST_SAMPLE_S = 30.0  # every subscriber has its first wrench message within this


def observe_zenoh(router: str, station: str, count: int, max_s: float,
                  ready: Callable[[], None], stop: threading.Event) -> dict:
    """Subscribe `count` sessions, call ready() once each has a wrench message, then count
    until `stop` (or max_s): per subscriber, the samples it got per second, the samples lost
    (sequence gaps) and the lag p50 / p99 (received minus taken, one clock)."""
    started = time.monotonic()
    sessions = [client(router) for _ in range(count)]
    observers: list[Observer] = []
    try:
        observers = [Observer(session, station, ("wrench",)) for session in sessions]
        counts = [observer.counts["wrench"] for observer in observers]
        deadline = started + FIRST_SAMPLE_S
        while time.monotonic() < deadline and not stop.is_set() and \
                not all(c.messages for c in counts):
            stop.wait(0.05)
        never = sum(1 for c in counts if not c.messages)
        marks = [(c.samples, c.lost, len(c.lags_ms)) for c in counts]
        marked_at = time.monotonic()
        ready()
        stop.wait(max(0.0, max_s - (marked_at - started)))
        seconds = time.monotonic() - marked_at
    finally:
        # First: with every subscriber's callback still firing, this thread would wait for
        # the GIL behind all of them at each step of the summary. Subscribers before their
        # sessions, so that no callback holds a closing session up.
        unclosed = _close(observers, sessions)
    return {"observers": count, "seconds": round(seconds, 3), "never_received": never,
            "close_timeouts": unclosed,
            "per_observer": [_since(c, mark, seconds) for c, mark in zip(counts, marks,
                                                                          strict=True)]}


def _close(observers: list[Observer], sessions: list[zenoh.Session]) -> int:
    """Undeclare every subscriber, then close every session: how many timed out (an
    overloaded process's sessions may; the process ends anyway)."""
    timeouts = 0
    for closing in [*(o.close for o in observers), *(s.close for s in sessions)]:
        try:
            closing()
        except zenoh.ZError:
            timeouts += 1
    return timeouts


def _since(count: TopicCount, mark: tuple[int, int, int], seconds: float) -> dict:
    """One subscriber's figures since `mark` (samples, lost, lags seen then)."""
    samples, lost, lags = mark
    measured = np.asarray(count.lags_ms[lags:])
    return {"samples_per_s": round((count.samples - samples) / seconds, 1),
            "lost": count.lost - lost,
            "lag_p50_ms": round(float(np.percentile(measured, 50)), 3) if measured.size
            else None,
            "lag_p99_ms": round(float(np.percentile(measured, 99)), 3) if measured.size
            else None}
