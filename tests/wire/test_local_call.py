"""wire.local_call on a real Unix socket, server and client in this process: replies and errors
come back as gRPC's would; a server that restarted between calls is reconnected to; a call whose
reply was lost is never sent twice; a late reply never answers the next call."""

from __future__ import annotations

import os
import stat
import threading

import pytest

from telerobot.v1 import proxy_robot_pb2 as pb
from tests.conftest import wait_for
from wire.errors import (
    DeadlineExceededError,
    FailedPreconditionError,
    InternalError,
    InvalidArgumentError,
    UnavailableError,
    UnimplementedError,
)
from wire.local_call import LocalCallClient, LocalCallServer

METHOD = "/telerobot.v1.ProxyRobot/MoveJointsIncremental"


class Arm:
    """A handler that moves a joint vector: it sums the deltas, and can be told to refuse,
    fail or wait for the test."""

    def __init__(self):
        self.calls = 0
        self.refuse = False
        self.fail = False
        self.entered = threading.Event()
        self.release: threading.Event | None = None
        self.q = [0.0] * 6

    def move(self, request: pb.MoveJointsIncrementalRequest):
        self.calls += 1
        self.entered.set()
        if self.release is not None:
            self.release.wait(10)
        if self.refuse:
            raise FailedPreconditionError("the arm is ESTOPPED: Reset first", reason="ESTOPPED")
        if self.fail:
            raise ZeroDivisionError("a bug")
        if len(request.delta_joint_positions_rad) != 6:
            raise InvalidArgumentError("six deltas", reason="BAD_DELTA")
        self.q = [q + d for q, d in zip(self.q, request.delta_joint_positions_rad, strict=True)]
        return pb.MoveJointsIncrementalResponse(target_joint_positions_rad=self.q)


@pytest.fixture
def served(tmp_path):
    arm = Arm()
    server = LocalCallServer(tmp_path / "arm.sock", {
        METHOD: (pb.MoveJointsIncrementalRequest, arm.move)})
    server.start()
    client = LocalCallClient(server.path, timeout_s=5.0)
    yield arm, server, client
    client.close()
    server.stop()


def _move(client: LocalCallClient, delta: float = 0.1, joints: int = 6):
    return client.call(METHOD, pb.MoveJointsIncrementalRequest(
        delta_joint_positions_rad=[delta] * joints), pb.MoveJointsIncrementalResponse)


def test_a_call_gets_its_reply_and_the_socket_is_the_owners_only(served):
    arm, server, client = served
    answered: list[tuple] = []
    server.on_answered = lambda *call: answered.append(call)
    assert list(_move(client).target_joint_positions_rad) == pytest.approx([0.1] * 6)
    wait_for(lambda: answered, timeout_s=5, what="the call told to the audit hook")
    assert answered == [(METHOD, "OK", os.getuid())]  # the caller's user id, from the socket
    assert list(_move(client).target_joint_positions_rad) == pytest.approx([0.2] * 6)
    assert stat.S_IMODE(server.path.stat().st_mode) == 0o600
    assert arm.calls == 2


def test_errors_come_back_as_the_callers_own_classes(served):
    arm, server, client = served
    answered: list[tuple] = []  # told after each reply is sent: set before the first call
    server.on_answered = lambda *call: answered.append(call)
    with pytest.raises(InvalidArgumentError) as bad:
        _move(client, joints=5)
    assert (bad.value.reason, bad.value.method) == ("BAD_DELTA", METHOD)
    arm.refuse = True
    with pytest.raises(FailedPreconditionError, match="Reset first") as refused:
        _move(client)
    assert refused.value.reason == "ESTOPPED"
    wait_for(lambda: len(answered) == 2, timeout_s=5, what="both refusals told to the hook")
    assert [outcome for _, outcome, _ in answered] == ["INVALID_ARGUMENT", "FAILED_PRECONDITION"]
    arm.refuse, arm.fail = False, True
    with pytest.raises(InternalError, match="a bug"):
        _move(client)
    with pytest.raises(UnimplementedError) as unknown:
        client.call("/telerobot.v1.ProxyRobot/Hold", pb.HoldRequest(), pb.HoldResponse)
    assert unknown.value.reason == "NOT_LOCAL"
    arm.fail = False
    assert list(_move(client).target_joint_positions_rad) == pytest.approx([0.1] * 6)


def test_a_request_that_does_not_decode_is_invalid(served):
    _, server, _ = served
    reply = server.answer(METHOD.encode() + b"\0" + b"\xff\xff\xff")
    assert reply[0] == 1 and b"does not decode" in reply


def test_a_restarted_server_is_reconnected_to(served, tmp_path):
    arm, server, client = served
    _move(client)
    server.stop()
    with pytest.raises(UnavailableError) as down:
        _move(client)
    assert down.value.reason == "LOCAL_CALL_UNAVAILABLE"
    again = LocalCallServer(server.path, {METHOD: (pb.MoveJointsIncrementalRequest, arm.move)})
    again.start()
    try:
        _move(client)
        assert arm.calls == 2  # the refused call never reached the arm
    finally:
        again.stop()


def test_a_server_restarted_between_calls_gets_the_next_call_once(served):
    """The connection of the last call is stale: the request cannot be sent on it, so it is
    sent on a new connection, once."""
    arm, server, client = served
    _move(client)
    server.stop()
    again = LocalCallServer(server.path, {METHOD: (pb.MoveJointsIncrementalRequest, arm.move)})
    again.start()
    try:
        assert list(_move(client).target_joint_positions_rad) == pytest.approx([0.2] * 6)
        assert arm.calls == 2
    finally:
        again.stop()


def test_a_call_whose_reply_is_lost_is_not_sent_again(served):
    arm, server, client = served
    arm.release = threading.Event()
    outcome: list[BaseException] = []

    def call():
        try:
            _move(client)
        except UnavailableError as error:
            outcome.append(error)

    caller = threading.Thread(target=call)
    caller.start()
    assert arm.entered.wait(5)
    server.stop()  # mid-call: the connection goes, the reply with it
    arm.release.set()
    caller.join(5)
    assert outcome and outcome[0].reason == "LOCAL_CALL_LOST", outcome
    assert "may have been applied" in outcome[0].message
    assert arm.calls == 1


def test_a_late_reply_never_answers_the_next_call(tmp_path):
    arm = Arm()
    arm.release = threading.Event()
    server = LocalCallServer(tmp_path / "arm.sock", {
        METHOD: (pb.MoveJointsIncrementalRequest, arm.move)})
    server.start()
    client = LocalCallClient(server.path, timeout_s=0.05)
    try:
        with pytest.raises(DeadlineExceededError) as late:
            _move(client, 0.1)
        assert late.value.reason == "LOCAL_CALL_TIMEOUT"
        arm.release.set()  # the first move completes, and its reply goes to a closed socket
        arm.release = None
        wait_for(lambda: arm.q[0] == pytest.approx(0.1), timeout_s=5, what="the first move")
        client.timeout_s = 5.0
        reply = _move(client, 1.0)
        assert list(reply.target_joint_positions_rad) == pytest.approx([1.1] * 6)
    finally:
        client.close()
        server.stop()
