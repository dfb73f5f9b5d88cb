"""The scripted operator watches the tool, not a plan: when the station holds the arm (stale
commands are refused, never applied late), it strokes again until the tool gets where it aims.

The station here is a fake of the DecisionClient port with honest physics: a stiff position-
controlled arm, whose target moves by each applied increment; the tool follows it down to what
it meets (the hole's floor, or the fixture's top), which stops it and pushes back in proportion
to how far the target lies beyond. It refuses the commands that arrive inside a window, as a
station starved past a backlog does."""

from __future__ import annotations

import time
from types import SimpleNamespace

import numpy as np
import pytest

from clients.ar import RobotModel
from clients.python.values import Ack, CommandOutcome, RobotStatus
from clients.teleop import task
from clients.teleop.task import StrokingHand
from telerobot.v1 import decision_server_pb2 as ds_pb
from wire.pose import Pose

FLOOR_STIFFNESS_N_PER_M = 2e4
FLOOR_Z = task.MOUTH_Z - task.HOLE_DEPTH_M
PEG_DOWN = np.diag([1.0, -1.0, -1.0])  # the tool's z runs down the peg


class HeldStation:
    """A station whose arm is held (each command REJECTED) for commands `held` (sequences)."""

    def __init__(self, start_z: float, held: range, floor_z: float = FLOOR_Z):
        self.target = np.array([*task.workspace.FIXTURE_CENTER_XY, start_z])
        self.held = held
        self.floor_z = floor_z  # what the peg meets: the hole's floor, or the fixture's top
        self.refused = 0
        self.assistance = []
        self.robot = SimpleNamespace(get_state=lambda: SimpleNamespace(tool_pose=self.pose()))

    def pose(self) -> Pose:
        tool = self.target.copy()
        tool[2] = max(tool[2], self.floor_z)  # stopped by what it meets
        return Pose(PEG_DOWN, tool)

    def force(self) -> np.ndarray:
        # The floor pushes up the peg: along the tool's −z.
        return np.array([0.0, 0.0,
                         -FLOOR_STIFFNESS_N_PER_M * max(0.0, self.floor_z - self.target[2])])

    def teleoperate(self, *args, on_ack, **kwargs):
        return HeldSession(self, on_ack)

    def set_assistance(self, config) -> None:
        self.assistance.append(config)  # (force control is the station's: not simulated)


class HeldSession:
    interrupted = False
    unacked = 0
    resumes = resends = merged = 0

    def __init__(self, station: HeldStation, on_ack):
        self.station, self.on_ack = station, on_ack
        self.sequence = self.commands_acked = self.commands_applied = 0

    def send_nowait(self, delta_position, delta_rotation=None) -> None:
        self.sequence += 1
        held = self.sequence in self.station.held
        if held:
            self.station.refused += 1
        else:
            self.station.target = self.station.target + np.asarray(delta_position, dtype=float)
            self.commands_applied += 1
        self.commands_acked += 1
        self._ack(self.sequence, CommandOutcome.REJECTED if held else CommandOutcome.APPLIED)

    def heartbeat_nowait(self) -> None:
        self._ack(0, CommandOutcome.APPLIED)

    def _ack(self, sequence: int, outcome) -> None:
        now = time.time_ns()
        self.on_ack(Ack(sequence, outcome, "", now, now, now, now, self.station.pose(),
                        self.station.force(), np.zeros(3), RobotStatus.MOVING,
                        ds_pb.CommandAck()))

    def close(self) -> None:
        pass


@pytest.fixture
def quick_strokes(monkeypatch):
    """The operator's strokes in a fifth of their time, the same lengths, commanded four times
    as often (each command's step is then under a millimetre, as it is at the real pace)."""
    monkeypatch.setattr(task, "STROKE_S", 0.3)
    monkeypatch.setattr(task, "RETURN_S", 0.12)
    monkeypatch.setattr(task, "COMMAND_RATE_HZ", 200.0)
    monkeypatch.setattr(task, "SETTLE_S", 0.2)


def run_feedback(station: HeldStation):
    model = RobotModel(station.pose())
    return task.PegInHole(station, "feedback", model, passivity=False).run()


def test_an_operator_whose_commands_the_station_refused_strokes_again_and_seats_the_peg(
        quick_strokes):
    station = HeldStation(task.MOUTH_Z + 0.21, held=range(20, 140))  # 120 commands: 100 mm
    result = run_feedback(station)
    assert station.refused == 120
    assert result.success, result
    assert result.peak_force_n > task.FEEL_N  # it pushed until it felt the floor
    assert result.commands > station.refused


def test_an_operator_whose_every_command_was_applied_adds_no_stroke(quick_strokes):
    station = HeldStation(task.MOUTH_Z + 0.21, held=range(0))
    result = run_feedback(station)
    assert result.success, result
    # Six planned strokes of 5 cm bring it to the floor: none of them more.
    assert result.commands <= nominal_commands(task.HOLE_DEPTH_M + task.OVERREACH_M)


def nominal_commands(insert_m: float) -> float:
    """At most the commands of the planned strokes: one per tick of each (the way back up, the
    clutch held, included)."""
    strokes = int(np.ceil((0.21 + insert_m) / (task.STROKE_M * task.SCALE)))
    return strokes * (task.STROKE_S + task.RETURN_S) * task.COMMAND_RATE_HZ + strokes


def test_a_compliance_operator_whose_peg_meets_the_fixture_adds_no_stroke(quick_strokes,
                                                                          monkeypatch):
    """Beside the hole the peg meets the fixture's top: the operator hands over to force
    control rather than press on with more strokes."""
    monkeypatch.setattr(task, "APPROACH_SLACK", 0.0)  # (the station's force loop is not here)
    station = HeldStation(task.MOUTH_Z + 0.21, held=range(0), floor_z=task.MOUTH_Z)
    result = task.PegInHole(station, "compliance", RobotModel(station.pose())).run()
    assert not result.success and result.peak_force_n > task.CONTACT_N
    assert result.commands <= nominal_commands(task.HAND_INSERT_M)
    assert len(station.assistance) == 2  # force control on, then off


def test_a_stroke_added_starts_from_the_rest_after_the_last():
    rest = task.pin.SE3.Identity()
    hand = StrokingHand(rest, strokes=1)
    assert hand.duration() == pytest.approx(task.STROKE_S + task.RETURN_S)
    hand.add(0.5, 0.02)  # asked for while the first is under way: it follows it
    first_end = task.STROKE_S + task.RETURN_S
    assert hand.duration() == pytest.approx(2 * first_end)
    assert np.allclose(hand.pose(first_end).translation, rest.translation)
    halfway = first_end + task.STROKE_S / 2
    assert hand.pose(halfway).translation[2] == pytest.approx(-0.01)
    assert not hand.clutch(halfway) and hand.clutch(first_end + task.STROKE_S + 0.01)
    assert np.allclose(hand.pose(10.0).translation, rest.translation)  # done: at rest
