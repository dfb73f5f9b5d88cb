"""video: the stereo stream across real links (issue #27), H.264 paced by receipts beside the
JPEG stream as it was.

One station as the bench starts it (world, proxy_robot, force_sensor, emergency_stop), a
StereoCamera with the sim source (the work cell's MuJoCo cameras at the live arm pose, 640x480
per eye, at most 30 pairs/s) and a DecisionServer in front of them: the operator's one address.
services/impairment's link sits between the probe and the DecisionServer only, with half the
round trip each way and the bottleneck's bandwidth in both directions (no jitter, no stalls).

For each cell of ROUND_TRIPS_MS x BOTTLENECKS_MBIT (QUICK_*: fewer) a fresh link, and through
it, one after the other, clients.video_probe (the operator station's own client and meter, in a
worker process of its own):

- `h264`: IMAGE_ENCODING_H264 with receipts (ReportReceipt), what the operator station streams;
- `jpeg`: the baseline, the JPEG stream as it was: no receipts, a small receive window.

Each probe streams for `Plan.video_s` (10 s; 4 with --quick) after SKIP_S of start-up. Then
one LONG_S run (60 s; 20 with --quick) of H.264 at LONG_CELL (the campus routes' round trip
through the narrowest bottleneck) for the backlog check. Then, at each of CONSOLE_CELLS, the
web console's page in headless Chromium (`console`: H.264 decoded by WebCodecs, receipts on
their WebSocket), the link in front of the console, timed by the page itself (window.videoStats)
and summarized as the probe's meter summarizes (clients/python/video_meter.py).

Each H.264 run is judged against the issue's goals (`judge`): at least MIN_FPS frames a second
shown, the age's p95 (captured -> both eyes decoded at the client) within the link's one-way
delay + AGE_SLACK_MS, and no growing backlog: the p95 of the run's last third within
BACKLOG_MS of its first third's. The JPEG baseline is not judged; beside it the ratios
H.264 / JPEG of the age's p95 and the frame rate.

While each probe runs the worker also reads how busy the machine was and each station
process's share of a core (bench/cpu.py): the camera (rendering and encoding), the world's
1 kHz loop, the DecisionServer's forward, the link (the bench's own process) and the probe.

One result row, `video`, holds a record per cell (`cells`), the long run (`long`), the goals,
and the run it came from (`run`), so that a run of this group alone merges it into the
latest.json already there (`report.merge_row`) and a run without it keeps the one there
(`report.previous_row`), as the network group's row does. `table_rows` / `terminal_lines` /
`markdown` are its tables (`python -m bench.readme` writes `markdown` into
docs/bench_video.md) and `plot` its figure.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path

from services.impairment import LinkProfile

NAME = "video"
ROUND_TRIPS_MS = (0.0, 50.0, 183.0, 400.0)
BOTTLENECKS_MBIT = (None, 8.0, 4.0, 2.0)  # None: no bandwidth cap
QUICK_ROUND_TRIPS_MS = (0.0, 183.0)
QUICK_BOTTLENECKS_MBIT = (None, 2.0)
CAMPUS_RTT_MS = 183.0  # MTDF paper, section V (as bench/network.py)
LONG_CELL = (CAMPUS_RTT_MS, 2.0)  # (round trip ms, bottleneck Mbit/s) of the long run
# (round trip ms, bottleneck Mbit/s) of the console's runs in Chromium: the campus route,
# open and through the narrowest bottleneck.
CONSOLE_CELLS = ((CAMPUS_RTT_MS, None), (CAMPUS_RTT_MS, 2.0))
QUICK_CONSOLE_CELLS = ((CAMPUS_RTT_MS, 2.0),)
CHROMIUM = "/usr/bin/chromium"  # Debian's (Playwright cannot download its own here)
CHROMIUM_ARGS = ("--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
                 "--disable-background-networking", "--disable-component-update")
PROBE_S, QUICK_PROBE_S = 10.0, 4.0  # each probe, after SKIP_S
LONG_S, QUICK_LONG_S = 60.0, 20.0
SKIP_S = 2.0  # the probe's start-up, left out of its figures
SOURCE = "sim"  # --video-source pattern: a test card that costs next to nothing to draw
SOURCES = ("sim", "pattern")
WIDTH_PX, HEIGHT_PX, SOURCE_FPS = 640, 480, 30.0  # per eye; both side by side in one picture
CODECS = ("h264", "jpeg")  # the operator's stream, then the baseline
CONSOLE = "console"  # the console's page: H.264 with receipts, WebCodecs
# Issue #27's goals for the H.264 stream at every cell.
MIN_FPS = 25.0
AGE_SLACK_MS = 80.0  # the age's p95 within the one-way delay plus this
BACKLOG_MS = 20.0  # the last third's p95 age within this of the first third's
PLOT_FILE = "video.png"
PROBE_TIMEOUT_S = 90.0  # beyond the probe's own time: start-up and a slow first frame
# Whose CPU the probe's worker reads (bench/cpu.py): the station's processes by their names.
WATCHED = ("stereo_camera", "decision_server", "world", "proxy_robot", "force_sensor")


@dataclass(frozen=True)
class Cell:
    """One link: a round trip and a bottleneck (None: none), and how long each probe runs."""

    round_trip_ms: float
    bottleneck_mbit: float | None
    seconds: float
    long: bool = False
    console: bool = False  # the console's page in Chromium, not the probe

    @property
    def name(self) -> str:
        cap = "open" if self.bottleneck_mbit is None else f"{self.bottleneck_mbit:g}mbit"
        return (f"{self.round_trip_ms:g}ms_{cap}" + ("_long" if self.long else "")
                + ("_console" if self.console else ""))

    @property
    def one_way_ms(self) -> float:
        return self.round_trip_ms / 2

    @property
    def age_bound_ms(self) -> float:
        """The goal's bound on the age's p95."""
        return self.one_way_ms + AGE_SLACK_MS

    @property
    def codecs(self) -> tuple[str, ...]:
        """What runs at the cell, the judged one first."""
        return (CONSOLE,) if self.console else ("h264",) if self.long else CODECS


def cells(quick: bool, seconds: float | None = None,
          long_seconds: float | None = None) -> list[Cell]:
    """The grid, round trip by round trip (each bottleneck from none to the narrowest), then
    the long run. `seconds` / `long_seconds`: the probes' lengths instead of the defaults."""
    seconds = seconds or (QUICK_PROBE_S if quick else PROBE_S)
    trips = QUICK_ROUND_TRIPS_MS if quick else ROUND_TRIPS_MS
    caps = QUICK_BOTTLENECKS_MBIT if quick else BOTTLENECKS_MBIT
    grid = [Cell(trip, cap, seconds) for trip in trips for cap in caps]
    consoles = [Cell(trip, cap, seconds, console=True)
                for trip, cap in (QUICK_CONSOLE_CELLS if quick else CONSOLE_CELLS)]
    return [*grid, Cell(*LONG_CELL, long_seconds or (QUICK_LONG_S if quick else LONG_S),
                        long=True), *consoles]


