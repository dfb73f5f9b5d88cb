"""Observer: a subscriber to a station's observation in Zenoh (wire/observation.py), counting
what arrives per topic: messages, samples, samples lost (gaps in the sequence numbers) and
each sample's lag (received minus taken, on this host's clock).

Each topic's samples wait in a ring of RING_MESSAGES, read by a thread of its own: an observer
that falls behind (a slow host, a busy interpreter) gets the newest messages, with gaps, never a
growing queue of stale ones.

Lag across hosts includes the two clocks' offset: both ends on one host (or hosts kept in step
by PTP or NTP) make it a delay.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
import zenoh
from google.protobuf.message import DecodeError

from wire.observation import DEFAULT_TOPICS, KEY_ROOT, TOPICS, decode, topic_of

LAG_KEEP = 200_000  # lags kept per topic for the percentiles (the newest)
RING_MESSAGES = 8  # per topic: 80 ms of the wrench
CLOSE_TIMEOUT_S = 2.0


@dataclass
class TopicCount:
    """What one topic delivered."""

    messages: int = 0
    samples: int = 0
    lost: int = 0  # wrench samples the sequence numbers skipped (dropped on the way)
    undecodable: int = 0
    last_sequence: int | None = None
    lags_ms: list[float] = field(default_factory=list)

    def summary(self, seconds: float) -> dict:
        lags = np.asarray(self.lags_ms[-LAG_KEEP:])
        return {"messages": self.messages, "samples": self.samples, "lost": self.lost,
                "undecodable": self.undecodable,
                "samples_per_s": round(self.samples / seconds, 1) if seconds > 0 else None,
                "lag_p50_ms": round(float(np.percentile(lags, 50)), 3) if lags.size else None,
                "lag_p99_ms": round(float(np.percentile(lags, 99)), 3) if lags.size else None}


def _samples(topic: str, message) -> list[tuple[int, int]]:
    """(sequence, taken at ns) of each sample in a message. The sequence is 0 where its gaps
    mean nothing: the state is published at 100 Hz of the arm's 1 kHz samples, and events
    number themselves per stream, and the video skips pairs by design when its link is slow.
    The wrench carries every sample."""
    if topic == "wrench":
        return [(s.sequence, s.sample_time.ToNanoseconds()) for s in message.samples]
    if topic == "state":
        return [(0, message.state.sample_time.ToNanoseconds())]
    if topic == "status":
        return [(0, message.status_time.ToNanoseconds())]
    if topic == "video":  # a pair, taken when its left eye was captured; a header is none
        return [(0, message.pair.left_capture_time.ToNanoseconds())] \
            if message.WhichOneof("content") == "pair" else []
    return [(0, message.event_time.ToNanoseconds())]


class Observer:
    """Subscribes on `session` to `topics` of `station` ("*" for every station) and counts.
    `on_message(topic, message)` sees each decoded message (on the topic's reader thread)."""

    def __init__(self, session: zenoh.Session, station: str = "*",
                 topics: tuple[str, ...] = DEFAULT_TOPICS,
                 on_message: Callable[[str, object], None] | None = None,
                 clock_ns: Callable[[], int] = time.time_ns):
        unknown = set(topics) - set(TOPICS)
        if unknown:
            raise ValueError(f"unknown topics {sorted(unknown)}; known: {', '.join(TOPICS)}")
        self.counts = {topic: TopicCount() for topic in topics}
        self._on_message = on_message
        self._clock_ns = clock_ns
        self._lock = threading.Lock()
        self.started = time.monotonic()
        self._subscribers = [session.declare_subscriber(f"{KEY_ROOT}/{station}/{topic}",
                                                        zenoh.handlers.RingChannel(RING_MESSAGES))
                             for topic in topics]
        self._readers = [threading.Thread(target=self._read, args=(subscriber,), daemon=True,
                                          name=f"observe-{topic}")
                         for topic, subscriber in zip(topics, self._subscribers, strict=True)]
        for reader in self._readers:
            reader.start()

    def _read(self, subscriber: zenoh.Subscriber) -> None:
        for sample in subscriber:  # until undeclared
            self._received(sample)

    def _received(self, sample: zenoh.Sample) -> None:
        now = self._clock_ns()
        found = topic_of(str(sample.key_expr))
        if found is None or found[1] not in self.counts:
            return
        topic = found[1]
        count = self.counts[topic]
        try:
            message = decode(topic, sample.payload.to_bytes())
        except DecodeError:
            with self._lock:
                count.undecodable += 1
            return
        with self._lock:
            count.messages += 1
            for sequence, taken_ns in _samples(topic, message):
                count.samples += 1
                if sequence and count.last_sequence is not None \
                        and sequence > count.last_sequence + 1:
                    count.lost += sequence - count.last_sequence - 1
                if sequence:
                    count.last_sequence = sequence
                count.lags_ms.append((now - taken_ns) / 1e6)
            if len(count.lags_ms) > 2 * LAG_KEEP:
                del count.lags_ms[:-LAG_KEEP]
        if self._on_message is not None:
            self._on_message(topic, message)

    def summary(self) -> dict[str, dict]:
        seconds = time.monotonic() - self.started
        with self._lock:
            return {topic: count.summary(seconds) for topic, count in self.counts.items()}

    def close(self) -> None:
        for subscriber in self._subscribers:
            subscriber.undeclare()
        for reader in self._readers:
            reader.join(CLOSE_TIMEOUT_S)
