"""Real cameras and recordings: cv2.VideoCapture on two devices or files, or on one side-by-side
source whose left half is the left eye.

Devices are named by index ("0") or path ("/dev/video0"); files by path (any container and
codec FFmpeg reads, such as MJPG in .avi). The source is live: while a stream is open it is
grabbed continuously, a device at its own rate and a recording at its frame rate (so a
recording replays in real time, and by default loops, its sequence numbers running on).

Synchronization: both eyes are grabbed (cv2 ``grab``, which only latches the frame) back to
back, then decoded (``retrieve``), so the eye skew is the time between the two grabs. Each
eye's tick is its own frame number (for a file, the frame index), and a pair is made only when
the two agree (source.PairAssembler); a side-by-side source is one grab, so zero skew.

Calibration comes from a JSON file (calibration.py); without one it is unknown (zeros).
Opening fails with FailedPreconditionError naming the device or file; a camera that stops
delivering frames gives UnavailableError, and the next stream opens it again.
"""

from __future__ import annotations

import logging
import os
import time
from pathlib import Path

import cv2
import numpy as np

from services.stereo_camera.calibration import load_calibration, unknown_calibration
from services.stereo_camera.source import LEFT, RIGHT, EyeFrame, SourceGeometry
from wire.errors import FailedPreconditionError, UnavailableError

log = logging.getLogger(__name__)

DEVICE, FILE = "device", "file"
DEFAULT_FILE_FPS = 30.0  # for a recording that does not say its rate


def _capture_target(name: str) -> int | str:
    """cv2.VideoCapture takes a device index as an int."""
    return int(name) if name.isdigit() else name


