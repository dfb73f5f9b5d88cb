"""teleop_<rate> and teleop_1000_zmq: master commands streamed the way a haptic master sends them.

A haptic master at 1 kHz sends a command every millisecond whether or not the last one has been
acknowledged: the Teleoperate stream is bidirectional so that it can. Measuring it lockstep
(send, wait for the ack, send the next; command.py's TeleoperateTransport) caps the delivered
rate at 1 / round trip and measures the client's patience, not the stream. So here:

- a sender thread streams MasterCommands at the offered rate on absolute deadlines (tick k is due
  at t0 + k/rate), at SCHED_FIFO where the host allows it, as a haptic master's loop runs
  (bench/worker.py); a tick it wakes up a whole period or more late for is skipped and counted
  in ``late_skipped`` (a master that fell behind sends the current command, not a backlog);
- a reader thread takes the acks as they come and matches them to commands by sequence number;
- ``delivered_hz``: commands acked APPLIED or MODIFIED per second, over the sending schedule (or
  until the last such ack, if that came later: a server that queues shows its true rate);
- latency (``p50_ms``...): the ack's ``apply_time`` (the server stamps it when ProxyRobot took
  the target) minus the command's send time, both time.time_ns() on this host; ``ack_*``: the
  ack's arrival at the client minus the send time; ``server_receive_*``: the ack's
  ``receive_time`` minus the send time;
- ``dropped`` = ticks not sent (late, or the stream ended) + commands still unacked DRAIN_S
  after the last send (``unacked``; the soak waits longer, ``drain_s``) + commands acked with
  another outcome (``refused``); ``ack_gaps``: the unacked commands sent before one that was
  acked (skipped, not late);
- every command is TELEOP_STEP_M along base y (the direction flips from one rate to the next,
  so the arm comes back; a long stream, the soak's, flips every ``swing`` commands too); each
  rate has a stream (a session) of its own, after WARMUP_COMMANDS sent the same way and
  waited for. The soak also asks for ``windows``: the latency per minute of the stream.
- the stream asks for grouped acks (``TeleoperateInit.grouped_acks``), as the project's Python
  client does: the acks of the commands the server took together come in one message (the
  zmq baseline answers the same way, with the servicer's own code);
- ``record_dir`` (teleop_1000_mcap, recording.py): the DecisionServer records the session as
  MCAP (StartRecording before the stream opens, StopRecording after it ends), and the file, in
  the server's recordings directory, is checked against ``session_applied``: the commands
  acked APPLIED or MODIFIED in the whole session, warm-up included;
- ``server_pid``: ``server_cpu_ms_per_command``, the server process's CPU time (user + system,
  all its threads) over the session, from before it opens (before StartRecording) to after it
  ends (after StopRecording), per command applied in it; and, for a recorded session,
  ``writer_cpu_ms_per_command``, the same of the recording's writer process (the server's
  child, reaped at StopRecording); ``server_cpu_us_per_command_by_thread``, the server's
  CPU split by thread name, the session's own threads (`teleop`, `teleop-in`, `watchdog`)
  and a recording's included (bench.cpu.ThreadCpuWatch);
- ``proxy_pid``: ``proxy_cpu_ms_per_command``, the same of ProxyRobot's process. At 1 kHz
  the DecisionServer is the stream's bottleneck on a 2-core machine: it keeps the rate by
  merging a backlog into fewer moves, so what recording costs it shows in its CPU, while the
  latency is a queue whose length the machine's load sets.

Transports (the same MasterCommand and TeleoperateResponse bytes on both):

- ``grpc``: DecisionServer.Teleoperate on a grpc.aio channel whose event loop, a thread of
  its own, writes what the sender hands it. A gRPC stream carries one message per write, and
  a Python client gets to its next write only after a thread woke for the last one, so what
  waited meanwhile goes as one ``commands`` message (TeleoperateRequest.commands), each
  command in it acked as if alone (docs/performance.md, "The master's side of the stream");
- ``zmq``: baseline_server.py's ``zmq-teleop`` (DEALER/ROUTER), the DecisionServer's own
  DecisionCore and GrpcSlave behind it. A zmq socket belongs to one thread, so the reader
  thread owns the DEALER and forwards what the sender pushes on an inproc pipe: one hand-off
  on the client, as gRPC's.
"""

