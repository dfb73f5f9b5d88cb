"""make teleop --mcap: the session as one MCAP file in the project's own protobuf messages.

A scripted sequence goes through the recorder and comes back through the `mcap` reader (with
mcap-protobuf-support's decoder, from the schemas in the file alone); then a real session
(`python -m clients.teleop --modes feedback --no-video --mcap`) against a local station leaves a
file whose command and ack counts are the session's own."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from collections import defaultdict

import cv2
import numpy as np
import pytest
from mcap.reader import make_reader
from mcap_protobuf.decoder import DecoderFactory

from clients.python.values import Ack, StereoFrame
from clients.teleop import mcap_inspect
from clients.teleop import mcap_log as channels
from clients.teleop.mcap_log import SessionRecorder
from clients.teleop.stack import local_station
from services.launcher import STATION
from telerobot.v1 import decision_server_pb2 as pb
from telerobot.v1 import stereo_camera_pb2 as sc_pb
from telerobot.v1 import types_pb2
from tests.conftest import REPO
from tests.world.conftest import unique_shm_name
from wire import convert

T0 = 1_700_000_000_000_000_000  # a fixed wall-clock time, ns
MS = 1_000_000


def read_back(path) -> dict[str, list]:
    """topic -> [(log_time, publish_time, schema name, decoded proto)] in file order."""
    messages = defaultdict(list)
    with open(path, "rb") as stream:
        reader = make_reader(stream, decoder_factories=[DecoderFactory()])
        for schema, channel, message, proto in reader.iter_decoded_messages(
                log_time_order=False):
            messages[channel.topic].append(
                (message.log_time, message.publish_time, schema.name, proto))
    return messages


def jpeg(value: int) -> bytes:
    image = np.full((24, 32, 3), value, dtype=np.uint8)
    return cv2.imencode(".jpg", image)[1].tobytes()


def scripted_session(recorder: SessionRecorder) -> dict[str, list]:
    """What a short session sends and receives, through the recorder's hooks; returns the
    protos written per topic, in order."""
    written = defaultdict(list)
    header = sc_pb.StereoHeader(width_px=32, height_px=24,
                                encoding=sc_pb.IMAGE_ENCODING_JPEG, source="sim",
                                left=sc_pb.CameraCalibration(fx_px=40.0),
                                right=sc_pb.CameraCalibration(fx_px=40.0), baseline_m=0.1)
    event = pb.StreamEventsResponse(
        sequence=1, event_time=convert.timestamp(T0),
        teleop_session=pb.TeleopSessionEvent(session_id="s1", operator_id="teleop-script",
                                             state=pb.TELEOP_SESSION_STATE_OPENED))
    recorder.event(event, T0)
    written[channels.EVENTS].append(event)
    for i in range(1, 6):
        sent = T0 + i * 20 * MS
        command = pb.MasterCommand(sequence=i, send_time=convert.timestamp(sent),
                                   delta_position_m=types_pb2.Vector3(z=-0.001 * i),
                                   clutch_engaged=i == 3)
        recorder.request(pb.TeleoperateRequest(command=command))
        written[channels.COMMAND].append(command)
        heartbeat = pb.Heartbeat(send_time=convert.timestamp(sent + 5 * MS))
        recorder.request(pb.TeleoperateRequest(heartbeat=heartbeat))
        written[channels.HEARTBEAT].append(heartbeat)
        ack = pb.CommandAck(sequence=i, command_send_time=command.send_time,
                            apply_time=convert.timestamp(sent + 2 * MS),
                            outcome=pb.COMMAND_OUTCOME_APPLIED,
                            status=types_pb2.ROBOT_STATUS_MOVING,
                            tool_pose=types_pb2.Pose(position_m=types_pb2.Vector3(z=0.5 - i)),
                            tool_wrench=types_pb2.Wrench(force_n=types_pb2.Vector3(z=-i)))
        recorder.ack(Ack.from_proto(ack, sent + 3 * MS))
        written[channels.ACK].append(ack)
        written[channels.TOOL_POSE].append(ack.tool_pose)
        written[channels.WRENCH].append(ack.tool_wrench)
        beat_ack = pb.CommandAck(sequence=0, command_send_time=heartbeat.send_time,
                                 outcome=pb.COMMAND_OUTCOME_HEARTBEAT)  # no pose, no wrench
        recorder.ack(Ack.from_proto(beat_ack, sent + 6 * MS))
        written[channels.ACK].append(beat_ack)
        pair = sc_pb.StereoPair(sequence=i, left_capture_time=convert.timestamp(sent),
                                right_capture_time=convert.timestamp(sent),
                                left_image=jpeg(10 * i), right_image=jpeg(10 * i + 5))
        recorder.stereo(StereoFrame(header, pair, None, None), sent + 4 * MS)
        if i == 1:  # the header goes once, before its first pair
            written[channels.STEREO_HEADER].append(header)
        written[channels.STEREO_PAIR].append(pair)
    # The wall clock steps back (NTP): the ack channel's log times still never go back.
    late = pb.CommandAck(sequence=6, outcome=pb.COMMAND_OUTCOME_APPLIED)
    recorder.ack(Ack.from_proto(late, T0))
    written[channels.ACK].append(late)
    return written


def test_a_scripted_session_reads_back_channel_for_channel(tmp_path):
    path = tmp_path / "session.mcap"
    with SessionRecorder(path) as recorder:
        written = scripted_session(recorder)
        recorder.run("feedback", T0, T0 + 200 * MS)
    assert recorder.closed
    recorder.ack(Ack.from_proto(pb.CommandAck(sequence=7), T0))  # after close: ignored

    read = read_back(path)
    assert set(read) == set(channels.CHANNELS) == set(written)
    for topic, protos in written.items():
        assert len(read[topic]) == len(protos) == recorder.counts[topic], topic
        # Decoded with the file's own schema (a class of its own), equal to what was written.
        generated = type(protos[0])
        assert [generated.FromString(proto.SerializeToString()) for *_, proto in read[topic]] \
            == protos, topic
        # Decoded from the schema in the file: the same message type, by its full name.
        assert {schema for _, _, schema, _ in read[topic]} == {
            protos[0].DESCRIPTOR.full_name}, topic
        times = [log_time for log_time, *_ in read[topic]]
        assert times == sorted(times), topic
    # Log times are the client's: a command's send time, an ack's receive time.
    assert [t for t, *_ in read[channels.COMMAND]] == [T0 + i * 20 * MS for i in range(1, 6)]
    assert [t for t, *_ in read[channels.ACK]][:2] == [T0 + 23 * MS, T0 + 26 * MS]
    assert read[channels.ACK][-1][0] == read[channels.ACK][-2][0]  # held, not gone back
    assert read[channels.ACK][0][1] == T0 + 22 * MS  # publish time: the server's apply time
    # The images decode, the eyes apart.
    _, _, _, pair = read[channels.STEREO_PAIR][2]
    left = cv2.imdecode(np.frombuffer(pair.left_image, np.uint8), cv2.IMREAD_COLOR)
    right = cv2.imdecode(np.frombuffer(pair.right_image, np.uint8), cv2.IMREAD_COLOR)
    assert left.shape == right.shape == (24, 32, 3)
    assert abs(int(left.mean()) - 30) <= 2 and abs(int(right.mean()) - 35) <= 2

    summary = mcap_inspect.summarize(path)
    assert {c.topic: c.count for c in summary.channels} == dict(recorder.counts)
    assert {c.topic: c.schema for c in summary.channels}[channels.COMMAND] == \
        "telerobot.v1.MasterCommand"
    assert summary.start_ns == T0 and summary.end_ns == T0 + 106 * MS
    assert json.loads(summary.metadata["teleop"]["runs"]) == [
        {"mode": "feedback", "start_ns": T0, "end_ns": T0 + 200 * MS}]
    assert json.loads(summary.metadata["teleop"]["counts"]) == dict(recorder.counts)


def test_a_failed_write_stops_the_recording_not_the_session(tmp_path):
    path = tmp_path / "session.mcap"
    with SessionRecorder(path) as recorder:
        recorder.write(channels.COMMAND, pb.MasterCommand(sequence=1), T0)
        recorder.write(channels.COMMAND, pb.Heartbeat(), T0 + MS)  # the wrong type: refused
        recorder.write(channels.COMMAND, pb.MasterCommand(sequence=2), T0 + 2 * MS)
    assert "/teleop/command" in recorder.error and recorder.counts[channels.COMMAND] == 1
    read = read_back(path)  # what came before the failure is in the file, which is whole
    assert [proto.sequence for *_, proto in read[channels.COMMAND]] == [1]
    assert mcap_inspect.summarize(path).metadata["teleop"]["error"] == recorder.error


def test_inspect_prints_every_channel_and_says_when_it_cannot_read(tmp_path, capsys):
    path = tmp_path / "session.mcap"
    with SessionRecorder(path) as recorder:
        scripted_session(recorder)
    assert mcap_inspect.main([str(path)]) == 0
    out = capsys.readouterr().out
    for topic in channels.CHANNELS:
        assert topic in out
    assert "telerobot.v1.CommandAck" in out and f"{len(channels.CHANNELS)} channels" in out
    (tmp_path / "junk.mcap").write_bytes(b"not an mcap file")
    assert mcap_inspect.main([str(tmp_path / "junk.mcap")]) == 2
    assert "cannot read" in capsys.readouterr().err


@pytest.mark.e2e
def test_make_teleop_mcap_counts_match_the_sessions_own(tmp_path):
    env = {f"TELEROBOT_{name.upper()}_ADDRESS": "127.0.0.1:0" for name in STATION}
    env["TELEROBOT_WORLD_SHM"] = unique_shm_name()
    out = tmp_path / "run"
    with local_station(env=env) as addresses:
        result = subprocess.run(
            [sys.executable, "-m", "clients.teleop", "--address",
             addresses["decision_server"], "--modes", "feedback", "--no-video", "--mcap",
             "--out", str(out), "--calibration", str(tmp_path / "cameras.json")],
            cwd=REPO, env={**os.environ, **env}, capture_output=True, text=True, timeout=400)
    assert result.returncode == 0, result.stdout[-3000:] + result.stderr[-3000:]
    summary = json.loads((out / "summary.json").read_text())
    (run,) = summary["runs"]
    assert summary["mcap"] == str(out / "session.mcap")

    read = read_back(out / "session.mcap")
    commands = [proto for *_, proto in read[channels.COMMAND]]
    command_acks = [proto for *_, proto in read[channels.ACK] if proto.sequence]
    assert len(commands) == run["commands"] > 0, (len(commands), run)
    assert len(command_acks) == run["commands_acked"] == run["commands"], run
    assert [c.sequence for c in commands] == list(range(1, len(commands) + 1))
    assert sorted(a.sequence for a in command_acks) == [c.sequence for c in commands]
    # Every ack the task saw is in the file (heartbeats' too), with the pose and wrench.
    assert len(read[channels.ACK]) == run["acks"], run
    assert read[channels.TOOL_POSE] and read[channels.WRENCH] and read[channels.HEARTBEAT]
    # The peak force the run reports is the peak of the wrenches recorded.
    peak = max(-w.force_n.z for *_, w in read[channels.WRENCH])
    assert peak == pytest.approx(run["peak_force_n"]), run
    # The DecisionServer's events (the arm's status changes, at least), decoded from the file.
    assert read[channels.EVENTS]
    assert all(e.WhichOneof("event") for *_, e in read[channels.EVENTS])
    assert channels.STEREO_PAIR not in read  # --no-video
    for topic, messages in read.items():
        times = [log_time for log_time, *_ in messages]
        assert times == sorted(times), topic
    assert summary["mcap_counts"] == {topic: len(m) for topic, m in read.items()}
