"""ImpairmentProxy: a TCP proxy that delays, throttles, stalls and cuts the bytes between its
clients and one target, as link.py schedules them.

It carries bytes and never parses them, so it fits anything over TCP (gRPC's HTTP/2 is one
long connection per channel). It runs an asyncio loop on a thread of its own, so a test or a
bench uses it as a context manager and calls cut() from any thread.

Cuts: while a cut lasts no byte moves either way. A connection accepted meanwhile is held, not
refused: a real cut drops the SYN and the client's kernel resends it, so the connection opens
late; a refusal would say nothing listens there, which is a different fault. When the cut ends,
a "stall" cut lets the connections resume (TCP retransmits what was lost), and a "reset" cut
resets the ones that were open when it began (RST to both sides: a peer or a middlebox that
lost their state, "Connection reset by peer").
"""

from __future__ import annotations

import asyncio
import itertools
import logging
import random
import socket
import struct
import threading
from collections.abc import Callable
from dataclasses import dataclass, field

from services.impairment.link import LinkProfile, LinkSchedule

log = logging.getLogger(__name__)

CUT_MODES = ("stall", "reset")
READ_BYTES = 65536
# Chunks queued per direction: bounded, so that a throttled direction pushes back on its
# sender (as TCP's window would) instead of buffering without end.
QUEUE_CHUNKS = 64
START_TIMEOUT_S = 5.0
_RESET = object()  # in a direction's queue: the sender's side was reset; reset the receiver's


class _PeerReset(Exception):
    """One side reset its connection; the proxy resets the other side."""


def split_address(address: str) -> tuple[str, int]:
    """("host", port) from "host:port" or "[v6]:port"."""
    host, _, port = address.rpartition(":")
    if not host or not port.isdigit():
        raise ValueError(f"expected host:port, not {address!r}")
    return host.strip("[]"), int(port)


def _reset(writer: asyncio.StreamWriter) -> None:
    """Close with an RST rather than a FIN (SO_LINGER 0), dropping what is unsent."""
    sock = writer.get_extra_info("socket")
    if sock is not None and sock.fileno() >= 0:
        try:
            sock.setsockopt(socket.SOL_SOCKET, socket.SO_LINGER, struct.pack("ii", 1, 0))
        except OSError:
            pass
    writer.transport.abort()


@dataclass
class ProxyStats:
    """Counts since the proxy started."""

    connections: int = 0
    held: int = 0  # accepted during a cut, connected to the target once it ended
    refused_by_target: int = 0
    reset_by_cuts: int = 0
    cuts: int = 0
    # per direction, "up" and "down": bytes delivered, chunks the model stalled
    bytes: dict[str, int] = field(default_factory=lambda: {"up": 0, "down": 0})
    stalls: dict[str, int] = field(default_factory=lambda: {"up": 0, "down": 0})


@dataclass(eq=False)  # hashed by identity: kept in sets
class _Connection:
    number: int
    client: asyncio.StreamWriter
    target: asyncio.StreamWriter
    schedules: list[LinkSchedule]
    task: asyncio.Task | None = None

    def reset(self) -> None:
        """Reset both sockets and stop carrying (from outside the connection's own task)."""
        _reset(self.client)
        _reset(self.target)
        if self.task is not None:
            self.task.cancel()


@dataclass
class _Cut:
    until_s: float
    mode: str
    connections: set = field(default_factory=set)  # open when it began
    timer: asyncio.TimerHandle | None = None


