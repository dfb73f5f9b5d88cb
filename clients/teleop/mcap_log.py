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
- ``/camera/stereo_pair``  StereoPair, the pairs as they came (JPEG bytes, capture times)
- ``/decision_server/events``  StreamEventsResponse, the DecisionServer's events (control,
  watchdog holds, assistance changes, teleop session states, dependency changes)

A metadata record ``teleop`` holds the counts written per channel, and one ``run`` per task run
(its mode and time range). `python -m clients.teleop.mcap_inspect FILE` summarizes a file.

Every hook is safe to call from any thread (the task's, the ack reader's, the video's).
"""

from __future__ import annotations

import json
import logging
import threading
import time
from collections import Counter
from pathlib import Path

from mcap_protobuf.writer import Writer

from clients.python.values import Ack, StereoFrame
from telerobot.v1 import decision_server_pb2 as pb
from telerobot.v1 import stereo_camera_pb2 as sc_pb
from wire.convert import time_ns

log = logging.getLogger(__name__)

COMMAND = "/teleop/command"
HEARTBEAT = "/teleop/heartbeat"
ACK = "/teleop/ack"
TOOL_POSE = "/robot/tool_pose"
WRENCH = "/robot/wrench"
STEREO_HEADER = "/camera/stereo_header"
STEREO_PAIR = "/camera/stereo_pair"
EVENTS = "/decision_server/events"
CHANNELS = (COMMAND, HEARTBEAT, ACK, TOOL_POSE, WRENCH, STEREO_HEADER, STEREO_PAIR, EVENTS)
PROFILE = "telerobot"


class SessionRecorder:
    """Writes a session's messages into one MCAP file until `close()`. A context manager."""

    def __init__(self, path: Path):
        self.path = Path(path)
        self._file = open(self.path, "wb")  # noqa: SIM115 - closed in close()
        self._writer = Writer(self._file, profile=PROFILE)
        self._lock = threading.Lock()
        self._last: dict[str, int] = {}  # topic -> last log time written
        self._header: sc_pb.StereoHeader | None = None
        self._runs: list[dict] = []
        self.counts: Counter[str] = Counter()
        self.closed = False
        self.error: str | None = None  # why the recording stopped early, if it did

    # -- the hooks ------------------------------------------------------------------------------
    def request(self, request: pb.TeleoperateRequest) -> None:
        """A TeleoperateRequest the session queued: its command or heartbeat."""
        kind = request.WhichOneof("message")
        if kind == "command":
            self.write(COMMAND, request.command, time_ns(request.command.send_time))
        elif kind == "heartbeat":
            self.write(HEARTBEAT, request.heartbeat, time_ns(request.heartbeat.send_time))

    def ack(self, ack: Ack) -> None:
        """An ack as the session delivered it, with the tool pose and wrench it carries."""
        now = ack.received_time_ns
        self.write(ACK, ack.message, now, ack.apply_time_ns or now)
        if ack.message.HasField("tool_pose"):
            self.write(TOOL_POSE, ack.message.tool_pose, now, ack.apply_time_ns or now)
        if ack.message.HasField("tool_wrench"):
            self.write(WRENCH, ack.message.tool_wrench, now, ack.apply_time_ns or now)

    def stereo(self, frame: StereoFrame, received_ns: int | None = None) -> None:
        """A stereo pair as it came from the camera (its header first when it is new);
        received now unless `received_ns` says when."""
        now = received_ns or time.time_ns()
        if frame.header != self._header:
            self._header = frame.header
            self.write(STEREO_HEADER, frame.header, now)
        self.write(STEREO_PAIR, frame.pair, now,
                   time_ns(frame.pair.left_capture_time) or now)

    def event(self, event: pb.StreamEventsResponse, received_ns: int | None = None) -> None:
        """One of the DecisionServer's events, as the station's event stream delivered it;
        received now unless `received_ns` says when."""
        now = received_ns or time.time_ns()
        self.write(EVENTS, event, now, time_ns(event.event_time) or now)

    def run(self, mode: str, start_ns: int, end_ns: int, **fields) -> None:
        """One task run (goes into the file's metadata when it closes)."""
        self._runs.append({"mode": mode, "start_ns": start_ns, "end_ns": end_ns, **fields})

    # -- writing --------------------------------------------------------------------------------
    def write(self, topic: str, message, log_time_ns: int, publish_time_ns: int | None = None
              ) -> None:
        """`message` on `topic` at `log_time_ns` (raised to the channel's last, so log times
        never go back on a channel, even when the wall clock does). Never raises: a failure
        (a full disk) stops the recording, says why once and leaves it in `error`; the
        session goes on."""
        with self._lock:
            if self.closed or self.error is not None:
                return
            log_time = max(int(log_time_ns), self._last.get(topic, 0))
            try:
                self._writer.write_message(topic, message, log_time=log_time,
                                           publish_time=int(publish_time_ns or log_time),
                                           sequence=self.counts[topic])
            except Exception as error:  # noqa: BLE001 - the hooks run on the session's threads
                self.error = f"{topic}: {error}"
                log.warning("the MCAP recording stopped (%s)", self.error)
                return
            self._last[topic] = log_time
            self.counts[topic] += 1

    def close(self) -> None:
        with self._lock:
            if self.closed:
                return
            self.closed = True
            try:
                self._writer.add_metadata("teleop", {
                    "counts": json.dumps(dict(self.counts)), "runs": json.dumps(self._runs),
                    "error": self.error or ""})
                self._writer.finish()
            finally:
                self._file.close()

    def __enter__(self) -> SessionRecorder:
        return self

    def __exit__(self, *exc) -> None:
        self.close()
