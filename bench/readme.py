"""python -m bench.readme: the Performance page's tables, generated from bench/results/latest.json.

Rewrites what lies between the markers BEGIN and END in docs/performance.md (`make bench` runs it
after the bench), so the table always shows one run as it was measured: each scenario with its
figures, its goal and PASS/FAIL (as the run judged it, goals.py), the baselines of the same
name from the same run, and the machine. Nothing outside the markers is touched.

The soak has a block of its own, between SOAK_BEGIN and SOAK_END: written when the results
hold a `soak` row. The table is written when they hold other scenarios than the soak, the
network experiment and the world loop, so a soak's results (`--only soak`) leave the table as it
was, and a `make bench` leaves the soak's block.

The network experiment (bench/network.py) has one too, between NETWORK_BEGIN and NETWORK_END,
with its plot (peak force against the round trip) drawn again from the same rows into docs/
(--network-plot), so the page's figure is the table's run.

The video rows (bench/video.py) are a Markdown page of their own, docs/bench_video.md
(--video-table), with its figure docs/bench_video.png (--video-plot). Results that hold nothing
else leave the Performance page as it was.
"""

from __future__ import annotations

import argparse
import fnmatch
import json
from pathlib import Path

from bench import goals, network, report, video
from bench.stats import ratio

REPO = Path(__file__).resolve().parent.parent
RESULTS = REPO / "bench" / "results" / "latest.json"
PAGE = REPO / "docs" / "performance.md"
BEGIN = "<!-- bench:table:begin -->"
END = "<!-- bench:table:end -->"
SOAK_BEGIN = "<!-- bench:soak:begin -->"
SOAK_END = "<!-- bench:soak:end -->"
SOAK = "soak"
NETWORK_BEGIN = "<!-- bench:network:begin -->"
NETWORK_END = "<!-- bench:network:end -->"
NETWORK_PLOT = REPO / "docs" / "bench_network.png"
VIDEO_TABLE = REPO / "docs" / "bench_video.md"
VIDEO_PLOT = REPO / "docs" / "bench_video.png"
# Rows with a block or a file of their own, not rows of the Performance table.
_OWN_BLOCKS = (SOAK, network.NAME, video.NAME)

# What each scenario measures, for a reader of the page (first match wins, as in goals.py).
WHAT = (
    ("command_*", "ProxyRobot unary call → target at the servo, lockstep"),
    ("teleop_1000_lockstep", "diagnostic: `teleop_1000` sent lockstep (wait for each ack)"),
    ("teleop_1000_mcap", "`teleop_1000` with the DecisionServer recording it as MCAP "
                         "(StartRecording); pairs off / on interleaved"),
    ("teleop_1000_episode", "`teleop_1000` with the DecisionServer recording it as a "
                            "demonstration episode (MCAP with the test card's stereo video); "
                            "pairs off / on interleaved"),
    ("teleop_1000_aa", "diagnostic: `teleop_1000` in pairs of identical legs, nothing "
                       "recorded: the noise the `_mcap`, `_episode` and `_tls` ratios are "
                       "judged in"),
    ("force_1000_mcap", "`force_1000` with the subscriber writing each sample to MCAP (wrench "
                        "and Foxglove arrow, as `make teleop --mcap`); pairs off / on "
                        "interleaved"),
    ("teleop_*", "Teleoperate command → applied, streamed at the rate (pipelined)"),
    ("force_*", "wrench sampled → at the operator"),
    ("observers_zenoh_*", "the operator's 1 kHz stream with n Zenoh subscribers to every wrench "
                          "sample behind a router (the station publishes once)"),
    ("observers_*", "the operator's 1 kHz stream with n observers at 100 Hz"),
    ("estop_idle", "EmergencyStop on the band → hold latched at the servo"),
    ("estop_under_load", "same, 200 low-lane calls in flight on ProxyRobot"),
    ("estop_under_load_proxy", "same load, the stop sent to ProxyRobot itself"),
    ("estop_ds_idle", "EmergencyStop through the DecisionServer"),
    ("estop_ds_busywork", "same, 200 BusyWork on its low lane"),
    ("closed_loop", "operator command → contact → force change at the operator"),
    ("franka_command_1000", "FR3 joint target → applied in franka-sim through libfranka, "
                            "1 kHz (and libfranka's control success rate)"),
    ("franka_command_1000_mirrored", "the same, the driver also publishing its mirror of the "
                                     "arm every cycle, as in the station"),
    ("stereo_*", "stereo pair captured → decoded, 640×480 JPEG"),
    ("world_loop", "the world's 1 kHz loop over the whole run"),
    ("soak_overload", "Teleoperate at 500 Hz (Python client, pipelined) beside a busy "
                      "co-tenant process per core: sent → applied; received → applied and "
                      "each third of the run in bench/results/latest.json"),
)
# The ratios a variant's row shows over its twin (label, result key): the TLS goal's p99; the
# recording goal's p50 or the DecisionServer's CPU per command, and the p99 beside them.
_TWIN_RATIOS = {report.PLAINTEXT: (("p99", "p99_ms"),),
                report.RECORDING_OFF: (("p50", "p50_ms"), ("p99", "p99_ms"),
                                       ("CPU/command", goals.CPU_KEY))}