class ImpairmentProxy:
    """Listens on `listen` and carries each connection to `target` through an impaired link:
    `up` for client→target bytes, `down` for target→client. `report` gets a line per event
    (connections, cuts); by default they are logged at INFO."""

    def __init__(self, listen: str, target: str, up: LinkProfile | None = None,
                 down: LinkProfile | None = None,
                 report: Callable[[str], None] | None = None):
        self.listen = listen
        self.target = target
        self.up = up or LinkProfile()
        self.down = down or LinkProfile()
        self.report = report or log.info
        self.stats = ProxyStats()
        self.address: str | None = None  # host:port it bound, once started
        self._numbers = itertools.count(1)
        self._connections: set[_Connection] = set()
        self._handlers: set[asyncio.Task] = set()
        self._cut: _Cut | None = None
        self._loop: asyncio.AbstractEventLoop | None = None
        self._thread: threading.Thread | None = None
        self._server: asyncio.Server | None = None
        self._link_up: asyncio.Event | None = None

    # -- from any thread -------------------------------------------------------------------

    def start(self) -> ImpairmentProxy:
        """Bind and serve on a thread of its own; `address` is then where it listens."""
        self._loop = asyncio.new_event_loop()
        self._thread = threading.Thread(target=self._loop.run_forever,
                                        name="impairment-proxy", daemon=True)
        self._thread.start()
        try:
            self._on_loop(self._listen())
        except BaseException:
            self.stop()
            raise
        return self

    def stop(self) -> None:
        """Close the listener and every connection; end the thread."""
        if self._loop is None:
            return
        if self._loop.is_running():
            self._on_loop(self._shutdown())
            self._loop.call_soon_threadsafe(self._loop.stop)
            self._thread.join(timeout=START_TIMEOUT_S)
        self._loop.close()
        self._loop = None

    def cut(self, duration_s: float, mode: str = "stall") -> None:
        """Cut the link for `duration_s` from now (see the module's doc for the modes). Returns
        once the cut is in force. A cut during a cut extends it; "reset" wins over "stall"."""
        if mode not in CUT_MODES:
            raise ValueError(f"cut mode must be one of {CUT_MODES}, not {mode!r}")
        if duration_s < 0:
            raise ValueError(f"a cut lasts >= 0 s, not {duration_s}")
        self._on_loop(self._start_cut(duration_s, mode))

    def reshape(self, up: LinkProfile | None = None, down: LinkProfile | None = None) -> None:
        """Change a direction's link from now on, for new and open connections alike (a
        bottleneck that narrows or widens mid-stream). Chunks already read keep their times."""
        self._on_loop(self._reshape(up, down))

    @property
    def cutting(self) -> bool:
        """Whether a cut is in force."""
        return self._cut is not None

    def __enter__(self) -> ImpairmentProxy:
        return self.start()

    def __exit__(self, *exc_info) -> None:
        self.stop()

    def _on_loop(self, coroutine):
        return asyncio.run_coroutine_threadsafe(coroutine, self._loop).result(START_TIMEOUT_S)

    # -- on the loop -----------------------------------------------------------------------

    async def _listen(self) -> None:
        self._link_up = asyncio.Event()
        self._link_up.set()
        host, port = split_address(self.listen)
        self._server = await asyncio.start_server(self._handle, host, port)
        bound_host, bound_port = self._server.sockets[0].getsockname()[:2]
        self.address = f"[{bound_host}]:{bound_port}" if ":" in bound_host \
            else f"{bound_host}:{bound_port}"
        self.report(f"listening on {self.address}, forwarding to {self.target}")
        self.report(f"up (client -> target): {self.up.describe()}")
        self.report(f"down (target -> client): {self.down.describe()}")

    async def _shutdown(self) -> None:
        self._server.close()
        if self._cut is not None and self._cut.timer is not None:
            self._cut.timer.cancel()
        for connection in list(self._connections):
            connection.reset()
        for task in list(self._handlers):
            task.cancel()
        await asyncio.gather(*self._handlers, return_exceptions=True)
        await self._server.wait_closed()

    async def _handle(self, client_reader: asyncio.StreamReader,
                      client_writer: asyncio.StreamWriter) -> None:
        task = asyncio.current_task()
        self._handlers.add(task)
        number = next(self._numbers)
        self.stats.connections += 1
        try:
            await self._connect_and_carry(number, client_reader, client_writer)
        except asyncio.CancelledError:
            pass  # a reset cut or the proxy stopping; the sockets are already reset
        finally:
            self._handlers.discard(task)
            if not client_writer.is_closing():
                client_writer.transport.abort()

    async def _connect_and_carry(self, number: int, client_reader: asyncio.StreamReader,
                                 client_writer: asyncio.StreamWriter) -> None:
        peer = client_writer.get_extra_info("peername")
        if not self._link_up.is_set():
            self.stats.held += 1
            self.report(f"connection {number} from {peer[0]}:{peer[1]} held: the link is cut")
            await self._link_up.wait()
        try:
            target_reader, target_writer = await asyncio.open_connection(
                *split_address(self.target))
        except OSError as error:
            self.stats.refused_by_target += 1
            self.report(f"connection {number}: target {self.target} refused it ({error})")
            _reset(client_writer)
            return
        self.report(f"connection {number} from {peer[0]}:{peer[1]} open")
        # Each connection and direction draws from its own stream of the seed, so that one
        # connection's schedule does not depend on how many chunks the others carried.
        schedules = [
            LinkSchedule(self.up, random.Random(f"{self.up.seed}/up/{number}")),
            LinkSchedule(self.down, random.Random(f"{self.down.seed}/down/{number}")),
        ]
        connection = _Connection(number, client_writer, target_writer, schedules,
                                 asyncio.current_task())
        self._connections.add(connection)
        try:
            async with asyncio.TaskGroup() as group:
                group.create_task(self._carry(client_reader, target_writer, schedules[0], "up"))
                group.create_task(
                    self._carry(target_reader, client_writer, schedules[1], "down"))
            self.report(f"connection {number} closed")
            for writer in (client_writer, target_writer):
                writer.close()  # a FIN after what is still buffered, not an RST
        except* (OSError, _PeerReset):
            self.report(f"connection {number} reset by a peer: resetting the other side")
            _reset(client_writer)
            _reset(target_writer)
        finally:
            self._connections.discard(connection)
            if not target_writer.is_closing():
                target_writer.transport.abort()

    async def _carry(self, reader: asyncio.StreamReader, writer: asyncio.StreamWriter,
                     schedule: LinkSchedule, direction: str) -> None:
        """One direction: read chunks as they come, write each out at its release time."""
        queue: asyncio.Queue = asyncio.Queue(QUEUE_CHUNKS)
        async with asyncio.TaskGroup() as group:
            group.create_task(self._read(reader, queue, schedule, direction))
            group.create_task(self._deliver(queue, writer, direction))

    async def _read(self, reader: asyncio.StreamReader, queue: asyncio.Queue,
                    schedule: LinkSchedule, direction: str) -> None:
        loop = asyncio.get_running_loop()
        while True:
            try:
                data = await reader.read(READ_BYTES)
            except ConnectionError:
                data = _RESET
            size = len(data) if isinstance(data, bytes) else 0
            stalls = schedule.stalls
            release_s = schedule.release_time(loop.time(), size)
            self.stats.stalls[direction] += schedule.stalls - stalls
            await queue.put((release_s, data))
            if data is _RESET or not data:
                return

    async def _deliver(self, queue: asyncio.Queue, writer: asyncio.StreamWriter,
                       direction: str) -> None:
        loop = asyncio.get_running_loop()
        while True:
            release_s, data = await queue.get()
            # Never early: the model's times are lower bounds.
            while (wait_s := release_s - loop.time()) > 0:
                await asyncio.sleep(wait_s)
            await self._link_up.wait()
            if data is _RESET:
                raise _PeerReset(direction)
            if not data:  # the sender half-closed: pass the FIN on, in order
                if writer.can_write_eof() and not writer.is_closing():
                    writer.write_eof()
                return
            writer.write(data)
            await writer.drain()
            self.stats.bytes[direction] += len(data)

    async def _reshape(self, up: LinkProfile | None, down: LinkProfile | None) -> None:
        self.up, self.down = up or self.up, down or self.down
        for connection in self._connections:
            connection.schedules[0].profile = self.up
            connection.schedules[1].profile = self.down
        self.report(f"link reshaped: up {self.up.describe()}; down {self.down.describe()}")

    async def _start_cut(self, duration_s: float, mode: str) -> None:
        loop = asyncio.get_running_loop()
        until_s = loop.time() + duration_s
        self.stats.cuts += 1
        if self._cut is None:
            self._cut = _Cut(until_s, mode, set(self._connections))
            self._link_up.clear()
        else:  # extend the cut in force
            self._cut.timer.cancel()
            self._cut.until_s = max(self._cut.until_s, until_s)
            self._cut.mode = "reset" if "reset" in (mode, self._cut.mode) else "stall"
            self._cut.connections |= self._connections
        self._cut.timer = loop.call_at(self._cut.until_s, self._end_cut)
        for connection in self._connections:
            for schedule in connection.schedules:
                schedule.hold(self._cut.until_s)
        self.report(f"link cut for {duration_s:g} s ({mode}): "
                    f"{len(self._connections)} connection(s) open")

    def _end_cut(self) -> None:
        cut, self._cut = self._cut, None
        if cut.mode == "reset":
            reset = [c for c in cut.connections if c in self._connections]
            for connection in reset:
                connection.reset()
            self.stats.reset_by_cuts += len(reset)
            self.report(f"link back: {len(reset)} connection(s) reset")
        else:
            self.report("link back: connections resume")
        self._link_up.set()
