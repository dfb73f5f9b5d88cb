"""bench.teleop's pipelined measurement against an in-memory stream (no server): acks are
matched by sequence, refused and unanswered commands count as dropped. No timing asserted."""

from __future__ import annotations

import queue

from bench import teleop
from telerobot.v1 import decision_server_pb2 as dpb


class EchoStream:
    """Answers the init with ready and each command with an ack at once; refuses the
    sequences in `refuse`, never answers those in `ignore`."""

    def __init__(self, refuse=(), ignore=()):
        self.refuse, self.ignore = set(refuse), set(ignore)
        self._out: queue.SimpleQueue = queue.SimpleQueue()
        self._out.put(dpb.TeleoperateResponse(ready=dpb.TeleoperateReady(session_id="s")))

    def send(self, request):
        command = request.command
        if command.sequence in self.ignore:
            return
        outcome = (dpb.COMMAND_OUTCOME_REJECTED if command.sequence in self.refuse
                   else dpb.COMMAND_OUTCOME_APPLIED)
        ack = dpb.CommandAck(sequence=command.sequence, command_send_time=command.send_time,
                             receive_time=command.send_time, apply_time=command.send_time,
                             outcome=outcome, detail="no")
        self._out.put(dpb.TeleoperateResponse(ack=ack))

    def responses(self):
        yield from iter(self._out.get, None)

    def end(self):
        self._out.put(None)

    def cancel(self):
        self._out.put(None)

    def close(self):
        pass


class EchoClient:
    name = "in-memory"

    def __init__(self, stream):
        self.stream = stream

    def open(self):
        return self.stream


def test_every_command_is_acked_applied_refused_or_counted_unacked():
    # Sequences 1..20 are the warm-up (fewer if the sender skipped late ticks); the measured
    # commands follow, 5 ms apart: the first few are always sent.
    stream = EchoStream(refuse={22, 23}, ignore={24})
    result = teleop.run_rate(EchoClient(stream), rate_hz=200.0, duration_s=0.1, sign=1.0,
                             loop=None)
    assert result["mode"] == "pipelined"
    assert result["refused"] == 2 and result["unacked"] == 1
    assert result["failures"] == ["COMMAND_OUTCOME_REJECTED: no"] * 2
    sent = result["sent"]
    assert result["samples"] == sent - 3  # latencies of the APPLIED acks only
    assert result["dropped"] == 20 - sent + 3
    assert result["late_skipped"] == 20 - sent
    assert all(value == 0.0 for value in result["latencies_ms"])  # apply_time = send_time


def test_a_stream_that_never_says_ready_fails():
    stream = EchoStream()
    stream._out = queue.SimpleQueue()
    stream.end()
    try:
        teleop.run_rate(EchoClient(stream), 1000.0, 0.01, 1.0, None)
    except teleop.StreamFailed as error:
        assert "ready" in str(error)
    else:
        raise AssertionError("no StreamFailed")


def test_an_unacked_command_before_an_acked_one_is_a_gap():
    stream = EchoStream(ignore={22})
    result = teleop.run_rate(EchoClient(stream), rate_hz=200.0, duration_s=0.1, sign=1.0,
                             loop=None, drain_s=0.2)
    assert result["unacked"] == 1 and result["ack_gaps"] == 1


def test_a_long_stream_swings_back_and_forth():
    class Recorder(EchoStream):
        def __init__(self):
            super().__init__()
            self.deltas = {}

        def send(self, request):
            self.deltas[request.command.sequence] = request.command.delta_position_m.y
            super().send(request)

    stream = Recorder()
    teleop.run_rate(EchoClient(stream), rate_hz=1000.0, duration_s=0.05, sign=1.0, loop=None,
                    swing=10)
    signs = {sequence: delta > 0 for sequence, delta in stream.deltas.items()}
    assert signs[1] and not signs[10] and not signs[19] and signs[20]


def test_windows_split_the_acks_by_when_they_were_sent():
    first = 1_000_000_000
    applied = teleop.dpb.COMMAND_OUTCOME_APPLIED
    acks = [(first + i * 100_000_000, 0, 0, first + i * 100_000_000 + (i + 1) * 1_000_000,
             applied) for i in range(20)]  # one every 0.1 s, latency 1..20 ms
    acks.append((first, 0, 0, first, teleop.dpb.COMMAND_OUTCOME_REJECTED))  # not counted
    rows = teleop.windows(acks, first, 1.0)
    assert [(r["t_s"], r["acked"]) for r in rows] == [(0.0, 10), (1.0, 10)]
    assert rows[0]["max_ms"] == 10.0 and rows[1]["max_ms"] == 20.0
    assert teleop.windows(acks, None, 1.0) == []


def _command(sequence: int) -> dpb.TeleoperateRequest:
    return dpb.TeleoperateRequest(command=dpb.MasterCommand(sequence=sequence))


def test_commands_that_waited_together_go_as_one_message_in_order(monkeypatch):
    monkeypatch.setattr(teleop, "MAX_COMMANDS_PER_MESSAGE", 3)
    heartbeat = dpb.TeleoperateRequest(heartbeat=dpb.Heartbeat())
    waiting = [_command(1), _command(2), heartbeat, *(_command(i) for i in range(3, 8))]
    packed = teleop._packed(waiting)
    assert [m.WhichOneof("message") for m in packed] == [
        "commands", "heartbeat", "commands", "commands"]
    assert [[c.sequence for c in m.commands.commands] for m in packed if m.HasField("commands")
            ] == [[1, 2], [3, 4, 5], [6, 7]]
    assert teleop._packed([_command(1)]) == [_command(1)]  # alone: as it was
