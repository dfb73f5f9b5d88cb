"""ProxyRobot's Franka driver against franka-sim: libfranka's own protocol, served by a MuJoCo FR3
(the project's own FR3 cell) from its own venv, on 127.0.0.1:1337. The link alone, then the
ProxyRobot process with --driver franka, with the force sensor and the emergency-stop band on its
mirror of the arm."""

from __future__ import annotations

import os
import signal
import threading
import time
from types import SimpleNamespace

import numpy as np
import pytest

from clients.python import ForceSensorClient, ProxyRobotClient, RobotStatus
from domain.robot_model.description import arm_description
from domain.robot_model.workspace import cell_for
from services.franka_sim.process import start_franka_sim as launch
from services.proxy_robot.franka_link import FrankaArmLink, libfranka_exceptions
from services.runtime import children
from services.runtime.priority import COMMAND_PATH_FIFO_PRIORITY
from tests.conftest import wait_for
from tests.processes import start_process, unique_shm_name
from wire.errors import FailedPreconditionError, UnavailableError

pytestmark = pytest.mark.e2e

HOST = "127.0.0.1"
FR3 = arm_description("fr3")
CELL = cell_for("fr3")
# A spot on the table beside the fixture, that the FR3 reaches with its peg pointing down.
TABLE_SPOT = np.array([CELL.fixture_center_xy[0] + 0.10, CELL.fixture_center_xy[1] + 0.10,
                       CELL.table_top_z])

def start_franka_sim(*args: str) -> children.Child:
    return launch(HOST, *args, max_lines=None)


@pytest.fixture
def franka_sim():
    sim = start_franka_sim()
    yield sim
    sim.stop(signal.SIGTERM)


@pytest.fixture
def link(franka_sim):
    link = FrankaArmLink(HOST, FR3)
    yield link
    link.close()


def _at(link: FrankaArmLink, q: np.ndarray, tolerance: float = 1e-3) -> bool:
    return bool(np.abs(link.read_arm().joint_positions_rad - q).max() < tolerance)


def test_the_link_drives_the_arm_home_through_libfrankas_loop(franka_sim):
    """Made from a thread at the station's real-time priority, as ProxyRobot makes it: libfranka
    raises the connecting thread to SCHED_FIFO 99, and the link puts it back, so its control
    loop keeps the maker's priority. How many commands reach the robot in time (libfranka's
    control_command_success_rate) is not asserted: the loop gives up the GIL in readOnce() and
    waits for it afterwards, so any busy Python thread of the same process costs it cycles (a
    spinning thread read 0.60 here), and this process is the test runner's. make bench's
    franka_command_1000 reports the rate."""
    made: list[FrankaArmLink] = []

    def make() -> None:
        os.sched_setscheduler(0, os.SCHED_FIFO, os.sched_param(COMMAND_PATH_FIFO_PRIORITY))
        made.append(FrankaArmLink(HOST, FR3))
        assert os.sched_getparam(0).sched_priority == COMMAND_PATH_FIFO_PRIORITY

    maker = threading.Thread(target=make)
    maker.start()
    maker.join(30)
    link = made[0]
    try:
        loop = next(t for t in threading.enumerate() if t.name == "franka-control")
        assert os.sched_getscheduler(loop.native_id) == os.SCHED_FIFO
        assert os.sched_getparam(loop.native_id).sched_priority == COMMAND_PATH_FIFO_PRIORITY
        link.write_target(FR3.home_q)
        wait_for(lambda: _at(link, FR3.home_q), timeout_s=15, what="the FR3 at home")
        sample = link.read_arm()
        assert not sample.hold_latched and sample.fault == ""
        assert link.mode == "RobotMode.Move"
    finally:
        link.close()


def _still_for(link, cycles: int) -> bool:
    """Every joint slower than 1 mrad/s now, and within 0.1 mrad of where it was `cycles`
    control cycles ago."""
    before = link.read_arm()
    wait_for(lambda: link.read_arm().sequence >= before.sequence + cycles, timeout_s=2,
             what=f"{cycles} cycles")
    now = link.read_arm()
    return (np.abs(now.joint_velocities_rad_per_s).max() < 1e-3
            and np.abs(now.joint_positions_rad - before.joint_positions_rad).max() < 1e-4)


