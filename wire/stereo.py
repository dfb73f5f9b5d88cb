"""The StereoCamera's client side: channel options that keep the freshest pairs coming, and
decoding a pair's images.

StreamPairs is a server stream: the server cannot see what the client has read, only what the
transport accepted. It never queues pairs itself (each send takes the newest pair), but gRPC's
HTTP/2 flow control lets as much data be in flight as the *client's* receive window allows,
and by default a gRPC client grows that window to megabytes (BDP probing): a client that reads
slower than pairs come would then read a backlog of seconds-old pairs. A channel made with
LOW_LATENCY_OPTIONS keeps the window to about one message, so at most about one pair waits in
the pipe and a slow reader's next pair is the newest when it was sent (its age is about the
reader's own read interval). The cost is one round trip per pair on long links, which is the
paper's request-a-picture scheme; on loopback it costs nothing measurable. Clients that simply
want fewer pairs should say so with max_fps.

Raw RGB8 images need only numpy; OpenCV is imported the first time a JPEG or PNG is decoded.
"""

from __future__ import annotations

import numpy as np

from telerobot.v1 import stereo_camera_pb2 as pb

LOW_LATENCY_OPTIONS: tuple[tuple[str, int], ...] = (
    ("grpc.http2.bdp_probe", 0),  # do not grow the receive window beyond...
    ("grpc.http2.lookahead_bytes", 1024),  # ...what the message being read needs
)


def decode_image(data: bytes, encoding: int, width_px: int, height_px: int) -> np.ndarray:
    """The bytes of a StereoPair image back to RGB8 (height, width, 3); ValueError if they do
    not hold a width_px x height_px image."""
    if encoding == pb.IMAGE_ENCODING_RAW_RGB8:
        expected = width_px * height_px * 3
        if len(data) != expected:
            raise ValueError(f"a raw {width_px}x{height_px} image has {expected} bytes, "
                             f"not {len(data)}")
        return np.frombuffer(data, dtype=np.uint8).reshape(height_px, width_px, 3)
    import cv2  # only compressed images (JPEG, PNG: imdecode tells them apart) need OpenCV

    bgr = cv2.imdecode(np.frombuffer(data, dtype=np.uint8), cv2.IMREAD_COLOR)
    if bgr is None or bgr.shape[:2] != (height_px, width_px):
        got = "nothing" if bgr is None else f"{bgr.shape[1]}x{bgr.shape[0]}"
        raise ValueError(f"expected a {width_px}x{height_px} image, decoded {got}")
    return cv2.cvtColor(bgr, cv2.COLOR_BGR2RGB)


def decode_pair(header: pb.StereoHeader, pair: pb.StereoPair) -> tuple[np.ndarray, np.ndarray]:
    """Both eyes of `pair` as RGB8 arrays (height, width, 3), per the stream's header."""
    return (decode_image(pair.left_image, header.encoding, header.width_px, header.height_px),
            decode_image(pair.right_image, header.encoding, header.width_px, header.height_px))
