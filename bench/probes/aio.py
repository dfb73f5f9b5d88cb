"""python -m bench.probes.aio: would grpc.aio make the Teleoperate stream faster? It prints
figures and judges nothing; what it showed: docs/probes.md. The same bidirectional echo served
three ways, each in a process of its own, driven at 1 kHz (pipelined) by one grpc.aio client:

- ``sync``: grpcio's sync server; the handler does the work and yields the ack;
- ``sync-threads``: grpcio's sync server in the DecisionServer's three threads
  (services/common/inbox.py): one reads, one does the work on each batch, the handler yields
  the acks;
- ``aio-inline``: grpc.aio, the work done in the event loop;
- ``aio-executor``: grpc.aio, the work handed to a thread (run_in_executor) and awaited, as
  blocking domain code would have to be;
- ``sync-bare``: grpcio's sync server with no work and no busy threads: the transport's own
  cost.

Each line also gives the server process's CPU time per message (user and system, from /proc).

"Work" is WORK_S of pure Python per message (about a merged move's CPU in the DecisionServer),
and three threads in the server burn the GIL 1 ms in every 10 (the DecisionServer's followers,
watchdogs and grpcio threads), so the GIL is contended as in the real process. Every server
hands the GIL over every 1 ms, as the services do.
"""

from __future__ import annotations

import argparse
import asyncio
import subprocess
import sys
import tempfile
import threading
import time
from concurrent import futures
from pathlib import Path

import grpc
import numpy as np

from bench.cpu import process_cpu_s
from bench.probes.tenant import start_tenant
from services.common.inbox import Inbox, Producer
from services.runtime.process import GIL_SWITCH_INTERVAL_S
from telerobot.v1 import decision_server_pb2 as pb
from telerobot.v1 import decision_server_pb2_grpc as pb_grpc

WORK_S = 0.0003
KINDS = ("sync", "sync-threads", "aio-inline", "aio-executor", "sync-bare")


def _work() -> None:
    started = time.perf_counter()
    while time.perf_counter() - started < WORK_S:
        pass


def _busy_threads(count: int = 3) -> None:
    def burn():
        while True:
            time.sleep(0.01)
            started = time.perf_counter()
            while time.perf_counter() - started < 0.001:
                pass

    for _ in range(count):
        threading.Thread(target=burn, daemon=True).start()


def _ack(request: pb.TeleoperateRequest) -> pb.TeleoperateResponse:
    return pb.TeleoperateResponse(ack=pb.CommandAck(sequence=request.command.sequence))


class SyncEcho(pb_grpc.DecisionServerServicer):
    def __init__(self, work: bool = True):
        self._work = work

    def Teleoperate(self, requests, context):
        for request in requests:
            if self._work:
                _work()
            yield _ack(request)


class ThreadedEcho(pb_grpc.DecisionServerServicer):
    def Teleoperate(self, requests, context):
        inbox = Inbox(requests, lambda request: request)

        def serve(emit) -> None:
            while batch := inbox.take():
                _work()
                for request in batch:
                    emit(_ack(request))

        try:
            yield from Producer(serve)
        finally:
            inbox.close()


class AioEcho(pb_grpc.DecisionServerServicer):
    def __init__(self, inline: bool):
        self._inline = inline
        self._pool = futures.ThreadPoolExecutor(2)

    async def Teleoperate(self, requests, context):
        loop = asyncio.get_running_loop()
        async for request in requests:
            if self._inline:
                _work()
            else:
                await loop.run_in_executor(self._pool, _work)
            await context.write(_ack(request))


