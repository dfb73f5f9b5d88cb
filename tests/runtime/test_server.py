"""The service runtime over a real in-process gRPC server on port 0: lanes chosen from the
proto options and client metadata, status codes for domain errors and malformed messages,
health and reflection. The servicers here are test fixtures; the runtime under test is real."""

from __future__ import annotations

import threading
from concurrent import futures

import grpc
import pytest
from google.rpc import error_details_pb2
from grpc_health.v1 import health_pb2, health_pb2_grpc
from grpc_reflection.v1alpha import reflection_pb2, reflection_pb2_grpc
from grpc_status import rpc_status

from services.runtime.lanes import Lane, LaneConfig, current_lane
from services.runtime.rpc import declared_lane
from services.runtime.server import binding, create_server
from telerobot.v1 import (
    decision_server_pb2,
    decision_server_pb2_grpc,
    proxy_robot_pb2,
    proxy_robot_pb2_grpc,
)
from tests.conftest import wait_for
from wire.errors import InvalidArgumentError, OutOfRangeError

LANES = {
    Lane.EMERGENCY: LaneConfig(static_threads=1, max_threads=1, queue_capacity=2),
    Lane.HIGH: LaneConfig(static_threads=1, max_threads=2, queue_capacity=4),
    Lane.MEDIUM: LaneConfig(static_threads=1, max_threads=1, queue_capacity=4),
    Lane.LOW: LaneConfig(static_threads=1, max_threads=2, queue_capacity=4),
}
LOW_CAPACITY = 2 + 4  # threads + queue


def where() -> str:
    """The lane a call runs as and the thread it runs on (a lane's thread, or gRPC's own when
    the lane had room: run_here)."""
    return f"{current_lane().name.lower()} on {threading.current_thread().name}"


class Robot(proxy_robot_pb2_grpc.ProxyRobotServicer):
    """Answers with where the call ran."""

    def GetStatus(self, request, context):
        return proxy_robot_pb2.GetStatusResponse(reason=where())

    def EmergencyStop(self, request, context):
        return proxy_robot_pb2.EmergencyStopResponse()

    def MoveJointsIncremental(self, request, context):
        if len(request.delta_joint_positions_rad) != 6:
            raise InvalidArgumentError("send six joint increments", reason="BAD_LENGTH")
        raise OutOfRangeError("joint 2 would pass its limit of 225 deg", reason="JOINT_LIMIT")

    def StreamRobotEvents(self, request, context):
        ended = threading.Event()
        context.add_callback(ended.set)
        while not ended.is_set():
            yield proxy_robot_pb2.StreamRobotEventsResponse(sequence=1)
            ended.wait(0.01)  # an event every 10 ms until the call ends


class Decisions(decision_server_pb2_grpc.DecisionServerServicer):
    """ListRecordings (a low-lane RPC) blocks until released: the long low-priority call."""

    def __init__(self):
        self.release = threading.Event()
        self.entered = threading.Semaphore(0)

    def ListRecordings(self, request, context):
        self.entered.release()
        self.release.wait(10)
        return decision_server_pb2.ListRecordingsResponse(
            recordings=[decision_server_pb2.Recording(name=where())])


@pytest.fixture(params=[False, True], ids=["sync", "aio"])
def station(request):
    decisions = Decisions()
    server, port = create_server(
        "127.0.0.1:0",
        [binding(proxy_robot_pb2_grpc, "ProxyRobot", Robot()),
         binding(decision_server_pb2_grpc, "DecisionServer", decisions)],
        lanes=LANES, max_streams=2, aio=request.param,
    )
    server.start()
    channel = grpc.insecure_channel(f"127.0.0.1:{port}")
    yield server, channel, decisions
    decisions.release.set()
    channel.close()
    server.stop(0)


def robot(channel):
    return proxy_robot_pb2_grpc.ProxyRobotStub(channel)


