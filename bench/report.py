"""Budgets, verdicts, ratios, the terminal table and results/latest.json."""

from __future__ import annotations

import json
import os
import platform
import time
from importlib import metadata
from pathlib import Path

from bench.stats import ratio

# ARCHITECTURE.md's budgets (loopback, 2-core machine), by scenario family.
LATENCY_BUDGET_MS = {"command": 2.0, "teleop": 2.0, "force": 2.0, "observers": 2.0,
                     "stereo": 30.0, "estop": 5.0}
STEREO_MIN_FPS = 30.0
RATE_TOLERANCE = 0.95  # delivered below this share of the offered rate is "short"

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


def is_baseline(name: str) -> bool:
    return name.endswith("_zmq") or name.endswith("_tcp")


def budget_text(name: str) -> str:
    if is_baseline(name) or name == "closed_loop":
        return "-"
    fam = family(name)
    if fam == "stereo":
        return f">={STEREO_MIN_FPS:.0f} fps, p99<={LATENCY_BUDGET_MS['stereo']:.0f}"
    if fam in LATENCY_BUDGET_MS:
        return f"p99<={LATENCY_BUDGET_MS[fam]:g}"
    return "-"


def verdict(name: str, result: dict) -> str:
    """ok, over (latency past the budget), short (rate under the offered one), both, or -."""
    if result.get("status") in ("pending", "failed"):
        return result["status"]
    if is_baseline(name) or name == "closed_loop" or family(name) not in LATENCY_BUDGET_MS:
        return "-"
    problems = []
    p99 = result.get("p99_ms")
    if p99 is None or p99 > LATENCY_BUDGET_MS[family(name)]:
        problems.append("over")
    offered, delivered = result.get("rate_hz"), result.get("delivered_hz")
    if family(name) == "stereo":
        if delivered is None or delivered < RATE_TOLERANCE * STEREO_MIN_FPS:
            problems.append("short")
    elif offered and (delivered is None or delivered < RATE_TOLERANCE * offered):
        problems.append("short")
    if result.get("dropped"):
        problems.append("drops")
    return "+".join(problems) or "ok"


def add_verdicts_and_ratios(results: dict[str, dict]) -> dict[str, dict]:
    """Budget and verdict on every scenario; project/baseline ratios on the project's ones.
    Returns {project scenario: {baseline: {p50, p99 (, ack_p50, ack_p99)}}}."""
    ratios: dict[str, dict] = {}
    for name, result in results.items():
        result["budget"] = budget_text(name)
        result["verdict"] = verdict(name, result)
        paper = PAPERS.get(name) or (None if is_baseline(name) else PAPERS.get(family(name)))
        if paper:
            result["paper"] = paper
    for name, result in results.items():
        if is_baseline(name):
            continue
        stem = name.replace("teleop_", "command_", 1) if name.startswith("teleop_") else name
        for transport in ("zmq", "tcp"):
            base = results.get(f"{stem}_{transport}")
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


def _fmt(value, digits: int = 2) -> str:
    if value is None:
        return "-"
    if isinstance(value, float):
        return f"{value:.{digits}f}"
    return str(value)


def table(results: dict[str, dict]) -> str:
    """The results as a fixed-width table, then the project/baseline ratios."""
    columns = ("scenario", "transport", "offered Hz", "deliv. Hz", "p50 ms", "p99 ms",
               "max ms", "dropped", "budget", "verdict", "papers")
    rows = []
    for name, r in results.items():
        rows.append((name, _short_transport(r.get("transport", "")), _fmt(r.get("rate_hz"), 1),
                     _fmt(r.get("delivered_hz"), 1), _fmt(r.get("p50_ms"), 3),
                     _fmt(r.get("p99_ms"), 3), _fmt(r.get("max_ms"), 3),
                     _fmt(r.get("dropped")), r.get("budget", "-"), r.get("verdict", "-"),
                     r.get("paper", "")))
    widths = [max(len(str(row[i])) for row in [columns, *rows]) for i in range(len(columns))]
    lines = ["  ".join(str(c).ljust(w) for c, w in zip(columns, widths, strict=True)),
             "  ".join("-" * w for w in widths)]
    lines += ["  ".join(str(c).ljust(w) for c, w in zip(row, widths, strict=True))
              for row in rows]
    ratio_lines = []
    for name, r in results.items():
        for transport in ("zmq", "tcp"):
            entry = r.get(f"ratio_vs_{transport}")
            if entry:
                parts = [f"{key} x{_fmt(value)}" for key, value in entry.items()]
                stem = name.replace("teleop_", "command_", 1)
                ratio_lines.append(f"  {name} / {stem}_{transport}: " + ", ".join(parts))
    if ratio_lines:
        lines += ["", "Project / baseline (same payloads, same domain cores, same run):",
                  *ratio_lines]
    extras = _extras(results)
    if extras:
        lines += ["", *extras]
    return "\n".join(lines)


def _short_transport(text: str) -> str:
    return text.split(" ", 1)[0] if text else ""


def _extras(results: dict[str, dict]) -> list[str]:
    lines = []
    for name, r in results.items():
        if r.get("status") == "pending":
            lines.append(f"  {name}: pending: {r.get('reason')}")
        elif family(name) in ("command", "teleop"):
            lines.append(f"  {name}: ack round trip p50 {_fmt(r.get('ack_p50_ms'), 3)} / p99 "
                         f"{_fmt(r.get('ack_p99_ms'), 3)} ms; late ticks skipped "
                         f"{r.get('late_skipped')}")
        elif family(name) == "observers":
            lines.append(f"  {name}: operator jitter {_fmt(r.get('jitter_ms'), 3)} ms, "
                         f"inter-arrival p99 {_fmt(r.get('interarrival_p99_ms'), 3)} ms; "
                         f"observers got {_fmt(r.get('observer_delivered_hz_mean'), 1)} Hz "
                         f"each (of {_fmt(r.get('observer_rate_hz'), 0)})")
        elif family(name) == "estop":
            lines.append(f"  {name}: RPC returned p50 {_fmt(r.get('ack_p50_ms'), 3)} / p99 "
                         f"{_fmt(r.get('ack_p99_ms'), 3)} ms; joints under 0.05 rad/s p50 "
                         f"{_fmt(r.get('stopped_p50_ms'), 1)} ms (braking at 10 rad/s^2)")
        elif name == "closed_loop":
            lines.append(f"  {name}: = call ack p50 {_fmt(r.get('ack_p50_ms'), 2)} ms; "
                         f"send->contact sample p50 {_fmt(r.get('motion_p50_ms'), 1)} ms; "
                         f"sample->operator p50 {_fmt(r.get('feedback_p50_ms'), 3)} / p99 "
                         f"{_fmt(r.get('feedback_p99_ms'), 3)} ms")
    if lines:
        lines.insert(0, "Details:")
    return lines


def write_json(path: Path, results: dict[str, dict], ratios: dict, info: dict) -> None:
    document = {"time": time.strftime("%Y-%m-%dT%H:%M:%S%z"), **info, **results,
                "ratios": ratios}
    path.write_text(json.dumps(document, indent=2, default=str))
