"""Every request is checked before its handler runs: unknown enum values and over-long
strings get INVALID_ARGUMENT naming the field, on unary and streaming calls alike. The
servicers here record what reached them; the runtime under test is real."""

from __future__ import annotations

import grpc
import pytest

from services.runtime.server import binding, create_server
from services.runtime.validation import DEFAULT_MAX_STRING_LENGTH, check_request
from telerobot.v1 import (
    decision_server_pb2,
    decision_server_pb2_grpc,
    proxy_robot_pb2,
    proxy_robot_pb2_grpc,
)


class Recorder:
    def __init__(self):
        self.calls: list[str] = []


class Robot(proxy_robot_pb2_grpc.ProxyRobotServicer):
    def __init__(self, recorder: Recorder):
        self.recorder = recorder

    def EmergencyStop(self, request, context):
        self.recorder.calls.append(f"EmergencyStop {request.reason!r}")
        return proxy_robot_pb2.EmergencyStopResponse()


class Decisions(decision_server_pb2_grpc.DecisionServerServicer):
    def __init__(self, recorder: Recorder):
        self.recorder = recorder

    def AcquireControl(self, request, context):
        # The handler a hostile client crashed: Name() raises on an unknown value.
        mode = decision_server_pb2.ControlMode.Name(request.mode)
        self.recorder.calls.append(f"AcquireControl {mode}")
        return decision_server_pb2.AcquireControlResponse(lease_id="lease")

    def Teleoperate(self, request_iterator, context):
        for request in request_iterator:
            self.recorder.calls.append(f"Teleoperate {request.WhichOneof('message')}")
            yield decision_server_pb2.TeleoperateResponse()


@pytest.fixture(params=[False, True], ids=["sync", "aio"])
def server(request):
    recorder = Recorder()
    server, port = create_server("127.0.0.1:0", [
        binding(proxy_robot_pb2_grpc, "ProxyRobot", Robot(recorder)),
        binding(decision_server_pb2_grpc, "DecisionServer", Decisions(recorder))],
        aio=request.param)
    server.start()
    channel = grpc.insecure_channel(f"127.0.0.1:{port}")
    yield recorder, channel
    channel.close()
    server.stop(0)


@pytest.mark.parametrize("mode", [3, 99, -5, 2**31 - 1])
def test_an_unknown_enum_value_is_invalid_argument_naming_the_field(server, mode):
    recorder, channel = server
    stub = decision_server_pb2_grpc.DecisionServerStub(channel)
    with pytest.raises(grpc.RpcError) as caught:
        stub.AcquireControl(decision_server_pb2.AcquireControlRequest(mode=mode), timeout=5)
    assert caught.value.code() == grpc.StatusCode.INVALID_ARGUMENT
    assert f"mode = {mode} is not a ControlMode value" in caught.value.details()
    assert "CONTROL_MODE_EXCLUSIVE" in caught.value.details()
    assert recorder.calls == []
    stub.AcquireControl(decision_server_pb2.AcquireControlRequest(mode=1), timeout=5)
    assert recorder.calls == ["AcquireControl CONTROL_MODE_EXCLUSIVE"]


def test_a_nested_unknown_enum_value_names_its_path():
    request = decision_server_pb2.SetAssistanceRequest()
    request.assistance.constraint.type = 7
    with pytest.raises(Exception, match=r"assistance\.constraint\.type = 7"):
        check_request(request)


def test_a_string_past_its_bound_is_refused_and_never_reaches_the_handler(server):
    recorder, channel = server
    stub = decision_server_pb2_grpc.DecisionServerStub(channel)
    with pytest.raises(grpc.RpcError) as caught:
        stub.AcquireControl(decision_server_pb2.AcquireControlRequest(
            mode=1, operator_id="x" * 10_000), timeout=5)
    assert caught.value.code() == grpc.StatusCode.INVALID_ARGUMENT
    assert (f"operator_id has 10000 characters; it takes at most {DEFAULT_MAX_STRING_LENGTH}"
            in caught.value.details())
    assert recorder.calls == []
    stub.AcquireControl(decision_server_pb2.AcquireControlRequest(
        mode=1, operator_id="y" * DEFAULT_MAX_STRING_LENGTH), timeout=5)
    assert recorder.calls == ["AcquireControl CONTROL_MODE_EXCLUSIVE"]


def test_an_emergency_stop_is_never_refused_for_its_reason(server):
    """Safety first: the stop goes through, its over-long reason cut to the bound (so the logs
    stay bounded all the same)."""
    recorder, channel = server
    stub = proxy_robot_pb2_grpc.ProxyRobotStub(channel)
    stub.EmergencyStop(proxy_robot_pb2.EmergencyStopRequest(reason="x" * 10_000), timeout=5)
    assert recorder.calls == [f"EmergencyStop {'x' * DEFAULT_MAX_STRING_LENGTH!r}"]


def test_a_bad_message_mid_stream_ends_the_stream_with_invalid_argument(server):
    recorder, channel = server
    stub = decision_server_pb2_grpc.DecisionServerStub(channel)
    bad = decision_server_pb2.TeleoperateRequest()
    bad.init.mapping = 42
    requests = [decision_server_pb2.TeleoperateRequest(
        heartbeat=decision_server_pb2.Heartbeat()), bad]
    with pytest.raises(grpc.RpcError) as caught:
        list(stub.Teleoperate(iter(requests), timeout=5))
    assert caught.value.code() == grpc.StatusCode.INVALID_ARGUMENT
    assert "init.mapping = 42 is not a ReferenceFrame value" in caught.value.details()
    assert recorder.calls == ["Teleoperate heartbeat"]


@pytest.mark.parametrize(("seconds", "nanos"), [(315_576_000_001, 0), (2**63 - 1, 0), (0, 10**9),
                                                (1, -1), (-1, 5)])
def test_a_duration_outside_its_range_is_refused(seconds, nanos):
    request = decision_server_pb2.AcquireControlRequest(mode=1)
    request.lease_duration.seconds, request.lease_duration.nanos = seconds, nanos
    with pytest.raises(Exception, match="lease_duration is not a valid Duration"):
        check_request(request)


def test_a_timestamp_outside_its_range_is_refused_and_a_valid_one_passes():
    request = decision_server_pb2.TeleoperateRequest()
    request.command.send_time.seconds = 253_402_300_800  # year 10000
    with pytest.raises(Exception, match="command.send_time is not a valid Timestamp"):
        check_request(request)
    request.command.send_time.seconds = 1_800_000_000
    request.command.send_time.nanos = 999_999_999
    check_request(request)


def test_messages_of_numbers_only_are_passed_over_and_the_rest_still_checked():
    """A Vector3 or a Matrix3 cannot hold anything to refuse, so the check does not walk it;
    a message that holds one beside an enum is still checked, at any depth."""
    from services.runtime.validation import _may_refuse
    from telerobot.v1 import types_pb2

    assert not _may_refuse(types_pb2.Vector3.DESCRIPTOR)
    assert not _may_refuse(types_pb2.Matrix3.DESCRIPTOR)
    assert _may_refuse(proxy_robot_pb2.MoveCartesianIncrementalRequest.DESCRIPTOR)
    assert _may_refuse(decision_server_pb2.TeleoperateRequest.DESCRIPTOR)  # a Timestamp, deep
    request = proxy_robot_pb2.MoveCartesianIncrementalRequest(frame=99)
    request.delta_position_m.x = 1e-3
    with pytest.raises(Exception, match="frame = 99"):
        check_request(request)
