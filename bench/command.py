"""command_<rate>: master command -> applied at the servo, and the ack round trip, lockstep.

A "master command" here is one ProxyRobot.MoveJointsIncremental unary call (the transport
``grpc-unary``). The baselines send the same request bytes to the same ProxyRobotCore over
pyzmq REQ/REP and over a plain TCP socket (baseline_server.py). A unary call is lockstep by
nature (its answer is the ack), so these scenarios stay lockstep. The Teleoperate stream is
measured pipelined, as a haptic master drives it (teleop.py); its lockstep figure,
teleop_1000_lockstep, is a diagnostic kept here as one more CommandTransport, whose `send`
writes a MasterCommand on the stream and waits for the ack with that sequence.

How it is measured (each rate, each transport, the same way):
- lockstep at the offered rate: tick k is due at t0 + k/rate; a call is sent at its tick and
  waited for (ack). A tick that comes while the previous call is still out, or that the client
  wakes up too late for, is skipped and counted in ``dropped`` (``late_skipped``);
- every increment is +1e-5 rad on joint 1 (-1e-5 at the next rate, so the arm comes back):
  command n's target is T0 + n * 1e-5, and the servo's target only ever moves one way;
- ack round trip: time.time_ns() at send to the reply decoded at the client;
- applied at the servo: the proxy sends each target once, with the segment the servo is to
  spread it over (the time since the previous command, at most 50 ms; commands 1 ms apart
  pass straight through), and the world's servo reports the latest target it holds. Command n
  counts as applied at the first servo step whose target moved past command n-1's target (the
  servo has command n and walks toward it), at that step's time (the world's time.time_ns(),
  same host clock) minus the send time. The step where the servo's target reaches command n's
  own is reported as `reached_*`; since the servo holds each target whole, it is the same
  step. (Until the servo interpolated, the proxy wrote the segment's setpoints every 1 ms and
  the servo's target passed command n-1's only at a later write: the figure then included up
  to a segment of waiting, p99 17-24 ms at 50-1000 Hz against 2.7-3.6 ms since.)
"""

from __future__ import annotations

import queue
import threading
import time
from typing import Protocol

import grpc
import numpy as np
from google.protobuf import duration_pb2, timestamp_pb2

from bench import framing
from bench.schedule import Schedule
from bench.stats import summary
from bench.worldwatch import WorldWatch
from telerobot.v1 import proxy_robot_pb2, proxy_robot_pb2_grpc, types_pb2
from wire.tls import ChannelSecurity, open_channel

DELTA_RAD = 1e-5
CALL_TIMEOUT_S = 1.0
WARMUP_CALLS = 20
SETTLE_S = 0.08  # longer than the proxy's longest interpolation segment (50 ms)
TELEOP_STEP_M = 1e-5  # Teleoperate: 10 um along base y per command
LEASE_S = 60.0
LEASE_RENEW_S = 5.0
STREAM_TIMEOUT_S = 3600.0
# A gRPC client's default: plaintext, whatever TELEROBOT_TLS_DIR the environment has.
PLAINTEXT = ChannelSecurity()


class CommandFailed(Exception):
    """A command was refused or timed out."""


class CommandTransport(Protocol):
    """One way of getting a master command to the slave; `send` returns once it is acked.

    Joint-space transports (`joint_space`) send DELTA_RAD on joint 1, so the world's servo
    target shows when each command was applied; the others return the server's own "handed
    to the servo" time instead."""

    name: str
    joint_space: bool

    def send(self, sign: float) -> int | None:
        """Send one increment in direction `sign` (+1 or -1) and wait for its ack; the
        server's apply time (time.time_ns) if it reports one. CommandFailed."""

    def close(self) -> None:
        """Release the connection."""


class GrpcUnaryTransport:
    """ProxyRobot.MoveJointsIncremental, one unary call per command (default lane: high);
    `security`: plaintext, or mutual TLS with a certificate of the station or an admin."""

    name = "grpc-unary"
    joint_space = True

    def __init__(self, address: str, security: ChannelSecurity = PLAINTEXT):
        self._channel = open_channel(address, security=security)
        self._call = proxy_robot_pb2_grpc.ProxyRobotStub(self._channel).MoveJointsIncremental

    def send(self, sign: float) -> None:
        try:
            self._call(_request(sign), timeout=CALL_TIMEOUT_S)
        except grpc.RpcError as error:
            raise CommandFailed(f"{error.code().name}: {error.details()}") from None

    def close(self) -> None:
        self._channel.close()


