"""Chaos: during a teleoperation session, every service but the world is killed (SIGKILL) in
turn, then hung for 2 s (SIGSTOP, SIGCONT), while the arm is watched at the world's 1 kHz.

For each fault the test measures how long the arm took to hold (its fastest joint under
HOLD_SPEED_RAD_S) and checks what the issue asks (#16):
- where the fault cuts the command path (ProxyRobot, the DecisionServer) or the force feedback
  the operator moves by (the sensor), the arm holds within 100 ms, with no unintended motion
  (the arm never moves faster than the operator drives it);
- a killed service is back, serving on its address, within 5 s;
- the operator's session resumes (it re-acquires, re-initializes and reopens as a real
  operator station would) or ended with a clear status, never UNKNOWN or INTERNAL;
- the recording made across all of it is readable afterwards.

The hold times are printed as a table (pytest -s), the README's Faults table.
"""

from __future__ import annotations

import math
import os
import signal
import threading
import time
from dataclasses import dataclass, field

import numpy as np
import pytest

from bench.worldwatch import WorldWatch
from clients.python import (
    DecisionClient,
    FailedPreconditionError,
    RobotStatus,
    TelerobotError,
)
from tests.conftest import wait_for
from tests.processes import restarted, service_pid, start_station, station_env

pytestmark = [pytest.mark.e2e, pytest.mark.slow]

HOLD_SPEED_RAD_S = 0.002  # the fastest joint under this: the arm holds
HOLD_WITHIN_S = 0.1
BACK_WITHIN_S = 5.0
HANG_S = 2.0
STEP_M = 0.0002  # per command, at 100 Hz: the tool moves at 20 mm/s
COMMAND_PERIOD_S = 0.01
# The operator drives the tool at 20 mm/s; no joint of the PUMA moves faster than this for it
# here, so a faster one is motion nobody asked for.
MAX_DRIVEN_SPEED_RAD_S = 0.5
# Faults that cut what the arm moves by: the arm must hold. (The band and the camera are not on
# the motion path: the session goes on through them.)
ON_THE_MOTION_PATH = {"proxy_robot", "decision_server", "force_sensor"}
VICTIMS = ["emergency_stop", "stereo_camera", "force_sensor", "proxy_robot", "decision_server"]


class ArmWatch:
    """The arm's fastest joint speed at every world step, read from the world's shared memory
    (read only), on a thread."""

    def __init__(self, shm_name: str):
        self._world = WorldWatch(shm_name)
        self.samples: list[tuple[int, float]] = []  # (monotonic ns, max |qd|)
        self._lock = threading.Lock()
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True)
        self._thread.start()

    def _run(self) -> None:
        last = -1
        while not self._stop.is_set():
            state = self._world.read()
            if state["arm_sequence"] != last:
                last = int(state["arm_sequence"])
                with self._lock:
                    self.samples.append((int(state["heartbeat_ns"]),
                                         float(np.max(np.abs(state["qd"])))))
            time.sleep(0.0003)  # polls faster than the 1 kHz it samples

    def since(self, t_ns: int) -> list[tuple[int, float]]:
        with self._lock:
            return [s for s in self.samples if s[0] >= t_ns]

    def moving(self) -> bool:
        recent = self.since(time.monotonic_ns() - 50_000_000)
        return bool(recent) and max(speed for _, speed in recent) > 5 * HOLD_SPEED_RAD_S

    def close(self) -> None:
        self._stop.set()
        self._thread.join(1)
        self._world.close()


@dataclass
class Operator:
    """Drives the arm back and forth along the base x axis at 100 Hz, as a scripted operator
    station; when its session breaks it starts over (re-acquire, re-initialize, reopen).
    Every error it met is kept."""

    address: str
    errors: list[tuple[str, str]] = field(default_factory=list)  # (code, message)
    sessions: int = 0
    acked: int = 0
    stop: threading.Event = field(default_factory=threading.Event)

    def start(self) -> Operator:
        self._thread = threading.Thread(target=self._run, daemon=True)
        self._thread.start()
        return self

    def _run(self) -> None:
        tick = 0
        while not self.stop.is_set():
            try:
                with DecisionClient(self.address, default_timeout=5.0) as station:
                    station.acquire_control("chaos", lease_duration_s=10.0)
                    try:  # one recording across everything (a restarted server lost it)
                        station.start_recording(f"chaos-{time.time_ns()}")
                    except FailedPreconditionError:
                        pass  # still recording since before the session broke
                    status = station.robot.get_status().status
                    if status is RobotStatus.NOT_CONNECTED:
                        station.robot.connect()
                        status = station.robot.get_status().status
                    if status is RobotStatus.CONNECTED:
                        station.robot.initialize()
                    station.sensor.start_reading()  # as make teleop does; a no-op if reading
                    with station.teleoperate(watchdog_timeout_s=0.1) as session:
                        self.sessions += 1
                        while not self.stop.is_set():
                            direction = math.copysign(1.0, math.sin(tick * math.pi / 100))
                            session.send([direction * STEP_M, 0.0, 0.0], np.eye(3))
                            self.acked += 1
                            tick += 1
                            self.stop.wait(COMMAND_PERIOD_S)
                        station.stop_recording()
            except TelerobotError as error:
                self.errors.append((error.code.name, str(error)))
                self.stop.wait(0.1)

    def close(self) -> None:
        self.stop.set()
        self._thread.join(10)


