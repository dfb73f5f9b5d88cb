"""The recording-on twins (issue #17): teleop_1000_mcap and force_1000_mcap, and what their
MCAP files hold.

- ``teleop_1000_mcap``: teleop_1000 with the DecisionServer recording the session as MCAP
  (StartRecording before the stream, StopRecording after it; teleop.py). The server records
  one increment per move it makes, and it merges a backlog of commands into one move, so the
  file's increments are counted in commands: their displacement over the one step every
  command makes (TELEOP_STEP_M along base y, no assistance), which must equal the commands
  applied in the session (warm-up included); and its acks of applied commands must too.
- ``force_1000_mcap``: force_1000 with the subscriber writing each wrench sample it receives
  into an MCAP file with `make teleop --mcap`'s SessionRecorder (the Wrench on /robot/wrench and
  its Foxglove arrow on /force/arrow) before it takes the latency timestamp (force.py); both
  channels must hold every sample received.

`expected` is what the client counted, `recorded` what the file holds, channel by channel;
goals.py fails a row whose `recorded` falls short (or whose recorder failed: `error`).
"""

from __future__ import annotations

import time
from pathlib import Path

from mcap.reader import make_reader
from mcap_protobuf.decoder import DecoderFactory

from clients.teleop import mcap_log
from services.decision_server import recording_mcap
from telerobot.v1 import decision_server_pb2 as dpb
from wire import foxglove as fox

ACCEPTED = (dpb.COMMAND_OUTCOME_APPLIED, dpb.COMMAND_OUTCOME_MODIFIED)


def topic_counts(path: Path) -> dict[str, int]:
    """Messages per topic, from the finished file's summary statistics."""
    with open(path, "rb") as stream:
        summary = make_reader(stream).get_summary()
    if summary is None or summary.statistics is None:
        raise ValueError(f"{path.name} has no summary: not finished")
    return {summary.channels[channel].topic: count
            for channel, count in summary.statistics.channel_message_counts.items()}


def teleop_check(path: Path, applied: int, server_moves: int, step_m: float) -> dict:
    """What a DecisionServer recording of a Teleoperate session holds against the `applied`
    commands the client had acked APPLIED or MODIFIED (every command `step_m` along base y)
    and the moves StopRecording said it saved (`server_moves`)."""
    moves, displacement_m, acks = 0, 0.0, 0
    with open(path, "rb") as stream:
        reader = make_reader(stream, decoder_factories=[DecoderFactory()])
        for _, channel, _, message in reader.iter_decoded_messages(
                topics=[recording_mcap.INCREMENT, recording_mcap.ACK]):
            if channel.topic == recording_mcap.INCREMENT:
                moves += 1
                displacement_m += abs(message.delta_position_m.y)
            elif message.sequence and message.outcome in ACCEPTED:  # not a heartbeat's
                acks += 1
    return {"format": "MCAP (DecisionServer)", "file_bytes": path.stat().st_size,
            "expected": applied, "recorded": {"increments (in commands)":
                                              round(displacement_m / step_m),
                                              "applied acks": acks},
            "moves": moves, "moves_saved": server_moves,
            "error": (None if moves == server_moves else
                      f"StopRecording saved {server_moves} moves, the file holds {moves}")}


class WrenchRecorder:
    """What `make teleop --mcap` writes per wrench (SessionRecorder.wrench, as its ack hook
    does: the Wrench and its Foxglove arrow), for each sample of a StreamWrench message."""

    def __init__(self, path: Path):
        self.path = Path(path)
        self.recorder = mcap_log.SessionRecorder(self.path)
        self.samples = 0

    def write(self, message) -> None:
        now = time.time_ns()  # received: the log time, as the operator station logs it
        for sample in message.samples:
            self.recorder.wrench(sample.wrench, now, sample.sample_time.ToNanoseconds())
            self.samples += 1

    def close(self) -> dict:
        self.recorder.close()
        counts = topic_counts(self.path)
        return {"format": "MCAP (SessionRecorder)", "file_bytes": self.path.stat().st_size,
                "expected": self.samples,
                "recorded": {topic: counts.get(topic, 0)
                             for topic in (mcap_log.WRENCH, fox.FORCE_ARROW)},
                "error": self.recorder.error}
