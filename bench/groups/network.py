"""The network group: the peg-in-hole task across the impairment link, in both modes, at each
round trip and with a cut (bench/network.py says what and why, and judges it; its worker side
runs the task). The link runs here, in the orchestrator, which does little else meanwhile."""

from __future__ import annotations

import dataclasses
import time

from bench.network import (
    CAMPUS_RTT_MS,
    CUT_AT_S,
    CUT_MODE,
    CUT_S,
    JITTER_FRACTION,
    NAME,
    PAPERS,
    ROW_TIMEOUT_S,
    RowSpec,
    home_position,
    link_profiles,
    median_run,
    row_specs,
    row_text,
)
from bench.plan import Plan
from bench.procs import ChildFailed
from bench.session import Session, reason
from services.impairment import ImpairmentProxy


def steps(plan: Plan) -> int:
    return len(row_specs(plan.quick))


def run(bench: Session) -> None:
    """A step per run (row_specs), one result row."""
    plan, started = bench.plan, time.monotonic()
    specs = row_specs(plan.quick)
    try:
        with bench.decision_server(bench.station) as address:
            home = home_position()
            rows = [_run_row(bench, address, spec, home) for spec in specs]
    except ChildFailed as error:
        bench.progress.step("network: starting the DecisionServer")
        return bench.fail([NAME], error)
    result = {
        "rows": rows, "round_trips_ms": sorted({spec.round_trip_ms for spec in specs}),
        "jitter_fraction": JITTER_FRACTION, "campus_rtt_ms": CAMPUS_RTT_MS,
        "cut": {"s": CUT_S, "at_s": CUT_AT_S, "mode": CUT_MODE, "round_trip_ms": CAMPUS_RTT_MS},
        "papers": PAPERS, "elapsed_s": round(time.monotonic() - started, 1),
        "succeeded": sum(1 for row in rows if row["success"]), "runs": len(rows),
        # No latency of its own for the other groups' columns.
        "rate_hz": None, "delivered_hz": None, "p50_ms": None, "p99_ms": None,
        # The world loop over every run (each row has its own), not just since the last.
        "world_loop": {key: sum((row.get("world_loop") or {}).get(key) or 0 for row in rows)
                       for key in ("steps", "overruns", "dropped_steps")}}
    bench.record(NAME, result)


def _run_row(bench: Session, address: str, spec: RowSpec, home: list[float]) -> dict:
    cut = f", a {spec.cut_s:g} s {CUT_MODE} cut {CUT_AT_S:g} s into the task" if spec.cut_s else ""
    times = f", {spec.repeats} runs (the median kept)" if spec.repeats > 1 else ""
    bench.progress.step(f"network {spec.name}: peg-in-hole ({spec.mode}), round trip "
                        f"{spec.round_trip_ms:g} ms ± {100 * JITTER_FRACTION:g} %{cut}{times}")
    up, down = link_profiles(spec.round_trip_ms, spec.seed)
    events: list[str] = []  # the proxy's lines: connections, cuts
    runs, cut_at = [], None
    with ImpairmentProxy("127.0.0.1:0", address, up=up, down=down,
                         report=events.append) as proxy:
        for _ in range(spec.repeats):
            outcome, cut_at = _run_once(bench, proxy, spec, home)
            runs.append(outcome)
        stats = dataclasses.asdict(proxy.stats)
    row = {"name": spec.name, "mode": spec.mode, "passivity": spec.passivity,
           "round_trip_ms": spec.round_trip_ms,
           "one_way_delay_ms": up.delay_s * 1e3, "jitter_ms": up.jitter_s * 1e3,
           "seed": spec.seed, "cut_s": spec.cut_s,
           "cut": {"at_s": CUT_AT_S, "mode": CUT_MODE, "happened": cut_at is not None}
           if spec.cut_s else None,
           **_blank(), **median_run(runs), "proxy": stats,
           "world_loop": bench.loop_since_mark(),
           "link_events": [line for line in events if "cut" in line or "back" in line
                           or "reset" in line or "held" in line]}
    bench.progress.done(row_text(row))
    return row


def _run_once(bench: Session, proxy, spec: RowSpec, home: list[float]) -> tuple[dict, float | None]:
    """One run of the task through `proxy` in a worker: (its outcome, when the cut began)."""
    child = bench.procs.start_worker(NAME, {"address": proxy.address, "mode": spec.mode,
                                            "home": home, "passivity": spec.passivity},
                                     name=f"network_{spec.mode}")
    cut_at = None
    try:
        if spec.cut_s:
            bench.procs.wait_worker_ready(child, ROW_TIMEOUT_S)  # the task has started
            time.sleep(CUT_AT_S)
            if child.process.poll() is None:
                cut_at = time.monotonic()
                proxy.cut(spec.cut_s, CUT_MODE)
        return bench.procs.finish_worker(child, ROW_TIMEOUT_S), cut_at
    except ChildFailed as error:
        if child.process.poll() is None:
            bench.procs.stop(child)
        return {"success": False, "error": reason(error)}, cut_at


def _blank() -> dict:
    return {"success": False, "error": None, "duration_s": None, "depth_m": None,
            "peak_force_n": None, "final_force_n": None, "round_trip_p50_ms": None,
            "round_trip_p99_ms": None, "commands": None, "acks": None, "drift_m": None,
            "transparency_rms_n": None, "oscillation_swings": None, "energy": None}
