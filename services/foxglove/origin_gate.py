"""The live view's front door: a gate that refuses WebSocket upgrades from pages of other
origins.

The SDK's server (services/foxglove/live.py) checks no Origin (its handshake looks at the
subprotocol only, and it tells its listener nothing of a connection before a subscription), so
any page in the user's browser could watch the arm through it. `OriginGate` stands in front of
it: it reads each upgrade's head and passes on only those whose Origin it allows; the SDK's
server listens on loopback behind it, serving wss:// with a certificate made at start and known
to the gate alone, so a page that finds that port cannot shake hands with it either.
"""

from __future__ import annotations

import asyncio
import concurrent.futures
import contextlib
import datetime
import ipaddress
import logging
import ssl
import threading
from collections import Counter
from collections.abc import Iterable

from cryptography import x509
from cryptography.hazmat.primitives import hashes, serialization
from cryptography.hazmat.primitives.asymmetric import ec
from cryptography.x509.oid import ExtendedKeyUsageOID, NameOID

log = logging.getLogger(__name__)

# Origins a viewer's page may have: the Foxglove web app, and Foxglove's and Lichtblick's desktop
# apps (Electron pages loaded from file://). A request with no Origin is a program's (Python,
# the launcher's probe): a browser always sends one. Not "null": any page can send that, from
# a sandboxed frame.
DEFAULT_ORIGINS = ("https://app.foxglove.dev", "file://")
MAX_VIEWERS = 32  # connections at once, handshakes included; more get 503
HEAD_TIMEOUT_S = 10.0  # a connection's TLS handshake and upgrade request come within this
MAX_HEAD_BYTES = 16 * 1024  # an upgrade request's line and headers
_CHUNK = 1 << 16
_INNER_NAME = "127.0.0.1"


def loopback_certificate() -> tuple[bytes, bytes]:
    """A new self-signed certificate for 127.0.0.1 and its key (PEM, the key PKCS#8), for the
    SDK's server behind the gate: no browser trusts it, so no page can shake hands there."""
    key = ec.generate_private_key(ec.SECP256R1())
    name = x509.Name([x509.NameAttribute(NameOID.COMMON_NAME, "telerobot live view, inner")])
    now = datetime.datetime.now(datetime.UTC)
    certificate = (
        x509.CertificateBuilder().subject_name(name).issuer_name(name)
        .public_key(key.public_key()).serial_number(x509.random_serial_number())
        .not_valid_before(now - datetime.timedelta(minutes=5))
        .not_valid_after(now + datetime.timedelta(days=3650))
        .add_extension(x509.SubjectAlternativeName(
            [x509.IPAddress(ipaddress.ip_address(_INNER_NAME))]), critical=False)
        .add_extension(x509.ExtendedKeyUsage([ExtendedKeyUsageOID.SERVER_AUTH]), critical=False)
        .sign(key, hashes.SHA256()))
    return (certificate.public_bytes(serialization.Encoding.PEM),
            key.private_bytes(serialization.Encoding.PEM, serialization.PrivateFormat.PKCS8,
                              serialization.NoEncryption()))


def normal_origin(origin: str) -> str:
    """An origin as browsers send it: lower case, no trailing slash after its host."""
    scheme, separator, host = origin.strip().lower().partition("://")
    return f"{scheme}{separator}{host.rstrip('/')}"


