"""The scripted peg-in-hole task, run two ways as the paper's experiments did.

At home the peg hangs straight above the fixture's hole, 0.21 m over its mouth. The simulated
operator's hand strokes down the master arm at eq. 2's scale 0.5, using the clutch (indexing) to
bring the hand back up between strokes, as a person would with a small master and a long
approach. Then:

- `feedback`: force feedback to the operator only. The operator keeps pushing the peg into the
  hole until the force it feels (the acks' wrench, as the master arm displays it) passes
  FEEL_N, then backs off until it falls under half that: with a stiff position-controlled slave
  the force peaks before the operator can react, which is what the comparison shows. Under
  delay the slave pushes on for a whole round trip first; with `passivity` (TDPA, #15, on by
  default in this mode) the master arm and the DecisionServer keep the channel passive
  (domain.passivity), and the run reports the energies, the transparency, the drift
  and any oscillation at contact.
- `compliance`: active compliance on the server. Once the peg is in the hole's mouth the
  operator holds still and the DecisionServer's force control pushes along the peg to
  DESIRED_FORCE_N and holds it.

The operator watches where the tool goes, not only the plan: a loaded station refuses commands
that waited too long (it holds the arm rather than move it late), and when the planned strokes
leave the tool short, the operator strokes again, as far as it is short.

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
from domain.passivity import MasterPassivity
from domain.robot_model import workspace
from telerobot.v1 import decision_server_pb2 as pb
from telerobot.v1 import types_pb2
from wire.errors import DeadlineExceededError
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
SETTLED_N = 1.0  # compliance has settled once the contact force stays this close to the desired
# The force loop approaches at A·F; on a loaded station it runs slower (it skips wrench samples
# that arrive stale), so the operator waits for the contact itself, up to this many times the
# nominal approach.
APPROACH_SLACK = 3.0
FINAL_WINDOW_S = 1.0  # the final force is the mean over the run's last second
OVERREACH_M = 0.01  # the feedback operator aims past the floor and stops when it feels it
BACK_OFF_STEP_M = 0.0002  # then raises the peg this much per command
BACK_OFF_TICKS = 100
HAND_INSERT_M = 0.03  # the compliance operator's own share of the 40 mm insertion
MAX_EXTRA_STROKES = 4  # strokes the operator adds when it sees the tool short of its aim
ACKED_WAIT_S = 5.0  # how long it waits for the arm to catch up before it looks
HOLE_DEPTH_M = workspace.FIXTURE_HEIGHT


def mouth_z(cell: workspace.WorkCell) -> float:
    """Height of the hole's mouth in a work cell (m)."""
    return cell.table_top_z + workspace.FIXTURE_HEIGHT


MOUTH_Z = mouth_z(workspace.PUMA560_CELL)  # the default arm's
# Oscillation at contact: swings of the contact force (between successive turning points) of
# more than SWING_N in the run's last FINAL_WINDOW_S; SUSTAINED_SWINGS or more is sustained.
SWING_N = 2.0
SUSTAINED_SWINGS = 4
CONTACT_N = 1.0  # transparency is judged where either force is over this


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
    commands_applied: int = 0  # of those, acked APPLIED, MODIFIED or MERGED_LATE
    # Of those, commands the client sent inside a newer one (the link was slower than the
    # master): the server processed the rest.
    commands_merged: int = 0
    passivity: bool = False  # TDPA on (feedback mode only)
    # Master–slave position drift at the end (m): where the master sent the tool (its start
    # plus every increment sent) against where it is. (In compliance mode the server's force
    # loop moves the tool too, so there it is not a drift.)
    drift_m: float = 0.0
    # Transparency: RMS of the displayed force minus the environment's at the same instant
    # (N, slave units, along the base's z), where either is over CONTACT_N.
    transparency_rms_n: float = 0.0
    oscillation_swings: int = 0  # force swings over SWING_N in the last FINAL_WINDOW_S
    final_force_p2p_n: float = 0.0  # the contact force's peak to peak over that window
    # TDPA's energies at the end (J): each port's in and out, and what each controller
    # dissipated (the slave's from its last ack).
    energy: dict | None = None


