"""The DecisionServer's contracts over a real in-process gRPC server, in front of a fake slave
on a fake clock: no process, no world, no sleeps."""

from __future__ import annotations

import grpc
import numpy as np
import pytest

from clients.python.errors import from_rpc_error
from services.common import se3
from services.decision_server.clock_offset import ClockOffsetEstimator
from services.decision_server.servicer import MAX_COMMANDS_PER_MESSAGE, make_facades
from services.decision_server.sessions import CommandResult
from telerobot.v1 import decision_server_pb2 as pb
from telerobot.v1 import options_pb2, proxy_robot_pb2, types_pb2
from tests.conftest import wait_for
from tests.decision_server.conftest import Operator
from wire import convert
from wire.errors import FailedPreconditionError
from wire.metadata import LEASE_METADATA_KEY


def test_acks_carry_the_outcome_pose_status_and_a_fresh_wrench(fake_station):
    station, slave = fake_station
    lease, _ = station.acquire()
    operator = Operator(station, lease)
    ack = operator.move((0, 0, 0.005))
    assert ack.sequence == 1 and ack.outcome == pb.COMMAND_OUTCOME_APPLIED
    assert ack.status == types_pb2.ROBOT_STATUS_MOVING
    np.testing.assert_allclose(se3.pose_from_proto(ack.tool_pose, "").translation,
                               slave.tool_pose().translation)
    assert not ack.HasField("tool_wrench")  # the sensor has sampled nothing yet
    slave.step(0.001)
    assert operator.move().HasField("tool_wrench")
    slave.sensor_reading = False  # StopReading: the wrench leaves the acks
    assert not operator.move().HasField("tool_wrench")
    assert operator.move((0, 0, 0.005), clutch=True).outcome == pb.COMMAND_OUTCOME_INDEXED
    too_big = operator.move((0.2, 0, 0))
    assert too_big.outcome == pb.COMMAND_OUTCOME_REJECTED and "cap" in too_big.detail
    operator.close()


def test_each_command_is_aged_on_arrival_from_the_send_time_it_carries(fake_station):
    station, _ = fake_station
    ages: list[float] = []
    station.servicer.on_command_age = ages.append
    lease, _ = station.acquire()
    operator = Operator(station, lease)
    now_ns = station.core.clock.time_ns()
    operator.move(send_time_ns=now_ns - 200_000_000)  # 200 ms on the way, by the server's clock
    operator.move(send_time_ns=now_ns - 1_000_000)
    operator.close()
    assert ages == pytest.approx([0.200, 0.001])


def _burst(lease: str, grouped_acks: bool = False) -> list[pb.TeleoperateRequest]:
    """An init, then 20 commands of 0.5 mm up with a heartbeat after the tenth."""
    messages = [pb.TeleoperateRequest(init=pb.TeleoperateInit(
        operator_id="tester", lease_id=lease, mapping=types_pb2.REFERENCE_FRAME_BASE,
        watchdog_timeout=convert.duration(1.0), grouped_acks=grouped_acks))]
    for sequence in range(1, 21):
        messages.append(pb.TeleoperateRequest(command=pb.MasterCommand(
            sequence=sequence, delta_position_m=types_pb2.Vector3(z=0.0005))))
        if sequence == 10:
            messages.append(pb.TeleoperateRequest(heartbeat=pb.Heartbeat()))
    return messages


def test_a_burst_of_commands_gets_one_ack_each_in_order_and_moves_by_their_sum(fake_station):
    """However the server batches a backlog, every command gets its ack, in order, heartbeats
    in their place; the arm moves by all the increments."""
    station, slave = fake_station
    lease, _ = station.acquire()
    replies = list(station.decisions.Teleoperate(iter(_burst(lease)), timeout=30))
    acks = [r.ack for r in replies[1:]]
    assert [a.sequence for a in acks] == [*range(1, 11), 0, *range(11, 21)]
    assert acks[10].outcome == pb.COMMAND_OUTCOME_HEARTBEAT
    assert {a.outcome for a in acks[:10] + acks[11:]} == {pb.COMMAND_OUTCOME_APPLIED}
    moves = [c.detail[1] for c in slave.commands if c.kind == "cartesian"]
    np.testing.assert_allclose(np.sum(moves, axis=0), [0.0, 0.0, 0.01], atol=1e-9)


