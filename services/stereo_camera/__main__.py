"""python -m services.stereo_camera: the StereoCamera service process.

Serves synchronized stereo pairs (section IV of the full paper) from one source, chosen by
--source (env TELEROBOT_STEREO_CAMERA_SOURCE; config.py lists every flag):

- sim (default): the work cell's left_eye/right_eye MuJoCo cameras, rendered at the arm's live
  joint positions read from the world process's shared memory (--shm-name). Without a running
  world, streams and snapshots answer UNAVAILABLE saying so; the service itself still starts.
  By default (no shadows, no multisampling) a 640x480 pair costs 19-28 ms on Mesa's software
  EGL (35-47 pairs/s rendered; 26-30 pairs/s, the 30 fps cap, delivered to a client decoding
  JPEG while the world runs, on a shared 2-core machine). --sim-shadows on (--sim-shadow-map,
  default 1024) makes it 55-110 ms, --sim-multisample 4 about twice the default; sim.py has
  the figures. A GPU (MUJOCO_GL=egl on a real driver) makes any setting a few milliseconds.
  Rendering competes for the same cores as the world's 1 kHz loop, which runs at real-time
  priority where allowed (services/world/service.py).
- pattern: a synthetic test card with the tick drawn in both eyes (--pattern-cost-ms).
- device / file: cv2.VideoCapture on --left and --right, or on one --side-by-side source, with
  an optional --calibration JSON file.

Every thread runs at nice VIDEO_NICE (10; --nice): video yields to control, so on a shared
machine the operator's own processes come before the capture and the encoders.

The capture thread starts with the service and opens the source only when a client first wants
pairs; close() stops it and releases the renderer or the devices.
"""

from __future__ import annotations

import argparse
import logging
from collections.abc import Sequence
from dataclasses import dataclass

from services.runtime.priority import VIDEO_NICE
from services.runtime.process import run_service
from services.runtime.server import ServiceBinding, binding
from services.runtime.service import Service
from services.stereo_camera.capture import CaptureHub
from services.stereo_camera.config import SourceSetup, add_source_arguments, source_from_args
from services.stereo_camera.servicer import StereoCameraServicer
from telerobot.v1 import stereo_camera_pb2_grpc
from wire.errors import TelerobotError

log = logging.getLogger(__name__)


@dataclass
class StereoCameraService(Service):
    setup: SourceSetup

    def __post_init__(self) -> None:
        self.hub = CaptureHub(self.setup.source)

    def bindings(self) -> Sequence[ServiceBinding]:
        return [binding(stereo_camera_pb2_grpc, "StereoCamera", StereoCameraServicer(self.hub))]

    def start(self) -> None:
        self.hub.start()

    def close(self) -> None:
        self.hub.close()  # stops the capture thread, which releases the source on its thread
        for close in self.setup.closers:
            try:
                close()
            except Exception:
                log.exception("releasing the stereo source's link failed")


def build(args: argparse.Namespace) -> StereoCameraService:
    try:
        setup = source_from_args(args)
    except (ValueError, TelerobotError) as exc:
        raise SystemExit(f"python -m services.stereo_camera: {exc}") from None
    log.info("source: %s", args.source)
    return StereoCameraService(setup)


if __name__ == "__main__":
    raise SystemExit(run_service("stereo_camera", "StereoCamera: synchronized stereo pairs.",
                                 build, add_arguments=add_source_arguments, nice=VIDEO_NICE))
