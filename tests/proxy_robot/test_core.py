"""ProxyRobotCore on a fake arm and a fake clock: the status machine, eq. 1 mappings, the e-stop
latch, faults, link loss and every kind of bad input. The test drives the proxy's monitor and
setpoints itself (tests/proxy_robot/conftest.py's Rig). The tests marked e2e run the real
simulated arm, for what only its physics and its shared memory can show."""

from __future__ import annotations

import threading

import numpy as np
import pinocchio as pin
import pytest

from domain.robot_model.puma560 import HOME_Q
from services.proxy_robot import core as core_module
from services.proxy_robot.segment_timing import (
    INTERVAL_SMOOTHING,
    LONE_COMMAND_SPEED_RAD_PER_S,
    MAX_SEGMENT_S,
)
from services.proxy_robot.status import Moved, RobotErrorRaised, RobotStatus, StatusChanged
from services.world.shm_link import STALE_AFTER_S, SharedMemoryEmergencyStop
from tests.conftest import wait_for
from tests.fakes.arm_link import HOLD, TARGET, FakeArmLink
from wire.errors import (
    FailedPreconditionError,
    InvalidArgumentError,
    OutOfRangeError,
    UnavailableError,
)

S = RobotStatus


def drain(subscription) -> list:
    items = []
    while (item := subscription.get(0.0)) is not None:
        items.append(item)
    return items


def rot_z(angle: float) -> np.ndarray:
    return pin.utils.rotate("z", angle)


def statuses(events) -> list[tuple[RobotStatus, RobotStatus]]:
    return [(e.payload.previous, e.payload.status) for e in events
            if isinstance(e.payload, StatusChanged)]


# -- the status machine and its events ------------------------------------------------------


def test_full_status_cycle_with_an_event_for_every_change(rig, core):
    events = core.events.subscribe(256)
    assert core.status[0] == S.NOT_CONNECTED
    with pytest.raises(FailedPreconditionError, match="Connect first"):
        core.snapshot()
    assert core.connect() == S.CONNECTED
    assert core.initialize() == S.READY
    core.move_joints([0.05, 0, 0, 0, 0, 0])
    assert core.status[0] == S.MOVING
    rig.run_until_status(S.READY)
    assert core.emergency_stop("test")[0] == S.ESTOPPED
    assert core.reset() == S.READY
    assert core.disconnect() == S.NOT_CONNECTED

    received = drain(events)
    assert statuses(received) == [
        (S.NOT_CONNECTED, S.CONNECTED), (S.CONNECTED, S.INITIALIZING), (S.INITIALIZING, S.READY),
        (S.READY, S.MOVING), (S.MOVING, S.READY), (S.READY, S.ESTOPPED), (S.ESTOPPED, S.READY),
        (S.READY, S.NOT_CONNECTED),
    ]
    # Stamped by the injected clock, in order.
    times = [e.time_ns for e in received]
    assert times == sorted(times) and times[-1] == rig.clock.time_ns()


def test_event_sequence_has_no_gaps_and_moved_follows_arrival(rig, ready):
    events = ready.events.subscribe(256)
    target, _ = ready.move_joints([0, 0.05, 0, 0, 0, 0])
    rig.run_until_status(S.READY)
    received = drain(events)
    assert [e.sequence for e in received] == list(
        range(received[0].sequence, received[0].sequence + len(received)))
    moved = [e.payload for e in received if isinstance(e.payload, Moved)]
    assert len(moved) == 1
    # The sample that showed the arrival is the one the event carries.
    arrived = ready.snapshot()
    np.testing.assert_array_equal(moved[0].joint_positions_rad, arrived.joint_positions_rad)
    assert np.max(np.abs(arrived.joint_positions_rad - target)) < core_module.ARRIVAL_TOLERANCE_RAD
    assert np.max(np.abs(arrived.joint_velocities_rad_per_s)) < core_module.ARRIVAL_SPEED_RAD_PER_S


