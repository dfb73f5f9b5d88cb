"""An emergency-lane call latches its stop as it arrives, before any lane thread is free to run
its handler (services.runtime.rpc's on_emergency_call), over a real in-process server."""

from __future__ import annotations

import threading

import grpc
import pytest

from services.runtime.lanes import Lane, LaneConfig
from services.runtime.server import binding, create_server
from telerobot.v1 import proxy_robot_pb2, proxy_robot_pb2_grpc
from tests.conftest import wait_for

# One emergency thread, nothing to borrow: a stop whose handler blocks saturates the lane.
LANES = {
    Lane.EMERGENCY: LaneConfig(static_threads=1, max_threads=1, queue_capacity=4),
    Lane.HIGH: LaneConfig(static_threads=1, max_threads=1, queue_capacity=4),
    Lane.MEDIUM: LaneConfig(static_threads=1, max_threads=1, queue_capacity=4),
    Lane.LOW: LaneConfig(static_threads=1, max_threads=1, queue_capacity=4),
}


class Robot(proxy_robot_pb2_grpc.ProxyRobotServicer):
    """EmergencyStop handlers wait until the test lets them finish."""

    def __init__(self):
        self.release = threading.Event()
        self.handled: list[str] = []

    def EmergencyStop(self, request, context):
        self.release.wait(10)
        self.handled.append(request.reason)
        return proxy_robot_pb2.EmergencyStopResponse()

    def GetStatus(self, request, context):
        return proxy_robot_pb2.GetStatusResponse()


@pytest.fixture(params=[False, True], ids=["sync", "aio"])
def serve(request):
    started = []

    def start(hook):
        robot = Robot()
        server, port = create_server("127.0.0.1:0",
                                     [binding(proxy_robot_pb2_grpc, "ProxyRobot", robot)],
                                     lanes=LANES, on_emergency_call=hook, aio=request.param)
        server.start()
        channel = grpc.insecure_channel(f"127.0.0.1:{port}")
        started.append((server, channel, robot))
        return proxy_robot_pb2_grpc.ProxyRobotStub(channel), robot

    yield start
    for server, channel, robot in started:
        robot.release.set()
        channel.close()
        server.stop(0)


def test_each_stop_latches_on_arrival_even_while_the_emergency_lane_is_busy(serve):
    arrivals = []
    stub, robot = serve(lambda: arrivals.append(len(robot.handled)))
    first = stub.EmergencyStop.future(proxy_robot_pb2.EmergencyStopRequest(reason="one"),
                                      timeout=10)
    wait_for(lambda: len(arrivals) == 1, what="the first stop's early latch")
    second = stub.EmergencyStop.future(proxy_robot_pb2.EmergencyStopRequest(reason="two"),
                                       timeout=10)
    # The only emergency thread is held by the first handler; the second stop latched anyway.
    wait_for(lambda: len(arrivals) == 2, what="the second stop's early latch")
    assert arrivals == [0, 0] and robot.handled == []
    robot.release.set()
    first.result(), second.result()
    assert sorted(robot.handled) == ["one", "two"]  # the handlers still ran, with reasons


def test_a_failing_early_latch_leaves_the_stop_to_its_handler(serve):
    def broken():
        raise RuntimeError("the link is gone")

    stub, robot = serve(broken)
    robot.release.set()
    stub.EmergencyStop(proxy_robot_pb2.EmergencyStopRequest(reason="still stops"), timeout=10)
    assert robot.handled == ["still stops"]


def test_other_calls_do_not_latch(serve):
    arrivals = []
    stub, _ = serve(lambda: arrivals.append(1))
    stub.GetStatus(proxy_robot_pb2.GetStatusRequest(), timeout=10)
    assert arrivals == []
