"""python -m bench.probes.hop: what one ProxyRobot move costs, and what share of it gRPC
takes. It prints figures and judges nothing; what it showed: docs/probes.md.

1. The move handler alone (ProxyRobotServicer.MoveCartesianIncremental on an arm at rest,
   bench/probes/arm.py: the request's checks, IK, the singularity check, the target written),
   called in a loop back to back, then with the caller asleep 0.5 ms and 2 ms between calls,
   as a 1 kHz or a 500 Hz stream leaves it.
2. One lockstep client at 1 kHz against a server in a process of its own, three ways: a no-op
   handler on grpcio's sync server (the transport's floor), the real handler on a bare sync
   server, and the real handler behind the station's server stack (lanes, interceptors,
   metrics: services/runtime/server.py).
3. The same lockstep over one open gRPC stream (the no-op and the bare handler).
4. The same lockstep over ProxyRobot's local socket (wire/local_call.py), as the station's
   DecisionServer moves the arm: a no-op handler, and the real one behind ProxyRobot's request
   checks (services/proxy_robot/servicer.py's local_moves).
"""

from __future__ import annotations

import argparse
import queue
import subprocess
import sys
import tempfile
import time
from concurrent import futures
from pathlib import Path

import grpc
import numpy as np

from bench.probes.arm import proxy_robot_servicer
from services.proxy_robot.servicer import local_moves
from services.runtime.process import GIL_SWITCH_INTERVAL_S
from telerobot.v1 import proxy_robot_pb2 as pb
from telerobot.v1 import proxy_robot_pb2_grpc, types_pb2
from wire import convert
from wire.local_call import LocalCallClient, LocalCallServer

KINDS = ("noop", "bare", "stack")
STREAM_KINDS = ("noop", "bare")  # the kinds also served over a persistent stream
LOCAL_KINDS = ("noop", "bare")  # and over the local socket (bare: behind ProxyRobot's checks)
STREAM_METHOD = "/bench.probes.Hop/Moves"
MOVE_METHOD = "/telerobot.v1.ProxyRobot/MoveCartesianIncremental"
WARMUP = 200


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
    servicer = proxy_robot_servicer()
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
            "127.0.0.1:0", [binding(proxy_robot_pb2_grpc, "ProxyRobot", proxy_robot_servicer())])
    else:
        server = grpc.server(futures.ThreadPoolExecutor(max_workers=16))
        servicer = _Noop() if kind == "noop" else proxy_robot_servicer()
        proxy_robot_pb2_grpc.add_ProxyRobotServicer_to_server(servicer, server)
        server.add_generic_rpc_handlers((_stream_handler(servicer),))
        port = server.add_insecure_port("127.0.0.1:0")
    server.start()
    print(port, flush=True)
    sys.stdin.read()
    server.stop(0)


def serve_local(kind: str, path: str) -> None:
    """Serve `kind` on a local socket at `path`, say so, run until stdin closes."""
    sys.setswitchinterval(GIL_SWITCH_INTERVAL_S)
    if kind == "noop":
        noop = _Noop()
        methods = {MOVE_METHOD: (pb.MoveCartesianIncrementalRequest,
                                 lambda request: noop.MoveCartesianIncremental(request, None))}
    else:
        methods = local_moves(proxy_robot_servicer())
    server = LocalCallServer(path, methods)
    server.start()
    print("ready", flush=True)
    sys.stdin.read()
    server.stop()


