"""The bench run: start a slave station of its own, run the scenarios in order, stop it all.

The station (world, proxy_robot, force_sensor, emergency_stop; stereo_camera per source when
its scenarios run) listens on loopback port 0 (each service reports the port it bound) with a
shared-memory name of its own, so it never meets a `make serve` or a test. Every measuring
client is a separate worker process (worker.py); the baselines' servers are separate processes
too (baseline_server.py). Baselines run right after the project's scenarios they are compared
with, in the same run.

When the command or decision group runs, a twin of the station's services (proxy_robot,
force_sensor, emergency_stop, and a DecisionServer when needed) serves mutual TLS with a PKI
made for the run in its scratch directory; it joins the same world, which one of the two
drives at a time. Its scenarios (`*_tls`) run right after their plaintext twins.

teleop_1000_mcap and force_1000_mcap (issue #17, recording.py) repeat teleop_1000 and
force_1000 right after them, recording in MCAP: the DecisionServer (the same process) records
the Teleoperate session; the wrench subscriber records each sample it receives. They run as
interleaved pairs, off, on, off, on... (Plan.overhead_pairs; the twin's own run is the first
off leg), and are judged on the median of the pairs' ratios (report.interleaved).
"""

from __future__ import annotations

import contextlib
import json
import os
import signal
import sys
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path

import grpc

from bench import goals, network, plots, report, soak, stereo, video, worldloop
from bench.procs import Child, ChildFailed, ProcessSet, unique_shm_name
from bench.stats import ratio
from bench.worldloop import LoopMeter
from services.runtime.children import refused_address
from services.security import pki
from services.security.audit import AUDIT_DIR_ENV
from services.world.shm_layout import SHM_NAME_ENV
from telerobot.v1 import (
    force_sensor_pb2,
    force_sensor_pb2_grpc,
    proxy_robot_pb2,
    proxy_robot_pb2_grpc,
    types_pb2,
)
from wire.tls import TLS_DIR_ENV, ChannelSecurity, open_channel

RESULTS_DIR = Path(__file__).resolve().parent / "results"
SETUP_TIMEOUT_S = 10.0
OBSERVERS_PER_PROCESS = 8
# With TLS, ProxyRobot's inner port takes commands only from the station's or an admin's
# certificate: the bench's own set-up calls and the command worker present the admin one.
ADMIN_IDENTITY = "admin"
OPERATOR_IDENTITY = "operator"  # Teleoperate needs the operator role (and binds the lease)


@dataclass(frozen=True)
class Plan:
    """How long each scenario runs; `quick` shortens all (`make bench QUICK=1`)."""

    quick: bool
    command_rates: tuple[int, ...] = (50, 500, 1000)
    force_rates: tuple[tuple[int, int], ...] = ((1000, 1), (120, 8))  # (name, decimation)
    observer_counts: tuple[int, ...] = (0, 1, 4, 16, 32)
    observer_decimation: int = 10
    load_concurrency: int = 200
    stereo_sources: tuple[str, ...] = ("pattern", "sim")
    stereo_modes: tuple[str, ...] = ("single", "double")
    stereo_source_fps: float = 30.0
    only: tuple[str, ...] = field(default_factory=tuple)
    profile: bool = False  # py-spy the DecisionServer and ProxyRobot at 1 kHz (bench/profile.py)
    soak_minutes: float | None = None  # the soak's length; None: 10 minutes, 1 when quick
    video_s: float | None = None  # each video probe's length; None: video.PROBE_S (quick: less)
    video_long_s: float | None = None  # the video group's long run; None: video.LONG_S
    video_source: str | None = None  # the video group's camera source; None: video.SOURCE

    @property
    def command_s(self) -> float:
        return 2.0 if self.quick else 8.0

    @property
    def force_s(self) -> float:
        return 2.5 if self.quick else 10.0

    @property
    def overhead_pairs(self) -> int:
        """The interleaved (recording off, on) pairs of an `_mcap` row (issue #17)."""
        return 3 if self.quick else 5

    # Each leg of those pairs after the twin's own run (the first off leg, as long as the
    # twin): the quick run's length, enough for a steady p50 and CPU per command.
    overhead_teleop_leg_s: float = 2.0
    overhead_force_leg_s: float = 2.5

    @property
    def observers_s(self) -> float:
        return 2.0 if self.quick else 8.0

    @property
    def estop_trials(self) -> int:
        return 12 if self.quick else 50

    @property
    def closed_loop_trials(self) -> int:
        return 8 if self.quick else 30

    @property
    def stereo_pairs(self) -> int:
        return 20 if self.quick else 120

    @property
    def soak_s(self) -> float:
        if self.soak_minutes is not None:
            return 60.0 * self.soak_minutes
        return 60.0 if self.quick else 600.0

    @property
    def soak_sample_s(self) -> float:
        """How often the soak reads every station process's RSS."""
        return 2.0 if self.soak_s <= 120.0 else 5.0

    def wants(self, group: str) -> bool:
        """Whether `group` runs: the ones asked for with --only, else every default group
        (the soak and the network experiment run only when asked for: they take minutes).
        The video rows (bench/video.py) are part of the network group, and a group alone."""
        if not self.only:
            return group in DEFAULT_GROUPS
        return group in self.only or (group == video.NAME and network.NAME in self.only)

    @property
    def tls(self) -> bool:
        """Whether a group with a TLS variant runs (then the TLS station is started)."""
        return self.wants("command") or self.wants("decision")


