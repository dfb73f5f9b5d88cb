"""The Teleoperate stream on the real simulated arm (e2e): assistance functions moving the
real arm, and a killed client's stream. The contract itself is tested in-process in
test_servicer.py, the watchdog's timing in test_core.py."""

from __future__ import annotations

import signal
import textwrap
import threading
import time

import grpc
import numpy as np
import pinocchio as pin
import pytest

from services.decision_server import servicer as servicer_module
from services.decision_server.sessions import WatchdogHold
from telerobot.v1 import decision_server_pb2 as pb
from telerobot.v1 import proxy_robot_pb2, types_pb2
from tests.conftest import wait_for
from tests.decision_server.conftest import Operator
from tests.processes import start_process
from wire import convert

BASE, TOOL = types_pb2.REFERENCE_FRAME_BASE, types_pb2.REFERENCE_FRAME_TOOL


pytestmark = pytest.mark.e2e


def settled_position(station) -> np.ndarray:
    """The tool position once the arm is READY and a state sample 0.1 s later agrees."""
    station.wait_status(types_pb2.ROBOT_STATUS_READY)
    first = station.robot.GetState(proxy_robot_pb2.GetStateRequest()).state
    wait_for(lambda: station.robot.GetState(proxy_robot_pb2.GetStateRequest()).state.sample_time
             .ToNanoseconds() > first.sample_time.ToNanoseconds() + 100_000_000, 5,
             "a state sample 0.1 s later")
    position = station.tool_position()
    p = first.tool_pose.position_m
    np.testing.assert_allclose(position, [p.x, p.y, p.z], atol=1e-4)  # it is at rest
    return position


@pytest.fixture
def driven(station):
    lease, metadata = station.acquire()
    station.ready_at_home(metadata)
    return station, lease, metadata


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
    # Let the arm arrive before ending the stream: an end while moving holds the arm where
    # braking in joint space takes it, which need not be in the plane.
    station.wait_status(types_pb2.ROBOT_STATUS_READY)
    operator.close()
    end = settled_position(station)
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
    moved = settled_position(station) - before.translation
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
    settled_position(station)
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
    assert settled_position(station)[2] - before[2] == pytest.approx(0.01, abs=2e-4)


def test_a_killed_client_gets_the_arm_held(driven):
    """A real operator process streams at 100 Hz and is killed mid-stream."""
    station, lease, _ = driven
    script = textwrap.dedent(f"""
        import time, grpc
        from wire import convert
        from telerobot.v1 import decision_server_pb2 as pb, decision_server_pb2_grpc
        stub = decision_server_pb2_grpc.DecisionServerStub(grpc.insecure_channel(
            "{station.address}"))
        def requests():
            yield pb.TeleoperateRequest(init=pb.TeleoperateInit(operator_id="doomed",
                lease_id="{lease}", watchdog_timeout=convert.duration(0.1)))
            for i in range(100000):
                yield pb.TeleoperateRequest(command=pb.MasterCommand(sequence=i + 1,
                    delta_position_m=convert.vector3_to_proto((0, 0.002, 0))))
                time.sleep(0.01)  # the operator's own 100 Hz pace, in its own process
        for reply in stub.Teleoperate(requests()):
            if reply.HasField("ack") and reply.ack.sequence == 5:
                print("TELEROBOT_READY operator 0:0", flush=True)
    """)
    holds = station.core.events.subscribe(64)
    client = start_process(["-c", script])
    client.wait_ready(["operator"], timeout_s=20)
    client.stop(signal.SIGKILL)
    killed = time.monotonic()
    event = None
    while time.monotonic() - killed < 2 and event is None:
        item = holds.get(0.1)
        if item is not None and isinstance(item.payload, WatchdogHold):
            event = item
    assert event is not None
    # The stream's end is noticed at once: the hold is the stream's, not the watchdog's
    # (which would say "watchdog timeout" after 100 ms of silence).
    assert "watchdog timeout" not in event.payload.reason, event.payload.reason
    assert event.payload.silence_s < 0.1
    settled_position(station)  # it stays




def test_a_stream_that_sends_no_init_is_ended_and_frees_its_slot(fake_station, monkeypatch):
    """A stream holds one of the capped stream slots from its first byte: without an init in
    time, the server cancels it."""
    station, _ = fake_station
    monkeypatch.setattr(servicer_module, "INIT_TIMEOUT_S", 0.2)
    silent = threading.Event()

    def nothing():
        silent.wait(30)  # sends nothing until the test ends
        yield from ()

    call = station.decisions.Teleoperate(nothing(), timeout=20)
    with pytest.raises(grpc.RpcError) as ended:
        next(call)
    silent.set()
    assert ended.value.code() == grpc.StatusCode.CANCELLED
