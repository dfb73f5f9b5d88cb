"""Calls between a station's processes on one host without gRPC: one protobuf request and one
reply per call, over a Unix seqpacket socket.

Every Teleoperate command crosses the DecisionServer -> ProxyRobot hop. As a gRPC unary call in
Python that hop costs about 0.65 ms at p50 with nothing to do, and several thread hand-overs
(grpcio's polling threads on both sides). Over this socket it costs under 0.1 ms: a send and a
receive on the caller's own thread, and one waiting thread on the server's
(docs/performance.md, "The local call").

- A packet is one message: the request is the full method name
  (/telerobot.v1.ProxyRobot/MoveCartesianIncremental), a NUL, then the serialized request; the
  reply is a byte OK (0) and the serialized response, or ERROR (1) and a google.rpc.Status
  with a google.rpc.ErrorInfo, as gRPC's rich errors carry them. The caller gets the same
  TelerobotError it would have got over gRPC.
- Access is the socket file's: it is made owner-only (0600), in a directory of the station's
  own, as the station's shared memory is. Each call answered can be told to an audit log,
  with the caller's user id from the socket's peer credentials.
- A caller's call waits at most `timeout_s`. A call whose request went out and whose reply did
  not come back (the server died or timed out) is never sent again: a move may have been
  applied (UNAVAILABLE LOCAL_CALL_LOST, or DEADLINE_EXCEEDED). Only a request that could not
  be sent at all is sent again, once, on a new connection (the server restarted since the
  last call); if that fails too, the error's reason is NOT_SENT, and the caller may send it
  another way.
"""

from __future__ import annotations

import contextlib
import logging
import os
import socket
import struct
import threading
from collections.abc import Callable
from pathlib import Path

from google.protobuf.message import DecodeError, Message
from google.rpc import code_pb2, error_details_pb2, status_pb2

from wire.addresses import env_name
from wire.errors import (
    DeadlineExceededError,
    InternalError,
    InvalidArgumentError,
    TelerobotError,
    UnavailableError,
    UnimplementedError,
    error_for_status,
)

log = logging.getLogger(__name__)

# Where ProxyRobot answers its moves on this host (its --local-calls, the DecisionServer's
# --proxy-robot-local-calls): `make serve` sets it for every station.
LOCAL_CALLS_ENV = env_name("proxy_robot", "local_calls")

OK, ERROR = 0, 1
# The reason of an UnavailableError whose request never left: nothing was applied.
NOT_SENT = "LOCAL_CALL_UNAVAILABLE"
MAX_PACKET = 1 << 16
ERROR_DOMAIN = "telerobot.v1"


def encode_error(error: TelerobotError) -> bytes:
    status = status_pb2.Status(code=code_pb2.Code.Value(error.status_name),
                               message=error.message)
    if error.reason:
        status.details.add().Pack(error_details_pb2.ErrorInfo(reason=error.reason,
                                                              domain=ERROR_DOMAIN))
    return bytes([ERROR]) + status.SerializeToString()


def decode_error(body: bytes, method: str) -> TelerobotError:
    status = status_pb2.Status.FromString(body)
    reason = None
    for detail in status.details:
        info = error_details_pb2.ErrorInfo()
        if detail.Unpack(info):
            reason = info.reason
    return error_for_status(code_pb2.Code.Name(status.code), status.message, reason,
                            method=method)


# A method the server answers: its request type, and the handler that turns a request into its
# response (or raises a TelerobotError).
Handler = tuple[type[Message], Callable[[Message], Message]]


def method_path(service, name: str) -> str:
    """A method's full name, as gRPC writes it: method_path(ProxyRobot's descriptor,
    "MoveCartesianIncremental") -> "/telerobot.v1.ProxyRobot/MoveCartesianIncremental"."""
    return f"/{service.full_name}/{service.methods_by_name[name].name}"


# Told of each call answered: its method, its outcome (OK or the error's status name) and the
# user id of the process that called (the socket's peer credentials). It must not raise.
Answered = Callable[[str, str, int], None]


