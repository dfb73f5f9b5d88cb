"""soak: the station under a steady operator's load for minutes; its memory and its losses.

Issue #16. The station (world, proxy_robot, force_sensor, emergency_stop, decision_server,
stereo_camera) serves, for `Plan.soak_s` (10 minutes; 1 with --quick; --soak-minutes N), at
once and each from a worker process of its own:

- the operator: Teleoperate at TELEOP_RATE_HZ, pipelined (teleop.py's worker, the same code:
  one session for the whole run, the direction of motion flipping every SWING commands so the
  arm goes back and forth, a session watchdog of WATCHDOG_S);
- OBSERVERS wrench observers at 100 Hz (force.py's observers worker);
- one stereo client (stereo.py's, streams of CHUNK_S one after another: `sim` source, double
  buffer, 640x480 JPEG decoded);
- a follower of the DecisionServer's StreamEvents (`follow_events`, DATA_RECEIVED included so
  that a gap in the events' sequence numbers is an event this follower lost).

Meanwhile the orchestrator reads `/proc/<pid>/status` (VmRSS, Threads), `/proc/<pid>/fd` and
`/proc/<pid>/stat` (CPU time) of every station process every `Plan.soak_sample_s` seconds,
and the world loop's counters (worldloop.py). Each process's RSS trend (`rss_trend`): the least
squares slope in MiB per minute over the samples after the first WARMUP_FRACTION of the run,
the same over the second half of that window (`late_slope_mib_min`: still growing at the
end?), and the growth the slope makes over the window.

One result row, `soak`: the Teleoperate stream's figures at the top level (delivered, latency
command -> applied, `dropped` as teleop's), and `teleop`, `observers`, `stereo`, `events`,
`rss` (per process), `rss_series` (the samples) beside. Its goal (goals.py) fails on
sustained RSS growth or on loss; see bench/README.md, "The soak".
"""

from __future__ import annotations

import os
import threading
import time
from collections import Counter
from collections.abc import Callable, Sequence

import numpy as np

from bench.cpu import process_cpu_s

NAME = "soak"
TELEOP_RATE_HZ = 500
OBSERVERS = 4
OBSERVER_DECIMATION = 10  # 100 Hz each, as in the observers group
WATCHDOG_S = 1.0  # the soak session's watchdog; teleop's own 5 s would hide a stall
SWING = 2000  # commands of 10 um: the arm goes 2 cm one way, then back (4 s at 500 Hz)
WINDOW_S = 60.0  # the stream's latency per minute (teleop.windows); a short soak: a 6th
DRAIN_S = 15.0  # a command not acked this long after the last send is lost, not late
STEREO_SOURCE, STEREO_MODE = "sim", "double"
WARMUP_FRACTION = 0.2
STATION = ("world", "proxy_robot", "force_sensor", "emergency_stop", "decision_server",
           "stereo_camera")
NOTE_EVERY_S = 60.0  # a progress line with the RSS this often
KEEP_EVENTS = 50  # events of each kind kept with their details (all are counted)
WORKER_SLACK_S = 180.0  # a worker's time limit beyond the soak's duration


# -- the RSS trend (pure) ---------------------------------------------------------------------

def slope(times: Sequence[float], values: Sequence[float]) -> float | None:
    """The least squares slope of `values` over `times` (value units per time unit); None
    with fewer than two samples or no time between them."""
    t = np.asarray(times, dtype=float)
    v = np.asarray(values, dtype=float)
    if t.size < 2 or np.ptp(t) == 0:
        return None
    centred = t - t.mean()
    return float((centred * (v - v.mean())).sum() / (centred * centred).sum())


def rss_trend(times_s: Sequence[float], rss_mib: Sequence[float],
              warmup_fraction: float = WARMUP_FRACTION) -> dict:
    """One process's RSS over the run: first, last and peak sample (MiB); over the samples
    after the first `warmup_fraction` of the sampled time, the least squares slope (MiB/min),
    the slope over the second half of that window (`late_slope_mib_min`), the growth the slope
    makes over the window (`growth_mib`), the window's length and its sample count. Samples
    of None (the process gone) are left out."""
    pairs = [(t, v) for t, v in zip(times_s, rss_mib, strict=True) if v is not None]
    if not pairs:
        return {"start_mib": None, "end_mib": None, "peak_mib": None, "slope_mib_min": None,
                "late_slope_mib_min": None, "growth_mib": None, "window_min": 0.0,
                "samples": 0}
    t = np.array([p[0] for p in pairs], dtype=float)
    v = np.array([p[1] for p in pairs], dtype=float)
    keep = t >= t[0] + warmup_fraction * (t[-1] - t[0])
    t_kept, v_kept = t[keep], v[keep]
    window_min = float(t_kept[-1] - t_kept[0]) / 60.0
    late = t_kept >= t_kept[0] + (t_kept[-1] - t_kept[0]) / 2
    rate = slope(t_kept / 60.0, v_kept)
    late_rate = slope(t_kept[late] / 60.0, v_kept[late])
    return {"start_mib": round(float(v[0]), 2), "end_mib": round(float(v[-1]), 2),
            "peak_mib": round(float(v.max()), 2),
            "slope_mib_min": None if rate is None else round(rate, 3),
            "late_slope_mib_min": None if late_rate is None else round(late_rate, 3),
            "growth_mib": None if rate is None else round(rate * window_min, 2),
            "window_min": round(window_min, 2), "samples": int(t_kept.size)}