def test_grouped_acks_answer_every_command_in_order_in_acks_messages(fake_station):
    """TeleoperateInit.grouped_acks: every reply after ready is an `acks` group, and the
    groups together answer every command and heartbeat, in order, as single acks would."""
    station, _ = fake_station
    lease, _ = station.acquire()
    replies = list(station.decisions.Teleoperate(iter(_burst(lease, grouped_acks=True)),
                                                 timeout=30))
    assert {r.WhichOneof("message") for r in replies[1:]} == {"acks"}
    acks = [a for r in replies[1:] for a in r.acks.acks]
    assert [a.sequence for a in acks] == [*range(1, 11), 0, *range(11, 21)]
    assert all(a.HasField("tool_pose") for a in acks)


def _packed_burst(lease: str) -> list[pb.TeleoperateRequest]:
    """_burst with each run of commands in one `commands` message."""
    packed: list[pb.TeleoperateRequest] = []
    for request in _burst(lease, grouped_acks=True):
        if request.WhichOneof("message") != "command":
            packed.append(request)
        elif packed[-1].WhichOneof("message") == "commands":
            packed[-1].commands.commands.append(request.command)
        else:
            packed.append(pb.TeleoperateRequest(
                commands=pb.MasterCommands(commands=[request.command])))
    return packed


def test_commands_sent_together_are_each_applied_and_acked_as_if_alone(fake_station):
    """TeleoperateRequest.commands (a master whose link fell behind): each command gets its
    own ack, in order, the heartbeat between two such messages in its place; the arm moves by
    every increment."""
    station, slave = fake_station
    lease, _ = station.acquire()
    messages = _packed_burst(lease)
    assert [m.WhichOneof("message") for m in messages] == [
        "init", "commands", "heartbeat", "commands"]
    replies = list(station.decisions.Teleoperate(iter(messages), timeout=30))
    acks = [a for r in replies[1:] for a in r.acks.acks]
    assert [a.sequence for a in acks] == [*range(1, 11), 0, *range(11, 21)]
    assert {a.outcome for a in acks[:10] + acks[11:]} == {pb.COMMAND_OUTCOME_APPLIED}
    moves = [c.detail[1] for c in slave.commands if c.kind == "cartesian"]
    np.testing.assert_allclose(np.sum(moves, axis=0), [0.0, 0.0, 0.01], atol=1e-9)


def test_each_command_of_a_commands_message_reports_its_ack_receipt(fake_station):
    servicer = fake_station[0].servicer
    message = pb.TeleoperateRequest(commands=pb.MasterCommands(commands=[
        pb.MasterCommand(sequence=5, ack_receipt=pb.AckReceipt(sequence=3)),
        pb.MasterCommand(sequence=6, ack_receipt=pb.AckReceipt(sequence=4))]))
    session, receipts = _Session(), []
    session.clock_offset.receipt = lambda sequence, _receive_ns: receipts.append(sequence)
    replies = list(servicer._answers(session, 1, [servicer._received(message)], grouped=True))
    assert [[a.sequence for a in r.acks.acks] for r in replies] == [[5, 6]]
    assert receipts == [3, 4]


@pytest.mark.parametrize("count", [0, MAX_COMMANDS_PER_MESSAGE + 1])
def test_a_commands_message_with_no_command_or_too_many_is_refused(fake_station, count):
    station, slave = fake_station
    lease, _ = station.acquire()
    messages = [*_burst(lease)[:1], pb.TeleoperateRequest(commands=pb.MasterCommands(
        commands=[pb.MasterCommand(sequence=i + 1) for i in range(count)]))]
    with pytest.raises(grpc.RpcError) as refused:
        list(station.decisions.Teleoperate(iter(messages), timeout=30))
    assert refused.value.code() == grpc.StatusCode.INVALID_ARGUMENT
    assert f"1 to {MAX_COMMANDS_PER_MESSAGE} commands, not {count}" in refused.value.details()
    assert not [c for c in slave.commands if c.kind == "cartesian"]


