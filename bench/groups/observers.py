"""The observers group: the operator's 1 kHz wrench stream measured while 0 to 32 observers
stream at 100 Hz from processes of their own (the Parma table)."""

from __future__ import annotations

from bench.plan import Plan
from bench.procs import ChildFailed, worker_sizes
from bench.session import Session, reason

OBSERVERS_PER_PROCESS = 8


def steps(plan: Plan) -> int:
    return len(plan.observer_counts)


def run(bench: Session) -> None:
    """observers_<count> for each of Plan.observer_counts."""
    plan = bench.plan
    for count in plan.observer_counts:
        name = f"observers_{count}"
        bench.progress.step(f"{name}: operator at 1 kHz with {count} observers at "
                            f"{1000 / plan.observer_decimation:.0f} Hz "
                            f"(in {len(worker_sizes(count, OBSERVERS_PER_PROCESS))} processes)")
        retried = None
        try:
            try:
                result = _observers_once(bench, count)
            except ChildFailed as error:  # once more, from a fresh start
                retried = reason(error)
                bench.progress.note(f"failed ({retried}); retrying once")
                bench.station.arm_ready()
                result = _observers_once(bench, count)
        except ChildFailed as error:
            bench.fail([name], error)
            continue
        if retried:
            result["retried_after"] = retried
        bench.record(name, result)
        bench.progress.done(bench.headline(name) + f", jitter {result.get('jitter_ms')} ms")


def _observers_once(bench: Session, count: int) -> dict:
    """Observer processes streaming, then the operator's 1 kHz stream measured."""
    plan = bench.plan
    address = bench.station.address["force_sensor"]
    groups = []
    try:
        for size in worker_sizes(count, OBSERVERS_PER_PROCESS):
            groups.append(bench.procs.start_worker("observers", {
                "address": address, "count": size,
                "decimation": plan.observer_decimation, "max_s": plan.observers_s + 60}))
        for group in groups:
            bench.procs.wait_worker_ready(group, 60.0)
        # Where the CPU goes while the operator is measured: the station's busy
        # processes, and the observers' (on the same cores, as the bench runs).
        watched = {name: pid for name in ("force_sensor", "world")
                   if (pid := bench.pid(name)) is not None}
        watched.update({f"observers {i + 1}": group.pid for i, group in enumerate(groups)})
        result = bench.procs.run_worker("force", {
            "transport": "grpc", "address": address, "decimation": 1,
            "duration_s": plan.observers_s, "watch_pids": watched},
            60 + 3 * plan.observers_s)
        observed = []
        for group in groups:
            group.stop(grace_s=5.0)
            observed.append(bench.procs.finish_worker(group, 10.0))
    finally:
        for group in groups:
            if group.process.poll() is None:
                bench.procs.stop(group)
    result["observers"] = count
    result["observer_rate_hz"] = 1000 / plan.observer_decimation
    if observed:
        means = [o["observer_delivered_hz_mean"] for o in observed]
        sizes = [o["observers"] for o in observed]
        result["observer_delivered_hz_mean"] = round(
            sum(m * s for m, s in zip(means, sizes, strict=True)) / sum(sizes), 2)
        result["observer_delivered_hz_min"] = min(o["observer_delivered_hz_min"]
                                                  for o in observed)
        result["observer_errors"] = [e for o in observed for e in o["errors"]][:5]
    return result
