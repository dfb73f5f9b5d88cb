"""The DecisionServer's end of an MCAP recording's writer process (recording_writer). No gRPC.

`RemoteMcapFile` looks like recording_mcap.McapFile to the recorder, but only serializes each
message and sends it on, a batch per `flush()` with the increments and acks the command path
packed (`write_packed`): building those messages, the MCAP writer's records, CRCs and zstd
chunks, and the stereo video, run in the writer, a process with a GIL of its own, started at
ordinary scheduling and BACKGROUND_NICE (priority.start_in_background) so that on a busy
machine it waits, not the command path.

Writers are started ahead (WriterProcesses), each with one end of a socket pair; a recording
takes one. The server opens the partial file itself, so a directory it cannot write in fails
StartRecording at once, and hands the descriptor over the socket (SCM_RIGHTS). The messages on
the socket are recording_writer's (its docstring). The writer says when writing fails (a full
disk), and its end closes when it dies; the next `flush()` raises either as an OSError, which
ends the recording as any failed write does. recording_writer.on_a_thread is the same writer on
a thread of this process (the unit tests', which start no process).
"""

from __future__ import annotations

import os
import socket
import subprocess
import sys
import threading
from collections import Counter
from collections.abc import Callable
from multiprocessing.connection import Connection
from pathlib import Path

from services.runtime.priority import start_in_background

WRITER_MODULE = "services.decision_server.recording_writer"
# How long the end of a recording may take the writer: the last chunk compressed and synced.
FINISH_TIMEOUT_S = 30.0
EXIT_TIMEOUT_S = 5.0


class WriterProcesses:
    """Writers in processes of their own, at ordinary scheduling and BACKGROUND_NICE, one kept
    started ahead: a recording takes a writer that has already imported what it needs (about
    half a second of CPU on a busy 2-core machine), so its video starts with it. The next one
    starts when that recording's writer has exited, so that its imports never share the
    machine with a recording. `warm()` starts the first before any recording (the
    DecisionServer does at its start); else the first recording starts its own."""

    def __init__(self):
        self._lock = threading.Lock()
        self._spare: tuple[socket.socket, subprocess.Popen] | None = None
        self._closed = False

    def warm(self) -> None:
        with self._lock:
            if self._spare is None and not self._closed:
                self._spare = self._start()

    def __call__(self) -> tuple[socket.socket, subprocess.Popen]:
        """A started writer (our end of its connection, its process); the next is started
        once it has exited."""
        with self._lock:
            taken, self._spare = self._spare, None
            if taken is not None and taken[1].poll() is not None:  # it died waiting
                taken[0].close()
                taken = None
            taken = taken or self._start()
        threading.Thread(target=self._warm_after, args=(taken[1],), name="recording-writer-next",
                         daemon=True).start()
        return taken

    def _warm_after(self, process: subprocess.Popen) -> None:
        process.wait()
        with self._lock:
            if not self._closed and self._spare is None:
                self._spare = self._start()

    def close(self) -> None:
        """The spare stops (its connection closes), and no other is started."""
        with self._lock:
            self._closed = True
            if self._spare is not None:
                self._spare[0].close()
                self._spare[1].wait(EXIT_TIMEOUT_S)
                self._spare = None

    @staticmethod
    def _start() -> tuple[socket.socket, subprocess.Popen]:
        ours, theirs = socket.socketpair()
        argv = [sys.executable, "-m", WRITER_MODULE, str(theirs.fileno())]
        try:
            process = start_in_background(lambda: subprocess.Popen(
                argv, pass_fds=(theirs.fileno(),), stdin=subprocess.DEVNULL))
        except BaseException:
            ours.close()
            raise
        finally:
            theirs.close()
        return ours, process


# Gives a started writer: our end of its connection and a handle with a process's poll(),
# wait() and kill() (a WriterProcesses, or recording_writer.on_a_thread).
WriterStart = Callable[[], tuple[socket.socket, object]]


