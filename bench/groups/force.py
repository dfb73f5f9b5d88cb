"""The force group: ForceSensor.StreamWrench to one subscriber at each of Plan.force_rates
(bench/force.py in a worker), and force_1000 recording each sample in MCAP, in pairs
interleaved with it."""

from __future__ import annotations

from bench.plan import Plan
from bench.procs import ChildFailed
from bench.session import Session


def steps(plan: Plan) -> int:
    return len(plan.force_rates) + 1


def run(bench: Session) -> None:
    """force_<rate> for each of Plan.force_rates; force_1000_mcap right after force_1000."""
    for rate, decimation in bench.plan.force_rates:
        name = f"force_{rate}"
        bench.progress.step(f"{name}: StreamWrench, sensor period 1 ms, decimation "
                            f"{decimation} ({1000 / decimation:.0f} Hz)")
        try:
            result = _force_worker(bench, decimation)
        except ChildFailed as error:
            bench.fail([name], error)
        else:
            bench.record(name, result)
            bench.progress.done(bench.headline(name))
        if name == "force_1000":
            bench.mcap_twin(name, "the subscriber writing each sample to MCAP (wrench and "
                            "Foxglove arrow, as make teleop --mcap) before its timestamp",
                            lambda index, _sign: _force_leg(bench, index),
                            lambda index, _sign: _force_leg(bench, index, True))


def _force_leg(bench: Session, index: int, record: bool = False) -> dict:
    """A leg of force_1000_mcap's pair `index`: force_1000 for overhead_force_leg_s,
    recording into a file of the pair's own when `record`."""
    path = bench.procs.scratch / f"force_1000_{index + 1}.mcap"
    return _force_worker(bench, 1, str(path) if record else None,
                         duration_s=bench.plan.overhead_force_leg_s)


def _force_worker(bench: Session, decimation: int, mcap_path: str | None = None,
                  duration_s: float | None = None) -> dict:
    """force_<rate>'s worker (plan.force_s, or `duration_s`); `mcap_path`: recording each
    sample there."""
    duration_s = duration_s or bench.plan.force_s
    return bench.worker("force", {
        "transport": "grpc", "address": bench.station.address["force_sensor"],
        "decimation": decimation, "duration_s": duration_s,
        **({"mcap_path": mcap_path} if mcap_path else {})}, 60 + 3 * duration_s)
