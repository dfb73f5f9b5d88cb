"""The shared-memory link, world end and driver end in this process (no physics loop): command
ordering, validation, liveness, segment ownership."""

from __future__ import annotations

import os
import subprocess
import sys
import time

import numpy as np
import pytest

from domain.robot_model.description import arm_description
from services.world.realtime import LoopStats
from services.world.shm_layout import STATUS_RUNNING, WorldSegment, attach_untracked
from services.world.shm_link import (
    Command,
    SharedMemoryArmLink,
    SharedMemoryEmergencyStop,
    SharedMemoryWrenchLink,
    WorldPublisher,
)
from services.world.sim import ArmSim
from tests.fakes.clock import FakeClock
from tests.processes import segment_exists, unique_shm_name
from wire.errors import (
    AlreadyExistsError,
    FailedPreconditionError,
    InvalidArgumentError,
    OutOfRangeError,
    UnavailableError,
)

PERIOD_S = 0.001


@pytest.fixture(scope="module")
def sim() -> ArmSim:
    return ArmSim()


@pytest.fixture
def publisher(sim: ArmSim):
    world = WorldPublisher(sim.arm.name, sim.joint_lower, sim.joint_upper, PERIOD_S,
                           unique_shm_name())
    world.publish(sim.arm_sample(), sim.wrench_sample())
    yield world
    world.close()


@pytest.fixture
def link(publisher: WorldPublisher):
    arm = SharedMemoryArmLink(publisher.name)
    yield arm
    arm.close()


@pytest.fixture
def clock() -> FakeClock:
    return FakeClock()


@pytest.fixture
def paused_publisher(sim: ArmSim, clock: FakeClock):
    """A world whose heartbeat comes from `clock`: it goes stale only when the test says so."""
    world = WorldPublisher(sim.arm.name, sim.joint_lower, sim.joint_upper, PERIOD_S,
                           unique_shm_name(), clock=clock)
    world.publish(sim.arm_sample(), sim.wrench_sample())
    yield world
    world.close()


def kinds(commands: list[Command]) -> list[str]:
    return [command.kind for command in commands]


@pytest.mark.e2e
def test_samples_arrive_intact(publisher, link, sim: ArmSim) -> None:
    arm, wrench = sim.arm_sample(42), sim.wrench_sample(43)
    loop = LoopStats(steps=5, overruns=1, dropped_steps=2, worst_lateness_ns=7, worst_step_ns=3)
    publisher.publish(arm, wrench, loop)
    read = link.read_arm()
    assert (read.sequence, read.sample_time_ns, read.hold_latched, read.fault) == (
        arm.sequence, 42, False, "")
    np.testing.assert_array_equal(read.joint_positions_rad, arm.joint_positions_rad)
    np.testing.assert_array_equal(read.joint_velocities_rad_per_s, arm.joint_velocities_rad_per_s)
    np.testing.assert_array_equal(read.joint_targets_rad, arm.joint_targets_rad)
    sensor = SharedMemoryWrenchLink(publisher.name)
    got = sensor.read_wrench()
    sensor.close()
    assert (got.sequence, got.sample_time_ns) == (wrench.sequence, 43)
    np.testing.assert_array_equal(got.force_n, wrench.force_n)
    np.testing.assert_array_equal(got.torque_nm, wrench.torque_nm)
    assert link.read_loop_stats() == loop


@pytest.mark.e2e
def test_faults_and_holds_arrive(publisher, link, sim: ArmSim) -> None:
    arm = sim.arm_sample()
    faulty = type(arm)(**{**arm.__dict__, "hold_latched": True, "fault": "motor 3 über-hot"})
    publisher.publish(faulty, sim.wrench_sample())
    read = link.read_arm()
    assert read.hold_latched and read.fault == "motor 3 über-hot"


@pytest.mark.e2e
def test_the_record_keeps_the_time_of_the_step_the_hold_latched_at(publisher, sim: ArmSim):
    """A reader that missed the first latched step (a busy bench) still reads its time."""
    arm = sim.arm_sample()

    def publish(time_ns: int, latched: bool) -> int:
        publisher.publish(type(arm)(**{**arm.__dict__, "sample_time_ns": time_ns,
                                       "hold_latched": latched}), sim.wrench_sample())
        return int(publisher._segment.state.read(timeout_s=1.0)[0]["hold_latched_ns"])

    assert publish(100, False) == 0
    assert publish(200, True) == 200
    assert publish(300, True) == 200  # still the step it latched at
    assert publish(400, False) == 0  # released
    assert publish(500, True) == 500  # a new stop, a new time


