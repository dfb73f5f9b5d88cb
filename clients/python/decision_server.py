"""DecisionServer clients: the operator's one address, with the control lease and Teleoperate.

``DecisionClient`` (blocking) and ``AsyncDecisionClient`` (asyncio) have the same methods.

The lease: ``acquire_control(...)`` returns a `Lease` and keeps it; from then on every call of
this client and of its facades (``client.robot``, ``client.sensor``, ``client.camera``, the
ProxyRobot, ForceSensor and StereoCamera services on the same port) carries its id in the
``telerobot-lease-id`` metadata, which is what commanding calls need. ``release_control()``
drops it; closing the client releases a lease it still holds (``release_on_close``). The lease
is not renewed in the background: every authorized call renews it, and an operator who only
watches calls ``renew_control()`` within the lease (5 s by default). A lease that lapsed gets
NOT_FOUND on renew and FAILED_PRECONDITION on commands: acquire again (explicitly).

Teleoperate: ``client.teleoperate(...)`` opens the bidirectional stream with its Init, waits
for the server's Ready and returns a session:

- ``send(ΔX, ΔM=None, clutch=False) -> Ack`` sends one MasterCommand and blocks until its ack;
- ``send_nowait(...) -> sequence`` sends without waiting (pipelining: the acks still come, in
  order, to ``latest_ack`` and to the ``on_ack`` callback, which runs on the reader thread, or
  in the event loop for the async session: keep it short);
- ``heartbeat() -> Ack`` / ``heartbeat_nowait()`` feed the watchdog while the operator holds
  still;
- ``close()`` half-closes the stream (the server then holds the arm: that is the watchdog's
  "stream ended").

The blocking session reads acks on a background thread (so a `timeout` applies to each ack, and
sends can be pipelined); the async session does the same with a task. An ack that does not come
within its timeout raises DeadlineExceededError and the stream stays open. When the stream ends
with an error (ABORTED when the lease is lost, INVALID_ARGUMENT for a malformed message), every
later call on the session raises that error: the session is over, open a new one. Nothing is
ever resent: a command is sent exactly once.

Returns: `Lease`, `Recording`, `Cobegin`, `ActionRun`, `Ack`, `Dependency` (``values.py``);
the proto ``AssistanceConfig`` and ``ControlState`` (nested configuration records, clearest as
protos), and proto ``StreamEventsResponse`` events (their oneof says which event).
"""

from __future__ import annotations

import asyncio
import dataclasses
import logging
import queue
import threading
import time
from collections.abc import Callable, Sequence
from typing import Any

import grpc
import numpy as np

from clients.python.base import DEFAULT_TIMEOUT_S, AsyncClient, SyncClient, run_in_thread
from clients.python.errors import (
    DeadlineExceededError,
    TelerobotRpcError,
    error_for_code,
    from_rpc_error,
)
from clients.python.force_sensor import AsyncForceSensorClient, ForceSensorClient
from clients.python.proxy_robot import (
    AsyncProxyRobotClient,
    ProxyRobotClient,
    cartesian_request,
    joints_request,
)
from clients.python.stereo_camera import AsyncStereoCameraClient, StereoCameraClient
from clients.python.values import (
    Ack,
    ActionRun,
    BusyWork,
    CartesianIncrement,
    Cobegin,
    ControlMode,
    Dependency,
    JointIncrement,
    Lane,
    Lease,
    Recording,
    ReferenceFrame,
    RobotStatus,
    enum_value,
    seconds,
    time_ns,
)
from telerobot.v1 import decision_server_pb2 as pb
from telerobot.v1 import decision_server_pb2_grpc
from wire import convert
from wire.tls import ChannelSecurity

log = logging.getLogger(__name__)

TELEOPERATE_METHOD = "/telerobot.v1.DecisionServer/Teleoperate"
_END = object()  # ends the request iterator: the client half-closes


def _action_request(action, cobegin_id: str, action_id: str) -> pb.RunActionRequest:
    request = pb.RunActionRequest(cobegin_id=cobegin_id, action_id=action_id)
    if isinstance(action, BusyWork):
        request.busy_work.duration.CopyFrom(convert.duration(action.duration_s))
    elif isinstance(action, JointIncrement):
        request.move_joints.CopyFrom(joints_request(action.delta))
    elif isinstance(action, CartesianIncrement):
        request.move_cartesian.CopyFrom(cartesian_request(
            action.delta_position, action.delta_rotation, action.frame))
    else:
        raise TypeError(f"action must be BusyWork, JointIncrement or CartesianIncrement, "
                        f"not {type(action).__name__}")
    return request


