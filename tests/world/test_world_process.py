"""The real `python -m services.world` process, driven through SharedMemoryArmLink from here."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap

import grpc
import numpy as np
import pytest
from grpc_health.v1 import health_pb2, health_pb2_grpc

from services.runtime.priority import COMMAND_PATH_FIFO_PRIORITY
from services.world.link import ArmSample
from services.world.service import PHYSICS_THREAD_FIFO_PRIORITY
from services.world.shm_link import STALE_AFTER_S, SharedMemoryArmLink, SharedMemoryWrenchLink
from tests.conftest import wait_for
from tests.processes import REPO, World, segment_exists
from wire.errors import UnavailableError

pytestmark = pytest.mark.e2e

ARRIVAL_TOLERANCE_RAD = 1e-3
AT_REST_RAD_PER_S = 1e-2
MOVE = np.array([0.2, -0.1, 0.15, 0.3, 0.2, -0.3])  # rad, 0.3 s at the speed cap
WAIT_S = 10.0  # generous: the machine may be busy; nothing here measures speed
STOP_LIMIT_S = 3.0
WATCH_STEPS = 200  # world steps (1 ms each) to watch an arm that must not move


def arm_reaches(link: SharedMemoryArmLink, condition, what: str) -> ArmSample:
    """The first sample that meets `condition`."""
    def met() -> ArmSample | None:
        sample = link.read_arm()
        return sample if condition(sample) else None
    return wait_for(met, WAIT_S, what)


def steps_later(link: SharedMemoryArmLink, steps: int) -> ArmSample:
    """A sample taken `steps` world steps after the latest one (the world ran that long)."""
    first = link.read_arm().sequence
    return arm_reaches(link, lambda sample: sample.sequence >= first + steps,
                       f"{steps} more world steps")


def unavailable(link: SharedMemoryArmLink) -> UnavailableError | None:
    """Why the link cannot read the arm, or None while it can."""
    try:
        link.read_arm()
    except UnavailableError as error:
        return error
    return None


def at_rest(sample: ArmSample) -> bool:
    return np.abs(sample.joint_velocities_rad_per_s).max() < AT_REST_RAD_PER_S


def wait_applied(link: SharedMemoryArmLink) -> None:
    wait_for(link.commands_applied, WAIT_S, "the world to apply the command")


@pytest.fixture
def link(shared_world: World):
    arm = SharedMemoryArmLink(shared_world.shm_name)
    yield arm
    arm.release_hold()  # leave the shared world free to move for the next test
    wait_applied(arm)
    arm.close()


def test_health_is_serving_once_the_loop_runs(shared_world: World) -> None:
    with grpc.insecure_channel(shared_world.running.ready["world"]) as channel:
        reply = health_pb2_grpc.HealthStub(channel).Check(health_pb2.HealthCheckRequest(),
                                                           timeout=5)
    assert reply.status == health_pb2.HealthCheckResponse.SERVING
    link = SharedMemoryArmLink(shared_world.shm_name)
    assert link.read_loop_stats().steps > 0
    link.close()


def test_a_target_written_through_the_link_is_reached(link) -> None:
    start = link.read_arm()
    target = start.joint_targets_rad + MOVE
    link.write_target(target)
    wait_applied(link)
    np.testing.assert_allclose(link.read_arm().joint_targets_rad, target)
    arrived = arm_reaches(link, lambda s: np.abs(s.joint_positions_rad - target).max()
                          < ARRIVAL_TOLERANCE_RAD and at_rest(s), "the arm to arrive")
    assert arrived.sequence > start.sequence
    assert not arrived.hold_latched and arrived.fault == ""


def test_hold_and_release_through_the_link(link) -> None:
    start = link.read_arm().joint_positions_rad
    link.write_target(start - MOVE)
    arm_reaches(link, lambda s: not at_rest(s), "the arm to move")
    link.hold()
    wait_applied(link)
    held = arm_reaches(link, at_rest, "the arm to stop")
    assert held.hold_latched
    assert np.abs(held.joint_positions_rad - (start - MOVE)).max() > 0.01  # stopped short

    link.write_target(start)  # ignored while latched
    wait_applied(link)
    still = steps_later(link, WATCH_STEPS)
    assert still.hold_latched
    np.testing.assert_allclose(still.joint_targets_rad, held.joint_targets_rad)
    assert np.abs(still.joint_positions_rad - held.joint_positions_rad).max() < 1e-3

    link.release_hold()
    wait_applied(link)
    released = link.read_arm()
    assert not released.hold_latched
    np.testing.assert_allclose(released.joint_targets_rad, still.joint_positions_rad, atol=1e-3)
    later = steps_later(link, WATCH_STEPS)
    assert np.abs(later.joint_positions_rad - still.joint_positions_rad).max() < 1e-3


def test_the_wrist_sensor_reads_the_peg(shared_world: World) -> None:
    sensor = SharedMemoryWrenchLink(shared_world.shm_name)
    first = sensor.read_wrench()
    later = wait_for(lambda: (sample := sensor.read_wrench()).sequence > first.sequence
                     and sample, WAIT_S, "a newer wrench sample")
    sensor.close()
    assert later.sample_time_ns > first.sample_time_ns
    assert np.linalg.norm(later.force_n) == pytest.approx(0.1 * 9.81, rel=0.05)  # N, at rest


def test_a_driver_process_exiting_leaves_the_segment(shared_world: World) -> None:
    driver = textwrap.dedent(f"""
        from services.world.shm_link import SharedMemoryArmLink, SharedMemoryWrenchLink
        closed = SharedMemoryArmLink({shared_world.shm_name!r})
        closed.read_arm()
        closed.close()
        left_open = SharedMemoryArmLink({shared_world.shm_name!r})
        left_open.hold(); left_open.release_hold()
        SharedMemoryWrenchLink({shared_world.shm_name!r}).read_wrench()
        print("ok")
    """)  # exits with links still attached
    done = subprocess.run([sys.executable, "-c", driver], cwd=REPO, capture_output=True,
                          text=True, timeout=30)
    assert done.returncode == 0 and done.stdout.strip() == "ok", done.stderr
    # No resource_tracker clean-up of the world's segment. The driver's tracker (Python < 3.13)
    # acts when the driver exits, and holds the driver's stderr open until it has: run() read
    # that to its end, so whatever the tracker would do is done by now.
    assert "leaked" not in done.stderr
    assert segment_exists(shared_world.shm_name)
    link = SharedMemoryArmLink(shared_world.shm_name)
    link.read_arm()
    link.close()


@pytest.mark.parametrize("signum", [signal.SIGTERM, signal.SIGINT])
def test_a_signal_stops_the_world_and_removes_its_segment(world_factory, signum) -> None:
    world = world_factory()
    link = SharedMemoryArmLink(world.shm_name)
    link.read_arm()
    # (Should it hang, stop() has it write its threads' stacks before it is killed, and the
    # output shows them.)
    assert world.running.stop(signum, grace_s=STOP_LIMIT_S) == 0, world.output()
    assert not segment_exists(world.shm_name)
    with pytest.raises(UnavailableError, match="shut down"):
        link.read_arm()
    link.close()
    with pytest.raises(UnavailableError, match="no world is running"):
        SharedMemoryArmLink(world.shm_name)
    assert "loop stats at shutdown" in world.output()


def test_a_killed_world_is_stale_and_a_new_one_takes_its_place(world_factory) -> None:
    world = world_factory()
    link = SharedMemoryArmLink(world.shm_name)
    world.running.process.kill()
    world.running.process.wait(STOP_LIMIT_S)
    gone = wait_for(lambda: unavailable(link), STALE_AFTER_S + WAIT_S,
                    "the link to see the heartbeat stop")
    assert gone.reason in ("WORLD_STALE", "WORLD_STOPPED"), gone
    link.close()

    world_factory(world.shm_name)  # replaces the segment if the killed one left it
    fresh = SharedMemoryArmLink(world.shm_name)
    assert not fresh.read_arm().hold_latched
    fresh.close()


def test_a_second_world_on_the_same_segment_refuses_to_start(shared_world: World) -> None:
    second = subprocess.run(
        [sys.executable, "-m", "services.world", "--address", "127.0.0.1:0",
         "--shm-name", shared_world.shm_name],
        cwd=REPO, capture_output=True, text=True, timeout=60)
    assert second.returncode == 1
    assert "already running" in second.stderr
    SharedMemoryArmLink(shared_world.shm_name).close()  # the first is untouched


def test_every_thread_that_serves_runs_real_time_below_the_physics_thread(
        shared_world: World) -> None:
    # The physics thread needs the GIL at every step: whichever thread of the world holds it
    # must get a core at once, so gRPC's and the lanes' threads are real-time too.
    pid = shared_world.running.process.pid
    scheduling = {}
    for task in os.listdir(f"/proc/{pid}/task"):
        with open(f"/proc/{pid}/task/{task}/comm") as comm:
            name = comm.read().strip()
        policy = os.sched_getscheduler(int(task)) & ~os.SCHED_RESET_ON_FORK
        scheduling[name] = (policy, os.sched_getparam(int(task)).sched_priority)
    if scheduling["physics"][0] != os.SCHED_FIFO:
        pytest.skip("this host gives the world no SCHED_FIFO (its log says why)")
    assert scheduling["physics"] == (os.SCHED_FIFO, PHYSICS_THREAD_FIFO_PRIORITY)
    serving = {name: policy for name, policy in scheduling.items()
               if name.startswith(("rpc-", "event_engine", "metrics-", "loop-stats"))}
    assert serving and set(serving.values()) == {(os.SCHED_FIFO, COMMAND_PATH_FIFO_PRIORITY)}, (
        scheduling)
