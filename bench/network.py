"""network: the papers' experiment across a delayed link (issues #14 and #15).

The peg-in-hole task of `make teleop` (clients/teleop/task.py, imported, not copied) in both
modes, feedback and compliance, with services/impairment's link between the operator's client
and the DecisionServer only (the operator's path: the station's own calls stay on loopback).
Feedback runs twice at each round trip: with TDPA (#15, make teleop's default) and without it
(`--no-passivity`), next to each other, so both see the same machine; `passivity_verdict`
judges the TDPA runs against #15's goals:

- round trips of 0, 100, 200 and 400 ms (ROUND_TRIPS_MS), half each way, jitter ±10 % of
  the one-way delay, and the papers' campus routes' 183 ms (CAMPUS_RTT_MS);
- on the campus link again, with a cut of CUT_S in the middle of the task (CUT_AT_S after it
  starts). Until the client resumes sessions by itself, such a row may end with an error: it is
  reported as failed with the error's text. The row needs no change once it resumes.

Every row has a seed of its own (a hash of its name), so a row's delays repeat from run to run.
Each run is a worker process of its own (`python -m bench.worker network`): it acquires control,
connects, initializes, starts and tares the sensor at home as `make teleop` does, runs the task,
and releases control. The link runs in the orchestrator, which does little else meanwhile.

One result row, `network`, holds a row per run (`rows`) and the run it came from (`run`), so a
run of this group alone merges it into an existing latest.json instead of replacing the whole
run there (`report.merge_row`), and a run without it keeps the one there
(`report.previous_row`).
`plot` draws the peak force against the round trip, a line per mode.
"""

from __future__ import annotations

import dataclasses
import time
import zlib
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from services.impairment import LinkProfile

NAME = "network"
MODES = ("feedback", "compliance")
ROUND_TRIPS_MS = (0.0, 100.0, 200.0, 400.0)
QUICK_ROUND_TRIPS_MS = (0.0,)  # and the campus routes, as always
CAMPUS_RTT_MS = 183.0  # MTDF paper, section V: "overall round-trip delay is 183 ms"
JITTER_FRACTION = 0.10  # of the one-way delay
CUT_S = 3.0
CUT_AT_S = 5.0  # after the task starts: mid-approach in both modes (they last 12-20 s)
# A stall is what a lost route does: nothing moves, TCP resends once it is back; the
# keepalives (a ping a second, a second to answer) notice it before the link returns.
CUT_MODE = "stall"
OPERATOR = "bench-network"
LEASE_S = 30.0  # as make teleop's: outlives the cut
CALL_TIMEOUT_S = 10.0
ROW_TIMEOUT_S = 240.0  # a whole run at 400 ms, with its set-up, takes about a minute
PLOT_FILE = "network_peak_force.png"
# #15's goals for the feedback runs with TDPA, at every round trip.
PEAK_VS_LOOPBACK = 1.5  # peak force within this many times the TDPA run's on loopback
# The peak at first contact varies a lot from run to run (130 to 240 N on loopback here): it is
# the motion in flight when the contact begins (the servo's interpolation, a command or two)
# times the contact's stiffness, and when the contact comes within a command period is chance.
# So each feedback run with TDPA is made TDPA_REPEATS times, and judged on the median. Three
# were too few: the 15 runs of one go spread 116-227 N alike at every delay, and a median of
# three on loopback (145.5 N) left one delay's median of three (221 N) just past 1.5 x.
TDPA_REPEATS = 5
MAX_DRIFT_M = 0.005  # master–slave position drift at the end
# (and no sustained oscillation: clients.teleop.task.SUSTAINED_SWINGS swings or more)
PAPERS = ("MTDF paper, section V: three campus routes streaming video, force and commands at "
          "once; commands at 50 Hz, force at 120 Hz, stereo at 17 fps; force and stereo "
          "delays 8 and 83 ms; overall round trip 183 ms (5.5 Hz) with the slave arm operated "
          "at 10 Hz. Of the peg-in-hole task it says that active compliance at the server is "
          "more effective than the operator's reaction through force feedback, with no forces.")