def test_declared_lanes_come_from_the_protos():
    assert declared_lane("/telerobot.v1.ProxyRobot/EmergencyStop") is Lane.EMERGENCY
    assert declared_lane("/telerobot.v1.ProxyRobot/GetState") is Lane.HIGH
    assert declared_lane("/telerobot.v1.ProxyRobot/Connect") is Lane.MEDIUM
    assert declared_lane("/telerobot.v1.DecisionServer/ListRecordings") is Lane.LOW
    assert declared_lane("/grpc.health.v1.Health/Check") is Lane.HIGH


def test_calls_run_on_their_declared_lane(station):
    _, channel, _ = station
    reply = robot(channel).GetStatus(proxy_robot_pb2.GetStatusRequest(), timeout=5)
    assert reply.reason.startswith("high on ")


def test_client_may_lower_its_lane_and_is_clamped_when_raising(station):
    _, channel, _ = station
    lowered = robot(channel).GetStatus(
        proxy_robot_pb2.GetStatusRequest(), metadata=[("telerobot-lane", "low")], timeout=5)
    assert lowered.reason.startswith("low on ")
    raised = robot(channel).GetStatus(
        proxy_robot_pb2.GetStatusRequest(), metadata=[("telerobot-lane", "emergency")], timeout=5)
    assert raised.reason.startswith("high on ")  # the server's client_lane_limit is HIGH


def test_bad_lane_metadata_is_invalid_argument(station):
    _, channel, _ = station
    with pytest.raises(grpc.RpcError) as error:
        robot(channel).GetStatus(proxy_robot_pb2.GetStatusRequest(),
                                 metadata=[("telerobot-lane", "urgent")], timeout=5)
    assert error.value.code() is grpc.StatusCode.INVALID_ARGUMENT
    assert "use one of emergency, high, medium, low" in error.value.details()


def test_domain_errors_become_status_codes_with_error_info(station):
    _, channel, _ = station
    with pytest.raises(grpc.RpcError) as error:
        robot(channel).MoveJointsIncremental(
            proxy_robot_pb2.MoveJointsIncrementalRequest(delta_joint_positions_rad=[0.1] * 6),
            timeout=5)
    assert error.value.code() is grpc.StatusCode.OUT_OF_RANGE
    assert "limit of 225 deg" in error.value.details()
    status = rpc_status.from_call(error.value)
    info = error_details_pb2.ErrorInfo()
    assert status.details[0].Unpack(info)
    assert (info.reason, info.domain) == ("JOINT_LIMIT", "telerobot.v1")


def test_malformed_message_is_invalid_argument_and_server_stays_up(station):
    _, channel, _ = station
    raw = channel.unary_unary("/telerobot.v1.ProxyRobot/MoveJointsIncremental")
    with pytest.raises(grpc.RpcError) as error:
        raw(b"\x0a\xff\xff\xff", timeout=5)  # a length-delimited field that runs off the end
    assert error.value.code() is grpc.StatusCode.INVALID_ARGUMENT
    assert robot(channel).GetStatus(proxy_robot_pb2.GetStatusRequest(), timeout=5)


def test_unknown_method_is_unimplemented_and_server_stays_up(station):
    _, channel, _ = station
    raw = channel.unary_unary("/telerobot.v1.ProxyRobot/Teleport")
    with pytest.raises(grpc.RpcError) as error:
        raw(b"", timeout=5)
    assert error.value.code() is grpc.StatusCode.UNIMPLEMENTED
    assert robot(channel).GetStatus(proxy_robot_pb2.GetStatusRequest(), timeout=5)


