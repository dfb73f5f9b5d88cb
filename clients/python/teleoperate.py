"""Teleoperate sessions, blocking (`TeleopSession`) and asyncio (`AsyncTeleopSession`).

``client.teleoperate(...)`` opens the bidirectional stream with its Init, waits for the
server's Ready and returns a session:

- ``send(ΔX, ΔM=None, clutch=False) -> Ack`` sends one MasterCommand and blocks until its ack;
- ``send_nowait(...) -> sequence`` sends without waiting (pipelining: the acks still come, in
  order, to ``latest_ack`` and to the ``on_ack`` callback, which runs on the reader thread, or
  in the event loop for the async session: keep it short);
- ``heartbeat() -> Ack`` / ``heartbeat_nowait()`` feed the watchdog while the operator holds
  still;
- ``close()`` ends the session (an `end` message, then a half-close; the server then holds
  the arm: that is the watchdog's "stream ended").

The blocking session reads acks on a background thread (so a `timeout` applies to each ack, and
sends can be pipelined); the async session does the same with a task. An ack that does not come
within its timeout raises DeadlineExceededError and the stream stays open. When the stream ends
with an error (ABORTED when the lease is lost, INVALID_ARGUMENT for a malformed message), every
later call on the session raises that error: the session is over, open a new one.

**Resume (blocking session, #14).** When the link breaks (the stream fails UNAVAILABLE: a cut,
a reset, a peer the keepalives found dead), the session does not end: it reconnects, with
backoff from 0.1 s capped at 1 s, and re-opens Teleoperate with ``resume_session_id`` and its
lease, for as long as the server keeps the session (``TeleoperateReady.resume_window``, 10 s by
default). Then it resends, in order and with their sequence numbers, the commands not yet
acked; the server answers the ones it had processed with their first ack instead of applying
them again, so every command sent is applied once and acked once. While the link is down the
arm holds (the server's watchdog), ``interrupted`` is true, ``send``/``send_nowait`` raise
`LinkInterruptedError` (the operator's motion in the meantime is not applied: as with the
clutch, the master re-indexes) and ``heartbeat_nowait`` sends nothing. ``on_link(state,
detail)`` is told "lost", "reconnecting", "resumed" and "gave up". If the session cannot be
resumed (the lease lapsed, the server restarted, the window passed), the session ends with that
error. ``resume=False`` turns this off. The asyncio session does not resume.

**A link slower than the master (blocking session).** Commands sent with ``send_nowait`` that
are still waiting to go when the link takes the next message go as one (clients/python/
outbox.py): the newest sequence carries their composed increment, and each merged command's
ack is that command's ack again, its detail saying so (``merged`` counts them). So the arm is
never driven from a queue of old increments on this side either; the server's own bound on a
command's wait is ``max_command_age`` (MERGED_LATE).

**Clocks.** Every command and heartbeat tells the server when the last command ack arrived
(AckReceipt); from these exchanges the server estimates this machine's clock offset, NTP-style,
and each ack carries it: ``Ack.clock_offset_s`` and ``Ack.sent_to_applied_s`` (send to apply on
one clock, across hosts).
"""

from __future__ import annotations

import asyncio
import logging
import threading
import time
from collections import deque
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any

import grpc
import numpy as np

from clients.python.base import run_in_thread
from clients.python.errors import from_rpc_error
from clients.python.outbox import Outbox, compose_increments
from clients.python.values import Ack, ReferenceFrame, enum_value, seconds
from telerobot.v1 import decision_server_pb2 as pb
from wire import convert
from wire.errors import DeadlineExceededError, TelerobotError, UnavailableError, error_for_status

if TYPE_CHECKING:  # the master's side of TDPA; the client only reads its ledger
    from domain.passivity import MasterPassivity

log = logging.getLogger(__name__)

TELEOPERATE_METHOD = "/telerobot.v1.DecisionServer/Teleoperate"
_END = object()  # ends the request iterator: the client half-closes
_END_MESSAGE = pb.TeleoperateRequest(end=pb.TeleoperateEnd())