def test_arrival_waits_for_the_arm_not_the_command(rig, ready):
    ready.move_joints([0.2, 0, 0, 0, 0, 0])
    rig.run(0.1)  # the arm is on its way, at the speed cap
    assert ready.status[0] == S.MOVING
    assert np.max(np.abs(ready.snapshot().joint_velocities_rad_per_s)) > 0.5
    elapsed = rig.run_until_status(S.READY)
    assert elapsed > 0.05  # 0.2 rad at 1 rad/s: it could not have arrived sooner


def test_reset_from_estop_without_initialize_returns_to_connected(core):
    core.connect()
    core.emergency_stop("before init")
    assert core.reset() == S.CONNECTED
    with pytest.raises(FailedPreconditionError, match="Initialize first"):
        core.move_joints([0.01, 0, 0, 0, 0, 0])


def test_connect_without_a_world_is_unavailable(rig, core):
    rig.arm.shut_down()
    with pytest.raises(UnavailableError, match="no world is running"):
        core.connect()
    assert core.status[0] == S.NOT_CONNECTED


def test_connect_to_a_latched_arm_is_estopped(rig, core):
    rig.arm.latch_stop()
    rig.run(0.002)
    assert core.connect() == S.ESTOPPED
    with pytest.raises(FailedPreconditionError, match="Reset first"):
        core.initialize()
    assert core.reset() == S.CONNECTED
    assert not rig.arm.state().hold_latched


def test_moves_while_not_ready_are_failed_precondition(core):
    with pytest.raises(FailedPreconditionError, match="Connect and Initialize first"):
        core.move_joints([0.01, 0, 0, 0, 0, 0])
    core.connect()
    with pytest.raises(FailedPreconditionError, match="Initialize first"):
        core.move_cartesian([0, 0, 0.01], np.eye(3), "BASE")


# -- joint moves ----------------------------------------------------------------------------


def test_the_arm_settles_on_the_commanded_joints(rig, ready):
    target, _ = ready.move_joints([0.1, -0.05, 0.08, 0.1, -0.1, 0.2])
    rig.run_until_status(S.READY)
    # the whole segment was written
    np.testing.assert_allclose(rig.arm.state().joint_targets_rad, target, atol=1e-12)
    rig.run(0.2)
    np.testing.assert_allclose(ready.snapshot().joint_positions_rad, target, atol=1e-4)


def test_increments_add_to_the_target_not_the_lagging_arm(rig, ready):
    start = ready.snapshot().joint_positions_rad
    for _ in range(4):
        target, _ = ready.move_joints([0.05, 0, 0, 0, 0, 0])
    np.testing.assert_allclose(target - start, [0.2, 0, 0, 0, 0, 0], atol=1e-12)
    rig.run(0.01)
    assert ready.snapshot().joint_positions_rad[0] - start[0] < 0.05  # still lagging behind
    rig.run_until_status(S.READY)
    np.testing.assert_allclose(ready.snapshot().joint_positions_rad, target,
                               atol=core_module.ARRIVAL_TOLERANCE_RAD)


def test_a_50_hz_command_stream_is_spread_over_the_servo_rate(rig, ready):
    """Each 20 ms command goes to the servo once, with the segment to spread it over: the first
    (after a pause, a lone one) as fast as the lone-command speed allows, the next over the
    running average of the gaps. The servo moves every period, never by a whole command."""
    watcher = rig.arm.open_link()  # read-only here: the proxy is the driver
    before = len(rig.arm.commands)  # (Initialize's hold where the arm is)
    seen = []
    for _ in range(10):
        ready.move_joints([0.004, 0, 0, 0, 0, 0])
        for _ in range(20):
            rig.tick()
            seen.append(watcher.read_arm().joint_positions_rad[0])
    written = [c for c in rig.arm.commands[before:] if c.kind == TARGET]
    assert len(written) == 10  # one write per command: the servo makes the setpoints
    assert written[0].duration_s == pytest.approx(0.004 / LONE_COMMAND_SPEED_RAD_PER_S)
    average = MAX_SEGMENT_S + INTERVAL_SMOOTHING * (0.02 - MAX_SEGMENT_S)
    assert written[1].duration_s == pytest.approx(average)
    durations = [c.duration_s for c in written[1:]]
    assert durations == sorted(durations, reverse=True)  # toward the 20 ms gaps
    steps = np.diff(seen)
    assert np.all(steps[5:] > 0)  # moving every period once under way
    assert np.max(steps) < 0.001  # a whole command at once would be a 0.004 rad step
    rig.run_until_status(S.READY)
    np.testing.assert_allclose(rig.arm.state().joint_targets_rad[0] - HOME_Q[0], 0.04, atol=1e-12)


