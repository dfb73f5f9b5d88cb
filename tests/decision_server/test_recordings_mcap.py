"""DecisionServer recordings as MCAP (issue #17): the store, the converter, the servicer's
field and status codes (in-process, fake slave, fake clock), and one end-to-end recording and
replay with the real DecisionServer in front of the real world."""

from __future__ import annotations

import json
import subprocess
import threading
import time
from collections import Counter, defaultdict
from collections.abc import Iterator
from concurrent import futures
from pathlib import Path

import grpc
import numpy as np
import pytest
from mcap.reader import make_reader
from mcap_protobuf.decoder import DecoderFactory

from services.decision_server import recording_convert, recording_mcap
from services.decision_server.camera_feed import CameraSource
from services.decision_server.recordings import RecordingStore
from services.decision_server.servicer import event_to_proto
from telerobot.v1 import decision_server_pb2 as pb
from telerobot.v1 import force_sensor_pb2, types_pb2
from telerobot.v1 import proxy_robot_pb2 as pr_pb
from telerobot.v1 import stereo_camera_pb2 as sc_pb
from telerobot.v1 import stereo_camera_pb2_grpc as sc_grpc
from tests.conftest import wait_for
from tests.decision_server.conftest import Operator
from tests.processes import BUF
from wire.errors import FailedPreconditionError, UnavailableError


def _rotation_z(angle: float) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def _record_some(rig, name: str, format: str = "JSONL") -> list:
    """Cartesian increments in each frame and a joint one, 10 ms apart; the recorded ones."""
    lease = rig.lease.lease_id
    rig.core.start_recording(lease, name, format)
    for i in range(6):
        frame = ("BASE", "TOOL", "WRIST")[i % 3]
        rig.core.move_cartesian(lease, np.array([0.001 * i, -0.0005, 0.0002]),
                                _rotation_z(0.01 * i), frame)
        rig.clock.advance(0.01)
    rig.core.move_joints(lease, np.array([0.01, -0.02, 0, 0, 0, 0.03]))
    info = rig.core.recordings.stop()
    assert info.command_count == 7 and info.format == format
    return rig.core.recordings.load(name)[1]


def _assert_same(commands, others) -> None:
    assert len(commands) == len(others)
    for a, b in zip(commands, others, strict=True):
        assert a.frame == b.frame
        assert a.offset_s == pytest.approx(b.offset_s, abs=1e-9)  # Duration: whole ns
        for field in ("delta_position_m", "delta_rotation", "target_position_m"):
            np.testing.assert_array_equal(getattr(a, field), getattr(b, field))
        assert (a.delta_joints_rad is None) == (b.delta_joints_rad is None)
        if a.delta_joints_rad is not None:
            np.testing.assert_array_equal(a.delta_joints_rad, b.delta_joints_rad)


def _replay(rig, name: str) -> list:
    """Replays `name` to the end on the fake clock; the arm commands it sent."""
    before = len(rig.slave.commands)
    events = rig.core.events.subscribe(256)
    rig.core.start_replay(rig.lease.lease_id, name, 1.0)
    finished = []

    def done() -> bool:
        while (event := events.get(0)) is not None:
            if getattr(event.payload, "state", "") == "FINISHED":
                finished.append(event.payload)
        rig.clock.advance(0.005)
        return bool(finished)

    wait_for(done, 5, "the replay to finish")
    return rig.slave.commands[before:]


def test_jsonl_converted_to_mcap_replays_the_same_increments(rig, tmp_path):
    recorded = _record_some(rig, "original")
    target, count = recording_convert.convert(tmp_path / "original.jsonl",
                                              tmp_path / "converted.mcap")
    assert count == 7
    info, converted = rig.core.recordings.load("converted")
    assert info.format == "MCAP" and info.command_count == 7
    _assert_same(recorded, converted)
    back, _ = recording_convert.convert(target, tmp_path / "back.jsonl")
    _assert_same(recorded, rig.core.recordings.load("back")[1])

    sent = _replay(rig, "converted")
    assert [c.kind for c in sent] == ["cartesian"] * 6 + ["joints"]
    for command, replayed in zip(recorded, sent, strict=True):
        if command.delta_joints_rad is None:
            frame, delta = replayed.detail
            assert frame == command.frame
            np.testing.assert_array_equal(delta, command.delta_position_m)
        else:
            np.testing.assert_array_equal(replayed.detail, command.delta_joints_rad)


