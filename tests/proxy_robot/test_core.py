"""ProxyRobotCore on the real simulated arm: the status machine, eq. 1 mappings, the e-stop latch
and every kind of bad input."""

from __future__ import annotations

import time

import numpy as np
import pinocchio as pin
import pytest

from services.proxy_robot import core as core_module
from services.proxy_robot.core import ProxyRobotCore
from services.proxy_robot.status import Moved, RobotErrorRaised, RobotStatus, StatusChanged
from services.robot_model.puma560 import HOME_Q
from services.runtime.errors import FailedPrecondition, InvalidArgument, OutOfRange, Unavailable
from services.world.shm_link import SharedMemoryArmLink
from tests.conftest import wait_for

S = RobotStatus


def wait_ready(core: ProxyRobotCore, timeout_s: float = 10.0) -> None:
    wait_for(lambda: core.status[0] == S.READY, timeout_s, "READY")


def drain(subscription) -> list:
    items = []
    while (item := subscription.get(0.0)) is not None:
        items.append(item)
    return items


def rot_z(angle: float) -> np.ndarray:
    return pin.utils.rotate("z", angle)


def test_full_status_cycle_with_an_event_for_every_change(core):
    events = core.events.subscribe(256)
    assert core.status[0] == S.NOT_CONNECTED
    with pytest.raises(FailedPrecondition, match="Connect first"):
        core.snapshot()
    assert core.connect() == S.CONNECTED
    assert core.initialize() == S.READY
    core.move_joints([0.05, 0, 0, 0, 0, 0])
    assert core.status[0] == S.MOVING
    wait_ready(core)
    assert core.emergency_stop("test")[0] == S.ESTOPPED
    assert core.reset() == S.READY
    assert core.disconnect() == S.NOT_CONNECTED

    changes = [(e.payload.previous, e.payload.status) for e in drain(events)
               if isinstance(e.payload, StatusChanged)]
    assert changes == [
        (S.NOT_CONNECTED, S.CONNECTED), (S.CONNECTED, S.INITIALIZING), (S.INITIALIZING, S.READY),
        (S.READY, S.MOVING), (S.MOVING, S.READY), (S.READY, S.ESTOPPED), (S.ESTOPPED, S.READY),
        (S.READY, S.NOT_CONNECTED),
    ]


def test_event_sequence_has_no_gaps_and_moved_follows_arrival(ready):
    events = ready.events.subscribe(256)
    ready.move_joints([0, 0.05, 0, 0, 0, 0])
    wait_ready(ready)
    received = drain(events)
    assert [e.sequence for e in received] == list(
        range(received[0].sequence, received[0].sequence + len(received)))
    moved = [e.payload for e in received if isinstance(e.payload, Moved)]
    assert len(moved) == 1
    np.testing.assert_allclose(moved[0].joint_positions_rad, ready.snapshot().joint_positions_rad,
                               atol=core_module.ARRIVAL_TOLERANCE_RAD)


def test_reset_from_estop_without_initialize_returns_to_connected(core):
    core.connect()
    core.emergency_stop("before init")
    assert core.reset() == S.CONNECTED
    with pytest.raises(FailedPrecondition, match="Initialize first"):
        core.move_joints([0.01, 0, 0, 0, 0, 0])


def test_connect_without_a_world_is_unavailable():
    proxy = ProxyRobotCore(lambda: SharedMemoryArmLink("telerobot_test_no_such_world"))
    with pytest.raises(Unavailable, match="no world is running"):
        proxy.connect()
    assert proxy.status[0] == S.NOT_CONNECTED


def test_arm_tracks_commanded_joints_in_steady_state(ready):
    target, _ = ready.move_joints([0.1, -0.05, 0.08, 0.1, -0.1, 0.2])
    wait_ready(ready)
    time.sleep(0.2)
    np.testing.assert_allclose(ready.snapshot().joint_positions_rad, target, atol=1e-4)