@pytest.mark.e2e
def test_commands_arrive_in_the_order_they_were_issued(publisher, link) -> None:
    target = link.read_arm().joint_targets_rad + 0.1
    link.hold()
    link.release_hold()
    link.write_target(target)
    commands = publisher.poll_commands()
    assert kinds(commands) == ["hold", "release", "target"]
    assert [c.number for c in commands] == sorted(c.number for c in commands)
    np.testing.assert_array_equal(commands[2].target, target)
    assert publisher.poll_commands() == []  # each command is handed out once

    link.release_hold()
    link.hold()  # the later one wins: the arm ends up held
    assert kinds(publisher.poll_commands()) == ["release", "hold"]


@pytest.mark.e2e
def test_a_target_carries_the_segment_to_reach_it_over(publisher, link) -> None:
    target = link.read_arm().joint_targets_rad + 0.01
    link.write_target(target, 0.02)
    (command,) = publisher.poll_commands()
    assert command.kind == "target" and command.duration_s == 0.02
    link.write_target(target)  # at once
    assert publisher.poll_commands()[0].duration_s == 0.0
    for bad in (-0.01, float("nan"), float("inf")):
        with pytest.raises(InvalidArgumentError, match="segment duration"):
            link.write_target(target, bad)
    assert publisher.poll_commands() == []  # nothing half-written


@pytest.mark.e2e
def test_no_edge_is_lost_between_two_polls(publisher, link) -> None:
    for _ in range(3):
        link.hold()
        link.release_hold()
    link.hold()
    # Repeats collapse (holding twice is holding), but the latest of each kind is there and in
    # order: held, then the final hold after the last release.
    assert kinds(publisher.poll_commands()) == ["release", "hold"]


@pytest.mark.e2e
def test_an_emergency_stop_beside_the_driver_latches_after_its_commands(publisher, link) -> None:
    button = SharedMemoryEmergencyStop(publisher.name)
    try:
        link.hold()
        first = button.stop()
        link.release_hold()  # issued after the stop, but in the same step: the stop still wins
        assert kinds(publisher.poll_commands()) == ["hold", "release", "hold"]
        assert publisher.poll_commands() == []  # one request, one hold
        assert button.stop() > first  # strictly new, even within one clock tick
        assert button.stop() > first
        assert kinds(publisher.poll_commands()) == ["hold"]
        link.write_target(link.read_arm().joint_targets_rad)  # the driver goes on numbering
        assert kinds(publisher.poll_commands()) == ["target"]
    finally:
        button.close()


@pytest.mark.e2e
def test_an_emergency_stop_into_a_stale_world_is_unavailable(paused_publisher, clock,
                                                              sim) -> None:
    button = SharedMemoryEmergencyStop(paused_publisher.name, stale_after_s=0.05, clock=clock)
    try:
        clock.advance(0.04)
        button.stop()  # within the limit: delivered
        clock.advance(0.02)  # no publish meanwhile: the world is stuck
        with pytest.raises(UnavailableError, match="has not stepped"):
            button.stop()  # not delivered, and the caller is told so
        paused_publisher.publish(sim.arm_sample(), sim.wrench_sample())
        button.stop()
    finally:
        button.close()


@pytest.mark.e2e
def test_the_driver_sees_when_its_commands_are_applied(publisher, link, sim: ArmSim) -> None:
    link.write_target(link.read_arm().joint_targets_rad)
    assert not link.commands_applied()
    publisher.poll_commands()
    assert not link.commands_applied()  # not until the world has published after applying
    publisher.publish(sim.arm_sample(), sim.wrench_sample())
    assert link.commands_applied()


@pytest.mark.e2e
def test_a_new_driver_continues_the_command_numbers(publisher, link) -> None:
    link.hold()
    first = publisher.poll_commands()[0].number
    second_driver = SharedMemoryArmLink(publisher.name)
    second_driver.release_hold()
    second_driver.close()
    assert publisher.poll_commands()[0].number > first


@pytest.mark.e2e
def test_a_torn_target_from_a_dead_driver_is_never_applied(publisher, link, sim) -> None:
    link.hold()
    publisher.poll_commands()
    publisher.publish(sim.arm_sample(), sim.wrench_sample())
    segment = WorldSegment(attach_untracked(publisher.name))
    writing = segment.command.writing()
    record = writing.__enter__()  # a driver that dies half-way through a target
    record["target"][0, :6] = np.full(6, 0.5)
    record["target_command"] = 99
    assert publisher.poll_commands() == []  # mid-write: nothing is taken
    recovered = SharedMemoryArmLink(publisher.name)
    recovered.release_hold()
    assert kinds(publisher.poll_commands()) == ["release"]
    recovered.close()
    del writing, record
    segment.close()


