"""soak_overload: Teleoperate at RATE_HZ beside busy co-tenant processes (issue #29).

The station as the bench runs it (world, proxy_robot, force_sensor, emergency_stop) with a
DecisionServer in front, and, started before the session and killed after it, one co-tenant
per core: a plain Python process spinning on CPU (`SPIN_CODE`, not niced), so the station's
processes compete for every core. The operator is a worker process (`python -m bench.worker
overload`, `operate`) using the project's blocking Python client (clients.python
DecisionClient.teleoperate): one session, commands sent with `send_nowait` on absolute
deadlines at RATE_HZ (bench/schedule.py: a tick the sender wakes up a whole period late for is
skipped, `late_skipped`), each STEP_M along base y, the direction flipping every SWING
commands so the arm strokes 2 mm up and down and stays in its workspace.

Before the session and after it (the arm at rest, `at_rest`), ProxyRobot's measured tool pose
is read (GetState on its own port). The session: WARMUP_COMMANDS first (in the motion, not in
the latency), then the measured stream for `Plan.overload_s`, then, while commands are still
unacked (a command the server holds as late is carried until a fresh one comes), a zero
increment every TAIL_PERIOD_S (a master holding still), then heartbeats while the arm settles.

The row, `soak_overload`:

- per third of the measured stream (by send time), p50 and p99 of received -> applied
  (ack.apply_time - ack.receive_time, both the server's clock) and sent -> applied
  (ack.apply_time - the command's send_time, this host's clock for both: client and server
  share it), over the commands whose ack says they moved the arm (APPLIED, MODIFIED,
  MERGED_LATE); `p50_ms`/`p99_ms` are sent -> applied over the whole stream, `received_*` the
  other. A command the client merged into a newer one (`session.merged`) is acked with the
  newer one's ack; its sent -> applied is from its own send time.
  `queued_*` is the rest: sent -> received, through the client's outbox and gRPC.
- `outcomes`: the acks by outcome over the session; `client_merged`; `unacked`.
- `max_wait_applied_ms`: the longest apply - receive of a command acked APPLIED or MODIFIED (one
  that moved the arm on its own), against the session's `max_command_age_ms`;
  `stale_applied`: how many of them waited longer.
- `motion`: the sum of every command's increment whose ack says it moved the arm, against the
  tool's measured displacement from before the session to after it settled (`error_mm`).
- `cpu`: the machine's busy share and each process's share of a core over the session
  (bench/cpu.py), the co-tenants among them; the operator's is its own count over its
  session (`operator_cpu_pct`: it has exited when the orchestrator's window closes).

Its goal (goals.py) is judged by `goals.overload_misses`.
"""

from __future__ import annotations

import os
import threading
import time
from collections import Counter
from collections.abc import Callable, Sequence
from typing import NamedTuple

import numpy as np

from bench.stats import percentiles_ms

NAME = "soak_overload"
RATE_HZ = 500
STEP_M = 1e-5  # 10 um a command, as the teleop rows' (bench.command.TELEOP_STEP_M)
SWING = 200  # commands one way, then as many back: 2 mm strokes, 0.4 s each at 500 Hz
WARMUP_COMMANDS = 20
WATCHDOG_S = 1.0  # the session's watchdog, as the soak's
OPERATOR = "bench-overload"
LEASE_S = 60.0
CALL_TIMEOUT_S = 10.0
DRAIN_S = 10.0  # after the last send, how long commands may still be acked
TAIL_PERIOD_S = 0.05  # while some are unacked, a zero increment this often
HEARTBEAT_S = 0.2
# The arm is at rest when over REST_SAMPLES readings REST_PERIOD_S apart its tool moved less
# than REST_TOLERANCE_M and no joint turns faster than REST_JOINT_RAD_S.
REST_SAMPLES = 10
REST_PERIOD_S = 0.02
REST_TOLERANCE_M = 1e-6
REST_JOINT_RAD_S = 1e-3
REST_TIMEOUT_S = 5.0
WORKER_SLACK_S = 120.0  # the worker's time limit beyond the stream's duration
THIRDS = 3
APPLIED = ("APPLIED", "MODIFIED", "MERGED_LATE")  # the ack says the arm moved (Ack.applied)
ON_ITS_OWN = ("APPLIED", "MODIFIED")  # moved the arm in a move of its own (not carried late)
CLIENT_MERGED_PREFIX = "merged by the client"  # TeleopSession's detail on such an ack