class ZmqReqTransport:
    """The same request bytes over a pyzmq REQ socket to baseline_server's REP."""

    name = "zmq-reqrep"
    joint_space = True

    def __init__(self, address: str):
        import zmq

        self._zmq = zmq
        self._context = zmq.Context()
        self._socket = self._context.socket(zmq.REQ)
        self._socket.setsockopt(zmq.LINGER, 0)
        self._socket.setsockopt(zmq.REQ_RELAXED, 1)  # a timed-out request may be abandoned
        self._socket.setsockopt(zmq.REQ_CORRELATE, 1)
        self._socket.connect(f"tcp://{address}")

    def send(self, sign: float) -> None:
        self._socket.send(_request(sign).SerializeToString())
        if not self._socket.poll(int(CALL_TIMEOUT_S * 1000)):
            raise CommandFailed("no reply within the timeout")
        _check_reply(self._socket.recv())

    def close(self) -> None:
        self._socket.close()
        self._context.term()


class TcpTransport:
    """The same request bytes over a plain TCP socket with struct framing."""

    name = "tcp-struct"
    joint_space = True

    def __init__(self, address: str):
        self._socket = framing.connect(address)
        self._socket.settimeout(CALL_TIMEOUT_S)
        self._socket.sendall(framing.MODE_COMMANDS)

    def send(self, sign: float) -> None:
        try:
            framing.send_frame(self._socket, _request(sign).SerializeToString())
            _check_reply(framing.recv_frame(self._socket))
        except (TimeoutError, ConnectionError) as error:
            raise CommandFailed(str(error)) from None

    def close(self) -> None:
        self._socket.close()


class TeleoperateTransport:
    """DecisionServer.Teleoperate: one MasterCommand per command on the bidirectional stream
    (BASE mapping, TELEOP_STEP_M along base y), each waited for its ack: the lockstep
    diagnostic (teleop_1000_lockstep), which caps the rate at 1 / round trip. The DecisionServer
    applies it with ProxyRobot.MoveCartesianIncremental (IK) and stamps `apply_time` when
    ProxyRobot took the target; that stamp is this transport's "applied"."""

    name = "grpc-teleoperate"
    joint_space = False

    def __init__(self, address: str, security: ChannelSecurity = PLAINTEXT):
        from telerobot.v1 import decision_server_pb2 as dpb
        from telerobot.v1 import decision_server_pb2_grpc

        self._dpb = dpb
        self._channel = open_channel(address, security=security)
        self._stub = decision_server_pb2_grpc.DecisionServerStub(self._channel)
        self._lease = acquire_control(self._stub)
        self._stop = threading.Event()
        self._renewer = threading.Thread(target=self._renew, name="lease", daemon=True)
        self._renewer.start()
        self._requests: queue.SimpleQueue = queue.SimpleQueue()
        self._responses = self._stub.Teleoperate(iter(self._requests.get, None),
                                                 timeout=STREAM_TIMEOUT_S)
        self._requests.put(dpb.TeleoperateRequest(init=dpb.TeleoperateInit(
            operator_id="bench", lease_id=self._lease, mapping=types_pb2.REFERENCE_FRAME_BASE,
            watchdog_timeout=duration_pb2.Duration(seconds=5))))
        if next(self._responses).WhichOneof("message") != "ready":
            raise CommandFailed("Teleoperate did not answer its init with ready")
        self._sequence = 0
        self.receive_ms: list[float] = []  # send -> the DecisionServer has the command
        self._accepted = (dpb.COMMAND_OUTCOME_APPLIED, dpb.COMMAND_OUTCOME_MODIFIED)

    def _renew(self) -> None:
        while not self._stop.wait(LEASE_RENEW_S):
            self._stub.RenewControl(self._dpb.RenewControlRequest(lease_id=self._lease),
                                    timeout=CALL_TIMEOUT_S)

    def send(self, sign: float) -> int:
        self._sequence += 1
        sent = timestamp_pb2.Timestamp()
        sent.FromNanoseconds(time.time_ns())
        self._requests.put(self._dpb.TeleoperateRequest(command=self._dpb.MasterCommand(
            sequence=self._sequence, send_time=sent,
            delta_position_m=types_pb2.Vector3(y=sign * TELEOP_STEP_M))))
        try:
            ack = next(self._responses).ack
        except grpc.RpcError as error:
            raise CommandFailed(f"{error.code().name}: {error.details()}") from None
        if ack.sequence != self._sequence:
            raise CommandFailed(f"ack {ack.sequence} for command {self._sequence}")
        if ack.outcome not in self._accepted:
            raise CommandFailed(f"{self._dpb.CommandOutcome.Name(ack.outcome)}: {ack.detail}")
        self.receive_ms.append((ack.receive_time.ToNanoseconds() - sent.ToNanoseconds()) / 1e6)
        return ack.apply_time.ToNanoseconds()

    def close(self) -> None:
        self._requests.put(None)  # half-close: the stream ends OK
        self._stop.set()
        self._responses.cancel()
        release_control(self._stub, self._lease)
        self._channel.close()