@dataclass(frozen=True)
class RowSpec:
    """One run of the task: a mode, a link, maybe a cut."""

    mode: str
    round_trip_ms: float
    cut_s: float = 0.0
    passivity: bool = True  # TDPA in feedback mode (compliance has no force feedback)

    @property
    def repeats(self) -> int:
        """Runs of the task this row is made of (see TDPA_REPEATS)."""
        return TDPA_REPEATS if self.mode == "feedback" and self.passivity and not self.cut_s \
            else 1

    @property
    def name(self) -> str:
        off = "_nopassivity" if self.mode == "feedback" and not self.passivity else ""
        return f"{self.mode}{off}_{self.round_trip_ms:g}ms" + ("_cut" if self.cut_s else "")

    @property
    def seed(self) -> int:
        """The row's own, the same in every run (crc32: Python's hash() is salted)."""
        return zlib.crc32(self.name.encode())


def row_specs(quick: bool) -> list[RowSpec]:
    """The runs in order: each round trip in both modes, feedback with and without TDPA (next
    to each other, so all see the same machine), the campus routes' among them, then the cuts
    on the campus link."""
    trips = sorted({*(QUICK_ROUND_TRIPS_MS if quick else ROUND_TRIPS_MS), CAMPUS_RTT_MS})
    specs = [spec for trip in trips
             for spec in (RowSpec("feedback", trip), RowSpec("feedback", trip, passivity=False),
                          RowSpec("compliance", trip))]
    specs += [RowSpec(mode, CAMPUS_RTT_MS, CUT_S) for mode in MODES]
    return specs


def label(row: dict) -> str:
    """A row's mode for people: feedback with TDPA or without it, or compliance."""
    if row["mode"] != "feedback":
        return row["mode"]  # (its run reports passivity false: it has no force feedback)
    return "feedback, TDPA" if row.get("passivity", True) else "feedback, no passivity"


def link_profiles(round_trip_ms: float, seed: int) -> tuple[LinkProfile, LinkProfile]:
    """(up, down): half the round trip each way, jitter JITTER_FRACTION of that; down draws
    from seed + 1, as the impairment CLI does."""
    one_way_s = round_trip_ms / 2e3
    return tuple(LinkProfile(delay_s=one_way_s, jitter_s=JITTER_FRACTION * one_way_s,
                             seed=seed + offset) for offset in (0, 1))


def home_position() -> list[float]:
    """The tool's position at the world's home configuration, straight above the hole: where
    the task starts (make teleop starts where the arm is, which is home on a fresh station)."""
    from domain.robot_model.kinematics import ArmKinematics

    kinematics = ArmKinematics()
    return [float(v) for v in kinematics.tool_pose(kinematics.home_q).translation]


# -- a row from its runs (bench/groups/network.py makes the runs) -------------------------------

