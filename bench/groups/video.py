"""The video group: the stereo stream across the impairment link, H.264 paced by receipts
beside the JPEG stream, cell by cell (bench/video.py says what and why, and judges it; its
worker side runs clients.video_probe)."""

from __future__ import annotations

import dataclasses
import os
import time
from pathlib import Path

from bench import stereo
from bench.plan import Plan
from bench.procs import ChildFailed
from bench.session import Session, reason
from bench.video import (
    AGE_SLACK_MS,
    BACKLOG_MS,
    BOTTLENECKS_MBIT,
    CAMPUS_RTT_MS,
    HEIGHT_PX,
    MIN_FPS,
    NAME,
    PROBE_TIMEOUT_S,
    QUICK_BOTTLENECKS_MBIT,
    SKIP_S,
    SOURCE,
    SOURCE_FPS,
    WATCHED,
    WIDTH_PX,
    Cell,
    cell_text,
    cells,
    goal_text,
    judge,
    link_profiles,
    ratios,
    step_count,
)
from services.impairment import ImpairmentProxy


def steps(plan: Plan) -> int:
    return step_count(plan)


def run(bench: Session) -> None:
    """A StereoCamera (sim) and a DecisionServer before it, then a step per cell; one result
    row."""
    plan, started = bench.plan, time.monotonic()
    grid = cells(plan.quick, plan.video_s, plan.video_long_s)
    source = plan.video_source or SOURCE
    bench.progress.step(f"video: a StereoCamera ({source}, {WIDTH_PX}x{HEIGHT_PX} per eye, "
                        f"{SOURCE_FPS:g} fps) and a DecisionServer in front of it")
    why = stereo.available()
    if why:
        bench.results[NAME] = {**_blank(), "status": "pending", "reason": why}
        return bench.progress.done(f"pending: {why}")
    procs = bench.procs
    try:
        camera, camera_address = procs.run_service("stereo_camera", [
            "--source", source, "--width", str(WIDTH_PX), "--height", str(HEIGHT_PX),
            "--fps", str(SOURCE_FPS)])
    except ChildFailed as error:
        return bench.fail([NAME], error)
    records = []
    try:
        with bench.decision_server(bench.station, camera_address) as address:
            bench.progress.done(f"camera at {camera_address}, the operator's address {address}")
            for cell in grid:
                records.append(_run_cell(bench, address, cell))
    except ChildFailed as error:  # the DecisionServer did not start
        return bench.fail([NAME], error)
    finally:
        procs.stop(camera)
    grid_records = [record for record in records if not record["long"]]
    result = {
        "cells": grid_records, "long": next((r for r in records if r["long"]), None),
        "round_trips_ms": sorted({cell.round_trip_ms for cell in grid if not cell.long}),
        "bottlenecks_mbit": [cap for cap in (QUICK_BOTTLENECKS_MBIT if plan.quick
                                             else BOTTLENECKS_MBIT)],
        "commit": _commit(),
        "camera": {"source": source, "width_px": WIDTH_PX, "height_px": HEIGHT_PX,
                   "fps": SOURCE_FPS},
        "goals": {"min_fps": MIN_FPS, "age_slack_ms": AGE_SLACK_MS, "backlog_ms": BACKLOG_MS,
                  "text": goal_text()},
        "skip_s": SKIP_S, "campus_rtt_ms": CAMPUS_RTT_MS,
        "passed": sum(1 for record in records if record["pass"]), "judged": len(records),
        "elapsed_s": round(time.monotonic() - started, 1),
        **_blank(),
        "world_loop": {key: sum((r.get("world_loop") or {}).get(key) or 0 for r in records)
                       for key in ("steps", "overruns", "dropped_steps")}}
    bench.record(NAME, result)


def _run_cell(bench: Session, address: str, cell: Cell) -> dict:
    cap = "no bottleneck" if cell.bottleneck_mbit is None else \
        f"{cell.bottleneck_mbit:g} Mbit/s bottleneck"
    what = "H.264 with receipts" if cell.long else "H.264 with receipts, then JPEG as it was"
    bench.progress.step(f"video {cell.name}: round trip {cell.round_trip_ms:g} ms, {cap}; "
                        f"{what}, {cell.seconds:g} s each after {SKIP_S:g} s")
    record = {"name": cell.name, "round_trip_ms": cell.round_trip_ms,
              "one_way_delay_ms": cell.one_way_ms, "bottleneck_mbit": cell.bottleneck_mbit,
              "seconds": cell.seconds, "skip_s": SKIP_S, "long": cell.long,
              "age_bound_ms": cell.age_bound_ms,
              "load_avg_at_start": round(os.getloadavg()[0], 2)}  # others' work shows here
    for codec in cell.codecs:
        record[codec] = _probe(bench, address, cell, codec)
    record["misses"] = judge(record["h264"], cell)
    record["pass"] = not record["misses"]
    if "jpeg" in record:
        record["vs_jpeg"] = ratios(record["h264"], record["jpeg"])
    record["world_loop"] = bench.loop_since_mark()
    bench.progress.done(cell_text(record))
    return record


def _probe(bench: Session, address: str, cell: Cell, codec: str) -> dict:
    """One probe through a fresh link of its own (its bytes queue behind nobody's)."""
    up, down = link_profiles(cell)
    events: list[str] = []
    watched = {name: pid for name in WATCHED if (pid := bench.pid(name)) is not None}
    watched["link (bench)"] = os.getpid()
    with ImpairmentProxy("127.0.0.1:0", address, up=up, down=down,
                         report=events.append) as proxy:
        try:
            result = bench.procs.run_worker(NAME, {
                "address": proxy.address, "encoding": codec, "receipts": codec == "h264",
                "seconds": cell.seconds, "skip_s": SKIP_S, "watch_pids": watched},
                PROBE_TIMEOUT_S + SKIP_S + cell.seconds, name=f"video_{codec}")
        except ChildFailed as error:
            result = {"status": "failed", "reason": reason(error)}
        stats = dataclasses.asdict(proxy.stats)
    result["link"] = {"bytes": stats["bytes"], "connections": stats["connections"]}
    result.pop("address", None)  # the link's port: no use after the run
    return result


def _commit() -> str | None:
    """The repository's commit, "+dirty" when its tracked files differ from it (the station
    ran the working tree)."""
    import subprocess

    repo = Path(__file__).resolve().parents[2]
    try:
        head = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=repo, text=True,
                              capture_output=True, timeout=10, check=True).stdout.strip()
        dirty = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no"],
                               cwd=repo, text=True, capture_output=True, timeout=10).stdout
    except (OSError, subprocess.SubprocessError):
        return None
    return head + ("+dirty" if dirty.strip() else "")


def _blank() -> dict:
    """No latency of its own for the other groups' columns."""
    return {"rate_hz": None, "delivered_hz": None, "p50_ms": None, "p99_ms": None,
            "max_ms": None, "dropped": None}
