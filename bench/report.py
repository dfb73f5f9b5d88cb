"""Ratios against the baselines (and of each TLS variant against its plaintext twin, each
recording-on variant against its twin without), the terminal table and results/latest.json
(the goals and their PASS/FAIL are goals.py's)."""

from __future__ import annotations

import json
import math
import os
import platform
import statistics
import time
from importlib import metadata
from pathlib import Path

from bench.goals import (
    CPU_KEY,
    PROXY_CPU_KEY,
    SUBSCRIBER_CPU_KEY,
    THREAD_CPU_KEY,
    is_baseline,
    verdict_text,
)
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
    "network": "campus routes: 183 ms round trip",
    "video": "stereo 17 fps, 83 ms",
}


TLS_SUFFIX = "_tls"
PLAINTEXT = "plaintext"  # what a TLS variant is compared with, as the ratios name it
MCAP_SUFFIX = "_mcap"
EPISODE_SUFFIX = "_episode"  # recorded as a demonstration episode: MCAP with the video
RECORDING_OFF = "recording_off"  # what a recording-on variant is compared with
MIRRORED_SUFFIX = "_mirrored"
UNMIRRORED = "unmirrored"  # what a driver publishing its arm's mirror is compared with
TWINS = {TLS_SUFFIX: PLAINTEXT, MCAP_SUFFIX: RECORDING_OFF, EPISODE_SUFFIX: RECORDING_OFF,
         MIRRORED_SUFFIX: UNMIRRORED}


def family(name: str) -> str:
    return name.split("_", 1)[0]


def plaintext_twin(name: str) -> str | None:
    """The plaintext scenario a TLS variant repeats (command_1000_tls: command_1000)."""
    return name.removesuffix(TLS_SUFFIX) if name.endswith(TLS_SUFFIX) else None


def twin_of(name: str) -> tuple[str, str] | None:
    """(label, scenario) of the scenario a variant repeats: teleop_1000_tls's plaintext
    teleop_1000, teleop_1000_mcap's teleop_1000 without recording, franka_command_1000_mirrored's
    franka_command_1000 without the arm's mirror; None for the others."""
    for suffix, label in TWINS.items():
        if name.endswith(suffix):
            return label, name.removesuffix(suffix)
    return None


def compared_with(name: str) -> list[tuple[str, str]]:
    """(label, scenario) for each scenario whose figures `name`'s are divided by: a variant's
    twin (twin_of); a project scenario's baselines of the same name (zmq, tcp)."""
    if is_baseline(name):
        return []
    twin = twin_of(name)
    if twin is not None:
        return [twin]
    return [(transport, f"{name}_{transport}") for transport in ("zmq", "tcp")]


def comparison(result: dict, base: dict) -> dict[str, float | None]:
    """result / base: p50, p99, the delivered rate when both stream, the ack round trip's p50
    and p99 when the result has one, the server's CPU per command when both have it. Empty
    when `base` has no latencies."""
    if base.get("p50_ms") is None:
        return {}
    entry = {"p50": ratio(result.get("p50_ms"), base["p50_ms"]),
             "p99": ratio(result.get("p99_ms"), base["p99_ms"])}
    if result.get("rate_hz") and base.get("rate_hz"):
        entry["delivered"] = ratio(result.get("delivered_hz"), base.get("delivered_hz"))
    if "ack_p50_ms" in result:
        entry["ack_p50"] = ratio(result.get("ack_p50_ms"), base.get("ack_p50_ms"))
        entry["ack_p99"] = ratio(result.get("ack_p99_ms"), base.get("ack_p99_ms"))
    if CPU_KEY in result and CPU_KEY in base:
        entry["server_cpu"] = ratio(result[CPU_KEY], base[CPU_KEY])
    if SUBSCRIBER_CPU_KEY in result and SUBSCRIBER_CPU_KEY in base:
        entry["subscriber_cpu"] = ratio(result[SUBSCRIBER_CPU_KEY], base[SUBSCRIBER_CPU_KEY])
    return entry


# A leg's figures an interleaved pair keeps (the rest, e.g. latencies, is the leg's worker's).
LEG_KEYS = ("delivered_hz", "p50_ms", "p99_ms", "dropped", CPU_KEY, PROXY_CPU_KEY,
            SUBSCRIBER_CPU_KEY, THREAD_CPU_KEY, "session_applied", "retried_after")
