"""The closed_loop group: in contact with the fixture, a press of 2 mm, timed until the force
it makes reaches the operator (bench/closed_loop.py in a worker)."""

from __future__ import annotations

from bench.plan import Plan
from bench.procs import ChildFailed
from bench.session import Session


def steps(plan: Plan) -> int:
    return 1


def run(bench: Session) -> None:
    """One row, closed_loop, over Plan.closed_loop_trials trials."""
    plan = bench.plan
    bench.progress.step(f"closed_loop: in contact (1 mm preload), press 2 mm further -> "
                        f"force > 2 N at the operator, {plan.closed_loop_trials} trials")
    try:
        result = bench.worker("closed_loop", {
            "proxy_address": bench.station.address["proxy_robot"],
            "force_address": bench.station.address["force_sensor"],
            "trials": plan.closed_loop_trials}, 90 + plan.closed_loop_trials * 5)
    except ChildFailed as error:
        return bench.fail(["closed_loop"], error)
    bench.record("closed_loop", result)
    bench.progress.done(bench.headline("closed_loop"))
