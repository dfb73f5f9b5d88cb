"""Ratios against the baselines, the terminal table and results/latest.json (the goals and
their PASS/FAIL are goals.py's)."""

from __future__ import annotations

import json
import os
import platform
import time
from importlib import metadata
from pathlib import Path

from bench.goals import is_baseline, verdict_text
from bench.stats import ratio

# What the papers report for the same path, for the table's last column.
PAPERS = {
    "command_50": "50 Hz; 1 ms call",
    "command_50_tcp": "custom protocol: 55 ms",
    "force_120": "120 Hz, 8 ms",
    "stereo": "17 fps, 83 ms",
    "closed_loop": "183 ms",
    "observers": "Parma: grows with consumers",
    "estop_under_load": "Parma: no inversion",
    "estop_ds_busywork": "Parma: no inversion",
    "teleop_50": "50 Hz; 1 ms call",
}


def family(name: str) -> str:
    return name.split("_", 1)[0]


def add_ratios(results: dict[str, dict]) -> dict[str, dict]:
    """Papers' figures, and project/baseline ratios on every project scenario that has a
    baseline of the same name (teleop_1000 / teleop_1000_zmq, command_50 / command_50_tcp).
    Returns {project scenario: {baseline transport: {p50, p99 (, ack_p50, ack_p99)}}}."""
    ratios: dict[str, dict] = {}
    for name, result in results.items():
        paper = PAPERS.get(name) or (None if is_baseline(name) else PAPERS.get(family(name)))
        if paper:
            result["paper"] = paper
    for name, result in results.items():
        if is_baseline(name):
            continue
        for transport in ("zmq", "tcp"):
            base = results.get(f"{name}_{transport}")
            if not base or base.get("p50_ms") is None:
                continue
            entry = {"p50": ratio(result.get("p50_ms"), base["p50_ms"]),
                     "p99": ratio(result.get("p99_ms"), base["p99_ms"])}
            if "ack_p50_ms" in result:
                entry["ack_p50"] = ratio(result.get("ack_p50_ms"), base.get("ack_p50_ms"))
                entry["ack_p99"] = ratio(result.get("ack_p99_ms"), base.get("ack_p99_ms"))
            result[f"ratio_vs_{transport}"] = entry
            ratios.setdefault(name, {})[transport] = entry
    return ratios


def machine() -> dict:
    model = "unknown"
    try:
        with open("/proc/cpuinfo") as cpuinfo:
            for line in cpuinfo:
                if line.startswith("model name"):
                    model = line.split(":", 1)[1].strip()
                    break
    except OSError:
        model = platform.processor() or "unknown"
    versions = {}
    for package in ("grpcio", "protobuf", "pyzmq", "numpy", "mujoco"):
        try:
            versions[package] = metadata.version(package)
        except metadata.PackageNotFoundError:
            versions[package] = None
    return {"cores": os.cpu_count(), "cpu_model": model, "python": platform.python_version(),
            "platform": platform.platform(), "packages": versions}


def fmt(value, digits: int = 2) -> str:
    if value is None:
        return "-"
    if isinstance(value, float):
        return f"{value:.{digits}f}"
    return str(value)


