"""The franka group: ProxyRobot's Franka driver commanding franka-sim through libfranka at
1 kHz (bench/franka.py in a worker), bare and publishing its mirror of the arm as the station
runs it."""

from __future__ import annotations

from bench.plan import Plan
from bench.procs import ChildFailed
from bench.report import MIRRORED_SUFFIX
from bench.session import Session

NAME = "franka_command_1000"
MIRRORED = f"{NAME}{MIRRORED_SUFFIX}"


def steps(plan: Plan) -> int:
    return 2


def run(bench: Session) -> None:
    """Two rows over Plan.command_s: franka_command_1000, and franka_command_1000_mirrored."""
    plan = bench.plan
    for name, mirrored, what in ((NAME, False, ""), (MIRRORED, True, ", mirrored")):
        bench.progress.step(f"{name}: FR3 joint targets at 1 kHz through libfranka into "
                            f"franka-sim{what}, {plan.command_s:.0f} s")
        try:
            result = bench.worker("franka", {"duration_s": plan.command_s, "mirrored": mirrored},
                                  60 + plan.command_s * 2, retry=False)
        except ChildFailed as error:
            bench.fail([name], error)
            continue
        bench.record(name, result)
        bench.progress.done(bench.headline(name))
