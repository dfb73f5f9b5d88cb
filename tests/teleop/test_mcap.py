"""make teleop --mcap: the session as one MCAP file in the project's own protobuf messages.

A scripted sequence goes through the recorder and comes back through the `mcap` reader (with
mcap-protobuf-support's decoder, from the schemas in the file alone); then a real session
(`python -m clients.teleop --modes feedback --mcap`) against a local station leaves a file whose
counts are the session's own, in our channels and Foxglove's: its images decode to the
header's size and each /tf is Pinocchio's forward kinematics of the state sample it came
from. An H.264 stream, from a real in-process StereoCamera, is recorded as Foxglove's
CompressedVideo, which starts at a key frame and decodes (PyAV) to the stream's pictures."""

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
from domain.robot_model.kinematics import ArmKinematics
from services.launcher import STATION
from telerobot.v1 import decision_server_pb2 as pb
from telerobot.v1 import stereo_camera_pb2 as sc_pb
from telerobot.v1 import types_pb2
from tests.foxglove.test_channels import stereo_header, world_poses
from tests.processes import REPO, unique_shm_name
from wire import convert
from wire import foxglove as fox

T0 = 1_700_000_000_000_000_000  # a fixed wall-clock time, ns
MS = 1_000_000
ALL_CHANNELS = {*channels.CHANNELS, *channels.FOXGLOVE_CHANNELS}
# A session's camera channels depend on its stream's encoding: each eye's JPEG, or the video.
JPEG_CHANNELS = ALL_CHANNELS - {fox.STEREO_VIDEO}
H264_CHANNELS = ALL_CHANNELS - {fox.LEFT_IMAGE, fox.RIGHT_IMAGE}


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


def decode_video(read: dict[str, list]) -> list[np.ndarray]:
    """The /camera/stereo/video messages decoded in order (PyAV), as RGB pictures; the first
    must be a key frame, and every message must give one picture."""
    import av

    videos = [proto for *_, proto in read[fox.STEREO_VIDEO]]
    assert videos and fox.h264_is_keyframe(videos[0].data)
    decoder = av.CodecContext.create("h264", "r")
    pictures = []
    for video in videos:
        assert (video.format, video.frame_id) == ("h264", fox.STEREO_CAMERA_FRAME)
        (frame,) = decoder.decode(av.Packet(video.data))  # no B-frames: one out per one in
        pictures.append(frame.to_ndarray(format="rgb24"))
    return pictures


def check_the_video(read: dict[str, list], sizes: set[tuple[int, int]]) -> None:
    """An H.264 session: no per-eye images; the video decodes to pictures of both eyes side by
    side, each eye the size of the header and the calibration."""
    assert not read[fox.LEFT_IMAGE] and not read[fox.RIGHT_IMAGE]
    (*_, calibration) = read[fox.LEFT_CALIBRATION][0]
    for picture in decode_video(read):
        assert picture.shape[:2] in {(height, 2 * width) for height, width in sizes}
        assert picture.shape[:2] == (calibration.height, 2 * calibration.width)


def check_the_images(read: dict[str, list], sizes: set[tuple[int, int]]) -> None:
    """A JPEG session: no video; every image decodes to its calibration's size (the
    header's)."""
    assert not read[fox.STEREO_VIDEO]
    for image_topic, calibration_topic in ((fox.LEFT_IMAGE, fox.LEFT_CALIBRATION),
                                           (fox.RIGHT_IMAGE, fox.RIGHT_CALIBRATION)):
        assert len(read[image_topic]) == len(read[calibration_topic])
        for (*_, image), (*_, calibration) in zip(read[image_topic], read[calibration_topic],
                                                  strict=True):
            decoded = cv2.imdecode(np.frombuffer(image.data, np.uint8), cv2.IMREAD_COLOR)
            assert image.format == "jpeg" and decoded is not None
            assert decoded.shape[:2] == (calibration.height, calibration.width)
            assert decoded.shape[:2] in sizes
            assert calibration.K[0] > 0 and image.frame_id == calibration.frame_id