# -- /proc ------------------------------------------------------------------------------------

def read_process(pid: int) -> dict | None:
    """RSS and its anonymous part (the heap, without mapped files and shared memory; MiB),
    threads, open file descriptors and CPU time (s, user + system) of `pid`; None if it is
    gone."""
    try:
        with open(f"/proc/{pid}/status") as status:
            fields = dict(line.split(":", 1) for line in status if ":" in line)
        cpu_s = process_cpu_s(pid)
        fds = len(os.listdir(f"/proc/{pid}/fd"))
    except (FileNotFoundError, ProcessLookupError):
        return None
    if fields.get("State", "").strip().startswith("Z"):
        return None  # exited, not yet reaped
    return {"rss_mib": round(int(fields["VmRSS"].split()[0]) / 1024.0, 3),
            "anon_mib": round(int(fields["RssAnon"].split()[0]) / 1024.0, 3),
            "threads": int(fields["Threads"]), "fds": fds,
            "cpu_s": cpu_s}


class Sampler:
    """Every `period_s`, `read_process` of each station process and the world loop's counters
    (`loop_read`, may be None), in a thread; `note` gets a progress line every NOTE_EVERY_S."""

    def __init__(self, pids: dict[str, int], period_s: float,
                 loop_read: Callable[[], dict] | None, note: Callable[[str], None]):
        self.pids, self.period_s, self.loop_read, self.note = pids, period_s, loop_read, note
        self.t_s: list[float] = []
        self.series: dict[str, list[dict | None]] = {name: [] for name in pids}
        self.loop: list[dict | None] = []
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, name="soak-sampler", daemon=True)

    def start(self) -> None:
        self._started = time.monotonic()
        self._thread.start()

    def stop(self) -> None:
        self._stop.set()
        self._thread.join(5.0)
        self._sample()  # the last one, as the run ends

    def _sample(self) -> None:
        self.t_s.append(round(time.monotonic() - self._started, 3))
        for name, pid in self.pids.items():
            self.series[name].append(read_process(pid))
        try:
            self.loop.append(self.loop_read() if self.loop_read else None)
        except RuntimeError:  # the world is stuck or gone: the row says so
            self.loop.append(None)

    def _run(self) -> None:
        next_note = NOTE_EVERY_S
        while True:
            self._sample()
            if self.t_s[-1] >= next_note:
                next_note += NOTE_EVERY_S
                self.note(self.progress_line())
            if self._stop.wait(self.period_s):
                return

    def progress_line(self) -> str:
        rss = ", ".join(f"{name} {sample['rss_mib']:.1f}" if sample else f"{name} gone"
                        for name, samples in self.series.items()
                        for sample in samples[-1:])
        line = f"soak {self.t_s[-1] / 60:.1f} min: RSS MiB {rss}"
        loops = [counts for counts in self.loop if counts]
        if len(loops) >= 2:
            line += (f"; world overruns {loops[-1]['overruns'] - loops[0]['overruns']} in "
                     f"{loops[-1]['steps'] - loops[0]['steps']} steps")
        return line

    def processes(self) -> dict[str, dict]:
        """Per process: rss_trend (and `anon`: the anonymous part's first, last and slope),
        threads and file descriptors (first, last, most), CPU % of one core over the run, and
        whether it was gone at a sample (`exited`)."""
        out = {}
        for name, samples in self.series.items():
            rss = [s["rss_mib"] if s else None for s in samples]
            entry = rss_trend(self.t_s, rss)
            anon = rss_trend(self.t_s, [s["anon_mib"] if s else None for s in samples])
            entry["anon"] = {key: anon[key] for key in ("start_mib", "end_mib",
                                                        "slope_mib_min")}
            alive = [(t, s) for t, s in zip(self.t_s, samples, strict=True) if s]
            for key in ("threads", "fds"):
                values = [s[key] for _, s in alive]
                entry[key] = ({"start": values[0], "end": values[-1], "max": max(values)}
                              if values else None)
            if len(alive) >= 2 and alive[-1][0] > alive[0][0]:
                entry["cpu_pct"] = round(100.0 * (alive[-1][1]["cpu_s"] - alive[0][1]["cpu_s"])
                                         / (alive[-1][0] - alive[0][0]), 1)
            entry["exited"] = any(s is None for s in samples)
            out[name] = entry
        return out

    def record(self) -> dict:
        """The samples as they were taken: times (s), RSS (MiB) per process, world overruns
        since the first sample."""
        loops = [counts for counts in self.loop]
        first = next((c for c in loops if c), None)
        return {"t_s": self.t_s,
                "rss_mib": {name: [s["rss_mib"] if s else None for s in samples]
                            for name, samples in self.series.items()},
                "world_overruns": [c["overruns"] - first["overruns"] if c and first else None
                                   for c in loops]}