_METADATA = ("time", "machine", "quick", "run_s", "world_shm", "ratios")


def scenarios(document: dict) -> dict[str, dict]:
    """The scenarios of a latest.json, in the order they ran."""
    return {name: value for name, value in document.items()
            if name not in _METADATA and isinstance(value, dict)}


def _what(name: str, result: dict) -> str:
    twin = report.plaintext_twin(name)
    if twin is not None:
        return f"`{twin}` with mutual TLS (client certificates, role checks, audit log)"
    if name.startswith("teleop_") and "mode" not in result and "lockstep" not in name:
        return "Teleoperate command → applied, lockstep (a run from before pipelining)"
    return next((text for pattern, text in WHAT if fnmatch.fnmatchcase(name, pattern)), "")


def _ms(value) -> str:
    if value is None:
        return "–"
    return f"{value:.2f}" if value < 10 else f"{value:.0f}" if value >= 100 else f"{value:.1f}"


def _pct(value) -> str:
    return "?" if value is None else f"{value:.2f}"


def _delivered(name: str, result: dict) -> str:
    if name == "world_loop":
        return (f"{result.get('overruns')} overruns in {result.get('steps')} steps "
                f"({_pct(result.get('overrun_pct'))} %)")
    if result.get("rate_hz") is None or result.get("delivered_hz") is None:
        return "–"  # trials, not a stream
    if name.startswith("stereo_"):
        return f"{result['delivered_hz']:.1f} fps"
    return f"{result['delivered_hz']:.0f} Hz"


def _verdict(name: str, result: dict, results: dict[str, dict]) -> tuple[str, str]:
    """(goal text, PASS / FAIL (why) / no goal), as the run stored them."""
    judged = ({"goal": result["goal"], "pass": result.get("pass"),
               "misses": result.get("goal_misses", [])} if "goal" in result
              else goals.judge(name, results))
    verdict = goals.verdict_text(judged)
    if verdict == goals.NO_GOAL:
        return "–", "no goal"
    if verdict == goals.FAIL and judged["misses"]:
        return judged["goal"], f"**FAIL**: {'; '.join(judged['misses'])}"
    return judged["goal"], f"**{verdict}**"


