"""The operator's stereo view: the camera's H.264 stream (paced to the link by receipts), the AR
ball where the station measured the gripper at each frame's capture time, into a side-by-side
video; what the stream delivers (fps, age, bitrate) for the status line and the summary. Runs
on its own thread while the task runs."""

from __future__ import annotations

import csv
import logging
import threading
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from clients.ar import (
    RobotModel,
    SideBySideComposer,
    StereoOverlay,
    identify_stereo,
    load_if_present,
    save_identification,
)
from clients.ar.adapters import projections_from_header
from clients.python.proxy_robot import ProxyRobotClient
from clients.python.stereo_camera import StereoCameraClient
from clients.python.values import StereoFrame
from clients.python.video_meter import VideoMeter
from clients.teleop.artifacts import VideoRecorder
from domain.robot_model import workspace
from telerobot.v1 import stereo_camera_pb2 as sc_pb
from wire.errors import TelerobotError, UnavailableError

log = logging.getLogger(__name__)

# What the operator station decodes, draws and records: the task's control loop shares this
# process and 2 cores with the station, and the full size at the camera's rate starved it. At
# this size the camera's rate (30 fps) leaves the task as it is at 10 fps (183 ms round trip:
# the same duration, depth and round trip), and the sim camera renders it without scaling
# once it is short of CPU (render_scale.py's half).
WIDTH_PX, HEIGHT_PX = 320, 240
MAX_FPS = 30.0
RESUME_AFTER_S = 0.5  # while the camera is away, try again this often
POSE_PERIOD_S = 0.02  # the arm's measured poses, for the ball, at 50 Hz
# Every frame shown, with where the ball went in each eye (pixels): the overlay can be checked
# against the arm's true pose at the capture time.
FRAMES_LOG = "stereo_frames.csv"
FRAMES_LOG_COLUMNS = ("sequence", "capture_ns", "received_ns", "left_u", "left_v", "right_u",
                      "right_v")


def reference_points(cell: workspace.WorkCell) -> np.ndarray:
    """Eight well-spread points around the fixture and the tool's path (base frame, m): the
    corners of a box from the table top to 5 cm above the home tool tip, for identifying the
    cameras."""
    x, y = cell.fixture_center_xy
    top = (cell.table_top_z + workspace.FIXTURE_HEIGHT + workspace.HOME_TIP_ABOVE_HOLE + 0.05)
    xs, ys, zs = (x - 0.08, x + 0.08), (y - 0.08, y + 0.08), (cell.table_top_z, top)
    return np.array([(a, b, c) for a in xs for b in ys for c in zs])


class MeasuredPoses:
    """The arm's measured tool poses, stamped by the station, into the RobotModel's history
    (`observe`), whatever moves the arm: ProxyRobot.StreamState on a thread of its own, opened
    again after a failure until stopped."""

    def __init__(self, robot: ProxyRobotClient, model: RobotModel, stop: threading.Event):
        self._robot = robot
        self._model = model
        self._stop = stop
        self._stream = None
        self._thread = threading.Thread(target=self._run, name="measured-poses", daemon=True)

    def start(self) -> None:
        self._thread.start()

    def join(self) -> None:
        if self._stream is not None:
            self._stream.cancel()
        self._thread.join(5)

    def _run(self) -> None:
        while not self._stop.is_set():
            try:
                self._stream = self._robot.stream_state(POSE_PERIOD_S)
                for state in self._stream:
                    self._model.observe(state.sample_time_ns, state.tool_pose)
            except TelerobotError as error:
                log.debug("measured poses paused: %s", error)
            self._stop.wait(RESUME_AFTER_S)