class RemoteMcapFile:
    """An MCAP file being written by a writer of its own, which `start` starts. `video` (a
    CameraSource, or None): the camera whose stream the writer records beside the messages.
    Not thread-safe: the recorder's drain thread alone calls it."""

    def __init__(self, path: Path, video, start: WriterStart):
        self.path = Path(path)
        self.counts: Counter[str] = Counter()  # what was sent; the writer's own, once finished
        self._batch: list[tuple] = []
        self._increments, self._acks = bytearray(), bytearray()  # recording_records' packing
        with open(self.path, "wb") as file:  # the writer's, once handed over
            ours = None
            try:
                ours, self._process = start()
                self._connection = Connection(os.dup(ours.fileno()))
                self._send(("open", video))
                socket.send_fds(ours, [b"F"], [file.fileno()])
            except BaseException:
                self.path.unlink(missing_ok=True)
                raise
            finally:
                if ours is not None:
                    ours.close()
        # The writer's answers, read as they come so that each flush only looks at a field.
        self._failure: str | None = None
        self._finished: dict | None = None
        self._answered = threading.Event()  # finished, failed or gone
        threading.Thread(target=self._listen, name="recording-writer-answers",
                         daemon=True).start()

    def write(self, topic: str, message, log_time_ns: int,
              publish_time_ns: int | None = None) -> None:
        self._batch.append((topic, type(message).DESCRIPTOR.full_name,
                            message.SerializeToString(), int(log_time_ns),
                            int(publish_time_ns or 0)))
        self.counts[topic] += 1

    def write_packed(self, increments: bytes, acks: bytes, counts: dict[str, int]) -> None:
        """Increments and acks packed by the command path (recording_records), which the
        writer unpacks and makes messages; `counts`: how many, by channel."""
        self._increments += increments
        self._acks += acks
        self.counts.update(counts)

    def metadata(self, name: str, data: dict[str, str]) -> None:
        """A metadata record, after the messages written before it."""
        self.flush()
        self._send(("metadata", name, data))

    def flush(self) -> None:
        """Send what was written since the last; OSError if the writer said writing failed,
        or is gone."""
        self._check()
        if self._batch or self._increments or self._acks:
            message = ("messages", self._batch, self._increments, self._acks)
            self._batch, self._increments, self._acks = [], bytearray(), bytearray()
            self._send(message)

    def finish(self, metadata: dict[str, str]) -> None:
        """The end of the file (McapFile.finish, in the writer), waited for; `counts` are then
        the writer's, the video's included. OSError if it failed."""
        try:
            self.flush()
            self._send(("finish", metadata))
            if not self._answered.wait(FINISH_TIMEOUT_S):
                raise OSError(f"the recording's writer did not finish within "
                              f"{FINISH_TIMEOUT_S:.0f} s")
            self._check()
            self.counts = Counter(self._finished)
        finally:
            self._close()

    def abandon(self) -> None:
        """Stop writing; the writer closes the file without finishing it (the caller deletes
        it)."""
        try:
            self._send(("abandon",))
        except OSError:
            pass  # gone already
        self._close()

    # -- the pipe ---------------------------------------------------------------------------
    def _send(self, message) -> None:
        try:
            self._connection.send(message)
        except (OSError, ValueError) as error:  # ValueError: closed already
            raise OSError(f"the recording's writer is gone ({self._exit_status()}): "
                          f"{error}") from error

    def _listen(self) -> None:
        """The writer's answers: ("failed", why) whenever writing fails, ("finished", counts)
        at the end; its end closing means it is gone."""
        try:
            while True:
                answer = self._connection.recv()
                if answer[0] == "failed":
                    self._failure = answer[1]
                    self._answered.set()
                elif answer[0] == "finished":
                    self._finished = answer[1]
                    self._answered.set()
                    return
        except (EOFError, OSError):
            if self._failure is None and self._finished is None:
                self._failure = f"the recording's writer is gone ({self._exit_status()})"
            self._answered.set()

    def _check(self) -> None:
        if self._failure is not None:
            raise OSError(self._failure)

    def _exit_status(self) -> str:
        code = self._process.poll()
        return "still running" if code is None else f"exit status {code}"

    def _close(self) -> None:
        try:
            self._process.wait(EXIT_TIMEOUT_S)
        except subprocess.TimeoutExpired:
            self._process.kill()
            self._process.wait()
        self._connection.close()