# The ratios (on / off) of an interleaved pair: {name: result key}; goals.py judges some.
OVERHEAD_RATIOS = {"delivered": "delivered_hz", "p50": "p50_ms", "p99": "p99_ms",
                   "server_cpu": CPU_KEY, "subscriber_cpu": SUBSCRIBER_CPU_KEY}


def _leg(result: dict) -> dict:
    return {key: result[key] for key in LEG_KEYS if result.get(key) is not None}


def _ratio3(numerator: float | None, denominator: float | None) -> float | None:
    if numerator is None or denominator is None or denominator <= 0:
        return None
    value = numerator / denominator
    return round(value, 3) if math.isfinite(value) else None


def interleaved(pairs: list[tuple[dict, dict]]) -> dict:
    """A recording-on row (issue #17) from interleaved pairs [(off leg, on leg), ...] made
    off, on, on, off, off, on... (Session.mcap_twin): the first on leg's result (its figures
    are the row's, as the first off leg's are the twin's), with `overhead_pairs` (each leg's
    figures, and the on leg's `recording`), `overhead_ratios` (on / off per pair, for each of
    OVERHEAD_RATIOS both legs have), `overhead_median` (their median: what goals.py judges),
    `thread_cpu_change` (where the server's CPU per command moved: thread_cpu_change) and
    `recordings` (every on leg's, each checked by goals.recording_misses; none when no leg
    recorded)."""
    row = dict(pairs[0][1])
    ratios: dict[str, list[float | None]] = {}
    for name, key in OVERHEAD_RATIOS.items():
        values = [_ratio3(on.get(key), off.get(key)) for off, on in pairs]
        if any(value is not None for value in values):
            ratios[name] = values
    row["overhead_pairs"] = [{"off": _leg(off), "on": _leg(on)} for off, on in pairs]
    row["overhead_ratios"] = ratios
    row["overhead_median"] = {
        name: round(statistics.median(known), 3)
        for name, values in ratios.items()
        if (known := [value for value in values if value is not None])}
    if change := thread_cpu_change(pairs):
        row["thread_cpu_change"] = change
    recordings = [on.get("recording") for _, on in pairs]
    if any(recording is not None for recording in recordings):  # (none in an A/A row)
        row["recordings"] = recordings
    return row


def thread_cpu_change(pairs: list[tuple[dict, dict]]) -> dict[str, float]:
    """{thread name: the median over pairs of the on leg's CPU per command less the off
    leg's, µs}, for the names either leg of a pair has (0 in the other), largest change
    first; {} when the legs were not split by thread."""
    legs = [(off.get(THREAD_CPU_KEY), on.get(THREAD_CPU_KEY)) for off, on in pairs]
    legs = [(off, on) for off, on in legs if off is not None and on is not None]
    names = {name for off, on in legs for name in (*off, *on)}
    change = {name: round(statistics.median(on.get(name, 0.0) - off.get(name, 0.0)
                                            for off, on in legs), 1) for name in names}
    return dict(sorted(change.items(), key=lambda item: -abs(item[1])))


def thread_cpu_text(row: dict, shown: int = 4) -> str:
    """"event_engine +11.7, follow-proxy_ro +5.7 µs/command": the `shown` largest changes of
    thread_cpu_change; "" without them."""
    change = list((row.get("thread_cpu_change") or {}).items())[:shown]
    return ", ".join(f"{name} {value:+.1f}" for name, value in change) + (
        " µs/command" if change else "")


def overhead_text(row: dict, symbol: str = "x") -> str:
    """"server_cpu x1.04 (x1.02, x1.04, x1.10), ...": each median of an interleaved row and
    its pairs' ratios; "" for a row without them."""
    medians, ratios = row.get("overhead_median") or {}, row.get("overhead_ratios") or {}
    return ", ".join(
        f"{name} {symbol}{value:.2f} ("
        + ", ".join("-" if v is None else f"{symbol}{v:.2f}" for v in ratios.get(name, []))
        + ")" for name, value in medians.items())


def ratio_text(entry: dict[str, float | None]) -> str:
    return ", ".join(f"{key} x{fmt(value)}" for key, value in entry.items()) or "-"