def test_joint_limit_is_out_of_range_and_keeps_the_target(rig, ready):
    # Joint 5 starts at -45 deg, limit -100 deg: the second -28.6 deg step would pass it.
    target, _ = ready.move_joints([0, 0, 0, 0, -0.5, 0])
    with pytest.raises(OutOfRangeError, match=r"joint 5 target -102.\d deg is past its limit"):
        ready.move_joints([0, 0, 0, 0, -0.5, 0])
    rig.run_until_status(S.READY)
    np.testing.assert_allclose(rig.arm.state().joint_targets_rad, target, atol=1e-12)


def test_bad_input_moves_nothing(rig, ready):
    position_before = ready.snapshot().joint_positions_rad
    commands_before = len(rig.arm.commands)
    bad_calls = [
        (InvalidArgumentError, "NaN", lambda: ready.move_joints([np.nan, 0, 0, 0, 0, 0])),
        (InvalidArgumentError, "NaN or Inf",
         lambda: ready.move_cartesian([np.inf, 0, 0], np.eye(3), "TOOL")),
        (InvalidArgumentError, "needs 6 values", lambda: ready.move_joints([0.1, 0.1])),
        (InvalidArgumentError, "needs 3 values",
         lambda: ready.move_cartesian([0.1], np.eye(3), "TOOL")),
        (InvalidArgumentError, "unknown frame",
         lambda: ready.move_cartesian([0, 0, 0.01], np.eye(3), "CAMERA")),
        (OutOfRangeError, "cap of 28.6 deg", lambda: ready.move_joints([0.6, 0, 0, 0, 0, 0])),
        (OutOfRangeError, "cap of 50 mm",
         lambda: ready.move_cartesian([0.06, 0, 0], np.eye(3), "BASE")),
        (OutOfRangeError, "cap of 15 deg",
         lambda: ready.move_cartesian([0, 0, 0], rot_z(0.3), "BASE")),
    ]
    for error, message, call in bad_calls:
        with pytest.raises(error, match=message):
            call()
    assert ready.status[0] == S.READY
    rig.run(0.05)
    assert len(rig.arm.commands) == commands_before  # nothing reached the servo
    np.testing.assert_array_equal(ready.snapshot().joint_positions_rad, position_before)
    # and the next good increment starts from the old target
    target, _ = ready.move_joints([0.01, 0, 0, 0, 0, 0])
    np.testing.assert_allclose(target, position_before + [0.01, 0, 0, 0, 0, 0], atol=1e-12)


# -- Cartesian moves (eq. 1) ----------------------------------------------------------------


def test_tool_mapping_moves_along_the_tool_axis(rig, ready):
    before = ready.snapshot().tool_pose  # at rest on its target
    _, target_pose, fraction = ready.move_cartesian([0.02, 0, 0], np.eye(3), "TOOL")
    assert fraction == 1.0
    np.testing.assert_allclose(target_pose.translation - before.translation,
                               0.02 * before.rotation[:, 0], atol=1e-4)
    np.testing.assert_allclose(target_pose.rotation, before.rotation, atol=1e-4)
    rig.run_until_status(S.READY)
    rig.run(0.2)  # settled
    after = ready.snapshot().tool_pose
    np.testing.assert_allclose(after.translation - before.translation,
                               0.02 * before.rotation[:, 0], atol=1e-4)


