"""The MCAP recordings' writer processes (recording_writer, writer_process): one is started
ahead of each recording, once the last one's has exited; they run at ordinary scheduling and
BACKGROUND_NICE even when the server's threads are real-time, write what the server sends,
and a writer that dies ends the recording with the reason while nothing else stops."""

from __future__ import annotations

import os
import signal
import threading
from pathlib import Path

import numpy as np
import pytest

from services.decision_server import recording_mcap
from services.decision_server.recordings import RecordingStore
from services.decision_server.writer_process import WriterProcesses
from services.runtime.priority import BACKGROUND_NICE
from telerobot.v1 import decision_server_pb2 as pb
from tests.conftest import wait_for
from wire.errors import FailedPreconditionError

pytestmark = pytest.mark.e2e


def _writers() -> list[int]:
    """The pids of this process's recording writers."""
    pids = []
    for entry in Path("/proc").iterdir():
        try:
            if not entry.name.isdigit() or int(
                    (entry / "stat").read_text().rsplit(")", 1)[1].split()[1]) != os.getpid():
                continue
            if b"recording_writer" in (entry / "cmdline").read_bytes():
                pids.append(int(entry.name))
        except OSError:
            continue  # gone meanwhile
    return pids


def _on_a_real_time_thread(body):
    """`body()` on a thread at SCHED_FIFO 1, as the DecisionServer's threads run; its result."""
    outcome = []

    def run():
        try:
            os.sched_setscheduler(0, os.SCHED_FIFO, os.sched_param(1))
        except OSError as error:
            outcome.append(error)
            return
        outcome.append(body())

    thread = threading.Thread(target=run)
    thread.start()
    thread.join(60)
    if isinstance(outcome[0], OSError):
        pytest.skip(f"no SCHED_FIFO here: {outcome[0]}")
    return outcome[0]


@pytest.fixture
def writers():
    writers = WriterProcesses()
    yield writers
    writers.close()


@pytest.fixture
def ours():
    """The pids of the recording writers started during the test (a station that other tests
    share, in this process, keeps a writer of its own ready)."""
    before = set(_writers())
    return lambda: [pid for pid in _writers() if pid not in before]


def test_the_writers_run_below_a_real_time_server_and_write_what_they_are_sent(tmp_path,
                                                                                writers, ours):
    store = RecordingStore(tmp_path, writer=writers)

    def record():
        writers.warm()  # as the DecisionServer does at its start
        [ahead] = wait_for(ours, 10, "the writer started ahead")
        store.start("low", "MCAP")
        assert ours() == [ahead]  # the recording took it; the next waits for its end
        return ahead, os.sched_getscheduler(ahead), os.getpriority(os.PRIO_PROCESS, ahead)

    recording, *scheduling = _on_a_real_time_thread(record)
    assert scheduling == [os.SCHED_OTHER, BACKGROUND_NICE]
    for i in range(5):
        store.add("BASE", np.array([0.001, 0.0, 0.0]), np.eye(3), np.array([0.5, 0.0, i]))
        store.note_ack(pb.CommandAck(sequence=i + 1))
    assert store.stop().command_count == 5
    [following] = wait_for(lambda: [p for p in ours() if p != recording], 10,
                           "the next writer, once the recording's has exited")
    assert recording not in ours()  # it ended with the recording
    assert (os.sched_getscheduler(following), os.getpriority(os.PRIO_PROCESS, following)) == (
        os.SCHED_OTHER, BACKGROUND_NICE)  # started from a real-time thread too
    assert [c.target_position_m[2] for c in store.load("low")[1]] == [0, 1, 2, 3, 4]
    counts = recording_mcap.read_summary(tmp_path / "low.mcap")["counts"]
    assert '"/recording/ack": 5' in counts
    writers.close()
    assert not ours()


def test_a_writer_that_dies_ends_the_recording_with_the_reason(tmp_path, writers, ours):
    store = RecordingStore(tmp_path, writer=writers)
    failed = []
    store.on_failed = lambda name, why: failed.append((name, why))
    store.start("lost", "MCAP")
    [pid] = wait_for(ours, 10, "the writer process")
    os.kill(pid, signal.SIGKILL)

    def stopped() -> bool:
        store.add("BASE", np.zeros(3), np.eye(3), np.zeros(3))  # the server goes on
        return bool(failed)

    wait_for(stopped, 10, "the recording to stop by itself")
    assert failed[0][0] == "lost" and "writer is gone" in failed[0][1]
    assert not store.recording
    with pytest.raises(FailedPreconditionError, match="writer is gone") as error:
        store.stop()
    assert error.value.reason == "RECORDING_FAILED"
    assert not list(tmp_path.iterdir())  # nothing half-written is left
    store.start("next", "MCAP")  # the next recording has a writer of its own, a live one
    assert store.stop().command_count == 0
