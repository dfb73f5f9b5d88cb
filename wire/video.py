"""The client side of an H.264 stereo stream: decoding its side-by-side frames into two eyes.

PyAV (FFmpeg) is imported the first time a decoder is made, so clients that never see video
do not load it.
"""

from __future__ import annotations

import numpy as np


class VideoDecodeError(ValueError):
    """A frame could not be decoded (a gap before it, or bad data): ask for a key frame."""


class H264Decoder:
    """Decodes the access units of one stream, in order, into (left, right) RGB8 arrays."""

    def __init__(self):
        import av

        self._av = av
        self._context = av.CodecContext.create("h264", "r")

    def decode(self, access_unit: bytes) -> tuple[np.ndarray, np.ndarray] | None:
        """Both eyes of the frame, or None if the decoder produced none (it waits for a key
        frame). VideoDecodeError on bad data."""
        try:
            frames = self._context.decode(self._av.Packet(access_unit))
        except self._av.error.FFmpegError as error:
            raise VideoDecodeError(f"H.264 frame did not decode: {error}") from error
        if not frames:
            return None
        picture = frames[-1].to_ndarray(format="rgb24")
        half = picture.shape[1] // 2
        return picture[:, :half], picture[:, half:]