def add_ratios(results: dict[str, dict]) -> dict[str, dict]:
    """Papers' figures, and `ratio_vs_<label>` on every scenario measured in the run with
    what it is compared with (compared_with: teleop_1000 / teleop_1000_zmq, command_50 /
    command_50_tcp, command_1000_tls / command_1000).
    Returns {scenario: {label: comparison}}."""
    ratios: dict[str, dict] = {}
    for name, result in results.items():
        paper = PAPERS.get(name) or (None if is_baseline(name) else PAPERS.get(family(name)))
        if paper:
            result["paper"] = paper
    for name, result in results.items():
        for label, other in compared_with(name):
            entry = comparison(result, results.get(other) or {})
            if entry:
                result[f"ratio_vs_{label}"] = entry
                ratios.setdefault(name, {})[label] = entry
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
        pass  # not Linux: platform.processor() would run `uname -p`, and the model is a label
    versions = {}
    for package in ("grpcio", "protobuf", "pyzmq", "numpy", "mujoco"):
        try:
            versions[package] = metadata.version(package)
        except metadata.PackageNotFoundError:
            versions[package] = None
    return {"cores": os.cpu_count(), "cpu_model": model, "python": platform.python_version(),
            # platform.platform() runs `uname -p`: these are the same fields without it.
            "platform": f"{platform.system()}-{platform.release()}-{platform.machine()}",
            "packages": versions}


def fmt(value, digits: int = 2) -> str:
    if value is None:
        return "-"
    if isinstance(value, float):
        return f"{value:.{digits}f}"
    return str(value)


def table(results: dict[str, dict], tables: dict[str, list[str]] | None = None) -> str:
    """The results (judged: goals.add_goals) as a fixed-width table, each row with its goal
    and PASS/FAIL; then the project/baseline ratios and the details, among them `tables`:
    the lines of the rows that have a table of their own (the network and video groups'),
    by row."""
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
    titles = {"baselines": "Project / baseline (same payloads, same domain cores, same run):",
              PLAINTEXT: "Mutual TLS / plaintext (the same scenario, right after it; "
                         "teleop's then on, off, off, on...):",
              RECORDING_OFF: "MCAP recording on / off (the same scenario, right after it; "
                             "then on, off, off, on...):"}
    sections: dict[str, list[str]] = {key: [] for key in titles}
    for name, r in results.items():
        for label, other in compared_with(name):
            entry = r.get(f"ratio_vs_{label}")
            if entry:
                sections[label if label in titles else "baselines"].append(
                    f"  {name} / {other}: {ratio_text(entry)}")
            if r.get("overhead_median") and label in titles:
                sections[label].append(
                    f"  {name}, median of {len(r.get('overhead_pairs') or [])} interleaved "
                    f"pairs (on / off): {overhead_text(r)}")
    for key, title in titles.items():
        if sections[key]:
            lines += ["", title, *sections[key]]
    extras = _extras(results, tables or {})
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


def _extras(results: dict[str, dict], tables: dict[str, list[str]]) -> list[str]:
    lines = []
    for name, r in results.items():
        if r.get("recordings"):  # an interleaved row: every on leg's
            lines += [f"  {name}, pair {index}: {recording_text(entry or {})}"
                      for index, entry in enumerate(r["recordings"], 1)]
        elif r.get("recording"):
            lines.append(f"  {name}: {recording_text(r['recording'])}")
        if r.get("status") == "pending":
            lines.append(f"  {name}: pending: {r.get('reason')}")
        elif family(name) in ("command", "teleop"):
            cpu = (f"; DecisionServer CPU {fmt(r[CPU_KEY], 3)} ms/command" if CPU_KEY in r
                   else "") + (f", ProxyRobot {fmt(r[PROXY_CPU_KEY], 3)}"
                               if PROXY_CPU_KEY in r else "")
            lines.append(f"  {name}: ack round trip p50 {fmt(r.get('ack_p50_ms'), 3)} / p99 "
                         f"{fmt(r.get('ack_p99_ms'), 3)} ms; late ticks skipped "
                         f"{r.get('late_skipped')}{cpu}")
        elif family(name) == "force" and SUBSCRIBER_CPU_KEY in r and not is_baseline(name):
            lines.append(f"  {name}: subscriber CPU {fmt(r[SUBSCRIBER_CPU_KEY], 1)} µs/sample")
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
        elif name == "soak":
            lines += _soak_lines(r)
        elif name in tables:
            lines += tables[name]
        elif name == "closed_loop":
            lines.append(f"  {name}: = call ack p50 {fmt(r.get('ack_p50_ms'), 2)} ms; "
                         f"send->contact sample p50 {fmt(r.get('motion_p50_ms'), 1)} ms; "
                         f"sample->operator p50 {fmt(r.get('feedback_p50_ms'), 3)} / p99 "
                         f"{fmt(r.get('feedback_p99_ms'), 3)} ms")
    if lines:
        lines.insert(0, "Details:")
    return lines