class OriginGate:
    """The live view's front door: a TCP server that reads each connection's upgrade request
    and refuses (403) one whose Origin is not allowed, and otherwise relays the connection,
    bytes as they are, to the SDK's server at 127.0.0.1:`inner_port`, over TLS that trusts
    `inner_certificate` alone. With `tls`, the gate serves wss:// itself. Its loop runs on a
    thread of its own, from start() to stop()."""

    def __init__(self, inner_port: int, inner_certificate: bytes,
                 allowed_origins: Iterable[str] = DEFAULT_ORIGINS, *,
                 tls: ssl.SSLContext | None = None, max_viewers: int = MAX_VIEWERS,
                 head_timeout_s: float = HEAD_TIMEOUT_S):
        self.inner_port = inner_port
        self._inner_tls = ssl.create_default_context(cadata=inner_certificate.decode())
        self.allowed = frozenset(normal_origin(o) for o in allowed_origins)
        self._tls = tls
        self.max_viewers = max_viewers
        self.head_timeout_s = head_timeout_s
        self.refused: Counter[str] = Counter()  # origin -> connections refused (the loop's)
        self._connections: set[asyncio.Task] = set()
        self._loop: asyncio.AbstractEventLoop | None = None
        self._stopping: asyncio.Event | None = None
        self._thread: threading.Thread | None = None

    def allows(self, origins: list[str]) -> bool:
        """Whether an upgrade with these Origin headers may pass: none, or one allowed."""
        return not origins or (len(origins) == 1 and normal_origin(origins[0]) in self.allowed)

    def start(self, host: str, port: int) -> int:
        """Listen on host:port (0: a free one); returns the port. OSError if it cannot."""
        bound: concurrent.futures.Future[int] = concurrent.futures.Future()
        self._thread = threading.Thread(target=asyncio.run, args=(self._run(host, port, bound),),
                                        name="live-view-gate", daemon=True)
        self._thread.start()
        return bound.result(timeout=30)

    def stop(self) -> None:
        if self._loop is not None and self._stopping is not None:
            with contextlib.suppress(RuntimeError):  # its loop already ended
                self._loop.call_soon_threadsafe(self._stopping.set)
        if self._thread is not None:
            self._thread.join(10)

    async def _run(self, host: str, port: int, bound: concurrent.futures.Future) -> None:
        self._loop, self._stopping = asyncio.get_running_loop(), asyncio.Event()
        try:
            server = await asyncio.start_server(
                self._serve, host, port, ssl=self._tls, limit=MAX_HEAD_BYTES,
                ssl_handshake_timeout=self.head_timeout_s if self._tls else None)
        except BaseException as error:  # noqa: BLE001 - the caller's to report
            bound.set_exception(error)
            return
        bound.set_result(server.sockets[0].getsockname()[1])
        await self._stopping.wait()
        server.close()
        for connection in list(self._connections):
            connection.cancel()
        await asyncio.gather(*self._connections, return_exceptions=True)

    async def _serve(self, reader: asyncio.StreamReader, writer: asyncio.StreamWriter) -> None:
        task = asyncio.current_task()
        try:
            if len(self._connections) >= self.max_viewers:
                return await _answer(writer, 503, "too many viewers")
            self._connections.add(task)
            try:
                head = await asyncio.wait_for(reader.readuntil(b"\r\n\r\n"),
                                              self.head_timeout_s)
            except (asyncio.IncompleteReadError, asyncio.LimitOverrunError, TimeoutError,
                    OSError):
                return  # gone, too slow, or a head too large: closed without a word
            origins = _header_values(head, b"origin")
            if not self.allows(origins):
                self._refused(origins)
                return await _answer(writer, 403, "this live view does not serve pages of "
                                     f"{', '.join(origins)}: start it with --allowed-origin "
                                     "to let a viewer at that origin in")
            await self._relay(head, reader, writer)
        finally:
            self._connections.discard(task)
            writer.close()

    async def _relay(self, head: bytes, reader, writer) -> None:
        try:
            inner_reader, inner_writer = await asyncio.open_connection(
                _INNER_NAME, self.inner_port, ssl=self._inner_tls, server_hostname=_INNER_NAME)
        except OSError as error:
            log.warning("live view: its server behind the gate is unreachable: %s", error)
            return await _answer(writer, 502, "the live view's server is unreachable")
        try:
            inner_writer.write(head)
            pipes = [asyncio.ensure_future(_pipe(reader, inner_writer)),
                     asyncio.ensure_future(_pipe(inner_reader, writer))]
            try:
                await asyncio.wait(pipes, return_when=asyncio.FIRST_COMPLETED)
            finally:
                for pipe in pipes:
                    pipe.cancel()
                await asyncio.gather(*pipes, return_exceptions=True)
        finally:
            inner_writer.close()

    def _refused(self, origins: list[str]) -> None:
        origin = ", ".join(origins)
        if not self.refused[origin] and len(self.refused) < 1000:
            log.warning("live view: refused a viewer from %s (not an allowed origin)", origin)
        self.refused[origin] += 1


def _header_values(head: bytes, name: bytes) -> list[str]:
    values = []
    for line in head.split(b"\r\n")[1:]:
        key, colon, value = line.partition(b":")
        if colon and key.strip().lower() == name:
            values.append(value.strip().decode("latin-1"))
    return values


async def _pipe(reader: asyncio.StreamReader, writer: asyncio.StreamWriter) -> None:
    with contextlib.suppress(OSError):
        while data := await reader.read(_CHUNK):
            writer.write(data)
            await writer.drain()


async def _answer(writer: asyncio.StreamWriter, status: int, text: str) -> None:
    reason = {403: "Forbidden", 502: "Bad Gateway", 503: "Service Unavailable"}[status]
    body = f"{text}\n".encode()
    writer.write(f"HTTP/1.1 {status} {reason}\r\nContent-Type: text/plain; charset=utf-8\r\n"
                 f"Content-Length: {len(body)}\r\nConnection: close\r\n\r\n".encode() + body)
    with contextlib.suppress(OSError):
        await asyncio.wait_for(writer.drain(), HEAD_TIMEOUT_S)