def ready_the_arm(client: DecisionClient) -> None:
    """Connected, un-latched, initialized, the sensor reading: what a run needs (the lease
    held). Idempotent, so a second run or another program can call it again."""
    client.robot.connect()
    if client.robot.get_status().status.name in ("ESTOPPED", "FAULT"):
        client.robot.reset()
    if client.robot.get_status().status.name == "CONNECTED":
        client.robot.initialize()
    client.sensor.start_reading()


HOME_STEP_RAD = 0.4  # joint moves home in steps under ProxyRobot's 0.5 rad cap
HOME_TOLERANCE_RAD = 1e-3
HOME_TIMEOUT_S = 30.0
STILL_RAD_PER_S = 1e-3  # at rest: a moving arm's wrench is not its resting one


def go_home(client: DecisionClient) -> bool:
    """Move the arm to its home pose (GetArmInfo's), where the task starts, in joint space; a
    no-op for an arm there already (a simulated one starts there; a real one stands where it
    was left, to be clear of the fixture). Whether it moved."""
    return move_to_joints(client, client.robot.get_arm_info().home, "home")


def move_to_joints(client: DecisionClient, joints: np.ndarray, what: str = "its start") -> bool:
    """Move the arm to `joints` in joint space and wait until it is there and at rest (the
    sensor may be tared next); a no-op for an arm there already. Whether it moved."""
    error = np.asarray(joints) - client.robot.get_state().joint_positions
    if np.max(np.abs(error)) < HOME_TOLERANCE_RAD:
        return False
    steps = int(np.ceil(np.max(np.abs(error)) / HOME_STEP_RAD))
    for _ in range(steps):
        client.robot.move_joints(error / steps)
    deadline = time.monotonic() + HOME_TIMEOUT_S
    while not _still_at(client, joints):
        if time.monotonic() > deadline:
            raise DeadlineExceededError(
                f"the arm did not reach {what} within {HOME_TIMEOUT_S:.0f} s", reason="NOT_THERE")
        time.sleep(0.05)
    return True


def _still_at(client: DecisionClient, joints: np.ndarray) -> bool:
    state = client.robot.get_state()
    return (state.status.name == "READY"
            and np.max(np.abs(joints - state.joint_positions)) <= HOME_TOLERANCE_RAD
            and np.max(np.abs(state.joint_velocities)) <= STILL_RAD_PER_S)


class StrokingHand:
    """Down strokes of the master's handle with the clutch engaged on the way back up. Each
    stroke takes the same time; an operator who sees the tool short of its goal adds one."""

    def __init__(self, hand_rest: pin.SE3, strokes: int):
        self.rest = hand_rest
        self.period = STROKE_S + RETURN_S
        self._strokes = [(i * self.period, STROKE_M) for i in range(strokes)]  # (start, length)

    def add(self, start_s: float, length_m: float) -> None:
        """One more stroke of `length_m` (master) from `start_s` on, the hand at rest then."""
        self._strokes.append((max(start_s, self.duration()), length_m))

    def _stroke(self, t: float) -> tuple[float, float] | None:
        """(phase, length) of the stroke under way at `t`, or None while the hand rests."""
        for start, length in self._strokes:
            if start <= t < start + self.period:
                return t - start, length
        return None

    def pose(self, t: float) -> pin.SE3:
        stroke = self._stroke(t)
        if stroke is None:
            return self.rest
        phase, length = stroke
        if phase < STROKE_S:
            depth = length * phase / STROKE_S
        else:
            depth = length * (1 - (phase - STROKE_S) / RETURN_S)
        return pin.SE3(self.rest.rotation, self.rest.translation - [0, 0, depth])

    def clutch(self, t: float) -> bool:
        stroke = self._stroke(t)
        return stroke is not None and stroke[0] >= STROKE_S

    def duration(self) -> float:
        return max((start + self.period for start, _ in self._strokes), default=0.0)


