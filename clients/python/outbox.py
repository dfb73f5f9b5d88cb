"""What a Teleoperate stream has yet to send, merged while the link is slower than the master.

gRPC's sending thread takes the next request from the stream's request iterator only when the
link accepts it. A master that sends faster than that would otherwise build a queue here, and
every increment in it would reach the arm later than the one before. Instead, motion commands
that are waiting together are sent as one when their turn comes: the newest one's sequence
carries their composed increment. Nothing is lost, and what is sent is as fresh as the link
allows. (The server does the same with what waits on its side: MERGED_LATE.)
"""

from __future__ import annotations

import threading
from collections import deque
from collections.abc import Callable
from typing import Generic, TypeVar

import numpy as np

T = TypeVar("T")


class Outbox(Generic[T]):
    """A request iterator for a gRPC stream. `put` queues; iterating takes the oldest, and when
    it and the ones behind it are `mergeable`, all of them at once through `merge` (called
    without the outbox's lock held). Iteration ends at `end`."""

    def __init__(self, end: object, mergeable: Callable[[T], bool],
                 merge: Callable[[list[T]], T]):
        self._end = end
        self._mergeable = mergeable
        self._merge = merge
        self._items: deque = deque()
        self._ready = threading.Condition()

    def put(self, item) -> None:
        with self._ready:
            self._items.append(item)
            self._ready.notify()

    def __iter__(self):
        return self

    def __next__(self) -> T:
        with self._ready:
            while not self._items:
                self._ready.wait()
            first = self._items.popleft()
            if first is self._end:
                self._items.appendleft(first)  # ended for good: every later call ends too
                raise StopIteration
            run = [first]
            if self._mergeable(first):
                while self._items and self._items[0] is not self._end \
                        and self._mergeable(self._items[0]):
                    run.append(self._items.popleft())
        return first if len(run) == 1 else self._merge(run)


def compose_increments(increments: list[tuple[np.ndarray, np.ndarray]], frame: str
                       ) -> tuple[np.ndarray, np.ndarray]:
    """One increment (ΔX, ΔM) with the effect of `increments` applied in turn in `frame`, as
    the server applies an increment (eq. 1): TOOL composes in the tool frame (the first's
    rotation turns the later translations), BASE adds translations and composes rotations about
    the tool point in base axes."""
    translation, rotation = np.zeros(3), np.eye(3)
    for dx, dm in increments:
        if frame == "TOOL":
            translation, rotation = translation + rotation @ dx, rotation @ dm
        else:
            translation, rotation = translation + dx, dm @ rotation
    return translation, rotation