def _baselines(name: str, results: dict[str, dict]) -> str:
    """The baselines' figures (a TLS variant's: its plaintext twin's, and its p99 over it;
    a recording-on variant's: its twin's, and its p50, p99 and CPU per command over them, then
    the medians of its interleaved pairs' ratios and the ratios)."""
    parts = []
    for label, other in report.compared_with(name):
        base = results.get(other)
        if base and base.get("p50_ms") is not None:
            rate = (f"{base['delivered_hz']:.0f} Hz, " if base.get("rate_hz")
                    and base.get("delivered_hz") is not None else "")
            text = (f"{label.replace('_', ' ')} {rate}{_ms(base['p50_ms'])} / "
                    f"{_ms(base['p99_ms'])}")
            ratios = [(text, ratio(results[name].get(key), base.get(key)))
                      for text, key in _TWIN_RATIOS.get(label, ())]
            shown = [f"{key} ×{value:.2f}" for key, value in ratios if value is not None]
            text += f" ({', '.join(shown)})" if shown else ""
            if results[name].get("overhead_median"):
                text += (f"; medians of {len(results[name].get('overhead_pairs') or [])} "
                         f"interleaved pairs: {_overhead(results[name])}")
                if by_thread := report.thread_cpu_text(results[name]):
                    text += f"; the server's CPU by thread, on − off: {by_thread}"
            parts.append(text)
    if results[name].get("cpu"):
        parts.append(_cpu_text(results[name]["cpu"]))
    return "; ".join(parts) or "–"


def _cpu_text(cpu: dict) -> str:
    """"while measured: both cores 95 % busy; force_sensor 60 %, ... of a core" (bench/cpu.py),
    the observer processes summed."""
    shares: dict[str, float] = {}
    for name, pct in cpu.get("cpu_pct", {}).items():
        key = ("observers" if name.startswith("observers")
               else "subscribers" if name.startswith("subscribers") else name)
        shares[key] = shares.get(key, 0.0) + pct
    each = ", ".join(f"{name.replace('_', ' ')} {pct:.0f} %"
                     for name, pct in sorted(shares.items(), key=lambda item: -item[1]))
    return (f"while measured: the machine {cpu['machine_busy_pct']:.0f} % busy"
            + (f"; {each} of a core" if each else ""))


# An interleaved row's medians (report.interleaved) as the page shows them, in this order.
_OVERHEAD_LABELS = {"delivered": "delivered", "p50": "p50", "p99": "p99",
                    "server_cpu": "CPU/command", "subscriber_cpu": "subscriber CPU/sample"}


def _overhead(result: dict) -> str:
    """"CPU/command ×1.04 (×1.02 ×1.04 ×1.10), ...": an interleaved row's medians of the
    pairs' ratios (on / off) and the ratios, those it judges or reports."""
    medians, ratios = result["overhead_median"], result.get("overhead_ratios") or {}
    parts = []
    for key, label in _OVERHEAD_LABELS.items():
        if medians.get(key) is not None:
            each = " ".join("–" if v is None else f"×{v:.2f}" for v in ratios.get(key, []))
            parts.append(f"{label} ×{medians[key]:.2f} ({each})")
    return ", ".join(parts)