class StereoView:
    """Streams pairs, draws the ball where the station measured the tool at each pair's capture
    time, records video."""

    def __init__(self, camera: StereoCameraClient, robot: ProxyRobotClient, model: RobotModel,
                 out: Path, calibration_path: Path,
                 on_frame: Callable[[StereoFrame], Any] | None = None,
                 cell: workspace.WorkCell = workspace.PUMA560_CELL):
        self._camera = camera
        self._cell = cell
        self._on_frame = on_frame  # every pair as it came (make teleop --mcap records them)
        self._model = model
        self._out = out
        self._calibration_path = calibration_path
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, name="stereo-view", daemon=True)
        self._poses = MeasuredPoses(robot, model, self._stop)
        self.recorder: VideoRecorder | None = None
        self.error: str | None = None
        self.identified_now = False
        self.pauses = 0  # times the camera went away and the video waited for it
        self.meter = VideoMeter()

    def start(self) -> None:
        self._frames_log = (self._out / FRAMES_LOG).open("w", newline="")
        self._frames_csv = csv.writer(self._frames_log)
        self._frames_csv.writerow(FRAMES_LOG_COLUMNS)
        self._poses.start()
        self._thread.start()

    def stop(self) -> None:
        self._stop.set()
        self._poses.join()
        self._thread.join(10)
        if self.recorder is not None:
            self.recorder.close()
        self._frames_log.close()

    def _log_frame(self, frame: StereoFrame, captured_ns: int, balls) -> None:
        """One row of stereo_frames.csv: the frame, its age, and where the ball went."""
        centres = [c for ball in (balls.left, balls.right)
                   for c in (ball.centre_px if ball is not None else (np.nan, np.nan))]
        self._frames_csv.writerow([frame.sequence, captured_ns, frame.received_ns,
                                   *(f"{c:.2f}" for c in centres)])

    def status(self) -> str:
        """What the video delivers now, for the status line."""
        now = self.meter.now()
        if not now["fps"]:
            return "video -"
        detail = "" if now["render_scale"] == 1.0 else f" detail {now['render_scale']:g}"
        return (f"video {now['fps']:4.1f} fps {now['age_ms_p50']:4.0f} ms "
                f"{now['kbit_per_s'] / 1e3:4.1f} Mbit/s{detail}")

    def summary(self) -> dict:
        """The whole session's video figures (VideoMeter.summary), for summary.json."""
        return {"codec": self.meter.codec, **self.meter.summary(skip_s=1.0)} \
            if self.meter.frames else {}

    def _overlay(self, header) -> StereoOverlay:
        """The saved identification, or a new one from the reference points (then saved)."""
        width, height = header.width_px, header.height_px
        identification = load_if_present(self._calibration_path, width, height)
        if identification is None:
            # The simulated cameras say where the reference points appear (a real rig: the
            # operator clicks them); identification then works as it would on real images.
            left, right = projections_from_header(header)
            points = reference_points(self._cell)
            identification = identify_stereo(points, left.project(points),
                                             right.project(points), width, height,
                                             source="teleop: reference box")
            save_identification(identification, self._calibration_path)
            self.identified_now = True
        return StereoOverlay.from_identification(identification)

    def _run(self) -> None:
        overlay = composer = None
        while not self._stop.is_set():
            try:
                stream = self._camera.stream_pairs(sc_pb.IMAGE_ENCODING_H264, width_px=WIDTH_PX,
                                                   height_px=HEIGHT_PX, max_fps=MAX_FPS,
                                                   timeout=None)
                for frame in stream:
                    if self._stop.is_set():
                        stream.cancel()
                        return
                    if self._on_frame is not None:
                        self._on_frame(frame)
                    if overlay is None:
                        overlay = self._overlay(frame.header)
                        composer = SideBySideComposer(frame.header.width_px,
                                                      frame.header.height_px)
                        self.recorder = VideoRecorder(self._out / "stereo.mp4",
                                                      *composer.frame_size)
                    captured_ns = frame.pair.left_capture_time.ToNanoseconds()
                    left, right, balls = overlay.draw(frame.left, frame.right,
                                                      self._model.tool_point_at(captured_ns))
                    self.meter.shown(frame)
                    self.recorder.add(composer.compose(left, right))
                    self._log_frame(frame, captured_ns, balls)
                return
            except UnavailableError as error:  # the camera restarts: pause, then resume
                if self._stop.is_set():
                    return
                self.pauses += 1
                log.warning("video paused (%s); resuming when the camera is back", error)
                self._stop.wait(RESUME_AFTER_S)
            except Exception as error:  # noqa: BLE001 - the task goes on without video; say why
                if not self._stop.is_set():
                    self.error = str(error)
                    log.warning("stereo view stopped: %s", error)
                return