GROUPS = ("command", "force", "baselines", "observers", "estop", "decision", "closed_loop",
          "stereo", "soak", "network", "video")
# `make bench`; the soak and the network experiment (bench/network.py, and its video rows,
# bench/video.py) take minutes.
DEFAULT_GROUPS = tuple(group for group in GROUPS if group not in ("soak", "network", "video"))
# Groups whose row carries its own run, so that a run of them alone merges into a latest.json.
OWN_RUN_GROUPS = {network.NAME: network, video.NAME: video}


class Progress:
    """One line per step on stderr: [step/total elapsed] what, then its headline figure."""

    def __init__(self, total: int, on_step: Callable[[], None] = lambda: None):
        self.total, self.index, self.started = total, 0, time.monotonic()
        self.on_step = on_step  # a scenario starts: the world-loop counters take a mark

    def step(self, text: str) -> None:
        self.on_step()
        self.index += 1
        elapsed = time.monotonic() - self.started
        print(f"[{self.index:2d}/{self.total} {elapsed:5.0f}s] {text} ...", end="",
              file=sys.stderr, flush=True)
        self._open = True  # the step's line waits for its figures

    def done(self, text: str) -> None:
        prefix = " " if self._open else "            ... "
        print(f"{prefix}{text}", file=sys.stderr, flush=True)
        self._open = False

    def note(self, text: str) -> None:
        """A line of its own, even in the middle of a step's line."""
        print(f"{chr(10) if self._open else ''}            {text}", file=sys.stderr,
              flush=True)
        self._open = False

    _open = False


class Station:
    """The slave station's processes for this run, and the set-up calls the bench makes.

    With `tls_dir` (a PKI from services.security.pki) its services serve mutual TLS and write
    their audit logs to `audit_dir`, and the bench's calls to them present the admin
    certificate. `world`: a running world to join (its shared memory) instead of starting
    one; only one station drives a world at a time (arm_ready, release)."""

    def __init__(self, procs: ProcessSet, shm_name: str, tls_dir: Path | None = None,
                 audit_dir: Path | None = None, world: Child | None = None):
        self.procs = procs
        self.shm = shm_name
        self.tls_dir = tls_dir
        self.security = ChannelSecurity(tls_dir, ADMIN_IDENTITY)  # plaintext without tls_dir
        self.env = ({TLS_DIR_ENV: str(tls_dir), AUDIT_DIR_ENV: str(audit_dir)}
                    if tls_dir else {})
        self.suffix = "_tls" if tls_dir else ""  # of its processes' names
        self.world = world
        self.address: dict[str, str] = {}  # service -> host:port, from its ready line

    def client_params(self, identity: str) -> dict:
        """A worker's parameters to reach this station: its TLS directory and the identity
        whose certificate to present; none for plaintext."""
        return {"tls_dir": str(self.tls_dir), "identity": identity} if self.tls_dir else {}

    def start(self) -> None:
        if self.world is None:
            self.world, self.address["world"] = self.procs.run_service("world")
        services = ("proxy_robot", "force_sensor", "emergency_stop")
        started = [self.procs.start_service(service, name=service + self.suffix, env=self.env)
                   for service in services]
        for service, child in zip(services, started, strict=True):
            self.address[service] = child.wait_ready(service, timeout_s=60.0)
        self.proxy, self.sensor = started[0], started[1]

    def arm_ready(self) -> None:
        """ProxyRobot connected, initialized and not stopped; the sensor reading. Also brings
        them back after a hiccup (on an overloaded machine a world that has not stepped for
        100 ms counts as gone: the proxy drops its link, the sensor stops sampling)."""
        for child in (self.world, self.proxy, self.sensor):
            if child.process.poll() is not None:
                raise ChildFailed(f"a station process died: {child.describe()}")
        with open_channel(self.address["proxy_robot"], security=self.security) as channel:
            robot = proxy_robot_pb2_grpc.ProxyRobotStub(channel)
            status = robot.GetStatus(proxy_robot_pb2.GetStatusRequest(),
                                     timeout=SETUP_TIMEOUT_S).status
            if status == types_pb2.ROBOT_STATUS_NOT_CONNECTED:
                status = robot.Connect(proxy_robot_pb2.ConnectRequest(),
                                       timeout=SETUP_TIMEOUT_S).status
            if status in (types_pb2.ROBOT_STATUS_ESTOPPED, types_pb2.ROBOT_STATUS_FAULT):
                status = robot.Reset(proxy_robot_pb2.ResetRequest(),
                                     timeout=SETUP_TIMEOUT_S).status
            if status == types_pb2.ROBOT_STATUS_CONNECTED:
                robot.Initialize(proxy_robot_pb2.InitializeRequest(), timeout=SETUP_TIMEOUT_S)
        with open_channel(self.address["force_sensor"], security=self.security) as channel:
            sensor = force_sensor_pb2_grpc.ForceSensorStub(channel)
            sensor.StartReading(force_sensor_pb2.StartReadingRequest(), timeout=SETUP_TIMEOUT_S)

    def release(self) -> None:
        """ProxyRobot disconnected (the world's command record is free for another driver)
        and the sensor stopped (one sampler at a time)."""
        with open_channel(self.address["proxy_robot"], security=self.security) as channel:
            proxy_robot_pb2_grpc.ProxyRobotStub(channel).Disconnect(
                proxy_robot_pb2.DisconnectRequest(), timeout=SETUP_TIMEOUT_S)
        with open_channel(self.address["force_sensor"], security=self.security) as channel:
            force_sensor_pb2_grpc.ForceSensorStub(channel).StopReading(
                force_sensor_pb2.StopReadingRequest(), timeout=SETUP_TIMEOUT_S)


