"""Client-side helpers: a channel that keeps the freshest pairs coming, and decoding.

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
"""

from __future__ import annotations

from collections.abc import Sequence

import grpc
import numpy as np

from services.stereo_camera.encoding import decode_image
from telerobot.v1 import stereo_camera_pb2 as pb

LOW_LATENCY_OPTIONS: tuple[tuple[str, int], ...] = (
    ("grpc.http2.bdp_probe", 0),  # do not grow the receive window beyond...
    ("grpc.http2.lookahead_bytes", 1024),  # ...what the message being read needs
)


def open_channel(address: str, options: Sequence[tuple[str, object]] = ()) -> grpc.Channel:
    """An insecure channel to a StereoCamera at `address` with LOW_LATENCY_OPTIONS (and any
    extra `options`)."""
    return grpc.insecure_channel(address, options=[*LOW_LATENCY_OPTIONS, *options])


def decode_pair(header: pb.StereoHeader, pair: pb.StereoPair) -> tuple[np.ndarray, np.ndarray]:
    """Both eyes of `pair` as RGB8 arrays (height, width, 3), per the stream's header."""
    return (decode_image(pair.left_image, header.encoding, header.width_px, header.height_px),
            decode_image(pair.right_image, header.encoding, header.width_px, header.height_px))
