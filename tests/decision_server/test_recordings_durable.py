"""Recordings that are not lost (issue #31): a JSONL recording is on disk as it runs, so a crash
loses only its last moments and the restarted server keeps the rest; a writer that falls behind
keeps its file, with the gap counted and recorded, instead of deleting it."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import threading
from pathlib import Path

import numpy as np
import pytest
from mcap.reader import make_reader

from services.decision_server import recording_mcap, recordings
from services.decision_server.recording_writer import on_a_thread
from services.decision_server.recordings import RecordingStore
from telerobot.v1 import decision_server_pb2 as pb
from tests.conftest import wait_for
from tests.fakes.clock import FakeClock
from wire.errors import FailedPreconditionError

REPO = Path(__file__).resolve().parents[2]


def _add(store: RecordingStore, clock: FakeClock, count: int, start: int = 0) -> None:
    for i in range(start, start + count):
        store.add("BASE", np.array([0.001 * i, 0.0, 0.0]), np.eye(3), np.array([0.5, 0.0, i]))
        clock.advance(0.01)


def _lines(path: Path) -> list[str]:
    return path.read_text().splitlines() if path.exists() else []


@pytest.fixture
def clock():
    return FakeClock()


def test_a_jsonl_recording_is_on_disk_as_it_runs_and_survives_a_crash(tmp_path, clock):
    """What the disk holds mid-recording (copied as a crash would leave it, a torn line at its
    end) becomes the recording when the next store opens the directory."""
    store = RecordingStore(tmp_path / "live", clock)
    store.start("crashed")
    _add(store, clock, 5)
    partial = tmp_path / "live" / "crashed.jsonl.partial"
    wait_for(lambda: len(_lines(partial)) == 1 + 5, what="the five increments on disk")
    crashed = tmp_path / "after_the_crash"
    crashed.mkdir()
    torn = partial.read_bytes() + b'{"offset_s": 0.05, "frame": "BA'  # cut mid-write
    (crashed / partial.name).write_bytes(torn)
    store.stop()  # (ends the live store's writer)

    restarted = RecordingStore(crashed, clock)
    assert not (crashed / partial.name).exists()
    [info] = restarted.list()
    assert (info.name, info.format, info.command_count, info.error) == (
        "crashed", "JSONL", 5, "")
    assert info.duration_s == pytest.approx(0.04)
    _, commands = restarted.load("crashed")
    assert [c.target_position_m[2] for c in commands] == [0, 1, 2, 3, 4]
    assert (crashed / "crashed.jsonl").read_bytes() == torn[:torn.rindex(b"\n") + 1]


def test_the_partial_files_left_are_recovered_unless_their_name_is_taken(tmp_path, clock):
    (tmp_path / "taken.jsonl").write_text('{"name": "taken", "create_time_ns": 1}\n')
    (tmp_path / "taken.jsonl.partial").write_text('{"name": "taken", "create_time_ns": 2}\n')
    (tmp_path / "free.jsonl.partial").write_text('{"name": "free", "create_time_ns": 3}\n')
    store = RecordingStore(tmp_path, clock, on_a_thread)
    assert (tmp_path / "taken.jsonl.partial").exists()
    assert [(i.name, i.create_time_ns, i.error) for i in store.list()] == [
        ("free", 3, ""), ("taken", 1, "")]


def test_stopping_a_jsonl_recording_syncs_it_to_the_disk(tmp_path, clock, monkeypatch):
    synced = []
    real_fsync = os.fsync
    monkeypatch.setattr(os, "fsync", lambda fd: synced.append(fd) or real_fsync(fd))
    store = RecordingStore(tmp_path, clock, on_a_thread)
    store.start("synced")
    _add(store, clock, 3)
    assert store.stop().command_count == 3
    assert len(synced) >= 2  # the file, then the directory after the rename
    assert len(_lines(tmp_path / "synced.jsonl")) == 1 + 3


@pytest.mark.e2e
def test_a_killed_server_keeps_what_it_recorded(tmp_path):
    """A process recording JSONL is killed (SIGKILL) mid-recording: the next store on its
    directory finds every increment the process had recorded a moment before."""
    script = (
        "import sys, numpy as np\n"
        "from services.decision_server.recordings import RecordingStore\n"
        "store = RecordingStore(sys.argv[1])\n"
        "store.start('killed')\n"
        "for i in range(40):\n"
        "    store.add('BASE', np.zeros(3), np.eye(3), np.array([0.5, 0.0, i]))\n"
        "print('recorded', flush=True)\n"
        "sys.stdin.read()\n")  # until killed
    process = subprocess.Popen([sys.executable, "-c", script, str(tmp_path)], cwd=REPO,
                               stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
    try:
        assert process.stdout.readline().strip() == "recorded"
        partial = tmp_path / "killed.jsonl.partial"
        wait_for(lambda: len(_lines(partial)) == 1 + 40, 10, "the increments on disk")
    finally:
        process.send_signal(signal.SIGKILL)
        process.wait(10)
    assert process.returncode == -signal.SIGKILL
    store = RecordingStore(tmp_path)
    _, commands = store.load("killed")
    assert [c.target_position_m[2] for c in commands] == list(range(40))


# -- a writer that falls behind --------------------------------------------------------------

class Blocked:
    """Holds the writer thread in its first write of an event until `release()`."""

    def __init__(self):
        self.writing = threading.Event()
        self._released = threading.Event()

    def __call__(self, event):
        self.writing.set()
        self._released.wait(10)
        return None  # the event is left out of the file

    def release(self) -> None:
        self._released.set()


def _metadata(path: Path) -> list[tuple[str, dict]]:
    with open(path, "rb") as stream:
        return [(record.name, dict(record.metadata))
                for record in make_reader(stream).iter_metadata()]


def _increments(path: Path) -> int:
    with open(path, "rb") as stream:
        return sum(1 for _ in make_reader(stream).iter_messages(
            topics=[recording_mcap.INCREMENT]))


def test_an_mcap_writer_that_falls_behind_keeps_its_file_with_the_gap(tmp_path, clock,
                                                                       monkeypatch):
    """The writer stalls; the server goes on: past the limit new messages are dropped and
    counted. The file is kept, with what was written, the gap (a metadata record) and the
    counts; a replay of it is refused, as it lost increments."""
    monkeypatch.setattr(recording_mcap, "QUEUE_LIMIT", 10)
    store = RecordingStore(tmp_path, clock, on_a_thread)
    store.event_to_message = blocked = Blocked()
    store.start("behind", "MCAP")
    store.note_event(object())
    assert blocked.writing.wait(5)
    _add(store, clock, 30)  # 19 fit beside the event (increments have 2 x 10), 11 do not
    for sequence in range(5):
        store.note_ack(pb.CommandAck(sequence=sequence))  # all dropped: the gap is open
    blocked.release()
    info = store.stop()

    assert (info.command_count, info.format) == (19, "MCAP")
    assert "lost 11 increments" in info.error
    path = tmp_path / "behind.mcap"
    assert _increments(path) == 19
    records = dict(_metadata(path))
    dropped = {recording_mcap.INCREMENT: 11, recording_mcap.ACK: 5}
    assert json.loads(records["recording"]["dropped"]) == dropped
    assert json.loads(records[recording_mcap.GAP]["dropped"]) == dropped
    assert int(records[recording_mcap.GAP]["first_ns"]) <= int(
        records[recording_mcap.GAP]["last_ns"])
    with pytest.raises(FailedPreconditionError, match="lost 11 increments") as error:
        store.load("behind")
    assert error.value.reason == "INCOMPLETE_RECORDING"
    [listed] = store.list()
    assert listed.command_count == 19 and "lost 11 increments" in listed.error


def test_a_stalled_mcap_writer_drops_acks_before_increments(tmp_path, clock, monkeypatch):
    monkeypatch.setattr(recording_mcap, "QUEUE_LIMIT", 10)
    store = RecordingStore(tmp_path, clock, on_a_thread)
    store.event_to_message = blocked = Blocked()
    store.start("acks", "MCAP")
    store.note_event(object())
    assert blocked.writing.wait(5)
    for sequence in range(15):
        store.note_ack(pb.CommandAck(sequence=sequence))  # 9 fit, 6 dropped
    _add(store, clock, 5)  # increments have room still
    blocked.release()
    info = store.stop()
    assert (info.command_count, info.error) == (5, "")
    path = tmp_path / "acks.mcap"
    assert json.loads(dict(_metadata(path))["recording"]["dropped"]) == {
        recording_mcap.ACK: 6}
    assert len(store.load("acks")[1]) == 5  # complete: it replays


def test_a_jsonl_writer_that_falls_behind_keeps_its_file_with_a_gap_line(tmp_path, clock,
                                                                          monkeypatch):
    monkeypatch.setattr(recording_mcap, "QUEUE_LIMIT", 5)
    writing, released = threading.Event(), threading.Event()
    to_json = recordings.RecordedCommand.to_json

    def slow_to_json(command):  # the first line written holds the writer
        if not writing.is_set():
            writing.set()
            released.wait(10)
        return to_json(command)

    monkeypatch.setattr(recordings.RecordedCommand, "to_json", slow_to_json)
    store = RecordingStore(tmp_path, clock, on_a_thread)
    store.start("gap")
    _add(store, clock, 1)
    assert writing.wait(5)
    _add(store, clock, 15, start=1)  # 9 fit beside the first (2 x 5), 6 do not
    released.set()
    info = store.stop()
    assert info.command_count == 10 and "lost 6 increments" in info.error
    lines = _lines(tmp_path / "gap.jsonl")
    gaps = [json.loads(line)["gap"] for line in lines if line.startswith('{"gap"')]
    assert len(lines) == 1 + 10 + 1 and gaps[0]["dropped"] == {recording_mcap.INCREMENT: 6}
    with pytest.raises(FailedPreconditionError) as error:
        store.load("gap")
    assert error.value.reason == "INCOMPLETE_RECORDING"
    assert "lost 6 increments" in store.info("gap").error