def link_profiles(cell: Cell) -> tuple[LinkProfile, LinkProfile]:
    """(up, down): half the round trip each way, the bottleneck both ways."""
    profile = LinkProfile(delay_s=cell.round_trip_ms / 2e3,
                          bandwidth_bps=(cell.bottleneck_mbit or 0.0) * 1e6)
    return profile, profile


# -- the goals ------------------------------------------------------------------------------------

def goal_text(cell: Cell | None = None) -> str:
    age = (f"age p95 <= {cell.age_bound_ms:g} ms" if cell is not None
           else f"age p95 <= one-way delay + {AGE_SLACK_MS:g} ms")
    return (f">= {MIN_FPS:g} fps, {age}, no growing backlog (last third's p95 <= first's + "
            f"{BACKLOG_MS:g} ms)")


def judge(result: dict | None, cell: Cell) -> list[str]:
    """What an H.264 run at `cell` fell short of the goals by; [] when it met them all."""
    if not result or result.get("status") in ("failed", "pending"):
        reason = (result or {}).get("reason", "no result")
        return [f"{(result or {}).get('status', 'failed')}: {reason}"[:200]]
    misses = []
    fps, p95 = result.get("fps"), result.get("age_ms_p95")
    if fps is None or fps < MIN_FPS:
        misses.append(f"{_num(fps)} fps < {MIN_FPS:g}")
    if p95 is None or p95 > cell.age_bound_ms:
        misses.append(f"age p95 {_num(p95, 0)} ms > {cell.age_bound_ms:g}")
    thirds = result.get("age_ms_p95_thirds") or []
    first, last = (thirds[0], thirds[-1]) if len(thirds) == 3 else (None, None)
    if first is None or last is None:
        misses.append("backlog: too few frames for thirds")
    elif last > first + BACKLOG_MS:
        misses.append(f"backlog: last third's p95 {_num(last, 0)} ms > first's "
                      f"{_num(first, 0)} + {BACKLOG_MS:g}")
    return misses