# Reconnecting after a cut: the first try at once, then backoff doubling from 0.1 s to at most
# 1 s; each try waits up to RESUME_TRY_S for the server's Ready.
RESUME_BACKOFF_S = (0.1, 1.0)
RESUME_TRY_S = 2.0
DEFAULT_RESUME_WINDOW_S = 10.0  # when the server does not say (an older server)
LINK_STATES = ("lost", "reconnecting", "resumed", "gave up")


class LinkInterruptedError(UnavailableError):
    """The link to the DecisionServer is down and the session is reconnecting: the command was
    not sent (the arm holds). Client side; the session goes on once it resumes."""

    def __init__(self, message: str = "the link to the DecisionServer is down; the session is "
                 "reconnecting and the arm holds", reason: str = "LINK_INTERRUPTED", *,
                 method: str = TELEOPERATE_METHOD, **kwargs):
        super().__init__(message, reason, method=method, **kwargs)


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


def teleoperate_init(operator_id: str, lease_id: str, mapping: int | None,
                     watchdog_timeout_s: float | None, passivity: bool = False,
                     max_command_age_s: float | None = None) -> pb.TeleoperateInit:
    init = pb.TeleoperateInit(operator_id=operator_id, lease_id=lease_id,
                              mapping=int(mapping or 0),
                              passivity=pb.PASSIVITY_TDPA if passivity else pb.PASSIVITY_OFF,
                              grouped_acks=True)
    if watchdog_timeout_s:
        init.watchdog_timeout.CopyFrom(convert.duration(watchdog_timeout_s))
    if max_command_age_s:
        init.max_command_age.CopyFrom(convert.duration(max_command_age_s))
    return init


def acks_in(reply: pb.TeleoperateResponse) -> list[pb.CommandAck]:
    """The acks a reply carries, in order: one (`ack`) or a group (`acks`, which this client
    asks for: fewer messages at high rates); none in a `ready`."""
    kind = reply.WhichOneof("message")
    if kind == "acks":
        return list(reply.acks.acks)
    return [reply.ack] if kind == "ack" else []


def _merged_ack(ack: Ack, sequence: int) -> Ack:
    """The ack of command `sequence`, which the client sent inside `ack`'s command."""
    message = pb.CommandAck()
    message.CopyFrom(ack.message)
    message.sequence = sequence
    message.detail = f"merged by the client into command {ack.sequence}; {ack.detail}".rstrip(
        "; ")
    return Ack.from_proto(message, ack.received_time_ns)


def _again(error: TelerobotError) -> TelerobotError:
    """A fresh copy of a stored stream error, to raise once more."""
    return error_for_status(error.status_name, error.message, error.reason,
                            domain=error.domain, method=error.method)


class _SessionState:
    """What the sync and async sessions share: the Ready, counters and ack bookkeeping."""

    def _setup(self, default_timeout: float | None, on_ack: Callable[[Ack], Any] | None):
        self.default_timeout = default_timeout
        self.ready: pb.TeleoperateReady | None = None
        self._on_ack = on_ack
        self._sent = 0  # messages after the init (resends not counted)
        self._received = 0  # acks received
        self._sequence = 0  # the last command sequence used
        self._latest_ack: Ack | None = None
        self._receipt: pb.AckReceipt | None = None  # the newest command ack's, not yet sent
        self._error: TelerobotError | None = None
        self._closing = False
        self._cancelled = False
        # TDPA's master port (domain.passivity.MasterPassivity), or None. Its ledger
        # goes out with every command and heartbeat; the slave's, from the acks, comes in.
        self.passivity = None

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
    def max_command_age_s(self) -> float:
        return seconds(self.ready.max_command_age) if self.ready else 0.0

    @property
    def latest_ack(self) -> Ack | None:
        """The newest ack received (any message's), for the slave's latest pose and wrench."""
        return self._latest_ack

    @property
    def error(self) -> TelerobotError | None:
        """The error the stream ended with, if it did."""
        return self._error

    @property
    def sequence(self) -> int:
        """The sequence number of the last command sent (= the commands sent: they count from
        one)."""
        return self._sequence

    def _with_receipt(self, request: pb.TeleoperateRequest) -> None:
        """The newest command ack's arrival, on the next command or heartbeat (once)."""
        if self._receipt is not None:
            getattr(request, request.WhichOneof("message")).ack_receipt.CopyFrom(self._receipt)
            self._receipt = None

    def _noted(self, ack: Ack) -> None:
        if ack.sequence:
            self._receipt = pb.AckReceipt(sequence=ack.sequence,
                                          receive_time=convert.timestamp(ack.received_time_ns))

    def _deliver(self, ack: Ack) -> None:
        if self.passivity is not None and ack.message.HasField("slave_energy"):
            self.passivity.heard(ack.message.slave_energy.energy_in_j)
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
            f"no ack for {what} within {timeout} s (client side); the stream stays open",
            method=TELEOPERATE_METHOD)


