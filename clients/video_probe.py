"""What the stereo video delivers at an address, as the operator's client sees it.

    python -m clients.video_probe 127.0.0.1:50051 --seconds 20 [--encoding jpeg] [--no-receipts]

Streams pairs through the same client the operator station uses (clients.python's
StereoCameraClient, which reports receipts and decodes H.264), measures them with its
VideoMeter, and prints one JSON line: fps, age_ms_p50, age_ms_p95, kbit_per_s, codec, and
more (the thirds' p95 ages, frames, the sender's last target bitrate, the median render scale:
the share of its width and height a sim camera short of CPU drew). The first --skip-s
seconds (start-up) are left out. The bench runs it too.
"""

from __future__ import annotations

import argparse
import json
import sys
import time

from clients.python.stereo_camera import StereoCameraClient
from clients.python.video_meter import VideoMeter
from telerobot.v1 import stereo_camera_pb2 as pb
from wire.errors import TelerobotError
from wire.stereo import LOW_LATENCY_OPTIONS

ENCODINGS = {"h264": pb.IMAGE_ENCODING_H264, "jpeg": pb.IMAGE_ENCODING_JPEG}


def probe(address: str, seconds: float, *, encoding: str = "h264", receipts: bool = True,
          skip_s: float = 2.0, max_kbit_per_s: int = 0, width_px: int = 0, height_px: int = 0,
          max_fps: float = 0.0) -> dict:
    """Stream for `seconds` (plus `skip_s` of start-up) and summarize what arrived."""
    meter = VideoMeter()
    # Without receipts only a small receive window keeps a slow path from queueing.
    options = () if receipts else LOW_LATENCY_OPTIONS
    with StereoCameraClient(address, options=options) as camera:
        stream = camera.stream_pairs(ENCODINGS[encoding], receipts=receipts,
                                     max_kbit_per_s=max_kbit_per_s, width_px=width_px,
                                     height_px=height_px, max_fps=max_fps)
        with stream:
            end = None
            for frame in stream:
                meter.shown(frame)
                end = end or time.monotonic() + skip_s + seconds
                if time.monotonic() >= end:
                    break
    result = meter.summary(skip_s)
    result.update(codec=encoding, address=address, receipts=receipts,
                  width_px=stream.header.width_px, height_px=stream.header.height_px)
    return result


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("address", help="host:port of a StereoCamera (or the DecisionServer)")
    parser.add_argument("--seconds", type=float, default=10.0)
    parser.add_argument("--skip-s", type=float, default=2.0, help="start-up left out")
    parser.add_argument("--encoding", choices=sorted(ENCODINGS), default="h264")
    parser.add_argument("--no-receipts", dest="receipts", action="store_false",
                        help="no ReportReceipt: the transport alone paces the stream")
    parser.add_argument("--max-kbit", type=int, default=0, help="the bitrate's ceiling")
    parser.add_argument("--width", type=int, default=0)
    parser.add_argument("--height", type=int, default=0)
    parser.add_argument("--max-fps", type=float, default=0.0)
    args = parser.parse_args(argv)
    try:
        result = probe(args.address, args.seconds, encoding=args.encoding,
                       receipts=args.receipts, skip_s=args.skip_s, max_kbit_per_s=args.max_kbit,
                       width_px=args.width, height_px=args.height, max_fps=args.max_fps)
    except TelerobotError as error:
        print(f"video_probe: {error}", file=sys.stderr)
        return 1
    print(json.dumps(result))
    return 0


if __name__ == "__main__":
    sys.exit(main())
