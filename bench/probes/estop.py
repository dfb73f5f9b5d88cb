"""python -m bench.probes.estop: how soon does a loaded Python gRPC server see a stop arrive
(the estop_under_load_proxy and estop_ds_busywork rows)? It prints figures and judges nothing;
what it showed: docs/probes.md.

Every kind serves the ProxyRobot contract (its generated code, so each method has its own
request slot in grpcio, as in the station): GetState for the load, on the low lane, and
EmergencyStop. The server notes the time each stop reaches it where the station latches its
early stop (services/runtime/rpc.py: in the interceptor, on gRPC's polling thread, before any
handler runs) and prints those times at the end: the figure is sent → seen, with no handler,
arm or world in it. The GIL is handed over every 1 ms, as in the services. Each server runs
in a process of its own; the load comes from one grpc.aio client in another, as
bench/estop.py's does. `--tenant SHARE` runs a process computing SHARE of every millisecond
beside the server (bench/probes/tenant.py; the world's share of a core is about 0.33).

- ``bare-paced``: grpcio's sync server (a thread pool as large as the station's), a GetState
  that does nothing, and a load offering 1000 calls/s with at most 200 in flight: the rate
  ProxyRobot serves estop_under_load_proxy's load at;
- ``bare-saturated``: the same server under estop_under_load_proxy's load itself: 200
  GetState calls in flight, each re-issued as soon as it returns, so the server is never idle
  however fast it answers;
- ``aio-saturated``: the same on grpc.aio, the interceptor an async one;
- ``aio-servicer``: ProxyRobot's own servicer (on an arm at rest, bench/probes/arm.py, no
  monitor thread) on grpc.aio, its sync handlers run in the server's migration thread pool,
  under the same load;
- ``stack-saturated``: ProxyRobot's servicer behind the station's server stack
  (services/runtime/server.py: lanes, interceptors, metrics), under the same load;
- ``aio-stack``: the same stack on grpc.aio (`create_server(aio=True)`, ProxyRobot's
  `--aio-server`), under the same load;
- ``bare-busy``: the bare server, GetState computing 20 ms on the DecisionServer's own
  SimulatedProcessor (1 ms slices, one at a time in the process), at most 4 calls at once (the
  low lane's threads), 200 calls in flight each re-issued as it returns: the load of
  estop_ds_busywork.
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

from bench.probes.arm import proxy_robot_servicer
from bench.probes.tenant import start_tenant
from services.runtime.process import GIL_SWITCH_INTERVAL_S
from telerobot.v1 import proxy_robot_pb2 as pb
from telerobot.v1 import proxy_robot_pb2_grpc

KINDS = ("bare-paced", "bare-saturated", "aio-saturated", "aio-servicer", "stack-saturated",
         "aio-stack", "bare-busy")
PACED = ("bare-paced",)
STOP = "/telerobot.v1.ProxyRobot/EmergencyStop"
LOW_LANE = (("telerobot-lane", "low"),)
POOL_SIZE = 600  # about the station's (services/runtime/server.py: lanes + streams + 16)
BUSY_S = 0.02
LANE_THREADS = 4  # the low lane's most
CONCURRENCY = 200
FLOOD_RATE_HZ = 1000.0
GAP_S = 0.02  # between stops


class _Seen:
    """The times stops reached the server, in time.time_ns()."""

    def __init__(self):
        self.times_ns: list[int] = []

    def stop_arrived(self) -> None:
        self.times_ns.append(time.time_ns())

    def noted(self, method: str) -> None:
        if method == STOP:
            self.stop_arrived()


class _SyncSeen(grpc.ServerInterceptor):
    def __init__(self, seen: _Seen):
        self._seen = seen

    def intercept_service(self, continuation, handler_call_details):
        self._seen.noted(handler_call_details.method)
        return continuation(handler_call_details)


class _AioSeen(grpc.aio.ServerInterceptor):
    def __init__(self, seen: _Seen):
        self._seen = seen

    async def intercept_service(self, continuation, handler_call_details):
        self._seen.noted(handler_call_details.method)
        return await continuation(handler_call_details)


class _Bare(proxy_robot_pb2_grpc.ProxyRobotServicer):
    """GetState does `work` (nothing by default); EmergencyStop answers at once."""

    def __init__(self, work=lambda: None):
        self._work = work

    def GetState(self, request, context):
        self._work()
        return pb.GetStateResponse()

    def EmergencyStop(self, request, context):
        return pb.EmergencyStopResponse()


class _AioBare(proxy_robot_pb2_grpc.ProxyRobotServicer):
    async def GetState(self, request, context):
        return pb.GetStateResponse()

    async def EmergencyStop(self, request, context):
        return pb.EmergencyStopResponse()


def _busy_work(lane: threading.Semaphore, processor):
    """BusyWork as the DecisionServer runs it: on one of the lane's threads, computing on its
    SimulatedProcessor (services/decision_server/cobegin.py) in 1 ms slices."""
    def work() -> None:
        with lane:
            processor.run(0, BUSY_S)
    return work


def _report_when_stdin_closes(seen: _Seen) -> None:
    sys.stdin.read()
    print(" ".join(map(str, seen.times_ns)), flush=True)


def serve(kind: str) -> None:
    """Serve `kind` on a free loopback port, print the port; when stdin closes, print the
    times the stops arrived and stop."""
    sys.setswitchinterval(GIL_SWITCH_INTERVAL_S)
    seen = _Seen()
    if kind.startswith("aio"):
        async def main():
            if kind == "aio-saturated":
                server = grpc.aio.server(interceptors=[_AioSeen(seen)])
                proxy_robot_pb2_grpc.add_ProxyRobotServicer_to_server(_AioBare(), server)
            else:  # the sync servicer's handlers run in the server's migration thread pool
                server = grpc.aio.server(interceptors=[_AioSeen(seen)],
                                         migration_thread_pool=futures.ThreadPoolExecutor(
                                             max_workers=POOL_SIZE))
                proxy_robot_pb2_grpc.add_ProxyRobotServicer_to_server(proxy_robot_servicer(),
                                                                      server)
            port = server.add_insecure_port("127.0.0.1:0")
            await server.start()
            print(port, flush=True)
            await asyncio.get_running_loop().run_in_executor(None, _report_when_stdin_closes,
                                                             seen)
            await server.stop(0)

        asyncio.run(main())
        return
    if kind in ("stack-saturated", "aio-stack"):
        from services.runtime.metrics import ServiceMetrics
        from services.runtime.server import binding, create_server

        server, port = create_server(
            "127.0.0.1:0", [binding(proxy_robot_pb2_grpc, "ProxyRobot", proxy_robot_servicer())],
            on_emergency_call=seen.stop_arrived, metrics=ServiceMetrics("probe"),
            aio=kind == "aio-stack")
    else:
        from services.decision_server.cobegin import SimulatedProcessor

        work = (_busy_work(threading.Semaphore(LANE_THREADS), SimulatedProcessor())
                if kind == "bare-busy" else (lambda: None))
        server = grpc.server(futures.ThreadPoolExecutor(max_workers=POOL_SIZE),
                             interceptors=[_SyncSeen(seen)])
        proxy_robot_pb2_grpc.add_ProxyRobotServicer_to_server(_Bare(work), server)
        port = server.add_insecure_port("127.0.0.1:0")
    server.start()
    print(port, flush=True)
    _report_when_stdin_closes(seen)
    server.stop(0)


def load(port: int, rate_hz: float) -> None:
    """GetState calls on the low lane, at most CONCURRENCY in flight, until stdin closes:
    offered at `rate_hz`, or each re-issued as it returns when `rate_hz` is 0. Prints `ready`
    once CONCURRENCY calls have been answered, and at the end how many were made after that."""

    async def main():
        done = asyncio.Event()
        loop = asyncio.get_running_loop()
        loop.run_in_executor(None, lambda: (sys.stdin.read(), loop.call_soon_threadsafe(done.set)))
        slots = asyncio.Semaphore(CONCURRENCY)
        calls, announced = 0, False
        async with grpc.aio.insecure_channel(f"127.0.0.1:{port}") as channel:
            get_state = proxy_robot_pb2_grpc.ProxyRobotStub(channel).GetState

            async def one_call():
                nonlocal calls, announced
                try:
                    await get_state(pb.GetStateRequest(), metadata=LOW_LANE, timeout=5.0)
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


def stops(kind: str, trials: int, tenant_share: float = 0.0) -> str:
    server = subprocess.Popen([sys.executable, "-m", "bench.probes.estop", "--serve", kind],
                              stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
    world = start_tenant(tenant_share)
    loader = None
    try:
        port = int(server.stdout.readline())
        with grpc.insecure_channel(f"127.0.0.1:{port}") as channel:
            stop = proxy_robot_pb2_grpc.ProxyRobotStub(channel).EmergencyStop
            sent_ns = [time.time_ns()]
            stop(pb.EmergencyStopRequest(reason="probe"), timeout=10.0)  # connected first
            loader = subprocess.Popen(
                [sys.executable, "-m", "bench.probes.estop", "--load", "--port", str(port),
                 "--rate", str(FLOOD_RATE_HZ if kind in PACED else 0)],
                stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
            if loader.stdout.readline().strip() != "ready":
                raise RuntimeError("the load did not start")
            started = time.monotonic()
            answered_ms = []
            for _ in range(trials):
                time.sleep(GAP_S)
                sent_ns.append(time.time_ns())
                stop(pb.EmergencyStopRequest(reason="probe"), timeout=5.0)
                answered_ms.append((time.time_ns() - sent_ns[-1]) / 1e6)
            elapsed = time.monotonic() - started
            loader.stdin.close()
            calls = int(loader.stdout.readline() or 0)
        server.stdin.close()
        seen_ns = [int(t) for t in server.stdout.readline().split()]
        if len(seen_ns) != len(sent_ns):
            raise RuntimeError(f"{len(sent_ns)} stops sent, {len(seen_ns)} seen")
        seen = (np.asarray(seen_ns[1:]) - np.asarray(sent_ns[1:])) / 1e6
        answered = np.asarray(answered_ms)
        return (f"{kind:15s} under {calls / elapsed:5.0f} GetState/s, tenant "
                f"{tenant_share:.2f}: stop seen p50 "
                f"{np.percentile(seen, 50):.2f}  p99 {np.percentile(seen, 99):.2f} ms; "
                f"answered p50 {np.percentile(answered, 50):.2f}  "
                f"p99 {np.percentile(answered, 99):.2f} ms")
    finally:
        if loader is not None and loader.poll() is None:
            loader.kill()
        if server.poll() is None:
            server.stdin.close()
            server.wait(10)
        if world is not None:
            world.stdin.close()
            world.wait(10)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m bench.probes.estop",
                                     description=__doc__.split("\n\n")[0])
    parser.add_argument("--serve", choices=KINDS, help=argparse.SUPPRESS)
    parser.add_argument("--load", action="store_true", help=argparse.SUPPRESS)
    parser.add_argument("--port", type=int, help=argparse.SUPPRESS)
    parser.add_argument("--rate", type=float, help=argparse.SUPPRESS)
    parser.add_argument("--trials", type=int, default=100)
    parser.add_argument("--kinds", nargs="+", choices=KINDS, default=list(KINDS))
    parser.add_argument("--tenant", type=float, default=0.0,
                        help="share of a core a tenant process computes beside the server, "
                             "every 1 ms (the world's is about 0.33; default: no tenant)")
    args = parser.parse_args(argv)
    if args.serve:
        serve(args.serve)
        return 0
    if args.load:
        load(args.port, args.rate)
        return 0
    for kind in args.kinds:
        print(stops(kind, args.trials, args.tenant), flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
