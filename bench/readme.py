"""python -m bench.readme: README.md's Performance table, generated from bench/results/latest.json.

Rewrites what lies between the markers BEGIN and END in README.md (`make bench` runs it after
the bench), so the table always shows one run as it was measured: each scenario with its
figures, its goal and PASS/FAIL (as the run judged it, goals.py), the baselines of the same
name from the same run, and the machine. Nothing outside the markers is touched.
"""

from __future__ import annotations

import argparse
import fnmatch
import json
from pathlib import Path

from bench import goals, report
from bench.stats import ratio

REPO = Path(__file__).resolve().parent.parent
RESULTS = REPO / "bench" / "results" / "latest.json"
README = REPO / "README.md"
BEGIN = "<!-- bench:table:begin -->"
END = "<!-- bench:table:end -->"

# What each scenario measures, for a reader of the README (first match wins, as in goals.py).
WHAT = (
    ("command_*", "ProxyRobot unary call → target at the servo, lockstep"),
    ("teleop_1000_lockstep", "diagnostic: `teleop_1000` sent lockstep (wait for each ack)"),
    ("teleop_*", "Teleoperate command → applied, streamed at the rate (pipelined)"),
    ("force_*", "wrench sampled → at the operator"),
    ("observers_*", "the operator's 1 kHz stream with n observers at 100 Hz"),
    ("estop_idle", "EmergencyStop on the band → hold latched at the servo"),
    ("estop_under_load", "same, 200 low-lane calls in flight on ProxyRobot"),
    ("estop_under_load_proxy", "same load, the stop sent to ProxyRobot itself"),
    ("estop_ds_idle", "EmergencyStop through the DecisionServer"),
    ("estop_ds_busywork", "same, 200 BusyWork on its low lane"),
    ("closed_loop", "operator command → contact → force change at the operator"),
    ("stereo_*", "stereo pair captured → decoded, 640×480 JPEG"),
    ("world_loop", "the world's 1 kHz loop over the whole run"),
)
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
    """The baselines' figures (a TLS variant's: its plaintext twin's, and its p99 over it)."""
    parts = []
    for label, other in report.compared_with(name):
        base = results.get(other)
        if base and base.get("p50_ms") is not None:
            rate = (f"{base['delivered_hz']:.0f} Hz, " if base.get("rate_hz")
                    and base.get("delivered_hz") is not None else "")
            text = f"{label} {rate}{_ms(base['p50_ms'])} / {_ms(base['p99_ms'])}"
            if label == report.PLAINTEXT:
                p99_ratio = ratio(results[name].get("p99_ms"), base["p99_ms"])
                text += f" (p99 ×{p99_ratio:.2f})" if p99_ratio is not None else ""
            parts.append(text)
    return "; ".join(parts) or "–"


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
        "`_tls` row the plaintext scenario it repeats (delivered, p50 / p99).",
        "",
        "| scenario | what | delivered | p50 | p99 | goal | result | baselines |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for name, result in results.items():
        if goals.is_baseline(name):
            continue
        goal, verdict = _verdict(name, result, results)
        if result.get("status") in ("pending", "failed"):
            verdict += f" ({result['status']})"
        goal = goal.replace(">=", "≥").replace("<=", "≤")
        lines.append(f"| `{name}` | {_what(name, result)} | {_delivered(name, result)} | "
                     f"{_ms(result.get('p50_ms'))} | {_ms(result.get('p99_ms'))} | {goal} | "
                     f"{verdict} | {_baselines(name, results)} |")
    return "\n".join(lines)


def rewrite(text: str, block: str) -> str:
    """`text` with what lies between the markers replaced by `block`. ValueError if the
    markers are missing or out of order."""
    start, end = text.find(BEGIN), text.find(END)
    if start < 0 or end < start:
        raise ValueError(f"README needs {BEGIN} ... {END} around the generated table")
    return f"{text[:start + len(BEGIN)]}\n{block}\n{text[end:]}"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m bench.readme",
                                     description=__doc__.split("\n\n")[0])
    parser.add_argument("--results", default=str(RESULTS), help="the bench's latest.json")
    parser.add_argument("--readme", default=str(README), help="the file to rewrite")
    args = parser.parse_args(argv)
    document = json.loads(Path(args.results).read_text())
    readme = Path(args.readme)
    readme.write_text(rewrite(readme.read_text(), table(document)))
    print(f"rewrote the Performance table in {readme} from {args.results}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
