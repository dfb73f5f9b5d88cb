"""What every client shares: the channel, metadata, timeouts, error mapping and streams.

Each service's client is written once, as a mixin of methods that build a request and say how to
convert the answer (``self._unary(method, request, convert, timeout, lane)``). Two bases run
them: `SyncClient` on a ``grpc.Channel`` (the method returns the value) and `AsyncClient` on a
``grpc.aio.Channel`` (the same method returns an awaitable of the same value). So
``ProxyRobotClient.get_state()`` and ``await AsyncProxyRobotClient.get_state()`` take the same
arguments and give the same value.

Conventions:

- ``target``: "host:port" (the client opens, owns and closes the channel), a channel (shared:
  the client never closes it), or None for the service's address from
  ``TELEROBOT_<SERVICE>_ADDRESS`` or its default port.
- ``timeout`` on every method: seconds for that call; None means the client's
  ``default_timeout`` (5 s unless set; a client made with ``default_timeout=None`` waits
  forever). Streams have no deadline unless one is given.
- ``lane`` on every method: "emergency", "high", "medium" or "low", sent as
  ``telerobot-lane`` metadata; None sends none and the server uses the RPC's declared lane.
- ``security``: how an owned channel authenticates (``wire.tls.ChannelSecurity``); None takes
  it from the environment: ``TELEROBOT_TLS_DIR`` with ``TELEROBOT_IDENTITY`` (a client
  certificate) or ``TELEROBOT_TOKEN`` (a bearer token), plaintext when unset.
- ``lease``: a lease id (or a function returning the current one) sent as
  ``telerobot-lease-id`` metadata on every call, which is what commanding calls need on the
  DecisionServer's port. Reads ignore it; ProxyRobot and ForceSensor on their own ports too.
- Failures raise `TelerobotError` subclasses (see ``errors.py``), never ``grpc.RpcError``.

Reconnection is explicit. Channels are made with ``grpc.enable_retries = 0``: gRPC never
resends a call on its own, not even one it believes never reached the server, so a motion
command is sent exactly once or fails with an error (UNAVAILABLE when the server is down; the
client does not wait for it to come back: ``wait_for_ready`` is off). The channel still
re-establishes its transport for the *next* call, so after a failure the caller decides: call
again, ``wait_for_ready(timeout)`` first, or give up. A broken stream stays broken: open a new
one.
"""

from __future__ import annotations

import asyncio
import threading
from collections.abc import Callable, Sequence
from typing import Any

import grpc

from clients.python.errors import from_rpc_error
from wire.addresses import address_for
from wire.errors import UnavailableError
from wire.metadata import LANE_METADATA_KEY, LANES, LEASE_METADATA_KEY
from wire.tls import ChannelSecurity, open_channel

DEFAULT_TIMEOUT_S = 5.0
# No retries of any kind: a motion command must never be sent twice behind the caller's back.
CHANNEL_OPTIONS: tuple[tuple[str, Any], ...] = (("grpc.enable_retries", 0),)

LeaseSource = str | Callable[[], str | None] | None
_SKIP = object()  # a converter's answer for a stream message that yields nothing


class _ClientCore:
    """State shared by the sync and async bases."""

    SERVICE: str = ""  # full service name, e.g. "telerobot.v1.ProxyRobot"
    ADDRESS_NAME: str = ""  # the name in TELEROBOT_<NAME>_ADDRESS, e.g. "proxy_robot"
    # Over TLS, the service whose name the server's certificate must carry (wire.tls), or None
    # for any certificate naming the host: a ProxyRobot or StereoCamera client may be talking
    # to the DecisionServer's forward of that service, with the DecisionServer's certificate.
    CERTIFICATE_SERVICE: str | None = None
    STUB: Callable[[Any], Any]
    EXTRA_OPTIONS: tuple[tuple[str, Any], ...] = ()

    def _setup(self, target, *, lease: LeaseSource, lane: str | None,
               default_timeout: float | None, options: Sequence[tuple[str, Any]],
               security: ChannelSecurity | None, aio: bool) -> None:
        if lane is not None:
            _check_lane(lane)
        self.default_timeout = default_timeout
        self.lane = lane
        self.security = security  # None: from the environment
        self._lease = lease
        if target is None or isinstance(target, str):
            self.address = target or address_for(self.ADDRESS_NAME)
            self._channel = open_channel(
                self.address, [*CHANNEL_OPTIONS, *self.EXTRA_OPTIONS, *options], security, aio,
                service=self.CERTIFICATE_SERVICE)
            self._owns_channel = True
        else:
            self.address = None
            self._channel = target
            self._owns_channel = False
        self._stub = self.STUB(self._channel)
        self._closed = False

    @property
    def channel(self):
        """The channel (share it with another client by passing it as `target`)."""
        return self._channel

    @property
    def lease_id(self) -> str | None:
        """The lease id sent with every call, or None."""
        return self._lease() if callable(self._lease) else self._lease

    def set_lease(self, lease: LeaseSource) -> None:
        """Send this lease id (or the id a function returns) from now on; None sends none."""
        self._lease = lease

    def _metadata(self, lane: str | None) -> tuple[tuple[str, str], ...]:
        metadata = []
        lane = lane if lane is not None else self.lane
        if lane is not None:
            metadata.append((LANE_METADATA_KEY, _check_lane(lane)))
        lease = self.lease_id
        if lease:
            metadata.append((LEASE_METADATA_KEY, lease))
        return tuple(metadata)

    def _timeout(self, timeout: float | None) -> float | None:
        return self.default_timeout if timeout is None else timeout

    def _method(self, name: str) -> str:
        return f"/{self.SERVICE}/{name}"

    def _check_open(self) -> None:
        if self._closed:
            raise RuntimeError(f"this {type(self).__name__} is closed; make a new one")


