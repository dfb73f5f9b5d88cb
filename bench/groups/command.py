"""The command group: ProxyRobot.MoveJointsIncremental unary calls, lockstep, at each of
Plan.command_rates (bench/command.py in a worker), and command_1000 again on the TLS
station."""

from __future__ import annotations

from bench.plan import Plan
from bench.procs import ChildFailed
from bench.session import Session
from bench.station import ADMIN_IDENTITY, Station


def steps(plan: Plan) -> int:
    return 2


def run(bench: Session) -> None:
    """command_<rate>, then command_1000_tls."""
    plan = bench.plan
    names = [f"command_{rate}" for rate in plan.command_rates]
    bench.progress.step(f"{', '.join(names)}: ProxyRobot.MoveJointsIncremental unary calls, "
                        f"lockstep, {plan.command_s:.0f} s each")
    try:
        results = bench.rate_worker("command", "grpc", bench.station.address["proxy_robot"],
                                    plan.command_rates)
    except ChildFailed as error:
        bench.fail(names, error)
    else:
        for rate in plan.command_rates:
            bench.record(f"command_{rate}", results[str(rate)])
        bench.progress.done("; ".join(f"{r}: {bench.headline(f'command_{r}')}"
                                      for r in plan.command_rates))
    bench.tls_twin("command_1000", lambda tls: _command_tls(bench, tls))


def _command_tls(bench: Session, tls: Station) -> dict:
    """command_1000 on the TLS station's ProxyRobot, the worker presenting the admin
    certificate (its inner port takes commands from the station or an admin)."""
    return bench.rate_worker("command", "grpc", tls.address["proxy_robot"], [1000],
                             tls.client_params(ADMIN_IDENTITY))["1000"]
