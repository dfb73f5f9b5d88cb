"""H264Encoder: one stream's encoder, both eyes side by side in one picture per capture tick.

Low latency, for a live view rather than a file: x264's ultrafast preset with zerolatency (no
B-frames, no look-ahead: each pair in gives its frame out at once), a key frame only at the
start and when a client asks (a reliable transport loses nothing, and a key frame is the
biggest frame there is), and a VBV buffer of one frame at twice the target rate, so that no frame is
much bigger than the rate allows and none waits behind a burst. The bitrate can change on any
frame (libavcodec reconfigures x264 in place), which is how the pacer steers it.
"""

from __future__ import annotations

from fractions import Fraction

import av
import cv2
import numpy as np

PRESET = "ultrafast"
X264_PARAMS = "keyint=infinite:scenecut=0:forced-idr=1:repeat-headers=1"
# x264's VBV (its cap on any frame's size) allows this times the target; it cannot change in
# place, so a target beyond it, or far below it, opens a new encoder (with a key frame).
VBV_HEADROOM = 2.0


class H264Encoder:
    """Encodes (left, right) RGB8 pairs of `width_px` x `height_px` per eye into H.264 access
    units (Annex B) of a (2 * width_px) x height_px picture."""

    def __init__(self, width_px: int, height_px: int, fps: float, kbit_per_s: int):
        if width_px % 2 or height_px % 2:
            raise ValueError(f"H.264 needs an even size, not {width_px}x{height_px}")
        self.width_px, self.height_px = width_px, height_px
        self._rate = Fraction(fps).limit_denominator(1000) if fps > 0 else Fraction(30)
        self._frames = 0
        self._open(kbit_per_s)

    def _open(self, kbit_per_s: int) -> None:
        """A new x264 whose VBV allows up to VBV_HEADROOM x `kbit_per_s` (its next frame is a
        key frame)."""
        vbv_bps = int(VBV_HEADROOM * kbit_per_s * 1000)
        context = av.CodecContext.create("libx264", "w")
        context.width, context.height = 2 * self.width_px, self.height_px
        context.pix_fmt = "yuv420p"
        context.framerate = self._rate
        context.time_base = 1 / self._rate
        context.bit_rate = kbit_per_s * 1000
        context.options = {"preset": PRESET, "tune": "zerolatency", "x264-params": X264_PARAMS,
                           "maxrate": str(vbv_bps), "bufsize": str(int(vbv_bps / self._rate))}
        context.open()
        self._context = context
        self._kbit = kbit_per_s
        self._vbv_kbit = vbv_bps // 1000

    @property
    def kbit_per_s(self) -> int:
        return self._kbit

    def encode(self, left: np.ndarray, right: np.ndarray, *, kbit_per_s: int | None = None,
               keyframe: bool = False) -> tuple[bytes, bool]:
        """The access unit for one pair at `kbit_per_s` (None: as before), and whether it is a
        key frame (the first always is)."""
        if kbit_per_s is not None and kbit_per_s != self._kbit:
            if kbit_per_s > self._vbv_kbit or kbit_per_s * VBV_HEADROOM ** 2 < self._vbv_kbit:
                self._open(kbit_per_s)  # x264 keeps its VBV: a far rate needs a new one
            else:
                self._context.bit_rate = kbit_per_s * 1000  # reconfigured in place
                self._kbit = kbit_per_s
        picture = np.hstack((left, right))
        frame = av.VideoFrame.from_ndarray(cv2.cvtColor(picture, cv2.COLOR_RGB2YUV_I420),
                                           format="yuv420p")
        frame.pts = self._frames
        if keyframe:
            frame.pict_type = av.video.frame.PictureType.I
        self._frames += 1
        packets = self._context.encode(frame)
        return b"".join(bytes(p) for p in packets), any(p.is_keyframe for p in packets)

    def close(self) -> None:
        """Frees the encoder (a stream's end)."""
        self._context = None