def ratios(h264: dict | None, jpeg: dict | None) -> dict[str, float | None]:
    """H.264 / JPEG at one cell: the age's p95 and the frame rate."""
    def over(key: str) -> float | None:
        a, b = (h264 or {}).get(key), (jpeg or {}).get(key)
        return round(a / b, 3) if a is not None and b else None

    return {"age_p95": over("age_ms_p95"), "fps": over("fps")}


# -- the group's steps (bench/groups/video.py runs them) ------------------------------------------

def step_count(plan) -> int:
    """The progress steps of the group: the camera's start, then one per cell."""
    return 1 + len(cells(plan.quick, plan.video_s, plan.video_long_s))


# -- the worker's side (python -m bench.worker video) ---------------------------------------------

def measure(params: dict) -> dict:
    """clients.video_probe through `params["address"]`, and the CPU of `watch_pids` and of
    this process (the probe) while it ran."""
    from bench.cpu import CpuWindow
    from clients.video_probe import probe

    window = CpuWindow({**(params.get("watch_pids") or {}), "probe": os.getpid()})
    result = probe(params["address"], params["seconds"], encoding=params["encoding"],
                   receipts=params["receipts"], skip_s=params["skip_s"])
    result["cpu"] = window.stop()
    return result


def measure_console(params: dict) -> dict:
    """The console's page at `params["url"]` in headless Chromium: the frames it showed over
    `seconds` after `skip_s` (its own timing, window.videoStats), summarized by the probe's
    meter; the decoder it used; and the CPU of `watch_pids` meanwhile (Chromium's own shows in
    the machine's share)."""
    from playwright.sync_api import sync_playwright

    from bench.cpu import CpuWindow
    from clients.python.video_meter import VideoMeter

    if not Path(CHROMIUM).exists():
        return {"status": "pending", "reason": f"{CHROMIUM} is missing (make test installs it)"}
    window = CpuWindow(params.get("watch_pids") or {})
    with sync_playwright() as driver:
        browser = driver.chromium.launch(executable_path=CHROMIUM, args=list(CHROMIUM_ARGS))
        try:
            page = browser.new_page(viewport={"width": 1400, "height": 1000})
            page.goto(params["url"])
            page.wait_for_function("() => (window.videoStats?.frames ?? 0) > 0",
                                   timeout=PROBE_TIMEOUT_S * 1e3)
            page.wait_for_timeout((params["skip_s"] + params["seconds"]) * 1e3)
            stats = page.evaluate("""() => ({codec: videoStats.codec,
                decoder: videoStats.decoder, fallback: videoStats.fallbackReason,
                errors: videoStats.decodeErrors, samples: videoStats.samples})""")
        finally:
            browser.close()
    meter = VideoMeter()
    for sample in stats["samples"]:
        meter.record(round(sample["shownMs"] * 1e6), sample["ageMs"], sample["bytes"],
                     sample["targetKbit"], sample.get("renderScale", 1.0))
    result = meter.summary(params["skip_s"])
    result.update(codec=stats["codec"], decoder=stats["decoder"],
                  fallback=stats["fallback"], decode_errors=stats["errors"],
                  cpu=window.stop())
    return result


