"""RobotModel: predicts the gripper from the commands, converges to the server's pose."""

from __future__ import annotations

import threading
import time

import numpy as np
import pinocchio as pin
import pytest

from clients.ar.adapters import RobotModelFeed, pose_matrix, pose_message
from clients.ar.model import (
    CorrectionMode,
    Frame,
    RobotModel,
    apply_increment,
    blend_pose,
    make_pose,
    pose_error,
    puma_forward_kinematics,
    rotation_exp,
    rotation_log,
)
from domain.robot_model.kinematics import ArmKinematics
from domain.robot_model.puma560 import HOME_Q
from services.proxy_robot.core import ProxyRobotCore
from services.proxy_robot.servicer import event_to_proto, snapshot_to_proto
from services.proxy_robot.status import Moved
from services.world.link import ArmSample
from telerobot.v1 import proxy_robot_pb2, types_pb2
from wire import convert

RNG = np.random.default_rng(0)


def _random_rotation(rng, max_angle=0.5) -> np.ndarray:
    axis = rng.normal(size=3)
    return rotation_exp(axis / np.linalg.norm(axis) * rng.uniform(0, max_angle))


def _home_pose() -> np.ndarray:
    return np.array(ArmKinematics().tool_pose(HOME_Q).homogeneous)


class FakeServer:
    """The arm as the server sees it: applies each increment exactly to the true tool pose."""

    def __init__(self, pose):
        self.pose = np.array(pose, float)

    def move(self, delta, rotation=None, frame=Frame.BASE) -> np.ndarray:
        self.pose = apply_increment(self.pose, delta, rotation, frame)
        return self.pose.copy()


# -- increments ----------------------------------------------------------------------------------


def test_increments_follow_the_proxy_robot_contract():
    """BASE: p + ΔX, ΔM R about the tool point; TOOL: tool · (ΔM, ΔX); WRIST: flange · Δ · F."""
    tool = pin.SE3(_random_rotation(RNG, 3.0), RNG.normal(size=3))
    delta = pin.SE3(_random_rotation(RNG), RNG.normal(size=3) * 0.05)
    offset = pin.SE3(_random_rotation(RNG), np.array([0.0, 0.0, 0.1]))
    base = apply_increment(tool.homogeneous, delta.translation, delta.rotation, "BASE")
    np.testing.assert_allclose(base[:3, 3], tool.translation + delta.translation)
    np.testing.assert_allclose(base[:3, :3], delta.rotation @ tool.rotation)
    np.testing.assert_allclose(apply_increment(tool, delta.translation, delta.rotation, "TOOL"),
                               (tool * delta).homogeneous, atol=1e-12)
    flange = tool * offset.inverse()
    np.testing.assert_allclose(
        apply_increment(tool, delta.translation, delta.rotation, Frame.WRIST, offset),
        (flange * delta * offset).homogeneous, atol=1e-12)


def test_rotation_helpers_round_trip_and_blend_along_the_geodesic():
    for angle in (1e-9, 0.3, 2.0, np.pi - 1e-6):
        axis = RNG.normal(size=3)
        vector = axis / np.linalg.norm(axis) * angle
        rotation = rotation_exp(vector)
        np.testing.assert_allclose(rotation_exp(rotation_log(rotation)), rotation, atol=1e-6)
    a = make_pose(_random_rotation(RNG, 1.0), [0, 0, 0])
    b = make_pose(_random_rotation(RNG, 1.0), [1, 2, 3])
    half = blend_pose(a, b, 0.5)
    np.testing.assert_allclose(half[:3, 3], [0.5, 1.0, 1.5])
    assert pose_error(a, half)[1] == pytest.approx(pose_error(half, b)[1])
    np.testing.assert_allclose(blend_pose(a, b, 1.0), b, atol=1e-12)


# -- prediction and correction -----------------------------------------------------------------