@pytest.mark.e2e
@pytest.mark.parametrize("bad", [np.zeros(5), np.array([0, 0, np.nan, 0, 0, 0])])
def test_malformed_targets_are_refused(link, bad) -> None:
    with pytest.raises(InvalidArgumentError):
        link.write_target(bad)


@pytest.mark.e2e
def test_targets_past_a_joint_limit_are_refused(link) -> None:
    target = link.read_arm().joint_positions_rad
    target[2] = link.joint_lower[2] - 0.1
    with pytest.raises(OutOfRangeError, match="joint 3"):
        link.write_target(target)


@pytest.mark.e2e
def test_a_world_that_has_not_published_yet_is_starting(sim: ArmSim) -> None:
    world = WorldPublisher(sim.arm.name, sim.joint_lower, sim.joint_upper, PERIOD_S,
                           unique_shm_name())
    with pytest.raises(UnavailableError, match="starting"):
        SharedMemoryArmLink(world.name)
    world.publish(sim.arm_sample(), sim.wrench_sample())
    SharedMemoryArmLink(world.name).close()
    world.close()


def test_opening_with_no_world_is_unavailable() -> None:
    with pytest.raises(UnavailableError, match="no world is running"):
        SharedMemoryArmLink(unique_shm_name())
    with pytest.raises(UnavailableError, match="no world is running"):
        SharedMemoryWrenchLink(unique_shm_name())


@pytest.mark.e2e
def test_a_world_that_stops_stepping_is_unavailable(paused_publisher, clock,
                                                    sim: ArmSim) -> None:
    link = SharedMemoryArmLink(paused_publisher.name, stale_after_s=0.05, clock=clock)
    clock.advance(0.04)
    link.read_arm()  # within the limit: alive
    clock.advance(0.02)  # no publish meanwhile: the world is stuck
    with pytest.raises(UnavailableError, match="has not stepped"):
        link.read_arm()
    with pytest.raises(UnavailableError, match="has not stepped"):
        link.hold()
    with pytest.raises(UnavailableError, match="has not stepped"):
        SharedMemoryArmLink(paused_publisher.name, stale_after_s=0.05, clock=clock)
    paused_publisher.publish(sim.arm_sample(), sim.wrench_sample())
    link.read_arm()  # it is back
    link.close()


@pytest.mark.e2e
def test_a_reader_preempted_mid_read_does_not_take_the_world_for_stale(paused_publisher, clock,
                                                                      sim: ArmSim) -> None:
    """The link's clock is read before the record: a reader that lost its core in between (a
    loaded machine) sees a world that stepped just now, not one that stopped."""
    link = SharedMemoryArmLink(paused_publisher.name, stale_after_s=0.05, clock=clock)
    state = link._connection.segment.state
    read = state.read

    def read_then_lose_the_core(timeout_s, **options):
        copy = read(timeout_s, **options)
        clock.advance(0.2)  # off the core for 200 ms; the world stepped meanwhile
        paused_publisher.publish(sim.arm_sample(), sim.wrench_sample())
        return copy

    state.read = read_then_lose_the_core
    link.read_arm()
    link.close()


class TickingClock(FakeClock):
    """Time moves 10 ms each time it is read, so a reader spinning on a record meets its
    deadline; `on_read(now_ns)` is called at each reading."""

    def __init__(self):
        super().__init__()
        self.on_read = lambda now_ns: None

    def monotonic_ns(self) -> int:
        self.advance(0.01)
        now_ns = super().monotonic_ns()
        self.on_read(now_ns)
        return now_ns


@pytest.fixture
def ticking_world(sim: ArmSim):
    """A world stamped by a TickingClock, and its state record as a writer sees it."""
    clock = TickingClock()
    world = WorldPublisher(sim.arm.name, sim.joint_lower, sim.joint_upper, PERIOD_S,
                           unique_shm_name(), clock=clock)
    world.publish(sim.arm_sample(), sim.wrench_sample())
    segment = WorldSegment(attach_untracked(world.name))
    yield world, clock, segment.state
    segment.close()
    world.close()