def test_an_mcap_recording_replays_like_its_jsonl_twin(rig):
    as_jsonl = _record_some(rig, "twin_jsonl")
    rig.core.reset(rig.lease.lease_id)
    as_mcap = _record_some(rig, "twin_mcap", "MCAP")
    assert [c.frame for c in as_mcap] == [c.frame for c in as_jsonl]
    sent = _replay(rig, "twin_mcap")
    assert len(sent) == 7
    names = {(i.name, i.format) for i in rig.core.recordings.list()}
    assert names == {("twin_jsonl", "JSONL"), ("twin_mcap", "MCAP")}


def test_a_truncated_or_corrupt_mcap_file_is_refused_clearly(rig, tmp_path):
    _record_some(rig, "whole", "MCAP")
    data = (tmp_path / "whole.mcap").read_bytes()
    cuts = {"end": data[:-10], "half": data[:len(data) // 2], "magic": data[:5]}
    flipped = bytearray(data)
    flipped[len(data) // 2] ^= 0xFF
    cuts["flipped"] = bytes(flipped)
    for name, content in cuts.items():
        (tmp_path / f"{name}.mcap").write_bytes(content)
        with pytest.raises(FailedPreconditionError, match=f"{name}.mcap cannot be read") as error:
            rig.core.start_replay(rig.lease.lease_id, name, 1.0)
        assert error.value.reason == "CORRUPT_RECORDING"
    listed = {i.name: i for i in rig.core.recordings.list()}
    assert "truncated" in listed["half"].error and listed["whole"].error == ""
    (tmp_path / "bad.jsonl").write_text('{"name": "bad"}\n{"offset_s": 0}\n')
    with pytest.raises(FailedPreconditionError, match="bad.jsonl cannot be read"):
        rig.core.start_replay(rig.lease.lease_id, "bad", 1.0)


def test_a_recording_whose_file_cannot_be_written_stops_and_commands_go_on(rig, tmp_path):
    """A full disk (the partial file is /dev/full): the recording stops with the reason, an
    event says so at once, the commands keep being applied, and StopRecording says what
    happened, once."""
    (tmp_path / "full.mcap.partial").symlink_to("/dev/full")
    lease = rig.lease.lease_id
    events = rig.core.events.subscribe(1024)
    rig.core.start_recording(lease, "full", "MCAP")

    def stopped() -> bool:
        rig.core.move_cartesian(lease, np.array([0.0, 0.0, 0.0005]), np.eye(3), "BASE")
        rig.clock.advance(recording_mcap.SAMPLE_PERIOD_S)  # the writer flushes each period
        return not rig.core.recordings.recording

    wait_for(stopped, 5, "the recording to stop by itself")
    failed = []

    def failures_seen() -> list:
        while (event := events.get(0)) is not None:
            message = event_to_proto(event, rig.clock)  # as StreamEvents sends it
            if message.WhichOneof("event") == "recording_failed":
                failed.append(message.recording_failed)
        return failed

    wait_for(failures_seen, 5, "the recording_failed event")
    assert [event.name for event in failed] == ["full"]
    assert "No space left on device" in failed[0].reason
    moves = rig.moves()
    rig.core.move_cartesian(lease, np.array([0.0, 0.0, 0.0005]), np.eye(3), "BASE")
    assert rig.moves() == moves + 1
    with pytest.raises(FailedPreconditionError, match="No space left on device") as error:
        rig.core.recordings.stop()
    assert error.value.reason == "RECORDING_FAILED"
    with pytest.raises(FailedPreconditionError, match="not recording"):
        rig.core.recordings.stop()
    assert not (tmp_path / "full.mcap").exists()
    assert not (tmp_path / "full.mcap.partial").exists()  # the partial file is gone
    rig.core.start_recording(lease, "after", "MCAP")  # the next recording starts afresh
    rig.core.move_cartesian(lease, np.array([0.0, 0.0, 0.0005]), np.eye(3), "BASE")
    assert rig.core.recordings.stop().command_count == 1


def test_the_converter_refuses_bad_files_with_status_2_and_no_traceback(tmp_path, capsys):
    (tmp_path / "junk.jsonl").write_text("not json\n")
    (tmp_path / "junk.mcap").write_bytes(b"\x89MCAP0\r\n" + b"\x00" * 7)
    (tmp_path / "notes.txt").write_text("x")
    for argv in (["junk.jsonl"], ["junk.mcap"], ["notes.txt"], ["missing.jsonl"]):
        assert recording_convert.main([str(tmp_path / a) for a in argv]) == 2
        err = capsys.readouterr().err
        assert err.startswith("error: ") and "Traceback" not in err
    (tmp_path / "ok.jsonl").write_text('{"name": "ok", "create_time_ns": 5}\n')
    assert recording_convert.main([str(tmp_path / "ok.jsonl")]) == 0
    assert recording_convert.main([str(tmp_path / "ok.jsonl")]) == 2  # never overwritten
    assert "exists" in capsys.readouterr().err
    assert RecordingStore(tmp_path).load("ok")[0].command_count == 0


# -- the servicer --------------------------------------------------------------------------

def _read(path: Path) -> dict[str, list]:
    """Every message of an MCAP file by topic: (log time, decoded message)."""
    by_topic: dict[str, list] = defaultdict(list)
    with open(path, "rb") as stream:
        reader = make_reader(stream, decoder_factories=[DecoderFactory()])
        for _, channel, message, decoded in reader.iter_decoded_messages(log_time_order=False):
            by_topic[channel.topic].append((message.log_time, decoded))
    return by_topic


def test_start_recording_takes_a_format_and_the_file_holds_every_channel(fake_station,
                                                                          tmp_path):
    station, slave = fake_station
    lease, metadata = station.acquire()
    with pytest.raises(grpc.RpcError) as error:
        station.decisions.StartRecording(pb.StartRecordingRequest(name="x", format=7),
                                         metadata=metadata)
    assert error.value.code() is grpc.StatusCode.INVALID_ARGUMENT
    started = station.decisions.StartRecording(pb.StartRecordingRequest(
        name="session", format=pb.RECORDING_FORMAT_MCAP), metadata=metadata).recording
    assert started.format == pb.RECORDING_FORMAT_MCAP
    operator = Operator(station, lease)
    for _ in range(5):
        assert operator.move((0, 0, 0.002)).outcome == pb.COMMAND_OUTCOME_APPLIED
        slave.step(0.01)  # a state and a wrench sample
    station.decisions.SetAssistance(pb.SetAssistanceRequest(assistance=pb.AssistanceConfig(
        scaling=pb.Scaling(translation_scale=0.5))), metadata=metadata)
    operator.move((0, 0, 0.002))
    operator.close()
    saved = station.decisions.StopRecording(pb.StopRecordingRequest(),
                                            metadata=metadata).recording
    assert saved.command_count == 6 and saved.format == pb.RECORDING_FORMAT_MCAP

    contents = _read(station.core.recordings.directory / "session.mcap")
    assert set(contents) == set(recording_mcap.CHANNELS)
    assert len(contents[recording_mcap.INCREMENT]) == 6
    assert [a.sequence for _, a in contents[recording_mcap.ACK]] == [1, 2, 3, 4, 5, 6]
    kinds = [e.WhichOneof("event") for _, e in contents[recording_mcap.EVENTS]]
    assert "assistance_changed" in kinds and "teleop_session" in kinds
    assert contents[recording_mcap.STATE][0][1].status in (types_pb2.ROBOT_STATUS_READY,
                                                          types_pb2.ROBOT_STATUS_MOVING)
    listed = station.decisions.ListRecordings(pb.ListRecordingsRequest()).recordings
    assert [(r.name, r.format, r.command_count) for r in listed] == [
        ("session", pb.RECORDING_FORMAT_MCAP, 6)]
    with pytest.raises(grpc.RpcError) as error:  # one name, whatever the format
        station.decisions.StartRecording(pb.StartRecordingRequest(name="session"),
                                         metadata=metadata)
    assert error.value.code() is grpc.StatusCode.ALREADY_EXISTS


def test_the_arms_routine_events_are_left_to_the_recordings_state_samples(fake_station):
    station, slave = fake_station
    _, metadata = station.acquire()
    station.decisions.StartRecording(pb.StartRecordingRequest(
        name="events", format=pb.RECORDING_FORMAT_MCAP), metadata=metadata)

    def status(previous, now, reason=""):
        return pr_pb.StreamRobotEventsResponse(status_changed=pr_pb.StatusChangedEvent(
            previous_status=previous, status=now, reason=reason))

    ready, moving = types_pb2.ROBOT_STATUS_READY, types_pb2.ROBOT_STATUS_MOVING
    for event in (status(ready, moving), pr_pb.StreamRobotEventsResponse(moved=pr_pb.MovedEvent()),
                  status(moving, ready),
                  pr_pb.StreamRobotEventsResponse(data_received=pr_pb.DataReceivedEvent()),
                  status(moving, types_pb2.ROBOT_STATUS_ESTOPPED, "stopped"),
                  pr_pb.StreamRobotEventsResponse(error=pr_pb.RobotErrorEvent(reason="X"))):
        slave.on_robot_event(event)
    station.decisions.StopRecording(pb.StopRecordingRequest(), metadata=metadata)

    robot = [e.robot for _, e in _read(station.core.recordings.directory / "events.mcap")[
        recording_mcap.EVENTS] if e.WhichOneof("event") == "robot"]
    assert [(r.WhichOneof("event"), r.status_changed.status) for r in robot] == [
        ("status_changed", types_pb2.ROBOT_STATUS_ESTOPPED), ("error", 0)]


def test_replaying_a_truncated_mcap_file_is_failed_precondition(fake_station):
    station, _ = fake_station
    _, metadata = station.acquire()
    path = station.core.recordings.directory / "cut.mcap"
    station.decisions.StartRecording(pb.StartRecordingRequest(
        name="cut", format=pb.RECORDING_FORMAT_MCAP), metadata=metadata)
    station.decisions.StopRecording(pb.StopRecordingRequest(), metadata=metadata)
    path.write_bytes(path.read_bytes()[:-30])
    with pytest.raises(grpc.RpcError) as error:
        station.decisions.StartReplay(pb.StartReplayRequest(name="cut"), metadata=metadata)
    assert error.value.code() is grpc.StatusCode.FAILED_PRECONDITION
    assert "cut.mcap cannot be read" in error.value.details()
    listed = station.decisions.ListRecordings(pb.ListRecordingsRequest()).recordings
    assert listed[0].name == "cut" and "truncated" in listed[0].error


# -- end to end: the real DecisionServer, world, ProxyRobot and ForceSensor ----------------

@pytest.fixture
def driven(station):
    lease, metadata = station.acquire()
    station.ready_at_home(metadata)
    return station, lease, metadata


@pytest.mark.e2e
def test_an_mcap_recording_of_a_session_reads_back_and_replays_the_recorded_path(driven):
    station, lease, metadata = driven
    station.sensor.StartReading(force_sensor_pb2.StartReadingRequest(), metadata=metadata)
    station.decisions.StartRecording(pb.StartRecordingRequest(
        name="square", format=pb.RECORDING_FORMAT_MCAP), metadata=metadata)
    operator = Operator(station, lease)
    strokes = [(0.004, 0, 0)] * 5 + [(0, 0.004, 0)] * 5 + [(0, 0, 0.004)] * 5
    for i, dx in enumerate(strokes):
        assert operator.move(dx).outcome == pb.COMMAND_OUTCOME_APPLIED
        station.wait_status(types_pb2.ROBOT_STATUS_READY)  # one stroke at a time
        if i == 7:  # an assistance change mid-recording (scale 1: the path is unchanged)
            station.decisions.SetAssistance(pb.SetAssistanceRequest(
                assistance=pb.AssistanceConfig(scaling=pb.Scaling(translation_scale=1.0))),
                metadata=metadata)
    operator.close()
    recording = station.decisions.StopRecording(pb.StopRecordingRequest(),
                                                metadata=metadata).recording
    assert recording.command_count == 15 and recording.format == pb.RECORDING_FORMAT_MCAP
    recorded_end = station.tool_position()

    path = station.core.recordings.directory / "square.mcap"
    contents = _read(path)
    assert set(contents) == set(recording_mcap.CHANNELS), sorted(contents)
    assert len(contents[recording_mcap.INCREMENT]) == recording.command_count
    for topic, messages in contents.items():
        times = [t for t, _ in messages]
        assert times == sorted(times), f"{topic}: log times go back"
    acks = Counter(a.outcome for _, a in contents[recording_mcap.ACK] if a.sequence)
    assert acks[pb.COMMAND_OUTCOME_APPLIED] == 15
    kinds = [e.WhichOneof("event") for _, e in contents[recording_mcap.EVENTS]]
    assert "assistance_changed" in kinds and "data_received" not in str(kinds)
    states = contents[recording_mcap.STATE]
    span_s = (states[-1][0] - states[0][0]) / 1e9
    assert len(states) >= 10 and len(states) <= span_s / recording_mcap.SAMPLE_PERIOD_S + 2
    assert len(contents[recording_mcap.WRENCH]) >= 10
    targets = [np.array([m.target_position_m.x, m.target_position_m.y, m.target_position_m.z])
               for _, m in contents[recording_mcap.INCREMENT]]
    np.testing.assert_allclose(targets[-1], recorded_end, atol=1e-3)
    with open(path, "rb") as stream:
        summary = make_reader(stream).get_summary()
    assert sum(summary.statistics.channel_message_counts.values()) == sum(
        len(m) for m in contents.values())

    station.ready_at_home(metadata)  # back to the start, then replay the MCAP file
    events = station.core.events.subscribe(256)
    station.decisions.StartReplay(pb.StartReplayRequest(name="square"), metadata=metadata)
    reached, finished = [], None
    deadline = time.monotonic() + 10
    while time.monotonic() < deadline and finished is None:
        event = events.get(0.01)
        reached.append(station.tool_position())
        if event is not None and getattr(event.payload, "state", "") == "FINISHED":
            finished = event.payload
    assert finished is not None and finished.replayed == 15
    wait_for(lambda: np.linalg.norm(station.tool_position() - recorded_end) < 1e-3, 3,
             "the replay to end where the recording did")
    # The arm passed by every recorded target on its way.
    reached.append(station.tool_position())
    misses = [min(np.linalg.norm(p - t) for p in reached) for t in targets]
    assert max(misses) < 2e-3, misses


@pytest.mark.e2e
def test_the_readme_buf_curl_calls_record_in_mcap_and_replay(driven):
    """README, Record and replay: the same calls, through buf curl and server reflection."""
    station, lease, _ = driven
    url = f"http://{station.address}/telerobot.v1.DecisionServer"

    def curl(method: str, body: dict, lease_id: str | None = None) -> dict:
        header = ["-H", f"telerobot-lease-id: {lease_id}"] if lease_id else []
        done = subprocess.run([BUF, "curl", "--protocol", "grpc", "--http2-prior-knowledge",
                               *header, "-d", json.dumps(body), f"{url}/{method}"],
                              capture_output=True, text=True, timeout=30)
        assert done.returncode == 0, done.stdout + done.stderr
        return json.loads(done.stdout)

    started = curl("StartRecording", {"name": "drive2", "format": "RECORDING_FORMAT_MCAP"},
                   lease)
    assert started["recording"]["format"] == "RECORDING_FORMAT_MCAP"
    operator = Operator(station, lease)
    for _ in range(3):
        operator.move((0, 0, 0.002))
        station.wait_status(types_pb2.ROBOT_STATUS_READY)
    operator.close()
    saved = curl("StopRecording", {}, lease)["recording"]
    assert saved["name"] == "drive2" and saved["commandCount"] == 3
    assert saved["format"] == "RECORDING_FORMAT_MCAP"
    events = station.core.events.subscribe(256)
    curl("StartReplay", {"name": "drive2", "speed": 1}, lease)
    wait_for(lambda: (event := events.get(0.1)) is not None
             and getattr(event.payload, "state", "") == "FINISHED", 5, "the replay to finish")


class FakeCamera(sc_grpc.StereoCameraServicer):
    """A StereoCamera whose first StreamPairs sends a header and `frames` pairs (the first
    ones not key frames) and ends; the calls after it send nothing until cancelled. Its
    second call (`fed`) means the recording's feed took every pair of the first."""

    def __init__(self, frames: int = 6, first_key: int = 2):
        self.frames, self.first_key = frames, first_key
        self.calls = 0
        self.fed = threading.Event()
        self.cancelled = threading.Event()

    def StreamPairs(self, request, context):
        self.calls += 1
        if self.calls > 1:
            self.fed.set()
            context.add_callback(self.cancelled.set)
            self.cancelled.wait(10)
            return
        yield sc_pb.StreamPairsResponse(header=sc_pb.StereoHeader(
            width_px=4, height_px=2, encoding=sc_pb.IMAGE_ENCODING_H264))
        for k in range(self.frames):
            pair = sc_pb.StereoPair(sequence=k + 1, video_frame=b"\x00\x00\x01" + bytes([k]),
                                    keyframe=k == self.first_key)
            pair.left_capture_time.FromNanoseconds(1_000_000_000 + k * 33_000_000)
            yield sc_pb.StreamPairsResponse(pair=pair)


@pytest.fixture
def camera() -> Iterator[tuple[FakeCamera, CameraSource]]:
    """A FakeCamera served in this process, and the CameraSource that reaches it."""
    fake = FakeCamera()
    server = grpc.server(futures.ThreadPoolExecutor(max_workers=4))
    sc_grpc.add_StereoCameraServicer_to_server(fake, server)
    port = server.add_insecure_port("127.0.0.1:0")
    server.start()
    yield fake, CameraSource(f"127.0.0.1:{port}", None, 320, 240, 1000)
    server.stop(0)


def test_an_episode_keeps_its_task_outcome_and_video(rig, camera):
    fake, rig.core.camera = camera
    lease = rig.lease.lease_id
    started = rig.core.start_recording(lease, "episode-1", "MCAP", "insert the peg")
    assert started.task == "insert the peg"
    assert fake.fed.wait(10)
    rig.core.move_cartesian(lease, np.array([0.001, 0.0, 0.0]), np.eye(3), "BASE")
    saved = rig.core.stop_recording(lease, "FAILED")
    assert fake.cancelled.wait(5)  # the feed ends with the file
    assert (saved.task, saved.outcome, saved.video_frames) == ("insert the peg", "FAILED", 4)
    assert rig.core.recordings.info("episode-1") == saved.__class__(
        "episode-1", saved.create_time_ns, saved.duration_s, 1, "MCAP", "", "insert the peg",
        "FAILED", 4)
    path = rig.core.recordings.directory / "episode-1.mcap"
    assert recording_mcap.read_summary(path)["robot"] == "puma560"  # the arm's name
    contents = _read(path)
    assert len(contents[recording_mcap.STEREO_HEADER]) == 1
    video = contents[recording_mcap.STEREO_VIDEO]
    # from the first key frame on, each at its capture time, as it came
    assert [bytes(v.data)[-1] for _, v in video] == [2, 3, 4, 5]
    assert [v.timestamp.ToNanoseconds() for _, v in video] == [
        1_000_000_000 + k * 33_000_000 for k in (2, 3, 4, 5)]
    assert all(v.format == "h264" for _, v in video)


def test_an_episode_whose_arm_cannot_say_its_name_records_without_it(rig):
    lease = rig.lease.lease_id
    def unreachable() -> str:
        raise UnavailableError("ProxyRobot is down")

    rig.slave.arm_name = unreachable
    rig.core.start_recording(lease, "episode-2", "MCAP", "wipe")
    rig.core.stop_recording(lease, "SUCCEEDED")
    summary = recording_mcap.read_summary(rig.core.recordings.directory / "episode-2.mcap")
    assert summary["task"] == "wipe" and "robot" not in summary


def test_a_task_is_refused_without_mcap_or_when_it_is_not_a_label(rig):
    from wire.errors import InvalidArgumentError

    lease = rig.lease.lease_id
    for task, format, reason in (("insert the peg", "JSONL", "TASK_NEEDS_MCAP"),
                                 ("x" * 257, "MCAP", "BAD_TASK"), ("a\nb", "MCAP", "BAD_TASK"),
                                 ("   ", "MCAP", "BAD_TASK")):
        with pytest.raises(InvalidArgumentError) as error:
            rig.core.start_recording(lease, "refused", format, task)
        assert error.value.reason == reason
    assert not rig.core.recordings.recording  # nothing half-started


def test_an_episode_over_the_wire_takes_its_outcome_and_refuses_a_bad_one(fake_station):
    station, _ = fake_station
    _, metadata = station.acquire()
    started = station.decisions.StartRecording(pb.StartRecordingRequest(
        name="ep", format=pb.RECORDING_FORMAT_MCAP, task="wipe"), metadata=metadata).recording
    assert started.task == "wipe"
    with pytest.raises(grpc.RpcError) as error:
        station.decisions.StopRecording(pb.StopRecordingRequest(outcome=42), metadata=metadata)
    assert error.value.code() is grpc.StatusCode.INVALID_ARGUMENT
    assert "EPISODE_OUTCOME_SUCCEEDED" in error.value.details()
    saved = station.decisions.StopRecording(pb.StopRecordingRequest(
        outcome=pb.EPISODE_OUTCOME_DISCARDED), metadata=metadata).recording
    assert (saved.task, saved.outcome) == ("wipe", pb.EPISODE_OUTCOME_DISCARDED)
    with pytest.raises(grpc.RpcError) as error:
        station.decisions.StartRecording(pb.StartRecordingRequest(name="j", task="wipe"),
                                         metadata=metadata)
    assert error.value.code() is grpc.StatusCode.INVALID_ARGUMENT


def _increment(offset_s: float, dz: float, **fields) -> pb.RecordedIncrement:
    from wire import convert

    return pb.RecordedIncrement(offset=convert.duration(offset_s),
                                frame=types_pb2.REFERENCE_FRAME_BASE,
                                delta_position_m=types_pb2.Vector3(z=dz), **fields)


def test_a_replay_of_increments_sent_with_the_request(rig):
    """What replay_dataset sends: the increments themselves, each at its offset."""
    from services.decision_server.servicer import inline_increments

    commands = inline_increments([_increment(k * 0.01, 0.001) for k in range(5)])
    info = rig.core.start_replay(rig.lease.lease_id, "dataset-episode-0", 1.0, commands)
    assert (info.name, info.command_count, info.format) == ("dataset-episode-0", 5,
                                                             "UNSPECIFIED")
    for _ in range(10):
        rig.clock.advance(0.01)
    wait_for(lambda: len(rig.slave.commands) == 5, timeout_s=5, what="the five increments")
    assert [c.detail[0] for c in rig.slave.commands] == ["BASE"] * 5
    assert sum(c.detail[1][2] for c in rig.slave.commands) == pytest.approx(0.005)


@pytest.mark.parametrize("increments, message", [
    ([_increment(0.0, 0.001, delta_joints_rad=[0.1] * 6)], "joint increment"),
    ([_increment(0.02, 0.001), _increment(0.01, 0.001)], "goes back"),
    ([_increment(0.0, float("nan"))], "not finite"),
    ([_increment(0.0, 0.001, delta_rotation=types_pb2.Matrix3(row_major=[2] * 9))],
     "not a rotation"),
    ([pb.RecordedIncrement()], "no frame"),
])
def test_increments_sent_with_a_replay_are_checked(fake_station, increments, message):
    station, _ = fake_station
    _, metadata = station.acquire()
    with pytest.raises(grpc.RpcError) as error:
        station.decisions.StartReplay(pb.StartReplayRequest(name="x", increments=increments),
                                      metadata=metadata)
    assert error.value.code() is grpc.StatusCode.INVALID_ARGUMENT
    assert message in error.value.details()