def test_increments_add_to_the_target_not_the_lagging_arm(ready):
    start = ready._target_q.copy()  # noqa: SLF001
    for _ in range(4):
        target, _ = ready.move_joints([0.05, 0, 0, 0, 0, 0])
    np.testing.assert_allclose(target - start, [0.2, 0, 0, 0, 0, 0], atol=1e-9)
    wait_ready(ready)


def test_tool_mapping_moves_along_the_tool_axis(ready):
    before = ready.snapshot().tool_pose
    _, target_pose, fraction = ready.move_cartesian([0.02, 0, 0], np.eye(3), "TOOL")
    assert fraction == 1.0
    # `before` is measured; increments apply to the commanded target, which differs by ~1e-5.
    np.testing.assert_allclose(target_pose.translation - before.translation,
                               0.02 * before.rotation[:, 0], atol=1e-4)
    np.testing.assert_allclose(target_pose.rotation, before.rotation, atol=1e-4)
    wait_ready(ready)
    after = ready.snapshot().tool_pose
    np.testing.assert_allclose(after.translation - before.translation,
                               0.02 * before.rotation[:, 0], atol=2e-4)


def test_base_mapping_moves_along_the_base_axis_and_rotates_about_the_tool_point(ready):
    before = ready.snapshot().tool_pose
    _, target_pose, _ = ready.move_cartesian([0, 0, 0.01], rot_z(0.1), "BASE")
    np.testing.assert_allclose(target_pose.translation - before.translation, [0, 0, 0.01],
                               atol=1e-4)
    np.testing.assert_allclose(target_pose.rotation, rot_z(0.1) @ before.rotation, atol=1e-4)
    wait_ready(ready)


def test_tool_rotation_keeps_the_tool_point_fixed(ready):
    before = ready.snapshot().tool_pose
    _, target_pose, _ = ready.move_cartesian([0, 0, 0], pin.utils.rotate("x", 0.1), "TOOL")
    np.testing.assert_allclose(target_pose.translation, before.translation, atol=1e-4)
    np.testing.assert_allclose(target_pose.rotation,
                               before.rotation @ pin.utils.rotate("x", 0.1), atol=1e-4)
    wait_ready(ready)


def test_wrist_mapping_moves_the_flange_and_the_tool_follows(ready):
    flange = ready.snapshot().flange_pose
    target_q, target_pose, _ = ready.move_cartesian([0, 0.01, 0], np.eye(3), "WRIST")
    expected_flange = flange * pin.SE3(np.eye(3), np.array([0, 0.01, 0]))
    np.testing.assert_allclose(target_pose.translation,
                               (expected_flange * ready.tool_frame).translation, atol=1e-4)
    wait_ready(ready)


def test_bad_input_moves_nothing(ready):
    wait_ready(ready)
    position_before = ready.snapshot().joint_positions_rad
    target_before = ready._target_q.copy()  # noqa: SLF001 - the commanded target itself
    bad_calls = [
        (InvalidArgument, "NaN", lambda: ready.move_joints([np.nan, 0, 0, 0, 0, 0])),
        (InvalidArgument, "NaN or Inf",
         lambda: ready.move_cartesian([np.inf, 0, 0], np.eye(3), "TOOL")),
        (InvalidArgument, "needs 6 values", lambda: ready.move_joints([0.1, 0.1])),
        (InvalidArgument, "needs 3 values",
         lambda: ready.move_cartesian([0.1], np.eye(3), "TOOL")),
        (InvalidArgument, "unknown frame",
         lambda: ready.move_cartesian([0, 0, 0.01], np.eye(3), "CAMERA")),
        (OutOfRange, "cap of 28.6 deg", lambda: ready.move_joints([0.6, 0, 0, 0, 0, 0])),
        (OutOfRange, "cap of 50 mm",
         lambda: ready.move_cartesian([0.06, 0, 0], np.eye(3), "BASE")),
        (OutOfRange, "cap of 15 deg", lambda: ready.move_cartesian([0, 0, 0], rot_z(0.3), "BASE")),
    ]
    for error, message, call in bad_calls:
        with pytest.raises(error, match=message):
            call()
    np.testing.assert_array_equal(ready._target_q, target_before)  # noqa: SLF001
    assert ready.status[0] == S.READY
    time.sleep(0.05)
    # Still settling within the arrival tolerance of the old target, nowhere near a new one.
    np.testing.assert_allclose(ready.snapshot().joint_positions_rad, position_before, atol=1e-4)


