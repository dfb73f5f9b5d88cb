"""python -m bench.estop_probe: how soon can a loaded Python gRPC server see a stop arrive? A
probe, not a scenario (issue #12's limits, the estop_under_load_proxy and estop_ds_busywork
rows): it prints figures, it judges nothing.

The server is bare: a `Work` method for the load and a `Stop` method, and an interceptor that
notes the time a Stop call reaches it, as the station's LaneInterceptor latches its early stop
(services/runtime/rpc.py: on gRPC's polling thread, before any handler runs). Stop answers with
that time, so the figure is sent → seen by the interceptor, with no handler, lane or arm in it:
the floor under the station's stop through a loaded ProxyRobot or DecisionServer. The GIL is
handed over every 1 ms, as in the services. Three kinds, each server in a process of its own:

- ``sync-flood``: grpcio's sync server (a thread pool as large as the station's), `Work` does
  nothing, and the load offers it 1000 calls/s with at most 200 in flight: the rate ProxyRobot
  served estop_under_load_proxy's load at (its `load_calls_per_s`, 875-1045), with less work
  in each call;
- ``sync-busy``: the same server, `Work` computes 20 ms in Python in 1 ms slices, at most 4
  calls at once (the low lane's threads) and one slice at a time in the process (the
  DecisionServer's SimulatedProcessor), 200 calls in flight each re-issued as it returns: the
  load of estop_ds_busywork;
- ``aio-flood``: grpc.aio with the flood, the interceptor an async one.

The load comes from one grpc.aio client in a process of its own, as bench/estop.py's does.

Seen on the 2-core VM, quiet, 2026-11-26, two runs of 100 stops each (sent → seen by the
interceptor, p50 / p99 in ms):
- sync-flood at 1000-1094 calls/s: 0.45-0.47 / 1.03-1.10. aio-flood: 0.67 / 1.52-1.64.
- sync-busy: 1.73-1.74 / **7.26-7.34**. (Its load made 119-188 calls/s, counting the ones
  that ran out of their 5 s deadline in the queue; the DecisionServer's made 42/s with some
  DEADLINE_EXCEEDED. The processor is as busy in both: one 1 ms slice at a time.)

So under a computing load the stop reaches the interceptor, the earliest point a Python
service can act on it, over 5 ms late at p99 before anything is done with it: the GIL is
handed between the computing threads and gRPC's polling thread, 1 ms at a time. The
DecisionServer must then forward the stop to ProxyRobot (one more hop), so estop_ds_busywork's
5 ms is out of reach in one Python process. A flood of cheap calls, on the other hand, delays
a bare server's stop by 1 ms at most: estop_under_load_proxy's 16-44 ms at p99 is ProxyRobot's
own stack under that flood, not the transport (bench/README.md → Profiles).

A first try at that stack, each call's wrapped handler kept by method instead of built on the
polling thread for every call, changed nothing in two alternating A/B pairs of `--only estop`
(50 stops each: p99 29.7, 38.6 ms before, 35.7, 29.7 after), and was dropped. Neither did
SCHED_FIFO for the emergency-stop band (p99 5.5 and 5.1 ms under load, against 4.5-7.4
without), nor nice -10 for every server's polling thread (worse: 51 and 57 ms).
"""

from __future__ import annotations

import argparse
import asyncio
import subprocess
import sys
import threading
import time
from concurrent import futures

import grpc
import numpy as np
from google.protobuf.timestamp_pb2 import Timestamp

KINDS = ("sync-flood", "sync-busy", "aio-flood")
SERVICE = "probe.Stops"
WORK, STOP = f"/{SERVICE}/Work", f"/{SERVICE}/Stop"
GIL_SWITCH_INTERVAL_S = 0.001  # as every service sets it
POOL_SIZE = 600  # about the station's (services/runtime/server.py: lanes + streams + 16)
BUSY_S, SLICE_S = 0.02, 0.001
LANE_THREADS = 4  # the low lane's most
CONCURRENCY = 200
FLOOD_RATE_HZ = 1000.0
GAP_S = 0.02  # between stops


