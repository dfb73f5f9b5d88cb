"""The same servicers and LaneInterceptor on a grpc.aio server: calls arrive on an event loop
instead of grpcio's sync polling thread.

Why (bench/probes/estop.py): under a load that keeps a server busy, every call's
events queue for the sync server's one polling thread, which takes the GIL for each, and an
emergency stop's arrival waits its turn: 12-15 ms at p99 on a server whose calls do nothing,
17-27 ms with ProxyRobot's stack. On grpc.aio the same servicer sees the stop within 3 ms.
Through this module, the bench's estop_under_load_proxy latched the hold at p99 6-8 ms
instead of 28-39. The price: every other call takes 0.3-0.45 ms longer (docs/performance.md →
Profiles), so a service opts in (ProxyRobot's and ForceSensor's --aio-server) and none does
by default.

What stays the same: servicers are sync code, and every call still goes through
LaneInterceptor (lanes, validation, security, audit, metrics, the early stop on arrival). The
interceptor's wrapped handlers run on a thread pool as they ran on the sync server's, with a
`SyncContext` that gives them the sync ServicerContext they were written for. A stream's
messages are pulled from its sync generator one at a time on that pool, always in the stream's
own set of context variables (the caller it acts as); a client stream's messages are read from
the loop for the handler's thread. A stream that yields a Wakeup (services/common/wakeup.py)
waits for it on the loop, and from then on is pulled on the loop too: such a stream never
blocks, and its messages then cost no hand-over between the pool and the loop (ForceSensor's
StreamWrench: docs/performance.md).
"""

from __future__ import annotations

import asyncio
import contextvars
import threading
from collections.abc import Callable, Iterator
from concurrent import futures

import grpc

from services.common.wakeup import Wakeup, reset_eventfd
from services.runtime.rpc import LaneInterceptor

_END = object()


class Aborted(Exception):
    """Raised on a handler's thread by SyncContext.abort*: the loop ends the call with it."""

    def __init__(self, code: grpc.StatusCode, details: str, trailing_metadata=()):
        super().__init__(details)
        self.code, self.details, self.trailing_metadata = code, details, trailing_metadata


class SyncContext:
    """A sync handler's view of a grpc.aio call (grpc.ServicerContext's methods that the
    runtime and servicers use), callable from any thread."""

    def __init__(self, context: grpc.aio.ServicerContext):
        self._context = context
        self._active = True

    def ended(self) -> None:
        """The call is over (finished, cancelled or failed): is_active() turns False."""
        self._active = False

    def is_active(self) -> bool:
        return self._active and not self._context.done()

    def add_callback(self, callback: Callable[[], None]) -> bool:
        self._context.add_done_callback(lambda _context: callback())
        return True

    def abort(self, code: grpc.StatusCode, details: str):
        self._context.set_code(code)
        self._context.set_details(details)
        raise Aborted(code, details)

    def abort_with_status(self, status: grpc.Status):
        self._context.set_code(status.code)
        self._context.set_details(status.details)
        raise Aborted(status.code, status.details, status.trailing_metadata)

    def code(self):
        return self._context.code()

    def details(self):
        return self._context.details()

    def __getattr__(self, name: str):
        # invocation_metadata, peer, auth_context, time_remaining, set_code, set_details,
        # set_trailing_metadata, send_initial_metadata: as the aio context has them.
        return getattr(self._context, name)


class _SyncRequests:
    """A client stream's requests as a blocking iterator, for the handler's thread."""

    def __init__(self, requests, loop: asyncio.AbstractEventLoop):
        self._requests = requests.__aiter__()
        self._loop = loop

    def __iter__(self) -> Iterator:
        return self

    def __next__(self):
        try:
            return asyncio.run_coroutine_threadsafe(self._requests.__anext__(),
                                                    self._loop).result()
        except StopAsyncIteration:
            raise StopIteration from None


def _close(iterator, pool: futures.Executor, context_vars: contextvars.Context) -> None:
    """Close a sync response generator (running its finally blocks: the stream's slot, the
    audit) on `pool`, or here once the pool is shut down."""
    close = getattr(iterator, "close", None)
    if close is None:
        return
    try:
        pool.submit(context_vars.run, close)
    except RuntimeError:  # the server stopped: its pool takes nothing new
        context_vars.run(close)