def local_round_trips(kind: str, calls: int, rate_hz: float) -> None:
    with tempfile.TemporaryDirectory() as scratch:
        path = str(Path(scratch) / "moves.sock")
        server = subprocess.Popen([sys.executable, "-m", "bench.probes.hop", "--serve-local",
                                   kind, "--path", path],
                                  stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
        try:
            server.stdout.readline()
            client = LocalCallClient(path, timeout_s=5.0)
            took = _lockstep(lambda i: client.call(MOVE_METHOD, _request(1 if i % 2 else -1),
                                                   pb.MoveCartesianIncrementalResponse),
                             calls, rate_hz)
            client.close()
            print(f"same, the local socket, {kind}:".ljust(34), _percentiles(took))
        finally:
            server.stdin.close()
            server.wait(10)


def _stream_handler(servicer) -> grpc.GenericRpcHandler:
    """STREAM_METHOD: each move request on the stream answered by `servicer`, in order."""
    def moves(requests, context):
        for request in requests:
            yield servicer.MoveCartesianIncremental(request, context)

    service, method = STREAM_METHOD.strip("/").split("/")
    handler = grpc.stream_stream_rpc_method_handler(
        moves, pb.MoveCartesianIncrementalRequest.FromString,
        pb.MoveCartesianIncrementalResponse.SerializeToString)
    return grpc.method_handlers_generic_handler(service, {method: handler})


def _lockstep(call, calls: int, rate_hz: float) -> np.ndarray:
    """`call(i)` paced at `rate_hz`, each after the one before answered; ms, warm-up left out."""
    took = []
    start = time.perf_counter()
    for i in range(WARMUP + calls):
        delay = start + i / rate_hz - time.perf_counter()
        if delay > 0:
            time.sleep(delay)
        started = time.perf_counter()
        call(i)
        took.append(time.perf_counter() - started)
    return np.asarray(took[WARMUP:]) * 1e3


def round_trips(kind: str, calls: int, rate_hz: float) -> None:
    server = subprocess.Popen([sys.executable, "-m", "bench.probes.hop", "--serve", kind],
                              stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
    try:
        port = int(server.stdout.readline())
        with grpc.insecure_channel(f"127.0.0.1:{port}") as channel:
            move = proxy_robot_pb2_grpc.ProxyRobotStub(channel).MoveCartesianIncremental
            took = _lockstep(lambda i: move(_request(1 if i % 2 else -1), timeout=5.0), calls,
                             rate_hz)
            print(f"round trip at {rate_hz:.0f} Hz, {kind}:".ljust(34), _percentiles(took))
            if kind in STREAM_KINDS:
                took = _over_one_stream(channel, calls, rate_hz)
                print(f"same, one open stream, {kind}:".ljust(34), _percentiles(took))
    finally:
        server.stdin.close()
        server.wait(10)


def _over_one_stream(channel: grpc.Channel, calls: int, rate_hz: float) -> np.ndarray:
    """The lockstep over STREAM_METHOD: grpcio's client reads the requests from a queue on a
    thread of its own, as a persistent hop's sender would."""
    requests: queue.Queue = queue.Queue()
    stream = channel.stream_stream(STREAM_METHOD,
                                   pb.MoveCartesianIncrementalRequest.SerializeToString,
                                   pb.MoveCartesianIncrementalResponse.FromString)
    answers = stream(iter(requests.get, None))

    def call(i: int) -> None:
        requests.put(_request(1 if i % 2 else -1))
        next(answers)

    try:
        return _lockstep(call, calls, rate_hz)
    finally:
        requests.put(None)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m bench.probes.hop",
                                     description=__doc__.split("\n\n")[0])
    parser.add_argument("--serve", choices=KINDS, help=argparse.SUPPRESS)
    parser.add_argument("--serve-local", choices=LOCAL_KINDS, help=argparse.SUPPRESS)
    parser.add_argument("--path", help=argparse.SUPPRESS)
    parser.add_argument("--calls", type=int, default=2000)
    parser.add_argument("--rate", type=float, default=1000.0)
    args = parser.parse_args(argv)
    if args.serve:
        serve(args.serve)
        return 0
    if args.serve_local:
        serve_local(args.serve_local, args.path)
        return 0
    handler_alone(args.calls)
    for kind in KINDS:
        round_trips(kind, args.calls, args.rate)
    for kind in LOCAL_KINDS:
        local_round_trips(kind, args.calls, args.rate)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
