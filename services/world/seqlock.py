"""A seqlock over one numpy record in shared memory: one writer, any number of lock-free readers.

The writer makes the sequence word odd, writes the record, then makes it even again. A reader
copies the record between two reads of the sequence word and keeps the copy only when both
reads are equal and even, so it never sees a torn record; it never blocks the writer.

Memory ordering: this relies on x86-64 (TSO: stores become visible in program order and loads
are not reordered with other loads) and on each step being a separate numpy call that the
compiler cannot reorder. On a weakly ordered CPU (ARM) the reader and writer would need fences,
which pure Python cannot issue (ORDERING_GUARANTEED says whether this machine is covered).
"""

from __future__ import annotations

import platform
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager

import numpy as np

ORDERING_GUARANTEED = platform.machine().lower() in {"x86_64", "amd64", "i386", "i686"}
SEQUENCE_BYTES = 8  # the uint64 sequence word in front of the record
# A write takes about a microsecond, so a reader first retries at once (a sleep, even sleep(0),
# can cost the 50 us of Linux timer slack); only then does it yield to a preempted writer.
SPIN_ATTEMPTS = 100


class TornRead(Exception):
    """No consistent copy within the time allowed: the writer is stuck mid-write (or died)."""


class SeqlockRecord:
    """A seqlock-protected record of ``dtype`` at ``offset`` in ``buffer``.

    Layout: [uint64 sequence][record]. The sequence counts writes twice (odd while writing).
    """

    def __init__(self, buffer, offset: int, dtype: np.dtype):
        self.dtype = np.dtype(dtype)
        self._sequence = np.ndarray((1,), np.uint64, buffer, offset)
        self._record = np.ndarray((1,), self.dtype, buffer, offset + SEQUENCE_BYTES)
        self._bytes = np.ndarray((self.dtype.itemsize,), np.uint8, buffer, offset + SEQUENCE_BYTES)

    @staticmethod
    def size(dtype: np.dtype) -> int:
        """Bytes the record takes, sequence word included."""
        return SEQUENCE_BYTES + np.dtype(dtype).itemsize

    @property
    def sequence(self) -> int:
        """The raw sequence word (odd while a write is in progress)."""
        return int(self._sequence[0])

    @contextmanager
    def writing(self) -> Iterator[np.ndarray]:
        """Writer only: yields the shared record (shape (1,)) to fill in place. If the body
        raises, the record stays marked mid-write (readers get TornRead) until the next write."""
        sequence = int(self._sequence[0]) | 1  # odd now (and after a writer that died mid-write)
        self._sequence[0] = sequence
        yield self._record
        self._sequence[0] = sequence + 1

    def write(self, record: np.ndarray) -> None:
        """Writer only: publish ``record`` (shape (1,), this dtype) with one memcpy, which keeps
        the window in which readers must retry to about a microsecond."""
        source = record.view(np.uint8)
        sequence = int(self._sequence[0]) | 1  # odd now (and after a writer that died mid-write)
        self._sequence[0] = sequence
        self._bytes[:] = source
        self._sequence[0] = sequence + 1

    def read(self, timeout_s: float, monotonic: Callable[[], float] = time.monotonic
             ) -> np.ndarray:
        """A consistent copy of the record (shape (1,), the caller's to keep). TornRead when
        none could be taken within ``timeout_s``: only once an attempt that started after the
        deadline failed too, so a reader preempted for longer than that (a loaded machine)
        takes its copy when it runs again instead of blaming the writer."""
        deadline = None
        attempts = 0
        while True:
            late = deadline is not None and monotonic() > deadline
            before = int(self._sequence[0])
            if not before & 1:
                copy = self._record.copy()
                if int(self._sequence[0]) == before:
                    return copy
            if late:
                raise TornRead(f"record still being written after {timeout_s * 1e3:.0f} ms")
            attempts += 1
            if deadline is None:
                deadline = monotonic() + timeout_s
            if attempts > SPIN_ATTEMPTS:
                time.sleep(0)  # the writer was preempted mid-write: give its core back

    def release(self) -> None:
        """Drop the views into the buffer so its owner can be closed."""
        del self._sequence, self._record, self._bytes
