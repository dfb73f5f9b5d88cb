"""A `make teleop` session as one MCAP file (`--mcap`: runs/teleop-<time>/session.mcap), in the
project's own protobuf messages (telerobot.v1); each channel's schema is the message's file
descriptors (mcap-protobuf-support writes them), so any MCAP reader decodes it without gen/.

Channels (log time: the operator station's clock, in ns, when it sent or received the message;
monotonic per channel):

- ``/teleop/command``  MasterCommand, as sent (log time: its send_time)
- ``/teleop/heartbeat``  Heartbeat, as sent
- ``/teleop/ack``  CommandAck, every ack delivered (a command's once; heartbeats' with
  sequence 0); publish time: the server's apply time
- ``/robot/tool_pose``  Pose, the slave's measured tool pose carried by the acks (base frame)
- ``/robot/wrench``  Wrench, the wrench at the tool carried by the acks (tool axes)
- ``/camera/stereo_header``  StereoHeader, once per stream of pairs (calibration of both eyes)
- ``/camera/stereo_pair``  StereoPair, the pairs as they came (JPEG bytes or an H.264 frame,
  capture times)
- ``/decision_server/events``  StreamEventsResponse, the DecisionServer's events (control,
  watchdog holds, assistance changes, teleop session states, dependency changes); never the
  arm's state samples, which come on a stream of their own (`RobotStateFeed`) so their flood
  can neither crowd these out nor change what this channel's count means
- ``/robot/state``  RobotState, the arm's state samples (ProxyRobot's DATA_RECEIVED events as
  the DecisionServer forwards them, about 10 Hz); publish time: the sample time

And the same session in Foxglove's own schemas (wire.foxglove), so Foxglove or
Lichtblick shows it in stock panels (docs/foxglove_layout.json):

- ``/tf``  FrameTransforms, the arm's frames (base -> link1..link6 -> flange -> tool) from each
  /robot/state sample's joint angles, stamped with its sample time; the cameras' frames too
  once a stereo header has given their poses
- ``/joint_states``  JointStates, each /robot/state sample's joint angles and rates
- ``/force/arrow``  SceneUpdate, one per /robot/wrench: the force as an arrow in the tool frame
- ``/camera/{left,right}/image``  CompressedImage, one per stereo pair and eye (the same JPEG),
  when the stream is JPEG
- ``/camera/stereo/video``  CompressedVideo (format h264), when the stream is H.264: each pair's
  side-by-side access unit as it came (both eyes in one picture, the left eye in the left half),
  stamped with its capture time, frame ``camera_stereo``. It starts at a key frame: a stream's
  pairs before its first key frame are left out of it (a player cannot start elsewhere); they
  stay in /camera/stereo_pair
- ``/camera/{left,right}/calibration``  CameraCalibration, one per stereo pair and eye (so a
  player that seeks always has the calibration next to the image)

A metadata record ``teleop`` holds the counts written per channel, and one ``run`` per task run
(its mode and time range). `python -m clients.teleop.mcap_inspect FILE` summarizes a file.

Every hook is safe to call from any thread (the task's, the ack reader's, the video's) and
only queues: a thread of the recorder's own converts and writes, so recording costs the
session's threads a queue append (at 1 kHz, writing a wrench and its arrow on the receiving
thread took about 40 µs of each millisecond: bench `force_1000_mcap`).
"""

from __future__ import annotations

import json
import logging
import queue
import threading
import time
from collections import Counter
from pathlib import Path

from mcap_protobuf.writer import Writer

from clients.python.values import Ack, StereoFrame
from telerobot.v1 import decision_server_pb2 as pb
from telerobot.v1 import stereo_camera_pb2 as sc_pb
from telerobot.v1 import types_pb2
from wire import foxglove as fox
from wire.convert import time_ns
from wire.errors import TelerobotError

log = logging.getLogger(__name__)