# -- text -----------------------------------------------------------------------------------------

def _num(value, digits: int = 1) -> str:
    return "–" if value is None else f"{value:.{digits}f}"


def _ms(value) -> str:
    return "–" if value is None else f"{value:.0f}"


def _link_text(record: dict) -> tuple[str, str]:
    trip = f"{record['round_trip_ms']:g} ms"
    cap = record.get("bottleneck_mbit")
    return trip, "none" if cap is None else f"{cap:g} Mbit/s"


def judged(record: dict) -> dict:
    """The judged run of a cell: the H.264 probe's, or the console page's."""
    return record.get("h264") or record.get(CONSOLE) or {}


def _records(result: dict) -> list[dict]:
    """Every cell's record: the grid, the long run, the console's."""
    return [*result.get("cells", []), *([result["long"]] if result.get("long") else []),
            *result.get("console", [])]


def _figures(result: dict | None) -> tuple[str, str, str]:
    """(fps, age p50 / p95, kbit/s) of one probe, or its failure."""
    if not result:
        return "–", "–", "–"
    if result.get("status") in ("failed", "pending"):
        return result["status"], "–", "–"
    return (_num(result.get("fps")),
            f"{_ms(result.get('age_ms_p50'))} / {_ms(result.get('age_ms_p95'))}",
            _num(result.get("kbit_per_s"), 0))


def _thirds(result: dict | None) -> str:
    thirds = (result or {}).get("age_ms_p95_thirds") or []
    return " → ".join(_ms(value) for value in thirds) or "–"


def _verdict(record: dict) -> str:
    return "PASS" if record["pass"] else "FAIL: " + "; ".join(record["misses"])


def _ratios_text(record: dict) -> str:
    versus = record.get("vs_jpeg") or {}
    parts = [f"{label} ×{versus[key]:.2f}" for key, label in (("age_p95", "age p95"),
                                                             ("fps", "fps"))
             if versus.get(key) is not None]
    return ", ".join(parts) or "–"


HEADER = ("round trip", "bottleneck", "H.264 fps", "render scale", "age p50 / p95 ms",
          "p95 by thirds ms", "kbit/s (target)", "age bound ms", "result", "JPEG fps",
          "JPEG age p50 / p95 ms", "JPEG kbit/s", "H.264 / JPEG")


def table_rows(result: dict) -> list[tuple[str, ...]]:
    """A tuple per cell (HEADER), then the long run's."""
    rows = []
    for record in _records(result):
        trip, cap = _link_text(record)
        if record.get("long"):
            cap += f", {record['seconds']:g} s"
        if record.get("console"):
            cap += ", the console in Chromium"
        h264, jpeg = judged(record), record.get("jpeg")
        fps, age, _ = _figures(h264)
        target = h264.get("target_kbit_per_s")
        kbit = (f"{_num(h264.get('kbit_per_s'), 0)} ({target})" if "kbit_per_s" in h264
                else "–")
        jpeg_fps, jpeg_age, jpeg_kbit = _figures(jpeg) if jpeg is not None else ("–",) * 3
        scale = h264.get("render_scale")
        rows.append((trip, cap, fps, "–" if scale is None else f"{scale:g}", age, _thirds(h264),
                     kbit, f"{record['age_bound_ms']:g}",
                     _verdict(record), jpeg_fps, jpeg_age, jpeg_kbit, _ratios_text(record)))
    return rows