from __future__ import annotations

import asyncio
import contextlib
import functools
import itertools
import queue
import threading
import time
import uuid
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Protocol

import grpc
from google.protobuf import duration_pb2, timestamp_pb2

from bench import framing
from bench.command import PLAINTEXT, TELEOP_STEP_M, acquire_control, release_control
from bench.cpu import ThreadCpuWatch, process_cpu_s, reaped_children_cpu_s
from bench.goals import PROXY_CPU_KEY, THREAD_CPU_KEY
from bench.schedule import Schedule
from bench.stats import summary
from bench.worldloop import LoopMeter
from clients.python.teleoperate import acks_in
from services.decision_server.servicer import MAX_COMMANDS_PER_MESSAGE
from services.runtime.aio_server import EventLoopThread
from telerobot.v1 import decision_server_pb2 as dpb
from telerobot.v1 import decision_server_pb2_grpc, types_pb2
from wire.metadata import LEASE_METADATA_KEY
from wire.tls import ChannelSecurity, open_channel

WARMUP_COMMANDS = 20
DRAIN_S = 1.0  # after the last send, acks still count this long
CLOSE_S = 2.0  # the stream gets this long to end after the half-close, then it is cancelled
STREAM_TIMEOUT_S = 3600.0
WATCHDOG_S = 5  # the session's watchdog: far longer than any pause of the bench's
POLL_MS = 50
END = b"X"  # zmq-teleop: the server's last frame of a session (the half-close answered)
ACCEPTED = (dpb.COMMAND_OUTCOME_APPLIED, dpb.COMMAND_OUTCOME_MODIFIED)


class StreamFailed(Exception):
    """The server ended the stream with an error."""


class Stream(Protocol):
    """One Teleoperate session: `send` never waits for an ack; `responses` yields what the
    server sends, in order, until the stream ends (one thread at a time iterates it)."""

    def send(self, request: dpb.TeleoperateRequest) -> None: ...

    def responses(self) -> Iterator[dpb.TeleoperateResponse]: ...

    def end(self) -> None:
        """Half-close: no more commands; the server answers what it has, then ends."""

    def cancel(self) -> None:
        """Give up on the stream now."""

    def close(self) -> None:
        """Release what the stream holds (after its reader has ended)."""


def init_request(lease_id: str, watchdog_s: float = WATCHDOG_S) -> dpb.TeleoperateRequest:
    watchdog = duration_pb2.Duration()
    watchdog.FromNanoseconds(int(round(watchdog_s * 1e9)))
    return dpb.TeleoperateRequest(init=dpb.TeleoperateInit(
        operator_id="bench", lease_id=lease_id, mapping=types_pb2.REFERENCE_FRAME_BASE,
        watchdog_timeout=watchdog, grouped_acks=True))


# -- gRPC -------------------------------------------------------------------------------------

