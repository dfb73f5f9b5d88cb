"""The Teleoperate stream on the real simulated arm: acks, assistance functions, watchdog."""

from __future__ import annotations

import queue
import signal
import textwrap
import threading
import time

import grpc
import numpy as np
import pinocchio as pin
import pytest

from services.common import convert
from services.decision_server.supervisor import WatchdogHold
from telerobot.v1 import decision_server_pb2 as pb
from telerobot.v1 import types_pb2
from tests.conftest import start_process

BASE, TOOL = types_pb2.REFERENCE_FRAME_BASE, types_pb2.REFERENCE_FRAME_TOOL


class Operator:
    """A Teleoperate stream driven from the test: send() one message, get its reply."""

    def __init__(self, station, lease_id: str, mapping=0, watchdog_s: float = 0.5):
        self._requests: queue.Queue = queue.Queue()
        self._sequence = 0
        init = pb.TeleoperateInit(operator_id="tester", lease_id=lease_id, mapping=mapping,
                                  watchdog_timeout=convert.duration(watchdog_s))
        self._requests.put(pb.TeleoperateRequest(init=init))
        self._replies = station.decisions.Teleoperate(iter(self._requests.get, None), timeout=60)
        self.ready = next(self._replies).ready

    def move(self, dx=(0, 0, 0), rotation=None, clutch=False) -> pb.CommandAck:
        self._sequence += 1
        command = pb.MasterCommand(sequence=self._sequence,
                                   send_time=convert.timestamp(time.time_ns()),
                                   delta_position_m=convert.vector3_to_proto(dx),
                                   clutch_engaged=clutch)
        if rotation is not None:
            command.delta_rotation.CopyFrom(convert.rotation_to_proto(rotation))
        self._requests.put(pb.TeleoperateRequest(command=command))
        return next(self._replies).ack

    def close(self):
        self._requests.put(None)
        for _ in self._replies:
            pass


@pytest.fixture
def driven(station):
    lease, metadata = station.acquire()
    station.ready_at_home(metadata)
    return station, lease, metadata


def test_acks_carry_sequence_pose_wrench_and_timing(driven):
    station, lease, _ = driven
    operator = Operator(station, lease)
    assert operator.ready.session_id and operator.ready.mapping == BASE
    ack = operator.move((0, 0, 0.005))
    assert ack.sequence == 1 and ack.outcome == pb.COMMAND_OUTCOME_APPLIED
    assert ack.receive_time.ToNanoseconds() <= ack.apply_time.ToNanoseconds()
    assert ack.status in (types_pb2.ROBOT_STATUS_MOVING, types_pb2.ROBOT_STATUS_READY)
    assert ack.tool_pose.rotation.row_major  # the slave's measured pose
    clutched = operator.move((0, 0, 0.005), clutch=True)
    assert clutched.outcome == pb.COMMAND_OUTCOME_INDEXED
    too_big = operator.move((0.2, 0, 0))
    assert too_big.outcome == pb.COMMAND_OUTCOME_REJECTED and "cap" in too_big.detail
    operator.close()


def test_first_message_must_be_init_and_the_lock_is_needed(station):
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


def test_planar_constraint_keeps_the_constrained_coordinate(driven):
    station, lease, metadata = driven
    station.decisions.SetAssistance(pb.SetAssistanceRequest(assistance=pb.AssistanceConfig(
        constraint=pb.MotionConstraint(type=pb.CONSTRAINT_TYPE_PLANAR,
                                       axis=types_pb2.Vector3(z=1), frame=BASE))),
        metadata=metadata)
    start = station.tool_position()
    operator = Operator(station, lease)
    rng = np.random.default_rng(7)
    for _ in range(40):
        ack = operator.move(rng.uniform(-0.004, 0.004, 3))
        assert ack.outcome == pb.COMMAND_OUTCOME_MODIFIED
        time.sleep(0.02)  # 50 Hz
    # Let the arm arrive before ending the stream: an end while moving holds the arm where
    # braking in joint space takes it, which need not be in the plane.
    station.wait_status(types_pb2.ROBOT_STATUS_READY)
    operator.close()
    time.sleep(0.3)
    end = station.tool_position()
    assert abs(end[2] - start[2]) < 1e-4
    assert np.linalg.norm(end[:2] - start[:2]) > 0.005  # it did move in the plane


def test_tool_mapping_moves_along_the_tool_axes(driven):
    station, lease, _ = driven
    before = station.tool_pose()
    operator = Operator(station, lease, mapping=TOOL)
    for _ in range(5):
        operator.move((0.004, 0, 0))
    station.wait_status(types_pb2.ROBOT_STATUS_READY)
    operator.close()
    time.sleep(0.2)
    moved = station.tool_position() - before.translation
    np.testing.assert_allclose(moved, 0.02 * before.rotation[:, 0], atol=3e-4)