def _command(sequence: int, delta_position, delta_rotation, clutch: bool) -> pb.MasterCommand:
    delta_position = np.asarray(delta_position, dtype=float)
    if delta_position.shape != (3,):
        raise ValueError(f"delta_position needs 3 values, got shape {delta_position.shape}")
    command = pb.MasterCommand(sequence=sequence, send_time=convert.timestamp(time.time_ns()),
                               delta_position_m=convert.vector3_to_proto(delta_position),
                               clutch_engaged=bool(clutch))
    if delta_rotation is not None:
        delta_rotation = np.asarray(delta_rotation, dtype=float)
        if delta_rotation.shape != (3, 3):
            raise ValueError(f"delta_rotation must be 3x3, got shape {delta_rotation.shape}")
        command.delta_rotation.CopyFrom(convert.rotation_to_proto(delta_rotation))
    return command


def _init(operator_id: str, lease_id: str, mapping: int | None,
          watchdog_timeout_s: float | None) -> pb.TeleoperateInit:
    init = pb.TeleoperateInit(operator_id=operator_id, lease_id=lease_id,
                              mapping=int(mapping or 0))
    if watchdog_timeout_s:
        init.watchdog_timeout.CopyFrom(convert.duration(watchdog_timeout_s))
    return init


def _again(error: TelerobotRpcError) -> TelerobotRpcError:
    """A fresh copy of a stored stream error, to raise once more."""
    return error_for_code(error.code, error.message, reason=error.reason, domain=error.domain,
                          method=error.method)


class _SessionState:
    """What the sync and async sessions share: the Ready, counters and ack bookkeeping."""

    def _setup(self, default_timeout: float | None, on_ack: Callable[[Ack], Any] | None):
        self.default_timeout = default_timeout
        self.ready: pb.TeleoperateReady | None = None
        self._on_ack = on_ack
        self._sent = 0  # messages after the init
        self._received = 0  # acks received
        self._sequence = 0  # the last command sequence used
        self._latest_ack: Ack | None = None
        self._error: TelerobotRpcError | None = None
        self._closing = False
        self._cancelled = False

    @property
    def session_id(self) -> str:
        return self.ready.session_id if self.ready else ""

    @property
    def mapping(self) -> ReferenceFrame:
        """The mapping frame in force (BASE or TOOL)."""
        return enum_value(ReferenceFrame, self.ready.mapping if self.ready else 0)

    @property
    def watchdog_timeout_s(self) -> float:
        return seconds(self.ready.watchdog_timeout) if self.ready else 0.0

    @property
    def latest_ack(self) -> Ack | None:
        """The newest ack received (any message's), for the slave's latest pose and wrench."""
        return self._latest_ack

    @property
    def error(self) -> TelerobotRpcError | None:
        """The error the stream ended with, if it did."""
        return self._error

    @property
    def sequence(self) -> int:
        """The sequence number of the last command sent."""
        return self._sequence

    def _deliver(self, ack: Ack) -> None:
        self._latest_ack = ack
        if self._on_ack is not None:
            try:
                self._on_ack(ack)
            except Exception:
                log.exception("the on_ack callback failed; the session goes on")

    def _dead(self) -> Exception:
        if self._error is not None:
            return _again(self._error)
        return RuntimeError("the Teleoperate session is closed; open a new one with "
                            "teleoperate()")

    def _ack_timeout(self, what: str, timeout: float | None) -> DeadlineExceededError:
        return DeadlineExceededError(
            grpc.StatusCode.DEADLINE_EXCEEDED,
            f"no ack for {what} within {timeout} s (client side); the stream stays open",
            method=TELEOPERATE_METHOD)


class _Waiter:
    def __init__(self):
        self.event = threading.Event()
        self.ack: Ack | None = None