def test_snap_on_moved_events_removes_a_deliberate_bias():
    """The model is told 20 % more than the arm does (a mis-set scale); without acknowledgements
    (the paper's scheme) the error grows with every command, and each moved event snaps it to
    zero."""
    home = _home_pose()
    server, model = FakeServer(home), RobotModel(home)
    steps = [np.array([0.01, -0.005, 0.004]), np.array([0.0, 0.01, -0.01]),
             np.array([-0.008, 0.0, 0.012])]
    for delta in steps * 3:  # nine commands, no correction
        model.command(1.2 * delta, frame=Frame.BASE)
        server.move(delta)
    drift = pose_error(model.tool_pose, server.pose)[0]
    assert drift == pytest.approx(0.2 * np.linalg.norm(3 * sum(steps)), rel=1e-9)
    model.correct(server.pose)  # the moved event
    assert pose_error(model.tool_pose, server.pose) == pytest.approx((0.0, 0.0), abs=1e-12)
    assert model.pending == 0
    for delta in steps:  # one command, one moved event: the error never exceeds one bias
        model.command(1.2 * delta, _random_rotation(RNG, 0.1), Frame.TOOL)
        server.move(delta, None, Frame.TOOL)
        assert pose_error(model.tool_pose, server.pose)[0] <= 0.2 * np.linalg.norm(delta) + 0.01
        model.correct(server.pose)
        np.testing.assert_allclose(model.tool_pose, server.pose, atol=1e-12)


def test_blend_converges_geometrically_while_the_arm_rests():
    home = _home_pose()
    server = FakeServer(home)
    model = RobotModel(home, mode=CorrectionMode.BLEND, gain=0.3)
    model.command([0.04, 0.0, 0.0], rotation_exp([0.0, 0.0, 0.2]), Frame.BASE)  # biased
    server.move([0.03, 0.01, 0.0], rotation_exp([0.0, 0.0, 0.1]))
    errors = [pose_error(model.tool_pose, server.pose)]
    for _ in range(40):  # state samples at rest
        model.correct(server.pose)
        errors.append(pose_error(model.tool_pose, server.pose))
    position, angle = np.array(errors).T
    np.testing.assert_allclose(position[1:] / position[:-1], 0.7, rtol=1e-6)
    np.testing.assert_allclose(angle[1:] / angle[:-1], 0.7, rtol=1e-4)
    assert position[-1] < 1e-7 and angle[-1] < 1e-7
    assert model.corrections == 40


def test_acknowledgements_reanchor_and_replay_the_commands_in_flight():
    home = _home_pose()
    server, model = FakeServer(home), RobotModel(home)
    deltas = [np.array([0.01, 0, 0]), np.array([0, 0.01, 0]), np.array([0, 0, 0.01])]
    ids = [model.command(1.2 * d) for d in deltas]  # three in flight, biased
    targets = [server.move(d) for d in deltas]
    assert model.pending == 3
    model.acknowledge(ids[0], targets[0])  # the server's target for the first...
    expected = apply_increment(apply_increment(targets[0], 1.2 * deltas[1]), 1.2 * deltas[2])
    np.testing.assert_allclose(model.tool_pose, expected)  # ...plus the two still in flight
    model.acknowledge(ids[2], targets[2])
    np.testing.assert_allclose(model.tool_pose, server.pose)
    assert model.pending == 0
    model.acknowledge(ids[1], targets[1])  # late and stale: ignored
    np.testing.assert_allclose(model.tool_pose, server.pose)

    # a command in flight when a moved event for the previous target arrives: the correction
    # drops it, its reply brings it back
    in_flight = model.command([0.0, 0.0, -0.01])
    model.correct(server.pose)
    np.testing.assert_allclose(model.tool_pose, server.pose)
    model.acknowledge(in_flight, server.move([0.0, 0.0, -0.01]))
    np.testing.assert_allclose(model.tool_pose, server.pose)