def test_a_hold_brakes_in_the_next_control_cycle_and_holds(link):
    link.write_target(FR3.home_q)
    wait_for(lambda: _at(link, FR3.home_q), timeout_s=15, what="the FR3 at home")
    far = FR3.home_q.copy()
    far[0] += 1.0
    link.write_target(far)
    wait_for(lambda: abs(link.read_arm().joint_velocities_rad_per_s[0]) > 0.5, timeout_s=5,
             what="joint 1 moving")
    link.hold()
    wait_for(lambda: link.hold_latency_cycles is not None, timeout_s=1, what="a cycle after it")
    assert link.hold_latency_cycles <= 2
    # At rest: every joint, and for 50 cycles, not a zero crossing of joint 1's ringing (the
    # other joints ring on after the brake too).
    wait_for(lambda: _still_for(link, 50), timeout_s=5, what="the arm at rest")
    held = link.read_arm()
    assert held.hold_latched and held.joint_positions_rad[0] < far[0] - 0.3
    link.write_target(far)  # ignored while latched
    time_ok = held.joint_positions_rad.copy()
    wait_for(lambda: link.read_arm().sequence > held.sequence + 100, timeout_s=2,
             what="100 more cycles")
    assert np.abs(link.read_arm().joint_positions_rad - time_ok).max() < 1e-3
    link.release_hold()
    link.write_target(FR3.home_q)
    wait_for(lambda: _at(link, FR3.home_q), timeout_s=15, what="the FR3 back home")


def test_a_reflex_is_a_named_fault_and_reset_recovers_the_robot():
    """A driver that stops commanding for 20 cycles trips the FCI's communication reflex (a
    stalled driver, here by taking the link's lock); libfranka's error recovery clears it."""
    sim = start_franka_sim("--enforce-comm-constraints")
    link = FrankaArmLink(HOST, FR3)
    try:
        with link._lock:  # the control loop waits here until the robot gives the motion up
            sim.wait_line("communication_constraints_violation", timeout_s=5)
        sample = wait_for(lambda: link.read_arm().fault and link.read_arm(), timeout_s=5,
                          what="the reflex as a fault")
        assert sample.hold_latched
        assert sample.fault.startswith("Franka (RobotMode."), sample.fault
        assert "communication_constraints_violation" in sample.fault, sample.fault
        link.release_hold()  # ProxyRobot's Reset
        assert link.read_arm().fault == "" and not link.read_arm().hold_latched
        link.write_target(FR3.home_q)
        wait_for(lambda: _at(link, FR3.home_q), timeout_s=15, what="the FR3 moving again")
    finally:
        link.close()
        sim.stop(signal.SIGTERM)


def _lost(link: FrankaArmLink) -> str:
    """Why the link says the robot is gone ("" while it answers): UNAVAILABLE when libfranka's
    loop went quiet, or the fault it latched when libfranka raised first."""
    try:
        return link.read_arm().fault
    except UnavailableError as error:
        return str(error)


def test_a_network_failure_asks_the_robot_nothing_more():
    """A robot that is gone is not read again for its errors (pylibfranka would hold the GIL
    through its 2 s receive timeout); one that raised a control exception still answers."""
    import pylibfranka

    class Robot:
        reads = 0

        def read_once(self):
            Robot.reads += 1
            return SimpleNamespace(last_motion_errors=SimpleNamespace(cartesian_reflex=True))

    link = FrankaArmLink.__new__(FrankaArmLink)
    link._franka, link._robot = pylibfranka, Robot()
    link._failures = libfranka_exceptions(pylibfranka)
    gone = pylibfranka.NetworkException("libfranka: UDP receive: Timeout")
    assert link._describe(gone) == "libfranka: UDP receive: Timeout" and Robot.reads == 0
    reflex = pylibfranka.ControlException("libfranka: Move command aborted")
    assert link._describe(reflex) == "libfranka: Move command aborted (cartesian_reflex)"
    assert Robot.reads == 1


def test_a_killed_franka_sim_is_a_clear_error_not_a_hang(franka_sim):
    link = FrankaArmLink(HOST, FR3)
    franka_sim.stop(signal.SIGKILL)
    why = wait_for(lambda: _lost(link), timeout_s=2, what="the link to say the robot is gone")
    assert (f"the Franka at {HOST} has not answered for" in why
            or why.startswith("Franka (RobotMode.")), why
    closing = time.monotonic()
    link.close()
    assert time.monotonic() - closing < 5
    restarted = start_franka_sim()  # and a new connection drives it again
    try:
        again = FrankaArmLink(HOST, FR3)
        again.write_target(FR3.home_q)
        wait_for(lambda: _at(again, FR3.home_q), timeout_s=15, what="the FR3 home again")
        again.close()
    finally:
        restarted.stop(signal.SIGTERM)


def start_franka_driver(shm_name: str, *args: str) -> children.Child:
    """ProxyRobot with --driver franka, mirroring the arm on the segment `shm_name`."""
    return start_process(["-m", "services.proxy_robot", "--address", "127.0.0.1:0",
                          "--arm", "fr3", "--driver", "franka", "--robot-host", HOST, *args],
                         env={"TELEROBOT_WORLD_SHM": shm_name})


def test_the_proxy_robot_process_drives_the_franka(franka_sim):
    robot_process = start_franka_driver(unique_shm_name())
    try:
        with ProxyRobotClient(robot_process.wait_ready(timeout_s=60)) as robot:
            assert robot.get_arm_info().name == "fr3"
            robot.connect()
            robot.initialize()
            start = robot.get_state().tool_pose.translation.copy()
            for _ in range(20):
                robot.move_cartesian([0.0, 0.004, 0.002])
            goal = start + np.array([0.0, 0.08, 0.04])
            wait_for(lambda: np.linalg.norm(robot.get_state().tool_pose.translation - goal)
                     < 1e-3, timeout_s=15, what="the tool at the sum of the moves")
            assert robot.emergency_stop("test") is RobotStatus.ESTOPPED
            assert robot.reset() is RobotStatus.READY
    finally:
        robot_process.stop(signal.SIGTERM)