def test_base_mapping_moves_along_the_base_axis_and_rotates_about_the_tool_point(rig, ready):
    before = ready.snapshot().tool_pose
    _, target_pose, _ = ready.move_cartesian([0, 0, 0.01], rot_z(0.1), "BASE")
    np.testing.assert_allclose(target_pose.translation - before.translation, [0, 0, 0.01],
                               atol=1e-4)
    np.testing.assert_allclose(target_pose.rotation, rot_z(0.1) @ before.rotation, atol=1e-4)
    rig.run_until_status(S.READY)


def test_tool_rotation_keeps_the_tool_point_fixed(rig, ready):
    before = ready.snapshot().tool_pose
    _, target_pose, _ = ready.move_cartesian([0, 0, 0], pin.utils.rotate("x", 0.1), "TOOL")
    np.testing.assert_allclose(target_pose.translation, before.translation, atol=1e-4)
    np.testing.assert_allclose(target_pose.rotation,
                               before.rotation @ pin.utils.rotate("x", 0.1), atol=1e-4)
    rig.run_until_status(S.READY)


def test_wrist_mapping_moves_the_flange_and_the_tool_follows(rig, ready):
    flange = ready.snapshot().flange_pose
    _, target_pose, _ = ready.move_cartesian([0, 0.01, 0], np.eye(3), "WRIST")
    expected_flange = flange * pin.SE3(np.eye(3), np.array([0, 0.01, 0]))
    np.testing.assert_allclose(target_pose.translation,
                               (expected_flange * ready.tool_frame).translation, atol=1e-4)
    np.testing.assert_allclose(target_pose.rotation, flange.rotation, atol=1e-4)
    rig.run_until_status(S.READY)


def test_pushing_out_of_reach_is_refused_and_never_jumps(rig, ready):
    previous = ready.snapshot().joint_positions_rad
    with pytest.raises(OutOfRangeError, match="workspace|singularity|past its limit"):
        for _ in range(60):
            target, _, _ = ready.move_cartesian([0.05, 0, 0.0], np.eye(3), "BASE")
            assert np.max(np.abs(target - previous)) <= core_module.MAX_IK_JOINT_STEP_RAD
            previous = target
    rig.run_until_status(S.READY, timeout_s=10.0)
    np.testing.assert_allclose(rig.arm.state().joint_targets_rad, previous, atol=1e-12)


def test_near_the_wrist_singularity_cartesian_moves_are_refused(rig, ready):
    # q5 from -45 deg to about -0.9 deg: the wrist axes 4 and 6 almost align.
    ready.move_joints([0, 0, 0, 0, 0.5, 0])
    before, _ = ready.move_joints([0, 0, 0, 0, 0.27, 0])
    rig.run_until_status(S.READY)
    # Turning a little about the tool y axis is joint 5 alone: toward q5 = 0 it goes deeper
    # into the singular region and is refused; away from it, it steers out and is allowed.
    with pytest.raises(OutOfRangeError, match="singularity"):
        ready.move_cartesian([0, 0, 0], pin.utils.rotate("y", -0.01), "TOOL")
    target, _, fraction = ready.move_cartesian([0, 0, 0], pin.utils.rotate("y", 0.01), "TOOL")
    assert fraction == 1.0 and target[4] < before[4]
    before, _ = ready.move_joints(before - target)  # back
    # Turning about the tool x axis here needs joints 4 and 6 to flip by about 1.5 rad.
    with pytest.raises(OutOfRangeError, match="singularity"):
        ready.move_cartesian([0, 0, 0], pin.utils.rotate("x", 0.05), "TOOL")
    # Turning about the tool axis is joint 6 alone: allowed, and it does not jump.
    target, _, fraction = ready.move_cartesian([0, 0, 0], rot_z(0.1), "TOOL")
    assert fraction == 1.0 and np.max(np.abs(target - before)) < 0.11
    # Turning about the tool y axis (joint 5) steers out of the singularity.
    ready.move_cartesian([0, 0, 0], pin.utils.rotate("y", -0.2), "TOOL")


