"""A bench run's session: its station, its results and its progress, and what every group
(bench/groups/) does with them: run a worker (retried once), record a row and judge it, fail
rows with the worker's reason, run a `*_tls` or `*_mcap` twin right after its scenario, put a
DecisionServer in front of a station. bench/run.py makes one and runs the groups in order.
"""

from __future__ import annotations

import contextlib
import os
import sys
import time
from collections.abc import Callable, Iterator
from pathlib import Path

import grpc

from bench import goals, report, worldloop
from bench.plan import Plan
from bench.procs import ChildFailed, ProcessSet, unique_shm_name
from bench.station import Station
from bench.worldloop import LoopMeter
from services.runtime.children import refused_address
from services.world.shm_layout import SHM_NAME_ENV


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


def reason(error: Exception) -> str:
    """The most telling line of a worker's failure: a gRPC status' details, else the last."""
    lines = [line.strip() for line in str(error).splitlines() if line.strip()]
    for line in lines:
        if line.startswith("details = "):
            return line.removeprefix("details = ").strip('"')
    return lines[-1] if lines else type(error).__name__


def missing(status: str, reason: str) -> dict:
    return {"rate_hz": None, "delivered_hz": None, "p50_ms": None, "p99_ms": None,
            "max_ms": None, "dropped": None, "status": status, "reason": reason}