def on_threads(handler: grpc.RpcMethodHandler, pool: futures.Executor
               ) -> grpc.RpcMethodHandler:
    """`handler`, whose behaviour is sync, with an async behaviour that runs it on `pool`.
    (grpc.aio tells async behaviours from sync ones by their functions, so these are
    `async def`s.)"""
    behavior = (handler.unary_unary or handler.stream_unary or handler.unary_stream
                or handler.stream_stream)

    def sync_request(request):
        if handler.request_streaming:
            return _SyncRequests(request, asyncio.get_running_loop())
        return request

    async def answered(request, context):
        sync_context = SyncContext(context)
        try:
            return await asyncio.wrap_future(
                pool.submit(behavior, sync_request(request), sync_context))
        except Aborted as aborted:
            await context.abort(aborted.code, aborted.details, aborted.trailing_metadata)
        finally:
            sync_context.ended()

    async def streamed(request, context):
        sync_context = SyncContext(context)
        # One set of context variables for the stream's whole life, as its one thread has on
        # the sync server: each pull may run on a different pool thread, and a variable the
        # generator sets (the caller it acts as) must still be there, and be reset, later.
        context_vars = contextvars.Context()
        responses = pending = wakeups = None
        try:
            responses = iter(await asyncio.wrap_future(pool.submit(
                context_vars.run, behavior, sync_request(request), sync_context)))
            while True:
                if wakeups is None:  # the handler may block: pulled on the pool
                    pending = pool.submit(context_vars.run, next, responses, _END)
                    item = await asyncio.wrap_future(pending)
                else:  # it waits through Wakeups, so it never blocks: pulled here
                    item = context_vars.run(next, responses, _END)
                if item is _END:
                    return
                if type(item) is Wakeup:
                    if wakeups is None:
                        wakeups = _Wakeups(asyncio.get_running_loop())
                    await wakeups.wait(item)
                    continue
                yield item
        except Aborted as aborted:
            await context.abort(aborted.code, aborted.details, aborted.trailing_metadata)
        finally:
            sync_context.ended()
            if wakeups is not None:
                wakeups.close()
            if responses is not None:
                # Once the pull in flight, if any, has returned: a running generator cannot
                # be closed.
                if pending is None:
                    _close(responses, pool, context_vars)
                else:
                    pending.add_done_callback(
                        lambda _done: _close(responses, pool, context_vars))

    kinds = {(False, False): "unary_unary", (True, False): "stream_unary",
             (False, True): "unary_stream", (True, True): "stream_stream"}
    kind = kinds[(bool(handler.request_streaming), bool(handler.response_streaming))]
    return handler._replace(**{kind: streamed if handler.response_streaming else answered})


class _Wakeups:
    """The eventfds a stream has waited on, each watched by the loop from the stream's first
    Wakeup on it to the stream's end: one registration, not one per message. The watch resets
    the fd whenever it is written, so the loop never spins on it, and remembers a write that
    came while the stream was not waiting, as the eventfd itself would."""

    def __init__(self, loop: asyncio.AbstractEventLoop):
        self._loop = loop
        self._fds: set[int] = set()
        self._written_meanwhile: set[int] = set()
        self._waiting_on: int | None = None
        self._waiter: asyncio.Future | None = None

    async def wait(self, wakeup: Wakeup) -> None:
        loop, fd = self._loop, wakeup.fd
        if fd not in self._fds:
            loop.add_reader(fd, self._written, fd)
            self._fds.add(fd)
        if fd in self._written_meanwhile:
            self._written_meanwhile.discard(fd)
            return
        self._waiting_on, self._waiter = fd, loop.create_future()
        timer = loop.call_later(wakeup.timeout_s, self._wake)
        try:
            await self._waiter
        finally:
            self._waiting_on = self._waiter = None
            timer.cancel()

    def _written(self, fd: int) -> None:
        reset_eventfd(fd)
        if fd == self._waiting_on:
            self._wake()
        else:
            self._written_meanwhile.add(fd)

    def _wake(self) -> None:
        waiter = self._waiter
        if waiter is not None and not waiter.done():
            waiter.set_result(None)

    def close(self) -> None:
        for fd in self._fds:
            self._loop.remove_reader(fd)
        self._fds.clear()


class AioLaneInterceptor(grpc.aio.ServerInterceptor):
    """LaneInterceptor on a grpc.aio server: the same early stop and wrapping, as each call
    arrives on the loop; the wrapped handler then runs on `pool`."""

    def __init__(self, lanes: LaneInterceptor, pool: futures.Executor):
        self.lanes = lanes
        self._pool = pool

    async def intercept_service(self, continuation, handler_call_details):
        handler = await continuation(handler_call_details)
        if handler is None:
            return None
        wrapped = self.lanes.intercept_service(lambda _details: handler, handler_call_details)
        return on_threads(wrapped, self._pool)


class EventLoopThread:
    """An asyncio event loop on a daemon thread, for the aio servers of one process."""

    def __init__(self, name: str = "grpc-aio"):
        self.loop = asyncio.new_event_loop()
        self._thread = threading.Thread(target=self.loop.run_forever, name=name, daemon=True)
        self._thread.start()

    def run(self, coroutine, timeout_s: float | None = None):
        """Run `coroutine` on the loop and wait for its result."""
        return asyncio.run_coroutine_threadsafe(coroutine, self.loop).result(timeout_s)

    def close(self) -> None:
        self.loop.call_soon_threadsafe(self.loop.stop)
        self._thread.join(5.0)
        if not self._thread.is_alive():
            self.loop.close()


class AioServerHandle:
    """A grpc.aio server driven from sync code: start() and stop(grace) -> threading.Event,
    as grpc.Server has them."""

    def __init__(self, server: grpc.aio.Server, loop: EventLoopThread):
        self.server = server
        self._loop = loop

    def add_insecure_port(self, address: str) -> int:
        return self.server.add_insecure_port(address)

    def add_secure_port(self, address: str, credentials) -> int:
        return self.server.add_secure_port(address, credentials)

    def start(self) -> None:
        self._loop.run(self.server.start())

    def stop(self, grace_s: float | None) -> threading.Event:
        stopped = threading.Event()
        future = asyncio.run_coroutine_threadsafe(self.server.stop(grace_s), self._loop.loop)
        future.add_done_callback(lambda _done: stopped.set())
        return stopped