def test_joint_limit_is_out_of_range_and_keeps_the_target(ready):
    # Joint 5 starts at -45 deg, limit -100 deg: the second -28.6 deg step would pass it.
    ready.move_joints([0, 0, 0, 0, -0.5, 0])
    target = ready._target_q.copy()  # noqa: SLF001
    with pytest.raises(OutOfRange, match=r"joint 5 target -102.\d deg is past its limit"):
        ready.move_joints([0, 0, 0, 0, -0.5, 0])
    np.testing.assert_array_equal(ready._target_q, target)  # noqa: SLF001
    wait_ready(ready)


def test_moves_while_not_ready_are_failed_precondition(core):
    with pytest.raises(FailedPrecondition, match="Connect and Initialize first"):
        core.move_joints([0.01, 0, 0, 0, 0, 0])
    core.connect()
    with pytest.raises(FailedPrecondition, match="Initialize first"):
        core.move_cartesian([0, 0, 0.01], np.eye(3), "BASE")


def test_pushing_out_of_reach_is_refused_and_never_jumps(ready):
    previous = ready._target_q.copy()  # noqa: SLF001
    with pytest.raises(OutOfRange, match="workspace|singularity|past its limit"):
        for _ in range(60):
            target, _, _ = ready.move_cartesian([0.05, 0, 0.0], np.eye(3), "BASE")
            assert np.max(np.abs(target - previous)) <= core_module.MAX_IK_JOINT_STEP_RAD
            previous = target
    np.testing.assert_array_equal(ready._target_q, previous)  # noqa: SLF001
    ready.emergency_stop("end of test")  # stop the long way back rather than wait for it


def test_near_the_wrist_singularity_cartesian_moves_are_refused(ready):
    # q5 from -45 deg to about -0.9 deg: the wrist axes 4 and 6 almost align.
    ready.move_joints([0, 0, 0, 0, 0.5, 0])
    ready.move_joints([0, 0, 0, 0, 0.27, 0])
    wait_ready(ready)
    # Turning about the tool x axis here needs joints 4 and 6 to flip by about 1.5 rad.
    with pytest.raises(OutOfRange, match="singularity"):
        ready.move_cartesian([0, 0, 0], pin.utils.rotate("x", 0.05), "TOOL")
    # Turning about the tool axis is joint 6 alone: allowed, and it does not jump.
    before = ready._target_q.copy()  # noqa: SLF001
    target, _, fraction = ready.move_cartesian([0, 0, 0], rot_z(0.1), "TOOL")
    assert fraction == 1.0 and np.max(np.abs(target - before)) < 0.11
    # Turning about the tool y axis (joint 5) steers out of the singularity.
    ready.move_cartesian([0, 0, 0], pin.utils.rotate("y", -0.2), "TOOL")


def test_emergency_stop_latches_until_reset_and_reset_does_not_move(ready):
    ready.move_joints([0.4, 0, 0, 0, 0, 0])
    time.sleep(0.1)  # mid-move
    status, _ = ready.emergency_stop("operator pressed stop")
    assert status == S.ESTOPPED
    assert "operator pressed stop" in ready.status[1]
    with pytest.raises(FailedPrecondition, match="emergency stop is latched"):
        ready.move_joints([0.01, 0, 0, 0, 0, 0])
    with pytest.raises(FailedPrecondition, match="Reset first"):
        ready.initialize()
    time.sleep(0.3)  # braking takes at most 0.1 s
    halted = ready.snapshot()
    assert np.max(np.abs(halted.joint_velocities_rad_per_s)) < 1e-2
    assert ready.emergency_stop("again")[0] == S.ESTOPPED  # idempotent

    assert ready.reset() == S.READY
    time.sleep(0.2)
    after = ready.snapshot()
    np.testing.assert_allclose(after.joint_positions_rad, halted.joint_positions_rad, atol=1e-4)
    assert ready.status[0] == S.READY