def acquire_control(stub) -> str:
    """An exclusive control lease from the DecisionServer `stub`; its id."""
    from telerobot.v1 import decision_server_pb2 as dpb

    reply = stub.AcquireControl(dpb.AcquireControlRequest(
        operator_id="bench", mode=dpb.CONTROL_MODE_EXCLUSIVE, wait=True,
        wait_timeout=duration_pb2.Duration(seconds=5),
        lease_duration=duration_pb2.Duration(seconds=int(LEASE_S))), timeout=10)
    return reply.lease_id


def release_control(stub, lease_id: str) -> None:
    """Give a control lease back (it expires by itself if this fails)."""
    from telerobot.v1 import decision_server_pb2 as dpb

    try:
        stub.ReleaseControl(dpb.ReleaseControlRequest(lease_id=lease_id), timeout=CALL_TIMEOUT_S)
    except grpc.RpcError:
        pass


def _check_reply(reply: bytes) -> None:
    if reply[:1] != framing.REPLY_OK:
        raise CommandFailed(reply[1:].decode(errors="replace"))
    proxy_robot_pb2.MoveJointsIncrementalResponse.FromString(reply[1:])  # decoded, as gRPC does


TRANSPORTS = {"grpc": GrpcUnaryTransport, "zmq": ZmqReqTransport, "tcp": TcpTransport,
              "teleop": TeleoperateTransport}


def _request(sign: float) -> proxy_robot_pb2.MoveJointsIncrementalRequest:
    return proxy_robot_pb2.MoveJointsIncrementalRequest(
        delta_joint_positions_rad=[sign * DELTA_RAD, 0.0, 0.0, 0.0, 0.0, 0.0])


