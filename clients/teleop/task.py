"""The scripted peg-in-hole task, run two ways as the paper's experiments did.

At home the peg hangs straight above the fixture's hole, 0.21 m over its mouth. The simulated
operator's hand strokes down the master arm at eq. 2's scale 0.5, using the clutch (indexing) to
bring the hand back up between strokes, as a person would with a small master and a long
approach. Then:

- `feedback`: force feedback to the operator only. The operator keeps pushing the peg into the
  hole until the force it feels (the acks' wrench) passes FEEL_N, then backs off until it
  falls under half that: with a stiff position-controlled slave the force peaks before the
  operator can react, which is what the comparison shows.
- `compliance`: active compliance on the server. Once the peg is in the hole's mouth the
  operator holds still and the DecisionServer's force control pushes along the peg to
  DESIRED_FORCE_N and holds it.

Success: the peg's tip reaches the hole's floor (its depth below the mouth within 5 mm of the
hole's depth), inside the hole.

Across a broken link (#14) the session resumes by itself (clients.python.teleoperate). While it
is down the arm holds, and the operator, told "link lost", holds still: the script's time stops
until the session is back, so no motion is lost and none is applied twice.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from clients.ar import RobotModel
from clients.master import IncrementFrame, MasterArm, SimulatedHand
from clients.python.decision_server import DecisionClient
from clients.python.teleoperate import LinkInterruptedError
from clients.python.values import Ack
from clients.teleop.artifacts import Trace
from services.robot_model import workspace
from telerobot.v1 import decision_server_pb2 as pb
from telerobot.v1 import types_pb2
from wire.pose import Pose

COMMAND_RATE_HZ = 50.0
SCALE = 0.5  # eq. 2: the slave moves half as far as the hand
STROKE_M = 0.10  # hand travel per stroke (slave: 5 cm)
STROKE_S = 1.5
RETURN_S = 0.6  # clutch engaged while the hand goes back up
FEEL_N = 8.0  # the operator stops pushing once it feels this much
DESIRED_FORCE_N = 5.0
COMPLIANCE_GAIN_M_PER_N_S = 3e-4  # stable with the arm's ~1e5 N/m contact stiffness
SETTLE_S = 3.0
FINAL_WINDOW_S = 1.0  # the final force is the mean over the run's last second
OVERREACH_M = 0.01  # the feedback operator aims past the floor and stops when it feels it
BACK_OFF_STEP_M = 0.0002  # then raises the peg this much per command
BACK_OFF_TICKS = 100
HAND_INSERT_M = 0.03  # the compliance operator's own share of the 40 mm insertion
HOLE_DEPTH_M = workspace.FIXTURE_HEIGHT
MOUTH_Z = workspace.TABLE_TOP_Z + workspace.FIXTURE_HEIGHT


@dataclass
class Result:
    mode: str
    success: bool
    duration_s: float
    depth_m: float
    lateral_error_m: float
    peak_force_n: float
    final_force_n: float
    commands: int
    acks: int
    round_trip_p50_ms: float
    round_trip_p99_ms: float
    link_interruptions: int = 0  # times the link broke and the session resumed
    resent: int = 0  # commands sent again after a resume (the server applied each once)
    commands_acked: int = 0  # commands acked, once each
    commands_applied: int = 0  # of those, acked APPLIED or MODIFIED


def ready_the_arm(client: DecisionClient) -> None:
    """Connected, un-latched, initialized, the sensor reading: what a run needs (the lease
    held). Idempotent, so a second run or another program can call it again."""
    client.robot.connect()
    if client.robot.get_status().status.name in ("ESTOPPED", "FAULT"):
        client.robot.reset()
    if client.robot.get_status().status.name == "CONNECTED":
        client.robot.initialize()
    client.sensor.start_reading()


class StrokingHand:
    """Down strokes of the master's handle with the clutch engaged on the way back up."""

    def __init__(self, hand_rest: pin.SE3, strokes: int):
        self.rest = hand_rest
        self.strokes = strokes
        self.period = STROKE_S + RETURN_S

    def pose(self, t: float) -> pin.SE3:
        stroke, phase = divmod(t, self.period)
        if stroke >= self.strokes:
            return self.rest  # done: the hand rests
        if phase < STROKE_S:
            depth = STROKE_M * phase / STROKE_S
        else:
            depth = STROKE_M * (1 - (phase - STROKE_S) / RETURN_S)
        return pin.SE3(self.rest.rotation, self.rest.translation - [0, 0, depth])

    def clutch(self, t: float) -> bool:
        stroke, phase = divmod(t, self.period)
        return stroke < self.strokes and phase >= STROKE_S

    def duration(self) -> float:
        return self.strokes * self.period


