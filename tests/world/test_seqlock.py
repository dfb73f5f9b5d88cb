"""The seqlock: readers in another process never see a torn record; a stuck writer is reported."""

from __future__ import annotations

import subprocess
import sys
import textwrap
import time
from multiprocessing import shared_memory

import numpy as np
import pytest

from services.world.seqlock import SeqlockRecord, TornRead
from tests.processes import REPO, unique_shm_name

pytestmark = pytest.mark.e2e

# A big record, so that an unprotected copy would very likely catch the writer half-way.
DTYPE = np.dtype([("counter", "u8"), ("values", "f8", (2048,))])
READ_S = 0.5

WRITER = textwrap.dedent("""
    import sys, time
    import numpy as np
    from services.world.seqlock import SeqlockRecord
    from services.world.shm_layout import attach_untracked
    from tests.world.test_seqlock import DTYPE

    shm = attach_untracked(sys.argv[1])
    record = SeqlockRecord(shm.buf, 0, DTYPE)
    local = np.zeros(1, DTYPE)
    print("writing", flush=True)
    n, deadline = 0, time.monotonic() + float(sys.argv[2])
    while time.monotonic() < deadline:
        n += 1
        local["counter"] = n
        local["values"] = float(n)  # the invariant: every value equals the counter
        record.write(local)
    record.release()
    shm.close()
""")


@pytest.fixture
def segment():
    shm = shared_memory.SharedMemory(unique_shm_name(), create=True,
                                     size=SeqlockRecord.size(DTYPE))
    yield shm
    shm.close()
    shm.unlink()


def test_a_reader_never_sees_a_torn_record_from_a_writer_process(segment) -> None:
    writer = subprocess.Popen([sys.executable, "-c", WRITER, segment.name, str(READ_S + 5.0)],
                              cwd=REPO, stdout=subprocess.PIPE, text=True)
    try:
        assert writer.stdout.readline().strip() == "writing"
        record = SeqlockRecord(segment.buf, 0, DTYPE)
        counters, deadline = set(), time.monotonic() + READ_S
        while time.monotonic() < deadline:
            copy = record.read(timeout_s=1.0)[0]
            counter = int(copy["counter"])
            assert np.all(copy["values"] == counter), f"torn record at counter {counter}"
            counters.add(counter)
        record.release()
    finally:
        writer.kill()
        writer.wait()
    assert len(counters) > 10  # the writer really was writing while we read


def test_a_writer_stuck_mid_write_is_reported_not_waited_for(segment) -> None:
    record = SeqlockRecord(segment.buf, 0, DTYPE)
    writing = record.writing()
    writing.__enter__()  # a writer that stops (or dies) half-way
    assert record.sequence % 2 == 1
    with pytest.raises(TornRead):
        record.read(timeout_s=0.01)
    writing.__exit__(None, None, None)
    assert record.read(timeout_s=0.01)["counter"][0] == 0
    record.release()


def test_a_new_writer_recovers_from_one_that_died_mid_write(segment) -> None:
    record = SeqlockRecord(segment.buf, 0, DTYPE)
    record.writing().__enter__()  # dies without finishing
    local = np.zeros(1, DTYPE)
    local["counter"] = 7
    record.write(local)
    assert record.sequence % 2 == 0
    assert record.read(timeout_s=0.01)["counter"][0] == 7
    record.release()


def test_a_reader_preempted_while_it_retried_takes_its_copy_when_it_runs_again(segment) -> None:
    """The writer was mid-write; the reader lost its core for longer than its timeout, and the
    writer finished meanwhile. Only a try that starts after the deadline and fails too means a
    stuck writer."""
    record = SeqlockRecord(segment.buf, 0, DTYPE)
    writing = record.writing()
    writing.__enter__()
    times = iter([0.0, 0.2])  # the deadline is set at 0.0; the reader next runs at 0.2

    def preempted_clock() -> float:
        now = next(times)
        if now > 0.0:
            writing.__exit__(None, None, None)  # the writer ran while the reader was off its core
        return now

    copy = record.read(timeout_s=0.05, monotonic=preempted_clock)
    assert record.sequence % 2 == 0 and copy.shape == (1,)
