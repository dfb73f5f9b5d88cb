"""StreamPacer: paces one stream to what its path delivers, from the client's receipts.

The sender cannot see the path; the client's receipts (StereoCamera.ReportReceipt: the newest
sequence and the bytes received so far) tell it, one round trip late. From them the pacer keeps:

- **the delivery rate**: bytes the client reported over the last DELIVERY_WINDOW_S, by time.
- **the queue**: a frame's round trip (sent to reported) against the least over
  MIN_RTT_WINDOW_S (the path's own round trip). A queue that QUEUE_RECEIPTS receipts in a row
  saw is real; a few late receipts are a hiccup (a busy host, a big key frame). A frame's round
  trip includes its own time on the narrowest link, so a stream whose frames fill much of the
  link reads as a queue of up to a frame interval: the thresholds leave room for that, and the
  target settles where its frames take under UNDERUSE_S on the line.
- **the target rate** (delay-based, after WebRTC's congestion control): a queue above
  OVERUSE_S means the path is full, and the target drops to DECREASE of what was delivered,
  then waits for receipts of frames sent after the drop before it judges again; what was
  delivered then is the path's capacity as last seen (a queue built, so the path set the pace).
  A queue below UNDERUSE_S lets the target grow: by INCREASE_PER_S a second while the target
  and what is sent are well below that capacity (or none is known), near it by only
  NEAR_INCREASE_PER_S of the capacity a second, so that a long round trip, which shows an
  overshoot late, overshoots little; once more than FORGET_CAPACITY x the capacity is *sent*
  with no queue, the path has widened and the fast growth resumes. (What is sent, not the
  target: an encoder that makes less than its target keeps the target above the path.)
  Above the start rate, never above GROWTH_CAP x what was delivered: an encoder that needs
  less than its target does not inflate it (x264 makes about half its target at the lowest
  rates, so below the start rate the target grows regardless).
- **the window**: bytes sent and not yet reported when a frame is sent, at most the target
  rate times the path's round trip plus SLACK_S, and never less than a frame. A frame that
  would not fit is not encoded (the sender skips the tick: the frame rate falls, nothing
  queues, and an H.264 stream stays decodable because it never loses an encoded frame).

An image stream (JPEG) paces the same way: its encoder ignores the target, but the target still
sizes the window, so frames are skipped rather than queued.

Pure: times are arguments (seconds on one monotonic clock), so tests drive it with a fake link.
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass

OVERUSE_S = 0.030  # a queue this long means the path is full...
QUEUE_RECEIPTS = 5  # ...when this many receipts in a row see it (a sixth of a second at
# 30 fps: a host that was busy for a moment is not a full path)
UNDERUSE_S = 0.015  # a queue below this means the path has room
DECREASE = 0.85  # of the delivery rate, on overuse
INCREASE_PER_S = 0.25  # relative growth of the target per second while the path has room...
NEAR_CAPACITY = 0.9  # ...below this much of the capacity last seen; above it the growth is...
NEAR_INCREASE_PER_S = 0.05  # ...this much of that capacity a second...
FORGET_CAPACITY = 1.1  # ...until it passes it by this much with no queue: the path widened
GROWTH_CAP = 2.0  # the target never exceeds this times the delivery rate (x264 makes
# about two thirds of its target on the simulated scenes: a tighter cap would hold it there)
SLACK_S = 0.040  # the window's room beyond one round trip
START_RTT_S = 0.2  # assumed until the first receipt
MIN_RTT_WINDOW_S = 10.0
DELIVERY_WINDOW_S = 1.0
MIN_WINDOW_FRAMES = 2


@dataclass(frozen=True)
class RateLimits:
    """The bitrates a stream's target may take, in kbit/s."""

    start_kbit: int = 1500
    min_kbit: int = 150
    max_kbit: int = 8000

    def __post_init__(self) -> None:
        if not 0 < self.min_kbit <= self.start_kbit <= self.max_kbit:
            raise ValueError(f"need 0 < min_kbit <= start_kbit <= max_kbit, got {self}")