class TeleopSession(_SessionState):
    """A blocking Teleoperate session; see the module docstring. Make it with
    ``DecisionClient.teleoperate()``. A context manager: leaving it closes the stream."""

    def __init__(self, stub, init: pb.TeleoperateInit, metadata, *, ready_timeout: float | None,
                 default_timeout: float | None, on_ack: Callable[[Ack], Any] | None = None):
        self._setup(default_timeout, on_ack)
        self._lock = threading.Lock()
        self._waiters: dict[int, _Waiter] = {}
        self._requests: queue.SimpleQueue = queue.SimpleQueue()
        self._requests.put(pb.TeleoperateRequest(init=init))
        self._ready_event = threading.Event()
        self._finished = threading.Event()
        self._call = stub.Teleoperate(iter(self._requests.get, _END), metadata=metadata)
        self._reader = run_in_thread(self._read, "teleoperate-acks")
        if not self._ready_event.wait(ready_timeout):
            self._abandon()
            raise DeadlineExceededError(
                grpc.StatusCode.DEADLINE_EXCEEDED,
                f"the server sent no Ready within {ready_timeout} s (client side)",
                method=TELEOPERATE_METHOD)
        if self.ready is None:
            self._abandon()
            raise self._dead()

    # -- the reader thread ----------------------------------------------------------------------
    def _read(self) -> None:
        try:
            for reply in self._call:
                if reply.WhichOneof("message") == "ready":
                    self.ready = reply.ready
                    self._ready_event.set()
                    continue
                ack = Ack.from_proto(reply.ack, time.time_ns())
                with self._lock:
                    self._received += 1
                    waiter = self._waiters.pop(self._received, None)
                if waiter is not None:
                    waiter.ack = ack
                    waiter.event.set()
                self._deliver(ack)
        except grpc.RpcError as error:
            if not (self._cancelled and error.code() == grpc.StatusCode.CANCELLED):
                self._error = from_rpc_error(error, TELEOPERATE_METHOD)
        finally:
            self._requests.put(_END)  # frees gRPC's thread that waits for our next message
            self._finished.set()
            self._ready_event.set()
            with self._lock:
                waiters, self._waiters = list(self._waiters.values()), {}
            for waiter in waiters:
                waiter.event.set()

    # -- sending --------------------------------------------------------------------------------
    def _submit(self, build: Callable[[], pb.TeleoperateRequest], waiter: _Waiter | None
                ) -> tuple[int, pb.TeleoperateRequest]:
        """Queue one message; returns its index among the messages after the init (its ack is
        the index-th) and the message."""
        with self._lock:
            if self._closing or self._finished.is_set():
                raise self._dead()
            request = build()
            self._sent += 1
            if waiter is not None:
                self._waiters[self._sent] = waiter
            self._requests.put(request)  # under the lock: queue order == index order
            return self._sent, request

    def _wait(self, index: int, waiter: _Waiter, what: str, timeout: float | None) -> Ack:
        timeout = self.default_timeout if timeout is None else timeout
        if not waiter.event.wait(timeout):
            with self._lock:
                self._waiters.pop(index, None)
            if waiter.ack is None:
                raise self._ack_timeout(what, timeout)
        if waiter.ack is None:
            raise self._dead()
        return waiter.ack

    def _command_builder(self, delta_position, delta_rotation, clutch):
        _command(0, delta_position, delta_rotation, clutch)  # check the shapes before sending

        def build():
            self._sequence += 1
            return pb.TeleoperateRequest(command=_command(self._sequence, delta_position,
                                                          delta_rotation, clutch))
        return build

    def send(self, delta_position: Sequence[float] | np.ndarray,
             delta_rotation: np.ndarray | None = None, clutch: bool = False, *,
             timeout: float | None = None) -> Ack:
        """Send one increment (ΔX in metres, ΔM a 3x3 rotation or None, in the session's
        mapping frame; `clutch` asks the server to index it) and block until its ack."""
        waiter = _Waiter()
        index, request = self._submit(
            self._command_builder(delta_position, delta_rotation, clutch), waiter)
        return self._wait(index, waiter, f"command {request.command.sequence}", timeout)

    def send_nowait(self, delta_position: Sequence[float] | np.ndarray,
                    delta_rotation: np.ndarray | None = None, clutch: bool = False) -> int:
        """Send one increment without waiting; returns its sequence number. Its ack goes to
        ``latest_ack`` and ``on_ack``."""
        _, request = self._submit(
            self._command_builder(delta_position, delta_rotation, clutch), None)
        return request.command.sequence

    def heartbeat(self, *, timeout: float | None = None) -> Ack:
        """Feed the watchdog and block until the ack (outcome HEARTBEAT)."""
        waiter = _Waiter()
        index, _ = self._submit(self._heartbeat, waiter)
        return self._wait(index, waiter, "a heartbeat", timeout)

    def heartbeat_nowait(self) -> None:
        self._submit(self._heartbeat, None)

    @staticmethod
    def _heartbeat() -> pb.TeleoperateRequest:
        return pb.TeleoperateRequest(heartbeat=pb.Heartbeat(
            send_time=convert.timestamp(time.time_ns())))

    # -- ending ---------------------------------------------------------------------------------
    @property
    def closed(self) -> bool:
        return self._closing or self._finished.is_set()

    def close(self, timeout: float | None = None) -> None:
        """Half-close the stream and wait (up to `timeout`, default the session's) for the
        server to end it; cancel it if it does not. Idempotent; never raises."""
        with self._lock:
            if self._closing:
                return
            self._closing = True
            self._requests.put(_END)
        wait = self.default_timeout if timeout is None else timeout
        if not self._finished.wait(wait):
            self._abandon()

    def _abandon(self) -> None:
        self._closing = True
        self._cancelled = True
        self._requests.put(_END)  # unblocks gRPC's request thread
        self._call.cancel()
        self._finished.wait(1.0)

    def __enter__(self):
        return self

    def __exit__(self, *exc) -> None:
        self.close()