def test_a_refused_command_is_taken_back():
    home = _home_pose()
    model = RobotModel(home)
    first = model.command([0.01, 0.0, 0.0])
    refused = model.command([0.0, 0.3, 0.0])  # say, past the workspace
    last = model.command([0.0, 0.0, 0.01])
    model.reject(refused)
    np.testing.assert_allclose(model.tool_point, home[:3, 3] + [0.01, 0.0, 0.01])
    assert model.pending == 2
    model.reject(refused)  # twice: nothing more to take back
    model.acknowledge(first, apply_increment(home, [0.01, 0.0, 0.0]))
    model.acknowledge(last, apply_increment(home, [0.01, 0.0, 0.01]))
    assert model.pending == 0


def test_correcting_from_joint_angles_uses_the_robots_kinematics():
    q = HOME_Q + np.array([0.2, -0.1, 0.15, 0.3, 0.2, -0.4])
    model = RobotModel(_home_pose(), forward_kinematics=puma_forward_kinematics())
    model.correct_joints(q)
    np.testing.assert_allclose(model.tool_pose, ArmKinematics().tool_pose(q).homogeneous,
                               atol=1e-12)
    with pytest.raises(ValueError, match="no forward kinematics"):
        RobotModel(_home_pose()).correct_joints(q)


def test_bad_settings_are_refused():
    with pytest.raises(ValueError, match="gain"):
        RobotModel(np.eye(4), mode="blend", gain=0.0)
    with pytest.raises(ValueError, match="4x4"):
        RobotModel(np.eye(3))
    with pytest.raises(ValueError):
        RobotModel(np.eye(4)).command([0, 0, 0], frame="ELBOW")


# -- protobuf feed -------------------------------------------------------------------------------


def test_the_feed_builds_requests_and_reads_replies_events_and_states():
    home = _home_pose()
    feed = RobotModelFeed(RobotModel(home))
    request, command_id = feed.request([0.01, 0.0, -0.02], frame=Frame.TOOL)
    assert request.frame == types_pb2.REFERENCE_FRAME_TOOL
    assert (request.delta_position_m.x, request.delta_position_m.z) == (0.01, -0.02)
    assert not request.delta_rotation.row_major
    target = apply_increment(home, [0.009, 0.0, -0.02], frame=Frame.TOOL)
    feed.on_reply(command_id, proxy_robot_pb2.MoveCartesianIncrementalResponse(
        target_tool_pose=pose_message(target), applied_fraction=1.0))
    np.testing.assert_allclose(feed.model.tool_pose, target, atol=1e-12)

    moving = types_pb2.RobotState(status=types_pb2.ROBOT_STATUS_MOVING,
                                  tool_pose=pose_message(home))
    assert not feed.on_state(moving)  # a moving arm lags the command: not a correction
    np.testing.assert_allclose(feed.model.tool_pose, target, atol=1e-12)

    reached = apply_increment(target, [0.0005, 0.0, 0.0])  # round-off at the arm
    event = proxy_robot_pb2.StreamRobotEventsResponse(
        sequence=7, moved=proxy_robot_pb2.MovedEvent(joint_positions_rad=list(HOME_Q),
                                                     tool_pose=pose_message(reached)))
    assert feed.on_event(event)
    np.testing.assert_allclose(feed.model.tool_pose, reached, atol=1e-12)

    rest = types_pb2.RobotState(status=types_pb2.ROBOT_STATUS_READY, tool_pose=pose_message(home))
    sample = proxy_robot_pb2.StreamRobotEventsResponse(
        data_received=proxy_robot_pb2.DataReceivedEvent(state=rest))
    status = proxy_robot_pb2.StreamRobotEventsResponse(
        status_changed=proxy_robot_pb2.StatusChangedEvent(status=types_pb2.ROBOT_STATUS_READY))
    assert feed.follow([status, sample]) == 1
    np.testing.assert_allclose(feed.model.tool_pose, home, atol=1e-12)
    np.testing.assert_allclose(pose_matrix(pose_message(home)), home, atol=1e-15)

    request, command_id = feed.request([0.0, 0.0, 0.05], rotation_exp([0.1, 0.0, 0.0]))
    assert len(request.delta_rotation.row_major) == 9
    feed.on_refused(command_id)  # e.g. OUT_OF_RANGE: the arm will not go there
    np.testing.assert_allclose(feed.model.tool_pose, home, atol=1e-12)