class LocalCallServer:
    """Answers `methods` (full method name -> Handler) on the socket at `path`: a thread
    accepts, and a thread per connection reads a request, calls its handler and replies, then
    tells `on_answered` (an audit log's hook) if set. Threads start from the thread that calls
    `start`, so they share its scheduling (a real-time service's, at SCHED_FIFO)."""

    def __init__(self, path: str | Path, methods: dict[str, Handler]):
        self.path = Path(path)
        self.on_answered: Answered | None = None
        self._methods = methods
        self._listener: socket.socket | None = None
        self._connections: set[socket.socket] = set()
        self._lock = threading.Lock()
        self._closed = threading.Event()

    def start(self) -> None:
        with contextlib.suppress(FileNotFoundError):
            self.path.unlink()  # a socket left by a process that died
        listener = socket.socket(socket.AF_UNIX, socket.SOCK_SEQPACKET)
        old_umask = os.umask(0o177)  # owner-only from the moment it exists
        try:
            listener.bind(str(self.path))
        finally:
            os.umask(old_umask)
        listener.listen(8)
        self._listener = listener
        threading.Thread(target=self._accept, name="local-calls", daemon=True).start()
        log.info("local calls on %s: %s", self.path, ", ".join(self._methods))

    def stop(self) -> None:
        self._closed.set()
        with self._lock:
            sockets = [s for s in (self._listener, *self._connections) if s is not None]
        for sock in sockets:
            with contextlib.suppress(OSError):
                sock.shutdown(socket.SHUT_RDWR)
            sock.close()
        with contextlib.suppress(FileNotFoundError):
            self.path.unlink()

    def _accept(self) -> None:
        while not self._closed.is_set():
            try:
                connection, _ = self._listener.accept()
            except OSError:
                return  # stopped
            with self._lock:
                if self._closed.is_set():
                    connection.close()
                    return
                self._connections.add(connection)
            threading.Thread(target=self._serve, args=(connection,), name="local-call",
                             daemon=True).start()

    def _serve(self, connection: socket.socket) -> None:
        try:
            _, peer_uid, _ = struct.unpack("3i", connection.getsockopt(
                socket.SOL_SOCKET, socket.SO_PEERCRED, struct.calcsize("3i")))
            while True:
                try:
                    packet = connection.recv(MAX_PACKET)
                except OSError:
                    return
                if not packet:
                    return  # the caller closed
                method, reply, outcome = self._answer(packet)
                try:
                    connection.send(reply)
                except OSError:
                    return
                finally:  # answered, whether the reply reached the caller or not
                    if self.on_answered is not None:
                        self.on_answered(method, outcome, peer_uid)
        finally:
            with self._lock:
                self._connections.discard(connection)
            connection.close()

    def answer(self, packet: bytes) -> bytes:
        """The reply to one request packet."""
        return self._answer(packet)[1]

    def _answer(self, packet: bytes) -> tuple[str, bytes, str]:
        """The method asked for, the reply, and its outcome (OK or the error's status)."""
        name, _, body = packet.partition(b"\0")
        method = name.decode("ascii", "replace")
        try:
            if method not in self._methods:
                raise UnimplementedError(f"{method} is not served on the local socket",
                                         reason="NOT_LOCAL")
            request_type, handler = self._methods[method]
            try:
                request = request_type.FromString(body)
            except DecodeError as error:
                raise InvalidArgumentError(f"the request does not decode: {error}",
                                           reason="BAD_REQUEST") from None
            return method, bytes([OK]) + handler(request).SerializeToString(), "OK"
        except TelerobotError as error:
            return method, encode_error(error), error.status_name
        except Exception as error:  # a bug: said, and the caller gets it, never a dead socket
            log.exception("local call %s failed", method)
            return method, encode_error(InternalError(f"{method} failed: {error!r}")), "INTERNAL"


class LocalCallClient:
    """Calls a LocalCallServer at `path`: one call at a time (callers queue on a lock), each
    waiting at most `timeout_s`. Connects on the first call, and again after the server
    went away."""

    def __init__(self, path: str | Path, timeout_s: float):
        self.path = Path(path)
        self.timeout_s = timeout_s  # each call's, from its next connection on
        self._socket: socket.socket | None = None
        self._lock = threading.Lock()

    def call(self, method: str, request: Message, response_type: type[Message]) -> Message:
        packet = method.encode("ascii") + b"\0" + request.SerializeToString()
        with self._lock:
            reply = self._exchange(method, packet)
        if reply[:1] == bytes([OK]):
            return response_type.FromString(reply[1:])
        raise decode_error(reply[1:], method)

    def close(self) -> None:
        with self._lock:
            self._disconnect()

    def _exchange(self, method: str, packet: bytes) -> bytes:
        fresh = self._socket is None
        sock = self._connect(method)
        try:
            sock.send(packet)
        except OSError as error:
            self._disconnect()
            if fresh:
                raise self._unavailable(method, error) from None
            sock = self._connect(method)  # not sent: the server restarted since the last call
            try:
                sock.send(packet)
            except OSError as error:
                self._disconnect()
                raise self._unavailable(method, error) from None
        try:
            reply = sock.recv(MAX_PACKET)
        except TimeoutError:
            self._disconnect()  # its late reply must not answer the next call
            raise DeadlineExceededError(
                f"{method}: no reply on {self.path} within {self.timeout_s * 1e3:.0f} ms",
                reason="LOCAL_CALL_TIMEOUT", method=method) from None
        except OSError as error:
            self._disconnect()
            raise self._lost(method, error.strerror or str(error)) from None
        if not reply:
            self._disconnect()
            raise self._lost(method, "the server closed the socket")
        return reply

    def _connect(self, method: str) -> socket.socket:
        if self._socket is None:
            sock = socket.socket(socket.AF_UNIX, socket.SOCK_SEQPACKET)
            sock.settimeout(self.timeout_s)
            try:
                sock.connect(str(self.path))
            except OSError as error:
                sock.close()
                raise self._unavailable(method, error) from None
            self._socket = sock
        return self._socket

    def _disconnect(self) -> None:
        if self._socket is not None:
            self._socket.close()
            self._socket = None

    def _unavailable(self, method: str, error: OSError) -> UnavailableError:
        """The request was not sent: the caller may send it another way."""
        return UnavailableError(f"{method}: {self.path}: {error.strerror or error}",
                                reason=NOT_SENT, method=method)

    def _lost(self, method: str, why: str) -> UnavailableError:
        return UnavailableError(f"{method}: {why} on {self.path} before it replied (the call "
                                "may have been applied)", reason="LOCAL_CALL_LOST",
                                method=method)
