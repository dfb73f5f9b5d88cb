"""VideoMeter: what a stereo stream delivers to its client, as the operator sees it.

Each frame counts at the moment the client has both eyes (decoded): its age is that moment
minus the frame's capture time (the earlier eye's), on the wall clock, which the camera and the
client share on one host and must share through NTP or PTP across two. The meter gives the
frame rate, the age's percentiles, the bitrate and the camera's render scale (how much of
its detail a sim camera short of CPU drew), over the whole stream and over its last
`window_s` (the live status line).
"""

from __future__ import annotations

import time
from collections import deque
from dataclasses import dataclass

import numpy as np

from clients.python.values import StereoFrame
from telerobot.v1 import stereo_camera_pb2 as pb

CODECS = {pb.IMAGE_ENCODING_H264: "h264", pb.IMAGE_ENCODING_JPEG: "jpeg",
          pb.IMAGE_ENCODING_PNG: "png", pb.IMAGE_ENCODING_RAW_RGB8: "raw"}


@dataclass(frozen=True)
class _Sample:
    shown_ns: int
    age_ms: float
    size_bytes: int
    target_kbit: int
    render_scale: float = 1.0


def _capture_ns(frame: StereoFrame) -> int:
    return min(frame.pair.left_capture_time.ToNanoseconds(),
               frame.pair.right_capture_time.ToNanoseconds())


class VideoMeter:
    """Counts frames as the client shows them (see the module docstring)."""

    def __init__(self, window_s: float = 2.0):
        self._window_ns = int(window_s * 1e9)
        self._samples: list[_Sample] = []
        self._recent: deque[_Sample] = deque()
        self.codec = ""

    def shown(self, frame: StereoFrame, shown_ns: int | None = None) -> None:
        """`frame` has been decoded and is shown now (or at `shown_ns`, wall clock)."""
        shown_ns = time.time_ns() if shown_ns is None else shown_ns
        pair = frame.pair
        self.codec = CODECS.get(frame.header.encoding, str(frame.header.encoding))
        self.record(shown_ns, (shown_ns - _capture_ns(frame)) / 1e6,
                    len(pair.left_image) + len(pair.right_image) + len(pair.video_frame),
                    pair.target_kbit_per_s, pair.render_scale or 1.0)  # 0: not said, full

    def record(self, shown_ns: int, age_ms: float, size_bytes: int, target_kbit: int,
               render_scale: float = 1.0) -> None:
        """A frame shown at `shown_ns` (wall clock), `age_ms` after its capture, of
        `size_bytes`: from a client that timed it itself (the console's page)."""
        sample = _Sample(shown_ns, age_ms, size_bytes, target_kbit, render_scale)
        self._samples.append(sample)
        self._recent.append(sample)
        while self._recent and self._recent[0].shown_ns < shown_ns - self._window_ns:
            self._recent.popleft()

    @property
    def frames(self) -> int:
        return len(self._samples)

    def now(self) -> dict:
        """fps, age and kbit/s over the last window: the status line."""
        return _summary(list(self._recent), len(self._recent), self._window_ns / 1e9)

    def summary(self, skip_s: float = 0.0) -> dict:
        """The whole stream after its first `skip_s` (start-up), and its thirds' p95 ages, so
        that a backlog shows as a last third older than the first."""
        if not self._samples:
            return _summary([], 0.0)
        start = self._samples[0].shown_ns + int(skip_s * 1e9)
        samples = [s for s in self._samples if s.shown_ns >= start] or self._samples[-1:]
        span_s = max((samples[-1].shown_ns - samples[0].shown_ns) / 1e9, 1e-9)
        result = _summary(samples, len(samples) - 1, span_s)  # n frames: n - 1 intervals
        thirds = np.array_split(np.array([s.age_ms for s in samples]), 3)
        result["age_ms_p95_thirds"] = [round(float(np.percentile(t, 95)), 1) if len(t) else None
                                       for t in thirds]
        result["frames"] = len(samples)
        return result


def _summary(samples: list[_Sample], intervals: int, span_s: float) -> dict:
    """`intervals` frames (and their bytes) over `span_s` seconds."""
    if not samples or not span_s:
        return {"fps": 0.0, "age_ms_p50": None, "age_ms_p95": None, "kbit_per_s": 0.0,
                "target_kbit_per_s": 0, "render_scale": None}
    ages = np.array([s.age_ms for s in samples])
    counted = samples[len(samples) - intervals:]
    return {
        "fps": round(intervals / span_s, 1),
        "age_ms_p50": round(float(np.percentile(ages, 50)), 1),
        "age_ms_p95": round(float(np.percentile(ages, 95)), 1),
        "kbit_per_s": round(sum(s.size_bytes for s in counted) * 8 / 1e3 / span_s, 1),
        "target_kbit_per_s": samples[-1].target_kbit,
        "render_scale": float(np.median([s.render_scale for s in samples])),
    }
