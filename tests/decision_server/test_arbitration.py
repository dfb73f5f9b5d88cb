"""Who may command the arm: exclusive and collaborative control, the queue, and leases."""

from __future__ import annotations

import signal
import textwrap
import threading
import time

import grpc
import pytest

from services.decision_server.arbitration import ControlMode, LockManager
from services.runtime.errors import Aborted, DeadlineExceeded, FailedPrecondition
from telerobot.v1 import decision_server_pb2 as pb
from telerobot.v1 import proxy_robot_pb2
from tests.conftest import start_process

EXCLUSIVE, COLLABORATIVE = ControlMode.EXCLUSIVE, ControlMode.COLLABORATIVE


@pytest.fixture
def locks():
    manager = LockManager()
    yield manager
    manager.close()


def test_two_operators_racing_have_exactly_one_winner(locks):
    start = threading.Barrier(8)
    winners, losers = [], []

    def race(name):
        start.wait()
        try:
            winners.append(locks.acquire(name, EXCLUSIVE))
        except Aborted as error:
            losers.append(error.message)

    threads = [threading.Thread(target=race, args=(f"op{i}",)) for i in range(8)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert len(winners) == 1 and len(losers) == 7
    assert all(f"'{winners[0].operator_id}' (EXCLUSIVE)" in message for message in losers)


def test_collaborative_control_is_shared_by_one_group(locks):
    a = locks.acquire("ann", COLLABORATIVE, "surgery")
    b = locks.acquire("bob", COLLABORATIVE, "surgery")
    assert {h.operator_id for h in locks.view().holders} == {"ann", "bob"}
    with pytest.raises(Aborted, match="COLLABORATIVE, group 'surgery'"):
        locks.acquire("cat", COLLABORATIVE, "other-group")
    with pytest.raises(Aborted):
        locks.acquire("dan", EXCLUSIVE)
    assert locks.require(a.lease_id) and locks.require(b.lease_id)


def test_waiters_are_served_in_order(locks):
    first = locks.acquire("first", EXCLUSIVE)
    granted = []

    def wait(name):
        granted.append(locks.acquire(name, EXCLUSIVE, wait=True, wait_timeout_s=5).operator_id)

    for name in ("second", "third"):
        threading.Thread(target=wait, args=(name,), daemon=True).start()
        time.sleep(0.05)
    assert [w[0] for w in locks.view().waiters] == ["second", "third"]
    # A newcomer may not overtake the queue, even though it asks for something else.
    with pytest.raises(Aborted):
        locks.acquire("newcomer", COLLABORATIVE, "g")
    locks.release(first.lease_id)
    time.sleep(0.05)
    assert granted == ["second"]
    locks.release(locks.view().holders[0].lease_id)
    time.sleep(0.05)
    assert granted == ["second", "third"]


def test_a_wait_can_time_out(locks):
    locks.acquire("holder", EXCLUSIVE)
    with pytest.raises(DeadlineExceeded, match="'holder'"):
        locks.acquire("waiter", EXCLUSIVE, wait=True, wait_timeout_s=0.1)
    assert locks.view().waiters == ()


def test_a_silent_holders_lease_expires_and_the_next_waiter_gets_control(locks):
    locks.acquire("sleepy", EXCLUSIVE, lease_s=0.2)
    started = time.monotonic()
    lease = locks.acquire("next", EXCLUSIVE, wait=True, wait_timeout_s=2)
    assert lease.operator_id == "next" and 0.15 < time.monotonic() - started < 0.6


def test_use_renews_the_lease(locks):
    lease = locks.acquire("busy", EXCLUSIVE, lease_s=0.2)
    for _ in range(6):
        time.sleep(0.1)
        locks.require(lease.lease_id)
    assert locks.view().holders[0].operator_id == "busy"


def test_commands_without_the_lock_are_refused_naming_the_holder(station):
    station.acquire("alice")
    with pytest.raises(grpc.RpcError) as error:
        station.robot.MoveJointsIncremental(proxy_robot_pb2.MoveJointsIncrementalRequest(
            delta_joint_positions_rad=[0.01, 0, 0, 0, 0, 0]))
    assert error.value.code() is grpc.StatusCode.FAILED_PRECONDITION
    assert "'alice' (EXCLUSIVE)" in error.value.details()
    # An observer without a lock still reads.
    assert station.robot.GetStatus(proxy_robot_pb2.GetStatusRequest()).status
    with pytest.raises(grpc.RpcError) as refused:
        station.decisions.AcquireControl(pb.AcquireControlRequest(
            operator_id="bob", mode=pb.CONTROL_MODE_EXCLUSIVE))
    assert refused.value.code() is grpc.StatusCode.ABORTED
    assert "'alice'" in refused.value.details()


def test_a_killed_holders_lease_expires(station):
    """A real client process takes control with a 0.5 s lease and is killed."""
    script = textwrap.dedent(f"""
        import time, grpc
        from telerobot.v1 import decision_server_pb2 as pb, decision_server_pb2_grpc
        stub = decision_server_pb2_grpc.DecisionServerStub(grpc.insecure_channel(
            "{station.address}"))
        stub.AcquireControl(pb.AcquireControlRequest(operator_id="doomed",
            mode=pb.CONTROL_MODE_EXCLUSIVE, lease_duration={{"nanos": 500_000_000}}))
        print("TELEROBOT_READY holder 0:0", flush=True)
        time.sleep(60)
    """)
    holder = start_process(["-c", script])
    holder.wait_ready(["holder"], timeout_s=20)
    state = station.decisions.GetControlState(pb.GetControlStateRequest()).state
    assert [h.operator_id for h in state.holders] == ["doomed"]
    holder.stop(signal.SIGKILL)
    started = time.monotonic()
    reply = station.decisions.AcquireControl(pb.AcquireControlRequest(
        operator_id="survivor", mode=pb.CONTROL_MODE_EXCLUSIVE, wait=True,
        wait_timeout={"seconds": 3}), timeout=5)
    assert reply.state.holders[0].operator_id == "survivor"
    assert time.monotonic() - started < 0.8


def test_lock_errors(station):
    with pytest.raises(grpc.RpcError) as error:
        station.decisions.AcquireControl(pb.AcquireControlRequest(operator_id="x"))
    assert error.value.code() is grpc.StatusCode.INVALID_ARGUMENT
    with pytest.raises(grpc.RpcError) as error:
        station.decisions.RenewControl(pb.RenewControlRequest(lease_id="nope"))
    assert error.value.code() is grpc.StatusCode.NOT_FOUND


def test_require_without_a_lease_explains(locks):
    with pytest.raises(FailedPrecondition, match="telerobot-lease-id"):
        locks.require(None)


def test_forwarded_errors_keep_their_reason(station):
    from google.rpc import error_details_pb2
    from grpc_status import rpc_status

    _, metadata = station.acquire("alice")
    station.ready_at_home(metadata)
    with pytest.raises(grpc.RpcError) as error:
        station.robot.MoveJointsIncremental(proxy_robot_pb2.MoveJointsIncrementalRequest(
            delta_joint_positions_rad=[2.0, 0, 0, 0, 0, 0]), metadata=metadata)
    assert error.value.code() is grpc.StatusCode.OUT_OF_RANGE
    info = error_details_pb2.ErrorInfo()
    assert rpc_status.from_call(error.value).details[0].Unpack(info)
    assert info.reason == "INCREMENT_CAP"
