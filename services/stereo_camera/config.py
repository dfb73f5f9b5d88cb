"""Flags (with environment defaults) that choose and configure the stereo source.

Every flag's environment variable is TELEROBOT_STEREO_CAMERA_<FLAG> (for example
TELEROBOT_STEREO_CAMERA_SOURCE=pattern), except --shm-name, which shares the world's
TELEROBOT_WORLD_SHM. ``python -m services.stereo_camera --help`` lists them.
"""

from __future__ import annotations

import argparse
import os
from collections.abc import Callable
from dataclasses import dataclass, field

from services.stereo_camera.pattern import PatternSource
from services.stereo_camera.render_scale import LADDER
from services.stereo_camera.sim import (
    DEFAULT_MULTISAMPLES,
    DEFAULT_SHADOW_MAP_PX,
    SimSource,
    WorldJoints,
    home_joints,
)
from services.stereo_camera.source import StereoSource
from services.stereo_camera.video import DEVICE, FILE, VideoSource
from services.world.shm_layout import add_shm_name_argument
from wire.addresses import env_name

SERVICE = "stereo_camera"
SOURCES = ("sim", "pattern", "device", "file")
DEFAULT_SIZE = (640, 480)
DEFAULT_FPS = 30.0


def _env(setting: str, default=None):
    return os.environ.get(env_name(SERVICE, setting), default)


def _on_off(value: str) -> bool:
    if value.lower() in ("on", "1", "true", "yes"):
        return True
    if value.lower() in ("off", "0", "false", "no"):
        return False
    raise argparse.ArgumentTypeError(f"expected on or off, got {value!r}")


def _optional_int(value):
    return None if value in (None, "") else int(value)


def _optional_float(value):
    return None if value in (None, "") else float(value)


def _render_scale(value: str) -> float | None:
    if value == "auto":
        return None
    try:
        scale = float(value)
    except ValueError:
        scale = None
    if scale not in LADDER:
        raise argparse.ArgumentTypeError(
            f"expected auto or one of {', '.join(f'{s:g}' for s in LADDER)}, got {value!r}")
    return scale


