"""Who may command the arm, through the DecisionServer's contracts: the lock in front of
commands, lock errors in-process; a killed holder and forwarded errors on the real station
(e2e). The LockManager itself is tested in test_locks.py."""

from __future__ import annotations

import signal
import textwrap
import time

import grpc
import pytest

from telerobot.v1 import decision_server_pb2 as pb
from telerobot.v1 import proxy_robot_pb2
from tests.processes import start_process


def test_commands_without_the_lock_are_refused_naming_the_holder(fake_station):
    station, slave = fake_station
    station.acquire("alice")
    with pytest.raises(grpc.RpcError) as error:
        station.robot.MoveJointsIncremental(proxy_robot_pb2.MoveJointsIncrementalRequest(
            delta_joint_positions_rad=[0.01, 0, 0, 0, 0, 0]))
    assert error.value.code() is grpc.StatusCode.FAILED_PRECONDITION
    assert "'alice' (EXCLUSIVE)" in error.value.details()
    assert slave.commands == []  # refused before it was forwarded
    # An observer without a lock still reads.
    state = station.decisions.GetControlState(pb.GetControlStateRequest()).state
    assert [h.operator_id for h in state.holders] == ["alice"]
    with pytest.raises(grpc.RpcError) as refused:
        station.decisions.AcquireControl(pb.AcquireControlRequest(
            operator_id="bob", mode=pb.CONTROL_MODE_EXCLUSIVE))
    assert refused.value.code() is grpc.StatusCode.ABORTED
    assert "'alice'" in refused.value.details()


@pytest.mark.e2e
def test_a_killed_holders_lease_expires(station):
    """A real client process takes control with a 0.5 s lease and is killed."""
    script = textwrap.dedent(f"""
        import signal, grpc
        from telerobot.v1 import decision_server_pb2 as pb, decision_server_pb2_grpc
        stub = decision_server_pb2_grpc.DecisionServerStub(grpc.insecure_channel(
            "{station.address}"))
        stub.AcquireControl(pb.AcquireControlRequest(operator_id="doomed",
            mode=pb.CONTROL_MODE_EXCLUSIVE, lease_duration={{"nanos": 500_000_000}}))
        print("TELEROBOT_READY holder 0:0", flush=True)
        signal.pause()  # silent until killed
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


def test_lock_errors(fake_station):
    station, _ = fake_station
    with pytest.raises(grpc.RpcError) as error:
        station.decisions.AcquireControl(pb.AcquireControlRequest(operator_id="x"))
    assert error.value.code() is grpc.StatusCode.INVALID_ARGUMENT
    with pytest.raises(grpc.RpcError) as error:
        station.decisions.RenewControl(pb.RenewControlRequest(lease_id="nope"))
    assert error.value.code() is grpc.StatusCode.NOT_FOUND


@pytest.mark.e2e
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