class _Waiter:
    def __init__(self):
        self.event = threading.Event()
        self.ack: Ack | None = None


class TeleopSession(_SessionState):
    """A blocking Teleoperate session that survives a broken link; see the module docstring.
    Make it with ``DecisionClient.teleoperate()``. A context manager: leaving it closes the
    stream.

    Acks are matched to commands by sequence number, and to heartbeats in order. The reader
    thread owns the stream: it reads acks and, when the link breaks, reconnects and swaps in
    the resumed stream (under `_lock`, so a command is queued either before the resends or
    after them, never in between)."""

    def __init__(self, stub, init: pb.TeleoperateInit, metadata, *, ready_timeout: float | None,
                 default_timeout: float | None, on_ack: Callable[[Ack], Any] | None = None,
                 resume: bool = True, on_link: Callable[[str, str], Any] | None = None,
                 passivity: MasterPassivity | None = None):
        self._setup(default_timeout, on_ack)
        self.passivity = passivity
        self._stub, self._init, self._metadata = stub, init, metadata
        self._resume, self._on_link = resume, on_link
        self._lock = threading.Lock()
        self._command_waiters: dict[int, _Waiter] = {}
        self._heartbeat_waiters: deque[_Waiter] = deque()  # this stream's, oldest first
        self._unacked: dict[int, pb.TeleoperateRequest] = {}  # sent, not acked; in order
        self._merged_into: dict[int, list[int]] = {}  # a sent sequence: the ones it carries
        # Resent commands are never merged: the server may have applied one already, and
        # answers its resend without applying it again; merged into a newer one, it would be.
        self._last_resent = 0
        self._interrupted = False
        # Called with every command and heartbeat queued (not resends), on the sender's thread.
        self.on_request: Callable[[pb.TeleoperateRequest], Any] | None = None
        self.commands_acked = 0  # commands acked once each (a repeated ack is not counted)
        self.commands_applied = 0  # of those, acked APPLIED or MODIFIED
        self.resends = 0  # commands sent again after a resume
        self.resumes = 0
        self.merged = 0  # commands sent inside a newer one (the link was slower than the master)
        self._ready_event = threading.Event()
        self._finished = threading.Event()
        self._stop_reconnecting = threading.Event()
        self._requests = self._outbox()
        self._requests.put(pb.TeleoperateRequest(init=init))
        self._call = stub.Teleoperate(self._requests, metadata=metadata)
        self._reader = run_in_thread(self._read, "teleoperate-acks")
        if not self._ready_event.wait(ready_timeout):
            self._abandon()
            raise DeadlineExceededError(
                f"the server sent no Ready within {ready_timeout} s (client side)",
                method=TELEOPERATE_METHOD)
        if self.ready is None:
            self._abandon()
            raise self._dead()

    # -- the reader thread ----------------------------------------------------------------------
    def _read(self) -> None:
        try:
            while True:
                error = self._drain(self._call)
                if error is None or not self._resumable(error):
                    self._error = error
                    return
                if not self._reconnect(error):
                    return
        finally:
            self._requests.put(_END)  # frees gRPC's thread that waits for our next message
            self._interrupted = False  # over, not reconnecting: a send raises why
            self._finished.set()
            self._ready_event.set()
            with self._lock:
                waiters = [*self._command_waiters.values(), *self._heartbeat_waiters]
                self._command_waiters, self._heartbeat_waiters = {}, deque()
            for waiter in waiters:
                waiter.event.set()

    def _drain(self, call) -> TelerobotError | None:
        """Reads `call` to its end: None when it ended cleanly, else its error."""
        try:
            for reply in call:
                if reply.WhichOneof("message") == "ready":
                    self.ready = reply.ready
                    self._ready_event.set()
                arrived = time.time_ns()
                for ack in acks_in(reply):
                    self._on_reply(Ack.from_proto(ack, arrived))
            return None
        except grpc.RpcError as error:
            if self._cancelled and error.code() == grpc.StatusCode.CANCELLED:
                return None
            return from_rpc_error(error, TELEOPERATE_METHOD)

    def _on_reply(self, ack: Ack) -> None:
        with self._lock:
            self._received += 1
            if ack.sequence:
                if self._unacked.pop(ack.sequence, None) is None:
                    return  # acked already (a resend raced its first ack): once is enough
                acks = [_merged_ack(ack, sequence)
                        for sequence in self._merged_into.pop(ack.sequence, [])] + [ack]
                self.commands_acked += len(acks)
                self.commands_applied += ack.applied * len(acks)
                waiter = self._command_waiters.pop(ack.sequence, None)
                self._noted(ack)
            else:
                acks = [ack]
                waiter = self._heartbeat_waiters.popleft() if self._heartbeat_waiters else None
        if waiter is not None:
            waiter.ack = ack
            waiter.event.set()
        for each in acks:
            self._deliver(each)

    # -- merging what waits to be sent --------------------------------------------------------
    def _outbox(self) -> Outbox:
        box: Outbox = Outbox(_END, self._mergeable, lambda run: self._merge(run, box))
        return box

    def _mergeable(self, request) -> bool:
        """A motion command nobody blocks on (send_nowait's), sent for the first time."""
        return (isinstance(request, pb.TeleoperateRequest)
                and request.WhichOneof("message") == "command"
                and not request.command.clutch_engaged
                and request.command.sequence > self._last_resent
                and request.command.sequence not in self._command_waiters)

    def _merge(self, run: list[pb.TeleoperateRequest], box: Outbox) -> pb.TeleoperateRequest:
        """One command for `run` (consecutive commands waiting together): the newest's, with
        their composed increment and the newest energy and receipt among them."""
        frame = "TOOL" if self.mapping == ReferenceFrame.TOOL else "BASE"
        dx, dm = compose_increments(
            [(convert.vector3_value(r.command.delta_position_m),
              convert.rotation_value(r.command.delta_rotation)) for r in run], frame)
        merged = pb.TeleoperateRequest()
        merged.CopyFrom(run[-1])
        merged.command.delta_position_m.CopyFrom(convert.vector3_to_proto(dx))
        merged.command.delta_rotation.CopyFrom(convert.rotation_to_proto(dm))
        receipt = next((r.command.ack_receipt for r in reversed(run)
                        if r.command.HasField("ack_receipt")), None)
        if receipt is not None:
            merged.command.ack_receipt.CopyFrom(receipt)
        with self._lock:
            if box is self._requests:  # (a stream a resume replaced: its commands were resent)
                older = [r.command.sequence for r in run[:-1]]  # (never resends: see above)
                for sequence in older:
                    self._unacked.pop(sequence, None)
                self.merged += len(older)
                self._unacked[merged.command.sequence] = merged  # what a resume would resend
                self._merged_into[merged.command.sequence] = older
        return merged

    def _resumable(self, error: TelerobotError) -> bool:
        return (self._resume and self.ready is not None and not self._closing
                and error.code == grpc.StatusCode.UNAVAILABLE)

    # -- resuming -------------------------------------------------------------------------------
    def _reconnect(self, lost: TelerobotError) -> bool:
        """Re-open the session after `lost` broke its stream; False (the error stored) when it
        cannot be resumed."""
        with self._lock:
            self._interrupted = True
            waiters, self._heartbeat_waiters = list(self._heartbeat_waiters), deque()
        for waiter in waiters:  # a heartbeat's ack is not worth a resend: they fail now
            waiter.event.set()
        self._link("lost", lost.message)
        window = seconds(self.ready.resume_window) or DEFAULT_RESUME_WINDOW_S
        deadline = time.monotonic() + window
        init = pb.TeleoperateInit(operator_id=self._init.operator_id,
                                  lease_id=self._init.lease_id,
                                  resume_session_id=self.session_id,
                                  grouped_acks=self._init.grouped_acks)
        delay, tries = 0.0, 0
        while (left := deadline - time.monotonic()) > 0 and not self._closing:
            if self._stop_reconnecting.wait(min(delay, left)):
                break
            tries += 1
            self._link("reconnecting", f"try {tries}")
            refused = self._try_resume(init, min(RESUME_TRY_S, max(left, 0.1)))
            if refused is None:
                self._link("resumed", f"after {window - left:.1f} s and {tries} tries; "
                           f"{self.resends} commands resent so far")
                return True
            if refused.code not in (grpc.StatusCode.UNAVAILABLE,
                                    grpc.StatusCode.DEADLINE_EXCEEDED):
                self._error = refused  # the lease or the session is gone: no use retrying
                self._link("gave up", refused.message)
                return False
            delay = min(max(2 * delay, RESUME_BACKOFF_S[0]), RESUME_BACKOFF_S[1])
        if self._closing:
            return False
        self._error = UnavailableError(
            f"the link to the DecisionServer broke ({lost.message}) and did not come back "
            f"within the session's {window:.0f} s resume window", reason="LINK_LOST",
            method=TELEOPERATE_METHOD)
        self._link("gave up", self._error.message)
        return False

    def _try_resume(self, init: pb.TeleoperateInit, wait_s: float
                    ) -> TelerobotError | None:
        """One try: a new stream that resumes the session; None once it serves the session
        (the unacked commands queued on it), else why not."""
        requests = self._outbox()
        requests.put(pb.TeleoperateRequest(init=init))
        call = self._stub.Teleoperate(requests, metadata=self._metadata, wait_for_ready=True)
        guard, outcome = threading.Lock(), {"ready": False, "expired": False}

        def expire() -> None:  # no Ready in time: give this try up (atomically with its Ready)
            with guard:
                if not outcome["ready"]:
                    outcome["expired"] = True
                    call.cancel()

        timer = threading.Timer(wait_s, expire)
        timer.start()
        try:
            reply = next(call)
            with guard:
                outcome["ready"] = not outcome["expired"]
        except (grpc.RpcError, StopIteration) as error:
            requests.put(_END)
            if outcome["expired"] or not isinstance(error, grpc.RpcError):
                return DeadlineExceededError(f"no Ready within {wait_s:.1f} s",
                                             method=TELEOPERATE_METHOD)
            return from_rpc_error(error, TELEOPERATE_METHOD)
        finally:
            timer.cancel()
        if not outcome["ready"] or reply.WhichOneof("message") != "ready":
            requests.put(_END)
            call.cancel()
            return DeadlineExceededError("no Ready in time", method=TELEOPERATE_METHOD)
        with self._lock:
            old, self._requests, self._call = self._requests, requests, call
            self.ready = reply.ready
            self._last_resent = max(self._unacked, default=self._last_resent)
            for request in self._unacked.values():  # in order, with their sequence numbers
                requests.put(request)
            self.resends += len(self._unacked)
            self.resumes += 1
            self._interrupted = False
        old.put(_END)
        return None

    def _link(self, state: str, detail: str) -> None:
        if self._on_link is not None:
            try:
                self._on_link(state, detail)
            except Exception:
                log.exception("the on_link callback failed; the session goes on")

    @property
    def interrupted(self) -> bool:
        """True while the link is down and the session reconnects (the arm holds)."""
        return self._interrupted

    @property
    def unacked(self) -> int:
        """Commands sent and not acked yet."""
        return len(self._unacked)

    # -- sending --------------------------------------------------------------------------------
    def _submit(self, build: Callable[[], pb.TeleoperateRequest], waiter: _Waiter | None
                ) -> pb.TeleoperateRequest | None:
        """Queue one message (with its waiter); None for a heartbeat while the link is down."""
        with self._lock:
            if self._closing or self._finished.is_set():
                raise self._dead()
            if self._interrupted:
                if build is self._heartbeat and waiter is None:
                    return None  # the arm holds anyway; nothing to feed
                raise LinkInterruptedError()
            request = build()
            if self.passivity is not None:
                self._with_energy(request)
            self._with_receipt(request)
            self._sent += 1
            if request.WhichOneof("message") == "command":
                self._unacked[request.command.sequence] = request
                if waiter is not None:
                    self._command_waiters[request.command.sequence] = waiter
            elif waiter is not None:
                self._heartbeat_waiters.append(waiter)
            self._requests.put(request)  # under the lock: queue order == sequence order
        if self.on_request is not None:  # (a recorder: make teleop --mcap)
            try:
                self.on_request(request)
            except Exception:  # noqa: BLE001 - a failed hook must not fail the send
                log.exception("the on_request callback failed; the session goes on")
        return request

    def _with_energy(self, request: pb.TeleoperateRequest) -> None:
        """The master port's energy, as it is now, on a command or heartbeat."""
        ledger = self.passivity.ledger
        energy = pb.PortEnergy(energy_in_j=ledger.energy_in_j, energy_out_j=ledger.energy_out_j,
                               dissipated_j=self.passivity.dissipated_j,
                               sample_time=convert.timestamp(time.time_ns()))
        message = getattr(request, request.WhichOneof("message"))
        message.master_energy.CopyFrom(energy)

    def _wait(self, waiter: _Waiter, what: str, timeout: float | None) -> Ack:
        timeout = self.default_timeout if timeout is None else timeout
        if not waiter.event.wait(timeout):
            with self._lock:  # (a heartbeat's waiter is dropped with its stream's ack)
                for sequence, value in list(self._command_waiters.items()):
                    if value is waiter:
                        del self._command_waiters[sequence]
            if waiter.ack is None:
                raise self._ack_timeout(what, timeout)
        if waiter.ack is None:
            raise self._dead() if self._finished.is_set() else LinkInterruptedError(
                f"the link broke before {what} was acked; the session is reconnecting")
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
        mapping frame; `clutch` asks the server to index it) and block until its ack (across
        a resume, if the link breaks meanwhile)."""
        waiter = _Waiter()
        request = self._submit(self._command_builder(delta_position, delta_rotation, clutch),
                               waiter)
        return self._wait(waiter, f"command {request.command.sequence}", timeout)

    def send_nowait(self, delta_position: Sequence[float] | np.ndarray,
                    delta_rotation: np.ndarray | None = None, clutch: bool = False) -> int:
        """Send one increment without waiting; returns its sequence number. Its ack goes to
        ``latest_ack`` and ``on_ack``."""
        request = self._submit(
            self._command_builder(delta_position, delta_rotation, clutch), None)
        return request.command.sequence

    def heartbeat(self, *, timeout: float | None = None) -> Ack:
        """Feed the watchdog and block until the ack (outcome HEARTBEAT)."""
        waiter = _Waiter()
        self._submit(self._heartbeat, waiter)
        return self._wait(waiter, "a heartbeat", timeout)

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
        server to end it; cancel it if it does not. While reconnecting, stop trying. Idempotent;
        never raises."""
        with self._lock:
            if self._closing:
                return
            self._closing = True
            self._requests.put(_END_MESSAGE)  # for good: the server will not wait for a resume
            self._requests.put(_END)
        self._stop_reconnecting.set()
        wait = self.default_timeout if timeout is None else timeout
        if not self._finished.wait(wait):
            self._abandon()

    def _abandon(self) -> None:
        self._closing = True
        self._cancelled = True
        self._stop_reconnecting.set()
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
                arrived = time.time_ns()
                for message in acks_in(reply):
                    ack = Ack.from_proto(message, arrived)
                    self._received += 1
                    future = self._waiters.pop(self._received, None)
                    if future is not None and not future.done():
                        future.set_result(ack)
                    self._noted(ack)
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
            self._with_receipt(request)
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
        """End the session (`end`, then a half-close) and wait for the server to end the
        stream; cancel it if it does not. Idempotent; never raises."""
        async with self._write_lock:
            if self._closing and (self._reader is None or self._reader.done()):
                return
            self._closing = True
            try:
                await self._call.write(_END_MESSAGE)
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