def _hold_time_s(watch: ArmWatch, fault_ns: int) -> float | None:
    """Seconds from the fault to the first step after which the arm stays under the hold speed
    for 50 ms; None if it never does within a second."""
    samples = watch.since(fault_ns)
    for i, (t_ns, speed) in enumerate(samples):
        if speed >= HOLD_SPEED_RAD_S:
            continue
        window = [s for tt, s in samples[i:] if tt - t_ns <= 50_000_000]
        if window and max(window) < HOLD_SPEED_RAD_S and samples[-1][0] - t_ns > 50_000_000:
            return (t_ns - fault_ns) / 1e9
    return None


@pytest.fixture(scope="module")
def station():
    env = station_env()
    launcher = start_station(env)
    watch = ArmWatch(env["TELEROBOT_WORLD_SHM"])
    operator = Operator(launcher.ready["decision_server"]).start()
    try:
        yield launcher, watch, operator
    finally:
        operator.close()
        watch.close()
        launcher.stop(signal.SIGINT)


@pytest.mark.parametrize("fault", ["kill", "hang"])
def test_every_fault_holds_the_arm_and_the_station_recovers(station, fault):
    launcher, watch, operator = station
    rows = []
    for victim in VICTIMS:
        wait_for(watch.moving, timeout_s=20, what=f"the operator driving before {victim}")
        pid = service_pid(launcher, victim)
        fault_ns = time.monotonic_ns()
        if fault == "kill":
            os.kill(pid, signal.SIGKILL)
        else:
            os.kill(pid, signal.SIGSTOP)
        watched_s = HANG_S if fault == "hang" else 1.0
        try:
            wait_for(lambda t=fault_ns, w=watched_s: _watched_for(watch, t, w), timeout_s=10,
                     what="the arm watched through the fault")
        finally:
            if fault == "hang":
                os.kill(pid, signal.SIGCONT)
        during = watch.since(fault_ns)
        hold = _hold_time_s(watch, fault_ns)
        fastest = max(speed for _, speed in during)
        if fault == "kill":
            wait_for(lambda v=victim, p=pid: restarted(launcher, v, p),
                     timeout_s=BACK_WITHIN_S, what=f"{victim} back within 5 s")
        back_s = (time.monotonic_ns() - fault_ns) / 1e9
        rows.append((victim, hold, fastest, back_s))
    print(f"\n{fault}: victim, arm held after (ms), fastest joint (rad/s), back after (s)")
    for victim, hold, fastest, back_s in rows:
        held = f"{hold * 1e3:.0f}" if hold is not None else "moving on"
        print(f"  {victim:16} {held:>10} {fastest:8.3f} {back_s:6.2f}")
    wait_for(watch.moving, timeout_s=20, what="the operator driving again after it all")
    for victim, hold, fastest, _ in rows:
        assert fastest < MAX_DRIVEN_SPEED_RAD_S, (victim, fastest)  # no unintended motion
        if victim in ON_THE_MOTION_PATH:
            assert hold is not None and hold <= HOLD_WITHIN_S, (fault, victim, hold)
    # Every failure the operator met said what it was (and the session came back each time).
    # NOT_FOUND: the session tried to resume on a restarted DecisionServer, which forgot it.
    assert {code for code, _ in operator.errors} <= {
        "UNAVAILABLE", "FAILED_PRECONDITION", "DEADLINE_EXCEEDED", "ABORTED", "CANCELLED",
        "NOT_FOUND"}, operator.errors


def test_recordings_made_across_the_faults_are_whole(station):
    """Runs after the faults: every recording on disk loads (ListRecordings reads them all).
    One in progress when the DecisionServer died is lost whole, never half-written: a
    recording is written once, by rename, when it stops."""
    launcher, _, operator = station
    operator.close()
    with DecisionClient(launcher.ready["decision_server"]) as client:
        recordings = client.list_recordings()
    assert recordings and max(r.command_count for r in recordings) > 0, recordings


def _watched_for(watch: ArmWatch, since_ns: int, seconds: float) -> bool:
    samples = watch.since(since_ns)
    return bool(samples) and samples[-1][0] - since_ns > seconds * 1e9
