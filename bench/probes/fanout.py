"""python -m bench.probes.fanout: can a Python gRPC server stream 1 kHz to an operator while it
streams 100 Hz to 16 or 32 observers (the observers_<n> rows)? It prints figures and judges
nothing; what it showed: docs/probes.md.

The server is bare: a sampler thread makes one message every 1 ms (a StreamWrenchResponse
serialized once, carrying its time), and each stream sends it as bytes, nothing else. No
sensor, no lanes, no interceptors: the floor under ForceSensor's StreamWrench. Two kinds, each
in a process of its own with the GIL handed over every 1 ms as in the services:

- ``sync``: grpcio's sync server, a thread per stream, each waiting on a queue of its own;
- ``aio``: grpc.aio, a coroutine per stream on one event loop; the sampler hands each message
  to the loop once (call_soon_threadsafe), the loop puts it on the streams' queues;
- ``aio-fd``: grpc.aio, each stream woken through an eventfd of its own that stays registered
  with the loop, as ForceSensor's streams are (services/runtime/aio_server.py).

The operator (decimation 1) is one client in this process; the observers (decimation 10, a
thread and a connection each, as bench/force.py's) are in a process of their own. Latency is
the operator's: received minus made. A tenant process (bench/probes/tenant.py) stands in for
the station's world: every 1 ms it computes for `--tenant` of a millisecond (0.33 by default,
the world's share of a core in the observers rows), on absolute deadlines as the world's loop
does.
"""

from __future__ import annotations

import argparse
import asyncio
import collections
import os
import queue
import subprocess
import sys
import threading
import time
from concurrent import futures

import grpc
import numpy as np
from google.protobuf.timestamp_pb2 import Timestamp

from bench.cpu import process_cpu_s
from bench.probes.tenant import start_tenant
from services.common.wakeup import reset_eventfd
from services.runtime.process import GIL_SWITCH_INTERVAL_S
from telerobot.v1 import force_sensor_pb2 as pb

KINDS = ("sync", "aio", "aio-fd")
METHOD = "/telerobot.v1.ForceSensor/StreamWrench"
PERIOD_S = 0.001
OBSERVER_DECIMATION = 10
WARMUP_S = 0.5