@pytest.mark.e2e
def test_a_world_preempted_mid_publish_is_waited_for_as_long_as_a_silent_one(ticking_world):
    """The world's thread lost its core (or the GIL) between the two halves of a publish for
    150 ms, under the 250 ms a world may go without stepping: the reader waits and reads."""
    world, clock, state = ticking_world
    link = SharedMemoryArmLink(world.name, stale_after_s=0.25, clock=clock)
    publishing = state.writing()
    publishing.__enter__()
    resume_at_ns = clock.monotonic_ns() + 150_000_000

    def resume(now_ns: int) -> None:
        if now_ns >= resume_at_ns:
            clock.on_read = lambda now_ns: None
            publishing.__exit__(None, None, None)

    clock.on_read = resume
    link.read_arm()
    link.close()


@pytest.mark.e2e
def test_a_world_stuck_mid_publish_is_stale_after_the_same_time(ticking_world):
    world, clock, state = ticking_world
    link = SharedMemoryArmLink(world.name, stale_after_s=0.25, clock=clock)
    state.writing().__enter__()  # never finished
    start_ns = clock.monotonic_ns()
    with pytest.raises(UnavailableError, match="middle of publishing a sample for 250 ms"):
        link.read_arm()
    assert clock.monotonic_ns() - start_ns >= 250_000_000
    link.close()


@pytest.mark.e2e
def test_a_closed_world_is_unavailable_and_its_segment_gone(sim: ArmSim) -> None:
    world = WorldPublisher(sim.arm.name, sim.joint_lower, sim.joint_upper, PERIOD_S,
                           unique_shm_name())
    world.publish(sim.arm_sample(), sim.wrench_sample())
    link = SharedMemoryArmLink(world.name)
    world.close()
    assert not segment_exists(world.name)
    with pytest.raises(UnavailableError, match="shut down"):
        link.read_arm()
    with pytest.raises(UnavailableError, match="shut down"):
        link.write_target(np.zeros(6))
    link.close()
    with pytest.raises(UnavailableError, match="closed"):
        link.read_arm()


@pytest.mark.e2e
def test_a_second_world_on_a_live_segment_is_refused(publisher, sim: ArmSim) -> None:
    with pytest.raises(AlreadyExistsError, match=f"pid {os.getpid()}"):
        WorldPublisher(sim.arm.name, sim.joint_lower, sim.joint_upper, PERIOD_S, publisher.name)
    SharedMemoryArmLink(publisher.name).close()  # the first is untouched


@pytest.mark.e2e
def test_a_stale_segment_from_a_killed_world_is_replaced(sim: ArmSim) -> None:
    name = unique_shm_name()
    killed = WorldPublisher(sim.arm.name, sim.joint_lower, sim.joint_upper, PERIOD_S, name)
    killed.publish(sim.arm_sample(), sim.wrench_sample())
    segment = killed._segment  # what a killed world leaves
    segment.header["world_pid"] = _dead_pid()
    segment.header["heartbeat_ns"] = time.monotonic_ns() - 10**10
    assert segment.status == STATUS_RUNNING
    segment.close()  # abandoned: not unlinked

    world = WorldPublisher(sim.arm.name, sim.joint_lower, sim.joint_upper, PERIOD_S, name)
    world.publish(sim.arm_sample(), sim.wrench_sample())
    link = SharedMemoryArmLink(name)
    assert link.read_arm().sequence == sim.steps
    link.close()
    world.close()
    assert not segment_exists(name)


def _dead_pid() -> int:
    process = subprocess.Popen([sys.executable, "-c", "pass"])
    process.wait()
    return process.pid


@pytest.mark.e2e
def test_a_seven_joint_arm_travels_whole_and_a_driver_for_another_arm_is_refused() -> None:
    fr3 = ArmSim(arm=arm_description("fr3"))
    world = WorldPublisher("fr3", fr3.joint_lower, fr3.joint_upper, PERIOD_S, unique_shm_name())
    try:
        world.publish(fr3.arm_sample(), fr3.wrench_sample())
        with pytest.raises(FailedPreconditionError, match="simulates the fr3, and this process "
                                                          "drives the puma560"):
            SharedMemoryArmLink(world.name)
        link = SharedMemoryArmLink(world.name, arm="fr3")
        np.testing.assert_array_equal(link.read_arm().joint_positions_rad, fr3.joint_positions)
        np.testing.assert_array_equal(link.joint_upper, fr3.joint_upper)
        target = fr3.joint_positions + 0.1
        link.write_target(target)
        (command,) = world.poll_commands()
        np.testing.assert_array_equal(command.target, target)
        with pytest.raises(InvalidArgumentError, match="needs 7 finite angles"):
            link.write_target(np.zeros(6))
        link.close()
    finally:
        world.close()