# A co-tenant: spins on the CPU until stopped (SIGTERM), or until the bench is gone.
SPIN_CODE = """\
import os, threading, time
parent = os.getppid()
def watch():
    while True:
        time.sleep(0.25)
        if os.getppid() != parent:
            os._exit(0)
threading.Thread(target=watch, daemon=True).start()
while True:
    sum(range(10000))
"""


def cotenant_count() -> int:
    """One busy co-tenant per core."""
    return os.cpu_count() or 2


# -- pure parts ---------------------------------------------------------------------------------

class Command(NamedTuple):
    """One command of the session as its ack told it (times in ns; apply/receive on the
    server's clock, sent on this host's)."""

    sent_ns: int
    receive_ns: int
    apply_ns: int
    outcome: str
    client_merged: bool = False


def direction(index: int, swing: int = SWING) -> float:
    """+1 for the first `swing` commands (index from 0), -1 for the next, and so on."""
    return 1.0 if (index // swing) % 2 == 0 else -1.0


def third_of(sent_ns: int, first_ns: int, duration_ns: int, parts: int = THIRDS) -> int:
    """Which part of the run (0 .. parts-1) a command sent at `sent_ns` falls in, the run
    starting at `first_ns` and lasting `duration_ns`; a command before the start is in the
    first, one after the end in the last."""
    if duration_ns <= 0:
        return 0
    return min(parts - 1, max(0, int((sent_ns - first_ns) * parts // duration_ns)))


def _latencies(commands: Sequence[Command]) -> dict:
    """received -> applied, sent -> applied and, where the rest of it goes, sent -> received
    (`queued_*`: from the client's send to the server's receipt, through the client's outbox
    and gRPC on both sides), in ms, of the commands that moved the arm."""
    moved = [c for c in commands if c.outcome in APPLIED]
    received = percentiles_ms([(c.apply_ns - c.receive_ns) / 1e6 for c in moved])
    sent = percentiles_ms([(c.apply_ns - c.sent_ns) / 1e6 for c in moved])
    queued = percentiles_ms([(c.receive_ns - c.sent_ns) / 1e6 for c in moved])
    return {"applied": len(moved),
            "received_p50_ms": received["p50_ms"], "received_p99_ms": received["p99_ms"],
            "received_max_ms": received["max_ms"],
            "sent_p50_ms": sent["p50_ms"], "sent_p99_ms": sent["p99_ms"],
            "sent_max_ms": sent["max_ms"],
            "queued_p50_ms": queued["p50_ms"], "queued_p99_ms": queued["p99_ms"]}


def per_third(commands: Sequence[Command], first_ns: int, duration_s: float,
              parts: int = THIRDS) -> list[dict]:
    """Each part of the run: its start (s), the commands sent in it, their outcomes, the
    commands the client merged, and the latencies (`_latencies`) of those that moved the arm."""
    duration_ns = int(round(duration_s * 1e9))
    buckets: list[list[Command]] = [[] for _ in range(parts)]
    for command in commands:
        buckets[third_of(command.sent_ns, first_ns, duration_ns, parts)].append(command)
    return [{"third": index + 1, "t_s": round(index * duration_s / parts, 3),
             "commands": len(bucket),
             "outcomes": dict(Counter(c.outcome for c in bucket)),
             "client_merged": sum(c.client_merged for c in bucket),
             **_latencies(bucket)}
            for index, bucket in enumerate(buckets)]


def worst_vs_first(thirds: Sequence[dict], key: str) -> dict:
    """The worst later third's `key` over the first third's: {ratio, third, first, worst}
    (ratio None when the first or a later third has no figure)."""
    first = thirds[0].get(key) if thirds else None
    later = [(t.get(key), t["third"]) for t in thirds[1:]]
    if first is None or not later or any(value is None for value, _ in later):
        return {"ratio": None, "third": None, "first": first,
                "worst": max((v for v, _ in later if v is not None), default=None)}
    worst, third = max(later)
    return {"ratio": round(worst / first, 3) if first > 0 else None, "third": third,
            "first": first, "worst": worst}


def waits_on_their_own(commands: Sequence[Command], max_age_s: float) -> dict:
    """Of the commands that moved the arm on their own (APPLIED, MODIFIED): the longest
    apply - receive (ms) and how many waited longer than `max_age_s`."""
    waits = [(c.apply_ns - c.receive_ns) / 1e6 for c in commands if c.outcome in ON_ITS_OWN]
    limit_ms = max_age_s * 1e3
    return {"max_wait_applied_ms": round(max(waits), 3) if waits else None,
            "stale_applied": sum(wait > limit_ms for wait in waits)}


def net_motion(commanded_m: Sequence[float], start_m: Sequence[float] | None,
               end_m: Sequence[float] | None) -> dict:
    """The commands' summed increment against the tool's measured displacement (end - start,
    metres in, millimetres out): both vectors and the norm of their difference, `error_mm`
    (None without both poses)."""
    commanded = np.asarray(commanded_m, dtype=float) * 1e3
    out = {"commanded_mm": [round(float(v), 4) for v in commanded],
           "measured_mm": None, "error_mm": None}
    if start_m is None or end_m is None:
        return out
    measured = (np.asarray(end_m, dtype=float) - np.asarray(start_m, dtype=float)) * 1e3
    out["measured_mm"] = [round(float(v), 4) for v in measured]
    out["error_mm"] = round(float(np.linalg.norm(measured - commanded)), 4)
    return out


def is_at_rest(positions_m: Sequence[Sequence[float]], joint_speeds: Sequence[float],
               tolerance_m: float = REST_TOLERANCE_M,
               joint_limit: float = REST_JOINT_RAD_S) -> bool:
    """Whether the tool positions read one after another stayed within `tolerance_m` of the
    first of them, and the last reading's fastest joint turns under `joint_limit` rad/s."""
    if len(positions_m) < 2:
        return False
    points = np.asarray(positions_m, dtype=float)
    spread = float(np.max(np.linalg.norm(points - points[0], axis=1)))
    return spread < tolerance_m and float(np.max(np.abs(joint_speeds), initial=0.0)) < joint_limit


def summarize(sends: dict[int, tuple[int, float, str]], acks: dict[int, tuple],
              first_ns: int | None, duration_s: float, max_age_s: float) -> dict:
    """The session's figures from what the worker saw: `sends` {sequence: (send time ns,
    increment along y in m, phase: warmup, measured or tail)}, `acks` {sequence: (outcome,
    receive ns, apply ns, merged by the client)}."""
    commands: dict[int, Command] = {}
    for sequence, (outcome, receive_ns, apply_ns, merged) in acks.items():
        if sequence in sends:
            commands[sequence] = Command(sends[sequence][0], receive_ns, apply_ns, outcome,
                                         merged)
    measured = [commands[s] for s, (_, _, phase) in sorted(sends.items())
                if phase == "measured" and s in commands]
    unacked = [s for s in sends if s not in commands]
    outcomes = Counter(c.outcome for c in commands.values())
    commanded = sum((sends[s][1] for s, c in commands.items() if c.outcome in APPLIED), 0.0)
    not_applied = sum((sends[s][1] for s in sends
                       if s not in commands or commands[s].outcome not in APPLIED), 0.0)
    whole = _latencies(measured)
    thirds = per_third(measured, first_ns, duration_s) if first_ns is not None else []
    return {
        "p50_ms": whole["sent_p50_ms"], "p99_ms": whole["sent_p99_ms"],
        "max_ms": whole["sent_max_ms"], "received_p50_ms": whole["received_p50_ms"],
        "received_p99_ms": whole["received_p99_ms"],
        "received_max_ms": whole["received_max_ms"], "queued_p50_ms": whole["queued_p50_ms"],
        "queued_p99_ms": whole["queued_p99_ms"], "samples": whole["applied"],
        "thirds": thirds,
        "worst_third": {key: worst_vs_first(thirds, key)
                        for key in ("sent_p99_ms", "received_p99_ms")},
        "outcomes": dict(outcomes),
        "client_merged": sum(c.client_merged for c in commands.values()),
        "session_commands": len(sends),
        "unacked": len(unacked),
        "unacked_measured": sum(sends[s][2] == "measured" for s in unacked),
        "rejected_measured": sum(c.outcome not in APPLIED for c in measured),
        "max_command_age_ms": round(max_age_s * 1e3, 3),
        **waits_on_their_own(list(commands.values()), max_age_s),
        "commanded_y_m": commanded, "not_applied_y_mm": round(not_applied * 1e3, 4),
    }


# -- the worker's side (python -m bench.worker overload) ---------------------------------------

class Book:
    """What the operator sent and what came back, by sequence; the acks come on the
    session's reader thread."""

    def __init__(self):
        self._lock = threading.Lock()
        self.sends: dict[int, tuple[int, float, str]] = {}
        self.acks: dict[int, tuple[str, int, int, bool]] = {}
        self._send_ns: dict[int, int] = {}

    def queued(self, request) -> None:
        """TeleopSession.on_request: the send time the command carries."""
        if request.WhichOneof("message") == "command":
            self._send_ns[request.command.sequence] = request.command.send_time.ToNanoseconds()

    def sent(self, sequence: int, dy_m: float, phase: str) -> None:
        self.sends[sequence] = (self._send_ns.get(sequence, time.time_ns()), dy_m, phase)

    def acked(self, ack) -> None:
        """TeleopSession's on_ack (an Ack of clients.python.values)."""
        if not ack.sequence:
            return  # a heartbeat's
        outcome = getattr(ack.outcome, "name", str(ack.outcome))
        merged = ack.detail.startswith(CLIENT_MERGED_PREFIX)
        with self._lock:
            self.acks.setdefault(ack.sequence, (outcome, ack.receive_time_ns,
                                                ack.apply_time_ns, merged))

    def snapshot(self) -> dict[int, tuple[str, int, int, bool]]:
        with self._lock:
            return dict(self.acks)


def at_rest(read: Callable[[], tuple[Sequence[float], Sequence[float]]],
            keep_alive: Callable[[], None] | None = None,
            timeout_s: float = REST_TIMEOUT_S) -> tuple[list[float], bool, float]:
    """Read (tool position, joint speeds) until the arm is at rest (`is_at_rest` over the last
    REST_SAMPLES readings) or `timeout_s`: (the last position, whether at rest, seconds it
    took). `keep_alive` is called every HEARTBEAT_S meanwhile (the session's watchdog)."""
    started = last_beat = time.monotonic()
    window: list[Sequence[float]] = []
    while True:
        position, speeds = read()
        window = [*window[-(REST_SAMPLES - 1):], list(position)]
        waited = time.monotonic() - started
        if len(window) >= REST_SAMPLES and is_at_rest(window, speeds):
            return list(position), True, round(waited, 3)
        if waited > timeout_s:
            return list(position), False, round(waited, 3)
        if keep_alive is not None and time.monotonic() - last_beat >= HEARTBEAT_S:
            keep_alive()
            last_beat = time.monotonic()
        time.sleep(REST_PERIOD_S)


def _stream(session, book: Book, rate_hz: float, ticks: int, first_index: int, phase: str,
            swing: int, step_m: float) -> tuple[int, int, int | None, str | None]:
    """`ticks` commands on absolute deadlines (schedule.Schedule), never waiting for an ack:
    (sent, ticks skipped late, time.time_ns() of the first send, the error that ended it)."""
    from bench.schedule import Schedule

    schedule = Schedule(rate_hz, ticks)
    sent, first_ns = 0, None
    for _ in schedule:
        dy = step_m * direction(first_index + sent, swing)
        first_ns = first_ns or time.time_ns()
        try:
            sequence = session.send_nowait((0.0, dy, 0.0))
        except Exception as error:  # noqa: BLE001 - the session ended: the row says why
            return sent, schedule.skipped, first_ns, f"{type(error).__name__}: {error}"
        book.sent(sequence, dy, phase)
        sent += 1
    return sent, schedule.skipped, first_ns, None


def _drain(session, book: Book, deadline: float) -> int:
    """Until every command is acked (or `deadline`, time.monotonic()): a zero increment every
    TAIL_PERIOD_S, so that commands the server carries as late go with a fresh one. The zero
    commands sent."""
    tail, last = 0, time.monotonic()
    while session.unacked and time.monotonic() < deadline and not session.closed:
        time.sleep(0.01)
        if session.unacked and time.monotonic() - last >= TAIL_PERIOD_S:
            try:
                book.sent(session.send_nowait((0.0, 0.0, 0.0)), 0.0, "tail")
            except Exception:  # noqa: BLE001 - ended: what is unacked stays so
                break
            tail += 1
            last = time.monotonic()
    return tail


def operate(params: dict, ready: Callable[[], None]) -> dict:
    """The operator: `params` address (the DecisionServer), proxy_address (ProxyRobot, for
    the measured pose), duration_s, and optionally rate_hz, swing, step_m. ready() once the
    session is open, right before the stream."""
    from clients.python.decision_server import DecisionClient
    from clients.python.proxy_robot import ProxyRobotClient
    from clients.python.values import ReferenceFrame

    rate_hz = params.get("rate_hz", RATE_HZ)
    swing, step_m = params.get("swing", SWING), params.get("step_m", STEP_M)
    duration_s = params["duration_s"]
    ticks = int(round(duration_s * rate_hz))
    book = Book()
    with DecisionClient(params["address"], default_timeout=CALL_TIMEOUT_S) as client, \
            ProxyRobotClient(params["proxy_address"], default_timeout=CALL_TIMEOUT_S) as robot:
        def read() -> tuple[Sequence[float], Sequence[float]]:
            state = robot.get_state()
            return state.tool_pose.translation, state.joint_velocities

        client.acquire_control(OPERATOR, wait=True, wait_timeout_s=LEASE_S,
                               lease_duration_s=LEASE_S, timeout=LEASE_S + 10)
        start, start_rest, _ = at_rest(read)
        session = client.teleoperate(OPERATOR, ReferenceFrame.BASE,
                                     watchdog_timeout_s=WATCHDOG_S, timeout=CALL_TIMEOUT_S,
                                     on_ack=book.acked, resume=False)
        session.on_request = book.queued
        end, end_rest, settle_s, error, tail = None, False, None, None, 0
        sent = skipped = 0
        first_ns = None
        try:
            ready()
            cpu_then, wall_then = time.process_time(), time.monotonic()
            warm, _, _, error = _stream(session, book, rate_hz, WARMUP_COMMANDS, 0, "warmup",
                                        swing, step_m)
            deadline = time.monotonic() + 1.0
            while session.unacked and time.monotonic() < deadline and error is None:
                time.sleep(0.01)
            if error is None:
                sent, skipped, first_ns, error = _stream(session, book, rate_hz, ticks, warm,
                                                         "measured", swing, step_m)
            last_send = time.monotonic()
            tail = _drain(session, book, last_send + DRAIN_S)
            drained_s = round(time.monotonic() - last_send, 3)
            end, end_rest, settle_s = at_rest(
                read, None if session.closed else session.heartbeat_nowait)
            max_age_s, merged = session.max_command_age_s, session.merged
            own_cpu_pct = round(100.0 * (time.process_time() - cpu_then)
                                / max(time.monotonic() - wall_then, 1e-9), 1)
        finally:
            session.close(timeout=5.0)
        error = error or (f"{type(session.error).__name__}: {session.error}"
                          if session.error else None)
    acks = book.snapshot()
    result = summarize(book.sends, acks, first_ns, duration_s, max_age_s)
    commanded = result.pop("commanded_y_m")
    motion = net_motion((0.0, commanded, 0.0), start, end)
    motion.update(start_at_rest=start_rest, end_at_rest=end_rest, settle_s=settle_s)
    applied = result["samples"]
    window_s = ticks / rate_hz
    result.update(
        rate_hz=float(rate_hz), delivered_hz=round(applied / window_s, 3) if window_s else None,
        dropped=ticks - sent + result["unacked_measured"] + result["rejected_measured"],
        sent=sent, late_skipped=skipped, warmup_commands=WARMUP_COMMANDS,
        tail_commands=tail, drained_s=drained_s, session_merged=merged,
        duration_s=round(duration_s, 3), swing=swing, step_um=round(step_m * 1e6, 3),
        watchdog_s=WATCHDOG_S, motion=motion, operator_cpu_pct=own_cpu_pct, error=error)
    return result


# -- the progress lines ------------------------------------------------------------------------

def third_lines(row: dict) -> list[str]:
    """The row's figures per third, then its outcomes, waits and motion, a line each."""
    lines = []
    for third in row.get("thirds", []):
        late = third["outcomes"].get("MERGED_LATE", 0)
        refused = third["commands"] - third["applied"]
        lines.append(
            f"{NAME} third {third['third']} (from {third['t_s']:g} s): {third['commands']} "
            f"commands, received -> applied p50 {_ms(third['received_p50_ms'])} / p99 "
            f"{_ms(third['received_p99_ms'])} ms, sent -> applied p50 "
            f"{_ms(third['sent_p50_ms'])} / p99 {_ms(third['sent_p99_ms'])} ms (sent -> "
            f"received p50 {_ms(third['queued_p50_ms'])} / p99 {_ms(third['queued_p99_ms'])}); "
            f"{late} merged late, {third['client_merged']} merged by the client, "
            f"{refused} not applied")
    worst = row.get("worst_third", {})
    ratios = ", ".join(f"{key.removesuffix('_p99_ms')} x{entry['ratio']:.2f} (third "
                       f"{entry['third']})" if entry.get("ratio") is not None
                       else f"{key.removesuffix('_p99_ms')} -"
                       for key, entry in worst.items())
    lines.append(f"{NAME}: worst third's p99 / the first's: {ratios}")
    motion = row.get("motion") or {}
    lines.append(
        f"{NAME}: outcomes {row.get('outcomes')}, {row.get('client_merged')} merged by the "
        f"client, {row.get('unacked')} unacked, {row.get('tail_commands')} zero tail commands; "
        f"longest wait applied on its own {_ms(row.get('max_wait_applied_ms'))} ms (max "
        f"command age {_ms(row.get('max_command_age_ms'))} ms: {row.get('stale_applied')} "
        "past it)")
    lines.append(
        f"{NAME}: motion commanded {motion.get('commanded_mm')} mm, measured "
        f"{motion.get('measured_mm')} mm, error {_ms(motion.get('error_mm'), 4)} mm (at rest "
        f"before {motion.get('start_at_rest')}, after {motion.get('end_at_rest')} in "
        f"{motion.get('settle_s')} s)")
    cpu = row.get("cpu") or {}
    if cpu:
        shares = ", ".join(f"{name} {pct:.0f} %" for name, pct in
                           sorted(cpu.get("cpu_pct", {}).items(), key=lambda item: -item[1]))
        lines.append(f"{NAME}: CPU over the session: machine {cpu.get('machine_busy_pct')} % "
                     f"busy; {shares} (of a core)")
    if row.get("error"):
        lines.append(f"{NAME}: the session ended with {row['error'][:200]}")
    return lines


def _ms(value, digits: int = 2) -> str:
    return "-" if value is None else f"{value:.{digits}f}"
