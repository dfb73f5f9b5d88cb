"""DecisionCore in-process, on a fake slave and a fake clock: no process, no world, no sleeps.

Each test of a defect names it; each failed on the core before it owned the arm."""

from __future__ import annotations

import threading

import numpy as np
import pytest

from services.decision_server.arbitration import ControlMode
from services.decision_server.assistance import Assistance
from services.decision_server.core import (
    AssistanceChanged,
    ControlChanged,
    DecisionCore,
    ReplayProgress,
)
from services.decision_server.sessions import WatchdogHold
from services.security.caller import Caller, acting_as
from services.security.roles import Role
from tests.conftest import wait_for
from tests.decision_server.conftest import Rig
from tests.fakes.slave import FakeSlave
from wire.errors import FailedPreconditionError, OutOfRangeError, PermissionDeniedError

SERVO_PERIOD_S = 0.001


def moves_in(rig: Rig, steps: int, loops: int) -> int:
    """Force-control moves sent while the arm steps `steps` servo periods, once `loops` loops
    read the sensor. One loop acts on every 5th sample; a second one would double it."""
    wait_for(lambda: rig.slave.subscribers() == loops, what=f"{loops} loops reading")
    # A stopped loop leaves the sensor first and its thread after: a step it was already
    # sending lands in between, so wait for the threads themselves to be gone.
    wait_for(lambda: sum(t.name == "force-control" and t.is_alive()
                         for t in threading.enumerate()) <= loops,
             what=f"at most {loops} loop threads")
    rig.slave.step(SERVO_PERIOD_S, 10)  # a fresh loop skips its first sample
    before = rig.moves()
    rig.slave.step(SERVO_PERIOD_S, steps)
    return rig.moves() - before


def test_force_control_brings_the_contact_force_to_its_target(rig):
    rig.slave.floor_z = rig.slave.tool_pose().translation[2] - 0.002  # 2 mm below the tip
    rig.force_control(desired_z_n=-5.0)
    wait_for(lambda: rig.slave.subscribers() == 1, what="the force loop to subscribe")
    rig.slave.step(SERVO_PERIOD_S, 3000)
    force = rig.core.wrench().force_n
    # The table pushes up on a tool whose z points down: −5 N along the tool's z. Increments
    # under the IK's resolution are added up, not lost, so it settles to within the smallest
    # step sent: K · 2 µm = 0.02 N (without that, anywhere within 0.1 N).
    assert force[2] == pytest.approx(-5.0, abs=0.02)
    assert np.abs(force[:2]).max() < 1e-3  # the IK's 1 µrad tilts the normal force
    depth = rig.slave.floor_z - rig.slave.tool_pose().translation[2]
    assert depth == pytest.approx(5.0 / rig.slave.stiffness, abs=0.02 / rig.slave.stiffness)


def test_a_stop_through_another_door_stops_force_control_within_one_state_sample(rig):
    """Defect: the DecisionServer kept its own e-stop flag, set only by its own stop path, so
    after a stop through the band its force loop kept sending refused moves at 200 Hz."""
    rig.force_control()
    wait_for(lambda: rig.slave.subscribers() == 1, what="the force loop to subscribe")
    rig.slave.step(SERVO_PERIOD_S, 50)
    assert rig.moves() > 0  # free space: the loop drives the tool towards the table
    rig.slave.latch_at_hardware("stopped through the band")
    rig.slave.step(SERVO_PERIOD_S)  # one state sample
    assert rig.core.latched == "ESTOPPED"
    assert rig.core.force_loop is None
    assert moves_in(rig, 50, loops=0) == 0
    commands = len(rig.slave.commands)
    with pytest.raises(FailedPreconditionError, match="ESTOPPED"):
        rig.core.open_session("alice", rig.lease.lease_id, None, 0.1)
    with pytest.raises(FailedPreconditionError, match="ESTOPPED"):
        rig.core.move_cartesian(rig.lease.lease_id, np.zeros(3), np.eye(3), "BASE")
    assert len(rig.slave.commands) == commands  # refused here, not by the arm
    # Reset clears it, and force control, still configured, resumes.
    assert rig.core.reset(rig.lease.lease_id) == "READY"
    assert rig.core.latched is None and rig.core.force_loop is not None


