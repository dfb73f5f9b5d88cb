"""The lane interceptor sends a response a servicer already serialized (bytes) as it is, and
every other response through the method's serializer, in unary calls and streams alike."""

from __future__ import annotations

import grpc
import pytest

from services.runtime.rpc import _passing_bytes
from services.runtime.server import binding, create_server
from telerobot.v1 import proxy_robot_pb2, proxy_robot_pb2_grpc

# A GetStatusResponse serialized by hand, with a field this build does not know (number 999):
# re-serializing it after a decode would keep the field but could reorder it, and a serializer
# given bytes would fail. It arriving byte for byte shows the bytes were not touched.
UNKNOWN_FIELD = b"\xb8\x3e\x07"  # field 999, varint 7
PRESERIALIZED = UNKNOWN_FIELD + proxy_robot_pb2.GetStatusResponse(
    reason="pre-serialized").SerializeToString()


class Robot(proxy_robot_pb2_grpc.ProxyRobotServicer):
    def GetStatus(self, request, context):
        if request.ByteSize() == 0:
            return PRESERIALIZED
        return proxy_robot_pb2.GetStatusResponse(reason="a message")

    def StreamRobotEvents(self, request, context):
        yield proxy_robot_pb2.StreamRobotEventsResponse(sequence=1)
        yield proxy_robot_pb2.StreamRobotEventsResponse(sequence=2).SerializeToString()
        yield proxy_robot_pb2.StreamRobotEventsResponse(sequence=3)


@pytest.fixture(params=[False, True], ids=["sync", "aio"])
def channel(request):
    server, port = create_server("127.0.0.1:0",
                                 [binding(proxy_robot_pb2_grpc, "ProxyRobot", Robot())],
                                 aio=request.param)
    server.start()
    with grpc.insecure_channel(f"127.0.0.1:{port}") as channel:
        yield channel
    server.stop(0)


def test_a_bytes_response_goes_out_unchanged(channel):
    raw = channel.unary_unary("/telerobot.v1.ProxyRobot/GetStatus")  # no deserializer: bytes
    assert raw(b"", timeout=5) == PRESERIALIZED
    stub = proxy_robot_pb2_grpc.ProxyRobotStub(channel)
    assert stub.GetStatus(proxy_robot_pb2.GetStatusRequest(), timeout=5).reason == (
        "pre-serialized")


def test_other_responses_still_go_through_the_serializer(channel):
    stub = proxy_robot_pb2_grpc.ProxyRobotStub(channel)
    # A request with a field set makes the servicer answer with a message.
    request = proxy_robot_pb2.GetStatusRequest.FromString(UNKNOWN_FIELD)
    assert request.ByteSize() > 0
    assert stub.GetStatus(request, timeout=5).reason == "a message"


def test_a_stream_may_mix_bytes_and_messages(channel):
    stub = proxy_robot_pb2_grpc.ProxyRobotStub(channel)
    events = stub.StreamRobotEvents(proxy_robot_pb2.StreamRobotEventsRequest(), timeout=5)
    assert [event.sequence for event in events] == [1, 2, 3]


def test_the_serializer_is_called_for_messages_only():
    calls = []

    def serializer(message):
        calls.append(message)
        return b"serialized"

    serialize = _passing_bytes(serializer)
    assert serialize(b"as it is") == b"as it is"
    message = proxy_robot_pb2.GetStatusResponse(reason="x")
    assert serialize(message) == b"serialized"
    assert calls == [message]
    assert _passing_bytes(None) is None  # a method without a serializer keeps none