def test_tool_frame_is_used_for_tool_poses(rig, ready):
    tool_frame = pin.SE3(np.eye(3), np.array([0, 0, 0.2]))
    ready.set_tool_frame(tool_frame)
    rig.run(core_module.STATE_PERIOD_S)  # the next sample
    snapshot = ready.snapshot()
    np.testing.assert_allclose(snapshot.tool_pose.translation,
                               (snapshot.flange_pose * tool_frame).translation, atol=1e-12)
    with pytest.raises(InvalidArgumentError, match="at most 1.0 m"):
        ready.set_tool_frame(pin.SE3(np.eye(3), np.array([0, 0, 1.5])))
    ready.move_joints([0.05, 0, 0, 0, 0, 0])
    with pytest.raises(FailedPreconditionError, match="MOVING"):
        ready.set_tool_frame(pin.SE3.Identity())


# -- stops, holds, faults, link loss --------------------------------------------------------


def test_emergency_stop_latches_until_reset_and_reset_does_not_move(rig, ready):
    ready.move_joints([0.4, 0, 0, 0, 0, 0])
    rig.run(0.1)  # mid-move
    assert np.max(np.abs(ready.snapshot().joint_velocities_rad_per_s)) > 0.5
    status, stop_time_ns = ready.emergency_stop("operator pressed stop")
    assert status == S.ESTOPPED and stop_time_ns == rig.clock.time_ns()
    assert rig.arm.commands[-1].kind == HOLD  # at the hardware, not only in the status
    assert "operator pressed stop" in ready.status[1]
    with pytest.raises(FailedPreconditionError, match="emergency stop is latched"):
        ready.move_joints([0.01, 0, 0, 0, 0, 0])
    with pytest.raises(FailedPreconditionError, match="Reset first"):
        ready.initialize()
    rig.run(0.3)
    halted = ready.snapshot()
    assert rig.arm.state().hold_latched
    assert np.max(np.abs(halted.joint_velocities_rad_per_s)) < 1e-2
    assert halted.joint_positions_rad[0] - HOME_Q[0] < 0.2  # it did not go on to the target
    assert ready.emergency_stop("again")[0] == S.ESTOPPED  # idempotent

    assert ready.reset() == S.READY
    assert not rig.arm.state().hold_latched
    rig.run(0.2)
    np.testing.assert_array_equal(ready.snapshot().joint_positions_rad,
                                  halted.joint_positions_rad)
    assert ready.status[0] == S.READY
    # The next increment starts where the arm stopped, not from the abandoned target.
    target, _ = ready.move_joints([0.01, 0, 0, 0, 0, 0])
    np.testing.assert_allclose(target, halted.joint_positions_rad + [0.01, 0, 0, 0, 0, 0],
                               atol=1e-12)


def test_a_stop_latched_by_the_band_shows_as_estopped_at_the_next_sample(rig, ready):
    band = rig.arm.emergency_stop_link()  # another process, past the driver
    band.stop()
    elapsed = rig.run_until_status(S.ESTOPPED)
    assert elapsed <= core_module.STATE_PERIOD_S  # seen in the next state sample
    assert "at the hardware" in ready.status[1]
    with pytest.raises(FailedPreconditionError, match="emergency stop is latched"):
        ready.move_joints([0.01, 0, 0, 0, 0, 0])
    assert ready.reset() == S.READY
    assert not rig.arm.state().hold_latched
    rig.run(0.01)
    assert ready.status[0] == S.READY  # the old latch is not read as a new stop