# -- the DecisionServer's events (in a worker) ------------------------------------------------

def is_lease_lost(reason: str) -> bool:
    """A ControlChangedEvent's reason that says a lease lapsed (arbitration.py: "<operator>'s
    lease expired"): its holder lost control without giving it up."""
    return "expired" in reason


def is_watchdog_trip(reason: str) -> bool:
    """A WatchdogHoldEvent's reason that says the watchdog fired on silence ("watchdog
    timeout: ..."), not the hold at a stream's end ("the stream ended", "... cancelled")."""
    return reason.startswith("watchdog")


class EventBook:
    """StreamEvents' messages, counted by kind; lease changes, watchdog holds, dependency
    changes and robot errors kept with their times (up to KEEP_EVENTS each); gaps in the
    sequence numbers (events this follower did not get)."""

    def __init__(self):
        self.kinds: Counter[str] = Counter()
        self.robot_kinds: Counter[str] = Counter()
        self.control: list[dict] = []
        self.watchdog: list[dict] = []
        self.dependencies: list[dict] = []
        self.robot_errors: list[dict] = []
        self.control_changes = self.leases_lost = 0
        self.watchdog_holds = self.watchdog_trips = 0
        self.gaps = 0
        self._last_sequence: int | None = None

    def add(self, message) -> None:
        from telerobot.v1 import decision_server_pb2 as dpb

        if self._last_sequence is not None and message.sequence > self._last_sequence + 1:
            self.gaps += message.sequence - self._last_sequence - 1
        self._last_sequence = message.sequence
        kind = message.WhichOneof("event") or "none"
        self.kinds[kind] += 1
        time_ns = message.event_time.ToNanoseconds()
        if kind == "control_changed":
            event = message.control_changed
            self.control_changes += 1
            self.leases_lost += is_lease_lost(event.reason)
            _keep(self.control, {"time_ns": time_ns, "reason": event.reason,
                                 "holders": [h.operator_id for h in event.state.holders]})
        elif kind == "watchdog_hold":
            event = message.watchdog_hold
            self.watchdog_holds += 1
            self.watchdog_trips += is_watchdog_trip(event.reason)
            _keep(self.watchdog, {"time_ns": time_ns, "reason": event.reason,
                                  "silence_ms": round(event.silence.ToNanoseconds() / 1e6, 1)})
        elif kind == "dependency_changed":
            event = message.dependency_changed
            _keep(self.dependencies, {
                "time_ns": time_ns, "name": event.dependency.name,
                "from": dpb.DependencyState.Name(event.previous_state),
                "to": dpb.DependencyState.Name(event.dependency.state),
                "reason": event.dependency.reason})
        elif kind == "robot":
            robot_kind = message.robot.WhichOneof("event") or "none"
            self.robot_kinds[robot_kind] += 1
            if robot_kind == "error":
                _keep(self.robot_errors, {"time_ns": time_ns,
                                          "error": str(message.robot.error)[:200]})

    def result(self) -> dict:
        return {"events": sum(self.kinds.values()), "kinds": dict(self.kinds),
                "robot_kinds": dict(self.robot_kinds), "sequence_gaps": self.gaps,
                "control_changes": self.control_changes, "leases_lost": self.leases_lost,
                "watchdog_holds": self.watchdog_holds, "watchdog_trips": self.watchdog_trips,
                "dependency_changes": self.kinds["dependency_changed"],
                "control": self.control, "watchdog": self.watchdog,
                "dependencies": self.dependencies, "robot_errors": self.robot_errors}


def _keep(kept: list[dict], entry: dict) -> None:
    if len(kept) < KEEP_EVENTS:
        kept.append(entry)


