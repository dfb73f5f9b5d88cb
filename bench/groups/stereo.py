"""The stereo group: StereoCamera pairs over gRPC, JPEG, from each source (a test pattern, the
simulated work cell) in each mode (bench/stereo.py in a worker)."""

from __future__ import annotations

from bench import stereo
from bench.plan import Plan
from bench.procs import ChildFailed
from bench.session import Session, missing


def steps(plan: Plan) -> int:
    return len(plan.stereo_sources) * len(plan.stereo_modes)


def run(bench: Session) -> None:
    """stereo_<source>_<mode> for each source and mode; pending when no camera can run."""
    plan = bench.plan
    names = [f"stereo_{s}_{m}" for s in plan.stereo_sources for m in plan.stereo_modes]
    reason = stereo.available()
    if reason:
        for name in names:
            bench.progress.step(name)
            bench.results[name] = missing("pending", reason)
            bench.progress.done("pending")
        return
    for source in plan.stereo_sources:
        try:
            service, address = bench.procs.run_service("stereo_camera", [
                "--source", source, "--width", str(stereo.WIDTH_PX),
                "--height", str(stereo.HEIGHT_PX), "--fps", str(plan.stereo_source_fps),
                # the papers' full picture, as these rows have always measured it
                "--sim-render-scale", "1"])
        except ChildFailed as error:
            for mode in plan.stereo_modes:
                bench.progress.step(f"stereo_{source}_{mode}")
                bench.fail([f"stereo_{source}_{mode}"], error)
            continue
        try:
            for mode in plan.stereo_modes:
                name = f"stereo_{source}_{mode}"
                bench.progress.step(f"{name}: {stereo.WIDTH_PX}x{stereo.HEIGHT_PX} JPEG, "
                                    f"{plan.stereo_pairs} pairs")
                try:
                    result = bench.worker("stereo", {
                        "address": address, "mode": mode, "pairs": plan.stereo_pairs,
                        "source_fps": plan.stereo_source_fps}, 180)
                except ChildFailed as error:
                    bench.fail([name], error)
                    continue
                bench.record(name, result)
                bench.progress.done(bench.headline(name))
        finally:
            bench.procs.stop(service)