def check_the_foxglove_channels(read: dict[str, list]) -> None:
    """Every image (JPEG) or video frame (H.264, side by side) decodes to its calibration's
    size (the header's); each /tf is Pinocchio's forward kinematics of the /robot/state and
    /joint_states sample with the same stamp."""
    headers = [proto for *_, proto in read[channels.STEREO_HEADER]]
    sizes = {(h.height_px, h.width_px) for h in headers}
    for calibration_topic in (fox.LEFT_CALIBRATION, fox.RIGHT_CALIBRATION):
        assert len(read[calibration_topic]) == len(read[channels.STEREO_PAIR])
    if {h.encoding for h in headers} == {sc_pb.IMAGE_ENCODING_H264}:
        check_the_video(read, sizes)
    else:
        check_the_images(read, sizes)
    kinematics = ArmKinematics()
    states = {proto.sample_time.ToNanoseconds(): proto for *_, proto in read[channels.ROBOT_STATE]}
    joints = {proto.timestamp.ToNanoseconds(): proto for *_, proto in read[fox.JOINT_STATES]}
    assert len(states) == len(read[channels.ROBOT_STATE]) == len(read[fox.TF]) > 0
    for *_, tf in read[fox.TF]:
        stamp = tf.transforms[0].timestamp.ToNanoseconds()
        q = np.array(states[stamp].joint_positions_rad)
        assert [j.position for j in joints[stamp].joints] == pytest.approx(q.tolist())
        poses = world_poses(tf)
        for frame in fox.ArmTransforms(kinematics).link_frames:
            assert np.allclose(poses[frame].homogeneous,
                               kinematics.frame_pose(q, frame).homogeneous, atol=1e-9), frame
        assert np.allclose(poses[fox.FLANGE_FRAME].homogeneous,
                           kinematics.flange_pose(q).homogeneous, atol=1e-9)
        # The tool where the arm said it was (its own tool frame), to the wire's precision.
        tool = convert.pose_value(states[stamp].tool_pose)
        assert np.allclose(poses[fox.TOOL_FRAME].translation, tool.translation, atol=1e-9)
        assert np.allclose(poses[fox.TOOL_FRAME].rotation, tool.rotation, atol=1e-9)
        if headers and fox.LEFT_CAMERA_FRAME in poses:  # the eyes where the header put them
            eye = convert.pose_value(headers[0].left.camera_pose)
            assert np.allclose(poses[fox.LEFT_CAMERA_FRAME].translation, eye.translation)


def jpeg(value: int) -> bytes:
    image = np.full((24, 32, 3), value, dtype=np.uint8)
    return cv2.imencode(".jpg", image)[1].tobytes()


def scripted_session(recorder: SessionRecorder) -> dict[str, list]:
    """What a short session sends and receives, through the recorder's hooks; returns the
    protos written per topic, in order."""
    written = defaultdict(list)
    header = stereo_header(32, 24)  # the simulation's cameras, with their poses
    kinematics = ArmKinematics()
    event = pb.StreamEventsResponse(
        sequence=1, event_time=convert.timestamp(T0),
        teleop_session=pb.TeleopSessionEvent(session_id="s1", operator_id="teleop-script",
                                             state=pb.TELEOP_SESSION_STATE_OPENED))
    recorder.event(event, T0)
    written[channels.EVENTS].append(event)
    for i in range(1, 6):
        sent = T0 + i * 20 * MS
        q = kinematics.home_q + 0.05 * i
        state = types_pb2.RobotState(
            sequence=i, sample_time=convert.timestamp(sent - MS), joint_positions_rad=q,
            joint_velocities_rad_per_s=[0.1 * i] * 6,
            flange_pose=convert.pose_to_proto(kinematics.flange_pose(q)),
            tool_pose=convert.pose_to_proto(kinematics.tool_pose(q)))
        recorder.robot_state(state, sent + MS)
        written[channels.ROBOT_STATE].append(state)
        written[fox.JOINT_STATES].append(fox.joint_states(state))
        tf = fox.ArmTransforms()
        if i > 1:  # the cameras' frames, once the header has come
            tf.set_cameras(header)
        written[fox.TF].append(tf.state_transforms(state))
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
        written[fox.FORCE_ARROW].append(fox.force_arrow(ack.tool_wrench, sent + 2 * MS))
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
        for topic, message in zip((fox.LEFT_IMAGE, fox.RIGHT_IMAGE,
                                   fox.LEFT_CALIBRATION, fox.RIGHT_CALIBRATION),
                                  (*fox.camera_images(pair),
                                   *fox.camera_calibrations(header, sent)), strict=True):
            written[topic].append(message)
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
    assert set(read) == JPEG_CHANNELS == set(written)
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
    check_the_foxglove_channels(read)
    # Foxglove's force arrow: the wrench's force, 0.01 m per newton, pointing down (-z tool).
    arrows = [update.entities[0].arrows[0] for *_, update in read[fox.FORCE_ARROW]]
    assert [a.shaft_length + a.head_length for a in arrows] == pytest.approx(
        [fox.FORCE_ARROW_M_PER_N * i for i in range(1, 6)])

    summary = mcap_inspect.summarize(path)
    assert {c.topic: c.count for c in summary.channels} == dict(recorder.counts)
    assert summary.foxglove_topics == [t for t in fox.FOXGLOVE_TOPICS if t in JPEG_CHANNELS]
    assert summary.video is None
    assert ("base", "link1") in summary.tf_frames and ("flange", "tool") in summary.tf_frames
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
    for topic in JPEG_CHANNELS:
        assert topic in out
    assert "telerobot.v1.CommandAck" in out and f"{len(JPEG_CHANNELS)} channels" in out
    assert "foxglove.FrameTransforms" in out
    assert f"Foxglove channels: 7 of 8 (none on {fox.STEREO_VIDEO})" in out
    assert "link5->link6" in out
    (tmp_path / "junk.mcap").write_bytes(b"not an mcap file")
    assert mcap_inspect.main([str(tmp_path / "junk.mcap")]) == 2
    assert "cannot read" in capsys.readouterr().err