def cell_text(record: dict) -> str:
    """A cell's figures on one line (the progress line)."""
    h264, jpeg = judged(record), record.get("jpeg")
    fps, age, kbit = _figures(h264)
    what = "console (WebCodecs)" if record.get("console") else "H.264"
    text = (f"{what} {fps} fps, age p50/p95 {age} ms (thirds {_thirds(h264)}), {kbit} kbit/s"
            f" [{'PASS' if record['pass'] else 'FAIL (' + '; '.join(record['misses']) + ')'}]")
    if jpeg is not None:
        jpeg_fps, jpeg_age, jpeg_kbit = _figures(jpeg)
        text += (f"; JPEG {jpeg_fps} fps, age p50/p95 {jpeg_age} ms, {jpeg_kbit} kbit/s; "
                 f"H.264/JPEG {_ratios_text(record)}")
    return text


def terminal_lines(result: dict) -> list[str]:
    """The group's table for the bench's terminal report, then the CPU while each cell's
    H.264 probe ran."""
    rows = [HEADER, *table_rows(result)]
    widths = [max(len(row[i]) for row in rows) for i in range(len(HEADER))]
    lines = [f"  video: the stereo stream across the impairment link ({goal_text()}; "
             f"{result.get('passed')} of {result.get('judged')} H.264 runs passed)"]
    lines += ["    " + "  ".join(cell.ljust(w) for cell, w in zip(row, widths, strict=True)
                                 ).rstrip() for row in rows]
    lines += ["  video: CPU while each H.264 probe ran (% of one core; machine % of all cores)"]
    records = _records(result)
    lines += [f"    {record['name']}: {cpu_text(judged(record))}"
              + (f" (load average {record['load_avg_at_start']:g} at its start)"
                 if record.get("load_avg_at_start") is not None else "")
              for record in records]
    return lines


def camera_ms_per_frame(result: dict | None) -> float | None:
    """The camera's CPU per frame shown (ms): its share of a core over the probe's window
    (start-up included) over the frame rate shown after the start-up. What a frame costs to
    render and encode, whatever the machine's load makes of the frame rate."""
    result = result or {}
    share = ((result.get("cpu") or {}).get("cpu_pct") or {}).get("stereo_camera")
    if share is None or not result.get("fps"):
        return None
    return round(10.0 * share / result["fps"], 1)


def cpu_text(result: dict | None) -> str:
    cpu = (result or {}).get("cpu") or {}
    if not cpu:
        return "–"
    shares = sorted((cpu.get("cpu_pct") or {}).items(), key=lambda item: -item[1])
    per_frame = camera_ms_per_frame(result)
    return (f"machine {_num(cpu.get('machine_busy_pct'), 0)} %; "
            + ", ".join(f"{name} {value:.0f}" for name, value in shares)
            + (f"; camera {per_frame:g} ms CPU/frame" if per_frame is not None else ""))


