"""The franka group: ProxyRobot's Franka driver commanding franka-sim through libfranka at
1 kHz (bench/franka.py in a worker)."""

from __future__ import annotations

from bench.plan import Plan
from bench.procs import ChildFailed
from bench.session import Session

NAME = "franka_command_1000"


def steps(plan: Plan) -> int:
    return 1


def run(bench: Session) -> None:
    """One row, franka_command_1000, over Plan.command_s."""
    plan = bench.plan
    bench.progress.step(f"{NAME}: FR3 joint targets at 1 kHz through libfranka into "
                        f"franka-sim, {plan.command_s:.0f} s")
    try:
        result = bench.worker("franka", {"duration_s": plan.command_s},
                              60 + plan.command_s * 2, retry=False)
    except ChildFailed as error:
        return bench.fail([NAME], error)
    bench.record(NAME, result)
    bench.progress.done(bench.headline(NAME))
