"""What a stereo source is, what it produces, and how two eyes become one pair.

A source (pattern, sim, device or file) is opened, grabbed and closed by one thread only, the
capture thread (capture.py): MuJoCo's GL context and cv2.VideoCapture both belong to the thread
that made them. ``grab(tick)`` returns one ``EyeFrame`` per eye; ``PairAssembler`` (the paper's
camera-status flags) turns them into a ``StereoFrame`` only when both eyes belong to the same
capture tick.

Images are RGB8 numpy arrays (height, width, 3), row-major, top row first.
Times: ``*_time_ns`` are wall-clock (time.time_ns, what the proto's Timestamps carry);
``started_ns`` is time.monotonic_ns, used only inside the server to tell fresh pairs from old.
"""

from __future__ import annotations

import threading
from dataclasses import dataclass
from typing import Protocol

import numpy as np

from services.stereo_camera.calibration import StereoCalibration

LEFT, RIGHT = "left", "right"


@dataclass(frozen=True)
class EyeFrame:
    """One eye's image as its camera delivered it."""

    tick: int  # the camera's own frame number (for a file: the frame index in the file)
    image: np.ndarray  # RGB8 (height, width, 3)
    capture_time_ns: int  # wall clock, when the camera captured it
    render_scale: float = 1.0  # of the source's size, what a renderer short of CPU drew
    # (render_scale.py); the image is that much smaller and streams scale it back


@dataclass(frozen=True)
class StereoFrame:
    """A synchronized pair: both eyes from the same capture tick."""

    sequence: int  # capture tick of the hub; +1 per tick, so skipped pairs show as gaps
    left: np.ndarray  # RGB8 (height, width, 3)
    right: np.ndarray
    left_time_ns: int  # wall clock
    right_time_ns: int
    started_ns: int  # time.monotonic_ns() when the capture of this tick started
    render_scale: float = 1.0  # of the source's width and height, as EyeFrame's

    @property
    def eye_skew_ns(self) -> int:
        """Time between the two eyes' captures (never negative)."""
        return abs(self.right_time_ns - self.left_time_ns)


@dataclass(frozen=True)
class SourceGeometry:
    """What every pair of a source looks like."""

    width_px: int  # each eye
    height_px: int
    calibration: StereoCalibration
    rate_hz: float  # the most ticks per second the source gives; 0 = as fast as grab() returns
    description: str  # for people, as in StereoHeader.source: "sim", "device:/dev/video0", ...


class StereoSource(Protocol):
    """A pair of cameras. Every method runs on the capture thread only.

    A source that knows its geometry before open() (pattern, sim) may expose it as a
    ``geometry`` attribute; clients then get headers without the source being opened."""

    live: bool
    """True when the cameras run on their own clock (devices, recordings replayed in real time):
    they are grabbed continuously while any stream is open, so each grab is current. False when
    a capture can be triggered on demand (pattern, sim): the source then idles between requests.
    """

    def open(self) -> SourceGeometry:
        """Open the cameras if they are not open (idempotent; cheap when open).

        FailedPrecondition naming the device when it cannot be opened."""

    def grab(self, tick: int) -> tuple[EyeFrame, EyeFrame]:
        """Capture both eyes for hub tick `tick`. Unavailable when the cameras stopped (a
        source that can recover closes itself, and the next open() reopens it)."""

    def close(self) -> None:
        """Release the cameras (idempotent)."""


class PairAssembler:
    """The paper's camera-status flags: each camera sets its flag when its image is in the back
    buffer; the buffer becomes a pair only when both flags are set for the same tick.

    An eye that arrives with a newer tick than the other's waiting image replaces it (that
    tick's pair is lost: ``mismatched`` counts them), so a pair never mixes two ticks.
    Thread-safe, so each eye may be delivered by its own thread.
    """

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._waiting: dict[str, EyeFrame] = {}
        self.mismatched = 0

    def offer(self, eye: str, frame: EyeFrame) -> tuple[EyeFrame, EyeFrame] | None:
        """Record `eye`'s frame; the (left, right) pair when this completes one, else None."""
        if eye not in (LEFT, RIGHT):
            raise ValueError(f"eye must be {LEFT!r} or {RIGHT!r}, not {eye!r}")
        other = RIGHT if eye == LEFT else LEFT
        with self._lock:
            waiting = self._waiting.get(other)
            if waiting is not None and waiting.tick == frame.tick:
                del self._waiting[other]
                return (frame, waiting) if eye == LEFT else (waiting, frame)
            if waiting is not None and waiting.tick < frame.tick:
                del self._waiting[other]  # the other eye's tick can no longer complete
                self.mismatched += 1
            if waiting is not None and waiting.tick > frame.tick:
                self.mismatched += 1  # this eye is late: its tick is gone
                return None
            if eye in self._waiting:
                self.mismatched += 1  # this eye's previous tick never got its partner
            self._waiting[eye] = frame
            return None