def test_parma_high_and_emergency_calls_are_served_with_low_lane_saturated(station):
    server, channel, decisions = station
    stub = decision_server_pb2_grpc.DecisionServerStub(channel)
    pool = futures.ThreadPoolExecutor(LOW_CAPACITY)
    low_calls = [pool.submit(stub.ListRecordings, decision_server_pb2.ListRecordingsRequest(),
                             timeout=20) for _ in range(LOW_CAPACITY)]
    for _ in range(2):  # the low lane's two threads are inside long calls
        assert decisions.entered.acquire(timeout=5)
    wait_for(lambda: server.executor.counters()[Lane.LOW].queued >= 4,
             what="the low lane's queue to fill")
    assert server.executor.counters()[Lane.LOW].queued == 4  # and its queue is full

    with pytest.raises(grpc.RpcError) as error:
        stub.ListRecordings(decision_server_pb2.ListRecordingsRequest(), timeout=5)
    assert error.value.code() is grpc.StatusCode.RESOURCE_EXHAUSTED
    assert "low lane is saturated" in error.value.details()

    reply = robot(channel).GetStatus(proxy_robot_pb2.GetStatusRequest(), timeout=2)
    assert reply.reason.startswith("high on ")
    robot(channel).EmergencyStop(proxy_robot_pb2.EmergencyStopRequest(), timeout=2)
    assert not any(call.done() for call in low_calls)  # served ahead of every low call

    decisions.release.set()
    names = [call.result(10).recordings[0].name for call in low_calls]
    assert all(name.startswith("low on ") for name in names)
    # Low work never ran on a higher lane's thread (on its own, or on gRPC's: run_here).
    assert not any(f"-{lane}-" in name for name in names for lane in ("emergency", "high",
                                                                           "medium"))
    counters = server.executor.counters()
    assert counters[Lane.LOW].rejected == 1 and counters[Lane.LOW].served == LOW_CAPACITY
    pool.shutdown()


def open_event_streams(channel, count: int) -> list:
    """`count` StreamRobotEvents calls, each past its first message (so each holds a slot)."""
    streams = [robot(channel).StreamRobotEvents(proxy_robot_pb2.StreamRobotEventsRequest(),
                                                timeout=10) for _ in range(count)]
    for stream in streams:
        next(stream)
    return streams


def test_stream_cap_gives_resource_exhausted(station):
    _, channel, _ = station
    streams = open_event_streams(channel, 2)
    with pytest.raises(grpc.RpcError) as error:
        next(robot(channel).StreamRobotEvents(proxy_robot_pb2.StreamRobotEventsRequest(),
                                              timeout=5))
    assert error.value.code() is grpc.StatusCode.RESOURCE_EXHAUSTED
    for stream in streams:
        stream.cancel()


def test_a_stream_the_client_leaves_gives_its_slot_back(station):
    server, channel, _ = station
    streams = open_event_streams(channel, 2)
    assert server.interceptor.open_streams == 2
    streams[0].cancel()
    # The servicer's loop ends (add_callback fired) and its generator is closed.
    wait_for(lambda: server.interceptor.open_streams == 1, what="the slot given back")
    again = robot(channel).StreamRobotEvents(proxy_robot_pb2.StreamRobotEventsRequest(),
                                             timeout=10)
    assert next(again).sequence == 1
    again.cancel()
    streams[1].cancel()
    wait_for(lambda: server.interceptor.open_streams == 0, what="every slot given back")


def test_health_is_not_serving_until_ready_and_during_drain(station):
    server, channel, _ = station
    health = health_pb2_grpc.HealthStub(channel)

    def status(service: str = ""):
        return health.Check(health_pb2.HealthCheckRequest(service=service), timeout=5).status

    not_serving = health_pb2.HealthCheckResponse.NOT_SERVING
    serving = health_pb2.HealthCheckResponse.SERVING
    assert status() == not_serving
    server.set_serving()
    assert status() == serving and status("telerobot.v1.ProxyRobot") == serving
    server.health.enter_graceful_shutdown()
    assert status() == not_serving


def test_reflection_lists_the_services(station):
    _, channel, _ = station
    stub = reflection_pb2_grpc.ServerReflectionStub(channel)
    request = reflection_pb2.ServerReflectionRequest(list_services="")
    reply = next(stub.ServerReflectionInfo(iter([request]), timeout=5))
    names = {service.name for service in reply.list_services_response.service}
    assert {"telerobot.v1.ProxyRobot", "telerobot.v1.DecisionServer",
            "grpc.health.v1.Health"} <= names