def _check_lane(lane: str) -> str:
    if lane not in LANES:
        raise ValueError(f"lane must be one of {', '.join(LANES)}, not {lane!r}")
    return lane


# -- sync -------------------------------------------------------------------------------------

class Stream:
    """A server stream: iterate it for converted messages; ``cancel()`` or leave the ``with``
    block to end it. Errors arrive as `TelerobotError` from the iteration; a stream this
    side cancelled just stops."""

    def __init__(self, call, convert: Callable[[Any], Any], method: str):
        self._call = call
        self._convert = convert
        self._method = method
        self._cancelled = False

    def __iter__(self):
        return self

    def __next__(self):
        while True:
            try:
                message = next(self._call)
            except grpc.RpcError as error:
                if self._cancelled and error.code() == grpc.StatusCode.CANCELLED:
                    raise StopIteration from None
                raise from_rpc_error(error, self._method) from error
            value = self._convert(message)
            if value is not _SKIP:
                return value

    @property
    def header(self):
        """The stream's header once read, for streams that have one (StereoCamera pairs)."""
        return getattr(self._convert, "header", None)

    def cancel(self) -> None:
        self._cancelled = True
        self._call.cancel()

    def __enter__(self):
        return self

    def __exit__(self, *exc) -> None:
        self.cancel()


class SyncClient(_ClientCore):
    """Base of the blocking clients. A context manager: leaving it closes an owned channel."""

    def __init__(self, target: str | grpc.Channel | None = None, *, lease: LeaseSource = None,
                 lane: str | None = None, default_timeout: float | None = DEFAULT_TIMEOUT_S,
                 options: Sequence[tuple[str, Any]] = (),
                 security: ChannelSecurity | None = None):
        self._setup(target, lease=lease, lane=lane, default_timeout=default_timeout,
                    options=options, security=security, aio=False)
        self._pending: set = set()
        self._pending_lock = threading.Lock()

    def _unary(self, name: str, request, convert: Callable[[Any], Any],
               timeout: float | None, lane: str | None):
        self._check_open()
        try:
            response = getattr(self._stub, name)(request, timeout=self._timeout(timeout),
                                                 metadata=self._metadata(lane))
        except grpc.RpcError as error:
            raise from_rpc_error(error, self._method(name)) from error
        return convert(response)

    def _send_and_forget(self, name: str, request, lane: str | None) -> None:
        """A unary call whose answer nobody waits for (receipts): it may fail unseen."""
        if self._closed:
            return
        future = getattr(self._stub, name).future(request, timeout=self._timeout(None),
                                                  metadata=self._metadata(lane))
        with self._pending_lock:  # a call's future that nobody holds cancels the call
            self._pending.add(future)
        future.add_done_callback(self._forget)

    def _forget(self, future) -> None:
        with self._pending_lock:
            self._pending.discard(future)

    def _server_stream(self, name: str, request, convert: Callable[[Any], Any],
                       timeout: float | None, lane: str | None) -> Stream:
        self._check_open()
        call = getattr(self._stub, name)(request, timeout=timeout, metadata=self._metadata(lane))
        return Stream(call, convert, self._method(name))

    def wait_for_ready(self, timeout: float) -> None:
        """Block until the channel connects; UnavailableError after `timeout` seconds. The only
        place a client waits for a server to come up."""
        self._check_open()
        ready = grpc.channel_ready_future(self._channel)
        try:
            ready.result(timeout=timeout)
        except grpc.FutureTimeoutError:
            ready.cancel()
            raise UnavailableError(f"no connection to {self.address or 'the server'} within "
                                   f"{timeout} s (client side)") from None

    def close(self) -> None:
        """Close the channel if this client opened it. Idempotent."""
        if self._closed:
            return
        self._closed = True
        if self._owns_channel:
            self._channel.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc) -> None:
        self.close()


