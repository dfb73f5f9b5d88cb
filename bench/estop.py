"""estop_idle, estop_under_load and estop_under_load_proxy: EmergencyStop call -> arm halted,
idle and with ProxyRobot's low lane saturated (estop_ds_*: the same through the DecisionServer).

"Arm halted" is the world's hold latched: the first servo step whose state record shows
`hold_latched` (read through the shared memory, read only), at that step's time, which the
world keeps in `hold_latched_ns`: a bench descheduled by the load may see the latch a few
steps late (`world_step_unseen` counts those), and that is the bench's delay, not the stop's.
From then the servo brakes at its acceleration cap (10 rad/s²), which is physics, not
software: the time until every joint is slower than HALT_SPEED_RAD_PER_S is reported too
(`stopped_*`), as is the RPC's own return (`ack_*`).

Each trial: Reset (if stopped), a 0.15 rad move of joint 1 (alternating sign, so the arm stays
near where it was), MOVING_S for the arm to pick up speed, then EmergencyStop (emergency lane),
sent to the emergency-stop band (services/emergency_stop) or to ProxyRobot itself.

The load (run_load, in its own process): 200 concurrent ProxyRobot.GetState calls asking for
the low lane (`telerobot-lane: low` metadata), each re-issued as soon as it returns, from one
grpc.aio client. The low lane (1-4 threads, 256 queued) is then always full. For estop_ds_busywork
the load is 200 DecisionServer.RunAction BusyWork calls instead (Parma's workload).
"""

from __future__ import annotations

import asyncio
import collections
import signal
import time

import grpc
import numpy as np
from google.protobuf import duration_pb2

from bench.stats import summary
from bench.worldwatch import WorldWatch
from telerobot.v1 import proxy_robot_pb2 as pb
from telerobot.v1 import proxy_robot_pb2_grpc, types_pb2

MOVE_RAD = 0.15
MOVING_S = 0.08
HALT_SPEED_RAD_PER_S = 0.05
CALL_TIMEOUT_S = 5.0
WAIT_S = 1.0
LOW_LANE = (("telerobot-lane", "low"),)
BUSY_WORK_S = 0.02  # each RunAction BusyWork of the DecisionServer load computes this long


def _ensure_ready(stub, metadata=()) -> bool:
    """Reset a stop; reconnect a proxy that dropped its link (a world that did not step for
    100 ms, on an overloaded machine, counts as gone). True when it had to reconnect."""
    status = stub.GetStatus(pb.GetStatusRequest(), timeout=CALL_TIMEOUT_S).status
    if status in (types_pb2.ROBOT_STATUS_ESTOPPED, types_pb2.ROBOT_STATUS_FAULT):
        stub.Reset(pb.ResetRequest(), metadata=metadata, timeout=CALL_TIMEOUT_S)
    elif status in (types_pb2.ROBOT_STATUS_NOT_CONNECTED, types_pb2.ROBOT_STATUS_CONNECTED):
        stub.Connect(pb.ConnectRequest(), metadata=metadata, timeout=CALL_TIMEOUT_S)
        stub.Initialize(pb.InitializeRequest(), metadata=metadata, timeout=CALL_TIMEOUT_S)
        return True
    return False