def test_a_sample_read_before_a_reset_does_not_latch_the_stop_again(rig, ready, monkeypatch):
    """The monitor read the arm while the stop was latched, and a Reset cleared it before the
    monitor looked at that sample: the old latch is not a new stop (a Reset then a move, sent
    at once, would be refused as ESTOPPED)."""
    ready.emergency_stop("test")
    rig.run(0.002)
    read_arm, reset_between = FakeArmLink.read_arm, [True]

    def a_reset_lands_after_this_read(link):
        sample = read_arm(link)
        if reset_between and sample.hold_latched:
            reset_between.clear()
            assert ready.reset() == S.READY
        return sample

    monkeypatch.setattr(FakeArmLink, "read_arm", a_reset_lands_after_this_read)
    ready.sample_once()  # the monitor, with the sample it read before the Reset
    assert not reset_between  # (the Reset came between)
    assert ready.status[0] == S.READY
    ready.move_joints([0.01, 0, 0, 0, 0, 0])
    rig.arm.emergency_stop_link().stop()  # a stop after the Reset is still seen
    rig.run_until_status(S.ESTOPPED)


def test_reset_gives_up_on_a_hold_the_hardware_does_not_release(rig, ready, monkeypatch):
    ready.emergency_stop("test")
    rig.run(0.002)
    assert rig.arm.state().hold_latched
    monkeypatch.setattr(FakeArmLink, "release_hold", lambda self: None)  # a stuck relay
    started_ns = rig.clock.monotonic_ns()
    with pytest.raises(UnavailableError, match="did not release"):
        ready.reset()
    waited_s = (rig.clock.monotonic_ns() - started_ns) * 1e-9
    assert waited_s == pytest.approx(core_module.RELEASE_TIMEOUT_S, abs=1e-3)
    assert ready.status[0] == S.ESTOPPED


def test_a_stop_latched_on_arrival_keeps_the_reason_its_handler_gives(rig, ready):
    """hold_now latches at the hardware as the call arrives; the monitor may see the latch
    first, but the status ends with the stop's own reason once its handler runs."""
    ready.move_joints([0.05, 0, 0, 0, 0, 0])
    rig.run(0.005)
    ready.hold_now()
    assert rig.arm.commands[-1].kind == HOLD  # at once, at the hardware
    rig.run_until_status(S.ESTOPPED)  # the monitor saw the latch before the handler ran
    assert "latched stop was set at the hardware" in ready.status[1]
    status, _ = ready.emergency_stop("operator pressed stop")
    assert status == S.ESTOPPED
    assert ready.status[1] == "emergency stop: operator pressed stop"


def test_hold_stops_without_latching(rig, ready):
    events = ready.events.subscribe(256)
    ready.move_joints([0.5, 0, 0, 0, 0, 0])
    rig.run(0.15)
    moving = ready.snapshot()
    going_to = ready._tool_pose(ready._target_q)
    target, tool, cut = ready.hold()
    assert tool.isApprox(ready._tool_pose(target)) and cut.isApprox(going_to)
    # Ahead of the arm by the braking distance at the servo's deceleration, no further.
    speed = moving.joint_velocities_rad_per_s[0]
    assert speed > 0.5
    assert 0 < target[0] - rig.arm.state().joint_positions_rad[0] <= (
        speed**2 / (2 * core_module.HOLD_DECELERATION_RAD_PER_S2) + 1e-9)
    rig.run_until_status(S.READY)
    np.testing.assert_allclose(ready.snapshot().joint_positions_rad, target,
                               atol=core_module.ARRIVAL_TOLERANCE_RAD)
    assert target[0] - HOME_Q[0] < 0.45  # it did not go on to the old target
    assert not rig.arm.state().hold_latched
    assert [e for e in drain(events) if isinstance(e.payload, Moved)]
    ready.move_joints([0.01, 0, 0, 0, 0, 0])  # and motion is accepted at once
    assert ready.status[0] == S.MOVING


def test_a_hardware_fault_is_reported_and_reset_clears_it(rig, ready):
    events = ready.events.subscribe(64)
    rig.arm.inject_fault("simulation diverged")
    rig.run_until_status(S.FAULT)
    errors = [e.payload for e in drain(events) if isinstance(e.payload, RobotErrorRaised)]
    assert [(e.reason, e.message) for e in errors] == [("HARDWARE_FAULT", "simulation diverged")]
    with pytest.raises(FailedPreconditionError, match="FAULT"):
        ready.move_joints([0.01, 0, 0, 0, 0, 0])
    assert ready.reset() == S.READY
    assert rig.arm.state().fault == ""


