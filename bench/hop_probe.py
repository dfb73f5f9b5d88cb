"""python -m bench.hop_probe: what one ProxyRobot move costs, and what share of it gRPC takes.
A probe, not a scenario (issue #12's limits): it prints figures, it judges nothing.

1. The move handler alone (ProxyRobotServicer.MoveCartesianIncremental on the tests' fake arm:
   the request's checks, IK, the singularity check, the target written), called in a loop
   back to back, then with the caller asleep 0.5 ms and 2 ms between calls, as a 1 kHz or a
   500 Hz stream leaves it.
2. One lockstep client at 1 kHz against a server in a process of its own, three ways: a no-op
   handler on grpcio's sync server (the transport's floor), the real handler on a bare sync
   server, and the real handler behind the station's server stack (lanes, interceptors,
   metrics: services/runtime/server.py).

Seen on the 2-core VM, quiet (load 0.5-2), 2026-11-26, two runs, p50 / p99 in ms:
- the handler back to back 0.27-0.29 / 0.61-0.63; 0.5 ms apart 0.67-0.79 / 0.97-1.14; 2 ms
  apart 0.79-0.81 / 1.04-1.33. The same code costs 2.5 times as much when it runs once a
  millisecond as in a tight loop: its caches are cold again each time.
- the round trip, paced at 1 kHz: no-op 0.81-0.84 / 1.01-1.10; the real handler 1.55-1.62 /
  2.14-2.39 on the bare server and 1.70-1.74 / 2.05-2.13 behind the stack. The stack adds
  little; grpcio's sync unary itself, paced at 1 kHz, takes 0.8 ms with nothing to do.
So a lockstep command stream at 1 kHz (a round trip under 1 ms, every time) is out of reach of
grpcio's sync unary call on this machine whatever the handler does: its no-op round trip is
0.8 ms at p50 and over 1 ms at p99. (The zmq baseline, REQ/REP with the real handler, keeps
978 Hz at 0.70 ms p50 in the bench: bench/README.md.)
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import time
from concurrent import futures

import grpc
import numpy as np

from telerobot.v1 import proxy_robot_pb2 as pb
from telerobot.v1 import proxy_robot_pb2_grpc, types_pb2
from wire import convert

KINDS = ("noop", "bare", "stack")
GIL_SWITCH_INTERVAL_S = 0.001  # as every service sets it
WARMUP = 200


def _servicer():
    """ProxyRobot's servicer on a fake arm and fake clock, connected and at rest at home."""
    from services.proxy_robot.core import ProxyRobotCore
    from services.proxy_robot.servicer import ProxyRobotServicer
    from tests.fakes.arm_link import FakeArm
    from tests.fakes.clock import FakeClock

    clock = FakeClock()
    arm = FakeArm(clock)
    core = ProxyRobotCore(arm.open_link, clock=clock, threads=False)
    core.connect()
    core.initialize()
    clock.advance(0.01)
    core.sample_once()
    return ProxyRobotServicer(core)


def _request(sign: int) -> pb.MoveCartesianIncrementalRequest:
    """A 1 µm step along base y, back and forth, so the arm stays where it is."""
    return pb.MoveCartesianIncrementalRequest(
        delta_position_m=types_pb2.Vector3(y=sign * 1e-6),
        delta_rotation=convert.rotation_to_proto(np.eye(3)),
        frame=types_pb2.REFERENCE_FRAME_BASE)


def _percentiles(ms: np.ndarray) -> str:
    return f"p50 {np.percentile(ms, 50):.2f}  p90 {np.percentile(ms, 90):.2f}  " \
           f"p99 {np.percentile(ms, 99):.2f} ms"


def handler_alone(calls: int) -> None:
    servicer = _servicer()
    for gap_s in (0.0, 0.0005, 0.002):
        took = []
        for i in range(WARMUP + calls):
            if gap_s:
                time.sleep(gap_s)
            started = time.perf_counter()
            servicer.MoveCartesianIncremental(_request(1 if i % 2 else -1), None)
            took.append(time.perf_counter() - started)
        print(f"handler, {gap_s * 1e3:.1f} ms apart:".ljust(34),
              _percentiles(np.asarray(took[WARMUP:]) * 1e3))


class _Noop(proxy_robot_pb2_grpc.ProxyRobotServicer):
    def MoveCartesianIncremental(self, request, context):
        return pb.MoveCartesianIncrementalResponse()


def serve(kind: str) -> None:
    """Serve `kind` on a free loopback port, print the port, run until stdin closes."""
    sys.setswitchinterval(GIL_SWITCH_INTERVAL_S)
    if kind == "stack":
        from services.runtime.server import binding, create_server

        server, port = create_server(
            "127.0.0.1:0", [binding(proxy_robot_pb2_grpc, "ProxyRobot", _servicer())])
    else:
        server = grpc.server(futures.ThreadPoolExecutor(max_workers=16))
        proxy_robot_pb2_grpc.add_ProxyRobotServicer_to_server(
            _Noop() if kind == "noop" else _servicer(), server)
        port = server.add_insecure_port("127.0.0.1:0")
    server.start()
    print(port, flush=True)
    sys.stdin.read()
    server.stop(0)


def round_trips(kind: str, calls: int, rate_hz: float) -> None:
    server = subprocess.Popen([sys.executable, "-m", "bench.hop_probe", "--serve", kind],
                              stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
    try:
        port = int(server.stdout.readline())
        with grpc.insecure_channel(f"127.0.0.1:{port}") as channel:
            move = proxy_robot_pb2_grpc.ProxyRobotStub(channel).MoveCartesianIncremental
            took = []
            start = time.perf_counter()
            for i in range(WARMUP + calls):
                delay = start + i / rate_hz - time.perf_counter()
                if delay > 0:
                    time.sleep(delay)
                started = time.perf_counter()
                move(_request(1 if i % 2 else -1), timeout=5.0)
                took.append(time.perf_counter() - started)
        print(f"round trip at {rate_hz:.0f} Hz, {kind}:".ljust(34),
              _percentiles(np.asarray(took[WARMUP:]) * 1e3))
    finally:
        server.stdin.close()
        server.wait(10)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m bench.hop_probe",
                                     description=__doc__.split("\n\n")[0])
    parser.add_argument("--serve", choices=KINDS, help=argparse.SUPPRESS)
    parser.add_argument("--calls", type=int, default=2000)
    parser.add_argument("--rate", type=float, default=1000.0)
    args = parser.parse_args(argv)
    if args.serve:
        serve(args.serve)
        return 0
    handler_alone(args.calls)
    for kind in KINDS:
        round_trips(kind, args.calls, args.rate)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