class Bench:
    def __init__(self, plan: Plan, out_dir: Path):
        self.plan = plan
        self.out_dir = out_dir
        self.shm = unique_shm_name()
        self.procs = ProcessSet({SHM_NAME_ENV: self.shm})
        self.station = Station(self.procs, self.shm)
        self.tls: Station | None = None  # the TLS twin, when plan.tls
        self.driver = self.station  # the station driving the world (one at a time)
        self.results: dict[str, dict] = {}
        self.raw: dict[str, list[float]] = {}
        self.progress = Progress(self._count_steps(), on_step=self._mark_loop)
        self.load_at_start = list(os.getloadavg())
        self.loop: LoopMeter | None = None  # once the world is up

    def _count_steps(self) -> int:
        p = self.plan
        counts = {"command": 2, "force": len(p.force_rates) + 1, "baselines": 2,
                  "observers": len(p.observer_counts), "estop": 4, "decision": 7 + p.profile,
                  "closed_loop": 1,
                  "stereo": len(p.stereo_sources) * len(p.stereo_modes), "soak": 1,
                  "network": len(network.row_specs(p.quick)), "video": video.step_count(p)}
        return 2 + sum(n for group, n in counts.items() if p.wants(group))  # + station, loop

    # -- running ----------------------------------------------------------------------------

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
            steps: list[tuple[str, Callable[[], None]]] = [
                ("command", self.commands), ("force", self.force),
                ("baselines", self.baselines), ("observers", self.observers),
                ("estop", self.estop), ("decision", self.decision),
                ("closed_loop", self.closed_loop),
                ("stereo", self.stereo), ("soak", self.soak), ("network", self.network),
                ("video", self.video)]
            for group, step in steps:
                if self.plan.wants(group):
                    step()
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

    @contextlib.contextmanager
    def _driving(self, station: Station) -> Iterator[Station]:
        """`station` drives the world (its ProxyRobot connected, its sensor reading) while the
        body runs; then the one that drove before does again."""
        before = self.driver
        before.release()
        self.driver = station
        try:
            station.arm_ready()
            yield station
        finally:
            try:
                station.release()
            except grpc.RpcError as error:  # gone: it drives nothing any more
                self.progress.note(f"releasing the world failed: {_reason(error)}")
            self.driver = before
            before.arm_ready()

    def _record(self, name: str, result: dict) -> None:
        raw = result.pop("latencies_ms", None)
        result.pop("ack_latencies_ms", None)
        if raw:
            self.raw[name] = raw
        # The world loop during this scenario: the worker's own count if it took one (it
        # brackets just the measurement), else the orchestrator's since the scenario began.
        since_mark = self._loop_since_mark()
        if "world_loop" in result:
            result["world_loop"] = worldloop.with_pct(result["world_loop"])
        elif since_mark is not None:
            result["world_loop"] = since_mark
        self.results[name] = result
        for dependent in goals.dependents(name):  # a baseline came: judge what waited for it
            if dependent in self.results:
                judged = goals.judge(dependent, self.results)
                self.progress.note(f"{dependent}: {self._verdict(judged)}")

    def _mark_loop(self) -> None:
        if self.loop is not None:
            try:
                self.loop.mark()
            except RuntimeError:
                pass  # the world is stuck or gone: the scenario says so itself

    def _loop_since_mark(self) -> dict | None:
        if self.loop is None:
            return None
        try:
            return self.loop.since_mark()
        except RuntimeError:
            return None

    def _headline(self, name: str) -> str:
        """A scenario's figures, the world loop's overruns during it, its goal and verdict."""
        result = self.results[name]
        if result.get("status") in ("pending", "failed"):
            return (f"{result['status']}: {result.get('reason', '')[:200]} "
                    f"{self._verdict(goals.judge(name, self.results, final=False))}")
        parts = []
        if result.get("delivered_hz") is not None:
            parts.append(f"{result['delivered_hz']:.1f} Hz")
        if result.get("p99_ms") is not None:
            parts.append(f"p50 {result['p50_ms']:.3f} / p99 {result['p99_ms']:.3f} ms")
        loop = result.get("world_loop") or {}
        if loop.get("overrun_pct") is not None:
            parts.append(f"world overruns {loop['overrun_pct']:.2f} %")
        judged = goals.judge(name, self.results, final=False)
        return f"{', '.join(parts) or 'done'} {self._verdict(judged)}"

    @staticmethod
    def _verdict(judged: dict) -> str:
        verdict = goals.verdict_text(judged)
        if verdict == goals.NO_GOAL:
            return "[no goal]"
        why = f" ({'; '.join(judged['misses'])})" if judged["misses"] else ""
        return f"[goal {judged['goal']}: {verdict}{why}]"

    def _fail(self, names: list[str], error: Exception) -> None:
        for name in names:
            self.results[name] = _missing("failed", _reason(error))
        verdicts = [f"{name} {self._verdict(goals.judge(name, self.results))}"
                    for name in names]
        self.progress.done(f"FAILED: {_reason(error)}; " + ", ".join(verdicts))
        print(str(error), file=sys.stderr)
        try:
            self.driver.arm_ready()  # for the scenarios after this one
        except (ChildFailed, grpc.RpcError) as problem:
            print(f"the station did not come back: {problem}", file=sys.stderr)

    def _worker(self, kind: str, params: dict, timeout_s: float, retry: bool = True) -> dict:
        """Run a worker; if it fails, bring the station back and try once more, noting why
        (`retried_after` in the result)."""
        try:
            return self.procs.run_worker(kind, params, timeout_s)
        except ChildFailed as error:
            if not retry:
                raise
            why = _reason(error)
            self.progress.note(f"{kind} worker failed ({why}); retrying once")
            self.driver.arm_ready()
            result = self.procs.run_worker(kind, params, timeout_s)
            for entry in (result.values() if kind in ("command", "teleop") else [result]):
                entry["retried_after"] = why
            return result

    def _rate_worker(self, kind: str, transport: str, address: str, rates,
                     params: dict | None = None, retry: bool = True) -> dict[str, dict]:
        """A command or teleop worker: each of `rates` for plan.command_s over `transport` to
        `address` (`params`: more of the worker's, e.g. Station.client_params);
        {str(rate): result}."""
        plan = self.plan
        return self._worker(kind, {
            "transport": transport, "address": address, "shm": self.shm, "rates": list(rates),
            "duration_s": plan.command_s, **(params or {})},
            60 + 3 * plan.command_s * len(rates), retry)

    def _tls_twin(self, twin: str, measure: Callable[[Station], dict]) -> None:
        """`<twin>_tls`: `measure(station)` on the TLS station, right after `twin` ran on the
        plaintext one, so that both see the same machine."""
        name = f"{twin}_tls"
        self.progress.step(f"{name}: {twin} again, the station serving mutual TLS")
        try:
            with self._driving(self.tls) as tls:
                result = measure(tls)
        except (ChildFailed, grpc.RpcError) as error:
            return self._fail([name], error)
        self._record(name, result)
        versus = report.comparison(result, self.results.get(twin, {}))
        self.progress.done(f"{self._headline(name)} (/ {twin}: {report.ratio_text(versus)})")

    def _mcap_twin(self, twin: str, what: str, off: Callable[[int], dict],
                   on: Callable[[int], dict]) -> None:
        """`<twin>_mcap`: plan.overhead_pairs interleaved pairs right after `twin` ran, on the
        same processes: the twin's run (else `off(0)` if it failed), `on(0)`, then `off(i)`,
        `on(i)` for each pair i after it (`on`: the twin's worker, recording in MCAP). The
        row is report.interleaved's: the first on leg's figures, each pair's ratios and their
        medians, which goals.py judges."""
        name = f"{twin}_mcap"
        count = self.plan.overhead_pairs
        self.progress.step(f"{name}: {twin} again, {what}; {count} pairs interleaved (off, on, "
                           "off, on...)")
        pairs = []
        try:
            for index in range(count):
                base = self.results.get(twin, {})
                first = base if index == 0 and base.get("p50_ms") is not None else None
                leg_off = first if first is not None else off(index)
                leg_on = on(index)
                for leg in (leg_off, leg_on):
                    leg.pop("ack_latencies_ms", None)
                    if index > 0:  # the row keeps pair 1's on leg's (raw_latencies.json)
                        leg.pop("latencies_ms", None)
                pairs.append((leg_off, leg_on))
                versus = report.comparison(leg_on, leg_off)
                self.progress.note(f"{name} pair {index + 1}: {report.ratio_text(versus)}")
        except ChildFailed as error:
            return self._fail([name], error)
        result = report.interleaved(pairs)
        if pairs[0][0] is not self.results.get(twin):  # the twin failed: pair 1 had its own
            result["overhead_first_off"] = "a leg of its own (the twin's run failed)"
        self._record(name, result)
        self.progress.done(f"{self._headline(name)} (medians of {count} pairs, on / off: "
                           f"{report.overhead_text(result)})")

    def commands(self) -> None:
        plan = self.plan
        names = [f"command_{rate}" for rate in plan.command_rates]
        self.progress.step(f"{', '.join(names)}: ProxyRobot.MoveJointsIncremental unary calls, "
                           f"lockstep, {plan.command_s:.0f} s each")
        try:
            results = self._rate_worker("command", "grpc", self.station.address["proxy_robot"],
                                        plan.command_rates)
        except ChildFailed as error:
            self._fail(names, error)
        else:
            for rate in plan.command_rates:
                self._record(f"command_{rate}", results[str(rate)])
            self.progress.done("; ".join(f"{r}: {self._headline(f'command_{r}')}"
                                         for r in plan.command_rates))
        self._tls_twin("command_1000", self._command_tls)

    def _command_tls(self, tls: Station) -> dict:
        """command_1000 on the TLS station's ProxyRobot, the worker presenting the admin
        certificate (its inner port takes commands from the station or an admin)."""
        return self._rate_worker("command", "grpc", tls.address["proxy_robot"], [1000],
                                 tls.client_params(ADMIN_IDENTITY))["1000"]

    def force(self) -> None:
        for rate, decimation in self.plan.force_rates:
            name = f"force_{rate}"
            self.progress.step(f"{name}: StreamWrench, sensor period 1 ms, decimation "
                               f"{decimation} ({1000 / decimation:.0f} Hz)")
            try:
                result = self._force_worker(decimation)
            except ChildFailed as error:
                self._fail([name], error)
            else:
                self._record(name, result)
                self.progress.done(self._headline(name))
            if name == "force_1000":
                self._mcap_twin(name, "the subscriber writing each sample to MCAP (wrench and "
                                "Foxglove arrow, as make teleop --mcap) before its timestamp",
                                self._force_leg, lambda index: self._force_leg(index, True))

    def _force_leg(self, index: int, record: bool = False) -> dict:
        """A leg of force_1000_mcap's pair `index`: force_1000 for overhead_force_leg_s,
        recording into a file of the pair's own when `record`."""
        path = self.procs.scratch / f"force_1000_{index + 1}.mcap"
        return self._force_worker(1, str(path) if record else None,
                                  duration_s=self.plan.overhead_force_leg_s)

    def _force_worker(self, decimation: int, mcap_path: str | None = None,
                      duration_s: float | None = None) -> dict:
        """force_<rate>'s worker (plan.force_s, or `duration_s`); `mcap_path`: recording each
        sample there."""
        duration_s = duration_s or self.plan.force_s
        return self._worker("force", {
            "transport": "grpc", "address": self.station.address["force_sensor"],
            "decimation": decimation, "duration_s": duration_s,
            **({"mcap_path": mcap_path} if mcap_path else {})}, 60 + 3 * duration_s)

    def baselines(self) -> None:
        """The command round trip and the force stream over pyzmq and over plain TCP, with the
        same payloads and the same domain cores (baseline_server.py)."""
        plan = self.plan
        self.station.release()
        try:
            for transport in ("zmq", "tcp"):
                names = ([f"command_{r}_{transport}" for r in plan.command_rates]
                         + [f"force_{r}_{transport}" for r, _ in plan.force_rates])
                label = "pyzmq REQ/REP + PUB/SUB" if transport == "zmq" else "TCP struct framing"
                self.progress.step(f"baselines over {label}: {', '.join(names)}")
                try:
                    try:
                        self._baseline(transport)
                    except ChildFailed as error:  # once more, with a fresh baseline server
                        why = _reason(error)
                        self.progress.note(f"failed ({why}); retrying once")
                        self._baseline(transport)
                        for name in names:
                            self.results[name]["retried_after"] = why
                except ChildFailed as error:
                    for name in names:
                        self.results[name] = _missing("failed", _reason(error))
                    self.progress.done(f"FAILED: {_reason(error)}")
                    continue
                self.progress.done("; ".join(f"{n}: {self._headline(n)}"
                                             for n in names if n in self.results))
        finally:
            self.station.arm_ready()

    def _baseline(self, transport: str) -> None:
        plan = self.plan
        server = self.procs.start(f"baseline_{transport}", [
            "-m", "bench.baseline_server", "--transport", transport, "--shm-name", self.shm])
        try:
            command_address = server.wait_ready("baseline_command", timeout_s=60.0)
            force_address = server.wait_ready("baseline_force", timeout_s=10.0)
            results = self._rate_worker("command", transport, command_address,
                                        plan.command_rates, retry=False)
            for rate in plan.command_rates:
                self._record(f"command_{rate}_{transport}", results[str(rate)])
            for rate, decimation in plan.force_rates:
                self._record(f"force_{rate}_{transport}", self._worker("force", {
                    "transport": transport, "address": force_address,
                    "decimation": decimation, "duration_s": plan.force_s},
                    60 + 3 * plan.force_s, retry=False))
        finally:
            self.procs.stop(server)

    def observers(self) -> None:
        plan = self.plan
        for count in plan.observer_counts:
            name = f"observers_{count}"
            self.progress.step(f"{name}: operator at 1 kHz with {count} observers at "
                               f"{1000 / plan.observer_decimation:.0f} Hz "
                               f"(in {-(-count // OBSERVERS_PER_PROCESS)} processes)")
            retried = None
            try:
                try:
                    result = self._observers_once(count)
                except ChildFailed as error:  # once more, from a fresh start
                    retried = _reason(error)
                    self.progress.note(f"failed ({retried}); retrying once")
                    self.station.arm_ready()
                    result = self._observers_once(count)
            except ChildFailed as error:
                self._fail([name], error)
                continue
            if retried:
                result["retried_after"] = retried
            self._record(name, result)
            self.progress.done(self._headline(name) + f", jitter {result.get('jitter_ms')} ms")

    def _observers_once(self, count: int) -> dict:
        """Observer processes streaming, then the operator's 1 kHz stream measured."""
        plan = self.plan
        address = self.station.address["force_sensor"]
        groups = []
        try:
            left = count
            while left > 0:
                size = min(OBSERVERS_PER_PROCESS, left)
                left -= size
                groups.append(self.procs.start_worker("observers", {
                    "address": address, "count": size,
                    "decimation": plan.observer_decimation, "max_s": plan.observers_s + 60}))
            for group in groups:
                self.procs.wait_worker_ready(group, 60.0)
            # Where the CPU goes while the operator is measured: the station's busy
            # processes, and the observers' (on the same cores, as the bench runs).
            watched = {name: pid for name in ("force_sensor", "world")
                       if (pid := self._pid(name)) is not None}
            watched.update({f"observers {i + 1}": group.pid for i, group in enumerate(groups)})
            result = self.procs.run_worker("force", {
                "transport": "grpc", "address": address, "decimation": 1,
                "duration_s": plan.observers_s, "watch_pids": watched},
                60 + 3 * plan.observers_s)
            observed = []
            for group in groups:
                group.stop(grace_s=5.0)
                observed.append(self.procs.finish_worker(group, 10.0))
        finally:
            for group in groups:
                if group.process.poll() is None:
                    self.procs.stop(group)
        result["observers"] = count
        result["observer_rate_hz"] = 1000 / plan.observer_decimation
        if observed:
            means = [o["observer_delivered_hz_mean"] for o in observed]
            sizes = [o["observers"] for o in observed]
            result["observer_delivered_hz_mean"] = round(
                sum(m * s for m, s in zip(means, sizes, strict=True)) / sum(sizes), 2)
            result["observer_delivered_hz_min"] = min(o["observer_delivered_hz_min"]
                                                      for o in observed)
            result["observer_errors"] = [e for o in observed for e in o["errors"]][:5]
        return result

    def estop(self) -> None:
        """estop_idle and estop_under_load through the emergency-stop band (the framework's
        stop path), and estop_under_load_proxy: ProxyRobot's own EmergencyStop under the same
        load, the path the band exists to avoid."""
        proxy = self.station.address["proxy_robot"]
        band = self.station.address["emergency_stop"]
        self._estop_trials("estop_idle", "EmergencyStop on the band of a moving arm -> hold "
                           "latched", proxy, band, loaded=False)
        self._estop_trials("estop_under_load", "the same with "
                           f"{self.plan.load_concurrency} concurrent GetState calls on "
                           "ProxyRobot's low lane", proxy, band, loaded=True)
        self._estop_trials("estop_under_load_proxy", "the same load, the stop sent to "
                           "ProxyRobot itself", proxy, proxy, loaded=True)

    def _estop_trials(self, name: str, what: str, proxy: str, stop_address: str,
                      loaded: bool) -> None:
        plan = self.plan
        timeout = 60 + plan.estop_trials * 3
        self.progress.step(f"{name}: {what}, {plan.estop_trials} trials")
        load = None
        try:
            if loaded:
                load = self.procs.start_worker("load", {
                    "address": proxy, "concurrency": plan.load_concurrency,
                    "max_s": timeout + 30})
                self.procs.wait_worker_ready(load, 60.0)
                time.sleep(0.5)  # let the low lane fill up
            result = self._worker("estop", {"address": proxy, "stop_address": stop_address,
                                            "shm": self.shm, "trials": plan.estop_trials,
                                            "label": name}, timeout)
            if load is not None:
                load.stop(grace_s=10.0)
                load_result = self.procs.finish_worker(load, 10.0)
                load = None
        except ChildFailed as error:
            if load is not None:
                self.procs.stop(load)
            return self._fail([name], error)
        extra = ""
        if loaded:
            idle = self.results.get("estop_idle", {})
            result.update(load_calls_per_s=load_result["calls_per_s"],
                          load_codes=load_result["codes"],
                          load=f"{plan.load_concurrency} concurrent ProxyRobot.GetState, "
                               "telerobot-lane: low",
                          vs_idle={"p50": ratio(result.get("p50_ms"), idle.get("p50_ms")),
                                   "p99": ratio(result.get("p99_ms"), idle.get("p99_ms"))})
            extra = f" (load {load_result['calls_per_s']:.0f} calls/s)"
        self._record(name, result)
        self.progress.done(self._headline(name) + extra)

    def decision(self) -> None:
        """Through the DecisionServer, the operator's one address: teleop_<rate> (master
        commands streamed on Teleoperate, pipelined; teleop_1000_lockstep the same sent
        lockstep, a diagnostic; teleop_1000_mcap teleop_1000 recorded in MCAP, in pairs
        interleaved with it), then
        teleop_1000_tls through a DecisionServer of the TLS station, teleop_1000_zmq (the same
        DecisionCore over pyzmq) with the DecisionServer stopped, so nothing else follows
        ProxyRobot's streams meanwhile; then, through a fresh DecisionServer, the emergency
        stop idle and under its intended load (200 RunAction BusyWork on the low lane)."""
        teleop = [f"teleop_{rate}" for rate in self.plan.command_rates]
        self._with_decision_server(teleop + ["teleop_1000_lockstep", "teleop_1000_mcap"],
                                   self._teleop)
        self._tls_twin("teleop_1000", self._teleop_tls)
        if self.plan.profile:
            self._with_decision_server(["profile"], self._profile)
        self._teleop_baseline()
        self._with_decision_server(["estop_ds_idle", "estop_ds_busywork"], self._estop_ds)

    @contextlib.contextmanager
    def _decision_server(self, station: Station, stereo_address: str | None = None
                         ) -> Iterator[str]:
        """A DecisionServer process in front of `station` (with its TLS, if any) while the
        body runs: its address. ChildFailed if it does not start. `stereo_address`: a stereo
        camera serving (the soak's); none by default."""
        server, address = self.procs.run_service("decision_server", [
            "--proxy-robot-address", station.address["proxy_robot"],
            "--force-sensor-address", station.address["force_sensor"],
            "--stereo-camera-address", stereo_address or refused_address(),
            "--emergency-stop-address", station.address["emergency_stop"],
            "--recordings-dir", str(self.procs.scratch / "recordings")],
            name="decision_server" + station.suffix, env=station.env)
        try:
            yield address
        finally:
            self.procs.stop(server)

    def _with_decision_server(self, names: list[str], body: Callable[[str], None]) -> None:
        """A DecisionServer process in front of the station while `body(address)` runs (it
        deals with its own failures); if it does not start, `names` fail."""
        with contextlib.ExitStack() as stack:
            try:
                address = stack.enter_context(self._decision_server(self.station))
            except ChildFailed as error:
                self.progress.step(f"starting the DecisionServer for {', '.join(names)}")
                return self._fail(names, error)
            body(address)

    def _profile(self, address: str) -> None:
        """Teleoperate at 1 kHz again, with py-spy on the DecisionServer and ProxyRobot."""
        from bench.profile import Recording

        seconds = self.plan.command_s + 1
        self.progress.step(f"profile: Teleoperate at 1 kHz for {seconds:.0f} s with py-spy on "
                           "decision_server and proxy_robot")
        pids = {child.name: child.pid for child in self.procs.children
                if child.name in ("decision_server", "proxy_robot")
                and child.process.poll() is None}
        recording = Recording(pids, seconds, self.out_dir)
        try:
            self._rate_worker("teleop", "grpc", address, [1000])
        except ChildFailed as error:
            self.progress.note(f"profile run failed: {error}")
        summaries = recording.finish()
        self.progress.done(f"raw stacks in {', '.join(str(p) for p in recording.paths.values())}")
        for name, text in summaries.items():
            print(f"\n== {name}, Teleoperate at 1 kHz: {text}", file=sys.stderr)

    def _teleop(self, address: str) -> None:
        plan = self.plan
        name = "teleop_1000_lockstep"
        self.progress.step(f"{name} (diagnostic): Teleoperate at 1 kHz offered, each command "
                           f"waited for (the old way), {plan.command_s:.0f} s")
        try:
            result = self._rate_worker("command", "teleop", address, [1000])["1000"]
            result["diagnostic"] = "lockstep: each command waits for the previous one's ack"
            self._record(name, result)
            self.progress.done(self._headline(name))
        except ChildFailed as error:
            self._fail([name], error)
        names = [f"teleop_{rate}" for rate in plan.command_rates]
        self.progress.step(f"{', '.join(names)}: DecisionServer.Teleoperate, commands streamed "
                           f"at the offered rate (pipelined), {plan.command_s:.0f} s each")
        server = {"server_pid": self._pid("decision_server")}  # its CPU per command
        try:
            results = self._rate_worker("teleop", "grpc", address, plan.command_rates, server)
        except ChildFailed as error:  # the recording's twin has nothing to compare with
            return self._fail([*names, "teleop_1000_mcap"], error)
        for rate in plan.command_rates:
            self._record(f"teleop_{rate}", results[str(rate)])
        lockstep = self.results.get(name, {})
        if "teleop_1000" in self.results and lockstep.get("delivered_hz") is not None:
            self.results["teleop_1000"].update(lockstep_delivered_hz=lockstep["delivered_hz"],
                                               lockstep_p99_ms=lockstep["p99_ms"])
        self.progress.done("; ".join(f"{r}: {self._headline(f'teleop_{r}')}"
                                     for r in plan.command_rates))
        # The same DecisionServer, right after. teleop_1000 moved +y: each on leg goes back
        # (-y), each off leg after it out again, so the arm swings about where it was.
        leg = {"duration_s": plan.overhead_teleop_leg_s, **server}
        self._mcap_twin("teleop_1000", "the DecisionServer recording the session in MCAP",
                        lambda index: self._rate_worker("teleop", "grpc", address, [1000], {
                            "first_sign": 1.0, **leg})["1000"],
                        lambda index: self._rate_worker("teleop", "grpc", address, [1000], {
                            "first_sign": -1.0, **leg,
                            "record_dir": str(self.procs.scratch / "recordings")})["1000"])

    def _pid(self, name: str) -> int | None:
        """The process id of the running child `name` (a service), if there is one."""
        return next((child.pid for child in self.procs.children
                     if child.name == name and child.process.poll() is None), None)

    def _teleop_tls(self, tls: Station) -> dict:
        """teleop_1000 through a DecisionServer of the TLS station (which presents its own
        certificate to ProxyRobot), the worker presenting an operator's."""
        with self._decision_server(tls) as address:
            return self._rate_worker("teleop", "grpc", address, [1000],
                                     tls.client_params(OPERATOR_IDENTITY))["1000"]

    def _teleop_baseline(self) -> None:
        """teleop_1000_zmq: the DecisionServer's DecisionCore and GrpcSlave (to this station's
        ProxyRobot and ForceSensor) behind pyzmq DEALER/ROUTER, streamed the same way."""
        plan = self.plan
        name = "teleop_1000_zmq"
        self.progress.step(f"{name}: the same DecisionCore over pyzmq DEALER/ROUTER, "
                           f"pipelined at 1 kHz, {plan.command_s:.0f} s")
        server = self.procs.start("baseline_teleop", [
            "-m", "bench.baseline_server", "--transport", "zmq-teleop",
            "--proxy-robot-address", self.station.address["proxy_robot"],
            "--force-sensor-address", self.station.address["force_sensor"]])
        try:
            address = server.wait_ready("baseline_teleop", timeout_s=60.0)
            result = self._rate_worker("teleop", "zmq", address, [1000])["1000"]
        except ChildFailed as error:
            return self._fail([name], error)
        finally:
            self.procs.stop(server)
        self._record(name, result)
        self.progress.done(self._headline(name))

    def _estop_ds(self, address: str) -> None:
        plan = self.plan
        params = {"address": address, "shm": self.shm, "trials": plan.estop_trials,
                  "decision_server": True}
        timeout = 60 + plan.estop_trials * 3
        self.progress.step("estop_ds_idle: EmergencyStop through the DecisionServer, idle")
        try:
            result = self._worker("estop", {**params, "label": "ds idle"}, timeout)
            self._record("estop_ds_idle", result)
            self.progress.done(self._headline("estop_ds_idle"))
        except ChildFailed as error:
            self._fail(["estop_ds_idle"], error)
        self.progress.step(f"estop_ds_busywork: the same with {plan.load_concurrency} "
                           "concurrent RunAction BusyWork (20 ms each) on the low lane")
        load = None
        try:
            load = self.procs.start_worker("load", {
                "address": address, "target": "decision_server",
                "concurrency": plan.load_concurrency, "max_s": timeout + 30})
            self.procs.wait_worker_ready(load, 60.0)
            time.sleep(0.5)
            result = self._worker("estop", {**params, "label": "ds busywork"}, timeout)
            load.stop(grace_s=10.0)
            load_result = self.procs.finish_worker(load, 10.0)
            load = None
        except ChildFailed as error:
            if load is not None:
                self.procs.stop(load)
            return self._fail(["estop_ds_busywork"], error)
        idle = self.results.get("estop_ds_idle", {})
        result.update(load_calls_per_s=load_result["calls_per_s"],
                      load_codes=load_result["codes"],
                      load="200 concurrent DecisionServer.RunAction BusyWork (20 ms), "
                           "telerobot-lane: low",
                      vs_idle={"p50": ratio(result.get("p50_ms"), idle.get("p50_ms")),
                               "p99": ratio(result.get("p99_ms"), idle.get("p99_ms"))})
        self._record("estop_ds_busywork", result)
        self.progress.done(self._headline("estop_ds_busywork")
                           + f" (load {load_result['calls_per_s']:.0f} calls/s)")

    def _world_loop(self) -> None:
        """The world_loop row: the loop's overruns from the station's start to here."""
        self.progress.step("world_loop: the world's 1 kHz loop over the whole run (shared "
                           "memory counters)")
        try:
            result = self.loop.row()
        except RuntimeError as error:
            return self._fail(["world_loop"], error)
        self.results["world_loop"] = result
        self.progress.done(f"{result['steps']} steps, {result['overruns']} overruns "
                           f"({report.fmt(result['overrun_pct'], 3)} %), "
                           f"{result['dropped_steps']} dropped "
                           f"{self._verdict(goals.judge('world_loop', self.results))}")

    def closed_loop(self) -> None:
        plan = self.plan
        self.progress.step(f"closed_loop: in contact (1 mm preload), press 2 mm further -> "
                           f"force > 2 N at the operator, {plan.closed_loop_trials} trials")
        try:
            result = self._worker("closed_loop", {
                "proxy_address": self.station.address["proxy_robot"],
                "force_address": self.station.address["force_sensor"],
                "trials": plan.closed_loop_trials}, 90 + plan.closed_loop_trials * 5)
        except ChildFailed as error:
            return self._fail(["closed_loop"], error)
        self._record("closed_loop", result)
        self.progress.done(self._headline("closed_loop"))

    def soak(self) -> None:
        """The station under a steady load for minutes: RSS, losses, events (soak.py)."""
        soak.run(self)

    def network(self) -> None:
        """The peg-in-hole task across the impairment link (network.py)."""
        network.run(self)

    def video(self) -> None:
        """The stereo stream across the impairment link, H.264 beside JPEG (video.py)."""
        video.run(self)

    def stereo(self) -> None:
        plan = self.plan
        names = [f"stereo_{s}_{m}" for s in plan.stereo_sources for m in plan.stereo_modes]
        reason = stereo.available()
        if reason:
            for name in names:
                self.progress.step(name)
                self.results[name] = _missing("pending", reason)
                self.progress.done("pending")
            return
        for source in plan.stereo_sources:
            try:
                service, address = self.procs.run_service("stereo_camera", [
                    "--source", source, "--width", str(stereo.WIDTH_PX),
                    "--height", str(stereo.HEIGHT_PX), "--fps", str(plan.stereo_source_fps)])
            except ChildFailed as error:
                for mode in plan.stereo_modes:
                    self.progress.step(f"stereo_{source}_{mode}")
                    self._fail([f"stereo_{source}_{mode}"], error)
                continue
            try:
                for mode in plan.stereo_modes:
                    name = f"stereo_{source}_{mode}"
                    self.progress.step(f"{name}: {stereo.WIDTH_PX}x{stereo.HEIGHT_PX} JPEG, "
                                       f"{plan.stereo_pairs} pairs")
                    try:
                        result = self._worker("stereo", {
                            "address": address, "mode": mode, "pairs": plan.stereo_pairs,
                            "source_fps": plan.stereo_source_fps}, 180)
                    except ChildFailed as error:
                        self._fail([name], error)
                        continue
                    self._record(name, result)
                    self.progress.done(self._headline(name))
            finally:
                self.procs.stop(service)

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
        for name, module in OWN_RUN_GROUPS.items():
            row = self.results.get(name)
            if row is None or ("rows" not in row and "cells" not in row):
                continue
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


def _reason(error: Exception) -> str:
    """The most telling line of a worker's failure: a gRPC status' details, else the last."""
    lines = [line.strip() for line in str(error).splitlines() if line.strip()]
    for line in lines:
        if line.startswith("details = "):
            return line.removeprefix("details = ").strip('"')
    return lines[-1] if lines else type(error).__name__


def _missing(status: str, reason: str) -> dict:
    return {"rate_hz": None, "delivered_hz": None, "p50_ms": None, "p99_ms": None,
            "max_ms": None, "dropped": None, "status": status, "reason": reason}


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
    print(report.table(results))
    print()
    for path in files:
        print(f"wrote {path.relative_to(Path.cwd()) if path.is_relative_to(Path.cwd()) else path}")
    return 0
