"""The soak_overload group: Teleoperate at 500 Hz from the Python client while busy co-tenant
processes, one per core, compete with the station for the CPU; bench/overload.py says what
the row holds, goals.py judges it."""

from __future__ import annotations

import contextlib

from bench.cpu import CpuWindow
from bench.overload import (
    NAME,
    RATE_HZ,
    SPIN_CODE,
    STEP_M,
    SWING,
    WORKER_SLACK_S,
    cotenant_count,
    third_lines,
)
from bench.plan import Plan
from bench.procs import Child, ChildFailed
from bench.session import Session

# The processes whose share of the CPU the row reports (the station's that serve the stream).
WATCHED = ("world", "proxy_robot", "force_sensor", "decision_server")


def steps(plan: Plan) -> int:
    return 1


def run(bench: Session) -> None:
    """One step, one row."""
    plan = bench.plan
    bench.progress.step(
        f"{NAME}: Teleoperate at {RATE_HZ} Hz (clients.python, send_nowait, "
        f"{STEP_M * 1e6:g} um strokes of {SWING}) beside {cotenant_count()} busy co-tenant "
        f"processes, for {plan.overload_s:g} s")
    try:
        result = _overload(bench)
    except ChildFailed as error:
        return bench.fail([NAME], error)
    bench.record(NAME, result)
    bench.progress.done(bench.headline(NAME))
    for line in third_lines(result):
        bench.progress.note(line)


def _overload(bench: Session) -> dict:
    plan, procs, station = bench.plan, bench.procs, bench.station
    station.arm_ready()
    with contextlib.ExitStack() as stack:
        address = stack.enter_context(bench.decision_server(station))
        cotenants: list[Child] = []
        operator: Child | None = None
        try:
            for index in range(cotenant_count()):
                cotenants.append(procs.start(f"cotenant_{index + 1}", ["-c", SPIN_CODE]))
            operator = procs.start_worker("overload", {
                "address": address, "proxy_address": station.address["proxy_robot"],
                "duration_s": plan.overload_s})
            procs.wait_worker_ready(operator, 60.0)  # the session is open
            watched = {name: pid for name in WATCHED if (pid := bench.pid(name)) is not None}
            watched["operator"] = operator.pid
            watched.update({child.name: child.pid for child in cotenants})
            window = CpuWindow(watched)
            result = procs.finish_worker(operator, plan.overload_s + WORKER_SLACK_S)
            cpu = window.stop()
            alive = [child.name for child in cotenants if child.process.poll() is None]
        finally:
            for child in [*cotenants, *([operator] if operator else [])]:
                if child.process.poll() is None:
                    procs.stop(child, grace_s=1.0)
    if result.get("operator_cpu_pct") is not None:  # its own count (it has exited by now)
        cpu["cpu_pct"]["operator"] = result["operator_cpu_pct"]
    result.update(transport=f"Teleoperate {RATE_HZ} Hz beside {len(cotenants)} busy "
                            "co-tenants (grpc, clients.python)",
                  cotenants={"count": len(cotenants), "alive_to_the_end": alive}, cpu=cpu)
    return result
