"""The DecisionServer's end of an MCAP recording's writer process (recording_writer). No gRPC.

`RemoteMcapFile` looks like recording_mcap.McapFile to the recorder, but only serializes each
message and sends it on, a batch per `flush()`: the MCAP writer's records, CRCs and zstd
chunks, and the stereo video, run in the writer, a process with a GIL of its own, started at
ordinary scheduling and BACKGROUND_NICE (priority.start_in_background) so that on a busy
machine it waits, not the command path.

The server opens the partial file itself, so a directory it cannot write in fails
StartRecording at once, and hands the descriptor to the writer with one end of a socket pair:
`in_a_process` (the DecisionServer's), or recording_writer.on_a_thread, the same writer in this
process (the unit tests', which start no process).
The messages on it are recording_writer's (its docstring). The writer says when writing fails
(a full disk); the next `flush()` raises it as an OSError, which ends the recording as a failed
write in the server always did.
"""

from __future__ import annotations

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


def in_a_process(connection: socket.socket, file) -> subprocess.Popen:
    """The writer in a process of its own, at ordinary scheduling and BACKGROUND_NICE, given
    its end of the connection and the file."""
    argv = [sys.executable, "-m", WRITER_MODULE, str(connection.fileno()), str(file.fileno())]
    return start_in_background(lambda: subprocess.Popen(
        argv, pass_fds=(connection.fileno(), file.fileno()), stdin=subprocess.DEVNULL))


WriterStart = Callable[[socket.socket, object], object]


class RemoteMcapFile:
    """An MCAP file being written by a writer of its own, which `start` starts. `video` (a
    CameraSource, or None): the camera whose stream the writer records beside the messages.
    Not thread-safe: the recorder's drain thread alone calls it."""

    def __init__(self, path: Path, video=None, start: WriterStart = in_a_process):
        self.path = Path(path)
        self.counts: Counter[str] = Counter()  # what was sent; the writer's own, once finished
        self._batch: list[tuple] = []
        file = open(self.path, "wb")  # noqa: SIM115 - the writer's from now on
        ours, theirs = socket.socketpair()
        try:
            self._process = start(theirs, file)
        except BaseException:
            ours.close()
            self.path.unlink(missing_ok=True)
            raise
        finally:
            file.close()
            theirs.close()
        self._connection = Connection(ours.detach())
        # The writer's answers, read as they come so that each flush only looks at a field.
        self._failure: str | None = None
        self._finished: dict | None = None
        self._answered = threading.Event()  # finished, failed or gone
        threading.Thread(target=self._listen, name="recording-writer-answers",
                         daemon=True).start()
        self._send(("open", video))

    def write(self, topic: str, message, log_time_ns: int,
              publish_time_ns: int | None = None) -> None:
        self._batch.append((topic, type(message).DESCRIPTOR.full_name,
                            message.SerializeToString(), int(log_time_ns),
                            int(publish_time_ns or 0)))
        self.counts[topic] += 1

    def metadata(self, name: str, data: dict[str, str]) -> None:
        """A metadata record, after the messages written before it."""
        self.flush()
        self._send(("metadata", name, data))

    def flush(self) -> None:
        """Send what was written since the last; OSError if the writer said writing failed,
        or is gone."""
        self._check()
        if self._batch:
            batch, self._batch = self._batch, []
            self._send(("messages", batch))

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