def _message(sequence: int) -> bytes:
    now = time.time_ns()
    sample = pb.WrenchSample(sequence=sequence, sample_time=Timestamp(
        seconds=now // 1_000_000_000, nanos=now % 1_000_000_000))
    sample.wrench.force_n.z = 1.0
    return pb.StreamWrenchResponse(samples=[sample]).SerializeToString()


def _sample_forever(publish) -> None:
    """Call publish(sequence, bytes) every PERIOD_S, on absolute deadlines."""
    start = time.perf_counter()
    sequence = 0
    while True:
        sequence += 1
        delay = start + sequence * PERIOD_S - time.perf_counter()
        if delay > 0:
            time.sleep(delay)
        publish(sequence, _message(sequence))


class _SyncFanout:
    def __init__(self):
        self._lock = threading.Lock()
        self._queues: dict[queue.SimpleQueue, int] = {}

    def publish(self, sequence: int, payload: bytes) -> None:
        with self._lock:
            for inbox, decimation in self._queues.items():
                if sequence % decimation == 0:
                    inbox.put(payload)

    def stream(self, request, context):
        inbox: queue.SimpleQueue = queue.SimpleQueue()
        with self._lock:
            self._queues[inbox] = max(1, request.decimation)
        try:
            while context.is_active():
                try:
                    yield inbox.get(timeout=0.1)
                except queue.Empty:
                    continue
        finally:
            with self._lock:
                del self._queues[inbox]


class _AioFanout:
    def __init__(self, loop: asyncio.AbstractEventLoop):
        self._loop = loop
        self._queues: dict[asyncio.Queue, int] = {}

    def publish(self, sequence: int, payload: bytes) -> None:  # the sampler's thread
        self._loop.call_soon_threadsafe(self._fan_out, sequence, payload)

    def _fan_out(self, sequence: int, payload: bytes) -> None:  # the loop's thread
        for inbox, decimation in self._queues.items():
            if sequence % decimation == 0:
                inbox.put_nowait(payload)

    async def stream(self, request, context):
        inbox: asyncio.Queue = asyncio.Queue()
        self._queues[inbox] = max(1, request.decimation)
        try:
            while True:
                yield await inbox.get()
        finally:
            del self._queues[inbox]


class _FdFanout:
    """ForceSensor's way on grpc.aio: each stream has an eventfd of its own, which the sampler
    writes for each message it queues for it, and which stays registered with the loop
    (add_reader) for the stream's life; the stream's coroutine awaits a future that the fd's
    reader resolves."""

    def __init__(self):
        self._lock = threading.Lock()
        self._inboxes: dict[int, tuple[collections.deque, int]] = {}

    def publish(self, sequence: int, payload: bytes) -> None:  # the sampler's thread
        with self._lock:
            inboxes = list(self._inboxes.items())
        for fd, (inbox, decimation) in inboxes:
            if sequence % decimation == 0:
                inbox.append(payload)
                os.eventfd_write(fd, 1)

    async def stream(self, request, context):
        loop = asyncio.get_running_loop()
        fd = os.eventfd(0, os.EFD_NONBLOCK | os.EFD_CLOEXEC)
        inbox: collections.deque = collections.deque()
        waiter = loop.create_future()

        def readable():
            reset_eventfd(fd)
            if not waiter.done():
                waiter.set_result(None)

        loop.add_reader(fd, readable)
        with self._lock:
            self._inboxes[fd] = (inbox, max(1, request.decimation))
        try:
            while True:
                while inbox:
                    yield inbox.popleft()
                waiter = loop.create_future()
                if not inbox:
                    await waiter
        finally:
            with self._lock:
                del self._inboxes[fd]
            loop.remove_reader(fd)
            # The sampler may hold it from its snapshot: closed once it cannot be written.
            threading.Timer(1.0, os.close, (fd,)).start()


def _handler(stream) -> grpc.GenericRpcHandler:
    # No response serializer: the streams send the sampler's bytes as they are.
    return grpc.method_handlers_generic_handler("telerobot.v1.ForceSensor", {
        "StreamWrench": grpc.unary_stream_rpc_method_handler(
            stream, request_deserializer=pb.StreamWrenchRequest.FromString)})


def serve(kind: str) -> None:
    """Serve `kind` on a free loopback port, print the port, run until stdin closes."""
    sys.setswitchinterval(GIL_SWITCH_INTERVAL_S)
    if kind == "sync":
        fanout = _SyncFanout()
        server = grpc.server(futures.ThreadPoolExecutor(max_workers=64))
        server.add_generic_rpc_handlers((_handler(fanout.stream),))
        port = server.add_insecure_port("127.0.0.1:0")
        server.start()
        threading.Thread(target=_sample_forever, args=(fanout.publish,), daemon=True).start()
        print(port, flush=True)
        sys.stdin.read()
        server.stop(0)
        return

    async def main():
        fanout = (_AioFanout(asyncio.get_running_loop()) if kind == "aio"
                  else _FdFanout())
        server = grpc.aio.server()
        server.add_generic_rpc_handlers((_handler(fanout.stream),))
        port = server.add_insecure_port("127.0.0.1:0")
        await server.start()
        threading.Thread(target=_sample_forever, args=(fanout.publish,), daemon=True).start()
        print(port, flush=True)
        await asyncio.get_running_loop().run_in_executor(None, sys.stdin.read)
        await server.stop(0)

    asyncio.run(main())


def _stream(port: int, decimation: int):
    channel = grpc.insecure_channel(f"127.0.0.1:{port}",
                                    options=[("grpc.use_local_subchannel_pool", 1)])
    call = channel.unary_stream(METHOD, request_serializer=pb.StreamWrenchRequest.SerializeToString,
                                response_deserializer=pb.StreamWrenchResponse.FromString)(
        pb.StreamWrenchRequest(decimation=decimation, batch_size=1))
    return channel, call


def observe(port: int, count: int) -> None:
    """`count` observers until stdin closes; prints `ready` once each has a message, and at
    the end the messages they received."""
    received = [0] * count
    first = [threading.Event() for _ in range(count)]
    calls = []

    def run(index: int, call):
        try:
            for _ in call:
                received[index] += 1
                first[index].set()
        except grpc.RpcError:
            pass

    for index in range(count):
        channel, call = _stream(port, OBSERVER_DECIMATION)
        calls.append((channel, call))
        threading.Thread(target=run, args=(index, call), daemon=True).start()
    for event in first:
        event.wait(10)
    print("ready", flush=True)
    sys.stdin.read()
    for channel, call in calls:
        call.cancel()
        channel.close()
    print(sum(received), flush=True)


def operator(kind: str, observers: int, seconds: float, tenant_share: float) -> str:
    server = subprocess.Popen([sys.executable, "-m", "bench.probes.fanout", "--serve", kind],
                              stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
    world = start_tenant(tenant_share)
    watchers = None
    try:
        port = int(server.stdout.readline())
        if observers:
            watchers = subprocess.Popen(
                [sys.executable, "-m", "bench.probes.fanout", "--observe", str(observers),
                 "--port", str(port)], stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
            if watchers.stdout.readline().strip() != "ready":
                raise RuntimeError("the observers did not start")
        channel, call = _stream(port, 1)
        latencies, count = [], 0
        start = time.monotonic()
        cpu_start = None
        for message in call:
            now = time.time_ns()
            elapsed = time.monotonic() - start
            if elapsed < WARMUP_S:
                continue
            if cpu_start is None:
                cpu_start = process_cpu_s(server.pid)
            if elapsed > WARMUP_S + seconds:
                break
            made = message.samples[0].sample_time.ToNanoseconds()
            latencies.append((now - made) / 1e6)
            count += 1
        server_cpu = (process_cpu_s(server.pid) - cpu_start) / seconds
        call.cancel()
        channel.close()
        observed = ""
        if watchers is not None:
            watchers.stdin.close()
            total = int(watchers.stdout.readline() or 0)
            observed = f"  observers got {total} in all"
        ms = np.asarray(latencies)
        return (f"{kind:4s} {observers:2d} observers, tenant {tenant_share:.2f}: "
                f"operator {count / seconds:6.0f} Hz, p50 {np.percentile(ms, 50):.2f}  "
                f"p99 {np.percentile(ms, 99):.2f} ms, server {server_cpu:.0%} of a core{observed}")
    finally:
        if watchers is not None and watchers.poll() is None:
            watchers.kill()
        for process in (server, world):
            if process is not None:
                process.stdin.close()
                process.wait(10)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m bench.probes.fanout",
                                     description=__doc__.split("\n\n")[0])
    parser.add_argument("--serve", choices=KINDS, help=argparse.SUPPRESS)
    parser.add_argument("--observe", type=int, help=argparse.SUPPRESS)
    parser.add_argument("--port", type=int, help=argparse.SUPPRESS)
    parser.add_argument("--seconds", type=float, default=4.0)
    parser.add_argument("--tenant", type=float, default=0.33,
                        help="the world's share of a core beside the server (0: none)")
    parser.add_argument("--observers", type=int, nargs="+", default=[0, 16, 32])
    args = parser.parse_args(argv)
    if args.serve:
        serve(args.serve)
        return 0
    if args.observe is not None:
        observe(args.port, args.observe)
        return 0
    for count in args.observers:
        for kind in KINDS:
            print(operator(kind, count, args.seconds, args.tenant), flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
