"""The operator's stereo view: pairs from the camera, the AR ball at the predicted gripper, into
a side-by-side video. Runs on its own thread while the task runs."""

from __future__ import annotations

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
from clients.python.errors import UnavailableError
from clients.python.stereo_camera import StereoCameraClient
from clients.python.values import StereoFrame
from clients.teleop.artifacts import VideoRecorder
from services.robot_model import workspace

log = logging.getLogger(__name__)

WIDTH_PX, HEIGHT_PX = 320, 240
MAX_FPS = 10.0
RESUME_AFTER_S = 0.5  # while the camera is away, try again this often


def reference_points() -> np.ndarray:
    """Eight well-spread points around the fixture and the tool's path (base frame, m): the
    corners of a box from the table top to above home, for identifying the cameras."""
    x, y = workspace.FIXTURE_CENTER_XY
    xs, ys, zs = (x - 0.08, x + 0.08), (y - 0.08, y + 0.08), (workspace.TABLE_TOP_Z, 0.55)
    return np.array([(a, b, c) for a in xs for b in ys for c in zs])


class StereoView:
    """Streams pairs, draws the ball where the RobotModel predicts the tool, records video."""

    def __init__(self, camera: StereoCameraClient, model: RobotModel, out: Path,
                 calibration_path: Path, on_frame: Callable[[StereoFrame], Any] | None = None):
        self._camera = camera
        self._on_frame = on_frame  # every pair as it came (make teleop --mcap records them)
        self._model = model
        self._out = out
        self._calibration_path = calibration_path
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, name="stereo-view", daemon=True)
        self.recorder: VideoRecorder | None = None
        self.error: str | None = None
        self.identified_now = False
        self.pauses = 0  # times the camera went away and the video waited for it

    def start(self) -> None:
        self._thread.start()

    def stop(self) -> None:
        self._stop.set()
        self._thread.join(10)
        if self.recorder is not None:
            self.recorder.close()

    def _overlay(self, header) -> StereoOverlay:
        """The saved identification, or a new one from the reference points (then saved)."""
        identification = load_if_present(self._calibration_path, WIDTH_PX, HEIGHT_PX)
        if identification is None:
            # The simulated cameras say where the reference points appear (a real rig: the
            # operator clicks them); identification then works as it would on real images.
            left, right = projections_from_header(header)
            points = reference_points()
            identification = identify_stereo(points, left.project(points),
                                             right.project(points), WIDTH_PX, HEIGHT_PX,
                                             source="teleop: reference box")
            save_identification(identification, self._calibration_path)
            self.identified_now = True
        return StereoOverlay.from_identification(identification)

    def _run(self) -> None:
        overlay = composer = None
        while not self._stop.is_set():
            try:
                stream = self._camera.stream_pairs(width_px=WIDTH_PX, height_px=HEIGHT_PX,
                                                   max_fps=MAX_FPS, timeout=None)
                for frame in stream:
                    if self._stop.is_set():
                        stream.cancel()
                        return
                    if self._on_frame is not None:
                        self._on_frame(frame)
                    if overlay is None:
                        overlay = self._overlay(frame.header)
                        composer = SideBySideComposer(WIDTH_PX, HEIGHT_PX)
                        self.recorder = VideoRecorder(self._out / "stereo.mp4",
                                                      *composer.frame_size)
                    left, right, _ = overlay.draw(frame.left, frame.right,
                                                  self._model.tool_point)
                    self.recorder.add(composer.compose(left, right))
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
