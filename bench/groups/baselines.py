"""The baselines group: the command round trip and the force stream over pyzmq and over a
plain TCP socket (bench/baseline_server.py), so a ratio against the command and force rows
isolates the transport."""

from __future__ import annotations

from bench.plan import Plan
from bench.procs import ChildFailed
from bench.session import Session, missing, reason


def steps(plan: Plan) -> int:
    return 2


def run(bench: Session) -> None:
    """The command round trip and the force stream over pyzmq and over plain TCP, with the
    same payloads and the same domain cores (baseline_server.py)."""
    plan = bench.plan
    bench.station.release()
    try:
        for transport in ("zmq", "tcp"):
            names = ([f"command_{r}_{transport}" for r in plan.command_rates]
                     + [f"force_{r}_{transport}" for r, _ in plan.force_rates])
            label = "pyzmq REQ/REP + PUB/SUB" if transport == "zmq" else "TCP struct framing"
            bench.progress.step(f"baselines over {label}: {', '.join(names)}")
            try:
                try:
                    _baseline(bench, transport)
                except ChildFailed as error:  # once more, with a fresh baseline server
                    why = reason(error)
                    bench.progress.note(f"failed ({why}); retrying once")
                    _baseline(bench, transport)
                    for name in names:
                        bench.results[name]["retried_after"] = why
            except ChildFailed as error:
                for name in names:
                    bench.results[name] = missing("failed", reason(error))
                bench.progress.done(f"FAILED: {reason(error)}")
                continue
            bench.progress.done("; ".join(f"{n}: {bench.headline(n)}"
                                          for n in names if n in bench.results))
    finally:
        bench.station.arm_ready()


def _baseline(bench: Session, transport: str) -> None:
    plan = bench.plan
    server = bench.procs.start(f"baseline_{transport}", [
        "-m", "bench.baseline_server", "--transport", transport, "--shm-name", bench.shm])
    try:
        command_address = server.wait_ready("baseline_command", timeout_s=60.0)
        force_address = server.wait_ready("baseline_force", timeout_s=10.0)
        results = bench.rate_worker("command", transport, command_address,
                                    plan.command_rates, retry=False)
        for rate in plan.command_rates:
            bench.record(f"command_{rate}_{transport}", results[str(rate)])
        for rate, decimation in plan.force_rates:
            bench.record(f"force_{rate}_{transport}", bench.worker("force", {
                "transport": transport, "address": force_address,
                "decimation": decimation, "duration_s": plan.force_s},
                60 + 3 * plan.force_s, retry=False))
    finally:
        bench.procs.stop(server)
