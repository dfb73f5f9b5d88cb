"""The streams whose clients report receipts: each stream's pacer behind its own condition, and
the registry that routes a ReportReceipt (which arrives on another thread, often through the
DecisionServer) to its stream by id.

A stream id is 64 random bits: only the stream's client, which read it in the header, can report
on it. Nothing here knows about gRPC.
"""

from __future__ import annotations

import contextlib
import secrets
import threading
import time
from collections.abc import Callable, Iterator

from services.stereo_camera.pacing import RateLimits, StreamPacer
from wire.errors import InvalidArgumentError, NotFoundError


class PacedStream:
    """One stream's pacer, shared by the thread that sends and the threads that report."""

    def __init__(self, stream_id: str, pacer: StreamPacer, clock: Callable[[], float]):
        self.stream_id = stream_id
        self._pacer = pacer
        self._clock = clock
        self._cond = threading.Condition()
        self._keyframe_wanted = False

    def wait_for_room(self, timeout_s: float) -> bool:
        """Whether the window takes one more frame, waiting up to timeout_s for a receipt."""
        with self._cond:
            return self._cond.wait_for(self._pacer.may_send, timeout_s)

    def admit(self) -> bool:
        """Whether the frame captured now may go (the window may have filled meanwhile)."""
        with self._cond:
            return self._pacer.admit()

    def sent(self, sequence: int, size_bytes: int) -> None:
        with self._cond:
            self._pacer.sent(sequence, size_bytes, self._clock())

    def report(self, sequence: int, received_bytes: int, want_keyframe: bool) -> tuple[int, int]:
        """A receipt; returns (target kbit/s, window bytes) as the pacer now has them."""
        with self._cond:
            self._pacer.received(sequence, received_bytes, self._clock())
            self._keyframe_wanted |= want_keyframe
            self._cond.notify_all()
            return self._pacer.target_kbit, self._pacer.window_bytes

    def take_keyframe_request(self) -> bool:
        """Whether the client asked for a key frame since the last call."""
        with self._cond:
            wanted, self._keyframe_wanted = self._keyframe_wanted, False
            return wanted

    @property
    def target_kbit(self) -> int:
        with self._cond:
            return self._pacer.target_kbit


class PacedStreams:
    """Every open stream that takes receipts, by id."""

    def __init__(self, clock: Callable[[], float] = time.monotonic):
        self._clock = clock
        self._lock = threading.Lock()
        self._streams: dict[str, PacedStream] = {}

    @contextlib.contextmanager
    def open(self, limits: RateLimits) -> Iterator[PacedStream]:
        """A stream registered for its life."""
        stream = PacedStream(secrets.token_hex(8), StreamPacer(limits, self._clock()),
                             self._clock)
        with self._lock:
            self._streams[stream.stream_id] = stream
        try:
            yield stream
        finally:
            with self._lock:
                self._streams.pop(stream.stream_id, None)

    def report(self, stream_id: str, sequence: int, received_bytes: int,
               want_keyframe: bool) -> tuple[int, int]:
        """Routes a receipt; InvalidArgumentError for a malformed one, NotFoundError for no such
        stream."""
        if not stream_id:
            raise InvalidArgumentError("stream_id is empty: send the id from the stream's header",
                                       reason="NO_STREAM_ID")
        if sequence < 0 or received_bytes < 0:
            raise InvalidArgumentError(f"sequence and received_bytes must not be negative, got "
                                       f"{sequence} and {received_bytes}", reason="BAD_RECEIPT")
        with self._lock:
            stream = self._streams.get(stream_id)
        if stream is None:
            raise NotFoundError(f"no open stream has id {stream_id!r}: it ended; stop reporting",
                                reason="NO_SUCH_STREAM")
        return stream.report(sequence, received_bytes, want_keyframe)

    def __len__(self) -> int:
        with self._lock:
            return len(self._streams)