class GrpcStream:
    """The stream on a grpc.aio channel, driven from the sender's and the reader's threads; its
    loop writes what waited as one message (see the module's docstring)."""

    def __init__(self, stub, loop: EventLoopThread, lease_id: str, watchdog_s: float):
        self._loop = loop.loop
        self._responses: queue.SimpleQueue = queue.SimpleQueue()
        self._outgoing: asyncio.Queue = asyncio.Queue()  # (bound to the loop at first use)
        self._call = loop.run(_open_call(stub))
        asyncio.run_coroutine_threadsafe(self._write(), self._loop)
        asyncio.run_coroutine_threadsafe(self._read(), self._loop)
        self.send(init_request(lease_id, watchdog_s))

    async def _write(self) -> None:
        try:
            ended = False
            while not ended:
                requests, ended = await _waiting(self._outgoing)
                for request in _packed(requests):
                    await self._call.write(request)
            await self._call.done_writing()
        except (grpc.RpcError, asyncio.InvalidStateError):
            pass  # the call ended: the reader says how

    async def _read(self) -> None:
        try:
            async for response in self._call:
                self._responses.put(response)
            self._responses.put(None)
        except grpc.RpcError as error:
            self._responses.put(error)
        except asyncio.CancelledError:
            self._responses.put(None)

    def send(self, request: dpb.TeleoperateRequest | None) -> None:
        self._loop.call_soon_threadsafe(self._outgoing.put_nowait, request)

    def responses(self) -> Iterator[dpb.TeleoperateResponse]:
        while (item := self._responses.get()) is not None:
            if isinstance(item, grpc.RpcError):
                if item.code() != grpc.StatusCode.CANCELLED:
                    raise StreamFailed(f"{item.code().name}: {item.details()}") from None
                return
            yield item

    def end(self) -> None:
        self.send(None)

    def cancel(self) -> None:
        self._loop.call_soon_threadsafe(self._call.cancel)

    def close(self) -> None:
        pass


async def _waiting(outgoing: asyncio.Queue) -> tuple[list, bool]:
    """What `outgoing` holds (waiting for at least one item), up to its None, and whether
    that None (the end) came."""
    items = [await outgoing.get()]
    while items[-1] is not None and not outgoing.empty():
        items.append(outgoing.get_nowait())
    ended = items[-1] is None
    return items[:-1] if ended else items, ended


def _packed(requests: list[dpb.TeleoperateRequest]) -> list[dpb.TeleoperateRequest]:
    """`requests` with each run of commands that waited together for the link as `commands`
    messages (TeleoperateRequest.commands), so a stream that fell behind catches up in a few
    messages instead of one per command; a command alone goes as it is."""
    packed: list[dpb.TeleoperateRequest] = []
    for commands, run in itertools.groupby(requests, lambda request: request.HasField("command")):
        run = list(run)
        if not commands or len(run) == 1:
            packed += run
            continue
        for start in range(0, len(run), MAX_COMMANDS_PER_MESSAGE):
            packed.append(dpb.TeleoperateRequest(commands=dpb.MasterCommands(
                commands=[r.command for r in run[start:start + MAX_COMMANDS_PER_MESSAGE]])))
    return packed


async def _open_call(stub):  # (on the loop, which the call keeps)
    return stub.Teleoperate(timeout=STREAM_TIMEOUT_S)


class GrpcTeleop:
    """DecisionServer.Teleoperate: one control lease for the run (each command renews it), a
    stream per rate, on a grpc.aio channel of its own (GrpcStream). `security`: plaintext,
    or mutual TLS with an operator's certificate (the lease is bound to that identity).
    `watchdog_s`: each session's watchdog."""

    name = "grpc-teleoperate pipelined"

    def __init__(self, address: str, security: ChannelSecurity = PLAINTEXT,
                 watchdog_s: float = WATCHDOG_S):
        self._channel = open_channel(address, security=security)
        self._stub = decision_server_pb2_grpc.DecisionServerStub(self._channel)
        self._lease = acquire_control(self._stub)
        self._watchdog_s = watchdog_s
        self._loop = EventLoopThread("teleop-client")
        self._aio_channel = self._loop.run(_aio_channel(address, security))
        self._aio_stub = decision_server_pb2_grpc.DecisionServerStub(self._aio_channel)

    def open(self) -> GrpcStream:
        return GrpcStream(self._aio_stub, self._loop, self._lease, self._watchdog_s)

    def start_recording(self, name: str, task: str = "") -> None:
        self._stub.StartRecording(
            dpb.StartRecordingRequest(name=name, format=dpb.RECORDING_FORMAT_MCAP, task=task),
            metadata=[(LEASE_METADATA_KEY, self._lease)], timeout=10)

    def stop_recording(self) -> dpb.Recording:
        return self._stub.StopRecording(dpb.StopRecordingRequest(),
                                        metadata=[(LEASE_METADATA_KEY, self._lease)],
                                        timeout=30).recording

    def close(self) -> None:
        release_control(self._stub, self._lease)
        self._channel.close()
        self._loop.run(self._aio_channel.close())
        self._loop.close()