class AsyncTeleopSession(_SessionState):
    """An asyncio Teleoperate session: the same methods as `TeleopSession`, awaited. Make it
    with ``await AsyncDecisionClient.teleoperate()``; ``async with`` closes it."""

    def __init__(self, call, *, default_timeout: float | None,
                 on_ack: Callable[[Ack], Any] | None):
        self._setup(default_timeout, on_ack)
        self._call = call
        self._write_lock = asyncio.Lock()
        self._waiters: dict[int, asyncio.Future] = {}
        self._ready: asyncio.Future = asyncio.get_running_loop().create_future()
        self._reader: asyncio.Task | None = None

    @classmethod
    async def open(cls, stub, init: pb.TeleoperateInit, metadata, *,
                   ready_timeout: float | None, default_timeout: float | None,
                   on_ack: Callable[[Ack], Any] | None = None) -> AsyncTeleopSession:
        session = cls(stub.Teleoperate(metadata=metadata), default_timeout=default_timeout,
                      on_ack=on_ack)
        session._reader = asyncio.create_task(session._read())
        try:
            await session._call.write(pb.TeleoperateRequest(init=init))
        except grpc.aio.AioRpcError:
            pass  # the reader reports the stream's error
        try:
            await asyncio.wait_for(asyncio.shield(session._ready), ready_timeout)
        except TimeoutError:
            await session._abandon()
            raise DeadlineExceededError(
                grpc.StatusCode.DEADLINE_EXCEEDED,
                f"the server sent no Ready within {ready_timeout} s (client side)",
                method=TELEOPERATE_METHOD) from None
        if session.ready is None:
            await session._abandon()
            raise session._dead()
        return session

    async def _read(self) -> None:
        try:
            while True:
                reply = await self._call.read()
                if reply is grpc.aio.EOF:
                    break
                if reply.WhichOneof("message") == "ready":
                    self.ready = reply.ready
                    if not self._ready.done():
                        self._ready.set_result(None)
                    continue
                ack = Ack.from_proto(reply.ack, time.time_ns())
                self._received += 1
                future = self._waiters.pop(self._received, None)
                if future is not None and not future.done():
                    future.set_result(ack)
                self._deliver(ack)
        except grpc.aio.AioRpcError as error:
            if not (self._cancelled and error.code() == grpc.StatusCode.CANCELLED):
                self._error = from_rpc_error(error, TELEOPERATE_METHOD)
        except asyncio.CancelledError:
            if not self._cancelled:
                raise
        finally:
            self._closing = True
            if not self._ready.done():
                self._ready.set_result(None)
            waiters, self._waiters = list(self._waiters.values()), {}
            for future in waiters:
                if not future.done():
                    future.set_result(None)

    async def _submit(self, build: Callable[[], pb.TeleoperateRequest],
                      future: asyncio.Future | None) -> tuple[int, pb.TeleoperateRequest]:
        async with self._write_lock:
            if self._closing:
                raise self._dead()
            request = build()
            self._sent += 1
            index = self._sent
            if future is not None:
                self._waiters[index] = future
            try:
                await self._call.write(request)
            except (grpc.aio.AioRpcError, grpc.aio.UsageError, asyncio.InvalidStateError):
                self._waiters.pop(index, None)
                if self._reader is not None:
                    await asyncio.wait({self._reader}, timeout=1.0)
                raise self._dead() from None
            return index, request

    async def _wait(self, index: int, future: asyncio.Future, what: str,
                    timeout: float | None) -> Ack:
        timeout = self.default_timeout if timeout is None else timeout
        try:
            ack = await asyncio.wait_for(asyncio.shield(future), timeout)
        except TimeoutError:
            self._waiters.pop(index, None)
            raise self._ack_timeout(what, timeout) from None
        if ack is None:
            raise self._dead()
        return ack

    _command_builder = TeleopSession._command_builder

    async def send(self, delta_position: Sequence[float] | np.ndarray,
                   delta_rotation: np.ndarray | None = None, clutch: bool = False, *,
                   timeout: float | None = None) -> Ack:
        future = asyncio.get_running_loop().create_future()
        index, request = await self._submit(
            self._command_builder(delta_position, delta_rotation, clutch), future)
        return await self._wait(index, future, f"command {request.command.sequence}", timeout)

    async def send_nowait(self, delta_position: Sequence[float] | np.ndarray,
                          delta_rotation: np.ndarray | None = None, clutch: bool = False) -> int:
        """Write one increment without waiting for its ack; returns its sequence number."""
        _, request = await self._submit(
            self._command_builder(delta_position, delta_rotation, clutch), None)
        return request.command.sequence

    async def heartbeat(self, *, timeout: float | None = None) -> Ack:
        future = asyncio.get_running_loop().create_future()
        index, _ = await self._submit(TeleopSession._heartbeat, future)
        return await self._wait(index, future, "a heartbeat", timeout)

    async def heartbeat_nowait(self) -> None:
        await self._submit(TeleopSession._heartbeat, None)

    @property
    def closed(self) -> bool:
        return self._closing

    async def close(self, timeout: float | None = None) -> None:
        """Half-close the stream and wait for the server to end it; cancel it if it does not.
        Idempotent; never raises."""
        async with self._write_lock:
            if self._closing and (self._reader is None or self._reader.done()):
                return
            self._closing = True
            try:
                await self._call.done_writing()
            except (grpc.aio.AioRpcError, grpc.aio.UsageError, asyncio.InvalidStateError):
                pass
        wait = self.default_timeout if timeout is None else timeout
        if self._reader is not None:
            done, _ = await asyncio.wait({self._reader}, timeout=wait)
            if not done:
                await self._abandon()

    async def _abandon(self) -> None:
        self._closing = True
        self._cancelled = True
        self._call.cancel()
        if self._reader is not None:
            await asyncio.wait({self._reader}, timeout=1.0)

    async def __aenter__(self):
        return self

    async def __aexit__(self, *exc) -> None:
        await self.close()