# -- against the real ProxyRobot core ------------------------------------------------------------


class OffsetArm:
    """An in-process ArmLink whose servo settles at once, but a little off the target (a
    mechanical error within the proxy's arrival tolerance, as on a real arm)."""

    OFFSET = np.array([0.0, 1.5e-3, -1.5e-3, 0.0, 1.0e-3, 0.0])  # rad

    def __init__(self):
        self._lock = threading.Lock()
        self._target = HOME_Q.copy()
        self._sequence = 0

    def read_arm(self) -> ArmSample:
        with self._lock:
            self._sequence += 1
            return ArmSample(self._sequence, time.time_ns(), self._target + self.OFFSET,
                             np.zeros(6), self._target.copy(), False, "")

    def write_target(self, joint_positions_rad: np.ndarray, duration_s: float = 0.0) -> None:
        with self._lock:
            self._target = np.asarray(joint_positions_rad, float).copy()

    def hold(self) -> None:
        pass

    def release_hold(self) -> None:
        pass

    def close(self) -> None:
        pass


@pytest.fixture
def proxy():
    core = ProxyRobotCore(OffsetArm)
    core.connect()
    core.initialize()
    yield core
    core.close()


def _next_moved(subscription, timeout_s: float = 10.0):
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        event = subscription.get(timeout_s=0.5)
        if event is not None and isinstance(event.payload, Moved):
            return event
    raise AssertionError("no moved event")


def test_the_model_follows_the_real_proxy_through_its_messages(proxy):
    """Commands go to ProxyRobotCore (IK, joint limits, targets); the replies and the moved
    events reach the model as the protobuf messages a client receives."""
    start = snapshot_to_proto(proxy.snapshot())
    feed = RobotModelFeed(RobotModel(pose_matrix(start.tool_pose)))
    moves = [([0.02, 0.0, 0.0], None, Frame.BASE), ([0.0, -0.015, 0.01], None, Frame.BASE),
             ([0.0, 0.0, 0.02], rotation_exp([0.0, 0.0, 0.1]), Frame.TOOL),
             ([0.01, 0.01, 0.0], rotation_exp([0.05, 0.0, 0.0]), Frame.BASE)]
    with proxy.events.subscribe() as events:
        for delta, rotation, frame in moves:
            request, command_id = feed.request(delta, rotation, frame)
            target_q, target_pose, fraction = proxy.move_cartesian(
                convert.vector3_from_proto(request.delta_position_m, "delta"),
                convert.rotation_from_proto(request.delta_rotation, "rotation"), frame.value)
            feed.on_reply(command_id, proxy_robot_pb2.MoveCartesianIncrementalResponse(
                target_joint_positions_rad=list(target_q),
                target_tool_pose=convert.pose_to_proto(target_pose), applied_fraction=fraction))
            # the prediction is the server's target; the arm settles a little off it
            moved = event_to_proto(_next_moved(events))
            arm_pose = pose_matrix(moved.moved.tool_pose)
            before = pose_error(feed.model.tool_pose, arm_pose)[0]
            assert 1e-4 < before < 5e-3
            assert feed.on_event(moved)
            assert pose_error(feed.model.tool_pose, arm_pose)[0] < 1e-12
            # The event carried where the arm is, not its target: on a loaded machine the arm
            # may still creep within its arrival tolerance before this snapshot is read.
            latest = np.array(proxy.snapshot().tool_pose.homogeneous)
            assert pose_error(feed.model.tool_pose, latest)[0] < 2e-3