def test_an_h264_stream_is_recorded_as_compressed_video_that_starts_at_a_key_frame(tmp_path):
    """A real in-process StereoCamera (the pattern source) streams H.264 to the Python client
    (receipts, decoding), whose frames go to the recorder as make teleop's StereoView hands
    them; the file's video is the stream, frame for frame."""
    from clients.python.stereo_camera import StereoCameraClient
    from services.stereo_camera.pattern import PatternSource, pattern_image
    from services.stereo_camera.source import LEFT, RIGHT
    from tests.stereo_camera.conftest import psnr, start_camera

    width, height, pairs = 160, 120, 12
    camera = start_camera(PatternSource(width, height, fps=30))
    path = tmp_path / "session.mcap"
    frames = []
    try:
        with StereoCameraClient(camera.channel) as client, SessionRecorder(path) as recorder:
            stream = client.stream_pairs(encoding=sc_pb.IMAGE_ENCODING_H264, max_fps=15,
                                         timeout=30)
            try:
                for frame in stream:
                    recorder.stereo(frame, frame.received_ns)
                    frames.append(frame)
                    if len(frames) == pairs:
                        break
            finally:
                stream.cancel()
    finally:
        camera.close()
    assert frames[0].pair.keyframe and recorder.skipped[fox.STEREO_VIDEO] == 0

    read = read_back(path)
    assert set(read) == {channels.STEREO_HEADER, channels.STEREO_PAIR, fox.STEREO_VIDEO,
                         fox.LEFT_CALIBRATION, fox.RIGHT_CALIBRATION}
    assert {schema for _, _, schema, _ in read[fox.STEREO_VIDEO]} == {"foxglove.CompressedVideo"}
    assert len(read[fox.STEREO_VIDEO]) == len(read[channels.STEREO_PAIR]) == pairs
    videos = [video for *_, video in read[fox.STEREO_VIDEO]]
    assert {video.format for video in videos} == {"h264"}
    assert fox.h264_is_keyframe(videos[0].data)
    # Stamped with each pair's capture time; the same access units the camera sent.
    assert [v.timestamp.ToNanoseconds() for v in videos] == [
        f.pair.left_capture_time.ToNanoseconds() for f in frames]
    assert [v.data for v in videos] == [f.pair.video_frame for f in frames]
    check_the_foxglove_channels_of_the_camera(read)
    pictures = decode_video(read)
    assert [p.shape for p in pictures] == [(height, 2 * width, 3)] * pairs
    for picture, frame in zip(pictures, frames, strict=True):
        # What the operator's client decoded, and close to what the camera captured.
        assert np.array_equal(picture[:, :width], frame.left)
        assert np.array_equal(picture[:, width:], frame.right)
        assert psnr(picture[:, :width], pattern_image(frame.sequence, LEFT, width, height)) > 28
        assert psnr(picture[:, width:], pattern_image(frame.sequence, RIGHT, width, height)) > 28

    summary = mcap_inspect.summarize(path)
    assert summary.video.frames == pairs and summary.video.starts_at_keyframe
    assert summary.video.formats == {"h264"} and summary.video.keyframes >= 1
    assert f"video {fox.STEREO_VIDEO}: {pairs} frames (h264)" in mcap_inspect.report(summary)


def check_the_foxglove_channels_of_the_camera(read: dict[str, list]) -> None:
    headers = [proto for *_, proto in read[channels.STEREO_HEADER]]
    for calibration_topic in (fox.LEFT_CALIBRATION, fox.RIGHT_CALIBRATION):
        assert len(read[calibration_topic]) == len(read[channels.STEREO_PAIR])
    check_the_video(read, {(h.height_px, h.width_px) for h in headers})