# -- the clients --------------------------------------------------------------------------------

class _DecisionMethods:
    """The DecisionServer calls; on the async client each returns an awaitable of the same
    value."""

    SERVICE = "telerobot.v1.DecisionServer"
    ADDRESS_NAME = "decision_server"
    STUB = decision_server_pb2_grpc.DecisionServerStub

    def _init_decision(self, release_on_close: bool) -> None:
        self.release_on_close = release_on_close
        self._held: Lease | None = None
        self._facades: dict[str, Any] = {}

    @property
    def lease(self) -> Lease | None:
        """The lease this client holds and sends, or None."""
        return self._held

    def _held_lease_id(self) -> str | None:
        return self._held.lease_id if self._held else None

    # -- control ---------------------------------------------------------------------------------
    def acquire_control(self, operator_id: str, mode: int = ControlMode.EXCLUSIVE, *,
                        group: str = "", wait: bool = False, wait_timeout_s: float = 0.0,
                        lease_duration_s: float = 0.0, timeout: float | None = None,
                        lane: str | None = None) -> Lease:
        """Ask for the control lock; keep and return the `Lease`. With ``wait=True`` the call
        queues fairly for up to `wait_timeout_s` (0: until the call's `timeout`)."""
        request = pb.AcquireControlRequest(operator_id=operator_id, mode=int(mode), group=group,
                                           wait=wait)
        if wait_timeout_s:
            request.wait_timeout.CopyFrom(convert.duration(wait_timeout_s))
        if lease_duration_s:
            request.lease_duration.CopyFrom(convert.duration(lease_duration_s))

        def keep(response: pb.AcquireControlResponse) -> Lease:
            holder = response.operator_id or operator_id  # with TLS: the server's identity
            self._held = Lease(response.lease_id, holder, enum_value(ControlMode, mode),
                               group, time_ns(response.expire_time), response.state)
            return self._held

        return self._unary("AcquireControl", request, keep, timeout, lane)

    def renew_control(self, *, timeout: float | None = None, lane: str | None = None) -> int:
        """Extend the held lease; returns its new expiry (ns). NOT_FOUND once it lapsed."""
        held = self._require_lease()

        def keep(response: pb.RenewControlResponse) -> int:
            expire = time_ns(response.expire_time)
            if self._held is not None and self._held.lease_id == held.lease_id:
                self._held = dataclasses.replace(self._held, expire_time_ns=expire)
            return expire

        return self._unary("RenewControl", pb.RenewControlRequest(lease_id=held.lease_id), keep,
                           timeout, lane)

    def release_control(self, *, timeout: float | None = None, lane: str | None = None
                        ) -> pb.ControlState:
        """Give the held lease up (the arm holds); returns who holds control now."""
        held = self._require_lease()

        def forget(response: pb.ReleaseControlResponse) -> pb.ControlState:
            if self._held is not None and self._held.lease_id == held.lease_id:
                self._held = None
            return response.state

        return self._unary("ReleaseControl", pb.ReleaseControlRequest(lease_id=held.lease_id),
                           forget, timeout, lane)

    def _require_lease(self) -> Lease:
        if self._held is None:
            raise RuntimeError("no lease held: call acquire_control() first")
        return self._held

    def get_control_state(self, *, timeout: float | None = None, lane: str | None = None
                          ) -> pb.ControlState:
        return self._unary("GetControlState", pb.GetControlStateRequest(), lambda r: r.state,
                           timeout, lane)

    # -- assistance ------------------------------------------------------------------------------
    def get_assistance(self, *, timeout: float | None = None, lane: str | None = None
                       ) -> pb.AssistanceConfig:
        return self._unary("GetAssistance", pb.GetAssistanceRequest(), lambda r: r.assistance,
                           timeout, lane)

    def set_assistance(self, assistance: pb.AssistanceConfig, *, timeout: float | None = None,
                       lane: str | None = None) -> pb.AssistanceConfig:
        """Replace the whole assistance configuration; returns the one in force."""
        return self._unary("SetAssistance", pb.SetAssistanceRequest(assistance=assistance),
                           lambda r: r.assistance, timeout, lane)

    def set_indexing(self, engaged: bool, *, timeout: float | None = None,
                     lane: str | None = None) -> bool:
        """Engage or release the server-side clutch; returns whether it is engaged."""
        return self._unary("SetIndexing", pb.SetIndexingRequest(engaged=engaged),
                           lambda r: r.engaged, timeout, lane)

    # -- record and replay -----------------------------------------------------------------------
    def start_recording(self, name: str, *, timeout: float | None = None,
                        lane: str | None = None) -> Recording:
        return self._unary("StartRecording", pb.StartRecordingRequest(name=name),
                           lambda r: Recording.from_proto(r.recording), timeout, lane)

    def stop_recording(self, *, timeout: float | None = None, lane: str | None = None
                       ) -> Recording:
        return self._unary("StopRecording", pb.StopRecordingRequest(),
                           lambda r: Recording.from_proto(r.recording), timeout, lane)

    def list_recordings(self, *, timeout: float | None = None, lane: str | None = None
                        ) -> list[Recording]:
        return self._unary("ListRecordings", pb.ListRecordingsRequest(),
                           lambda r: [Recording.from_proto(x) for x in r.recordings],
                           timeout, lane)

    def delete_recording(self, name: str, *, timeout: float | None = None,
                         lane: str | None = None) -> None:
        return self._unary("DeleteRecording", pb.DeleteRecordingRequest(name=name),
                           lambda r: None, timeout, lane)

    def start_replay(self, name: str, speed: float = 1.0, *, timeout: float | None = None,
                     lane: str | None = None) -> Recording:
        return self._unary("StartReplay", pb.StartReplayRequest(name=name, speed=speed),
                           lambda r: Recording.from_proto(r.recording), timeout, lane)

    def stop_replay(self, *, timeout: float | None = None, lane: str | None = None) -> int:
        """Interrupt the replay; returns the number of commands replayed."""
        return self._unary("StopReplay", pb.StopReplayRequest(), lambda r: r.commands_replayed,
                           timeout, lane)

    # -- cobegin ---------------------------------------------------------------------------------
    def begin_cobegin(self, action_count: int, barrier_timeout_s: float = 0.0, *,
                      timeout: float | None = None, lane: str | None = None) -> Cobegin:
        request = pb.BeginCobeginRequest(action_count=action_count)
        if barrier_timeout_s:
            request.barrier_timeout.CopyFrom(convert.duration(barrier_timeout_s))
        return self._unary("BeginCobegin", request,
                           lambda r: Cobegin(r.cobegin_id, time_ns(r.deadline_time)),
                           timeout, lane)

    def run_action(self, action: BusyWork | JointIncrement | CartesianIncrement, *,
                   cobegin_id: str = "", action_id: str = "", timeout: float | None = None,
                   lane: str | None = None) -> ActionRun:
        """Run one action on `lane`, at once or at its cobegin's barrier; returns when it
        ended."""
        return self._unary("RunAction", _action_request(action, cobegin_id, action_id),
                           lambda r: ActionRun(r.action_id, enum_value(Lane, r.lane),
                                               time_ns(r.arrive_time), time_ns(r.start_time),
                                               time_ns(r.end_time)), timeout, lane)

    # -- dependencies ----------------------------------------------------------------------------
    def get_dependencies(self, *, timeout: float | None = None, lane: str | None = None
                         ) -> list[Dependency]:
        """How each service the DecisionServer depends on is (proxy_robot, force_sensor,
        stereo_camera, emergency_stop): SERVING, NOT_SERVING or RESTARTING, and why. Changes
        also come as ``dependency_changed`` events (`Dependency.from_proto` reads them)."""
        return self._unary("GetDependencies", pb.GetDependenciesRequest(),
                           lambda r: [Dependency.from_proto(d) for d in r.dependencies],
                           timeout, lane)

    # -- events ----------------------------------------------------------------------------------
    def stream_events(self, include_data_received: bool = False, *,
                      timeout: float | None = None, lane: str | None = None):
        """Proto ``StreamEventsResponse`` events until cancelled."""
        return self._server_stream("StreamEvents", pb.StreamEventsRequest(
            include_data_received=include_data_received), lambda r: r, timeout, lane)

    # -- the inherited services on the same port -------------------------------------------------
    def _facade(self, name: str, cls, own_channel: bool = False):
        if name not in self._facades:
            target = self.address if own_channel and self.address else self.channel
            self._facades[name] = cls(target, lease=self._held_lease_id, lane=self.lane,
                                      default_timeout=self.default_timeout,
                                      security=self.security)
        return self._facades[name]

    def emergency_stop(self, reason: str = "", *, timeout: float | None = None,
                       lane: str | None = None) -> RobotStatus:
        """ProxyRobot.EmergencyStop on this port: needs no lock; also stops teleoperation,
        replay and force control."""
        return self.robot.emergency_stop(reason, timeout=timeout, lane=lane)

    def reset(self, *, timeout: float | None = None, lane: str | None = None) -> RobotStatus:
        """ProxyRobot.Reset on this port (needs the lock)."""
        return self.robot.reset(timeout=timeout, lane=lane)