def recording_text(recording: dict) -> str:
    """What a recording-on row's file holds against what it was given (recording.py)."""
    held = ", ".join(f"{name} {count}" for name, count in recording.get("recorded", {}).items())
    moves = (f"; {recording['moves']} moves (StopRecording: {recording['moves_saved']})"
             if "moves" in recording else "")
    error = f"; error: {recording['error']}" if recording.get("error") else ""
    return (f"{recording.get('format')} of {recording.get('expected')}: {held}{moves}, "
            f"{(recording.get('file_bytes') or 0) / 1e6:.1f} MB{error}")


def _soak_lines(r: dict) -> list[str]:
    """The soak's details: each station process's RSS, then its streams and events."""
    lines = [f"  soak: {r.get('minutes')} min; RSS (MiB) first -> last, slope after the "
             f"warm-up (MiB/min; over its second half), CPU % of a core:"]
    for process, e in (r.get("rss") or {}).items():
        lines.append(f"    {process}: {fmt(e.get('start_mib'), 1)} -> {fmt(e.get('end_mib'), 1)}"
                     f", slope {fmt(e.get('slope_mib_min'), 3)} "
                     f"({fmt(e.get('late_slope_mib_min'), 3)}), CPU {fmt(e.get('cpu_pct'), 0)} %"
                     f", threads {(e.get('threads') or {}).get('start')} -> "
                     f"{(e.get('threads') or {}).get('end')}, fds "
                     f"{(e.get('fds') or {}).get('start')} -> {(e.get('fds') or {}).get('end')}")
    teleop, observers = r.get("teleop") or {}, r.get("observers") or {}
    camera, events = r.get("stereo") or {}, r.get("events") or {}
    lines.append(f"    teleop: {teleop.get('sent')} sent, {teleop.get('unacked')} unacked "
                 f"({teleop.get('ack_gaps')} gaps), {teleop.get('refused')} refused, "
                 f"{teleop.get('late_skipped')} late ticks skipped; ack p50 "
                 f"{fmt(teleop.get('ack_p50_ms'), 1)} / p99 {fmt(teleop.get('ack_p99_ms'), 1)} ms")
    lines.append(f"    observers: {fmt(observers.get('observer_delivered_hz_mean'), 1)} Hz each "
                 f"of {fmt(observers.get('observer_rate_hz'), 0)}, "
                 f"{observers.get('observer_sequence_gaps')} samples missing "
                 f"({observers.get('observer_server_dropped')} dropped by the server)")
    lines.append(f"    stereo: {camera.get('pairs')} pairs, {fmt(camera.get('delivered_hz'), 1)} "
                 f"fps, p50 {fmt(camera.get('p50_ms'), 1)} / p99 {fmt(camera.get('p99_ms'), 1)} "
                 f"ms, {camera.get('dropped')} skipped {camera.get('reason') or ''}".rstrip())
    lines.append(f"    events: {events.get('events')} ({events.get('kinds')}); "
                 f"{events.get('control_changes')} control changes, {events.get('leases_lost')} "
                 f"leases lost, {events.get('watchdog_holds')} watchdog holds "
                 f"({events.get('watchdog_trips')} trips), {events.get('sequence_gaps')} missed")
    return lines


def previous_row(latest: Path, name: str) -> dict | None:
    """Row `name` of an existing latest.json, if it holds one with its own `run` (the network
    and video groups' rows, which may come from another run than the rest)."""
    try:
        row = json.loads(latest.read_text()).get(name)
    except (OSError, ValueError):
        return None
    return row if isinstance(row, dict) and "run" in row else None


def merge_row(latest: Path, name: str, row: dict) -> bool:
    """Put `row` into an existing latest.json as row `name`, leaving the rest (another run's
    scenarios and metadata) as it was. False if there is no such file."""
    try:
        document = json.loads(latest.read_text())
    except (OSError, ValueError):
        return False
    document[name] = row
    latest.write_text(json.dumps(document, indent=2, default=str))
    return True


def write_json(path: Path, results: dict[str, dict], ratios: dict, info: dict) -> None:
    document = {"time": time.strftime("%Y-%m-%dT%H:%M:%S%z"), **info, **results,
                "ratios": ratios}
    path.write_text(json.dumps(document, indent=2, default=str))