async def _aio_channel(address: str, security: ChannelSecurity):
    return open_channel(address, security=security, aio=True)


# -- pyzmq ------------------------------------------------------------------------------------

class ZmqStream:
    """A DEALER to the baseline's ROUTER. Frames back: [OK, TeleoperateResponse bytes],
    [ERROR, why] or [END, b""]; an empty frame out is the half-close."""

    def __init__(self, context, address: str):
        import zmq

        self._zmq = zmq
        self._dealer = context.socket(zmq.DEALER)
        self._dealer.setsockopt(zmq.LINGER, 0)
        self._dealer.connect(f"tcp://{address}")
        endpoint = f"inproc://teleop-{uuid.uuid4().hex}"
        self._inbox = context.socket(zmq.PULL)  # the reader's end of the pipe
        self._inbox.bind(endpoint)
        self._outbox = context.socket(zmq.PUSH)  # the sender's end
        self._outbox.setsockopt(zmq.LINGER, 0)
        self._outbox.connect(endpoint)
        self._cancelled = False
        # The baseline takes its lease itself for an init without one.
        self._outbox.send(init_request("").SerializeToString())

    def send(self, request: dpb.TeleoperateRequest) -> None:
        self._outbox.send(request.SerializeToString())

    def responses(self) -> Iterator[dpb.TeleoperateResponse]:
        zmq = self._zmq
        poller = zmq.Poller()
        poller.register(self._dealer, zmq.POLLIN)
        poller.register(self._inbox, zmq.POLLIN)
        while not self._cancelled:
            ready = dict(poller.poll(POLL_MS))
            if self._inbox in ready:
                while True:
                    try:
                        self._dealer.send(self._inbox.recv(zmq.NOBLOCK))
                    except zmq.Again:
                        break
            if self._dealer in ready:
                while True:
                    try:
                        kind, payload = self._dealer.recv_multipart(zmq.NOBLOCK)
                    except zmq.Again:
                        break
                    if kind == END:
                        return
                    if kind != framing.REPLY_OK:
                        raise StreamFailed(payload.decode(errors="replace"))
                    yield dpb.TeleoperateResponse.FromString(payload)

    def end(self) -> None:
        self._outbox.send(b"")

    def cancel(self) -> None:
        self._cancelled = True  # the reader sees it within POLL_MS

    def close(self) -> None:
        for sock in (self._outbox, self._inbox, self._dealer):
            sock.close(0)


class ZmqTeleop:
    name = "zmq-dealer-router pipelined"

    def __init__(self, address: str):
        import zmq

        self._context = zmq.Context()
        self._address = address

    def open(self) -> ZmqStream:
        return ZmqStream(self._context, self._address)

    def close(self) -> None:
        self._context.destroy(linger=0)  # every stream's sockets, should one be left open


CLIENTS = {"grpc": GrpcTeleop, "zmq": ZmqTeleop}


# -- measuring --------------------------------------------------------------------------------