def test_hold_latched_at_the_hardware_shows_as_estopped(ready):
    ready._link.hold()  # noqa: SLF001 - a latch the status machine did not ask for
    wait_for(lambda: ready.status[0] == S.ESTOPPED, what="ESTOPPED")
    assert "at the hardware" in ready.status[1]
    assert ready.reset() == S.READY


def test_link_loss_drops_to_not_connected_with_an_error_event(world_factory):
    world = world_factory()
    proxy = ProxyRobotCore(lambda: SharedMemoryArmLink(world.shm_name))
    events = proxy.events.subscribe(64)
    proxy.connect()
    proxy.initialize()
    world.running.stop()
    wait_for(lambda: proxy.status[0] == S.NOT_CONNECTED, what="NOT_CONNECTED")
    errors = [e.payload for e in drain(events) if isinstance(e.payload, RobotErrorRaised)]
    assert errors and errors[0].reason == "LINK_LOST"
    with pytest.raises(Unavailable):
        proxy.connect()
    proxy.close()


def test_tool_frame_is_used_for_tool_poses(ready):
    tool_frame = pin.SE3(np.eye(3), np.array([0, 0, 0.2]))
    ready.set_tool_frame(tool_frame)

    def tool_follows(snapshot) -> bool:
        expected = (snapshot.flange_pose * tool_frame).translation
        return np.allclose(snapshot.tool_pose.translation, expected, atol=1e-9)

    wait_for(lambda: tool_follows(ready.snapshot()), what="tool pose")
    assert np.isclose(np.linalg.norm(
        ready.snapshot().tool_pose.translation - ready.snapshot().flange_pose.translation), 0.2)
    with pytest.raises(InvalidArgument, match="at most 1.0 m"):
        ready.set_tool_frame(pin.SE3(np.eye(3), np.array([0, 0, 1.5])))


def test_a_50_hz_command_stream_is_spread_over_the_servo_rate(ready, world):
    """Each 20 ms command becomes a straight segment of 1 ms setpoints, so the servo's target
    moves every period instead of jumping every 20 ms."""
    link = SharedMemoryArmLink(world.shm_name)  # read-only here: the proxy is the driver
    try:
        seen = []
        for _ in range(10):
            ready.move_joints([0.004, 0, 0, 0, 0, 0])
            deadline = time.monotonic() + 0.02
            while time.monotonic() < deadline:
                seen.append(link.read_arm().joint_targets_rad[0])
                time.sleep(0.0005)
    finally:
        link.close()
    distinct = np.unique(np.round(seen, 9))
    assert len(distinct) > 60  # ~20 setpoints per command, not one
    # The median, not the max: when this reading thread is descheduled on a loaded machine it
    # misses setpoints, which shows up as one large step that the servo never took.
    assert np.median(np.diff(distinct)) < 0.001  # a whole command would be a 0.004 rad step
    wait_ready(ready)


def test_hold_stops_without_latching(ready):
    ready.move_joints([0.5, 0, 0, 0, 0, 0])
    time.sleep(0.15)
    target = ready.hold()
    wait_ready(ready)
    np.testing.assert_allclose(ready.snapshot().joint_positions_rad, target, atol=3e-3)
    assert abs(target[0] - ready._target_q[0]) < 1e-12  # noqa: SLF001
    assert target[0] - HOME_Q[0] < 0.45  # it did not go on to the old target
    ready.move_joints([0.01, 0, 0, 0, 0, 0])  # and motion is accepted at once