def table(results: dict[str, dict]) -> str:
    """The results (judged: goals.add_goals) as a fixed-width table, each row with its goal
    and PASS/FAIL; then the project/baseline ratios and the details."""
    columns = ("scenario", "transport", "offered Hz", "deliv. Hz", "p50 ms", "p99 ms",
               "max ms", "dropped", "world ovr %", "goal", "result", "papers")
    rows = []
    for name, r in results.items():
        rows.append((name, _short_transport(r.get("transport", "")), fmt(r.get("rate_hz"), 1),
                     fmt(r.get("delivered_hz"), 1), fmt(r.get("p50_ms"), 3),
                     fmt(r.get("p99_ms"), 3), fmt(r.get("max_ms"), 3),
                     fmt(r.get("dropped")), fmt(_overrun_pct(r), 2), r.get("goal", "-"),
                     verdict_text({"goal": r.get("goal", "-"), "pass": r.get("pass")}),
                     r.get("paper", "")))
    widths = [max(len(str(row[i])) for row in [columns, *rows]) for i in range(len(columns))]
    lines = ["  ".join(str(c).ljust(w) for c, w in zip(columns, widths, strict=True)),
             "  ".join("-" * w for w in widths)]
    lines += ["  ".join(str(c).ljust(w) for c, w in zip(row, widths, strict=True))
              for row in rows]
    misses = [f"  {name}: {'; '.join(r['goal_misses'])}" for name, r in results.items()
              if r.get("goal_misses")]
    if misses:
        lines += ["", "Goals missed:", *misses]
    ratio_lines = []
    for name, r in results.items():
        for transport in ("zmq", "tcp"):
            entry = r.get(f"ratio_vs_{transport}")
            if entry:
                parts = [f"{key} x{fmt(value)}" for key, value in entry.items()]
                ratio_lines.append(f"  {name} / {name}_{transport}: " + ", ".join(parts))
    if ratio_lines:
        lines += ["", "Project / baseline (same payloads, same domain cores, same run):",
                  *ratio_lines]
    extras = _extras(results)
    if extras:
        lines += ["", *extras]
    return "\n".join(lines)


def _overrun_pct(result: dict) -> float | None:
    """The world loop's overruns during the scenario, % of its steps (None if not read)."""
    if "overrun_pct" in result:
        return result["overrun_pct"]
    loop = result.get("world_loop")
    return loop.get("overrun_pct") if isinstance(loop, dict) else None


def _short_transport(text: str) -> str:
    return text.split(" ", 1)[0] if text else ""


def _extras(results: dict[str, dict]) -> list[str]:
    lines = []
    for name, r in results.items():
        if r.get("status") == "pending":
            lines.append(f"  {name}: pending: {r.get('reason')}")
        elif family(name) in ("command", "teleop"):
            lines.append(f"  {name}: ack round trip p50 {fmt(r.get('ack_p50_ms'), 3)} / p99 "
                         f"{fmt(r.get('ack_p99_ms'), 3)} ms; late ticks skipped "
                         f"{r.get('late_skipped')}")
        elif family(name) == "observers":
            lines.append(f"  {name}: operator jitter {fmt(r.get('jitter_ms'), 3)} ms, "
                         f"inter-arrival p99 {fmt(r.get('interarrival_p99_ms'), 3)} ms; "
                         f"observers got {fmt(r.get('observer_delivered_hz_mean'), 1)} Hz "
                         f"each (of {fmt(r.get('observer_rate_hz'), 0)})")
        elif family(name) == "estop":
            lines.append(f"  {name}: RPC returned p50 {fmt(r.get('ack_p50_ms'), 3)} / p99 "
                         f"{fmt(r.get('ack_p99_ms'), 3)} ms; joints under 0.05 rad/s p50 "
                         f"{fmt(r.get('stopped_p50_ms'), 1)} ms (braking at 10 rad/s^2)")
        elif name == "world_loop":
            since = r.get("since_world_start") or {}
            lines.append(f"  {name}: {r.get('steps')} steps, {r.get('overruns')} overruns, "
                         f"{r.get('dropped_steps')} dropped over the run; since the world "
                         f"started (start-up included) {since.get('overruns')} of "
                         f"{since.get('steps')} ({fmt(since.get('overrun_pct'), 2)} %)")
        elif name == "closed_loop":
            lines.append(f"  {name}: = call ack p50 {fmt(r.get('ack_p50_ms'), 2)} ms; "
                         f"send->contact sample p50 {fmt(r.get('motion_p50_ms'), 1)} ms; "
                         f"sample->operator p50 {fmt(r.get('feedback_p50_ms'), 3)} / p99 "
                         f"{fmt(r.get('feedback_p99_ms'), 3)} ms")
    if lines:
        lines.insert(0, "Details:")
    return lines


def write_json(path: Path, results: dict[str, dict], ratios: dict, info: dict) -> None:
    document = {"time": time.strftime("%Y-%m-%dT%H:%M:%S%z"), **info, **results,
                "ratios": ratios}
    path.write_text(json.dumps(document, indent=2, default=str))