class _Seen:
    """When the interceptor last saw a Stop arrive."""

    def __init__(self):
        self.at_ns = 0

    def stop_arrived(self, method: str) -> None:
        if method == STOP:
            self.at_ns = time.time_ns()

    def answer(self, request: bytes, context) -> bytes:
        return Timestamp(seconds=self.at_ns // 1_000_000_000,
                         nanos=self.at_ns % 1_000_000_000).SerializeToString()


class _SyncSeen(grpc.ServerInterceptor):
    def __init__(self, seen: _Seen):
        self._seen = seen

    def intercept_service(self, continuation, handler_call_details):
        self._seen.stop_arrived(handler_call_details.method)
        return continuation(handler_call_details)


class _AioSeen(grpc.aio.ServerInterceptor):
    def __init__(self, seen: _Seen):
        self._seen = seen

    async def intercept_service(self, continuation, handler_call_details):
        self._seen.stop_arrived(handler_call_details.method)
        return await continuation(handler_call_details)


def _handlers(seen: _Seen, work) -> grpc.GenericRpcHandler:
    # No (de)serializers: requests and answers are bytes.
    return grpc.method_handlers_generic_handler(SERVICE, {
        "Work": grpc.unary_unary_rpc_method_handler(work),
        "Stop": grpc.unary_unary_rpc_method_handler(seen.answer)})


def _busy_work(lane: threading.Semaphore, processor: threading.Lock):
    def work(request: bytes, context) -> bytes:
        with lane:
            for _ in range(round(BUSY_S / SLICE_S)):
                with processor:
                    busy_until = time.perf_counter() + SLICE_S
                    while time.perf_counter() < busy_until:
                        pass
        return b""
    return work


def serve(kind: str) -> None:
    """Serve `kind` on a free loopback port, print the port, run until stdin closes."""
    sys.setswitchinterval(GIL_SWITCH_INTERVAL_S)
    seen = _Seen()
    if kind.startswith("sync"):
        work = (_busy_work(threading.Semaphore(LANE_THREADS), threading.Lock())
                if kind == "sync-busy"
                else lambda request, context: b"")
        server = grpc.server(futures.ThreadPoolExecutor(max_workers=POOL_SIZE),
                             interceptors=[_SyncSeen(seen)])
        server.add_generic_rpc_handlers((_handlers(seen, work),))
        port = server.add_insecure_port("127.0.0.1:0")
        server.start()
        print(port, flush=True)
        sys.stdin.read()
        server.stop(0)
        return

    async def nothing(request: bytes, context) -> bytes:
        return b""

    async def answer(request: bytes, context) -> bytes:
        return seen.answer(request, context)

    async def main():
        server = grpc.aio.server(interceptors=[_AioSeen(seen)])
        server.add_generic_rpc_handlers((grpc.method_handlers_generic_handler(SERVICE, {
            "Work": grpc.unary_unary_rpc_method_handler(nothing),
            "Stop": grpc.unary_unary_rpc_method_handler(answer)}),))
        port = server.add_insecure_port("127.0.0.1:0")
        await server.start()
        print(port, flush=True)
        await asyncio.get_running_loop().run_in_executor(None, sys.stdin.read)
        await server.stop(0)

    asyncio.run(main())


