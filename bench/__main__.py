"""python -m bench [--quick] [--only GROUP ...]: run the benchmarks (`make bench`).

Starts a slave station of its own on free loopback ports, measures every scenario against its
baselines in the same run, prints a table, and writes bench/results/latest.json,
raw_latencies.json and PNG plots. --quick (`make bench QUICK=1`) shortens every scenario so the
whole run takes under 3 minutes. soak_overload (issue #29, bench/overload.py: Teleoperate at
500 Hz beside a busy co-tenant process per core) runs by default, 45 s (15 s with --quick);
alone: `python -m bench --only soak_overload`. The soak (issue #16) runs only when asked for:
`python -m bench --only soak [--soak-minutes N]` (10 minutes; 1 with --quick); so does the
network experiment (issue #14, bench/network.py): `python -m bench --only network` (about 8
minutes; --quick: fewer round trips), which merges its row into an existing latest.json,
and with it the video rows (issue #27, bench/video.py; alone: `--only video`, about 9
minutes; --video-seconds S for each probe).
"""

from __future__ import annotations

import argparse
import os
from pathlib import Path

from bench.plan import GROUPS, Plan
from bench.run import RESULTS_DIR, run


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m bench", description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true",
                        default=os.environ.get("QUICK", "") not in ("", "0"),
                        help="shorter scenarios, the whole run under 3 minutes (env QUICK=1)")
    parser.add_argument("--only", nargs="+", choices=GROUPS, default=(),
                        help="run only these groups (soak and network run only if named)")
    parser.add_argument("--soak-minutes", type=float, default=None, metavar="N",
                        help="the soak's length (default 10 minutes, 1 with --quick)")
    parser.add_argument("--out", default=str(RESULTS_DIR), help="where results go")
    parser.add_argument("--profile", action="store_true",
                        help="after the decision group, py-spy the DecisionServer and ProxyRobot "
                             "under Teleoperate at 1 kHz (bench/profile.py)")
    parser.add_argument("--video-seconds", type=float, default=None, metavar="S",
                        help="each video probe's length after its start-up (default 10, 4 "
                             "with --quick)")
    parser.add_argument("--video-long-seconds", type=float, default=None, metavar="S",
                        help="the video group's long run (default 60, 20 with --quick)")
    parser.add_argument("--video-source", choices=("sim", "pattern"), default=None,
                        help="the video group's camera source (default sim: the work cell "
                             "rendered; pattern: a test card, next to no CPU, a diagnostic)")
    parser.add_argument("--video-size", type=_size, default=None, metavar="WxH",
                        help="the video group's picture per eye (default 640x480); the sim "
                             "camera's render time grows with it")
    parser.add_argument("--video-render-scale", choices=("auto", "1", "0.75", "0.5"),
                        default=None,
                        help="the video group's sim camera render scale (default auto: fewer "
                             "pixels while rendering is over its budget; 1: the full picture "
                             "whatever it costs)")
    args = parser.parse_args(argv)
    if args.soak_minutes is not None and args.soak_minutes <= 0:
        parser.error("--soak-minutes must be > 0")
    for name in ("video_seconds", "video_long_seconds"):
        if getattr(args, name) is not None and getattr(args, name) <= 0:
            parser.error(f"--{name.replace('_', '-')} must be > 0")
    return run(Plan(quick=args.quick, only=tuple(args.only), profile=args.profile,
                    soak_minutes=args.soak_minutes, video_s=args.video_seconds,
                    video_long_s=args.video_long_seconds, video_source=args.video_source,
                    video_size=args.video_size, video_render_scale=args.video_render_scale),
               Path(args.out))


def _size(text: str) -> tuple[int, int]:
    """WxH, both even and at least 16 (H.264's 4:2:0 needs even sizes)."""
    width, _, height = text.lower().partition("x")
    try:
        size = int(width), int(height)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not WxH, e.g. 320x240") from None
    if any(side < 16 or side % 2 for side in size):
        raise argparse.ArgumentTypeError(f"{text!r}: both sides even and at least 16")
    return size


if __name__ == "__main__":
    raise SystemExit(main())