def test_link_loss_drops_to_not_connected_with_an_error_event(rig, ready):
    events = ready.events.subscribe(64)
    ready.move_joints([0.2, 0, 0, 0, 0, 0])
    rig.run(0.01)
    rig.arm.shut_down()
    rig.run_until_status(S.NOT_CONNECTED, timeout_s=0.01)
    errors = [e.payload.reason for e in drain(events) if isinstance(e.payload, RobotErrorRaised)]
    assert errors[-1] == "LINK_LOST"
    assert errors == ["LINK_LOST"]
    with pytest.raises(FailedPreconditionError, match="Connect first"):
        ready.snapshot()
    with pytest.raises(UnavailableError):
        ready.connect()


def test_a_world_that_stops_stepping_is_lost_once_stale(rig, ready):
    rig.arm.freeze()
    elapsed = rig.run_until_status(S.NOT_CONNECTED)
    # the monitor's first sample past the staleness limit
    assert STALE_AFTER_S < elapsed <= STALE_AFTER_S + core_module.STATE_PERIOD_S


# -- e2e: the real simulated arm ------------------------------------------------------------


@pytest.mark.e2e
def test_the_real_arm_reaches_and_holds_a_commanded_target(world_ready):
    """MuJoCo's servo, not the fake's lag, brings the arm onto the target and holds it."""
    target, _ = world_ready.move_joints([0.1, -0.05, 0.08, 0.1, -0.1, 0.2])
    wait_for(lambda: world_ready.status[0] == S.READY, 10.0, "READY")
    wait_for(lambda: np.max(np.abs(world_ready.snapshot().joint_positions_rad - target)) < 1e-4,
             5.0, "the arm settled on its target")


@pytest.mark.e2e
def test_emergency_stop_brakes_the_real_arm_and_reset_keeps_it_there(world_ready):
    world_ready.move_joints([0.4, 0, 0, 0, 0, 0])
    wait_for(lambda: world_ready.snapshot().joint_velocities_rad_per_s[0] > 0.5, 5.0,
             "the arm under way")
    assert world_ready.emergency_stop("operator pressed stop")[0] == S.ESTOPPED
    wait_for(lambda: np.max(np.abs(world_ready.snapshot().joint_velocities_rad_per_s)) < 1e-2,
             5.0, "the arm at rest")
    halted = world_ready.snapshot()
    # From at most 1 rad/s at 10 rad/s^2 the arm brakes within 0.05 rad.
    assert halted.joint_positions_rad[0] - HOME_Q[0] < 0.4 - 0.05
    assert world_ready.reset() == S.READY
    wait_for(lambda: world_ready.snapshot().sequence > halted.sequence + 200, 5.0,
             "200 more servo steps")
    np.testing.assert_allclose(world_ready.snapshot().joint_positions_rad,
                               halted.joint_positions_rad, atol=1e-4)
    assert world_ready.status[0] == S.READY


@pytest.mark.e2e
def test_a_stop_from_the_band_through_shared_memory_shows_as_estopped(world, world_ready):
    band = SharedMemoryEmergencyStop(world.shm_name)
    try:
        band.stop()
    finally:
        band.close()
    wait_for(lambda: world_ready.status[0] == S.ESTOPPED, 5.0, "ESTOPPED")
    assert "at the hardware" in world_ready.status[1]
    assert world_ready.reset() == S.READY


def test_the_proxy_under_test_runs_no_thread_of_its_own(rig, ready):
    """The test decides when the monitor samples and when setpoints are written."""
    ready.move_joints([0.05, 0, 0, 0, 0, 0])
    names = {thread.name for thread in threading.enumerate()}
    assert not names & {"arm-monitor", "setpoints"}
    rig.run(0.05)
    assert ready.status[0] == S.MOVING  # no tick, no arrival: only what the test ran happened