def markdown(result: dict, source: str = "bench/results/latest.json") -> str:
    """docs/bench_video.md: the run, how it was set up, the table, the long run, the misses."""
    run = result.get("run") or {}
    machine = run.get("machine", {})
    load = machine.get("load_avg_at_start"), machine.get("load_avg_at_end")
    loads = " → ".join(f"{values[0]:.1f}" for values in load if values)
    camera = result.get("camera") or {}
    long = result.get("long")
    lines = [
        f"<!-- Generated by `python -m bench.readme` from `{source}`: do not edit. -->",
        f"The video rows of the network group (`make bench ONLY=network`, or alone `make bench "
        f"ONLY=video`), a {'quick' if run.get('quick') else 'full'} run of "
        f"{result.get('elapsed_s')} s at {run.get('time')}"
        + (f" (commit {result['commit']})" if result.get("commit") else "")
        + f", on {machine.get('cores')} cores "
        f"({machine.get('cpu_model')}, Python {machine.get('python')}, load average "
        f"{loads or '?'}). One station: the `{camera.get('source')}` StereoCamera "
        f"({camera.get('width_px')}×{camera.get('height_px')} per eye, at most "
        f"{_num(camera.get('fps'), 0)} pairs/s, render scale "
        f"{camera.get('render_scale', '1')}: the share of the picture's width and height "
        "the sim renders, which `auto` lowers while a pair's render is over its budget) "
        "behind a DecisionServer, and "
        "`services/impairment`'s link between the probe (`clients.video_probe`, the operator "
        "station's client) and the DecisionServer: half the round trip each way, the "
        "bottleneck both ways, no jitter. Each probe streams "
        f"{_num((result.get('cells') or [{}])[0].get('seconds'), 0)} s after "
        f"{result.get('skip_s', SKIP_S):g} s of start-up, through a link of its own: H.264 with "
        "receipts (paced to the path), then the JPEG baseline (no receipts, a small receive "
        "window). Age: captured → both eyes decoded at the client. H.264 judged against "
        f"issue #27's goals: {goal_text()}.",
        "",
        "| " + " | ".join(HEADER) + " |",
        "|" + "---|" * len(HEADER),
    ]
    for cells_ in table_rows(result):
        lines.append("| " + " | ".join(cell.replace("|", "\\|") for cell in cells_) + " |")
    lines.append("")
    lines.append(goal_counts(result.get("cells", [])))
    cpu = cpu_summary([*result.get("cells", []), *([long] if long else [])])
    if cpu:
        lines += ["", cpu]
    if long:
        h264 = long.get("h264") or {}
        lines.append("")
        lines.append(f"Long run, {_link_text(long)[0]} / {_link_text(long)[1]}, "
                     f"{long['seconds']:g} s: {_figures(h264)[0]} fps, age p95 by thirds "
                     f"{_thirds(h264)} ms: {_verdict(long)}"
                     + ("" if any(m.startswith(("backlog", "failed", "pending"))
                                  for m in long["misses"])
                        else f" (no growing backlog: the last third within {BACKLOG_MS:g} ms of "
                             "the first)") + ".")
    for record in result.get("console", []):
        page = judged(record)
        lines.append("")
        lines.append(f"The console's page in headless Chromium ({page.get('decoder', '?')}, "
                     f"{page.get('codec', '?')}), the link in front of the console, "
                     f"{_link_text(record)[0]} / {_link_text(record)[1]}: {_figures(page)[0]} "
                     f"fps, age p50 / p95 {_figures(page)[1]} ms, p95 by thirds "
                     f"{_thirds(page)} ms: {_verdict(record)}.")
    return "\n".join(lines) + "\n"


def goal_counts(records: list[dict]) -> str:
    """How many cells met all the goals, and each goal on its own."""
    cells_ = [r for r in records if not r.get("long")]
    failed = [r["name"] for r in cells_ if not r["pass"]]

    def met(missed) -> int:
        return sum(1 for r in cells_ if not any(
            missed(miss) or miss.startswith(("failed:", "pending:")) for miss in r["misses"]))

    return (f"H.264 met every goal in {len(cells_) - len(failed)} of {len(cells_)} cells"
            + (f" (missed in {', '.join(failed)})" if failed and len(failed) < len(cells_)
               else "")
            + f"; ≥ {MIN_FPS:g} fps in {met(lambda miss: 'fps <' in miss)}, the age's p95 "
              f"bound in {met(lambda miss: miss.startswith('age p95'))}, no growing backlog in "
              f"{met(lambda miss: miss.startswith('backlog'))}.")


def cpu_summary(records: list[dict]) -> str:
    """The range over the H.264 probes of how busy the machine was and of each process's
    share of a core, and the camera's CPU per frame shown."""
    busy, shares, per_frame = [], {}, []
    for record in records:
        cpu = (record.get("h264") or {}).get("cpu") or {}
        if not cpu:
            continue
        busy.append(cpu.get("machine_busy_pct"))
        for name, value in (cpu.get("cpu_pct") or {}).items():
            shares.setdefault(name, []).append(value)
        if (value := camera_ms_per_frame(record.get("h264"))) is not None:
            per_frame.append(value)
    busy = [value for value in busy if value is not None]
    loads = [r["load_avg_at_start"] for r in records if r.get("load_avg_at_start") is not None]
    if not busy:
        return ""

    def span(values: list[float]) -> str:
        low, high = min(values), max(values)
        digits = 1 if high < 10 else 0
        return (f"{low:.{digits}f}" if round(low, digits) == round(high, digits)
                else f"{low:.{digits}f}–{high:.{digits}f}")

    ordered = sorted(shares.items(), key=lambda item: -max(item[1]))
    return (f"While the H.264 probes ran the machine was {span(busy)} % busy (both cores); "
            "share of one core: " + ", ".join(f"{name} {span(values)} %"
                                              for name, values in ordered)
            + (f"; the camera's CPU per frame shown {span(per_frame)} ms" if per_frame else "")
            + (f"; the load average at the cells' starts {span(loads)}" if loads else "")
            + ".")


