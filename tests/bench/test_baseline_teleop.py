"""baseline_server's zmq-teleop sessions without zmq: frames in, reply frames out, over the
DecisionServer's own DecisionCore on a fake slave."""

from __future__ import annotations

import pytest
from google.protobuf import timestamp_pb2

from bench import framing
from bench.baseline_server import TELEOP_END, OperatorSessions
from bench.teleop import init_request
from services.decision_server.core import DecisionCore
from services.decision_server.recording_writer import on_a_thread
from services.decision_server.recordings import RecordingStore
from telerobot.v1 import decision_server_pb2 as dpb
from telerobot.v1 import types_pb2
from tests.fakes.clock import FakeClock
from tests.fakes.slave import FakeSlave


@pytest.fixture
def sessions(tmp_path):
    clock = FakeClock()
    slave = FakeSlave(clock)
    core = DecisionCore(slave, RecordingStore(tmp_path / "recordings", clock, on_a_thread), clock)
    sessions = OperatorSessions(core)
    yield sessions, slave
    sessions.close()
    core.close()


def _command(sequence: int) -> bytes:
    return dpb.TeleoperateRequest(command=dpb.MasterCommand(
        sequence=sequence, send_time=timestamp_pb2.Timestamp(seconds=1),
        delta_position_m=types_pb2.Vector3(y=1e-4))).SerializeToString()


def test_commands_that_arrived_together_are_one_move_and_one_group_of_acks_in_order(sessions):
    """The bench asks for grouped acks (TeleoperateInit.grouped_acks), as the gRPC stream
    does: the commands taken together are answered in one message."""
    sessions, slave = sessions
    peer = b"peer"
    [(who, (kind, payload))] = sessions.handle([(peer, init_request("").SerializeToString())])
    assert (who, kind) == (peer, framing.REPLY_OK)
    assert dpb.TeleoperateResponse.FromString(payload).WhichOneof("message") == "ready"
    replies = sessions.handle([(peer, _command(n)) for n in (1, 2, 3)])
    [(_, (_, payload))] = replies
    acks = dpb.TeleoperateResponse.FromString(payload).acks.acks
    assert [ack.sequence for ack in acks] == [1, 2, 3]
    assert {ack.outcome for ack in acks} == {dpb.COMMAND_OUTCOME_APPLIED}
    assert [c.kind for c in slave.commands] == ["cartesian"]  # merged into one move
    assert sessions.handle([(peer, b"")]) == [(peer, [TELEOP_END, b""])]
    assert sessions.core.locks.view().holders == ()


def test_a_command_before_the_init_ends_that_stream_with_an_error(sessions):
    sessions, _ = sessions
    [(_, (kind, why))] = sessions.handle([(b"peer", _command(1))])
    assert kind == framing.REPLY_ERROR and b"init" in why