class DecisionClient(_DecisionMethods, SyncClient):
    """Blocking DecisionServer client (and, through ``robot``, ``sensor`` and ``camera``, the
    services forwarded on its port). A context manager: leaving it releases a held lease (if
    ``release_on_close``) and closes the channel."""

    def __init__(self, target: str | grpc.Channel | None = None, *, lane: str | None = None,
                 default_timeout: float | None = DEFAULT_TIMEOUT_S,
                 options: Sequence[tuple[str, Any]] = (), release_on_close: bool = True,
                 security: ChannelSecurity | None = None):
        self._init_decision(release_on_close)
        super().__init__(target, lease=self._held_lease_id, lane=lane,
                         default_timeout=default_timeout, options=options, security=security)

    @property
    def robot(self) -> ProxyRobotClient:
        """ProxyRobot on this port, on this channel, with this client's lease."""
        return self._facade("robot", ProxyRobotClient)

    @property
    def sensor(self) -> ForceSensorClient:
        """ForceSensor on this port, on this channel, with this client's lease."""
        return self._facade("sensor", ForceSensorClient)

    @property
    def camera(self) -> StereoCameraClient:
        """StereoCamera on this port, on its own low-latency channel when this client opened
        its channel from an address."""
        return self._facade("camera", StereoCameraClient, own_channel=True)

    def teleoperate(self, operator_id: str | None = None, mapping: int | None = None, *,
                    watchdog_timeout_s: float | None = None, timeout: float | None = None,
                    on_ack: Callable[[Ack], Any] | None = None) -> TeleopSession:
        """Open a Teleoperate session with the held lease (operator: the lease's, unless given;
        mapping: BASE or TOOL, None keeps the assistance configuration's; watchdog: None is the
        server's 100 ms). Waits up to `timeout` for the Ready; FAILED_PRECONDITION without the
        lock or when the arm is not READY."""
        self._check_open()
        init = _init(operator_id or (self._held.operator_id if self._held else ""),
                     self._held_lease_id() or "", mapping, watchdog_timeout_s)
        return TeleopSession(self._stub, init, self._metadata(None),
                             ready_timeout=self._timeout(timeout),
                             default_timeout=self.default_timeout, on_ack=on_ack)

    def close(self) -> None:
        if self._closed:
            return
        if self.release_on_close and self._held is not None:
            try:
                self.release_control(timeout=1.0)
            except TelerobotRpcError as error:
                log.info("could not release the lease on close: %s", error)
        for facade in self._facades.values():
            facade.close()
        super().close()


