"""services/runtime/aio_server.on_threads on a real grpc.aio server: a sync response stream
whose messages are pulled on different threads keeps one set of context variables for its
whole life, as it has on the sync server's one thread."""

from __future__ import annotations

import contextvars
import threading
from concurrent import futures

import grpc
import pytest

from services.runtime.aio_server import AioServerHandle, EventLoopThread, on_threads

_acting_as: contextvars.ContextVar[str | None] = contextvars.ContextVar("acting_as",
                                                                        default=None)


class ThreadPerTask(futures.Executor):
    """Runs every task on a new thread, so that no two pulls of a stream share one: the
    worst a real pool may do."""

    def __init__(self):
        self.threads: list[threading.Thread] = []

    def submit(self, fn, /, *args, **kwargs):
        future: futures.Future = futures.Future()

        def run():
            try:
                future.set_result(fn(*args, **kwargs))
            except BaseException as error:  # noqa: BLE001 - handed to the future's reader
                future.set_exception(error)

        thread = threading.Thread(target=run)
        self.threads.append(thread)
        thread.start()
        return future


def identities(request: bytes, context):
    """Sets a context variable, streams what it reads on each message's thread, and resets
    it at the end (which fails in a context other than the one it was set in)."""
    token = _acting_as.set(request.decode())
    try:
        for _ in range(4):
            yield f"{_acting_as.get()}@{threading.current_thread().name}".encode()
    finally:
        _acting_as.reset(token)


@pytest.fixture
def served():
    pool = ThreadPerTask()
    loop = EventLoopThread()
    handler = on_threads(grpc.unary_stream_rpc_method_handler(identities), pool)

    async def make_server():
        server = grpc.aio.server()
        server.add_generic_rpc_handlers(
            [grpc.method_handlers_generic_handler("test.Identities", {"Stream": handler})])
        return server

    server = AioServerHandle(loop.run(make_server()), loop)
    port = server.add_insecure_port("127.0.0.1:0")
    server.start()
    channel = grpc.insecure_channel(f"127.0.0.1:{port}")
    yield channel, pool
    channel.close()
    server.stop(None).wait(5)
    loop.close()
    for thread in pool.threads:
        thread.join(5)


def test_a_stream_keeps_its_context_variables_across_pool_threads(served):
    channel, _pool = served
    stream = channel.unary_stream("/test.Identities/Stream")
    messages = [message.decode() for message in stream(b"operator-1", timeout=5)]
    assert [message.split("@")[0] for message in messages] == ["operator-1"] * 4
    # Each message was pulled on a thread of its own, and the stream still ended OK: the
    # generator's reset ran in the context its set ran in.
    assert len({message.split("@")[1] for message in messages}) == 4