def test_a_driver_that_cannot_reach_its_robot_exits_2_before_serving():
    started = time.monotonic()
    process = start_process(["-m", "services.proxy_robot", "--address", "127.0.0.1:0",
                             "--arm", "fr3", "--driver", "franka", "--robot-host", "127.0.0.7"])
    assert process.wait(timeout_s=60) == 2
    output = "\n".join(process.lines)
    assert "cannot reach the Franka at 127.0.0.7 (libfranka, port 1337)" in output, output
    assert process.ready == {}
    assert time.monotonic() - started < 60


@pytest.mark.parametrize(("args", "says"), [
    (["--arm", "puma560", "--robot-host", HOST], "--driver franka drives a Franka FR3, and "
                                                 "--arm is puma560: use --arm fr3"),
    (["--arm", "fr3"], "--driver franka needs --robot-host"),
], ids=["another-arm", "no-host"])
def test_a_franka_driver_started_wrong_exits_2_saying_why(args, says):
    process = start_process(["-m", "services.proxy_robot", "--address", "127.0.0.1:0",
                             "--driver", "franka", *args])
    assert process.wait(timeout_s=60) == 2
    assert any(says in line for line in process.lines), "\n".join(process.lines)
    assert process.ready == {}


def _move_tool_to(robot: ProxyRobotClient, goal: np.ndarray) -> None:
    """Cartesian moves of at most 2 cm that add up to `goal`, then until the tool is there."""
    delta = goal - robot.get_state().tool_pose.translation
    steps = int(np.ceil(np.linalg.norm(delta) / 0.02))
    for _ in range(steps):
        robot.move_cartesian(delta / steps)
    wait_for(lambda: np.linalg.norm(goal - robot.get_state().tool_pose.translation) < 1e-3,
             timeout_s=30, what=f"the tool at {goal}")


def test_the_force_sensor_feels_a_push_through_the_frankas_joints_and_the_band_stops_it(
        franka_sim):
    """The force sensor and the band run on the driver's mirror of the Franka, as on the world:
    pressed onto the table, the joint-impedance spring's push reads as the table's reaction
    along the peg; the band's stop latches the Franka's hold."""
    shm_name = unique_shm_name()
    env = {"TELEROBOT_WORLD_SHM": shm_name}
    robot_process = start_franka_driver(shm_name, "--torque-source", "impedance")
    processes = [robot_process]
    try:
        robot_address = robot_process.wait_ready(timeout_s=60)
        processes.append(start_process(["-m", "services.force_sensor", "--address",
                                        "127.0.0.1:0", "--arm", "fr3", "--sensor", "franka"],
                                       env=env))
        processes.append(start_process(["-m", "services.emergency_stop", "--address",
                                        "127.0.0.1:0", "--arm", "fr3"], env=env))
        sensor_address, band_address = (p.wait_ready(timeout_s=60) for p in processes[1:])
        with ProxyRobotClient(robot_address) as robot, \
                ForceSensorClient(sensor_address) as sensor, \
                ProxyRobotClient(band_address) as band:
            robot.connect()
            robot.initialize()
            sensor.start_reading()
            _move_tool_to(robot, TABLE_SPOT + [0.0, 0.0, 0.03])
            wait_for(lambda: np.linalg.norm(sensor.get_wrench().force) < 0.5, timeout_s=5,
                     what="no push in free air")
            for _ in range(7):  # 5 mm into the table
                robot.move_cartesian([0.0, 0.0, -0.005])
            # Held back by the table short of its target: at rest, pressing.
            wait_for(lambda: sensor.get_wrench().force[2] < -30.0
                     and np.abs(robot.get_state().joint_velocities).max() < 1e-3,
                     timeout_s=10, what="the arm at rest on the table, pressing")
            pushed = sensor.get_wrench()
            # Up the peg's axis (the tool's z points down, into the table), with some friction
            # sideways: the joint springs are stiffer in some directions than in others.
            assert pushed.force[2] < -30.0, pushed
            assert abs(pushed.force[2]) > 0.85 * np.linalg.norm(pushed.force), pushed
            band.emergency_stop("the band, on the Franka")
            wait_for(lambda: robot.get_status().status is RobotStatus.ESTOPPED, timeout_s=5,
                     what="the band's stop latched on the Franka")
            with pytest.raises(FailedPreconditionError):
                robot.move_cartesian([0.0, 0.0, 0.01])
            # The reset holds where the arm stands: the table's push relaxes the spring.
            assert robot.reset() is RobotStatus.READY
    finally:
        for process in reversed(processes):
            process.stop(signal.SIGTERM)