COMMAND = "/teleop/command"
HEARTBEAT = "/teleop/heartbeat"
ACK = "/teleop/ack"
TOOL_POSE = "/robot/tool_pose"
WRENCH = fox.ROBOT_WRENCH
STEREO_HEADER = "/camera/stereo_header"
STEREO_PAIR = "/camera/stereo_pair"
STEREO_VIDEO = fox.STEREO_VIDEO
EVENTS = "/decision_server/events"
ROBOT_STATE = fox.ROBOT_STATE
CHANNELS = (COMMAND, HEARTBEAT, ACK, TOOL_POSE, WRENCH, STEREO_HEADER, STEREO_PAIR, EVENTS,
            ROBOT_STATE)
FOXGLOVE_CHANNELS = tuple(fox.FOXGLOVE_TOPICS)
PROFILE = "telerobot"
QUEUE_LIMIT = 50_000  # hooks waiting for the writer; past that it has fallen behind: stop


class SessionRecorder:
    """Writes a session's messages into one MCAP file until `close()`. A context manager.
    `counts` and `skipped` are final once closed."""

    def __init__(self, path: Path):
        self.path = Path(path)
        self._file = open(self.path, "wb")  # noqa: SIM115 - closed in close()
        self._writer = Writer(self._file, profile=PROFILE)
        self._lock = threading.Lock()  # closing
        self._last: dict[str, int] = {}  # topic -> last log time written
        self._header: sc_pb.StereoHeader | None = None
        self._video_keyed = False  # the video channel has had this stream's first key frame
        self._arm = fox.ArmTransforms()  # the writer thread's
        self._runs: list[dict] = []
        self.counts: Counter[str] = Counter()
        self.skipped: Counter[str] = Counter()  # Foxglove messages our messages had no form for
        self.closed = False
        self.error: str | None = None  # why the recording stopped early, if it did
        self._work: queue.SimpleQueue = queue.SimpleQueue()
        self._queued = 0  # approximate (no lock): only to notice a writer that fell behind
        self._writer_thread = threading.Thread(target=self._write_queued, name="mcap-writer",
                                               daemon=True)
        self._writer_thread.start()

    # -- the hooks ------------------------------------------------------------------------------
    def request(self, request: pb.TeleoperateRequest) -> None:
        """A TeleoperateRequest the session queued: its command or heartbeat."""
        self._submit(lambda: self._request(request))

    def _request(self, request: pb.TeleoperateRequest) -> None:
        kind = request.WhichOneof("message")
        if kind == "command":
            self._write(COMMAND, request.command, time_ns(request.command.send_time))
        elif kind == "heartbeat":
            self._write(HEARTBEAT, request.heartbeat, time_ns(request.heartbeat.send_time))

    def ack(self, ack: Ack) -> None:
        """An ack as the session delivered it, with the tool pose and wrench it carries."""
        self._submit(lambda: self._ack(ack))

    def _ack(self, ack: Ack) -> None:
        now = ack.received_time_ns
        applied = ack.apply_time_ns or now
        self._write(ACK, ack.message, now, applied)
        if ack.message.HasField("tool_pose"):
            self._write(TOOL_POSE, ack.message.tool_pose, now, applied)
        if ack.message.HasField("tool_wrench"):
            self._wrench(ack.message.tool_wrench, now, applied)

    def wrench(self, wrench: types_pb2.Wrench, received_ns: int, sampled_ns: int) -> None:
        """A wrench at the tool (/robot/wrench) and its force arrow (/force/arrow), received
        at `received_ns` (the log time), sampled or applied at `sampled_ns`."""
        self._submit(lambda: self._wrench(wrench, received_ns, sampled_ns))

    def _wrench(self, wrench: types_pb2.Wrench, received_ns: int, sampled_ns: int) -> None:
        self._write(WRENCH, wrench, received_ns, sampled_ns)
        self._foxglove(fox.FORCE_ARROW, lambda: fox.force_arrow(wrench, sampled_ns),
                       received_ns)

    def stereo(self, frame: StereoFrame, received_ns: int | None = None) -> None:
        """A stereo pair as it came from the camera (its header first when it is new);
        received now unless `received_ns` says when."""
        now = received_ns or time.time_ns()
        self._submit(lambda: self._stereo(frame, now))

    def _stereo(self, frame: StereoFrame, now: int) -> None:
        captured = time_ns(frame.pair.left_capture_time) or now
        if frame.header != self._header:
            self._header = frame.header
            self._video_keyed = False  # a new stream: its video starts at its first key frame
            self._arm.set_cameras(frame.header)
            self._write(STEREO_HEADER, frame.header, now)
        self._write(STEREO_PAIR, frame.pair, now, captured)
        if frame.header.encoding == sc_pb.IMAGE_ENCODING_H264:
            self._video_keyed |= frame.pair.keyframe
            if self._video_keyed:
                self._foxglove(STEREO_VIDEO, lambda: fox.stereo_video(frame.pair), now, captured)
            else:
                self.skipped[STEREO_VIDEO] += 1  # before the stream's first key frame
        else:
            images = self._convert(fox.LEFT_IMAGE, lambda: fox.camera_images(frame.pair))
            for topic, message in zip((fox.LEFT_IMAGE, fox.RIGHT_IMAGE), images or (),
                                      strict=False):
                self._write(topic, message, now, captured)
        calibrations = self._convert(fox.LEFT_CALIBRATION,
                                     lambda: fox.camera_calibrations(frame.header, captured))
        for topic, message in zip((fox.LEFT_CALIBRATION, fox.RIGHT_CALIBRATION),
                                  calibrations or (), strict=False):
            self._write(topic, message, now, captured)

    def event(self, event: pb.StreamEventsResponse, received_ns: int | None = None) -> None:
        """One of the DecisionServer's events, as the station's event stream delivered it;
        received now unless `received_ns` says when."""
        now = received_ns or time.time_ns()
        self.write(EVENTS, event, now, time_ns(event.event_time) or now)

    def robot_state(self, state: types_pb2.RobotState, received_ns: int | None = None) -> None:
        """One of the arm's state samples (/robot/state), with its frames (/tf) and joint
        angles (/joint_states); received now unless `received_ns` says when."""
        now = received_ns or time.time_ns()
        self._submit(lambda: self._robot_state(state, now))

    def _robot_state(self, state: types_pb2.RobotState, now: int) -> None:
        sampled = time_ns(state.sample_time) or now
        self._write(ROBOT_STATE, state, now, sampled)
        self._foxglove(fox.JOINT_STATES, lambda: fox.joint_states(state), now, sampled)
        self._foxglove(fox.TF, lambda: self._arm.state_transforms(state), now, sampled)

    def run(self, mode: str, start_ns: int, end_ns: int, **fields) -> None:
        """One task run (goes into the file's metadata when it closes)."""
        self._runs.append({"mode": mode, "start_ns": start_ns, "end_ns": end_ns, **fields})

    def write(self, topic: str, message, log_time_ns: int, publish_time_ns: int | None = None
              ) -> None:
        """`message` on `topic` at `log_time_ns` (see _write)."""
        self._submit(lambda: self._write(topic, message, log_time_ns, publish_time_ns))

    # -- the writer thread ----------------------------------------------------------------------
    def _submit(self, work) -> None:
        if self.closed or self.error is not None:
            return
        if self._queued >= QUEUE_LIMIT:
            self._stop(f"the writer fell {QUEUE_LIMIT} messages behind the session")
            return
        self._queued += 1
        self._work.put(work)

    def _write_queued(self) -> None:
        while (work := self._work.get()) is not None:
            self._queued -= 1
            if self.error is not None:
                continue
            try:
                work()
            except Exception as error:  # noqa: BLE001 - it ends the recording, not the session
                self._stop(f"{type(error).__name__}: {error}")

    def _stop(self, error: str) -> None:
        """The recording stops here (said once); the session goes on."""
        if self.error is None:
            self.error = error
            log.warning("the MCAP recording stopped (%s)", error)

    def _convert(self, topic: str, convert):
        """`convert()`, or None when our message has no Foxglove form (raw images, a state with
        the wrong number of joints): counted in `skipped`, said once per topic."""
        try:
            return convert()
        except ValueError as error:
            if not self.skipped[topic]:
                log.warning("MCAP: %s left out (%s)", topic, error)
            self.skipped[topic] += 1
            return None

    def _foxglove(self, topic: str, convert, log_time_ns: int,
                  publish_time_ns: int | None = None) -> None:
        message = self._convert(topic, convert)
        if message is not None:
            self._write(topic, message, log_time_ns, publish_time_ns)

    def _write(self, topic: str, message, log_time_ns: int, publish_time_ns: int | None = None
               ) -> None:
        """`message` on `topic` at `log_time_ns` (raised to the channel's last, so log times
        never go back on a channel, even when the wall clock does). Never raises: a failure
        (a full disk) stops the recording, says why once and leaves it in `error`."""
        if self.error is not None:
            return
        log_time = max(int(log_time_ns), self._last.get(topic, 0))
        try:
            self._writer.write_message(topic, message, log_time=log_time,
                                       publish_time=int(publish_time_ns or log_time),
                                       sequence=self.counts[topic])
        except Exception as error:  # noqa: BLE001 - a failure ends the recording, not the session
            self._stop(f"{topic}: {error}")
            return
        self._last[topic] = log_time
        self.counts[topic] += 1

    def close(self) -> None:
        """Write what is queued, then the metadata, and close the file."""
        with self._lock:
            if self.closed:
                return
            self.closed = True
            self._work.put(None)
            self._writer_thread.join()
            try:
                self._writer.add_metadata("teleop", {
                    "counts": json.dumps(dict(self.counts)), "runs": json.dumps(self._runs),
                    "foxglove_skipped": json.dumps(dict(self.skipped)),
                    "error": self.error or ""})
                self._writer.finish()
            finally:
                self._file.close()

    def __enter__(self) -> SessionRecorder:
        return self

    def __exit__(self, *exc) -> None:
        self.close()