def table(document: dict) -> str:
    """The Markdown block: where the figures come from, then one row per project scenario
    (baselines appear beside the scenario they are the baseline of)."""
    results = scenarios(document)
    machine = document.get("machine", {})
    load = machine.get("load_avg_at_start"), machine.get("load_avg_at_end")
    loads = " → ".join(f"{values[0]:.1f}" for values in load if values)
    lines = [
        f"Generated by `python -m bench.readme` from `bench/results/latest.json`: a "
        f"{'quick' if document.get('quick') else 'full'} run of {document.get('run_s')} s "
        f"at {document.get('time')}, on {machine.get('cores')} cores ({machine.get('cpu_model')},"
        f" Python {machine.get('python')}, load average {loads or '?'}). Latency in ms; "
        "baselines: the same domain code over pyzmq and plain TCP in the same run, and for a "
        "`_tls` or `_mcap` row the scenario it repeats, without TLS or recording (delivered, "
        "p50 / p99).",
        "",
        "| scenario | what | delivered | p50 | p99 | goal | result | baselines |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for name, result in results.items():
        if goals.is_baseline(name) or name in _OWN_BLOCKS:  # blocks of their own
            continue
        goal, verdict = _verdict(name, result, results)
        if result.get("status") in ("pending", "failed"):
            verdict += f" ({result['status']})"
        goal = goal.replace(">=", "≥").replace("<=", "≤")
        lines.append(f"| `{name}` | {_what(name, result)} | {_delivered(name, result)} | "
                     f"{_ms(result.get('p50_ms'))} | {_ms(result.get('p99_ms'))} | {goal} | "
                     f"{verdict} | {_baselines(name, results)} |")
    return "\n".join(lines)


def has_table(document: dict) -> bool:
    """Whether the results hold scenarios for the table (more than a soak, the network
    experiment or the video rows, and its run's world loop)."""
    return any(name not in (*_OWN_BLOCKS, "world_loop") for name in scenarios(document))


def has_soak(document: dict) -> bool:
    return SOAK in scenarios(document)


def has_network(document: dict) -> bool:
    return "rows" in scenarios(document).get(network.NAME, {})


def has_video(document: dict) -> bool:
    return "cells" in scenarios(document).get(video.NAME, {})


# -- the soak's block ---------------------------------------------------------------------------

def _num(value, digits: int = 1, sign: bool = False) -> str:
    if value is None:
        return "–"
    value = round(value, digits) + 0.0  # no "-0.00"
    return f"{value:+.{digits}f}" if sign else f"{value:.{digits}f}"


def _span(entry: dict | None) -> str:
    return "–" if not entry else f"{entry['start']} → {entry['end']}"


def _events_text(events: dict) -> str:
    if events.get("status") in ("failed", "pending"):
        return f"not followed ({events['status']}: {events.get('reason', '')[:120]})"
    control = "; ".join(f"{c['reason']} at {c['t_s']:.1f} s" for c in events.get("control", []))
    holds = "; ".join(f"{w['reason']} at {w['t_s']:.1f} s" for w in events.get("watchdog", []))
    changes = "; ".join(f"{d['name']} {d['from']} → {d['to']} at {d['t_s']:.1f} s"
                        for d in events.get("dependencies", []))
    kinds = ", ".join(f"{kind} {count}" for kind, count in
                      {**events.get("kinds", {}), **events.get("robot_kinds", {})}.items()
                      if kind != "robot")
    return (f"{events.get('events')} events ({kinds}), {events.get('sequence_gaps')} missed. "
            f"Control changes: {events.get('control_changes')}"
            f"{f' ({control})' if control else ''}; leases lost: {events.get('leases_lost')}; "
            f"watchdog holds: {events.get('watchdog_holds')}{f' ({holds})' if holds else ''}, "
            f"of which watchdog trips: {events.get('watchdog_trips')}; dependency changes: "
            f"{events.get('dependency_changes')}{f' ({changes})' if changes else ''}.")


def _sensor_rate(observers: dict) -> str:
    """An observer gets every Nth sample the sensor takes (N = 1000 Hz / its rate): so, with
    none missing, its rate x N is the rate the sensor sampled at."""
    rate, mean = observers.get("observer_rate_hz"), observers.get("observer_delivered_hz_mean")
    if not rate or mean is None:
        return ""
    every = round(1000.0 / rate)
    return (f"; each gets every {every}th sample the sensor takes, so it sampled at about "
            f"{mean * every:.0f} Hz (of 1000)")


def soak_block(document: dict, source: str = "bench/results/latest.json") -> str:
    """The soak's Markdown block: the run, its verdict, each process's memory, the streams,
    the world loop and the DecisionServer's events."""
    results = scenarios(document)
    soak = results[SOAK]
    machine = document.get("machine", {})
    load = machine.get("load_avg_at_start"), machine.get("load_avg_at_end")
    loads = " → ".join(f"{values[0]:.1f}" for values in load if values)
    goal, verdict = _verdict(SOAK, soak, results)
    goal = goal.replace("<=", "≤")
    lines = [
        f"Generated by `python -m bench.readme` from `{source}`: a soak of "
        f"{soak.get('minutes', 0):g} min (`python -m bench --only soak`) at "
        f"{document.get('time')}, on {machine.get('cores')} cores ({machine.get('cpu_model')}, "
        f"Python {machine.get('python')}, load average {loads or '?'}).",
    ]
    if soak.get("status") in ("pending", "failed"):
        lines += ["", f"**Result: FAIL** ({soak['status']}: {soak.get('reason', '')[:300]})"]
        return "\n".join(lines)
    teleop, observers = soak.get("teleop") or {}, soak.get("observers") or {}
    camera, events = soak.get("stereo") or {}, soak.get("events") or {}
    lines[0] += (f" All at once: Teleoperate at {_num(soak.get('rate_hz'), 0)} Hz pipelined "
                 f"(session watchdog {soak.get('watchdog_s'):g} s), "
                 f"{observers.get('observers', '?')} wrench observers at "
                 f"{_num(observers.get('observer_rate_hz'), 0)} Hz, a stereo client "
                 f"({camera.get('source') or '?'}, {camera.get('mode', '?')} buffer, "
                 f"{camera.get('width_px')}×{camera.get('height_px')} JPEG decoded). RSS read "
                 f"every {soak.get('sample_s'):g} s; slopes are least squares after the first "
                 f"{100 * soak.get('warmup_fraction', 0):.0f} % of the run.")
    lines += ["", f"**Result: {verdict.replace('**', '')}** (goal: {goal})", "",
              "| process | RSS first → last (MiB) | slope (MiB/min) | over its 2nd half | "
              "anon. first → last (MiB) | CPU % of a core | threads | fds |",
              "|---|---|---|---|---|---|---|---|"]
    for name, entry in (soak.get("rss") or {}).items():
        anon = entry.get("anon") or {}
        lines.append(
            f"| `{name}`{' (exited)' if entry.get('exited') else ''} | "
            f"{_num(entry.get('start_mib'))} → {_num(entry.get('end_mib'))} | "
            f"{_num(entry.get('slope_mib_min'), 2, True)} | "
            f"{_num(entry.get('late_slope_mib_min'), 2, True)} | "
            f"{_num(anon.get('start_mib'))} → {_num(anon.get('end_mib'))} | "
            f"{_num(entry.get('cpu_pct'), 0)} | {_span(entry.get('threads'))} | "
            f"{_span(entry.get('fds'))} |")
    lines += ["", "| stream | offered | delivered | lost | p50 / p99 ms | notes |",
              "|---|---|---|---|---|---|"]
    unacked, gaps = teleop.get("unacked"), teleop.get("ack_gaps")
    queued = unacked - gaps if unacked is not None and gaps is not None else None
    refusals = sorted(set(teleop.get("failures") or []))
    lines.append(
        f"| Teleoperate (the operator) | {_num(teleop.get('rate_hz'), 0)} Hz | "
        f"{_num(teleop.get('delivered_hz'), 1)} Hz | {unacked} unacked "
        f"{teleop.get('drain_s', 15):g} s after the last send ({gaps} skipped, {queued} still "
        f"queued), {teleop.get('refused')} refused"
        f"{' (' + '; '.join(r[:120] for r in refusals[:2]) + ')' if refusals else ''}, "
        f"{teleop.get('unsent', 0)} unsent | "
        f"{_ms(teleop.get('p50_ms'))} / {_ms(teleop.get('p99_ms'))} (sent → applied) | "
        f"{teleop.get('sent')} sent; {teleop.get('late_skipped')} late ticks skipped by the "
        f"client; ack p50 / p99 {_ms(teleop.get('ack_p50_ms'))} / "
        f"{_ms(teleop.get('ack_p99_ms'))} |")
    lines.append(
        f"| wrench observers ×{observers.get('observers', '?')} | "
        f"{_num(observers.get('observer_rate_hz'), 0)} Hz each | "
        f"{_num(observers.get('observer_delivered_hz_mean'), 1)} Hz each (min "
        f"{_num(observers.get('observer_delivered_hz_min'), 1)}) | "
        f"{observers.get('observer_sequence_gaps')} samples missing "
        f"({observers.get('observer_server_dropped')} dropped by the sensor for them) | – | "
        f"{observers.get('observer_samples')} samples{_sensor_rate(observers)} |")
    lines.append(
        f"| stereo | {_num(camera.get('rate_hz'), 0)} fps | "
        f"{_num(camera.get('delivered_hz'), 1)} fps | pairs skipped: {camera.get('dropped')} | "
        f"{_ms(camera.get('p50_ms'))} / {_ms(camera.get('p99_ms'))} (captured → decoded) | "
        f"{camera.get('pairs')} pairs in {camera.get('streams')} stream(s) one after another"
        f"{'; ' + str(camera.get('errors')) + ' failed' if camera.get('errors') else ''}"
        f"{' ' + camera.get('reason', '')[:120] if camera.get('status') else ''} |")
    windows = teleop.get("windows") or []
    if len(windows) > 1:
        width = windows[1]["t_s"] - windows[0]["t_s"]
        lines += ["", "Teleoperate, sent → applied by when the command was sent (p50 / p99 ms): "
                  + "; ".join(f"{w['t_s'] / 60:.4g}–{(w['t_s'] + width) / 60:.4g} min "
                              f"{_ms(w['p50_ms'])} / {_ms(w['p99_ms'])}" for w in windows) + "."]
    loop = soak.get("world_loop") or {}
    lines += ["", f"World loop during the stream: {loop.get('overruns')} overruns in "
                  f"{loop.get('steps')} steps ({_pct(loop.get('overrun_pct'))} %), "
                  f"{loop.get('dropped_steps')} dropped steps. DecisionServer events: "
                  f"{_events_text(events)}"]
    if soak.get("exited"):
        lines.append(f"Station processes that exited: {', '.join(soak['exited'])}.")
    return "\n".join(lines)


# -- the network experiment's block ---------------------------------------------------------

def network_block(document: dict, source: str = "bench/results/latest.json",
                  figure: str = "docs/bench_network.png") -> str:
    """The network experiment's Markdown block: its run, how the link was set, a row per run
    of the task, the figure, and the comparison with the papers' campus routes."""
    row = scenarios(document)[network.NAME]
    run = row.get("run") or document
    machine = run.get("machine", {})
    load = machine.get("load_avg_at_start"), machine.get("load_avg_at_end")
    loads = " → ".join(f"{values[0]:.1f}" for values in load if values)
    cut = row.get("cut") or {}
    lines = [
        f"Generated by `python -m bench.readme` from `{source}`: the network group "
        f"(`make bench ONLY=network`), a {'quick' if run.get('quick') else 'full'} run of "
        f"{row.get('elapsed_s')} s ({row.get('succeeded')} of {row.get('runs')} runs "
        f"succeeded) at {run.get('time')}, on {machine.get('cores')} cores "
        f"({machine.get('cpu_model')}, Python {machine.get('python')}, load average "
        f"{loads or '?'}). The peg-in-hole task of `make teleop` (`clients/teleop/task.py`) "
        "with `services/impairment`'s link between the operator's client and the "
        "DecisionServer only: half the round trip each way, each chunk's delay drawn within "
        f"±{100 * row.get('jitter_fraction', 0):g} % of it, a seed per row. A cut: "
        f"{cut.get('s', 0):g} s, {cut.get('at_s', 0):g} s into the task, `{cut.get('mode')}` "
        "(no byte moves; TCP resends once it is back). Measured round trip: a command sent → "
        "its ack back at the client, the station's own time included.",
        "",
        "| " + " | ".join(network.HEADER) + " |",
        "|" + "---|" * len(network.HEADER),
    ]
    for cells in network.table_rows(row):
        *figures, note = cells
        lines.append("| " + " | ".join([*figures, note.replace("|", "\\|")[:300]]) + " |")
    lines += ["", f"![Peak force against the link's round trip, per mode]({figure})", "",
              f"The papers: {row.get('papers', network.PAPERS)}", "",
              network.campus_comparison(row), "",
              f"Passivity (#15), the feedback runs with TDPA against its goals: the peak within "
              f"{network.PEAK_VS_LOOPBACK:g}× the TDPA run's on loopback, no sustained "
              f"oscillation at contact, the task done, the drift at the end under "
              f"{network.MAX_DRIFT_M * 1e3:g} mm:", "",
              *[f"- {line}" for line in network.passivity_verdict(row)]]
    return "\n".join(lines)


def rewrite(text: str, block: str, begin: str = BEGIN, end: str = END) -> str:
    """`text` with what lies between the markers `begin` and `end` replaced by `block`.
    ValueError if the markers are missing or out of order."""
    start, stop = text.find(begin), text.find(end)
    if start < 0 or stop < start:
        raise ValueError(f"the page needs {begin} ... {end} around the generated block")
    return f"{text[:start + len(begin)]}\n{block}\n{text[stop:]}"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m bench.readme",
                                     description=__doc__.split("\n\n")[0])
    parser.add_argument("--results", default=str(RESULTS), help="the bench's latest.json")
    parser.add_argument("--page", "--readme", dest="page", default=str(PAGE),
                        help="the Markdown page to rewrite between its markers")
    parser.add_argument("--network-plot", default=str(NETWORK_PLOT),
                        help="where the network block's figure is drawn (the page links to it)")
    parser.add_argument("--video-table", default=str(VIDEO_TABLE),
                        help="where the video rows' Markdown page is written")
    parser.add_argument("--video-plot", default=str(VIDEO_PLOT),
                        help="where the video rows' figure is drawn")
    args = parser.parse_args(argv)
    document = json.loads(Path(args.results).read_text())
    if has_video(document):
        row = scenarios(document)[video.NAME]
        table_path = Path(args.video_table)
        table_path.parent.mkdir(parents=True, exist_ok=True)
        table_path.write_text(video.markdown(row, _shown(Path(args.results))))
        figure = video.plot(row, Path(args.video_plot))
        print(f"wrote the video rows' table {table_path} and drew {figure} from {args.results}")
    if not (has_table(document) or has_soak(document) or has_network(document)):
        if has_video(document):
            return 0  # the page has no video block: left as it was
        print(f"{args.results} holds no scenario for the Performance page: nothing rewritten")
        return 1
    page = Path(args.page)
    text = page.read_text()
    if has_table(document):
        text = rewrite(text, table(document))
        print(f"rewrote the Performance table in {page} from {args.results}")
    if has_soak(document):
        text = rewrite(text, soak_block(document, _shown(Path(args.results))), SOAK_BEGIN,
                       SOAK_END)
        print(f"rewrote the soak's block in {page} from {args.results}")
    if has_network(document):
        row = scenarios(document)[network.NAME]
        figure = network.plot(row, Path(args.network_plot))
        text = rewrite(text, network_block(document, _shown(Path(args.results)),
                                           _relative(figure, page.parent)),
                       NETWORK_BEGIN, NETWORK_END)
        print(f"rewrote the network block in {page} and drew {figure} from {args.results}")
    page.write_text(text)
    return 0


def _relative(path: Path, base: Path) -> str:
    """`path` as a link from a file in `base` (as given when it is not under it)."""
    path, base = path.resolve(), base.resolve()
    return str(path.relative_to(base)) if path.is_relative_to(base) else str(path)


def _shown(path: Path) -> str:
    """A results path as the page shows it: from the repository's root when it is inside."""
    path = path.resolve()
    return str(path.relative_to(REPO)) if path.is_relative_to(REPO) else str(path)


if __name__ == "__main__":
    raise SystemExit(main())
