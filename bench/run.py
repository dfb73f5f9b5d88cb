"""The bench run: start a slave station of its own, run the groups the plan wants in order
(each a module of bench/groups/, GROUP_MODULES), stop it all, write the results.

The station (world, proxy_robot, force_sensor, emergency_stop; stereo_camera per source when
its scenarios run) listens on loopback port 0 (each service reports the port it bound) with a
shared-memory name of its own, so it never meets a `make serve` or a test. Every measuring
client is a separate worker process (worker.py); the baselines' servers are separate processes
too (baseline_server.py). Baselines run right after the project's scenarios they are compared
with, in the same run.

When the command or decision group runs, a twin of the station's services (proxy_robot,
force_sensor, emergency_stop, and a DecisionServer when needed) serves mutual TLS with a PKI
made for the run in its scratch directory; it joins the same world, which one of the two
drives at a time. `command_1000_tls` runs right after its plaintext twin; `teleop_1000_tls`
in pairs interleaved with it, the TLS station driving for its legs.

teleop_1000_mcap and force_1000_mcap (issue #17, recording.py) repeat teleop_1000 and
force_1000 right after them, recording in MCAP: the DecisionServer (the same process) records
the Teleoperate session; the wrench subscriber records each sample it receives. They run as
interleaved pairs in balanced order, off, on, on, off... (Plan.overhead_pairs, an even
number; the twin's own run is the first off leg), and are judged on the median of the pairs'
ratios (report.interleaved; Session.mcap_twin in bench/session.py).

The results go to results/latest.json and raw_latencies.json, with the plots (plots.py), and
the terminal report (report.table) is printed; the network and video rows carry their own run
and their own table and figure (OWN_RUN_GROUPS), so a run of those groups alone merges its
row into the latest.json already there.
"""

from __future__ import annotations

import json
import os
import signal
import sys
import time
from pathlib import Path

from bench import goals, network, plots, report, video
from bench.groups import (
    baselines,
    closed_loop,
    command,
    decision,
    estop,
    force,
    franka,
    observers,
    observers_zenoh,
    soak,
    soak_overload,
    stereo,
)
from bench.groups import network as network_group
from bench.groups import video as video_group
from bench.plan import Plan
from bench.procs import ChildFailed
from bench.session import Session
from bench.station import Station
from bench.worldloop import LoopMeter
from services.security import pki

RESULTS_DIR = Path(__file__).resolve().parent / "results"
# Each group's module (bench/groups/), in the order they run: steps(plan), run(session).
GROUP_MODULES = {"command": command, "force": force, "baselines": baselines,
                 "observers": observers, "estop": estop, "decision": decision,
                 "closed_loop": closed_loop, "stereo": stereo, "franka": franka,
                 "observers_zenoh": observers_zenoh, "soak": soak,
                 "soak_overload": soak_overload, "network": network_group,
                 "video": video_group}
# Groups whose row carries its own run, so that a run of them alone merges into a latest.json;
# each has its own table (terminal_lines) and figure (plot, PLOT_FILE).
OWN_RUN_GROUPS = {network.NAME: network, video.NAME: video}


def own_rows(results: dict[str, dict]) -> dict[str, dict]:
    """The rows of OWN_RUN_GROUPS that hold their runs (not a failed or pending row)."""
    return {name: row for name in OWN_RUN_GROUPS
            if (row := results.get(name)) is not None and ("rows" in row or "cells" in row)}


def own_tables(results: dict[str, dict]) -> dict[str, list[str]]:
    """Each own-run row's terminal table (its group's terminal_lines), by row."""
    return {name: OWN_RUN_GROUPS[name].terminal_lines(row)
            for name, row in own_rows(results).items()}


def report_text(results: dict[str, dict]) -> str:
    """The run's terminal report: report.table with the own-run groups' tables."""
    return report.table(results, own_tables(results))


