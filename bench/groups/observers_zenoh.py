"""The observers_zenoh group (issue #33): the operator's 1 kHz wrench stream measured while N
subscribers, in processes of their own behind the station's Zenoh router (another process),
each get every wrench sample, which the station publishes once (services.observation).

The station's CPU is its services' (world, ProxyRobot, ForceSensor, the DecisionServer) and
the publisher's, which serve one stream whatever N is; the router's, which sends each
subscriber its copy, and the subscribers' own are reported beside it. The subscribers stand
for hosts of their own: together they are capped at SUBSCRIBER_CORES (bench/cgroup.py), so
that they fall behind, as a subscriber on a slow host does, instead of taking the station's
cores (a saturated machine stretches the CPU time of every process on it, the world's fixed
work included: +24 % at 256 uncapped subscribers)."""

from __future__ import annotations

import signal
import statistics
import time

from bench.cgroup import cpu_capped
from bench.plan import Plan
from bench.procs import ChildFailed, worker_sizes
from bench.session import Session

# A process's subscribers share its GIL: 32 each keeps one process from being the bottleneck
# of the ones it holds at the lower counts (128 each fell seconds behind at 100 messages/s).
SUBSCRIBERS_PER_PROCESS = 32
SUBSCRIBER_CORES = 0.5  # all subscriber processes together
READY_TIMEOUT_S = 300.0  # for every subscriber process to be up
STOP_TIMEOUT_S = 120.0
STATION_NAME = "bench"
# Whose CPU is the station's: one stream each, whatever the number of subscribers.
STATION_PROCESSES = ("world", "proxy_robot", "force_sensor", "decision_server", "observation")


def steps(plan: Plan) -> int:
    return 1 + len(plan.zenoh_observer_counts)


def run(bench: Session) -> None:
    """observers_zenoh_<n> for each of Plan.zenoh_observer_counts."""
    names = [f"observers_zenoh_{count}" for count in bench.plan.zenoh_observer_counts]
    bench.progress.step("starting a Zenoh router and the observation publisher")
    router = bench.procs.start("zenoh_router", ["-m", "services.zenoh_router", "--address",
                                                "127.0.0.1:0"])
    try:
        router_address = router.wait_ready("zenoh_router", timeout_s=30.0)
    except ChildFailed as error:
        bench.procs.stop(router)
        return bench.fail(names, error)
    try:
        with bench.decision_server(bench.station) as door:
            publisher = bench.procs.start("observation", [
                "-m", "services.observation", "--router", f"tcp/{router_address}",
                "--station", STATION_NAME,
                "--proxy-robot", bench.station.address["proxy_robot"],
                "--force-sensor", bench.station.address["force_sensor"],
                "--decision-server", door])
            try:
                publisher.wait_ready("observation", timeout_s=30.0)
            except ChildFailed as error:
                return bench.fail(names, error)
            bench.progress.done(f"router on {router_address}")
            for count in bench.plan.zenoh_observer_counts:
                _row(bench, count, f"tcp/{router_address}", router.pid)
            bench.procs.stop(publisher)
    except ChildFailed as error:  # the DecisionServer did not start
        bench.fail([n for n in names if n not in bench.results], error)
    finally:
        bench.procs.stop(router)


def _row(bench: Session, count: int, router: str, router_pid: int) -> None:
    name = f"observers_zenoh_{count}"
    processes = len(worker_sizes(count, SUBSCRIBERS_PER_PROCESS))
    bench.progress.step(f"{name}: operator at 1 kHz with {count} Zenoh subscribers to every "
                        f"wrench sample, behind the router (in {processes} processes)")
    plan = bench.plan
    groups = []
    with cpu_capped(SUBSCRIBER_CORES) as cap:
        try:
            for size in worker_sizes(count, SUBSCRIBERS_PER_PROCESS):
                groups.append(bench.procs.start_worker("zenoh_observers", {
                    "router": router, "station": STATION_NAME, "count": size,
                    "max_s": READY_TIMEOUT_S + plan.observers_s + 60}))
            deadline = time.monotonic() + READY_TIMEOUT_S
            for group in groups:
                bench.procs.wait_worker_ready(group, max(1.0, deadline - time.monotonic()))
            for group in groups:  # capped while measured (starting up, they would crawl)
                if cap is not None:
                    cap.add(group.pid)
            watched = {n: pid for n in STATION_PROCESSES if (pid := bench.pid(n)) is not None}
            watched["zenoh_router"] = router_pid
            watched.update({f"subscribers {i + 1}": group.pid for i, group in enumerate(groups)})
            result = bench.procs.run_worker("force", {
                "transport": "grpc", "address": bench.station.address["force_sensor"],
                "decimation": 1, "duration_s": plan.observers_s, "watch_pids": watched},
                60 + 3 * plan.observers_s)
            if cap is not None:
                cap.lift()
            for group in groups:  # all at once: each closes its sessions
                group.process.send_signal(signal.SIGTERM)
            observed = [bench.procs.finish_worker(group, STOP_TIMEOUT_S) for group in groups]
        except ChildFailed as error:
            return bench.fail([name], error)
        finally:
            for group in groups:
                if group.process.poll() is None:
                    bench.procs.stop(group)
    result.update(_subscribers(observed, result.get("cpu") or {}))
    result["subscriber_cores_cap"] = SUBSCRIBER_CORES if cap is not None else None
    bench.record(name, result)
    bench.progress.done(bench.headline(name) + f"; station CPU {result['station_cpu_pct']} %, "
                        f"router {result['router_cpu_pct']} %, each subscriber "
                        f"{result['subscriber_samples_per_s_median']} samples/s (min "
                        f"{result['subscriber_samples_per_s_min']}), lag p99 median "
                        f"{result['subscriber_lag_p99_ms_median']} ms")


def _subscribers(observed: list[dict], cpu: dict) -> dict:
    """The row's figures of its subscribers and where the CPU went."""
    each = [entry for result in observed for entry in result["per_observer"]]
    rates = [entry["samples_per_s"] for entry in each]
    p50s = [e["lag_p50_ms"] for e in each if e["lag_p50_ms"] is not None]
    p99s = [e["lag_p99_ms"] for e in each if e["lag_p99_ms"] is not None]
    shares = cpu.get("cpu_pct") or {}
    return {
        "observers": len(each),
        "station_cpu_pct": round(sum(shares.get(n, 0.0) for n in STATION_PROCESSES), 1),
        # The world's work is the same whatever N is: its CPU rising says how much a busy
        # machine inflates every process's CPU time, the station's included.
        "world_cpu_pct": shares.get("world"),
        "router_cpu_pct": shares.get("zenoh_router"),
        "subscribers_cpu_pct": round(sum(v for n, v in shares.items()
                                         if n.startswith("subscribers")), 1),
        "subscriber_samples_per_s_median": round(statistics.median(rates), 1) if rates else None,
        "subscriber_samples_per_s_min": min(rates, default=None),
        "subscriber_lost": sum(entry["lost"] for entry in each),
        "subscribers_never_received": sum(result["never_received"] for result in observed),
        "subscriber_close_timeouts": sum(result["close_timeouts"] for result in observed),
        "subscriber_lag_p50_ms_median": round(statistics.median(p50s), 3) if p50s else None,
        "subscriber_lag_p99_ms_median": round(statistics.median(p99s), 3) if p99s else None,
        "subscriber_lag_p99_ms_max": max(p99s, default=None),
    }
