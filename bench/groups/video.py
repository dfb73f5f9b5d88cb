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
    CONSOLE,
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
    width, height = plan.video_size or (WIDTH_PX, HEIGHT_PX)
    render_scale = plan.video_render_scale or "auto"
    bench.progress.step(f"video: a StereoCamera ({source}, {width}x{height} per eye, "
                        f"{SOURCE_FPS:g} fps, render scale {render_scale}) and a "
                        "DecisionServer in front of it")
    why = stereo.available()
    if why:
        bench.results[NAME] = {**_blank(), "status": "pending", "reason": why}
        return bench.progress.done(f"pending: {why}")
    procs = bench.procs
    try:
        camera, camera_address = procs.run_service("stereo_camera", [
            "--source", source, "--width", str(width), "--height", str(height),
            "--fps", str(SOURCE_FPS), "--sim-render-scale", render_scale])
    except ChildFailed as error:
        return bench.fail([NAME], error)
    records, console = [], None
    try:
        with bench.decision_server(bench.station, camera_address) as address:
            # The web console in front of the DecisionServer, for the page's cells (an HTTP
            # gateway: no --grace-s, so not run_service).
            console = procs.start("web_console", [
                "-m", "services.web_console", "--address", "127.0.0.1:0",
                "--decision-server", address])
            console_address = console.wait_ready("web_console", timeout_s=60)
            bench.progress.done(f"camera at {camera_address}, the operator's address {address}, "
                                f"the console at {console_address}")
            for cell in grid:
                target = console_address if cell.console else address
                records.append(_run_cell(bench, target, cell, console))
    except ChildFailed as error:  # the DecisionServer or the console did not start
        return bench.fail([NAME], error)
    finally:
        if console is not None:
            procs.stop(console)
        procs.stop(camera)
    grid_records = [r for r in records if not r["long"] and not r["console"]]
    result = {
        "cells": grid_records, "long": next((r for r in records if r["long"]), None),
        "console": [r for r in records if r["console"]],
        "round_trips_ms": sorted({cell.round_trip_ms for cell in grid if not cell.long}),
        "bottlenecks_mbit": [cap for cap in (QUICK_BOTTLENECKS_MBIT if plan.quick
                                             else BOTTLENECKS_MBIT)],
        "commit": _commit(),
        "camera": {"source": source, "width_px": width, "height_px": height,
                   "fps": SOURCE_FPS, "render_scale": render_scale},
        "goals": {"min_fps": MIN_FPS, "age_slack_ms": AGE_SLACK_MS, "backlog_ms": BACKLOG_MS,
                  "text": goal_text()},
        "skip_s": SKIP_S, "campus_rtt_ms": CAMPUS_RTT_MS,
        "passed": sum(1 for record in records if record["pass"]), "judged": len(records),
        "elapsed_s": round(time.monotonic() - started, 1),
        **_blank(),
        "world_loop": {key: sum((r.get("world_loop") or {}).get(key) or 0 for r in records)
                       for key in ("steps", "overruns", "dropped_steps")}}
    bench.record(NAME, result)


def _run_cell(bench: Session, address: str, cell: Cell, console) -> dict:
    cap = "no bottleneck" if cell.bottleneck_mbit is None else \
        f"{cell.bottleneck_mbit:g} Mbit/s bottleneck"
    what = ("the console's page in Chromium (H.264, WebCodecs)" if cell.console
            else "H.264 with receipts" if cell.long
            else "H.264 with receipts, then JPEG as it was")
    bench.progress.step(f"video {cell.name}: round trip {cell.round_trip_ms:g} ms, {cap}; "
                        f"{what}, {cell.seconds:g} s each after {SKIP_S:g} s")
    record = {"name": cell.name, "round_trip_ms": cell.round_trip_ms,
              "one_way_delay_ms": cell.one_way_ms, "bottleneck_mbit": cell.bottleneck_mbit,
              "seconds": cell.seconds, "skip_s": SKIP_S, "long": cell.long,
              "console": cell.console,
              "age_bound_ms": cell.age_bound_ms,
              "load_avg_at_start": round(os.getloadavg()[0], 2)}  # others' work shows here
    for codec in cell.codecs:
        record[codec] = _probe(bench, address, cell, codec, console)
    record["misses"] = judge(record[cell.codecs[0]], cell)
    record["pass"] = not record["misses"]
    if "jpeg" in record:
        record["vs_jpeg"] = ratios(record["h264"], record["jpeg"])
    record["world_loop"] = bench.loop_since_mark()
    bench.progress.done(cell_text(record))
    return record


def _probe(bench: Session, address: str, cell: Cell, codec: str, console) -> dict:
    """One probe (or the console's page) through a fresh link of its own (its bytes queue
    behind nobody's)."""
    up, down = link_profiles(cell)
    events: list[str] = []
    watched = {name: pid for name in WATCHED if (pid := bench.pid(name)) is not None}
    watched["link (bench)"] = os.getpid()
    if codec == CONSOLE:
        watched["web_console"] = console.pid
    with ImpairmentProxy("127.0.0.1:0", address, up=up, down=down,
                         report=events.append) as proxy:
        params = {"seconds": cell.seconds, "skip_s": SKIP_S, "watch_pids": watched}
        if codec == CONSOLE:
            kind, params["url"] = "video_console", f"http://{proxy.address}/"
        else:
            kind = NAME
            params.update(address=proxy.address, encoding=codec, receipts=codec == "h264")
        try:
            result = bench.procs.run_worker(kind, params, PROBE_TIMEOUT_S + SKIP_S
                                            + cell.seconds, name=f"video_{codec}")
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