class Bench(Session):
    """The run: start the station (and its TLS twin), run each group the plan wants in
    order, the world loop's row last; then write the results."""

    def __init__(self, plan: Plan, out_dir: Path):
        total = 2 + sum(group.steps(plan) for name, group in GROUP_MODULES.items()
                        if plan.wants(name))  # + the station, the world loop
        super().__init__(plan, out_dir, total)

    def run(self) -> dict[str, dict]:
        started = time.monotonic()
        try:
            self.progress.step(f"starting the station (world, proxy_robot, force_sensor; "
                               f"shared memory {self.shm})"
                               + (", and their twins with mutual TLS" if self.plan.tls else ""))
            self.station.start()
            if self.plan.tls:
                self.tls = self._start_tls_station()
            self.station.arm_ready()
            self.loop = LoopMeter(self.shm)
            self.progress.done("up")
            for name, group in GROUP_MODULES.items():
                if self.plan.wants(name):
                    group.run(self)
            self._world_loop()
        finally:
            if self.loop is not None:
                self.loop.close()
            self.procs.stop_all()
            _remove_segment(self.shm)
        self.elapsed_s = time.monotonic() - started
        return self.results

    def _start_tls_station(self) -> Station:
        """proxy_robot, force_sensor and emergency_stop again, serving mutual TLS, on the same
        world; the PKI and the audit logs in the run's scratch directory (removed with it)."""
        tls_dir = self.procs.scratch / "pki"
        pki.init(tls_dir)
        station = Station(self.procs, self.shm, tls_dir, self.procs.scratch / "audit",
                          world=self.station.world)
        station.start()
        return station

    def _world_loop(self) -> None:
        """The world_loop row: the loop's overruns from the station's start to here."""
        self.progress.step("world_loop: the world's 1 kHz loop over the whole run (shared "
                           "memory counters)")
        try:
            result = self.loop.row()
        except RuntimeError as error:
            return self.fail(["world_loop"], error)
        self.results["world_loop"] = result
        self.progress.done(f"{result['steps']} steps, {result['overruns']} overruns "
                           f"({report.fmt(result['overrun_pct'], 3)} %), "
                           f"{result['dropped_steps']} dropped "
                           f"{self.verdict(goals.judge('world_loop', self.results))}")

    # -- output -----------------------------------------------------------------------------

    def write(self) -> list[Path]:
        self.out_dir.mkdir(parents=True, exist_ok=True)
        ratios = report.add_ratios(self.results)
        goals.add_goals(self.results)
        machine = report.machine()
        machine["load_avg_at_end"] = list(os.getloadavg())
        machine["load_avg_at_start"] = self.load_at_start
        info = {"machine": machine, "quick": self.plan.quick,
                "run_s": round(self.elapsed_s, 1), "world_shm": self.shm}
        latest = self.out_dir / "latest.json"
        figures, own = [], {}
        for name, row in own_rows(self.results).items():
            module = OWN_RUN_GROUPS[name]
            # The network and video rows carry their own run, so that each can live beside
            # another run's.
            row["run"] = {"time": time.strftime("%Y-%m-%dT%H:%M:%S%z"), **info,
                          "world_loop": self.results.get("world_loop")}
            figures.append(module.plot(row, self.out_dir / module.PLOT_FILE))
            own[name] = row
        # The network and video groups alone: into the latest.json there, the rest kept.
        if own and set(self.plan.only) <= set(OWN_RUN_GROUPS) and latest.exists() and all(
                [report.merge_row(latest, name, row) for name, row in own.items()]):
            return [latest, *figures]
        written = dict(self.results)
        for name in OWN_RUN_GROUPS:
            previous = report.previous_row(latest, name) if name not in self.results else None
            if previous is not None:  # a run without the group keeps the one there
                written[name] = previous
        report.write_json(latest, written, ratios, info)
        raw = self.out_dir / "raw_latencies.json"
        raw.write_text(json.dumps(self.raw))
        return [latest, raw, *plots.write_plots(self.out_dir, self.results, self.raw), *figures]


def _remove_segment(name: str) -> None:
    """A world that had to be killed leaves its segment behind: remove it."""
    path = Path("/dev/shm") / name
    if path.exists():
        try:
            path.unlink()
        except OSError:
            pass


def run(plan: Plan, out_dir: Path = RESULTS_DIR) -> int:
    def on_sigterm(signum, _frame):
        raise KeyboardInterrupt(f"signal {signum}")

    signal.signal(signal.SIGTERM, on_sigterm)
    signal.signal(signal.SIGINT, signal.default_int_handler)  # even if started with it ignored
    bench = Bench(plan, out_dir)
    try:
        results = bench.run()
    except KeyboardInterrupt:
        print("\ninterrupted: the station and every worker were stopped", file=sys.stderr)
        return 130
    except ChildFailed as error:
        print(f"\nthe station did not start: {error}", file=sys.stderr)
        return 1
    files = bench.write()
    print()
    print(f"telerobot bench ({'quick' if plan.quick else 'full'} run, "
          f"{bench.elapsed_s:.0f} s, {report.machine()['cores']} cores, "
          f"{report.machine()['cpu_model']})")
    print(report_text(results))
    print()
    for path in files:
        print(f"wrote {path.relative_to(Path.cwd()) if path.is_relative_to(Path.cwd()) else path}")
    return 0