class AckTracker:
    """Commands in flight by sequence, and what their acks said. The sender registers a
    command before sending it; the reader thread (`follow`) matches the acks."""

    def __init__(self):
        self._lock = threading.Lock()
        self._pending: dict[int, int] = {}  # sequence -> send time (time.time_ns)
        self._highest = 0  # the highest sequence acked (counted or not)
        self._drained = threading.Event()
        self.ended = threading.Event()
        self.error: str | None = None
        self.applied_total = 0  # every command acked APPLIED or MODIFIED, books or not
        self.forget()

    def forget(self) -> None:
        """Start counting afresh (after the warm-up): a late warm-up ack is not counted."""
        with self._lock:
            self._pending.clear()
            self._acks: list[tuple[int, int, int, int, int]] = []  # sent, arrived, receive,
            self._refusals: list[str] = []                         # apply, outcome

    def close_books(self) -> tuple[list[tuple[int, int, int, int, int]], list[str], int, int]:
        """(acks, refusals, commands still unacked, gaps) as of now; later acks are not
        counted. Gaps: the unacked commands sent before one that was acked (the server acks in
        order, so these were skipped, not merely late)."""
        with self._lock:
            gaps = sum(1 for sequence in self._pending if sequence < self._highest)
            books = self._acks, self._refusals, len(self._pending), gaps
            self._pending.clear()
            self._acks, self._refusals = [], []
            return books

    def sent(self, sequence: int, sent_ns: int) -> None:
        with self._lock:
            self._pending[sequence] = sent_ns
            self._drained.clear()

    def wait_drained(self, timeout_s: float) -> bool:
        return self._drained.wait(timeout_s)

    def follow(self, responses: Iterator[dpb.TeleoperateResponse]) -> None:
        try:
            for response in responses:
                arrived = time.time_ns()
                for ack in acks_in(response):
                    self._took(ack, arrived)
        except StreamFailed as error:
            self.error = str(error)
        finally:
            self.ended.set()
            self._drained.set()

    def _took(self, ack: dpb.CommandAck, arrived: int) -> None:
        times = (arrived, ack.receive_time.ToNanoseconds(), ack.apply_time.ToNanoseconds())
        with self._lock:
            self._highest = max(self._highest, ack.sequence)
            self.applied_total += ack.outcome in ACCEPTED
            sent = self._pending.pop(ack.sequence, None)
            if not self._pending:
                self._drained.set()
            if sent is None:
                return  # not counted (the warm-up's, or after the books closed)
            self._acks.append((sent, *times, ack.outcome))
            if ack.outcome not in ACCEPTED and len(self._refusals) < 5:
                self._refusals.append(f"{dpb.CommandOutcome.Name(ack.outcome)}: "
                                      f"{ack.detail}")


def _command(sequence: int, sign: float) -> tuple[dpb.TeleoperateRequest, int]:
    sent_ns = time.time_ns()
    stamp = timestamp_pb2.Timestamp()
    stamp.FromNanoseconds(sent_ns)
    return dpb.TeleoperateRequest(command=dpb.MasterCommand(
        sequence=sequence, send_time=stamp,
        delta_position_m=types_pb2.Vector3(y=sign * TELEOP_STEP_M))), sent_ns