class Session:
    """The run's state, shared by the groups: the plan, the station (and its TLS twin), the
    station driving the world, the results and raw latencies so far, the progress lines and
    the world loop's meter."""

    def __init__(self, plan: Plan, out_dir: Path, total_steps: int):
        self.plan = plan
        self.out_dir = out_dir
        self.shm = unique_shm_name()
        self.procs = ProcessSet({SHM_NAME_ENV: self.shm})
        self.station = Station(self.procs, self.shm)
        self.tls: Station | None = None  # the TLS twin, when plan.tls
        self.driver = self.station  # the station driving the world (one at a time)
        self.results: dict[str, dict] = {}
        self.raw: dict[str, list[float]] = {}
        self.progress = Progress(total_steps, on_step=self.mark_loop)
        self.load_at_start = list(os.getloadavg())
        self.loop: LoopMeter | None = None  # once the world is up

    def record(self, name: str, result: dict) -> None:
        """`result` as row `name` (its raw latencies kept aside for the plots, the world loop
        during it added), and a verdict for each row that waited for it as its baseline."""
        raw = result.pop("latencies_ms", None)
        result.pop("ack_latencies_ms", None)
        if raw:
            self.raw[name] = raw
        # The world loop during this scenario: the worker's own count if it took one (it
        # brackets just the measurement), else the orchestrator's since the scenario began.
        since_mark = self.loop_since_mark()
        if "world_loop" in result:
            result["world_loop"] = worldloop.with_pct(result["world_loop"])
        elif since_mark is not None:
            result["world_loop"] = since_mark
        self.results[name] = result
        for dependent in goals.dependents(name):  # a baseline came: judge what waited for it
            if dependent in self.results:
                judged = goals.judge(dependent, self.results)
                self.progress.note(f"{dependent}: {self.verdict(judged)}")

    def mark_loop(self) -> None:
        if self.loop is not None:
            try:
                self.loop.mark()
            except RuntimeError:
                pass  # the world is stuck or gone: the scenario says so itself

    def loop_since_mark(self) -> dict | None:
        if self.loop is None:
            return None
        try:
            return self.loop.since_mark()
        except RuntimeError:
            return None

    def headline(self, name: str) -> str:
        """A scenario's figures, the world loop's overruns during it, its goal and verdict."""
        result = self.results[name]
        if result.get("status") in ("pending", "failed"):
            return (f"{result['status']}: {result.get('reason', '')[:200]} "
                    f"{self.verdict(goals.judge(name, self.results, final=False))}")
        parts = []
        if result.get("delivered_hz") is not None:
            parts.append(f"{result['delivered_hz']:.1f} Hz")
        if result.get("p99_ms") is not None:
            parts.append(f"p50 {result['p50_ms']:.3f} / p99 {result['p99_ms']:.3f} ms")
        loop = result.get("world_loop") or {}
        if loop.get("overrun_pct") is not None:
            parts.append(f"world overruns {loop['overrun_pct']:.2f} %")
        judged = goals.judge(name, self.results, final=False)
        return f"{', '.join(parts) or 'done'} {self.verdict(judged)}"

    @staticmethod
    def verdict(judged: dict) -> str:
        verdict = goals.verdict_text(judged)
        if verdict == goals.NO_GOAL:
            return "[no goal]"
        why = f" ({'; '.join(judged['misses'])})" if judged["misses"] else ""
        return f"[goal {judged['goal']}: {verdict}{why}]"

    def fail(self, names: list[str], error: Exception) -> None:
        for name in names:
            self.results[name] = missing("failed", reason(error))
        verdicts = [f"{name} {self.verdict(goals.judge(name, self.results))}"
                    for name in names]
        self.progress.done(f"FAILED: {reason(error)}; " + ", ".join(verdicts))
        print(str(error), file=sys.stderr)
        try:
            self.driver.arm_ready()  # for the scenarios after this one
        except (ChildFailed, grpc.RpcError) as problem:
            print(f"the station did not come back: {problem}", file=sys.stderr)

    def worker(self, kind: str, params: dict, timeout_s: float, retry: bool = True) -> dict:
        """Run a worker; if it fails, bring the station back and try once more, noting why
        (`retried_after` in the result)."""
        try:
            return self.procs.run_worker(kind, params, timeout_s)
        except ChildFailed as error:
            if not retry:
                raise
            why = reason(error)
            self.progress.note(f"{kind} worker failed ({why}); retrying once")
            self.driver.arm_ready()
            result = self.procs.run_worker(kind, params, timeout_s)
            for entry in (result.values() if kind in ("command", "teleop") else [result]):
                entry["retried_after"] = why
            return result

    def rate_worker(self, kind: str, transport: str, address: str, rates,
                    params: dict | None = None, retry: bool = True) -> dict[str, dict]:
        """A command or teleop worker: each of `rates` for plan.command_s over `transport` to
        `address` (`params`: more of the worker's, e.g. Station.client_params);
        {str(rate): result}."""
        plan = self.plan
        return self.worker(kind, {
            "transport": transport, "address": address, "shm": self.shm, "rates": list(rates),
            "duration_s": plan.command_s, **(params or {})},
            60 + 3 * plan.command_s * len(rates), retry)

    def tls_twin(self, twin: str, measure: Callable[[Station], dict]) -> None:
        """`<twin>_tls`: `measure(station)` on the TLS station, right after `twin` ran on the
        plaintext one, so that both see the same machine."""
        name = f"{twin}_tls"
        self.progress.step(f"{name}: {twin} again, the station serving mutual TLS")
        try:
            with self.driving(self.tls) as tls:
                result = measure(tls)
        except (ChildFailed, grpc.RpcError) as error:
            return self.fail([name], error)
        self.record(name, result)
        versus = report.comparison(result, self.results.get(twin, {}))
        self.progress.done(f"{self.headline(name)} (/ {twin}: {report.ratio_text(versus)})")

    def mcap_twin(self, twin: str, what: str, off: Callable[[int, float], dict],
                  on: Callable[[int, float], dict], suffix: str = "mcap",
                  reuse_twin: bool = True, pair_count: int | None = None) -> None:
        """`<twin>_mcap`: `pair_count` (plan.overhead_pairs) interleaved pairs right after `twin`
        ran, on the same processes, in balanced order: off, on, then on, off, then off, on...
        so that neither a drift through the row nor the motion's direction favours one side. Pair
        1's off leg is the twin's own run (else, or when not `reuse_twin`, a leg of its own).
        Each leg is `off(pair, sign)` or `on(pair, sign)` (`on`: the twin's worker,
        recording); `sign` alternates from leg to leg, the twin's run being +1, so that a leg
        that moves the arm goes back where the one before went out. The row is
        report.interleaved's: the first on leg's figures, each pair's ratios and their
        medians, which goals.py judges."""
        name = f"{twin}_{suffix}"
        count = pair_count or self.plan.overhead_pairs
        self.progress.step(f"{name}: {twin} again, {what}; {count} pairs interleaved (off, on, "
                           "on, off...)")
        pairs = []
        sign = 1.0  # of the next leg
        try:
            for index in range(count):
                base = self.results.get(twin, {})
                legs = {}
                if reuse_twin and index == 0 and base.get("p50_ms") is not None:
                    legs["off"], sign = base, -sign
                for role in ("off", "on") if index % 2 == 0 else ("on", "off"):
                    if role not in legs:
                        legs[role], sign = (off if role == "off" else on)(index, sign), -sign
                for leg in legs.values():
                    leg.pop("ack_latencies_ms", None)
                    if index > 0:  # the row keeps pair 1's on leg's (raw_latencies.json)
                        leg.pop("latencies_ms", None)
                pairs.append((legs["off"], legs["on"]))
                versus = report.comparison(legs["on"], legs["off"])
                self.progress.note(f"{name} pair {index + 1}: {report.ratio_text(versus)}")
        except ChildFailed as error:
            return self.fail([name], error)
        result = report.interleaved(pairs)
        if reuse_twin and pairs[0][0] is not self.results.get(twin):  # the twin failed
            result["overhead_first_off"] = "a leg of its own (the twin's run failed)"
        self.record(name, result)
        self.progress.done(f"{self.headline(name)} (medians of {count} pairs, on / off: "
                           f"{report.overhead_text(result)})")

    @contextlib.contextmanager
    def driving(self, station: Station) -> Iterator[Station]:
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
                self.progress.note(f"releasing the world failed: {reason(error)}")
            self.driver = before
            before.arm_ready()

    @contextlib.contextmanager
    def decision_server(self, station: Station, stereo_address: str | None = None
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

    def with_decision_server(self, names: list[str], body: Callable[[str], None]) -> None:
        """A DecisionServer process in front of the station while `body(address)` runs (it
        deals with its own failures); if it does not start, `names` fail."""
        with contextlib.ExitStack() as stack:
            try:
                address = stack.enter_context(self.decision_server(self.station))
            except ChildFailed as error:
                self.progress.step(f"starting the DecisionServer for {', '.join(names)}")
                return self.fail(names, error)
            body(address)

    def pid(self, name: str) -> int | None:
        """The process id of the running child `name` (a service), if there is one."""
        return next((child.pid for child in self.procs.children
                     if child.name == name and child.process.poll() is None), None)
