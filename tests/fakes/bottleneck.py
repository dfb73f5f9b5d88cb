"""A path with a bottleneck, for the stream pacer's tests: honest queueing, no sockets.

Frames enter a FIFO in front of a line of `bandwidth_bps`; each is serialized after the ones
before it, then travels `one_way_s`; its receipt travels `one_way_s` back (receipts are small:
the return path never queues). The bandwidth can change at any time, as a real bottleneck's
share does. Time is the caller's: the simulation steps are explicit.
"""

from __future__ import annotations

import heapq
from dataclasses import dataclass, field


@dataclass(order=True)
class _Arrival:
    at_s: float
    sequence: int = field(compare=False)
    size_bytes: int = field(compare=False)
    sent_s: float = field(compare=False)


class Bottleneck:
    """Frames in, arrivals (and receipts) out, in time order."""

    def __init__(self, bandwidth_bps: float, one_way_s: float):
        self.bandwidth_bps = bandwidth_bps
        self.one_way_s = one_way_s
        self._line_free_s = 0.0
        self._arrivals: list[_Arrival] = []
        self.received_bytes = 0

    def send(self, sequence: int, size_bytes: int, now_s: float) -> None:
        start = max(now_s, self._line_free_s)
        self._line_free_s = start + size_bytes * 8 / self.bandwidth_bps
        heapq.heappush(self._arrivals,
                       _Arrival(self._line_free_s + self.one_way_s, sequence, size_bytes, now_s))

    def arrived_by(self, now_s: float) -> list[tuple[int, int, float, float]]:
        """(sequence, received bytes so far, arrival time, send time) of each frame that reached
        the client by `now_s`, in order."""
        out = []
        while self._arrivals and self._arrivals[0].at_s <= now_s:
            arrival = heapq.heappop(self._arrivals)
            self.received_bytes += arrival.size_bytes
            out.append((arrival.sequence, self.received_bytes, arrival.at_s, arrival.sent_s))
        return out