class VideoSource:
    """Two cameras (or one side-by-side camera) through cv2.VideoCapture."""

    live = True

    def __init__(self, kind: str, left: str, right: str | None = None, *,
                 side_by_side: bool = False, calibration_path: str | Path | None = None,
                 loop: bool = True, fps: float | None = None, width_px: int | None = None,
                 height_px: int | None = None):
        if kind not in (DEVICE, FILE):
            raise ValueError(f"kind must be {DEVICE!r} or {FILE!r}, not {kind!r}")
        if side_by_side == (right is not None):
            raise ValueError("give two cameras (left and right), or one side-by-side camera")
        if fps is not None and not fps > 0:
            raise ValueError(f"fps must be positive, got {fps}")
        self.kind = kind
        self.names = [left] if side_by_side else [left, right]
        self.side_by_side = side_by_side
        self.loop = loop
        self._fps = fps
        self._requested_size = (width_px, height_px)
        self._calibration_path = calibration_path
        if calibration_path is not None:
            load_calibration(calibration_path, 1, 1)  # ValueError now rather than at open
        joined = "+".join(self.names)
        self.description = f"{kind}:{joined}" + (" (side by side)" if side_by_side else "")
        self._captures: list[cv2.VideoCapture] = []
        self._counters: list[int] = []
        self._geometry: SourceGeometry | None = None
        self._frame_size = (0, 0)  # of what each capture delivers

    # -- StereoSource ---------------------------------------------------------------------------

    def open(self) -> SourceGeometry:
        if self._captures and self._geometry is not None:
            return self._geometry
        self.close()
        try:
            eyes = (LEFT, RIGHT)[:len(self.names)]
            sizes = [self._open_one(name, eye) for name, eye in zip(self.names, eyes, strict=True)]
        except FailedPreconditionError:
            self.close()
            raise
        if len(set(sizes)) > 1:
            self.close()
            raise FailedPreconditionError(
                f"the left camera {self.names[0]} gives {sizes[0][0]}x{sizes[0][1]} images and "
                f"the right camera {self.names[1]} {sizes[1][0]}x{sizes[1][1]}: a stereo pair "
                "needs one size", reason="CAMERA_SIZE_MISMATCH")
        self._frame_size = width, height = sizes[0]
        if self.side_by_side:
            width //= 2
        if self._calibration_path is not None:
            try:
                calibration = load_calibration(self._calibration_path, width, height)
            except ValueError as exc:
                self.close()
                raise FailedPreconditionError(str(exc), reason="BAD_CALIBRATION") from None
        else:
            calibration = unknown_calibration(width, height)
        self._geometry = SourceGeometry(width, height, calibration, self._rate_hz(),
                                        self.description)
        self._counters = [0] * len(self._captures)
        return self._geometry

    def grab(self, tick: int) -> tuple[EyeFrame, EyeFrame]:
        if not self._captures:
            raise UnavailableError(f"the {self.kind} source {self.description} is not open",
                                   reason="SOURCE_CLOSED")
        times = self._grab_all()
        if times is None and self.kind == FILE and self.loop:
            for capture in self._captures:
                capture.set(cv2.CAP_PROP_POS_FRAMES, 0)
            times = self._grab_all()
        if times is None:
            self.close()
            what = "ended" if self.kind == FILE else "stopped delivering frames"
            raise UnavailableError(f"the {self.kind} source {self.description} {what}",
                                   reason="SOURCE_ENDED" if self.kind == FILE else "CAMERA_STOPPED")
        images = [self._retrieve(index) for index in range(len(self._captures))]
        ticks = [self._eye_tick(index) for index in range(len(self._captures))]
        if self.side_by_side:
            half = self._geometry.width_px
            image = images[0]
            return (EyeFrame(ticks[0], np.ascontiguousarray(image[:, :half]), times[0]),
                    EyeFrame(ticks[0], np.ascontiguousarray(image[:, half:2 * half]), times[0]))
        return (EyeFrame(ticks[0], images[0], times[0]),
                EyeFrame(ticks[1], images[1], times[1]))

    def close(self) -> None:
        captures, self._captures = self._captures, []
        self._geometry = None
        for capture in captures:
            capture.release()

    # -- helpers --------------------------------------------------------------------------------

    def _open_one(self, name: str, eye: str) -> tuple[int, int]:
        what = "side-by-side camera" if self.side_by_side else f"{eye} camera"
        if self.kind == FILE and not os.path.isfile(name):
            raise FailedPreconditionError(f"cannot open the {what} file {name}: no such file",
                                          reason="CAMERA_UNAVAILABLE")
        capture = cv2.VideoCapture(_capture_target(name))
        if not capture.isOpened():
            capture.release()
            hint = ("check that it is plugged in and that no other program holds it"
                    if self.kind == DEVICE else "check its container and codec")
            raise FailedPreconditionError(f"cannot open the {what} {self.kind} {name}: {hint}",
                                          reason="CAMERA_UNAVAILABLE")
        self._captures.append(capture)
        width, height = self._requested_size
        if self.kind == DEVICE:
            if width:
                capture.set(cv2.CAP_PROP_FRAME_WIDTH, width)
            if height:
                capture.set(cv2.CAP_PROP_FRAME_HEIGHT, height)
            if self._fps:
                capture.set(cv2.CAP_PROP_FPS, self._fps)
        ok, frame = capture.read()  # the size a frame really has
        if not ok or frame is None:
            raise FailedPreconditionError(
                f"the {what} {self.kind} {name} opened but gives no frames",
                reason="CAMERA_UNAVAILABLE")
        if self.kind == FILE:
            capture.set(cv2.CAP_PROP_POS_FRAMES, 0)
        return frame.shape[1], frame.shape[0]

    def _rate_hz(self) -> float:
        if self.kind == DEVICE:
            return 0.0  # grab() blocks until the device's next frame
        if self._fps:
            return float(self._fps)
        reported = self._captures[0].get(cv2.CAP_PROP_FPS)
        return float(reported) if reported and np.isfinite(reported) and reported > 0 \
            else DEFAULT_FILE_FPS

    def _grab_all(self) -> list[int] | None:
        times = []
        for index, capture in enumerate(self._captures):
            if not capture.grab():
                return None
            times.append(time.time_ns())
            self._counters[index] += 1
        return times

    def _retrieve(self, index: int) -> np.ndarray:
        ok, frame = self._captures[index].retrieve()
        width, height = self._frame_size
        if not ok or frame is None or frame.shape[:2] != (height, width):
            name = self.names[index]
            self.close()
            raise UnavailableError(
                f"the {self.kind} {name} delivered a frame that cannot be decoded "
                "or changed size", reason="CAMERA_STOPPED")
        if frame.ndim == 2:
            return cv2.cvtColor(frame, cv2.COLOR_GRAY2RGB)
        return cv2.cvtColor(frame, cv2.COLOR_BGR2RGB)

    def _eye_tick(self, index: int) -> int:
        if self.kind == FILE:
            return int(self._captures[index].get(cv2.CAP_PROP_POS_FRAMES)) - 1
        return self._counters[index]