# -- the figure -----------------------------------------------------------------------------------

def plot(result: dict, path: Path) -> Path:
    """Two panels, a group of bars per cell (and the long run), H.264 beside JPEG: the age's
    p95 with each cell's goal (one-way delay + AGE_SLACK_MS) and the frame rate with MIN_FPS."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    from matplotlib.ticker import FuncFormatter

    records = _records(result)
    figure, (ages, rates) = plt.subplots(2, 1, figsize=(14, 8.5), sharex=True)
    x = np.arange(len(records))
    width = 0.38
    colors = {"h264": "tab:blue", "jpeg": "tab:orange"}
    names = {"h264": "H.264 with receipts", "jpeg": "JPEG as it was (no receipts)"}
    for offset, codec in ((-width / 2, "h264"), (width / 2, "jpeg")):
        # The console's page stands in the H.264 slot (its stream is the same).
        values = [judged(r) if codec == "h264" else (r.get(codec) or {}) for r in records]
        age = [v.get("age_ms_p95") or np.nan for v in values]
        fps = [v.get("fps") if v.get("fps") is not None else np.nan for v in values]
        ages.bar(x + offset, age, width, color=colors[codec], label=names[codec])
        rates.bar(x + offset, fps, width, color=colors[codec], label=names[codec])
    for index, record in enumerate(records):
        bound = record["age_bound_ms"]
        ages.hlines(bound, index - 0.45, index + 0.45, color="red", linewidth=1.5,
                    label=f"goal: one-way delay + {AGE_SLACK_MS:g} ms" if index == 0 else None)
        if not record["pass"]:
            rates.text(index - width / 2, 1, "FAIL", rotation=90, ha="center", va="bottom",
                       fontsize=7, color="white", fontweight="bold")
    rates.axhline(MIN_FPS, color="red", linewidth=1.5, label=f"goal: {MIN_FPS:g} fps")
    ages.set_yscale("log")
    ages.yaxis.set_major_formatter(FuncFormatter(lambda value, _: f"{value:g}"))
    ages.set_ylabel("age p95, captured → decoded (ms, log)")
    source = (result.get("camera") or {}).get("source", SOURCE)
    ages.set_title(f"stereo video ({source} camera) through the impairment link: age p95 per "
                   "cell")
    rates.set_ylabel("frames shown per second")
    rates.set_title("frame rate per cell")
    labels = []
    for record in records:
        trip, cap = _link_text(record)
        labels.append(f"{trip}\n{cap}" + (f"\n{record['seconds']:g} s" if record.get("long")
                                          else "\nconsole" if record.get("console") else ""))
    rates.set_xticks(x, labels, fontsize=7)
    rates.set_xlabel("round trip / bottleneck (both ways)")
    for axis in (ages, rates):
        axis.grid(True, axis="y", which="both", alpha=0.3)
        axis.legend(fontsize=8, loc="upper left")
        for boundary in range(1, len(records)):  # between round trips
            if records[boundary]["round_trip_ms"] != records[boundary - 1]["round_trip_ms"] \
                    or records[boundary].get("long"):
                axis.axvline(boundary - 0.5, color="grey", linewidth=0.8, alpha=0.6)
    figure.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    figure.savefig(path, dpi=100)
    plt.close(figure)
    return path
