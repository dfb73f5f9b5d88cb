"""KeyframePacing: when a follower of an H.264 stream should ask the camera for a key frame
(in a receipt, services.common.video_receipts). No transport code.

The live view (services.foxglove.live) asks for one for each newcomer and every few seconds;
the observation publisher (services.observation.video) every VIDEO_KEYFRAME_S, since it cannot
tell when an observer joins.
"""

from __future__ import annotations

import time
from collections.abc import Callable

KEYFRAME_RETRY_S = 0.5  # a key frame asked for and not come by then: asked for again


class KeyframePacing:
    """Whether the next receipt should ask for a key frame: one was asked for (`ask()`, a
    newcomer), none came for `every_s`, or one was asked for `retry_s` ago and has not come.
    `clock` is monotonic seconds. Not thread-safe: its user holds its own lock."""

    def __init__(self, every_s: float, retry_s: float = KEYFRAME_RETRY_S,
                 clock: Callable[[], float] = time.monotonic):
        self._every_s, self._retry_s, self._clock = every_s, retry_s, clock
        self._last_keyframe_s = clock()
        self._asked_s: float | None = None
        self._wanted = False

    def ask(self) -> None:
        """A key frame is wanted now: the next due() says so."""
        self._wanted = True

    def keyframe(self) -> None:
        """A key frame came (or a stream opened, which starts with one)."""
        self._last_keyframe_s, self._asked_s, self._wanted = self._clock(), None, False

    def due(self) -> bool:
        now = self._clock()
        if self._wanted:
            ask = True
        elif self._asked_s is not None:
            ask = now - self._asked_s >= self._retry_s
        else:
            ask = now - self._last_keyframe_s >= self._every_s
        if ask:
            self._asked_s, self._wanted = now, False
        return ask