def run_rate(transport: CommandTransport, watch: WorldWatch, rate_hz: float,
             duration_s: float, sign: float) -> dict:
    """Lockstep commands at rate_hz for duration_s, every increment `sign` * DELTA_RAD on
    joint 1; the scenario's summary and raw latencies."""
    for _ in range(WARMUP_CALLS):
        transport.send(sign)
    if hasattr(transport, "receive_ms"):
        transport.receive_ms.clear()
    time.sleep(SETTLE_S)  # the last warm-up segment ends; its target is where we count from
    before = watch.read()
    base_target = float(before["target"][0])
    watch.start()
    sends, acks, server_applied = [], [], []
    failed = 0
    failures: list[str] = []
    schedule = Schedule(rate_hz, int(round(duration_s * rate_hz)), lead_s=0.01)
    try:
        for _ in schedule:
            sent_ns = time.time_ns()
            try:
                applied_ns = transport.send(sign)
            except CommandFailed as error:
                failed += 1
                if len(failures) < 5:
                    failures.append(str(error))
                continue
            acks.append(time.time_ns() - sent_ns)
            sends.append(sent_ns)
            if applied_ns is not None:
                server_applied.append((applied_ns - sent_ns) / 1e6)
        elapsed = time.perf_counter() - schedule.start
        skipped = schedule.skipped
        time.sleep(SETTLE_S)  # the last segment ends
    finally:
        watch.stop()
    after = watch.read()
    world_loop = {key: int(after[f"loop_{key}"]) - int(before[f"loop_{key}"])
                  for key in ("steps", "overruns", "dropped_steps")}
    if transport.joint_space:
        started, reached, not_applied = _applied(watch, sends, base_target, sign)
        means = "first servo step whose target moved past the previous command's"
    else:
        started, reached, not_applied = server_applied, [], len(sends) - len(server_applied)
        means = "the server's apply_time (target handed to ProxyRobot)"
    ack_ms = np.asarray(acks, dtype=float) / 1e6
    ack = summary(ack_ms, rate_hz, len(acks), elapsed, 0)
    done = summary(reached, None, 0, 1, 0)
    result = summary(
        started, rate_hz, len(started), elapsed, skipped + failed + not_applied,
        transport=transport.name, duration_s=round(elapsed, 3),
        applied_means=means,
        ack_p50_ms=ack["p50_ms"], ack_p99_ms=ack["p99_ms"], ack_max_ms=ack["max_ms"],
        reached_p50_ms=done["p50_ms"], reached_p99_ms=done["p99_ms"],
        reached_max_ms=done["max_ms"], late_skipped=skipped, failed=failed,
        not_applied=not_applied, world_missed_steps=watch.missed_steps, world_loop=world_loop,
        failures=failures)
    receive_ms = getattr(transport, "receive_ms", None)
    if receive_ms is not None:  # Teleoperate: where the time goes, by the server's stamps
        received = summary(receive_ms, None, 0, 1, 0)
        result.update(server_receive_p50_ms=received["p50_ms"],
                      server_receive_p99_ms=received["p99_ms"])
        receive_ms.clear()
    result["latencies_ms"] = [round(v, 4) for v in started]
    result["ack_latencies_ms"] = [round(float(v), 4) for v in ack_ms]
    return result


def _applied(watch: WorldWatch, sends: list[int], base_target: float, sign: float
             ) -> tuple[list[float], list[float], int]:
    """Per command (ms from its send): the servo step where the target first moved past the
    previous command's target (started), and where it reached its own (reached)."""
    times = np.asarray(watch.times_ns, dtype=np.int64)
    # Every increment has the same sign, so (sign * target) never decreases over the run.
    progress = sign * np.asarray(watch.targets, dtype=float)
    # The first setpoint of a segment is a hair past its start (the interpolation fraction a
    # few microseconds in); far above float rounding of the targets (~1e-17 rad).
    started_epsilon, reached_epsilon = 1e-6 * DELTA_RAD, 1e-3 * DELTA_RAD
    started, reached, missing = [], [], 0
    for index, sent_ns in enumerate(sends):
        previous = sign * base_target + index * DELTA_RAD
        first = int(np.searchsorted(progress, previous + started_epsilon, side="right"))
        last = int(np.searchsorted(progress, previous + DELTA_RAD - reached_epsilon,
                                   side="left"))
        if first >= len(times):
            missing += 1
            continue
        started.append((times[first] - sent_ns) / 1e6)
        if last < len(times):
            reached.append((times[last] - sent_ns) / 1e6)
    return started, reached, missing


def measure(transport_kind: str, address: str, shm_name: str, rates: list[float],
            duration_s: float, **transport_options) -> dict[str, dict]:
    """run_rate for each rate over one connection (alternating the direction of motion from
    one rate to the next, so the arm ends near where it started); {str(rate): result}.
    `transport_options` go to the transport (`security` for the gRPC ones)."""
    transport = TRANSPORTS[transport_kind](address, **transport_options)
    watch = WorldWatch(shm_name)
    try:
        return {str(int(rate)): run_rate(transport, watch, rate, duration_s,
                                         1.0 if index % 2 == 0 else -1.0)
                for index, rate in enumerate(rates)}
    finally:
        watch.close()
        transport.close()