# -- async ------------------------------------------------------------------------------------

class AsyncStream:
    """A server stream on grpc.aio: ``async for`` it; ``cancel()`` or leave the ``async with``
    block to end it."""

    def __init__(self, call, convert: Callable[[Any], Any], method: str):
        self._call = call
        self._convert = convert
        self._method = method
        self._cancelled = False

    def __aiter__(self):
        return self

    async def __anext__(self):
        while True:
            try:
                message = await self._call.read()
            except asyncio.CancelledError:
                if self._cancelled:
                    raise StopAsyncIteration from None
                raise
            except grpc.aio.AioRpcError as error:
                if self._cancelled and error.code() == grpc.StatusCode.CANCELLED:
                    raise StopAsyncIteration from None
                raise from_rpc_error(error, self._method) from error
            if message is grpc.aio.EOF:
                raise StopAsyncIteration
            value = self._convert(message)
            if value is not _SKIP:
                return value

    @property
    def header(self):
        """The stream's header once read, for streams that have one (StereoCamera pairs)."""
        return getattr(self._convert, "header", None)

    def cancel(self) -> None:
        self._cancelled = True
        self._call.cancel()

    async def __aenter__(self):
        return self

    async def __aexit__(self, *exc) -> None:
        self.cancel()


class AsyncClient(_ClientCore):
    """Base of the asyncio clients (grpc.aio). Make them inside a running event loop; use
    ``async with`` or ``await close()``."""

    def __init__(self, target: str | grpc.aio.Channel | None = None, *,
                 lease: LeaseSource = None, lane: str | None = None,
                 default_timeout: float | None = DEFAULT_TIMEOUT_S,
                 options: Sequence[tuple[str, Any]] = (),
                 security: ChannelSecurity | None = None):
        self._setup(target, lease=lease, lane=lane, default_timeout=default_timeout,
                    options=options, security=security, aio=True)
        self._pending: set[asyncio.Future] = set()

    async def _unary(self, name: str, request, convert: Callable[[Any], Any],
                     timeout: float | None, lane: str | None):
        self._check_open()
        try:
            response = await getattr(self._stub, name)(
                request, timeout=self._timeout(timeout), metadata=self._metadata(lane))
        except grpc.aio.AioRpcError as error:
            raise from_rpc_error(error, self._method(name)) from error
        return convert(response)

    def _send_and_forget(self, name: str, request, lane: str | None) -> None:
        """A unary call whose answer nobody waits for (receipts): it may fail unseen."""
        if self._closed:
            return
        task = asyncio.ensure_future(getattr(self._stub, name)(
            request, timeout=self._timeout(None), metadata=self._metadata(lane)))
        self._pending.add(task)  # a task nobody holds may be collected before it runs
        task.add_done_callback(self._forget)

    def _forget(self, task: asyncio.Future) -> None:
        self._pending.discard(task)
        if not task.cancelled():
            task.exception()  # read, so asyncio does not log it as never retrieved

    def _server_stream(self, name: str, request, convert: Callable[[Any], Any],
                       timeout: float | None, lane: str | None) -> AsyncStream:
        self._check_open()
        call = getattr(self._stub, name)(request, timeout=timeout, metadata=self._metadata(lane))
        return AsyncStream(call, convert, self._method(name))

    async def wait_for_ready(self, timeout: float) -> None:
        """Wait until the channel connects; UnavailableError after `timeout` seconds."""
        self._check_open()
        try:
            await asyncio.wait_for(self._channel.channel_ready(), timeout)
        except TimeoutError:
            raise UnavailableError(f"no connection to {self.address or 'the server'} within "
                                   f"{timeout} s (client side)") from None

    async def close(self) -> None:
        """Close the channel if this client opened it. Idempotent."""
        if self._closed:
            return
        self._closed = True
        if self._owns_channel:
            await self._channel.close()

    async def __aenter__(self):
        return self

    async def __aexit__(self, *exc) -> None:
        await self.close()


def run_in_thread(target: Callable[[], None], name: str) -> threading.Thread:
    thread = threading.Thread(target=target, name=name, daemon=True)
    thread.start()
    return thread