class RobotStateFeed:
    """The arm's state samples for the recording: a DecisionServer event stream of its own with
    ``include_data_received``, on a thread, handing each DATA_RECEIVED sample to `on_state`
    (the other events come on the session's own stream, which leaves the samples out). From
    start() until stop()."""

    def __init__(self, client, on_state):
        self._client = client
        self._on_state = on_state
        self._events = None
        self._thread: threading.Thread | None = None
        self.samples = 0
        self.error: str | None = None  # why the feed ended early, if it did

    def start(self) -> RobotStateFeed:
        self._events = self._client.stream_events(include_data_received=True, timeout=None)
        self._thread = threading.Thread(target=self._read, name="mcap-robot-state", daemon=True)
        self._thread.start()
        return self

    def _read(self) -> None:
        try:
            for event in self._events:
                if (event.WhichOneof("event") == "robot"
                        and event.robot.WhichOneof("event") == "data_received"):
                    self._on_state(event.robot.data_received.state)
                    self.samples += 1
        except TelerobotError as error:  # (a stream cancelled by stop() just ends)
            self.error = str(error)
            log.warning("MCAP: the arm's state samples stopped (%s)", error)

    def stop(self) -> None:
        if self._events is not None:
            try:
                self._events.cancel()
            except Exception as error:  # noqa: BLE001 - stopping goes on regardless
                log.debug("cancel: %s", error)
        if self._thread is not None:
            self._thread.join(timeout=5.0)

    def __enter__(self) -> RobotStateFeed:
        return self.start()

    def __exit__(self, *exc) -> None:
        self.stop()
