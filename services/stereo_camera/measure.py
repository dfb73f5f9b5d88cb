"""Rate and latency of a stereo stream, measured by a real gRPC client.

``measure_source(source, mode)`` serves `source` from an in-process server on a free loopback
port and streams from it; ``measure_address(address, mode)`` streams from a running service.
The client decodes both eyes of every pair and records:

- fps: pairs received per second (after a few warm-up pairs);
- latency: capture (the earlier eye's capture time) to both eyes decoded at the client, in ms
  (p50 / p99 / max). Client and server share the wall clock here (same host);
- eye skew, sequence gaps (pairs the client skipped), bytes per pair.

``python -m services.stereo_camera.measure --source pattern --mode single`` prints the result as
JSON; it takes the service's source flags (``--source sim --sim-joints home`` needs no world),
or ``--address`` to measure a running service.
"""

from __future__ import annotations

import argparse
import json
import time
from dataclasses import asdict, dataclass

import numpy as np

from services.runtime.server import binding, create_server
from services.stereo_camera.capture import CaptureHub
from services.stereo_camera.client import open_channel
from services.stereo_camera.config import add_source_arguments, source_from_args
from services.stereo_camera.encoding import decode_image
from services.stereo_camera.servicer import StereoCameraServicer
from services.stereo_camera.source import StereoSource
from services.world.measure import Latency
from telerobot.v1 import stereo_camera_pb2 as pb
from telerobot.v1 import stereo_camera_pb2_grpc

MODES = {"single": pb.TRANSFER_MODE_SINGLE_BUFFER_SERIALIZED,
         "double": pb.TRANSFER_MODE_DOUBLE_BUFFER_CONCURRENT}
ENCODINGS = {"jpeg": pb.IMAGE_ENCODING_JPEG, "png": pb.IMAGE_ENCODING_PNG,
             "raw": pb.IMAGE_ENCODING_RAW_RGB8}
DEFAULT_PAIRS = 60
WARMUP_PAIRS = 3


@dataclass(frozen=True)
class StreamMeasurement:
    source: str
    mode: str
    encoding: str
    width_px: int
    height_px: int
    pairs: int  # measured (after warm-up)
    fps: float
    latency: Latency  # capture to decoded, ms
    mean_eye_skew_ms: float
    sequence_gaps: int  # pairs skipped between the measured ones
    mean_pair_bytes: float


def measure_address(address: str, mode: str = "double", *, encoding: str = "jpeg",
                    jpeg_quality: int = 90, pairs: int = DEFAULT_PAIRS, max_fps: float = 0.0,
                    width_px: int = 0, height_px: int = 0,
                    timeout_s: float = 120.0) -> StreamMeasurement:
    """Stream `pairs` pairs (plus warm-up) from the service at `address` and time them."""
    request = pb.StreamPairsRequest(
        encoding=ENCODINGS[encoding], jpeg_quality=jpeg_quality, max_fps=max_fps,
        transfer_mode=MODES[mode], width_px=width_px, height_px=height_px)
    latencies, skews, sizes, sequences, arrivals = [], [], [], [], []
    with open_channel(address) as channel:
        stub = stereo_camera_pb2_grpc.StereoCameraStub(channel)
        stream = stub.StreamPairs(request, timeout=timeout_s)
        try:
            header = next(stream).header
            for index, message in enumerate(stream):
                pair = message.pair
                for image in (pair.left_image, pair.right_image):
                    decode_image(image, header.encoding, header.width_px, header.height_px)
                done = time.time_ns()
                if index < WARMUP_PAIRS:
                    continue
                captured = min(pair.left_capture_time.ToNanoseconds(),
                               pair.right_capture_time.ToNanoseconds())
                latencies.append(done - captured)
                skews.append(pair.eye_skew.ToNanoseconds())
                sizes.append(len(pair.left_image) + len(pair.right_image))
                sequences.append(pair.sequence)
                arrivals.append(time.monotonic())
                if len(latencies) >= pairs:
                    break
        finally:
            stream.cancel()
    elapsed = arrivals[-1] - arrivals[0]
    return StreamMeasurement(
        source=header.source, mode=mode, encoding=encoding, width_px=header.width_px,
        height_px=header.height_px, pairs=len(latencies),
        fps=(len(arrivals) - 1) / elapsed if elapsed > 0 else 0.0,
        latency=Latency.of(latencies), mean_eye_skew_ms=float(np.mean(skews)) / 1e6,
        sequence_gaps=int(sum(b - a - 1 for a, b in zip(sequences, sequences[1:],
                                                         strict=False))),
        mean_pair_bytes=float(np.mean(sizes)))


def measure_source(source: StereoSource, mode: str = "double", **options) -> StreamMeasurement:
    """measure_address() against `source` served by an in-process server (closed after)."""
    hub = CaptureHub(source)
    server, port = create_server(
        "127.0.0.1:0", [binding(stereo_camera_pb2_grpc, "StereoCamera",
                                StereoCameraServicer(hub))])
    server.start()
    hub.start()
    try:
        return measure_address(f"127.0.0.1:{port}", mode, **options)
    finally:
        server.stop(0)
        hub.close()


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="python -m services.stereo_camera.measure",
                                     description=__doc__.split("\n\n")[0])
    parser.add_argument("--mode", choices=MODES, default="double")
    parser.add_argument("--encoding", choices=ENCODINGS, default="jpeg")
    parser.add_argument("--jpeg-quality", type=int, default=90)
    parser.add_argument("--pairs", type=int, default=DEFAULT_PAIRS)
    parser.add_argument("--max-fps", type=float, default=0.0)
    parser.add_argument("--address", help="measure the service running here instead")
    add_source_arguments(parser)
    args = parser.parse_args(argv)
    options = dict(encoding=args.encoding, jpeg_quality=args.jpeg_quality, pairs=args.pairs,
                   max_fps=args.max_fps)
    if args.address:
        result = measure_address(args.address, args.mode, **options)
    else:
        setup = source_from_args(args)
        try:
            result = measure_source(setup.source, args.mode, **options)
        finally:
            for close in setup.closers:
                close()
    print(json.dumps(asdict(result), indent=2))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