class PegInHole:
    """One run of the task, recording into `trace` and predicting the tool into `model`, in
    `cell`: the work cell of the station's arm."""

    def __init__(self, client: DecisionClient, mode: str, model: RobotModel, status=None,
                 on_link: Callable[[str, str], None] | None = None, recorder=None,
                 passivity: bool = True, cell: workspace.WorkCell = workspace.PUMA560_CELL):
        self.client = client
        self._cell = cell
        self._mouth_z = mouth_z(cell)
        # TDPA's master port, in feedback mode (compliance closes its loop on the server).
        self._passivity = MasterPassivity() if passivity and mode == "feedback" else None
        self._arm: MasterArm | None = None
        self._sent_m = np.zeros(3)  # every increment sent, summed (base axes)
        self._displayed: list[tuple[int, float]] = []  # (time ns, force shown, slave N, up)
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

    def _felt(self, hand_step_m: np.ndarray | None = None) -> float:
        """The upward force the master arm displays now (slave newtons) for the last ack's
        wrench, through TDPA's controller when it is on; call once per control step
        (`hand_step_m`: master metres moved without `arm.update`, as in the back-off)."""
        last = self._acks[-1] if self._acks else None
        if last is None or last.force is None or last.tool_pose is None:
            return 0.0
        wrench = self._arm.feedback_wrench(last.force, last.torque, last.tool_pose.rotation,
                                           hand_step_m)
        up = float(wrench[2]) / SCALE  # the master shows s·F: back to the slave's newtons
        self._displayed.append((time.time_ns(), up))
        return up

    def run(self) -> Result:
        robot = self.client.robot
        start = robot.get_state().tool_pose
        self.model.reset(start)
        approach = start.translation[2] - self._mouth_z  # to the hole's mouth
        # Feedback: push past the floor until it is felt. Compliance: most of the way in by
        # hand, the rest under force control.
        insert = HOLE_DEPTH_M + OVERREACH_M if self.mode == "feedback" else HAND_INSERT_M
        strokes = int(np.ceil((approach + insert) / (STROKE_M * SCALE)))
        hand = SimulatedHand()
        rest = hand.model.hand_pose(hand.q)
        script = StrokingHand(rest, strokes)
        hand.path = script.pose
        arm = self._arm = MasterArm(hand, translation_scale=SCALE, frame=IncrementFrame.BASE,
                                    passivity=self._passivity)
        session = self._session = self.client.teleoperate(
            "teleop-script", types_pb2.REFERENCE_FRAME_BASE, watchdog_timeout_s=0.5,
            on_ack=self._on_ack, on_link=self._on_link, passivity=self._passivity)
        if self._recorder is not None:  # every command and heartbeat, as sent
            session.on_request = self._recorder.request
        period = 1.0 / COMMAND_RATE_HZ
        # The depth that will do: in feedback mode none short of feeling the floor; in
        # compliance mode the hand's share of the insertion, the rest left to force control.
        enough = insert if self.mode == "feedback" else HAND_INSERT_M - 0.002
        script_time, extra = 0.0, 0
        try:
            while True:
                script_time, felt = self._stroke(script, arm, session, script_time, period)
                if felt or extra >= MAX_EXTRA_STROKES:
                    break
                # A station that held the arm (stale commands are refused, not applied late)
                # left the tool short: the operator sees that and strokes again, as far as it is.
                depth = self._mouth_z - self._tool_z_once_acked(session, period)
                if depth >= enough or self._blocked():
                    break
                script.add(script_time, min(STROKE_M, (insert - depth) / SCALE))
                extra += 1
            if self.mode == "compliance":
                self._comply(session, period)
            else:
                self._back_off(session, period)
                self._hold(session, period, SETTLE_S / 2)
        finally:
            session.close()
        return self._result(start)

    def _stroke(self, script: StrokingHand, arm: MasterArm, session, script_time: float,
                period: float) -> tuple[float, bool]:
        """Command the hand's strokes from `script_time` until they are done (and the hand has
        rested half a second) or, in feedback mode, the operator feels the floor: (the script's
        time then, whether it was felt)."""
        felt = False
        next_tick = time.monotonic()
        while script_time < script.duration() + 0.5 and not felt:
            next_tick += period
            if session.interrupted:  # the operator holds still until the link is back
                self._show(arm.indexing)
                time.sleep(period)
                next_tick = time.monotonic()
                continue
            arm.clutch = script.clutch(script_time)
            reference = arm.reference
            increment = arm.update(script_time)
            if self.mode == "feedback" and self._felt() > FEEL_N:
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
        return script_time, felt

    def _blocked(self) -> bool:
        """In compliance mode, whether the peg already pushes on something (the hole's floor, or
        the fixture beside it): force control takes over from there, and more strokes would
        only press harder. (In feedback mode feeling it ends the strokes.)"""
        return self.mode == "compliance" and self._contact_force() > CONTACT_N

    def _tool_z_once_acked(self, session, period: float) -> float:
        """The tool's height once every command sent has been acked (heartbeats meanwhile, up
        to ACKED_WAIT_S): where the arm went, not where it is on its way."""
        deadline = time.monotonic() + ACKED_WAIT_S
        while session.unacked and time.monotonic() < deadline:
            session.heartbeat_nowait()
            self._show(False)
            time.sleep(period)
        return float(self.client.robot.get_state().tool_pose.translation[2])

    def _send(self, delta_position, delta_rotation=None) -> bool:
        """Send one increment and predict it into the model; False when the link is down."""
        try:
            self._session.send_nowait(delta_position, delta_rotation)
        except LinkInterruptedError:
            return False
        self.model.command(delta_position, delta_rotation)
        self._sent_m = self._sent_m + np.asarray(delta_position, dtype=float)
        return True

    def _show(self, clutch: bool) -> None:
        self._status(mode=self.mode, clutch=clutch, force=self._contact_force(),
                     commands=self._commands, acks=len(self._acks),
                     round_trips=self.trace.round_trip_ms,
                     link_down=bool(self._session and self._session.interrupted))

    def _back_off(self, session, period: float) -> None:
        """Raise the peg a little at a time until the felt force is under half of FEEL_N."""
        # The hand feels between its small moves, at rest: while it moves back along the force
        # TDPA's master controller may take out what the slave has not yet paid for, and a
        # hand that stopped at that would leave the slave pressing.
        ticks = 0
        while ticks < BACK_OFF_TICKS and self._felt() >= FEEL_N / 2:
            if self._send([0.0, 0.0, BACK_OFF_STEP_M]):
                self._commands += 1
                ticks += 1
                # The hand's share of the step, weighed as it moves (master metres).
                self._felt(np.array([0.0, 0.0, BACK_OFF_STEP_M / SCALE]))
            time.sleep(period)

    def _hold(self, session, period: float, seconds: float) -> None:
        """Heartbeats only: the operator holds still while the arm settles."""
        deadline = time.monotonic() + seconds
        while time.monotonic() < deadline:
            session.heartbeat_nowait()  # (sends nothing while the link is down)
            self._show(False)
            time.sleep(period)

    def _hold_until_settled(self, session, period: float, limit_s: float) -> None:
        """Heartbeats until the contact force has stayed within SETTLED_N of the desired for
        SETTLE_S (or `limit_s` has passed): the operator watches the contact, not a clock."""
        deadline = time.monotonic() + limit_s
        settled_since = None
        while time.monotonic() < deadline:
            session.heartbeat_nowait()
            self._show(False)
            now = time.monotonic()
            if abs(self._contact_force() - DESIRED_FORCE_N) > SETTLED_N:
                settled_since = None
            elif settled_since is None:
                settled_since = now
            elif now - settled_since >= SETTLE_S:
                return
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
            approach_s = rest / (COMPLIANCE_GAIN_M_PER_N_S * DESIRED_FORCE_N)
            self._hold_until_settled(session, period, APPROACH_SLACK * approach_s + SETTLE_S)
        finally:
            self.client.set_assistance(pb.AssistanceConfig())

    def _result(self, start: Pose) -> Result:
        end = self.client.robot.get_state().tool_pose.translation
        x, y = self._cell.fixture_center_xy
        depth = self._mouth_z - end[2]
        lateral = float(np.hypot(end[0] - x, end[1] - y))
        forces = [-f[2] for f in self.trace.force_n] or [0.0]
        times = self.trace.force_time_s or [0.0]
        final = [f for f, t in zip(forces, times, strict=False) if t >= times[-1] - FINAL_WINDOW_S]
        trips = self.trace.round_trip_ms or [0.0]
        swings, p2p = contact_oscillation(forces, times, FINAL_WINDOW_S)
        return Result(
            self.mode, bool(depth > HOLE_DEPTH_M - 0.005 and lateral < workspace.HOLE_HALF_WIDTH),
            self._elapsed(), float(depth), lateral, float(max(forces)),
            float(np.mean(final)), self._commands, len(self._acks),
            float(np.percentile(trips, 50)), float(np.percentile(trips, 99)),
            self._session.resumes if self._session else 0,
            self._session.resends if self._session else 0,
            self._session.commands_acked if self._session else 0,
            self._session.commands_applied if self._session else 0,
            self._session.merged if self._session else 0,
            passivity=self._passivity is not None,
            drift_m=float(np.linalg.norm(start.translation + self._sent_m - end)),
            transparency_rms_n=self._transparency_rms(), oscillation_swings=swings,
            final_force_p2p_n=p2p, energy=self._energies())

    def _transparency_rms(self) -> float:
        """RMS of displayed minus environment force (upward, slave N) at the same instants,
        where either is over CONTACT_N: the environment's from the acks at their apply time
        (the station's clock: one host, or hosts in sync), interpolated."""
        samples = [(a.apply_time_ns, float((a.tool_pose.rotation @ a.force)[2]))
                   for a in self._acks
                   if a.force is not None and a.tool_pose is not None and a.apply_time_ns]
        if len(samples) < 2 or not self._displayed:
            return 0.0
        samples.sort()
        env_times, env = np.array(samples, dtype=float).T
        shown_times, shown = np.array(self._displayed, dtype=float).T
        inside = (shown_times >= env_times[0]) & (shown_times <= env_times[-1])
        environment = np.interp(shown_times[inside], env_times, env)
        shown = shown[inside]
        contact = (np.abs(environment) > CONTACT_N) | (np.abs(shown) > CONTACT_N)
        if not contact.any():
            return 0.0
        return float(np.sqrt(np.mean((shown[contact] - environment[contact]) ** 2)))

    def _energies(self) -> dict | None:
        if self._passivity is None:
            return None
        last = next((a.message.slave_energy for a in reversed(self._acks)
                     if a.message.HasField("slave_energy")), None)
        ledger = self._passivity.ledger
        return {"master_in_j": ledger.energy_in_j, "master_out_j": ledger.energy_out_j,
                "master_dissipated_j": self._passivity.dissipated_j,
                "slave_in_j": last.energy_in_j if last else 0.0,
                "slave_out_j": last.energy_out_j if last else 0.0,
                "slave_dissipated_j": last.dissipated_j if last else 0.0}


def contact_oscillation(forces: list[float], times: list[float], window_s: float
                        ) -> tuple[int, float]:
    """(swings, peak to peak N) of the contact force over the last `window_s`: a swing is a
    move of more than SWING_N between successive turning points (a hysteresis of SWING_N, so
    sensor noise and a slow settle count none)."""
    if not forces:
        return 0, 0.0
    end = times[-1]
    window = [f for f, t in zip(forces, times, strict=True) if t >= end - window_s]
    swings, extreme, direction = 0, window[0], 0
    for force in window[1:]:
        if direction == 0:  # the first move away from the window's start sets a direction
            if abs(force - extreme) > SWING_N:
                direction, extreme = (1 if force > extreme else -1), force
        elif (force - extreme) * direction > 0:
            extreme = force  # still going the same way: a new turning point candidate
        elif abs(force - extreme) > SWING_N:
            swings += 1  # turned back by more than SWING_N
            direction, extreme = -direction, force
    return swings, float(max(window) - min(window))