def follow_events(address: str, max_s: float, ready: Callable[[], None],
                  stop: threading.Event) -> dict:
    """StreamEvents from the DecisionServer at `address` (DATA_RECEIVED included, 10 Hz, so
    the first event comes soon and a gap is a loss) until `stop` or max_s, into an EventBook.
    ready() once the first event came (or after 10 s without one)."""
    import grpc

    from telerobot.v1 import decision_server_pb2 as dpb
    from telerobot.v1 import decision_server_pb2_grpc

    book = EventBook()
    first = threading.Event()
    ended = threading.Event()
    errors: list[str] = []
    channel = grpc.insecure_channel(address)
    call = decision_server_pb2_grpc.DecisionServerStub(channel).StreamEvents(
        dpb.StreamEventsRequest(include_data_received=True), timeout=max_s)

    def read() -> None:
        try:
            for message in call:
                book.add(message)
                first.set()
        except grpc.RpcError as error:
            if error.code() not in (grpc.StatusCode.CANCELLED,
                                    grpc.StatusCode.DEADLINE_EXCEEDED):
                errors.append(f"{error.code().name}: {error.details()}")
        finally:
            ended.set()
            first.set()

    started = time.monotonic()
    thread = threading.Thread(target=read, name="events", daemon=True)
    thread.start()
    first.wait(10.0)
    ready()
    while not stop.wait(0.2) and not ended.is_set():
        if time.monotonic() - started > max_s:
            break
    ended_early = ended.is_set() and not stop.is_set()
    call.cancel()
    thread.join(5.0)
    channel.close()
    result = book.result()
    result["errors"] = errors
    result["ended_early"] = ended_early
    return result


# -- the row (bench/groups/soak.py runs the soak) ----------------------------------------------

def build_row(duration_s: float, sample_s: float, teleop: dict, observers: dict,
              camera: dict, events: dict, sampler: Sampler, started_ns: int,
              exited: list[str]) -> dict:
    """The soak's row (see the module's docstring) from what the workers and the sampler
    measured; `started_ns`: time.time_ns() when the Teleoperate worker was started."""
    teleop.pop("latencies_ms", None)  # 300,000 of them: the windows say how they went
    teleop["drain_s"] = DRAIN_S
    if "sent" in teleop:  # ticks neither sent nor skipped as late: the stream ended early
        ticks = int(round(duration_s * TELEOP_RATE_HZ))
        teleop["unsent"] = max(0, ticks - teleop["sent"] - teleop.get("late_skipped", 0))
    for key in ("control", "watchdog", "dependencies", "robot_errors"):
        for entry in events.get(key, []):  # event times from the soak's start, in s
            entry["t_s"] = round((entry.pop("time_ns") - started_ns) / 1e9, 3)
    world_loop = teleop.pop("world_loop", None)
    row = {key: teleop.get(key) for key in ("rate_hz", "delivered_hz", "p50_ms", "p99_ms",
                                             "max_ms", "dropped", "samples")}
    row.update(
        transport=(f"Teleoperate {TELEOP_RATE_HZ} Hz + {OBSERVERS} wrench observers + stereo "
                   "(grpc)"),
        minutes=round(duration_s / 60.0, 3), duration_s=round(duration_s, 1),
        sample_s=sample_s, warmup_fraction=WARMUP_FRACTION, watchdog_s=WATCHDOG_S,
        teleop=teleop, observers=observers, stereo=camera, events=events,
        rss=sampler.processes(), rss_series=sampler.record(), exited=exited)
    if world_loop is not None:
        row["world_loop"] = world_loop  # the teleop worker's count, around its stream
    return row


def summary_line(row: dict) -> str:
    """The progress line's tail: the steepest RSS slope, the side streams, the events."""
    parts = []
    slopes = [(entry["slope_mib_min"], name) for name, entry in row.get("rss", {}).items()
              if entry.get("slope_mib_min") is not None]
    if slopes:
        rate, name = max(slopes)
        parts.append(f"steepest RSS slope {rate:+.2f} MiB/min ({name})")
    teleop = row.get("teleop", {})
    parts.append(f"commands {teleop.get('sent')} sent, {teleop.get('unacked')} unacked")
    observers, camera = row.get("observers", {}), row.get("stereo", {})
    if observers.get("observer_delivered_hz_mean") is not None:
        parts.append(f"observers {observers['observer_delivered_hz_mean']:.1f} Hz each")
    if camera.get("delivered_hz") is not None:
        parts.append(f"stereo {camera['delivered_hz']:.1f} fps")
    events = row.get("events", {})
    parts.append(f"{events.get('control_changes')} control changes, "
                 f"{events.get('leases_lost')} leases lost, {events.get('watchdog_trips')} "
                 "watchdog trips")
    return "; ".join(parts)