class PegInHole:
    """One run of the task, recording into `trace` and predicting the tool into `model`."""

    def __init__(self, client: DecisionClient, mode: str, model: RobotModel, status=None,
                 on_link: Callable[[str, str], None] | None = None, recorder=None):
        self.client = client
        self._recorder = recorder  # a clients.teleop.mcap_log.SessionRecorder, or None
        self.mode = mode
        self.model = model
        self.trace = Trace(mode)
        self._status = status or (lambda **fields: None)
        self._on_link = on_link
        self._session = None
        self._start = time.monotonic()
        self._commands = 0
        self._acks: list[Ack] = []

    def _elapsed(self) -> float:
        return time.monotonic() - self._start

    def _on_ack(self, ack: Ack) -> None:
        self._acks.append(ack)
        if self._recorder is not None:
            self._recorder.ack(ack)
        now = self._elapsed()
        if ack.sequence:
            self.trace.command_time_s.append(now)
            self.trace.round_trip_ms.append((ack.received_time_ns - ack.command_send_time_ns)
                                            / 1e6)
        if ack.force is not None:
            self.trace.force_time_s.append(now)
            self.trace.force_n.append(ack.force)
        if ack.tool_pose is not None:
            self.trace.tool_time_s.append(now)
            self.trace.tool_position_m.append(ack.tool_pose.translation.copy())
            if ack.status.name == "READY":  # at rest: the measured pose corrects the model
                self.model.correct(ack.tool_pose)

    def _contact_force(self) -> float:
        """Force along the peg felt through the last ack (the table pushes along −z_tool)."""
        last = self._acks[-1] if self._acks else None
        return float(-last.force[2]) if last is not None and last.force is not None else 0.0

    def run(self) -> Result:
        robot = self.client.robot
        start = robot.get_state().tool_pose
        self.model.reset(start)
        approach = start.translation[2] - MOUTH_Z  # to the hole's mouth
        # Feedback: push past the floor until it is felt. Compliance: most of the way in by
        # hand, the rest under force control.
        insert = HOLE_DEPTH_M + OVERREACH_M if self.mode == "feedback" else HAND_INSERT_M
        strokes = int(np.ceil((approach + insert) / (STROKE_M * SCALE)))
        hand = SimulatedHand()
        rest = hand.model.hand_pose(hand.q)
        script = StrokingHand(rest, strokes)
        hand.path = script.pose
        arm = MasterArm(hand, translation_scale=SCALE, frame=IncrementFrame.BASE)
        session = self._session = self.client.teleoperate(
            "teleop-script", types_pb2.REFERENCE_FRAME_BASE, watchdog_timeout_s=0.5,
            on_ack=self._on_ack, on_link=self._on_link)
        if self._recorder is not None:  # every command and heartbeat, as sent
            session.on_request = self._recorder.request
        period = 1.0 / COMMAND_RATE_HZ
        script_time, felt = 0.0, False
        next_tick = time.monotonic()
        try:
            while script_time < script.duration() + 0.5:
                next_tick += period
                if session.interrupted:  # the operator holds still until the link is back
                    self._show(arm.indexing)
                    time.sleep(period)
                    next_tick = time.monotonic()
                    continue
                arm.clutch = script.clutch(script_time)
                reference = arm.reference
                increment = arm.update(script_time)
                if self.mode == "feedback" and self._contact_force() > FEEL_N:
                    felt = True  # the operator feels the floor and stops pushing
                if increment is None or felt:
                    session.heartbeat_nowait()
                elif self._send(increment.delta_position, increment.delta_rotation):
                    self._commands += 1
                else:  # the link broke just now: this motion goes out with the next command
                    arm.reference = reference
                    continue
                self._show(arm.indexing)
                script_time += period
                time.sleep(max(0.0, next_tick - time.monotonic()))
                if felt:
                    break
            if self.mode == "compliance":
                self._comply(session, period)
            else:
                self._back_off(session, period)
                self._hold(session, period, SETTLE_S / 2)
        finally:
            session.close()
        return self._result(start)

    def _send(self, delta_position, delta_rotation=None) -> bool:
        """Send one increment and predict it into the model; False when the link is down."""
        try:
            self._session.send_nowait(delta_position, delta_rotation)
        except LinkInterruptedError:
            return False
        self.model.command(delta_position, delta_rotation)
        return True

    def _show(self, clutch: bool) -> None:
        self._status(mode=self.mode, clutch=clutch, force=self._contact_force(),
                     commands=self._commands, acks=len(self._acks),
                     round_trips=self.trace.round_trip_ms,
                     link_down=bool(self._session and self._session.interrupted))

    def _back_off(self, session, period: float) -> None:
        """Raise the peg a little at a time until the felt force is under half of FEEL_N."""
        ticks = 0
        while ticks < BACK_OFF_TICKS and self._contact_force() >= FEEL_N / 2:
            if self._send([0.0, 0.0, BACK_OFF_STEP_M]):
                self._commands += 1
                ticks += 1
            time.sleep(period)

    def _hold(self, session, period: float, seconds: float) -> None:
        """Heartbeats only: the operator holds still while the arm settles."""
        deadline = time.monotonic() + seconds
        while time.monotonic() < deadline:
            session.heartbeat_nowait()  # (sends nothing while the link is down)
            self._show(False)
            time.sleep(period)

    def _comply(self, session, period: float) -> None:
        """Server-side force control along the peg until the floor pushes back as desired."""
        assistance = pb.AssistanceConfig(force_control=pb.ForceControl(
            enabled=True, axes=pb.AxisSelection(z=True),
            desired_wrench=types_pb2.Wrench(force_n=types_pb2.Vector3(z=-DESIRED_FORCE_N)),
            translation_gain_m_per_n_s=COMPLIANCE_GAIN_M_PER_N_S))
        self.client.set_assistance(assistance)
        try:
            # Approach at A·F = 1.5 mm/s over the rest of the hole, then settle on the floor.
            rest = HOLE_DEPTH_M - HAND_INSERT_M
            self._hold(session, period,
                       rest / (COMPLIANCE_GAIN_M_PER_N_S * DESIRED_FORCE_N) + SETTLE_S)
        finally:
            self.client.set_assistance(pb.AssistanceConfig())

    def _result(self, start: Pose) -> Result:
        end = self.client.robot.get_state().tool_pose.translation
        x, y = workspace.FIXTURE_CENTER_XY
        depth = MOUTH_Z - end[2]
        lateral = float(np.hypot(end[0] - x, end[1] - y))
        forces = [-f[2] for f in self.trace.force_n] or [0.0]
        times = self.trace.force_time_s or [0.0]
        final = [f for f, t in zip(forces, times, strict=False) if t >= times[-1] - FINAL_WINDOW_S]
        trips = self.trace.round_trip_ms or [0.0]
        return Result(
            self.mode, bool(depth > HOLE_DEPTH_M - 0.005 and lateral < workspace.HOLE_HALF_WIDTH),
            self._elapsed(), float(depth), lateral, float(max(forces)),
            float(np.mean(final)), self._commands, len(self._acks),
            float(np.percentile(trips, 50)), float(np.percentile(trips, 99)),
            self._session.resumes if self._session else 0,
            self._session.resends if self._session else 0,
            self._session.commands_acked if self._session else 0,
            self._session.commands_applied if self._session else 0)
