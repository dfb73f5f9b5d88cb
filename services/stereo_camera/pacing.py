"""StreamPacer: paces one stream to what its path delivers, from the client's receipts.

The sender cannot see the path; the client's receipts (StereoCamera.ReportReceipt: the newest
sequence and the bytes received so far) tell it, one round trip late. From them the pacer keeps:

- **the round trip**: the time from sending a pair to the receipt for it. Its minimum over the
  last MIN_RTT_WINDOW_S is the path's own round trip; anything above it is a queue building
  somewhere on the path (the bottleneck's buffer, a socket, a forward).
- **the delivery rate**: bytes the client reported over the last DELIVERY_WINDOW_S, by time.
- **the target rate** (delay-based, after WebRTC's congestion control): a queue above
  OVERUSE_S means the path is full, and the target drops to DECREASE of what was delivered (at
  most once per round trip, so that a drop is seen to work before the next); a queue below
  UNDERUSE_S lets it grow by INCREASE_PER_S a second, up to GROWTH_CAP x what was delivered
  (an encoder that needs less than its target does not inflate it).
- **the window**: bytes sent and not yet reported, at most the target rate times the path's
  round trip plus SLACK_S, and never less than one frame. A frame that would not fit is not
  captured (the sender skips the tick: the frame rate falls, nothing queues, and an H.264
  stream stays decodable because it never loses an encoded frame).

An image stream (JPEG) paces the same way: its encoder ignores the target, but the target still
sizes the window, so frames are skipped rather than queued.

Pure: times are arguments (seconds on one monotonic clock), so tests drive it with a fake link.
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass

OVERUSE_S = 0.030  # queueing delay that means the path is full
UNDERUSE_S = 0.010  # queueing delay below which the path has room
DECREASE = 0.85  # of the delivery rate, on overuse
INCREASE_PER_S = 0.25  # relative growth of the target per second while the path has room
GROWTH_CAP = 1.5  # the target never exceeds this times the delivery rate
SLACK_S = 0.040  # the window's room beyond one round trip
START_RTT_S = 0.2  # assumed until the first receipt
MIN_RTT_WINDOW_S = 10.0
DELIVERY_WINDOW_S = 0.5
MIN_WINDOW_FRAMES = 1


@dataclass(frozen=True)
class RateLimits:
    """The bitrates an H.264 stream may use, in kbit/s."""

    start_kbit: int = 1500
    min_kbit: int = 150
    max_kbit: int = 8000

    def __post_init__(self) -> None:
        if not 0 < self.min_kbit <= self.start_kbit <= self.max_kbit:
            raise ValueError(f"need 0 < min_kbit <= start_kbit <= max_kbit, got {self}")


class StreamPacer:
    """One stream's pacing (see the module docstring). Not thread-safe: its owner holds a lock
    around it."""

    def __init__(self, limits: RateLimits, now_s: float):
        self.limits = limits
        self.target_bps = limits.start_kbit * 1e3
        self.sent_bytes = 0
        self.acked_bytes = 0
        self.acked_sequence = -1
        self.receipts = 0
        self.rtt_s: float | None = None  # the newest round trip
        self._sent: deque[tuple[int, float, int]] = deque()  # (sequence, time, size) unreported
        self._rtt_bytes = 0  # the size of the frame the newest round trip timed
        self._rtts: deque[tuple[float, float]] = deque()  # (time, rtt), for the minimum
        self._deliveries: deque[tuple[float, int]] = deque()  # (time, acked bytes)
        self._frame_bytes = 0.0  # a moving average of the frames sent
        self._hold_until_s = now_s  # no decrease before then (the last one's effect)
        self._last_update_s = now_s

    # -- what the sender asks ---------------------------------------------------------------

    @property
    def min_rtt_s(self) -> float:
        return min((rtt for _, rtt in self._rtts), default=START_RTT_S)

    @property
    def in_flight_bytes(self) -> int:
        return self.sent_bytes - self.acked_bytes

    @property
    def window_bytes(self) -> int:
        frames = MIN_WINDOW_FRAMES * max(self._frame_bytes, 1.0)
        return int(max(frames, self.target_bps / 8 * (self.min_rtt_s + SLACK_S)))

    @property
    def target_kbit(self) -> int:
        return round(self.target_bps / 1e3)

    def may_send(self) -> bool:
        """Whether one more frame fits in the window (an empty pipe always takes one)."""
        if self.in_flight_bytes <= 0:
            return True
        return self.in_flight_bytes + self._frame_bytes <= self.window_bytes

    # -- what happens -----------------------------------------------------------------------

    def sent(self, sequence: int, size_bytes: int, now_s: float) -> None:
        """A frame of `size_bytes` left for the client."""
        self.sent_bytes += size_bytes
        self._sent.append((sequence, now_s, size_bytes))
        self._frame_bytes = size_bytes if not self._frame_bytes \
            else 0.9 * self._frame_bytes + 0.1 * size_bytes

    def received(self, sequence: int, received_bytes: int, now_s: float) -> None:
        """The client's receipt: it has `sequence` and `received_bytes` in all. Receipts may
        arrive out of order (they are sent without waiting); an older one changes nothing."""
        if sequence <= self.acked_sequence:
            return
        self.acked_sequence = sequence
        self.receipts += 1
        self.acked_bytes = max(self.acked_bytes, min(received_bytes, self.sent_bytes))
        sent_at = sent_size = None
        while self._sent and self._sent[0][0] <= sequence:
            seq, at, size = self._sent.popleft()
            if seq == sequence:
                sent_at, sent_size = at, size
        if sent_at is not None:
            self.rtt_s = max(0.0, now_s - sent_at)
            self._rtt_bytes = sent_size
            self._rtts.append((now_s, self.rtt_s))
        _expire(self._rtts, now_s - MIN_RTT_WINDOW_S)
        self._deliveries.append((now_s, self.acked_bytes))
        _expire(self._deliveries, now_s - DELIVERY_WINDOW_S)
        if self.rtt_s is not None:
            self._adapt(now_s, self.delivery_bps())
        self._last_update_s = now_s

    def delivery_bps(self) -> float | None:
        """Bits per second the client reported over the last DELIVERY_WINDOW_S, or None
        before two receipts span some time."""
        if len(self._deliveries) < 2:
            return None
        (t0, b0), (t1, b1) = self._deliveries[0], self._deliveries[-1]
        return (b1 - b0) * 8 / (t1 - t0) if t1 > t0 else None

    def _adapt(self, now_s: float, delivery: float | None) -> None:
        # A frame's round trip includes its own serialization at the bottleneck: a key frame
        # takes longer without any queue.
        own_s = self._rtt_bytes * 8 / delivery if delivery else 0.0
        queue_s = self.rtt_s - own_s - self.min_rtt_s
        limits = self.limits
        if queue_s > OVERUSE_S:
            if now_s >= self._hold_until_s and delivery is not None:
                self.target_bps = DECREASE * min(delivery, self.target_bps)
                self._hold_until_s = now_s + self.rtt_s
        elif queue_s < UNDERUSE_S and now_s >= self._hold_until_s:
            dt = max(0.0, now_s - self._last_update_s)
            grown = self.target_bps * (1.0 + INCREASE_PER_S * dt)
            if delivery is not None:
                grown = min(grown, max(self.target_bps, GROWTH_CAP * delivery))
            self.target_bps = grown
        self.target_bps = min(max(self.target_bps, limits.min_kbit * 1e3),
                              limits.max_kbit * 1e3)


def _expire(entries: deque, before_s: float) -> None:
    """Drop the entries older than `before_s`, keeping the newest."""
    while len(entries) > 1 and entries[0][0] < before_s:
        entries.popleft()
