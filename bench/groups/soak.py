"""The soak group: the station under a steady load for minutes (Teleoperate, wrench observers,
a stereo client, an events follower), every station process's RSS sampled; bench/soak.py
says what and judges it."""

from __future__ import annotations

import contextlib
import time

from bench import stereo
from bench.plan import Plan
from bench.procs import Child, ChildFailed
from bench.session import Session
from bench.soak import (
    DRAIN_S,
    NAME,
    OBSERVER_DECIMATION,
    OBSERVERS,
    STATION,
    STEREO_MODE,
    STEREO_SOURCE,
    SWING,
    TELEOP_RATE_HZ,
    WATCHDOG_S,
    WINDOW_S,
    WORKER_SLACK_S,
    Sampler,
    build_row,
    summary_line,
)


def steps(plan: Plan) -> int:
    return 1


def run(bench: Session) -> None:
    """One step, one row."""
    plan = bench.plan
    bench.progress.step(
        f"{NAME}: Teleoperate at {TELEOP_RATE_HZ} Hz, {OBSERVERS} wrench observers, a stereo "
        f"client, for {plan.soak_s / 60:g} min; RSS of every station process every "
        f"{plan.soak_sample_s:g} s")
    try:
        result = _soak(bench)
    except ChildFailed as error:
        return bench.fail([NAME], error)
    bench.record(NAME, result)
    bench.progress.done(f"{bench.headline(NAME)}; {summary_line(result)}")


def _soak(bench: Session) -> dict:
    plan, procs, station = bench.plan, bench.procs, bench.station
    duration_s = plan.soak_s
    limit_s = duration_s + WORKER_SLACK_S
    workers: list[Child] = []
    with contextlib.ExitStack() as stack:
        stereo_address, stereo_missing = None, stereo.available()
        if stereo_missing is None:
            camera, stereo_address = procs.run_service("stereo_camera", [
                "--source", STEREO_SOURCE, "--width", str(stereo.WIDTH_PX),
                "--height", str(stereo.HEIGHT_PX), "--fps", str(plan.stereo_source_fps)])
            stack.callback(procs.stop, camera)
        address = stack.enter_context(bench.decision_server(station, stereo_address))
        children = {child.name: child for child in procs.children
                    if child.name in STATION and child.process.poll() is None}
        try:
            events = procs.start_worker("events", {"address": address, "max_s": limit_s})
            workers.append(events)
            procs.wait_worker_ready(events, 60.0)
            observers = procs.start_worker("observers", {
                "address": station.address["force_sensor"], "count": OBSERVERS,
                "decimation": OBSERVER_DECIMATION, "max_s": limit_s})
            workers.append(observers)
            procs.wait_worker_ready(observers, 60.0)
            camera_client = None
            if stereo_address is not None:
                camera_client = procs.start_worker("stereo", {
                    "address": stereo_address, "mode": STEREO_MODE, "duration_s": duration_s,
                    "source_fps": plan.stereo_source_fps})
                workers.append(camera_client)
            sampler = Sampler({name: child.pid for name, child in children.items()},
                              plan.soak_sample_s, bench.loop.read if bench.loop else None,
                              bench.progress.note)
            sampler.start()
            started_ns = time.time_ns()
            try:
                teleop = procs.start_worker("teleop", {
                    "transport": "grpc", "address": address, "shm": bench.shm,
                    "rates": [TELEOP_RATE_HZ], "duration_s": duration_s, "swing": SWING,
                    "window_s": min(WINDOW_S, duration_s / 6), "drain_s": DRAIN_S,
                    "watchdog_s": WATCHDOG_S})
                workers.append(teleop)
                teleop_result = _finish(procs, teleop, limit_s)
                teleop_result = teleop_result.get(str(TELEOP_RATE_HZ), teleop_result)
            finally:
                sampler.stop()
            exited = [name for name, child in children.items()
                      if child.process.poll() is not None]
            stereo_result = (_finish(procs, camera_client, 120.0) if camera_client
                             else {"status": "pending", "reason": stereo_missing})
            observers.stop(grace_s=5.0)
            observers_result = _finish(procs, observers, 15.0)
            time.sleep(0.5)  # the lease's release reaches the follower
            events.stop(grace_s=5.0)
            events_result = _finish(procs, events, 15.0)
        finally:
            for worker in workers:
                if worker.process.poll() is None:
                    procs.stop(worker)
    return build_row(duration_s, plan.soak_sample_s, teleop_result, observers_result,
                     stereo_result, events_result, sampler, started_ns, exited)


def _finish(procs, child: Child, timeout_s: float) -> dict:
    """A side worker's result; a failed one is a row of its own kind, not the soak's end."""
    try:
        return procs.finish_worker(child, timeout_s)
    except ChildFailed as error:
        return {"status": "failed", "reason": str(error)[-500:]}