def test_reset_with_force_control_on_runs_exactly_one_loop(rig):
    """Defect: Reset started a second force loop without stopping the first, whose stop
    event was then lost."""
    rig.force_control()
    wait_for(lambda: rig.slave.subscribers() == 1, what="the force loop to subscribe")
    assert moves_in(rig, 50, loops=1) == 10
    rig.core.reset(rig.lease.lease_id)  # an idle reset: nothing latched
    rig.core.reset(rig.lease.lease_id)
    assert moves_in(rig, 50, loops=1) == 10
    rig.core.set_assistance(rig.lease.lease_id, Assistance())
    assert moves_in(rig, 50, loops=0) == 0


def test_concurrent_set_assistance_leaves_exactly_one_loop(rig):
    """Defect: two concurrent SetAssistance calls each started a loop; one was never
    stopped."""
    start = threading.Barrier(8)

    def switch_on():
        start.wait()
        rig.force_control()

    threads = [threading.Thread(target=switch_on) for _ in range(8)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert moves_in(rig, 50, loops=1) == 10
    rig.core.set_assistance(rig.lease.lease_id, Assistance())
    assert moves_in(rig, 50, loops=0) == 0


def test_force_control_ends_when_its_lease_lapses(rig):
    events = rig.core.events.subscribe(64)
    rig.core.locks.release(rig.lease.lease_id)
    lease = rig.core.locks.acquire("bob", ControlMode.EXCLUSIVE, lease_s=0.5)
    rig.lease = lease
    rig.force_control()
    wait_for(lambda: rig.slave.subscribers() == 1, what="the force loop to subscribe")
    rig.slave.step(SERVO_PERIOD_S, 400)  # within the lease
    assert rig.core.assistance.force_control is not None
    moving = rig.moves()
    assert moving > 0
    rig.slave.step(SERVO_PERIOD_S, 200)  # nobody renews: the lease lapses at 0.5 s
    wait_for(lambda: rig.core.assistance.force_control is None, what="force control off")
    assert moves_in(rig, 100, loops=0) == 0
    payloads = []

    def told_after_the_lapse() -> bool:
        while (event := events.get(0)) is not None:
            payloads.append(event.payload)
        lapsed = [i for i, p in enumerate(payloads) if isinstance(p, ControlChanged)
                  and "bob's lease expired" in p.reason]
        return bool(lapsed) and any(
            isinstance(p, AssistanceChanged) and p.assistance.force_control is None
            for p in payloads[lapsed[-1]:])

    wait_for(told_after_the_lapse, what="the lapse, then force control off, as events")


def test_force_control_acts_on_fresh_samples_only(rig):
    """Samples that arrive late (a backlog on a loaded machine) are skipped, not acted on."""
    rig.force_control()
    rig.slave.wrench_delay_s = 0.1
    assert moves_in(rig, 50, loops=1) == 0
    rig.slave.wrench_delay_s = 0.0
    assert moves_in(rig, 50, loops=1) == 10


def test_a_refused_step_switches_force_control_off_and_says_so(rig, monkeypatch):
    events = rig.core.events.subscribe(64)
    rig.force_control()
    wait_for(lambda: rig.slave.subscribers() == 1, what="the force loop to subscribe")

    def refuse(*args):
        raise OutOfRangeError("past the workspace", reason="WORKSPACE")

    monkeypatch.setattr(rig.slave, "move_cartesian", refuse)
    rig.slave.step(SERVO_PERIOD_S, 20)

    def switched_off():
        event = events.get(0)
        return (event is not None and isinstance(event.payload, AssistanceChanged)
                and event.payload.assistance.force_control is None)

    wait_for(switched_off, what="an AssistanceChanged with force control off")
    assert rig.core.assistance.force_control is None and rig.core.force_loop is None


def test_a_step_refused_for_a_latch_pauses_force_control_until_reset(rig):
    """The loop (200 Hz) can meet a latch before the state stream (100 Hz) reports it: that
    pauses force control, like the latch itself, rather than switching it off."""
    rig.force_control()
    assert moves_in(rig, 50, loops=1) == 10
    rig.slave.publish_state = False  # the state stream lags behind
    rig.slave.latch_at_hardware()
    rig.slave.step(SERVO_PERIOD_S, 10)  # the loop's next step is refused: ESTOPPED
    wait_for(lambda: rig.core.force_loop is None, what="the loop to pause")
    assert rig.core.assistance.force_control is not None
    rig.slave.publish_state = True
    rig.slave.step(SERVO_PERIOD_S)
    assert rig.core.latched == "ESTOPPED"
    rig.core.reset(rig.lease.lease_id)
    assert moves_in(rig, 50, loops=1) == 10


def test_direct_moves_are_recorded_and_refused_while_latched(rig):
    """Defect: RunAction's moves went around the core: not recorded, no latch check."""
    lease = rig.lease.lease_id
    rig.core.start_recording(lease, "direct")
    rig.core.move_cartesian(lease, np.array([0.0, 0.0, 0.01]), np.eye(3), "BASE")
    rig.core.move_joints(lease, np.array([0.05, 0, 0, 0, 0, 0]))
    info = rig.core.recordings.stop()
    assert info.command_count == 2
    _, commands = rig.core.recordings.load("direct")
    assert [c.frame for c in commands] == ["BASE", "JOINTS"]
    np.testing.assert_allclose(commands[1].delta_joints_rad, [0.05, 0, 0, 0, 0, 0])

    rig.core.emergency_stop("test")
    commands = len(rig.slave.commands)
    with pytest.raises(FailedPreconditionError, match="ESTOPPED"):
        rig.core.move_joints(lease, np.array([0.05, 0, 0, 0, 0, 0]))
    assert len(rig.slave.commands) == commands  # refused here, not by the arm


def test_stop_and_reset_answer_with_the_status_after_them(rig):
    """Defect: the servicer asked for the status again after stop and reset."""
    assert rig.core.emergency_stop("test") == "ESTOPPED"
    assert rig.core.latched == "ESTOPPED"
    assert rig.core.reset(rig.lease.lease_id) == "READY"
    assert [c.kind for c in rig.slave.commands] == ["estop", "reset"]


def test_an_old_state_sample_does_not_undo_a_stop(rig):
    before = rig.slave.state()
    rig.clock.advance(0.001)
    rig.core.emergency_stop("test")
    rig.slave.on_state(before)  # a sample taken before the stop, delivered after it
    assert rig.core.latched == "ESTOPPED"


def test_the_tool_frame_reaches_the_arm_and_the_sensor(rig):
    import pinocchio as pin

    frame = pin.SE3(np.eye(3), np.array([0.0, 0.0, 0.15]))
    rig.core.set_tool_frame(rig.lease.lease_id, frame)
    assert rig.slave.kinematics.flange_T_tool == frame
    assert rig.slave.sensor_flange_to_tool == frame


def test_heartbeats_keep_the_lease(rig):
    rig.core.locks.release(rig.lease.lease_id)
    lease = rig.core.locks.acquire("carol", ControlMode.EXCLUSIVE, lease_s=0.5)
    session = rig.core.open_session("carol", lease.lease_id, None, 1.0)
    for _ in range(10):  # 2 s of heartbeats every 0.2 s: four leases' worth
        rig.clock.advance(0.2)
        session.heartbeat()
    assert [h.operator_id for h in rig.core.locks.view().holders] == ["carol"]
    session.close("done")


def test_the_watchdog_holds_the_arm_exactly_at_its_timeout(rig):
    events = rig.core.events.subscribe(64)
    armed = rig.clock.waiters()
    session = rig.core.open_session("alice", rig.lease.lease_id, None, 0.05)
    session.command(np.array([0.0, 0.0, 0.01]), np.eye(3), False)
    wait_for(lambda: rig.clock.waiters() > armed, what="the watchdog to arm")
    rig.clock.advance(0.049)
    assert not any(c.kind == "hold" for c in rig.slave.commands)
    rig.clock.advance(0.002)
    wait_for(lambda: any(c.kind == "hold" for c in rig.slave.commands), what="a hold")
    event = wait_for(lambda: events.get(0), what="the hold event")
    while not isinstance(event.payload, WatchdogHold):
        event = wait_for(lambda: events.get(0), what="the hold event")
    assert event.payload.silence_s == pytest.approx(0.051, abs=1e-9)
    assert "watchdog timeout" in event.payload.reason
    session.close("the stream ended")
    assert sum(c.kind == "hold" for c in rig.slave.commands) == 1  # no second hold


def test_commands_do_not_wake_the_watchdog_and_it_still_holds_at_the_last_ones_timeout(rig):
    """A command only moves the watchdog's deadline later: the watchdog finds that out when
    its wait ends, so commands cost it no wake-up, and its hold still comes exactly one
    timeout after the last of them."""
    armed = rig.clock.waiters()
    session = rig.core.open_session("alice", rig.lease.lease_id, None, 0.05)
    wakes = []
    wake = session._activity.set
    session._activity.set = lambda: (wakes.append(rig.clock.monotonic()), wake())
    wait_for(lambda: rig.clock.waiters() > armed, what="the watchdog to arm")
    for _ in range(20):  # 0.2 s of commands every 10 ms: four timeouts' worth
        session.command(np.array([0.0, 0.0, 0.0001]), np.eye(3), False)
        rig.clock.advance(0.01)
    assert wakes == []
    assert not any(c.kind == "hold" for c in rig.slave.commands)
    rig.clock.advance(0.039)  # 0.049 s after the last command
    assert not any(c.kind == "hold" for c in rig.slave.commands)
    rig.clock.advance(0.002)
    wait_for(lambda: any(c.kind == "hold" for c in rig.slave.commands), what="a hold")
    session.close("done")


def test_the_watchdog_holds_only_after_a_move_in_flight_lands(rig):
    """A station so slow that the watchdog times out while a command's move is in flight: the
    hold waits for that move to land. Sent beside it, the hold could reach the arm first and
    the late move carry the held arm on."""
    in_flight, land = threading.Event(), threading.Event()
    move = rig.slave.move_cartesian

    def slow_move(*args):
        in_flight.set()
        assert land.wait(10)
        return move(*args)

    rig.slave.move_cartesian = slow_move
    armed = rig.clock.waiters()
    session = rig.core.open_session("alice", rig.lease.lease_id, None, 0.05)
    sender = threading.Thread(target=session.command,
                              args=(np.array([0.0, 0.0, 0.001]), np.eye(3), False))
    sender.start()
    assert in_flight.wait(10)
    rig.clock.advance(0.06)  # past the watchdog's timeout, with the move in flight
    wait_for(lambda: rig.clock.waiters() == armed, what="the watchdog to wake and hold")
    land.set()
    sender.join(10)
    wait_for(lambda: any(c.kind == "hold" for c in rig.slave.commands), what="a hold")
    assert [c.kind for c in rig.slave.commands] == ["cartesian", "hold"]
    session.close("done")


# -- a backlog of commands: one move -------------------------------------------------------------

def _increments(rig: Rig, steps, clutch=()):
    from services.decision_server.sessions import MasterIncrement

    return [MasterIncrement(np.asarray(dx, float), rotation, i in clutch, rig.clock.time_ns())
            for i, (dx, rotation) in enumerate(steps)]


def _rotation_z(angle: float) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


@pytest.mark.parametrize("mapping", ["BASE", "TOOL"])
def test_a_backlog_of_commands_is_one_move_to_where_the_commands_one_by_one_lead(rig, mapping):
    """Commands that arrived together reach the arm as one move; the arm ends where the same
    commands sent one at a time take it, and each command gets its own result."""
    steps = [([0.001, 0.0, 0.0], _rotation_z(0.01)), ([0.0, 0.002, 0.0], np.eye(3)),
             ([0.0, 0.0, -0.001], _rotation_z(-0.02))]
    session = rig.core.open_session("alice", rig.lease.lease_id, mapping, 1.0)
    results = session.commands(_increments(rig, steps))
    assert [r.outcome for r in results] == ["APPLIED"] * 3
    assert rig.moves() == 1
    merged = rig.slave.kinematics.tool_pose(rig.slave.q_target)
    session.close("done")

    one_by_one = FakeSlave(rig.clock)
    core = DecisionCore(one_by_one, rig.core.recordings, rig.clock)
    lease = core.locks.acquire("bob", ControlMode.EXCLUSIVE)
    single = core.open_session("bob", lease.lease_id, mapping, 1.0)
    for dx, rotation in steps:
        single.command(np.asarray(dx, float), rotation, False)
    expected = one_by_one.kinematics.tool_pose(one_by_one.q_target)
    single.close("done")
    core.close()
    np.testing.assert_allclose(merged.translation, expected.translation, atol=1e-6)
    np.testing.assert_allclose(merged.rotation, expected.rotation, atol=1e-6)


def test_the_clutch_splits_a_backlog_and_its_commands_move_nothing(rig):
    session = rig.core.open_session("alice", rig.lease.lease_id, None, 1.0)
    step = ([0.001, 0.0, 0.0], np.eye(3))
    results = session.commands(_increments(rig, [step] * 5, clutch={2}))
    assert [r.outcome for r in results] == ["APPLIED", "APPLIED", "INDEXED", "APPLIED",
                                            "APPLIED"]
    assert rig.moves() == 2  # before and after the clutch
    session.close("done")


def test_a_backlog_past_the_merge_bounds_goes_as_several_moves_none_refused(rig):
    """Thirty 1 mm commands (30 mm in all) would pass the 20 mm a merged move may carry: they
    go as two moves, each within it (so inside the arm's 50 mm cap)."""
    session = rig.core.open_session("alice", rig.lease.lease_id, None, 1.0)
    results = session.commands(_increments(rig, [([0.0, 0.0, 0.001], np.eye(3))] * 30))
    assert {r.outcome for r in results} == {"APPLIED"}
    sizes = [np.linalg.norm(c.detail[1]) for c in rig.slave.commands if c.kind == "cartesian"]
    assert len(sizes) == 2 and max(sizes) <= 0.02 and sum(sizes) == pytest.approx(0.03)
    session.close("done")


def test_a_refused_merged_move_rejects_each_of_its_commands(rig):
    session = rig.core.open_session("alice", rig.lease.lease_id, None, 1.0)
    rig.slave.latch_at_hardware()
    rig.slave.step(SERVO_PERIOD_S)  # the state sample that says ESTOPPED
    results = session.commands(_increments(rig, [([0.001, 0.0, 0.0], np.eye(3))] * 3))
    assert [r.outcome for r in results] == ["REJECTED"] * 3
    assert all("ESTOPPED" in r.detail for r in results)
    assert rig.moves() == 0
    session.close("done")


def test_closing_a_session_holds_after_the_move_in_flight_and_no_move_follows(rig):
    """The acting thread may be mid-move when the stream ends: the hold waits for that move to
    land, so it is the arm's last command; a command after the close moves nothing."""
    entered, release = threading.Event(), threading.Event()
    move = rig.slave.move_cartesian

    def slow_move(*args):
        entered.set()
        release.wait(5)
        return move(*args)

    rig.slave.move_cartesian = slow_move
    session = rig.core.open_session("alice", rig.lease.lease_id, None, 1.0)
    mover = threading.Thread(target=session.command,
                             args=(np.array([0.0, 0.0, 0.001]), np.eye(3), False))
    mover.start()
    entered.wait(5)
    closer = threading.Thread(target=session.close, args=("the stream ended",))
    closer.start()
    wait_for(lambda: session._closed.is_set(), what="the close to begin")
    assert not any(c.kind == "hold" for c in rig.slave.commands)  # it waits for the move
    release.set()
    mover.join(5), closer.join(5)
    assert [c.kind for c in rig.slave.commands][-2:] == ["cartesian", "hold"]
    late = session.command(np.array([0.0, 0.0, 0.001]), np.eye(3), False)
    assert late.outcome == "REJECTED" and "ended" in late.detail
    assert rig.slave.commands[-1].kind == "hold"


def test_a_replay_stops_when_its_lease_ends(rig):
    """A replay moves the arm only while the lease that started it is held: released (or
    lapsed), the replay ends and no recorded move follows."""
    lease = rig.lease.lease_id
    rig.core.start_recording(lease, "three")
    for _ in range(3):
        rig.core.move_cartesian(lease, np.array([0.0, 0.0, 0.002]), np.eye(3), "BASE")
        rig.clock.advance(1.0)
    rig.core.recordings.stop()
    events = rig.core.events.subscribe(64)
    before = len(rig.slave.commands)
    rig.core.start_replay(lease, "three", 1.0)
    wait_for(lambda: len(rig.slave.commands) == before + 1, what="the replay's first move")
    rig.core.locks.release(lease)
    payloads = []

    def interrupted():
        while (event := events.get(0)) is not None:
            payloads.append(event.payload)
        return [p for p in payloads if isinstance(p, ReplayProgress)
                and p.state == "INTERRUPTED"]

    (ended,) = wait_for(interrupted, what="the replay to end with the lease")
    assert "lease" in ended.detail
    rig.clock.advance(5.0)  # past every recorded move's time
    assert len(rig.slave.commands) == before + 1


def test_only_the_lease_holder_stops_a_recording(rig):
    """Issue #31: StopRecording needed no lease. With identities (TLS), another operator
    presenting the holder's lease id is refused too, as for every call that needs the lock."""
    rig.core.locks.release(rig.lease.lease_id)
    with acting_as(Caller("alice", Role.OPERATOR)):
        lease = rig.core.locks.acquire("alice", ControlMode.EXCLUSIVE).lease_id
        rig.core.start_recording(lease, "hers")
    with acting_as(Caller("mallory", Role.OPERATOR)):
        with pytest.raises(FailedPreconditionError, match="held by 'alice'") as refused:
            rig.core.stop_recording(None)
        assert refused.value.reason == "NO_CONTROL"
        with pytest.raises(PermissionDeniedError) as refused:
            rig.core.stop_recording(lease)
        assert refused.value.reason == "NOT_YOUR_LEASE"
    assert rig.core.recordings.recording
    with acting_as(Caller("alice", Role.OPERATOR)):
        assert rig.core.stop_recording(lease).name == "hers"
    assert not rig.core.recordings.recording