def stream_at_rate(stream: Stream, tracker: AckTracker, sequences: Iterator[int],
                   rate_hz: float, ticks: int, sign: float, swing: int | None = None
                   ) -> tuple[int, int, int | None]:
    """Send `ticks` commands on absolute deadlines at rate_hz, never waiting for an ack
    (stopping early if the stream ends): (commands sent, ticks skipped for lateness,
    time.time_ns() of the first send). `swing`: the direction flips every `swing` sequence
    numbers (a long stream goes back and forth instead of leaving the workspace)."""
    schedule = Schedule(rate_hz, ticks)
    sent = 0
    first_ns = None
    for _ in schedule:
        if tracker.ended.is_set():
            break
        sequence = next(sequences)
        request, sent_ns = _command(sequence, sign if swing is None
                                    else sign * (-1.0) ** ((sequence // swing) % 2))
        tracker.sent(sequence, sent_ns)
        stream.send(request)
        first_ns = first_ns or sent_ns
        sent += 1
    skipped = schedule.skipped
    return sent, skipped, first_ns


def run_rate(client, rate_hz: float, duration_s: float, sign: float,
             loop: LoopMeter | None, swing: int | None = None,
             window_s: float | None = None, drain_s: float = DRAIN_S,
             drained: Callable[[], None] | None = None) -> dict:
    """One Teleoperate session streaming at rate_hz for duration_s; the scenario's summary and
    raw latencies. `swing`: see stream_at_rate; `window_s`: the summary adds the latency
    and the acked commands of every window of that length (`windows`), to see a drift;
    `drain_s`: how long acks still count after the last send; `drained()` is called then,
    the session still open."""
    stream = client.open()
    tracker = AckTracker()
    reader = None
    ticks = int(round(duration_s * rate_hz))
    try:
        responses = stream.responses()
        first = next(responses, None)  # the session is open once the server says ready
        if first is None or first.WhichOneof("message") != "ready":
            raise StreamFailed("Teleoperate did not answer its init with ready")
        reader = threading.Thread(target=tracker.follow, args=(responses,), name="acks",
                                  daemon=True)
        reader.start()
        sequences = itertools.count(1)
        stream_at_rate(stream, tracker, sequences, rate_hz, WARMUP_COMMANDS, sign, swing)
        tracker.wait_drained(DRAIN_S)
        tracker.forget()
        if loop is not None:
            loop.mark()
        sent, skipped, first_ns = stream_at_rate(stream, tracker, sequences, rate_hz, ticks,
                                                 sign, swing)
        tracker.wait_drained(drain_s)
        world_loop = loop.since_mark() if loop is not None else None
        books = tracker.close_books()
        if drained is not None:
            drained()
        stream.end()
        tracker.ended.wait(CLOSE_S)
    finally:
        if not tracker.ended.is_set():
            stream.cancel()
        if reader is not None:
            reader.join(CLOSE_S)
        stream.close()
    result = _summarize(books, tracker.error, client.name, rate_hz, ticks, sent, skipped,
                        first_ns, world_loop)
    result["session_applied"] = tracker.applied_total  # what a recording of it holds
    if window_s:
        result["windows"] = windows(books[0], first_ns, window_s)
    return result


def windows(acks: list[tuple[int, int, int, int, int]], first_ns: int | None,
            window_s: float) -> list[dict]:
    """The accepted acks by the window of `window_s` their command was sent in (from
    `first_ns`): its start (s), commands acked, p50 and p99 (command sent -> applied, ms)."""
    if first_ns is None:
        return []
    buckets: dict[int, list[float]] = {}
    for sent, _, _, apply, outcome in acks:
        if outcome in ACCEPTED:
            index = int((sent - first_ns) / 1e9 // window_s)
            buckets.setdefault(index, []).append((apply - sent) / 1e6)
    rows = []
    for index in sorted(buckets):
        figures = summary(buckets[index], None, 0, 1, 0)
        rows.append({"t_s": round(index * window_s, 3), "acked": len(buckets[index]),
                     "p50_ms": figures["p50_ms"], "p99_ms": figures["p99_ms"],
                     "max_ms": figures["max_ms"]})
    return rows


def _summarize(books: tuple[list, list[str], int, int], error: str | None, transport: str,
               rate_hz: float, ticks: int, sent: int, skipped: int, first_ns: int | None,
               world_loop: dict | None) -> dict:
    acks, refusals, unacked, gaps = books
    accepted = [a for a in acks if a[4] in ACCEPTED]
    applied_ms = [(apply - sent) / 1e6 for sent, _, _, apply, _ in accepted]
    ack_ms = [(arrived - sent) / 1e6 for sent, arrived, _, _, _ in acks]
    receive_ms = [(receive - sent) / 1e6 for sent, _, receive, _, _ in acks]
    scheduled_s = ticks / rate_hz
    last_ns = max((arrived for _, arrived, _, _, _ in accepted), default=None)
    window_s = scheduled_s
    if first_ns is not None and last_ns is not None:
        window_s = max(scheduled_s, (last_ns - first_ns) / 1e9)
    refused = len(acks) - len(accepted)
    ack, received = summary(ack_ms, None, 0, 1, 0), summary(receive_ms, None, 0, 1, 0)
    result = summary(
        applied_ms, rate_hz, len(accepted), window_s, ticks - sent + unacked + refused,
        transport=transport, mode="pipelined", duration_s=round(window_s, 3),
        applied_means="the server's apply_time (target handed to ProxyRobot) - send time",
        sent=sent, late_skipped=skipped, unacked=unacked, ack_gaps=gaps, refused=refused,
        ack_p50_ms=ack["p50_ms"], ack_p99_ms=ack["p99_ms"], ack_max_ms=ack["max_ms"],
        server_receive_p50_ms=received["p50_ms"], server_receive_p99_ms=received["p99_ms"],
        failures=refusals + ([error] if error else []))
    if world_loop is not None:
        result["world_loop"] = world_loop
    result["latencies_ms"] = [round(v, 4) for v in applied_ms]
    return result


def recorded(client: GrpcTeleop, record_dir: Path, run: Callable[[], dict],
             episode_task: str = "") -> dict:
    """`run()` (one session) with the DecisionServer recording it as MCAP into `record_dir`
    (its recordings directory), as an episode of `episode_task` if given (with the stereo
    video and the state at 100 Hz); the result gets `recording` (recording.teleop_check)."""
    from bench import recording  # the MCAP readers: only in a recording worker

    name = f"bench_{uuid.uuid4().hex[:12]}"  # a retried worker must not meet ALREADY_EXISTS
    client.start_recording(name, episode_task)
    try:
        result = run()
    except BaseException:
        with contextlib.suppress(grpc.RpcError):
            client.stop_recording()
        raise
    saved = client.stop_recording()
    result["recording"] = recording.teleop_check(record_dir / f"{name}.mcap",
                                                 result["session_applied"],
                                                 saved.command_count, TELEOP_STEP_M)
    if episode_task:
        result["recording"]["video_frames"] = saved.video_frames
    return result


def measure(transport_kind: str, address: str, shm_name: str | None, rates: list[float],
            duration_s: float, swing: int | None = None, window_s: float | None = None,
            drain_s: float = DRAIN_S, first_sign: float = 1.0, record_dir: str | None = None,
            server_pid: int | None = None, proxy_pid: int | None = None,
            episode_task: str = "", **client_options
            ) -> dict[str, dict]:
    """run_rate for each rate (a session each, the direction of motion alternating from
    `first_sign`); {str(rate): result}. `client_options` go to the client (`security` for
    gRPC, and `watchdog_s`); `swing`, `window_s`, `drain_s`: see run_rate (the soak's long
    stream); `record_dir`: each session recorded (`recorded`); `server_pid`: the server's CPU
    per command of each session (`server_cpu_ms_per_command`), and by thread; `proxy_pid`:
    ProxyRobot's (`proxy_cpu_ms_per_command`)."""
    client = CLIENTS[transport_kind](address, **client_options)
    loop = LoopMeter(shm_name) if shm_name else None
    results = {}
    try:
        for index, rate in enumerate(rates):
            sign = first_sign if index % 2 == 0 else -first_sign
            # The server's threads are read once more as the session's acks have drained, its
            # own threads still alive (they end with it).
            threads = ThreadCpuWatch(server_pid) if server_pid else None
            run = functools.partial(run_rate, client, rate, duration_s, sign, loop, swing,
                                    window_s, drain_s, threads.sample if threads else None)
            cpu_s = process_cpu_s(server_pid) if server_pid else None
            proxy_cpu_s = process_cpu_s(proxy_pid) if proxy_pid else None
            writer_cpu_s = reaped_children_cpu_s(server_pid) if server_pid else None
            result = run() if record_dir is None else recorded(client, Path(record_dir), run,
                                                                episode_task)
            spent_by_thread = threads.stop() if threads else None
            applied = result["session_applied"]
            if cpu_s is not None and applied:
                result["server_cpu_ms_per_command"] = round(
                    1e3 * (process_cpu_s(server_pid) - cpu_s) / applied, 4)
                result[THREAD_CPU_KEY] = {
                    name: round(1e6 * spent / applied, 1) for name, spent in sorted(
                        spent_by_thread.items(), key=lambda item: -item[1])}
                if record_dir is not None:
                    result["writer_cpu_ms_per_command"] = round(
                        1e3 * (reaped_children_cpu_s(server_pid) - writer_cpu_s) / applied, 4)
            if proxy_cpu_s is not None and applied:
                result[PROXY_CPU_KEY] = round(
                    1e3 * (process_cpu_s(proxy_pid) - proxy_cpu_s) / applied, 4)
            results[str(int(rate))] = result
        return results
    finally:
        if loop is not None:
            loop.close()
        client.close()