def test_floating_tool_frame_rotates_about_the_chosen_point(driven):
    station, lease, metadata = driven
    point = np.array([0.0, 0.0, 0.1])  # 10 cm beyond the peg's tip, along the tool axis
    station.decisions.SetAssistance(pb.SetAssistanceRequest(assistance=pb.AssistanceConfig(
        mapping=TOOL, floating_tool_frame=pb.FloatingToolFrame(
            enabled=True, point_m=convert.vector3_to_proto(point)))), metadata=metadata)
    before = station.tool_pose()
    pivot = before.act(point)
    operator = Operator(station, lease)
    for _ in range(5):
        assert operator.move(rotation=pin.utils.rotate("x", 0.03)).outcome in (
            pb.COMMAND_OUTCOME_APPLIED, pb.COMMAND_OUTCOME_MODIFIED)
    station.wait_status(types_pb2.ROBOT_STATUS_READY)
    operator.close()
    time.sleep(0.2)
    after = station.tool_pose()
    np.testing.assert_allclose(after.act(point), pivot, atol=3e-4)  # the pivot stayed put
    assert np.linalg.norm(after.translation - before.translation) > 0.01  # the tip swung
    turned = pin.log3(before.rotation.T @ after.rotation)
    np.testing.assert_allclose(turned, [0.15, 0, 0], atol=2e-3)


def test_server_scaling_halves_increments(driven):
    station, lease, metadata = driven
    station.decisions.SetAssistance(pb.SetAssistanceRequest(assistance=pb.AssistanceConfig(
        scaling=pb.Scaling(translation_scale=0.5, rotation_scale=0.5))), metadata=metadata)
    before = station.tool_position()
    operator = Operator(station, lease)
    operator.move((0, 0, 0.02))
    station.wait_status(types_pb2.ROBOT_STATUS_READY)
    operator.close()
    time.sleep(0.2)
    assert station.tool_position()[2] - before[2] == pytest.approx(0.01, abs=2e-4)


def test_watchdog_holds_the_arm_when_commands_stop(driven):
    station, lease, _ = driven
    holds = station.core.events.subscribe(64)
    operator = Operator(station, lease, watchdog_s=0.05)
    operator.move((0.02, 0, 0))  # a move in progress when the operator goes silent
    sent = time.monotonic()
    event = None
    while time.monotonic() - sent < 2:
        item = holds.get(0.1)
        if item is not None and isinstance(item.payload, WatchdogHold):
            event = item
            break
    assert event is not None and "watchdog timeout" in event.payload.reason
    # Never before the timeout; the upper bound leaves room for a loaded machine's scheduling.
    assert 0.05 <= event.payload.silence_s < 0.05 + 0.1
    station.wait_status(types_pb2.ROBOT_STATUS_READY)
    operator.close()


def test_a_killed_client_gets_the_arm_held(driven):
    """A real operator process streams at 100 Hz and is killed mid-stream."""
    station, lease, _ = driven
    script = textwrap.dedent(f"""
        import time, grpc
        from services.common import convert
        from telerobot.v1 import decision_server_pb2 as pb, decision_server_pb2_grpc
        stub = decision_server_pb2_grpc.DecisionServerStub(grpc.insecure_channel(
            "{station.address}"))
        def requests():
            yield pb.TeleoperateRequest(init=pb.TeleoperateInit(operator_id="doomed",
                lease_id="{lease}", watchdog_timeout=convert.duration(0.1)))
            for i in range(100000):
                yield pb.TeleoperateRequest(command=pb.MasterCommand(sequence=i + 1,
                    delta_position_m=convert.vector3_to_proto((0, 0.002, 0))))
                time.sleep(0.01)
        for reply in stub.Teleoperate(requests()):
            if reply.HasField("ack") and reply.ack.sequence == 5:
                print("TELEROBOT_READY operator 0:0", flush=True)
    """)
    holds = station.core.events.subscribe(64)
    client = start_process(["-c", script])
    client.wait_ready(["operator"], timeout_s=20)
    time.sleep(0.1)
    client.stop(signal.SIGKILL)
    killed = time.monotonic()
    event = None
    while time.monotonic() - killed < 2 and event is None:
        item = holds.get(0.1)
        if item is not None and isinstance(item.payload, WatchdogHold):
            event = item
    assert event is not None
    # The stream's end is noticed at once, well inside the 100 ms watchdog.
    assert event.payload.silence_s < 0.1 + 0.001 + 0.05
    station.wait_status(types_pb2.ROBOT_STATUS_READY, timeout_s=3)
    position = station.tool_position()
    time.sleep(0.2)
    np.testing.assert_allclose(station.tool_position(), position, atol=1e-4)  # it stays


def test_lost_control_ends_the_stream_with_aborted(driven):
    station, lease, _ = driven
    operator = Operator(station, lease)
    operator.move((0, 0, 0.002))
    station.decisions.ReleaseControl(pb.ReleaseControlRequest(lease_id=lease))
    with pytest.raises(grpc.RpcError) as error:
        operator.move((0, 0, 0.002))
    assert error.value.code() is grpc.StatusCode.ABORTED
    threading.Thread(target=operator._requests.put, args=(None,)).start()  # noqa: SLF001