class AsyncDecisionClient(_DecisionMethods, AsyncClient):
    """asyncio DecisionServer client: the same methods, awaited; ``async with`` releases a
    held lease (if ``release_on_close``) and closes the channel."""

    def __init__(self, target: str | grpc.aio.Channel | None = None, *,
                 lane: str | None = None, default_timeout: float | None = DEFAULT_TIMEOUT_S,
                 options: Sequence[tuple[str, Any]] = (), release_on_close: bool = True,
                 security: ChannelSecurity | None = None):
        self._init_decision(release_on_close)
        super().__init__(target, lease=self._held_lease_id, lane=lane,
                         default_timeout=default_timeout, options=options, security=security)

    @property
    def robot(self) -> AsyncProxyRobotClient:
        return self._facade("robot", AsyncProxyRobotClient)

    @property
    def sensor(self) -> AsyncForceSensorClient:
        return self._facade("sensor", AsyncForceSensorClient)

    @property
    def camera(self) -> AsyncStereoCameraClient:
        return self._facade("camera", AsyncStereoCameraClient, own_channel=True)

    async def teleoperate(self, operator_id: str | None = None, mapping: int | None = None, *,
                          watchdog_timeout_s: float | None = None,
                          timeout: float | None = None,
                          on_ack: Callable[[Ack], Any] | None = None) -> AsyncTeleopSession:
        """As `DecisionClient.teleoperate`, awaited."""
        self._check_open()
        init = _init(operator_id or (self._held.operator_id if self._held else ""),
                     self._held_lease_id() or "", mapping, watchdog_timeout_s)
        return await AsyncTeleopSession.open(self._stub, init, self._metadata(None),
                                             ready_timeout=self._timeout(timeout),
                                             default_timeout=self.default_timeout,
                                             on_ack=on_ack)

    async def close(self) -> None:
        if self._closed:
            return
        if self.release_on_close and self._held is not None:
            try:
                await self.release_control(timeout=1.0)
            except TelerobotRpcError as error:
                log.info("could not release the lease on close: %s", error)
        for facade in self._facades.values():
            await facade.close()
        await super().close()