class _Session:
    """A OperatorSession's two calls _serve_batch makes: each run of commands gets APPLIED,
    until `fail_on_run`, which raises as a lost lease would."""

    passivity = None

    def __init__(self, fail_on_run: int | None = None):
        self.runs = 0
        self.fail_on_run = fail_on_run
        self.clock_offset = ClockOffsetEstimator()

    def decide(self, increments, stream):
        self.runs += 1
        if self.runs == self.fail_on_run:
            raise FailedPreconditionError("control was lost", reason="NO_CONTROL")
        return [(i, CommandResult("APPLIED", "", 1, 2)) for i in increments]

    def heartbeat(self, stream, master_energy_in_j=None):
        return CommandResult("HEARTBEAT", "", 1, 1)


def _batch(servicer, *kinds):
    requests = [pb.TeleoperateRequest(command=pb.MasterCommand(sequence=i + 1))
                if kind == "command" else pb.TeleoperateRequest(heartbeat=pb.Heartbeat())
                for i, kind in enumerate(kinds)]
    return [servicer._received(request) for request in requests]


def test_a_batch_taken_together_is_one_acks_message_and_what_ran_before_an_error_is_answered(
        fake_station):
    servicer = fake_station[0].servicer
    batch = _batch(servicer, "command", "command", "heartbeat", "command")
    grouped = list(servicer._answers(_Session(), 1, batch, grouped=True))
    assert [[a.sequence for a in r.acks.acks] for r in grouped] == [[1, 2, 0, 4]]
    single = list(servicer._answers(_Session(), 1, batch, grouped=False))
    assert [r.ack.sequence for r in single] == [1, 2, 0, 4]
    answered = []
    with pytest.raises(FailedPreconditionError):  # the second run of commands fails
        for reply in servicer._answers(_Session(fail_on_run=2), 1, batch, grouped=True):
            answered.append([a.sequence for a in reply.acks.acks])
    assert answered == [[1, 2, 0]]  # done before the error: still answered


def test_the_first_message_must_be_init_and_the_lock_is_needed(fake_station):
    station, _ = fake_station
    bad = station.decisions.Teleoperate(iter([pb.TeleoperateRequest(
        heartbeat=pb.Heartbeat())]), timeout=5)
    with pytest.raises(grpc.RpcError) as error:
        next(bad)
    assert error.value.code() is grpc.StatusCode.INVALID_ARGUMENT
    no_lock = station.decisions.Teleoperate(iter([pb.TeleoperateRequest(
        init=pb.TeleoperateInit(operator_id="mallory"))]), timeout=5)
    with pytest.raises(grpc.RpcError) as error:
        next(no_lock)
    assert error.value.code() is grpc.StatusCode.FAILED_PRECONDITION


def test_lost_control_ends_the_stream_with_aborted(fake_station):
    station, _ = fake_station
    lease, _ = station.acquire()
    operator = Operator(station, lease)
    operator.move((0, 0, 0.002))
    station.decisions.ReleaseControl(pb.ReleaseControlRequest(lease_id=lease))
    with pytest.raises(grpc.RpcError) as error:
        operator.move((0, 0, 0.002))
    assert error.value.code() is grpc.StatusCode.ABORTED


def test_a_stop_through_another_door_shows_in_the_acks_within_one_sample(fake_station):
    station, slave = fake_station
    lease, _ = station.acquire()
    operator = Operator(station, lease)
    assert operator.move((0, 0, 0.002)).outcome == pb.COMMAND_OUTCOME_APPLIED
    slave.latch_at_hardware("stopped through the band")
    slave.step(0.001)
    ack = operator.move((0, 0, 0.002))
    assert ack.outcome == pb.COMMAND_OUTCOME_REJECTED and "ESTOPPED" in ack.detail
    assert ack.status == types_pb2.ROBOT_STATUS_ESTOPPED
    operator.close()