def run_estop(address: str, shm_name: str, trials: int, label: str,
              decision_server: bool = False, stop_address: str | None = None,
              lease_id: str | None = None) -> dict:
    """`trials` emergency stops of a moving arm; the scenario's summary and raw latencies.
    With `decision_server`, `address` is the DecisionServer's: the calls go through its
    ProxyRobot facade, with a control lease for the moves and resets. With `stop_address`
    (the emergency-stop band's), the stops go there and everything else to `address`. With
    `lease_id`, that lease (a plaintext station's, shared with a load worker) is used and kept
    instead of one of its own."""
    channel = grpc.insecure_channel(address)
    stub = proxy_robot_pb2_grpc.ProxyRobotStub(channel)
    stop_channel = (grpc.insecure_channel(stop_address)
                    if stop_address and stop_address != address else channel)
    stopper = proxy_robot_pb2_grpc.ProxyRobotStub(stop_channel)
    # Connected before the first trial, as the move channel is by its calls: a stop that has
    # to open its TCP connection first would time the handshake, not the stop.
    grpc.channel_ready_future(stop_channel).result(timeout=CALL_TIMEOUT_S)
    metadata: tuple = ()
    lease = decision = None
    if lease_id:
        metadata = (("telerobot-lease-id", lease_id),)
    elif decision_server:
        from bench.command import acquire_control
        from telerobot.v1 import decision_server_pb2_grpc

        decision = decision_server_pb2_grpc.DecisionServerStub(channel)
        lease = acquire_control(decision)
        metadata = (("telerobot-lease-id", lease),)
    watch = WorldWatch(shm_name)
    latched, acks, stopped, speeds = [], [], [], []
    gaps = failed = reconnects = 0
    errors: list[str] = []
    started = time.monotonic()
    try:
        _ensure_ready(stub, metadata)
        for trial in range(trials):
            delta = [MOVE_RAD if trial % 2 == 0 else -MOVE_RAD, 0, 0, 0, 0, 0]
            try:
                reconnects += _ensure_ready(stub, metadata)
                stub.MoveJointsIncremental(
                    pb.MoveJointsIncrementalRequest(delta_joint_positions_rad=delta),
                    metadata=metadata, timeout=CALL_TIMEOUT_S)
            except grpc.RpcError as error:
                failed += 1
                errors.append(f"{error.code().name}: {error.details()}")
                continue
            time.sleep(MOVING_S)
            speeds.append(float(np.max(np.abs(watch.read()["qd"]))))
            done: dict[str, int] = {}
            sent_ns = time.time_ns()
            future = stopper.EmergencyStop.future(pb.EmergencyStopRequest(reason=f"bench {label}"),
                                               timeout=CALL_TIMEOUT_S)
            future.add_done_callback(lambda _f, d=done: d.setdefault("at", time.time_ns()))
            record, _, gap = watch.wait_until(lambda r: bool(r["hold_latched"]), WAIT_S)
            if record is None:
                failed += 1
                errors.append("the hold did not latch within 1 s")
                continue
            gaps += int(gap)
            latched.append((int(record["hold_latched_ns"]) - sent_ns) / 1e6)
            record, _, _ = watch.wait_until(
                lambda r: float(np.max(np.abs(r["qd"]))) < HALT_SPEED_RAD_PER_S, WAIT_S)
            if record is not None:
                stopped.append((int(record["arm_time_ns"]) - sent_ns) / 1e6)
            try:
                future.result()
            except grpc.RpcError as error:
                errors.append(f"{error.code().name}: {error.details()}")
            acks.append((done.get("at", time.time_ns()) - sent_ns) / 1e6)
        _ensure_ready(stub, metadata)
    finally:
        watch.close()
        if lease is not None:
            from bench.command import release_control

            release_control(decision, lease)
        stop_channel.close()
        channel.close()
    elapsed = time.monotonic() - started
    ack = summary(acks, None, 0, 1, 0)
    stop = summary(stopped, None, 0, 1, 0)
    result = summary(
        latched, None, len(latched), elapsed, failed, trials=trials,
        transport=("grpc-unary DecisionServer's ProxyRobot.EmergencyStop (forwarded)"
                   if decision_server else "grpc-unary ProxyRobot.EmergencyStop"
                   + (" on the emergency-stop band" if stop_channel is not channel else "")),
        halted_means="world hold latched (first servo step showing it)",
        ack_p50_ms=ack["p50_ms"], ack_p99_ms=ack["p99_ms"], ack_max_ms=ack["max_ms"],
        stopped_p50_ms=stop["p50_ms"], stopped_p99_ms=stop["p99_ms"],
        stopped_max_ms=stop["max_ms"], mean_speed_at_stop_rad_per_s=round(
            float(np.mean(speeds)), 3) if speeds else None, world_step_unseen=gaps,
        proxy_reconnects=reconnects, errors=errors[:5])
    result["delivered_hz"] = None  # single calls: no rate
    result["latencies_ms"] = [round(v, 4) for v in latched]
    return result


def run_load(address: str, concurrency: int, max_s: float, ready,
             target: str = "proxy_robot", lease_id: str = "") -> dict:
    """`concurrency` GetState calls (RunAction BusyWork when `target` is "decision_server",
    which needs the control lease `lease_id`) on the low lane, re-issued as each returns,
    until SIGTERM or max_s. Calls ready() after the first `concurrency` completions."""
    return asyncio.run(_load(address, concurrency, max_s, ready, target, lease_id))


async def _load(address: str, concurrency: int, max_s: float, ready, target: str,
                lease_id: str) -> dict:
    stop = asyncio.Event()
    loop = asyncio.get_running_loop()
    loop.add_signal_handler(signal.SIGTERM, stop.set)
    codes: collections.Counter[str] = collections.Counter()
    completed = 0
    announced = False
    started = time.monotonic()

    metadata = LOW_LANE + ((("telerobot-lease-id", lease_id),) if lease_id else ())

    async def caller(call, request):
        nonlocal completed, announced
        while not stop.is_set():
            try:
                await call(request, metadata=metadata, timeout=CALL_TIMEOUT_S)
                codes["OK"] += 1
            except grpc.aio.AioRpcError as error:
                codes[error.code().name] += 1
                await asyncio.sleep(0.001)
            completed += 1
            if not announced and completed >= concurrency:
                announced = True
                ready()

    async with grpc.aio.insecure_channel(address) as channel:
        if target == "decision_server":  # the intended load: Parma's workload
            from telerobot.v1 import decision_server_pb2 as dpb
            from telerobot.v1 import decision_server_pb2_grpc

            stub = decision_server_pb2_grpc.DecisionServerStub(channel)
            call = stub.RunAction
            request = dpb.RunActionRequest(action_id="load", busy_work=dpb.BusyWorkAction(
                duration=duration_pb2.Duration(nanos=int(BUSY_WORK_S * 1e9))))
        else:
            stub = proxy_robot_pb2_grpc.ProxyRobotStub(channel)
            call, request = stub.GetState, pb.GetStateRequest()
        tasks = [asyncio.create_task(caller(call, request)) for _ in range(concurrency)]
        try:
            await asyncio.wait_for(stop.wait(), max_s)
        except TimeoutError:
            stop.set()
        await asyncio.wait(tasks, timeout=CALL_TIMEOUT_S + 1)
    elapsed = time.monotonic() - started
    return {"concurrency": concurrency, "calls": completed,
            "calls_per_s": round(completed / elapsed, 1), "codes": dict(codes)}