def add_source_arguments(parser: argparse.ArgumentParser) -> None:
    """The source flags, for the service and for measure.py."""
    group = parser.add_argument_group("stereo source")
    group.add_argument(
        "--source", choices=SOURCES, default=_env("source", "sim"),
        help="sim: the work cell's MuJoCo cameras at the live arm pose (needs the world "
             "process, or --sim-joints home); pattern: a synthetic test card with the tick "
             "drawn in both eyes; device: two cameras (or one side-by-side); file: two "
             "recordings (or one side-by-side). Default sim (env TELEROBOT_STEREO_CAMERA_SOURCE)")
    group.add_argument(
        "--width", type=int, default=_optional_int(_env("width")),
        help=f"image width of each eye: sim and pattern (default {DEFAULT_SIZE[0]}); the size "
             "asked of a device; ignored for files")
    group.add_argument(
        "--height", type=int, default=_optional_int(_env("height")),
        help=f"image height of each eye (default {DEFAULT_SIZE[1]}); as --width")
    group.add_argument(
        "--fps", type=float, default=_optional_float(_env("fps")),
        help=f"source rate: the most pairs per second for sim and pattern (default "
             f"{DEFAULT_FPS:.0f}; sim renders 35-47 pairs/s at 640x480 by default, 9-18 with "
             "--sim-shadows on, on software EGL), the replay rate of files (default: the "
             "file's), asked of devices")
    group.add_argument(
        "--left", default=_env("left"),
        help="device (index such as 0, or path such as /dev/video0) or file of the left eye")
    group.add_argument("--right", default=_env("right"), help="device or file of the right eye")
    group.add_argument(
        "--side-by-side", default=_env("side_by_side"),
        help="one device or file holding both eyes, the left eye in its left half")
    group.add_argument(
        "--calibration", default=_env("calibration"),
        help="JSON calibration of a device or file source (format: "
             "services/stereo_camera/calibration.py); without it the calibration is unknown")
    group.add_argument(
        "--loop", type=_on_off, default=_on_off(_env("loop", "on")),
        help="replay files from the start when they end (on or off; default on)")
    group.add_argument(
        "--pattern-cost-ms", type=float, default=float(_env("pattern_cost_ms", "0")),
        help="what capturing one pattern pair costs, in ms (default 0)")
    group.add_argument(
        "--sim-joints", choices=("world", "home"), default=_env("sim_joints", "world"),
        help="where the sim takes the arm's pose: the running world process (default) or the "
             "fixed home pose")
    group.add_argument(
        "--sim-shadows", type=_on_off, default=_on_off(_env("sim_shadows", "off")),
        help="render the light's shadows (on or off, default off): on software rendering they "
             "cost 55-110 ms a pair at 640x480, several times the rest of the picture")
    group.add_argument(
        "--sim-shadow-map", type=int, default=int(_env("sim_shadow_map", DEFAULT_SHADOW_MAP_PX)),
        help=f"side of the shadow map in pixels, with --sim-shadows on (default "
             f"{DEFAULT_SHADOW_MAP_PX}; MuJoCo's own 4096 costs about twice as much)")
    group.add_argument(
        "--sim-multisample", type=int,
        default=int(_env("sim_multisample", DEFAULT_MULTISAMPLES)),
        help=f"multisampling (anti-aliasing) samples per pixel (default {DEFAULT_MULTISAMPLES}: "
             "none; MuJoCo's own 4 smooths the edges and doubles the cost in software)")
    group.add_argument(
        "--sim-render-scale", type=_render_scale,
        default=_render_scale(_env("sim_render_scale", "auto")),
        help="of the picture's width and height, what the sim renders before streams scale it "
             "back: auto (default) renders fewer pixels, down to half, while a pair's "
             "render takes over half its frame interval, which keeps the frame rate on "
             "software rendering (render_scale.py); a number fixes it (1: full detail, "
             "whatever it costs)")
    add_shm_name_argument(group, "shared memory of the world process, for --sim-joints world")


@dataclass
class SourceSetup:
    """A source, and what its owner releases after the capture thread has stopped."""

    source: StereoSource
    closers: list[Callable[[], None]] = field(default_factory=list)


def source_from_args(args: argparse.Namespace) -> SourceSetup:
    """The source the flags describe; ValueError naming a bad or missing flag."""
    width = args.width or DEFAULT_SIZE[0]
    height = args.height or DEFAULT_SIZE[1]
    if args.source == "pattern":
        return SourceSetup(PatternSource(width, height, args.fps or DEFAULT_FPS,
                                         args.pattern_cost_ms))
    if args.source == "sim":
        closers = []
        if args.sim_joints == "home":
            home = home_joints()
            joints = home.copy
        else:
            joints = WorldJoints(args.shm_name)
            closers.append(joints.close)
        source = SimSource(joints, width, height, args.fps or DEFAULT_FPS, args.sim_shadows,
                           shadow_map_px=args.sim_shadow_map,
                           multisamples=args.sim_multisample,
                           render_scale=args.sim_render_scale)
        return SourceSetup(source, closers)
    kind = DEVICE if args.source == "device" else FILE
    if args.side_by_side and (args.left or args.right):
        raise ValueError("give --side-by-side alone, or --left and --right")
    if not args.side_by_side and not (args.left and args.right):
        raise ValueError(f"the {kind} source needs --left and --right, or --side-by-side")
    source = VideoSource(
        kind, args.side_by_side or args.left, None if args.side_by_side else args.right,
        side_by_side=bool(args.side_by_side), calibration_path=args.calibration,
        loop=args.loop, fps=args.fps, width_px=args.width, height_px=args.height)
    return SourceSetup(source)
