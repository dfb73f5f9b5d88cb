"""A response stream that yields Wakeups (services/common/wakeup.py) instead of blocking, on
both kinds of server: the stream's own thread waits for them on grpcio's sync server; on
grpc.aio the event loop does, and pulls the stream's next messages itself."""

from __future__ import annotations

import contextlib
import os
import threading

import grpc
import pytest

from services.common.wakeup import Wakeup
from services.runtime.server import binding, create_server
from telerobot.v1 import proxy_robot_pb2, proxy_robot_pb2_grpc
from tests.conftest import wait_for

NEVER_S = 60.0  # a wait's timeout that no test waits out


class WokenRobot(proxy_robot_pb2_grpc.ProxyRobotServicer):
    """StreamRobotEvents sends one event, then one more each time its eventfd is written (or
    its wait times out), noting the thread that pulled each."""

    def __init__(self):
        self.fd = os.eventfd(0, os.EFD_CLOEXEC | os.EFD_NONBLOCK)
        self.timeout_s = NEVER_S
        self.pulled_on: list[str] = []
        self.ended = threading.Event()

    def StreamRobotEvents(self, request, context):
        try:
            for sequence in range(1, 5):
                self.pulled_on.append(threading.current_thread().name)
                yield proxy_robot_pb2.StreamRobotEventsResponse(sequence=sequence)
                yield Wakeup(self.fd, self.timeout_s)
        finally:
            self.ended.set()


@contextlib.contextmanager
def serving(aio: bool):
    """(robot, channel, aio): a WokenRobot served on either kind of server."""
    robot = WokenRobot()
    server, port = create_server("127.0.0.1:0",
                                 [binding(proxy_robot_pb2_grpc, "ProxyRobot", robot)], aio=aio)
    server.start()
    channel = grpc.insecure_channel(f"127.0.0.1:{port}")
    try:
        yield robot, channel, aio
    finally:
        channel.close()
        _end(robot, server)


@pytest.fixture(params=[False, True], ids=["sync", "aio"])
def served(request):
    with serving(request.param) as served:
        yield served


def _end(robot: WokenRobot, server) -> None:
    # A stream left waiting on the sync server holds its thread until it wakes.
    wait_for(lambda: not robot.pulled_on or robot.ended.is_set()
             or os.eventfd_write(robot.fd, 1), timeout_s=10)
    server.stop(0)
    os.close(robot.fd)


def events(channel: grpc.Channel):
    return proxy_robot_pb2_grpc.ProxyRobotStub(channel).StreamRobotEvents(
        proxy_robot_pb2.StreamRobotEventsRequest(), timeout=10)


def test_each_message_after_a_wakeup_comes_once_the_fd_is_written(served):
    robot, channel, aio = served
    stream = events(channel)
    assert next(stream).sequence == 1
    for sequence in (2, 3, 4):
        # Nothing more until the fd is written: the stream waits, it does not end.
        assert len(robot.pulled_on) == sequence - 1
        os.eventfd_write(robot.fd, 1)
        assert next(stream).sequence == sequence
    os.eventfd_write(robot.fd, 1)
    assert list(stream) == []  # the handler returned: the stream ends OK
    first, *after_wakeups = robot.pulled_on
    if aio:  # pulled on the pool until the first Wakeup, then on the loop's thread
        assert first != "grpc-aio"
        assert set(after_wakeups) == {"grpc-aio"}
    else:  # one thread for the stream's whole life
        assert set(after_wakeups) == {first}


def test_a_wakeup_resumes_the_stream_unwritten_at_its_timeout(served):
    robot, channel, _aio = served
    robot.timeout_s = 0.01
    assert [event.sequence for event in events(channel)] == [1, 2, 3, 4]


def test_a_wakeup_written_before_the_wait_is_not_lost(served):
    robot, channel, _aio = served
    os.eventfd_write(robot.fd, 1)  # before the handler even yields its Wakeup
    stream = events(channel)
    assert next(stream).sequence == 1
    assert next(stream).sequence == 2


def test_a_client_that_leaves_a_waiting_stream_on_grpc_aio_ends_it_at_once():
    # (On the sync server the stream's thread sees the client gone only when its wait ends.)
    with serving(aio=True) as (robot, channel, _aio):
        stream = events(channel)
        assert next(stream).sequence == 1
        stream.cancel()
        assert robot.ended.wait(5)  # the handler's finally ran, long before the wait's timeout
        # The loop no longer watches the fd: written now, nothing wakes or breaks, and the
        # server serves on.
        os.eventfd_write(robot.fd, 1)
        assert next(events(channel)).sequence == 1