def test_stop_reset_and_tool_frame_go_through_the_core_alone(fake_station):
    """Defect: the servicer made extra GetStatus calls after stop and reset, and synced the
    sensor's tool frame itself."""
    station, slave = fake_station
    _, metadata = station.acquire()
    stopped = station.robot.EmergencyStop(proxy_robot_pb2.EmergencyStopRequest(reason="t"))
    assert stopped.status == types_pb2.ROBOT_STATUS_ESTOPPED
    with pytest.raises(grpc.RpcError) as error:  # anyone may stop; only the holder resets
        station.robot.Reset(proxy_robot_pb2.ResetRequest())
    assert error.value.code() is grpc.StatusCode.FAILED_PRECONDITION
    reset = station.robot.Reset(proxy_robot_pb2.ResetRequest(), metadata=metadata)
    assert reset.status == types_pb2.ROBOT_STATUS_READY
    frame = types_pb2.Pose(position_m=types_pb2.Vector3(z=0.15))
    reply = station.robot.SetToolFrame(proxy_robot_pb2.SetToolFrameRequest(
        flange_to_tool=frame), metadata=metadata)
    assert reply.flange_to_tool.position_m.z == pytest.approx(0.15)
    assert slave.sensor_flange_to_tool.translation[2] == pytest.approx(0.15)
    assert [c.kind for c in slave.commands] == ["estop", "reset", "tool_frame"]


def test_run_action_moves_go_through_the_core(fake_station):
    """Defect: RunAction's moves skipped recording and the latch check."""
    station, slave = fake_station
    _, metadata = station.acquire()
    station.decisions.StartRecording(pb.StartRecordingRequest(name="actions"),
                                     metadata=metadata)
    reply = station.decisions.RunAction(pb.RunActionRequest(
        action_id="a", move_joints=proxy_robot_pb2.MoveJointsIncrementalRequest(
            delta_joint_positions_rad=[0.05, 0, 0, 0, 0, 0])), metadata=metadata)
    assert reply.lane == options_pb2.LANE_MEDIUM  # RunAction's declared lane
    station.decisions.RunAction(pb.RunActionRequest(
        move_cartesian=proxy_robot_pb2.MoveCartesianIncrementalRequest(
            delta_position_m=types_pb2.Vector3(z=0.01), frame=types_pb2.REFERENCE_FRAME_BASE)),
        metadata=metadata)
    assert station.decisions.StopRecording(pb.StopRecordingRequest(),
                                           metadata=metadata).recording.command_count == 2
    station.robot.EmergencyStop(proxy_robot_pb2.EmergencyStopRequest(reason="t"))
    target = slave.q_target.copy()
    with pytest.raises(grpc.RpcError) as error:
        station.decisions.RunAction(pb.RunActionRequest(
            move_joints=proxy_robot_pb2.MoveJointsIncrementalRequest(
                delta_joint_positions_rad=[0.05, 0, 0, 0, 0, 0])), metadata=metadata)
    assert error.value.code() is grpc.StatusCode.FAILED_PRECONDITION
    np.testing.assert_array_equal(slave.q_target, target)
    with pytest.raises(grpc.RpcError) as error:  # six joints, finite
        station.decisions.RunAction(pb.RunActionRequest(
            move_joints=proxy_robot_pb2.MoveJointsIncrementalRequest(
                delta_joint_positions_rad=[float("nan")] * 6)), metadata=metadata)
    assert error.value.code() is grpc.StatusCode.INVALID_ARGUMENT
    with pytest.raises(grpc.RpcError) as error:  # one value per joint of the station's arm
        station.decisions.RunAction(pb.RunActionRequest(
            move_joints=proxy_robot_pb2.MoveJointsIncrementalRequest(
                delta_joint_positions_rad=[0.01] * 7)), metadata=metadata)
    assert error.value.code() is grpc.StatusCode.INVALID_ARGUMENT
    assert "delta_joint_positions_rad needs 6 values, got 7" in error.value.details()