@dataclass(frozen=True)
class _RoundTrip:
    at_s: float
    sequence: int
    rtt_s: float


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
        self.skips = 0  # frames not admitted
        self.rtt_s: float | None = None  # the newest round trip
        self._sent: deque[tuple[int, float]] = deque()  # (sequence, send time), unreported
        self._round_trips: deque[_RoundTrip] = deque()
        self._deliveries: deque[tuple[float, int]] = deque()  # (time, acked bytes)
        self._sends: deque[tuple[float, int]] = deque()  # (time, sent bytes)
        self._frame_bytes = 0.0  # a moving average of the frames sent
        self._judged_after = 0  # decisions use receipts of frames sent after this sequence
        self._capacity_bps: float | None = None  # delivered at the last overuse
        self._last_update_s = now_s

    # -- what the sender asks ---------------------------------------------------------------

    @property
    def min_rtt_s(self) -> float:
        """The path's round trip: the least seen over MIN_RTT_WINDOW_S."""
        return min((r.rtt_s for r in self._round_trips), default=START_RTT_S)

    @property
    def in_flight_bytes(self) -> int:
        return self.sent_bytes - self.acked_bytes

    @property
    def window_bytes(self) -> int:
        """The bytes that may be in flight when a frame is sent (the frame not counted: a
        frame is a burst, and the window is for the bytes the path holds between bursts)."""
        frames = (MIN_WINDOW_FRAMES - 1) * max(self._frame_bytes, 1.0)
        return int(max(frames, self.target_bps / 8 * (self.min_rtt_s + SLACK_S)))

    @property
    def target_kbit(self) -> int:
        return round(self.target_bps / 1e3)

    def may_send(self) -> bool:
        """Whether the window has room for one more frame."""
        return self.in_flight_bytes <= self.window_bytes

    def admit(self) -> bool:
        """Whether a frame captured now may be sent; one that does not fit is skipped."""
        if self.may_send():
            return True
        self.skips += 1
        return False

    def delivery_bps(self) -> float | None:
        """Bits per second the client reported over the last DELIVERY_WINDOW_S, or None
        before two receipts span some time."""
        return _rate(self._deliveries)

    def sending_bps(self) -> float | None:
        """Bits per second sent over the last DELIVERY_WINDOW_S."""
        return _rate(self._sends)

    def queue_s(self) -> float | None:
        """The queue the last QUEUE_RECEIPTS receipts all saw (see the module docstring), of
        frames sent since the last decision; None until there are that many."""
        recent = [t.rtt_s for t in list(self._round_trips)[-QUEUE_RECEIPTS:]
                  if t.sequence > self._judged_after]
        if len(recent) < QUEUE_RECEIPTS:
            return None
        return min(recent) - self.min_rtt_s

    # -- what happens -----------------------------------------------------------------------

    def sent(self, sequence: int, size_bytes: int, now_s: float) -> None:
        """A frame of `size_bytes` left for the client."""
        self.sent_bytes += size_bytes
        self._sent.append((sequence, now_s))
        self._sends.append((now_s, self.sent_bytes))
        _expire(self._sends, now_s - DELIVERY_WINDOW_S, lambda d: d[0])
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
        timed = None
        while self._sent and self._sent[0][0] <= sequence:
            entry = self._sent.popleft()
            if entry[0] == sequence:
                timed = entry
        self._deliveries.append((now_s, self.acked_bytes))
        _expire(self._deliveries, now_s - DELIVERY_WINDOW_S, lambda d: d[0])
        delivery = self.delivery_bps()
        if timed is not None:
            self.rtt_s = max(0.0, now_s - timed[1])
            self._round_trips.append(_RoundTrip(now_s, sequence, self.rtt_s))
            _expire(self._round_trips, now_s - MIN_RTT_WINDOW_S, lambda r: r.at_s)
        if self.rtt_s is not None:
            self._adapt(now_s, delivery)
        self._last_update_s = now_s

    def _adapt(self, now_s: float, delivery: float | None) -> None:
        queue_s = self.queue_s()
        if queue_s is None:
            pass  # too few receipts since the last decision to judge
        elif queue_s > OVERUSE_S:
            if delivery is not None:
                self._decrease(delivery)
        elif queue_s < UNDERUSE_S:
            self._increase(now_s - self._last_update_s, delivery)
        limits = self.limits
        self.target_bps = min(max(self.target_bps, limits.min_kbit * 1e3),
                              limits.max_kbit * 1e3)

    def _increase(self, dt_s: float, delivery: float | None) -> None:
        # The path has widened only once more than it carried went through without a queue:
        # judged by what is sent, since an encoder that makes less than its target keeps its
        # target above the path for good. Near it, by either.
        capacity, sending = self._capacity_bps, self.sending_bps() or 0.0
        if capacity is not None and sending > FORGET_CAPACITY * capacity:
            self._capacity_bps = capacity = None  # the path widened: probe fast again
        if capacity is not None and max(sending, self.target_bps) >= NEAR_CAPACITY * capacity:
            grown = self.target_bps + NEAR_INCREASE_PER_S * capacity * max(0.0, dt_s)
        else:
            grown = self.target_bps * (1.0 + INCREASE_PER_S * max(0.0, dt_s))
        if delivery is not None:  # up to the start rate, which is safe to come back to
            grown = min(grown, max(self.target_bps, GROWTH_CAP * delivery,
                                   self.limits.start_kbit * 1e3))
        self.target_bps = grown

    def _decrease(self, delivery: float) -> None:
        """To DECREASE of what arrives. The frames in flight were sent at the old rate: the next
        decision waits for receipts of frames sent after this one."""
        self._judged_after = self._sent[-1][0] if self._sent else self.acked_sequence
        self._capacity_bps = delivery  # a queue built: the path, not the encoder, set the pace
        self.target_bps = DECREASE * min(delivery, self.target_bps)


def _rate(entries: deque) -> float | None:
    """Bits per second between the first and last (time, bytes) entries; None for no span."""
    if len(entries) < 2:
        return None
    (t0, b0), (t1, b1) = entries[0], entries[-1]
    return (b1 - b0) * 8 / (t1 - t0) if t1 > t0 else None


def _expire(entries: deque, before_s: float, time_of) -> None:
    """Drop the entries older than `before_s`, keeping the newest."""
    while len(entries) > 1 and time_of(entries[0]) < before_s:
        entries.popleft()
