"""The estop group: the emergency stop on a moving arm, idle and under a flood of calls,
through the emergency-stop band and through ProxyRobot itself (bench/estop.py in a worker)."""

from __future__ import annotations

import time
from collections.abc import Callable

from bench.plan import Plan
from bench.procs import ChildFailed
from bench.session import Session
from bench.stats import ratio


def steps(plan: Plan) -> int:
    return 3


def run(bench: Session) -> None:
    """estop_idle and estop_under_load through the emergency-stop band (the framework's
    stop path), and estop_under_load_proxy: ProxyRobot's own EmergencyStop under the same
    load, the path the band exists to avoid."""
    proxy = bench.station.address["proxy_robot"]
    band = bench.station.address["emergency_stop"]
    _estop_trials(bench, "estop_idle", "EmergencyStop on the band of a moving arm -> hold "
                  "latched", proxy, band, loaded=False)
    _estop_trials(bench, "estop_under_load", "the same with "
                  f"{bench.plan.load_concurrency} concurrent GetState calls on "
                  "ProxyRobot's low lane", proxy, band, loaded=True)
    _estop_trials(bench, "estop_under_load_proxy", "the same load, the stop sent to "
                  "ProxyRobot itself", proxy, proxy, loaded=True)


def _estop_trials(bench: Session, name: str, what: str, proxy: str, stop_address: str,
                  loaded: bool) -> None:
    plan = bench.plan
    timeout = 60 + plan.estop_trials * 3
    bench.progress.step(f"{name}: {what}, {plan.estop_trials} trials")
    def trials() -> dict:
        return bench.worker("estop", {"address": proxy, "stop_address": stop_address,
                                      "shm": bench.shm, "trials": plan.estop_trials,
                                      "label": name}, timeout)

    try:
        if not loaded:
            result = trials()
        else:
            result, load = under_load(bench, {"address": proxy,
                                              "concurrency": plan.load_concurrency,
                                              "max_s": timeout + 30}, trials)
    except ChildFailed as error:
        return bench.fail([name], error)
    extra = ""
    if loaded:
        add_load(result, load, f"{plan.load_concurrency} concurrent ProxyRobot.GetState, "
                 "telerobot-lane: low", bench.results.get("estop_idle", {}))
        extra = f" (load {load['calls_per_s']:.0f} calls/s)"
    bench.record(name, result)
    bench.progress.done(bench.headline(name) + extra)


def under_load(bench: Session, load: dict, measure: Callable[[], dict]) -> tuple[dict, dict]:
    """`measure()` while a load worker (its parameters `load`) keeps the low lane full:
    (what it measured, the load worker's result). ChildFailed if either fails."""
    worker = bench.procs.start_worker("load", load)
    running = True
    try:
        bench.procs.wait_worker_ready(worker, 60.0)
        time.sleep(0.5)  # let the low lane fill up
        result = measure()
        worker.stop(grace_s=10.0)
        load_result = bench.procs.finish_worker(worker, 10.0)
        running = False
    finally:
        if running:
            bench.procs.stop(worker)
    return result, load_result


def add_load(result: dict, load: dict, what: str, idle: dict) -> None:
    """A loaded row's load (`what`, and the load worker's result `load`), and its latencies
    over the same row idle's."""
    result.update(load_calls_per_s=load["calls_per_s"], load_codes=load["codes"], load=what,
                  vs_idle={"p50": ratio(result.get("p50_ms"), idle.get("p50_ms")),
                           "p99": ratio(result.get("p99_ms"), idle.get("p99_ms"))})