def test_events_report_locks_assistance_and_holds_in_order(fake_station):
    station, _ = fake_station
    stream = station.decisions.StreamEvents(pb.StreamEventsRequest(), timeout=10)
    wait_for(lambda: station.core.events.subscriber_count >= 1,
             what="the event stream to subscribe")
    lease, metadata = station.acquire("eve")
    station.decisions.SetAssistance(pb.SetAssistanceRequest(assistance=pb.AssistanceConfig(
        scaling=pb.Scaling(translation_scale=0.5))), metadata=metadata)
    station.decisions.ReleaseControl(pb.ReleaseControlRequest(lease_id=lease))
    received = [next(stream) for _ in range(3)]
    stream.cancel()
    assert [m.WhichOneof("event") for m in received] == [
        "control_changed", "assistance_changed", "control_changed"]
    assert received[0].control_changed.state.holders[0].operator_id == "eve"
    assert received[1].assistance_changed.assistance.scaling.translation_scale == 0.5
    assert [m.sequence for m in received] == [1, 2, 3]


def test_busy_work_is_bounded(fake_station):
    """Found by the fuzz test: a busy_work of 2⁶³ s held a lane thread and a core for ever."""
    station, _ = fake_station
    for seconds in (11, -1):
        with pytest.raises(grpc.RpcError) as error:
            station.decisions.RunAction(pb.RunActionRequest(busy_work=pb.BusyWorkAction(
                duration=convert.duration(seconds))), timeout=5)
        assert error.value.code() is grpc.StatusCode.INVALID_ARGUMENT
        assert "busy_work.duration" in error.value.details()


def _command(sequence: int) -> pb.TeleoperateRequest:
    return pb.TeleoperateRequest(command=pb.MasterCommand(
        sequence=sequence, delta_position_m=types_pb2.Vector3(z=0.0005)))


def test_a_stream_without_end_is_resumed_with_its_sequence_and_first_acks(fake_station):
    """Half-closed without an `end` (as a cut link may look to the server), the session waits;
    an Init with its id resumes it, and resent commands get their first acks, unapplied."""
    station, slave = fake_station
    lease, _ = station.acquire()
    init = pb.TeleoperateInit(operator_id="tester", lease_id=lease,
                              watchdog_timeout=convert.duration(1.0))
    first = list(station.decisions.Teleoperate(iter([
        pb.TeleoperateRequest(init=init), _command(1), _command(2)]), timeout=30))
    session_id = first[0].ready.session_id
    assert station.core._sessions[session_id].detached
    resume = pb.TeleoperateInit(lease_id=lease, resume_session_id=session_id)
    second = list(station.decisions.Teleoperate(iter([
        pb.TeleoperateRequest(init=resume), _command(2), _command(3),
        pb.TeleoperateRequest(end=pb.TeleoperateEnd())]), timeout=30))
    ready = second[0].ready
    assert ready.resumed and ready.session_id == session_id and ready.last_sequence == 2
    assert ready.resume_window.ToSeconds() == 10
    resent, original = second[1].ack, first[2].ack  # the first ack again: same times, outcome
    assert (resent.receive_time, resent.apply_time, resent.outcome) == (
        original.receive_time, original.apply_time, original.outcome)
    assert [r.ack.sequence for r in second[1:]] == [2, 3]
    moves = [c.detail[1] for c in slave.commands if c.kind == "cartesian"]
    np.testing.assert_allclose(np.sum(moves, axis=0), [0.0, 0.0, 0.0015], atol=1e-9)
    assert session_id not in station.core._sessions  # `end`: gone for good


@pytest.mark.parametrize("which, code", [
    ("nosuchsession", grpc.StatusCode.NOT_FOUND),
    ("another lease", grpc.StatusCode.PERMISSION_DENIED)])
