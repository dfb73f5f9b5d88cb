"""The master's clock offset, estimated as NTP does from the session's own exchanges.

One exchange is a command and its ack: the master sends it at t0 (its clock), the server
receives it at t1 and answers at t2 (the server's clock), the master receives the ack at t3 (its
clock again; it reports t3 in a later message's AckReceipt). Then

    offset = ((t1 - t0) + (t2 - t3)) / 2       the server's clock minus the master's
    delay  = (t3 - t0) - (t2 - t1)             the round trip, less the server's own time

and the true offset lies within offset ± delay / 2, whatever the split of the delay between the
two directions. Of the last WINDOW exchanges the one with the shortest delay is taken (NTP's
clock filter): queueing only ever lengthens an exchange, so the shortest is the least distorted.
"""

from __future__ import annotations

from collections import OrderedDict, deque
from dataclasses import dataclass

WINDOW = 8
# Exchanges remembered until their receipt comes: a master reports on a later message, so a
# round trip's worth of commands at most (1,000 at 1 kHz across a second).
EXCHANGES_KEPT = 1024


@dataclass(frozen=True)
class OffsetEstimate:
    offset_ns: int  # the server's clock minus the master's
    error_ns: int  # the most the true offset can differ from offset_ns


class ClockOffsetEstimator:
    """Feed it `answered(...)` for each command the server acks and `receipt(...)` for each
    AckReceipt the master sends; `estimate()` is the offset, or None before any receipt."""

    def __init__(self):
        self._exchanges: OrderedDict[int, tuple[int, int, int]] = OrderedDict()
        self._samples: deque[tuple[int, int]] = deque(maxlen=WINDOW)  # (delay, offset)

    def answered(self, sequence: int, sent_ns: int, received_ns: int, answered_ns: int) -> None:
        """Command `sequence`, sent at `sent_ns` (master clock), was received and answered at
        `received_ns` and `answered_ns` (server clock)."""
        if sequence <= 0 or sent_ns <= 0:
            return  # no sequence to report on, or no send time: no exchange
        self._exchanges[sequence] = (sent_ns, received_ns, answered_ns)
        while len(self._exchanges) > EXCHANGES_KEPT:
            self._exchanges.popitem(last=False)

    def receipt(self, sequence: int, acked_ns: int) -> bool:
        """The master received command `sequence`'s ack at `acked_ns` (its clock). False when
        the exchange is unknown (too old, never answered) or impossible (a negative delay)."""
        exchange = self._exchanges.pop(sequence, None)
        if exchange is None:
            return False
        sent, received, answered = exchange
        delay = (acked_ns - sent) - (answered - received)
        if delay < 0:
            return False
        self._samples.append((delay, ((received - sent) + (answered - acked_ns)) // 2))
        return True

    def estimate(self) -> OffsetEstimate | None:
        if not self._samples:
            return None
        delay, offset = min(self._samples)
        return OffsetEstimate(offset, delay // 2)
