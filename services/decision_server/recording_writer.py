"""python -m services.decision_server.recording_writer CONNECTION_FD: the process that writes
one MCAP recording, started by the DecisionServer ahead of it (writer_process.WriterProcesses).

It waits on CONNECTION_FD (a socket) for pickled tuples:
- ("open", camera): first, then the file's descriptor (SCM_RIGHTS), which it writes; `camera`,
  a CameraSource or None, is the stereo camera whose H.264 stream it records beside the rest
  (header once, then every pair from the first key frame, at its capture time);
- ("messages", [(topic, type name, serialized message, log time ns, publish time ns), ...],
  increments, acks): the last two packed by the command path (recording_records), made
  messages here;
- ("metadata", name, data): a metadata record (a gap's);
- ("finish", metadata): the video stopped first, the "recording" metadata and the summary
  written and synced; answers ("finished", counts by channel), then exits;
- ("abandon",): the file closed unfinished, then exits.
When writing fails it answers ("failed", why) at once and writes nothing more. When the
server's end closes (the server died) it exits with the file as it is: the partial file a
crash leaves.
"""

from __future__ import annotations

import logging
import os
import socket
import subprocess
import sys
import threading
import time
from multiprocessing.connection import Connection

from google.protobuf import descriptor_pool, message_factory

from services.decision_server.camera_feed import CameraSource
from services.decision_server.recording_mcap import (
    ACK,
    INCREMENT,
    STEREO_HEADER,
    STEREO_VIDEO,
    McapFile,
    increment_message,
)
from services.decision_server.recording_records import unpack_acks, unpack_increments
from telerobot.v1.decision_server_pb2 import CommandAck
from wire import convert
from wire.foxglove_video import stereo_video

log = logging.getLogger("recording_writer")


class Writer:
    """The file, written from the connection's messages and from the camera's thread."""

    def __init__(self, connection: socket.socket):
        self._socket = connection
        self._connection = Connection(os.dup(connection.fileno()))
        self._file: McapFile | None = None  # once opened
        self._lock = threading.Lock()  # the file: the messages' and the video's
        self._failed = False
        self._types: dict[str, type] = {}  # message classes by full name
        self._header = None  # the stereo stream's, once written
        self._keyed = False  # the video starts at the stream's first key frame
        self._stop_video = lambda: None

    def run(self) -> None:
        try:
            while True:
                request = self._connection.recv()
                if self._handle(request):
                    return
        except EOFError:  # the server is gone: the partial file stays as it is
            self._stop_video()
            if self._file is not None:
                self._file.abandon()
        finally:
            self._connection.close()
            self._socket.close()

    def _handle(self, request) -> bool:
        """Act on one request; True when it was the last."""
        kind = request[0]
        if kind == "open":
            _, [descriptor], _, _ = socket.recv_fds(self._socket, 1, 1)
            self._file = McapFile(os.fdopen(descriptor, "wb"))
            self._open_video(request[1])
        elif kind in ("finish", "abandon"):
            self._stop_video()
            with self._lock:
                if kind == "finish" and not self._failed:
                    self._write(lambda: self._file.finish(request[1]))
                    if not self._failed:
                        self._connection.send(("finished", dict(self._file.counts)))
                        return True
                self._file.abandon()
            return True
        elif not self._failed:
            with self._lock:
                self._write(lambda: self._record(request))
        return False

    def _record(self, request) -> None:
        if request[0] == "metadata":
            self._file.metadata(request[1], request[2])
            return
        _, batch, increments, acks = request
        for topic, type_name, data, log_time, publish_time in batch:
            self._file.write_serialized(topic, self._type(type_name), data, log_time,
                                        publish_time or None)
        for log_time, fields in unpack_increments(increments):
            self._file.write(INCREMENT, increment_message(*fields), log_time)
        for received, data in unpack_acks(acks):
            ack = CommandAck.FromString(data)  # published at its apply time
            self._file.write_serialized(ACK, CommandAck, data, received,
                                        convert.time_ns(ack.apply_time) or received)
        self._file.flush()  # a full disk shows up now, not at the end

    def _type(self, name: str) -> type:
        """The message class of a full name (any of the protos this process imported)."""
        if name not in self._types:
            self._types[name] = message_factory.GetMessageClass(
                descriptor_pool.Default().FindMessageTypeByName(name))
        return self._types[name]

    def _write(self, write) -> None:
        """With the lock held: `write()`, a failure said once."""
        try:
            write()
        except Exception as error:  # noqa: BLE001 - any failure to write ends the recording
            self._failed = True
            log.warning("writing the recording failed: %s", error)
            self._connection.send(("failed", str(error)))

    def _open_video(self, camera: CameraSource | None) -> None:
        """The camera's feed (its module imported with this one's, before any recording: the
        "open" message only unpickles the CameraSource)."""
        if camera is None:
            return
        feed, channel = camera.open()
        stop = feed(self._video)

        def stop_video() -> None:
            stop()
            channel.close()

        self._stop_video = stop_video

    def _video(self, header, pair) -> None:
        """A stream's header once, then its frames from its first key frame, each at its
        capture time (both eyes share it)."""
        captured = convert.time_ns(pair.left_capture_time) or time.time_ns()
        with self._lock:
            if self._failed:
                return
            if header != self._header:
                self._header = header
                self._keyed = False
                self._write(lambda: self._file.write(STEREO_HEADER, header, captured))
            self._keyed |= pair.keyframe
            if self._keyed:
                self._write(lambda: self._file.write(STEREO_VIDEO, stereo_video(pair),
                                                     captured))


class _WriterThread:
    """The writer on a thread of this process, with a process's poll() and wait()."""

    def __init__(self, connection: socket.socket):
        writer = Writer(connection)
        self._thread = threading.Thread(target=writer.run, name="recording-writer",
                                        daemon=True)
        self._thread.start()

    def poll(self) -> int | None:
        return None if self._thread.is_alive() else 0

    def wait(self, timeout: float | None = None) -> int:
        self._thread.join(timeout)
        if self._thread.is_alive():
            raise subprocess.TimeoutExpired("recording-writer", timeout)
        return 0

    def kill(self) -> None:
        pass  # a thread cannot be killed: it ends when its connection closes


def on_a_thread() -> tuple[socket.socket, _WriterThread]:
    """A writer on a thread of this process (a writer_process.WriterStart): the same code as
    in WriterProcesses', no process (the unit tests')."""
    ours, theirs = socket.socketpair()
    return ours, _WriterThread(theirs)


def main(argv: list[str]) -> int:
    logging.basicConfig(level=logging.WARNING, stream=sys.stderr,
                        format="%(asctime)s recording_writer %(levelname)s %(message)s")
    Writer(socket.socket(fileno=int(argv[0]))).run()
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