def test_a_resume_of_a_session_not_ours_is_refused(fake_station, which, code):
    station, _ = fake_station
    lease, _ = station.acquire()
    opened = list(station.decisions.Teleoperate(iter([pb.TeleoperateRequest(
        init=pb.TeleoperateInit(operator_id="tester", lease_id=lease))]), timeout=30))
    session_id = opened[0].ready.session_id
    resume = pb.TeleoperateInit(
        lease_id=lease if which == "nosuchsession" else "not-" + lease,
        resume_session_id="nosuchsession" if which == "nosuchsession" else session_id)
    with pytest.raises(grpc.RpcError) as error:
        next(station.decisions.Teleoperate(iter([pb.TeleoperateRequest(init=resume)]),
                                           timeout=5))
    assert error.value.code() is code


def _refusal(call, *args, **kwargs):
    """The typed error (code and ErrorInfo reason) a call that must fail fails with."""
    with pytest.raises(grpc.RpcError) as error:
        call(*args, **kwargs)
    return from_rpc_error(error.value)


def test_busy_work_needs_the_lease_before_it_waits_at_a_barrier(fake_station):
    """Issue #31: RunAction busy_work needed no lease, so any operator could hold lane
    threads and the processor while the holder's RenewControl starved."""
    station, _ = fake_station
    work = pb.RunActionRequest(busy_work=pb.BusyWorkAction(duration=convert.duration(0.001)))
    _, metadata = station.acquire()
    cobegin = station.decisions.BeginCobegin(pb.BeginCobeginRequest(
        action_count=2, barrier_timeout=convert.duration(30))).cobegin_id
    for lease in (None, "not-a-lease"):
        refused = _refusal(station.decisions.RunAction, work, timeout=5, metadata=[
            ("telerobot-lease-id", lease)] if lease else None)
        assert refused.code is grpc.StatusCode.FAILED_PRECONDITION
        assert refused.reason == "NO_CONTROL" and "'alice' (EXCLUSIVE)" in refused.message
        at_barrier = pb.RunActionRequest(cobegin_id=cobegin, busy_work=work.busy_work)
        refused = _refusal(station.decisions.RunAction, at_barrier, timeout=5)
        assert refused.reason == "NO_CONTROL"
        assert station.core.barriers.arrived(cobegin) == 0  # it never reached the barrier
    reply = station.decisions.RunAction(work, metadata=metadata, timeout=5)
    assert reply.end_time.ToNanoseconds() >= reply.start_time.ToNanoseconds()


def test_stop_recording_needs_the_lease_and_the_next_holder_may_stop_it(fake_station):
    """Issue #31: StopRecording needed no lease, so anyone could cut another's recording."""
    station, _ = fake_station
    lease, alice = station.acquire("alice")
    station.decisions.StartRecording(pb.StartRecordingRequest(name="kept"), metadata=alice)
    refused = _refusal(station.decisions.StopRecording, pb.StopRecordingRequest(), timeout=5)
    assert refused.code is grpc.StatusCode.FAILED_PRECONDITION
    assert refused.reason == "NO_CONTROL"
    assert station.core.recordings.recording  # still recording
    station.decisions.ReleaseControl(pb.ReleaseControlRequest(lease_id=lease))
    _, bob = station.acquire("bob")  # alice left it running: whoever holds control may stop it
    assert station.decisions.StopRecording(pb.StopRecordingRequest(), metadata=bob,
                                           timeout=5).recording.name == "kept"