def median_run(runs: list[dict]) -> dict:
    """The run with the median peak force of `runs` (all of it, so its figures belong
    together), marked failed if any run failed, with every run's peak in `peaks_n`. One run
    is itself."""
    if len(runs) == 1:
        return runs[0]
    peaked = sorted((r for r in runs if r.get("peak_force_n") is not None),
                    key=lambda r: r["peak_force_n"])
    middle = dict(peaked[(len(peaked) - 1) // 2] if peaked else runs[0])
    middle["peaks_n"] = [r.get("peak_force_n") for r in runs]
    failed = [r for r in runs if not r.get("success")]
    if failed:
        middle["success"] = False
        middle["error"] = middle.get("error") or failed[0].get("error") or \
            f"{len(failed)} of {len(runs)} runs failed"
    return middle


def row_text(row: dict) -> str:
    """A row's figures on one line (the progress line)."""
    parts = ["success" if row["success"] else "FAILED"]
    for key, unit, digits in (("duration_s", "s", 1), ("peak_force_n", "N peak", 1),
                              ("final_force_n", "N final", 1)):
        if row.get(key) is not None:
            parts.append(f"{row[key]:.{digits}f} {unit}")
    if row.get("round_trip_p50_ms") is not None:
        parts.append(f"round trip p50 {row['round_trip_p50_ms']:.1f} / p99 "
                     f"{row['round_trip_p99_ms']:.1f} ms")
    if row.get("error"):
        parts.append(f"error: {row['error'][:200]}")
    return ", ".join(parts)


# -- the worker's side (python -m bench.worker network) ----------------------------------------

def task(params: dict, ready: Callable[[], None]) -> dict:
    """One run of the task through `params["address"]` (the link): make teleop's set-up, then
    PegInHole. A failure of the run itself (a cut the session did not survive) is the result,
    with the error's text and the figures up to it; a failure before it raises."""
    import numpy as np

    from clients.ar import RobotModel
    from clients.python.decision_server import DecisionClient
    from clients.teleop.__main__ import retract
    from clients.teleop.task import PegInHole, ready_the_arm

    # Released here, not on leaving: a failed release must not lose the run's figures.
    with DecisionClient(params["address"], default_timeout=CALL_TIMEOUT_S,
                        release_on_close=False) as client:
        # A lease left by the run before (killed with it) lapses within LEASE_S: wait for it.
        client.acquire_control(OPERATOR, wait=True, wait_timeout_s=LEASE_S + 5,
                               lease_duration_s=LEASE_S, timeout=LEASE_S + 15)
        try:
            ready_the_arm(client)  # make teleop's set-up
            retract(client, np.asarray(params["home"]))  # out of the hole the run before left
            client.sensor.tare(0.2)
            model = RobotModel(client.robot.get_state().tool_pose)
            peg = PegInHole(client, params["mode"], model,
                            passivity=params.get("passivity", True))
            started = time.monotonic()
            ready()  # the orchestrator times a cut from here
            try:
                return {**dataclasses.asdict(peg.run()), "error": None}
            except Exception as error:  # noqa: BLE001 - the row reports what ended the run
                return _partial(peg, time.monotonic() - started, error)
        finally:
            try:
                client.release_control(timeout=LEASE_S)
            except Exception:  # noqa: BLE001 - it lapses within LEASE_S; the next run waits
                pass


def _partial(peg, duration_s: float, error: Exception) -> dict:
    """A run that ended with an error: what its trace holds up to then."""
    import numpy as np

    forces = [-f[2] for f in peg.trace.force_n]
    trips = peg.trace.round_trip_ms
    return {"mode": peg.mode, "success": False, "duration_s": duration_s, "depth_m": None,
            "peak_force_n": float(max(forces)) if forces else None,
            "final_force_n": float(forces[-1]) if forces else None,
            "round_trip_p50_ms": float(np.percentile(trips, 50)) if trips else None,
            "round_trip_p99_ms": float(np.percentile(trips, 99)) if trips else None,
            "commands": peg._commands, "acks": len(peg._acks),
            "error": f"{type(error).__name__}: {error}"}


# -- the figure --------------------------------------------------------------------------------

def plot(result: dict, path: Path) -> Path:
    """Two panels against the link's round trip: the peak force, a line per mode (feedback with
    TDPA and without, compliance; the cut runs as crosses, the papers' campus routes marked);
    and, for feedback with and without TDPA side by side, the drift at the end and the
    transparency error."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.ticker import FuncFormatter

    figure, (axis, quality) = plt.subplots(1, 2, figsize=(13, 5))
    colors = {"feedback, TDPA": "tab:green", "feedback, no passivity": "tab:red",
              "compliance": "tab:blue"}
    rows = result.get("rows", [])
    for name, color in colors.items():
        line = sorted((r for r in rows if label(r) == name and not r.get("cut_s")
                       and r.get("peak_force_n") is not None), key=lambda r: r["round_trip_ms"])
        done = [r for r in line if r["success"]]  # a failed run's peak compares nothing
        if done:
            axis.plot([r["round_trip_ms"] for r in done], [r["peak_force_n"] for r in done],
                      "-o", color=color, label=name)
        failed = [r for r in line if not r["success"]]
        if failed:
            axis.plot([r["round_trip_ms"] for r in failed],
                      [r["peak_force_n"] for r in failed], "o", mfc="white",
                      color=color, label=f"{name}: task failed")
        cuts = [r for r in rows if label(r) == name and r.get("cut_s")
                and r.get("peak_force_n") is not None]
        if cuts:
            axis.plot([r["round_trip_ms"] for r in cuts], [r["peak_force_n"] for r in cuts],
                      "x", ms=10, mew=2, color=color,
                      label=f"{name}, {cuts[0]['cut_s']:g} s cut"
                            + ("" if all(r["success"] for r in cuts) else " (failed)"))
        if name.startswith("feedback"):
            kept = [r for r in line if r.get("drift_m") is not None]
            trips = [r["round_trip_ms"] for r in kept]
            quality.plot(trips, [r["drift_m"] * 1e3 for r in kept], "-o", color=color,
                         label=f"{name}: drift at the end (mm)")
            quality.plot(trips, [r.get("transparency_rms_n") or 0.0 for r in kept], "--s",
                         color=color, label=f"{name}: transparency error, RMS (N)")
    campus = result.get("campus_rtt_ms", CAMPUS_RTT_MS)
    for panel in (axis, quality):
        panel.axvline(campus, color="grey", linestyle="--", linewidth=1)
        panel.set_xlabel("link round trip set (ms), jitter ±10 % of each way")
        panel.grid(True, which="both", alpha=0.3)
    axis.text(campus, 0.02, f"papers' campus routes, {campus:g} ms ", rotation=90,
              va="bottom", ha="right", fontsize=8, color="grey",
              transform=axis.get_xaxis_transform())
    axis.set_yscale("log")  # feedback's hundreds of newtons and compliance's few on one axis
    axis.yaxis.set_major_formatter(FuncFormatter(lambda value, _: f"{value:g}"))
    axis.set_ylabel("peak contact force (N, log scale)")
    axis.set_title("peg-in-hole across a delayed link: peak force")
    axis.legend(fontsize=8)
    quality.axhline(MAX_DRIFT_M * 1e3, color="grey", linewidth=1)
    quality.set_yscale("symlog", linthresh=1.0)
    quality.set_ylabel("mm (drift) and N (transparency), symmetric log scale")
    quality.set_title("feedback with and without TDPA: drift and transparency")
    quality.legend(fontsize=7)
    figure.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    figure.savefig(path, dpi=100)
    plt.close(figure)
    return path


def passivity_verdict(result: dict) -> list[str]:
    """#15's goals, judged on the feedback runs with TDPA (no cut), a line per round trip,
    then how the same runs without passivity compare."""
    from clients.teleop.task import SUSTAINED_SWINGS

    rows = [r for r in result.get("rows", []) if r["mode"] == "feedback" and not r.get("cut_s")]
    on = {r["round_trip_ms"]: r for r in rows if r.get("passivity", True)}
    off = {r["round_trip_ms"]: r for r in rows if not r.get("passivity", True)}
    loopback = on.get(0.0)
    if not loopback or loopback.get("peak_force_n") is None:
        return ["No feedback run with TDPA on loopback in this run: nothing to judge against."]
    bound = PEAK_VS_LOOPBACK * loopback["peak_force_n"]
    lines = []
    for trip, row in sorted(on.items()):
        misses = []
        if not row["success"]:
            misses.append("the task failed")
        if row.get("peak_force_n") is None or row["peak_force_n"] > bound:
            misses.append(f"peak {_num(row.get('peak_force_n'))} N > {bound:.1f} N")
        if (row.get("oscillation_swings") or 0) >= SUSTAINED_SWINGS:
            misses.append(f"{row['oscillation_swings']} swings at contact")
        if row.get("drift_m") is None or row["drift_m"] >= MAX_DRIFT_M:
            misses.append(f"drift {_num((row.get('drift_m') or 0) * 1e3)} mm")
        twin = off.get(trip)
        versus = (f"; without passivity {_num(twin.get('peak_force_n'))} N peak, drift "
                  f"{_num((twin.get('drift_m') or 0) * 1e3)} mm" if twin else "")
        lines.append(f"{trip:g} ms: {'PASS' if not misses else 'FAIL (' + '; '.join(misses) + ')'}"
                     f" — TDPA {_num(row.get('peak_force_n'))} N peak (bound {bound:.1f}), "
                     f"drift {_num((row.get('drift_m') or 0) * 1e3)} mm, "
                     f"{row.get('oscillation_swings')} swings{versus}")
    return lines


# -- text ---------------------------------------------------------------------------------------

def _num(value, digits: int = 1) -> str:
    return "–" if value is None else f"{value:.{digits}f}"


def table_rows(result: dict) -> list[tuple[str, ...]]:
    """(mode, round trip set, cut, measured p50 / p99, success, time, peak, final, note) per
    run; the campus routes' round trip named as such."""
    campus = result.get("campus_rtt_ms", CAMPUS_RTT_MS)
    out = []
    for row in result.get("rows", []):
        trip = f"{row['round_trip_ms']:g} ms"
        if row["round_trip_ms"] == campus:
            trip += " (campus)"
        cut = (f"{row['cut_s']:g} s at {row['cut']['at_s']:g} s ({row['cut']['mode']})"
               if row.get("cut_s") else "–")
        measured = (f"{_num(row.get('round_trip_p50_ms'))} / {_num(row.get('round_trip_p99_ms'))}"
                    if row.get("round_trip_p50_ms") is not None else "–")
        proxy = row.get("proxy") or {}
        note = row.get("error") or ""
        if row.get("peaks_n"):
            note = (f"median of {len(row['peaks_n'])} runs: "
                    + ", ".join(_num(peak) for peak in row["peaks_n"]) + " N; " + note
                    ).rstrip("; ")
        if proxy.get("connections", 0) > 1 and not row.get("peaks_n"):  # it reconnected
            note = f"{proxy['connections']} connections; {note}".rstrip("; ")
        feedback = row["mode"] == "feedback"
        drift = _num(row["drift_m"] * 1e3) if feedback and row.get("drift_m") is not None \
            else "–"
        energy = row.get("energy") or {}
        kept = (f"{_num(energy.get('slave_dissipated_j', 0) * 1e3, 0)} / "
                f"{_num(energy.get('master_dissipated_j', 0) * 1e3, 0)}" if energy else "–")
        out.append((label(row), trip, cut, measured, "yes" if row["success"] else "NO",
                    _num(row.get("duration_s")), _num(row.get("peak_force_n")),
                    _num(row.get("final_force_n")), drift,
                    _num(row.get("transparency_rms_n")) if feedback else "–",
                    str(row.get("oscillation_swings", "–")) if feedback else "–", kept, note))
    return out


HEADER = ("mode", "round trip set", "cut", "measured p50 / p99 ms", "success", "time s",
          "peak N", "final N", "drift mm", "transparency RMS N", "swings",
          "dissipated mJ (slave / master)", "note")


def terminal_lines(result: dict) -> list[str]:
    """The group's table for the bench's terminal report."""
    rows = [HEADER, *[(*row[:-1], row[-1][:100]) for row in table_rows(result)]]
    widths = [max(len(row[i]) for row in rows) for i in range(len(HEADER))]
    return ["  network: the peg-in-hole task across the impairment link"] + [
        "    " + "  ".join(cell.ljust(w) for cell, w in zip(row, widths, strict=True)).rstrip()
        for row in rows]


def campus_comparison(result: dict) -> str:
    """What this run shows on the papers' campus round trip, next to what they report."""
    campus = result.get("campus_rtt_ms", CAMPUS_RTT_MS)
    at = {row["mode"]: row for row in result.get("rows", [])
          if row["round_trip_ms"] == campus and not row.get("cut_s")
          and (row["mode"] != "feedback" or row.get("passivity", True))}
    feedback, compliance = at.get("feedback"), at.get("compliance")
    if not feedback or not compliance or None in (feedback.get("peak_force_n"),
                                                  compliance.get("peak_force_n")):
        return f"No complete pair of runs at the campus routes' {campus:g} ms in this run."
    both = feedback["success"] and compliance["success"]
    ratio = (feedback["peak_force_n"] / compliance["peak_force_n"]
             if both and compliance["peak_force_n"] > 0 else None)
    trips = " and ".join(f"{mode} {_num(row.get('round_trip_p50_ms'))} ms"
                         for mode, row in at.items())
    failed = [mode for mode, row in (("feedback", feedback), ("compliance", compliance))
              if not row["success"]]
    return (f"At the campus routes' {campus:g} ms: with force feedback the peak is "
            f"{_num(feedback['peak_force_n'])} N, with compliance at the server "
            f"{_num(compliance['peak_force_n'])} N"
            + (f" ({ratio:.0f}× less)" if ratio and ratio >= 1 else "")
            # A run that never reached the floor felt little: its peak compares nothing.
            + (f"; the {' and '.join(failed)} run failed, so the peaks are no comparison"
               if failed else "")
            + f". The measured round trip (p50: {trips}) adds the station's own time to the "
              "link's, as the papers' 183 ms includes their arm's, operated at 10 Hz.")