def load(port: int, rate_hz: float) -> None:
    """Work calls, at most CONCURRENCY in flight, until stdin closes: offered at `rate_hz`, or
    each re-issued as it returns when `rate_hz` is 0. Prints `ready` once CONCURRENCY calls
    have been answered, and at the end how many were made after that."""

    async def main():
        done = asyncio.Event()
        loop = asyncio.get_running_loop()
        loop.run_in_executor(None, lambda: (sys.stdin.read(), loop.call_soon_threadsafe(done.set)))
        slots = asyncio.Semaphore(CONCURRENCY)
        calls, announced = 0, False
        async with grpc.aio.insecure_channel(f"127.0.0.1:{port}") as channel:
            work = channel.unary_unary(WORK)

            async def one_call():
                nonlocal calls, announced
                try:
                    await work(b"", timeout=5.0)
                except grpc.aio.AioRpcError:
                    await asyncio.sleep(0.001)
                finally:
                    slots.release()
                calls += 1
                if not announced and calls == CONCURRENCY:
                    print("ready", flush=True)
                    announced, calls = True, 0

            tasks = set()
            start = time.perf_counter()
            offered = 0
            while not done.is_set():
                await slots.acquire()
                if rate_hz:
                    offered += 1
                    delay = start + offered / rate_hz - time.perf_counter()
                    if delay > 0:
                        await asyncio.sleep(delay)
                task = asyncio.create_task(one_call())
                tasks.add(task)
                task.add_done_callback(tasks.discard)
            await asyncio.wait(tasks, timeout=6.0)
        print(calls, flush=True)

    asyncio.run(main())


def stops(kind: str, trials: int) -> str:
    server = subprocess.Popen([sys.executable, "-m", "bench.estop_probe", "--serve", kind],
                              stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
    loader = None
    try:
        port = int(server.stdout.readline())
        with grpc.insecure_channel(f"127.0.0.1:{port}") as channel:
            grpc.channel_ready_future(channel).result(timeout=10)
            stop = channel.unary_unary(STOP, response_deserializer=Timestamp.FromString)
            stop(b"", timeout=5.0)  # the connection is up before the load starts
            loader = subprocess.Popen(
                [sys.executable, "-m", "bench.estop_probe", "--load", "--port", str(port),
                 "--rate", str(0 if kind == "sync-busy" else FLOOD_RATE_HZ)],
                stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
            if loader.stdout.readline().strip() != "ready":
                raise RuntimeError("the load did not start")
            started = time.monotonic()
            seen_ms, answered_ms = [], []
            for _ in range(trials):
                time.sleep(GAP_S)
                sent = time.time_ns()
                seen_at = stop(b"", timeout=5.0).ToNanoseconds()
                answered_ms.append((time.time_ns() - sent) / 1e6)
                seen_ms.append((seen_at - sent) / 1e6)
            elapsed = time.monotonic() - started
            loader.stdin.close()
            calls = int(loader.stdout.readline() or 0)
        seen, answered = np.asarray(seen_ms), np.asarray(answered_ms)
        return (f"{kind:10s} under {calls / elapsed:5.0f} Work calls/s: stop seen p50 "
                f"{np.percentile(seen, 50):.2f}  p99 {np.percentile(seen, 99):.2f} ms; "
                f"answered p50 {np.percentile(answered, 50):.2f}  "
                f"p99 {np.percentile(answered, 99):.2f} ms")
    finally:
        if loader is not None and loader.poll() is None:
            loader.kill()
        server.stdin.close()
        server.wait(10)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m bench.estop_probe",
                                     description=__doc__.split("\n\n")[0])
    parser.add_argument("--serve", choices=KINDS, help=argparse.SUPPRESS)
    parser.add_argument("--load", action="store_true", help=argparse.SUPPRESS)
    parser.add_argument("--port", type=int, help=argparse.SUPPRESS)
    parser.add_argument("--rate", type=float, help=argparse.SUPPRESS)
    parser.add_argument("--trials", type=int, default=100)
    parser.add_argument("--kinds", nargs="+", choices=KINDS, default=list(KINDS))
    args = parser.parse_args(argv)
    if args.serve:
        serve(args.serve)
        return 0
    if args.load:
        load(args.port, args.rate)
        return 0
    for kind in args.kinds:
        print(stops(kind, args.trials), flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