def test_the_group_secret_is_in_the_members_answers_only(fake_station):
    """Issue #31: anyone could join a collaborative lease by naming its group. Joining takes
    the secret its members got, which neither the control state nor the events show."""
    station, _ = fake_station
    events = station.decisions.StreamEvents(pb.StreamEventsRequest(), timeout=10)
    wait_for(lambda: station.core.events.subscriber_count >= 1,
             what="the event stream to subscribe")
    collaborative = {"mode": pb.CONTROL_MODE_COLLABORATIVE, "group": "surgery"}
    ann = station.decisions.AcquireControl(pb.AcquireControlRequest(
        operator_id="ann", **collaborative), timeout=5)
    secret = ann.group_secret
    assert len(secret) >= 32
    for presented in ("", "guess"):
        refused = _refusal(station.decisions.AcquireControl, pb.AcquireControlRequest(
            operator_id="mallory", group_secret=presented, **collaborative), timeout=5)
        assert refused.code is grpc.StatusCode.PERMISSION_DENIED
        assert refused.reason == "BAD_GROUP_SECRET" and secret not in refused.message
    bob = station.decisions.AcquireControl(pb.AcquireControlRequest(
        operator_id="bob", group_secret=secret, **collaborative), timeout=5)
    assert bob.group_secret == secret
    assert [h.operator_id for h in bob.state.holders] == ["ann", "bob"]
    seen = [next(events) for _ in range(2)]  # ann's and bob's control changes
    events.cancel()
    assert [event.WhichOneof("event") for event in seen] == ["control_changed"] * 2
    shown = [bob.state, station.decisions.GetControlState(pb.GetControlStateRequest()).state,
             *(event.control_changed for event in seen)]
    assert all(secret.encode() not in message.SerializeToString() for message in shown)
    station.decisions.ReleaseControl(pb.ReleaseControlRequest(lease_id=ann.lease_id))
    station.decisions.ReleaseControl(pb.ReleaseControlRequest(lease_id=bob.lease_id))
    exclusive = station.decisions.AcquireControl(pb.AcquireControlRequest(
        operator_id="cat", mode=pb.CONTROL_MODE_EXCLUSIVE), timeout=5)
    assert exclusive.group_secret == ""


class _ArmStub:
    """ProxyRobot's Initialize, forwarded by the facade, on the fake slave's arm."""

    def __init__(self, slave):
        self.slave = slave

    def Initialize(self, request, metadata=(), timeout=None):
        self.slave.status = "READY"
        return proxy_robot_pb2.InitializeResponse(status=types_pb2.ROBOT_STATUS_READY)


class _Context:
    def __init__(self, lease_id: str):
        self.lease_id = lease_id

    def invocation_metadata(self):
        return ((LEASE_METADATA_KEY, self.lease_id),)

    def time_remaining(self):
        return 5.0


def test_teleoperate_right_after_initialize_sees_its_ready_not_an_older_sample(rig):
    """Defect (CI, under a flood): Teleoperate right after Initialize answered READY was refused
    'the arm is NOT_CONNECTED': the state stream still held a sample from before."""
    rig.slave.status = "NOT_CONNECTED"
    rig.slave.lagging_state = rig.slave.state()
    rig.clock.advance(0.001)
    with pytest.raises(FailedPreconditionError, match="NOT_CONNECTED"):
        rig.core.open_session("alice", rig.lease.lease_id, None, 1.0)
    (_, _, robot), *_ = make_facades(rig.core, _ArmStub(rig.slave), None, None)
    robot.Initialize(proxy_robot_pb2.InitializeRequest(), _Context(rig.lease.lease_id))
    session = rig.core.open_session("alice", rig.lease.lease_id, None, 1.0)
    session.close("done")


def test_the_benchs_grpc_client_gets_every_command_acked_in_order(fake_station):
    """bench/teleop.py's client (grpc.aio, a backlog packed into `commands` messages) against
    the DecisionServer: every command sent is acked once, in order."""
    from bench import teleop

    station, _ = fake_station
    client = teleop.GrpcTeleop(station.address)
    try:
        stream = client.open()
        for sequence in range(1, 201):  # faster than the stream takes them: some wait together
            stream.send(teleop._command(sequence, 1.0)[0])
        stream.end()
        replies = list(stream.responses())
    finally:
        client.close()
    assert replies[0].HasField("ready")
    acks = [a for r in replies[1:] for a in r.acks.acks]
    assert [a.sequence for a in acks] == list(range(1, 201))
    assert {a.outcome for a in acks} == {pb.COMMAND_OUTCOME_APPLIED}