def serve(kind: str, port_file: Path) -> None:
    sys.setswitchinterval(GIL_SWITCH_INTERVAL_S)
    if kind != "sync-bare":
        _busy_threads()
    if kind.startswith("sync"):
        server = grpc.server(futures.ThreadPoolExecutor(16))
        echo = ThreadedEcho() if kind == "sync-threads" else SyncEcho(work=kind == "sync")
        pb_grpc.add_DecisionServerServicer_to_server(echo, server)
        port_file.write_text(str(server.add_insecure_port("127.0.0.1:0")))
        server.start()
        server.wait_for_termination()
        return

    async def main():
        server = grpc.aio.server()
        pb_grpc.add_DecisionServerServicer_to_server(AioEcho(kind == "aio-inline"), server)
        port_file.write_text(str(server.add_insecure_port("127.0.0.1:0")))
        await server.start()
        await server.wait_for_termination()

    asyncio.run(main())


async def drive(port: int, rate_hz: float, seconds: float) -> tuple[int, int, np.ndarray]:
    """Pipelined commands at rate_hz on absolute deadlines: (sent, acked, round trips in ms)."""
    async with grpc.aio.insecure_channel(f"127.0.0.1:{port}") as channel:
        call = pb_grpc.DecisionServerStub(channel).Teleoperate()
        sent: dict[int, int] = {}
        round_trips: list[int] = []

        async def read():
            async for response in call:
                started = sent.pop(response.ack.sequence, None)
                if started is not None:
                    round_trips.append(time.perf_counter_ns() - started)

        reader = asyncio.create_task(read())
        count = int(rate_hz * seconds)
        start = time.perf_counter()
        for sequence in range(1, count + 1):
            delay = start + sequence / rate_hz - time.perf_counter()
            if delay > 0:
                await asyncio.sleep(delay)
            sent[sequence] = time.perf_counter_ns()
            await call.write(pb.TeleoperateRequest(command=pb.MasterCommand(sequence=sequence)))
        await asyncio.sleep(0.5)
        await call.done_writing()
        reader.cancel()
        return count, len(round_trips), np.asarray(round_trips) / 1e6


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m bench.probes.aio",
                                     description=__doc__.split("\n\n")[0])
    parser.add_argument("--serve", choices=KINDS, help=argparse.SUPPRESS)
    parser.add_argument("--port-file", help=argparse.SUPPRESS)
    parser.add_argument("--rate", type=float, default=1000.0)
    parser.add_argument("--seconds", type=float, default=3.0)
    parser.add_argument("--tenants", type=float, nargs="*", default=[],
                        help="shares of a core computed by tenant processes beside the server "
                             "(bench/probes/tenant.py), e.g. 0.6 0.6: a machine the station "
                             "keeps busy")
    args = parser.parse_args(argv)
    if args.serve:
        serve(args.serve, Path(args.port_file))
        return 0
    tenants = [tenant for share in args.tenants if (tenant := start_tenant(share))]
    try:
        for kind in KINDS:
            _measure(kind, args.rate, args.seconds)
    finally:
        for tenant in tenants:
            tenant.stdin.close()
            tenant.wait(5)
    return 0


def _measure(kind: str, rate: float, seconds: float) -> None:
    with tempfile.TemporaryDirectory() as scratch:
        port_file = Path(scratch) / "port"
        server = subprocess.Popen([sys.executable, "-m", "bench.probes.aio", "--serve", kind,
                                   "--port-file", str(port_file)])
        try:
            while not port_file.exists() or not port_file.read_text():
                if server.poll() is not None:
                    raise RuntimeError(f"the {kind} server exited")
                time.sleep(0.05)
            cpu_before = process_cpu_s(server.pid)
            sent, acked, ms = asyncio.run(drive(int(port_file.read_text()), rate, seconds))
            cpu_ms = (process_cpu_s(server.pid) - cpu_before) * 1e3 / sent
        finally:
            server.terminate()
            server.wait(5)
    print(f"{kind:13s} acked {acked}/{sent}  round trip p50 {np.percentile(ms, 50):7.2f}"
          f"  p99 {np.percentile(ms, 99):7.2f} ms  server CPU {cpu_ms:.3f} ms/message",
          flush=True)


if __name__ == "__main__":
    raise SystemExit(main())