def test_a_recording_that_joins_a_video_stream_mid_way_starts_at_its_next_key_frame(tmp_path):
    """A player cannot start at a delta frame: the pairs before the stream's first key frame
    stay in /camera/stereo_pair but not in the video, which then decodes from its start."""
    from services.stereo_camera.h264 import H264Encoder
    from services.stereo_camera.pattern import pattern_image
    from services.stereo_camera.source import LEFT, RIGHT

    width, height = 64, 48
    header = stereo_header(width, height)
    header.encoding = sc_pb.IMAGE_ENCODING_H264
    header.stream_id = "s1"
    encoder = H264Encoder(width, height, fps=10, kbit_per_s=300)
    path = tmp_path / "session.mcap"
    with SessionRecorder(path) as recorder:
        for i in range(6):
            data, key = encoder.encode(pattern_image(i, LEFT, width, height),
                                       pattern_image(i, RIGHT, width, height), keyframe=i == 3)
            pair = sc_pb.StereoPair(sequence=i, video_frame=data, keyframe=key,
                                    left_capture_time=convert.timestamp(T0 + i * 100 * MS))
            if i:  # the recording starts after the stream's first (key) frame
                recorder.stereo(StereoFrame(header, pair, None, None), T0 + i * 100 * MS + MS)
    read = read_back(path)
    assert [p.sequence for *_, p in read[channels.STEREO_PAIR]] == [1, 2, 3, 4, 5]
    assert [v.timestamp.ToNanoseconds() for *_, v in read[fox.STEREO_VIDEO]] == [
        T0 + i * 100 * MS for i in (3, 4, 5)]
    assert len(decode_video(read)) == 3
    assert recorder.skipped == {fox.STEREO_VIDEO: 2}
    assert len(read[fox.LEFT_CALIBRATION]) == 5
    assert "starts at a key frame" in mcap_inspect.report(mcap_inspect.summarize(path))


@pytest.mark.e2e
def test_make_teleop_mcap_counts_match_the_sessions_own(tmp_path):
    env = {f"TELEROBOT_{name.upper()}_ADDRESS": "127.0.0.1:0" for name in STATION}
    env["TELEROBOT_WORLD_SHM"] = unique_shm_name()
    out = tmp_path / "run"
    with local_station(env=env) as addresses:
        result = subprocess.run(
            [sys.executable, "-m", "clients.teleop", "--address",
             addresses["decision_server"], "--modes", "feedback", "--mcap",
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
    # Every channel, ours and Foxglove's, with the session's own counts: the recorder's (in
    # the summary and in the file's metadata), the feed's state samples, the video's frames.
    (header, *_) = [proto for *_, proto in read[channels.STEREO_HEADER]]
    expected = H264_CHANNELS if header.encoding == sc_pb.IMAGE_ENCODING_H264 else JPEG_CHANNELS
    assert set(read) == expected, expected ^ set(read)
    for topic, messages in read.items():
        times = [log_time for log_time, *_ in messages]
        assert times == sorted(times), topic
    counts = {topic: len(m) for topic, m in read.items()}
    assert summary["mcap_counts"] == counts and summary["mcap_error"] is None
    metadata = mcap_inspect.summarize(out / "session.mcap").metadata["teleop"]
    assert json.loads(metadata["counts"]) == counts
    assert json.loads(metadata["foxglove_skipped"]) == {}
    assert counts[channels.ROBOT_STATE] == summary["mcap_state_samples"] > 10, summary
    assert summary["mcap_state_feed_error"] is None
    assert counts[fox.TF] == counts[fox.JOINT_STATES] == counts[channels.ROBOT_STATE]
    assert counts[fox.FORCE_ARROW] == counts[channels.WRENCH]
    assert counts[channels.STEREO_PAIR] == summary["video_frames"] > 0, summary
    camera_topics = {fox.LEFT_IMAGE, fox.RIGHT_IMAGE, fox.STEREO_VIDEO} & expected
    for topic in (*camera_topics, fox.LEFT_CALIBRATION, fox.RIGHT_CALIBRATION):
        assert counts[topic] == counts[channels.STEREO_PAIR], topic
    # The events channel still holds no state samples (they have a stream of their own).
    assert not [e for *_, e in read[channels.EVENTS]
                if e.WhichOneof("event") == "robot"
                and e.robot.WhichOneof("event") == "data_received"]
    check_the_foxglove_channels(read)
    # The arm moved during the run, and /tf followed it.
    tool_heights = {round(world_poses(tf)[fox.TOOL_FRAME].translation[2], 4)
                    for *_, tf in read[fox.TF]}
    assert len(tool_heights) > 5, tool_heights
