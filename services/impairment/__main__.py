"""python -m services.impairment: the impairment proxy by hand (or from a bench's child).

    python -m services.impairment --listen 127.0.0.1:50061 --target 127.0.0.1:50051 \\
        --delay 50ms --jitter 5ms --cut-at 10s --cut-for 3s --cut-mode reset

--delay, --jitter, --bandwidth, --stall-prob and --stall-for set both directions; their
--up-… and --down-… forms override one (up: client to target). Once listening it prints
`TELEROBOT_READY impairment <host:port>` (the address it bound, for --listen …:0), then a
line per connection and cut. SIGUSR1 cuts the link now, for --cut-for in --cut-mode (a cut
by hand, or at the moment a test chooses); SIGUSR2 prints what it carried so far (`stats:
…`), as it does on stopping.
"""

from __future__ import annotations

import argparse
import re
import signal
import sys
import threading

from services.impairment.link import LinkProfile
from services.impairment.proxy import CUT_MODES, ImpairmentProxy
from wire.addresses import is_loopback
from wire.processes import dump_stacks_on_signal, handle_signals, say, say_ready

_DURATION_UNITS = {"us": 1e-6, "ms": 1e-3, "s": 1.0}
_BANDWIDTH_UNITS = {"bit": 1.0, "kbit": 1e3, "mbit": 1e6, "gbit": 1e9}
_NUMBER_AND_UNIT = re.compile(r"^\s*([0-9]*\.?[0-9]+)\s*([a-zA-Z]*)\s*$")
# (option, LinkProfile field, parser); each also has --up-<option> and --down-<option>.
_LINK_OPTIONS = (("delay", "delay_s", "duration"), ("jitter", "jitter_s", "duration"),
                 ("bandwidth", "bandwidth_bps", "bandwidth"),
                 ("stall-prob", "stall_probability", "probability"),
                 ("stall-for", "stall_s", "duration"))


def _parse(text: str, units: dict[str, float], example: str) -> float:
    match = _NUMBER_AND_UNIT.match(text)
    unit = match.group(2).lower() if match else ""
    if match and float(match.group(1)) == 0 and not unit:
        return 0.0
    if not match or unit not in units:
        raise argparse.ArgumentTypeError(
            f"{text!r}: give a number and one of {', '.join(units)} (e.g. {example})")
    return float(match.group(1)) * units[unit]


def parse_duration(text: str) -> float:
    """Seconds from "50ms", "3s", "250us" (a unit is required, except for 0)."""
    return _parse(text, _DURATION_UNITS, "50ms")


def parse_bandwidth(text: str) -> float:
    """Bits per second from "1mbit", "500kbit" (tc's units; 0 is unlimited)."""
    return _parse(text, _BANDWIDTH_UNITS, "1mbit")


def parse_probability(text: str) -> float:
    value = float(text)
    if not 0.0 <= value <= 1.0:
        raise argparse.ArgumentTypeError(f"{text}: a probability is in [0, 1]")
    return value


_PARSERS = {"duration": parse_duration, "bandwidth": parse_bandwidth,
            "probability": parse_probability}


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="python -m services.impairment",
        description="A TCP proxy that impairs the link to --target: delay, jitter, "
                    "bandwidth, stalls (TCP's answer to loss) and cuts.")
    parser.add_argument("--listen", required=True, help="host:port to accept on (port 0: any)")
    parser.add_argument("--target", required=True, help="host:port to forward to")
    for option, _, kind in _LINK_OPTIONS:
        for prefix in ("", "up-", "down-"):
            parser.add_argument(f"--{prefix}{option}", type=_PARSERS[kind], default=None)
    parser.add_argument("--seed", type=int, default=0,
                        help="repeats the jitter and stalls (down uses seed + 1)")
    parser.add_argument("--cut-at", type=parse_duration, default=None,
                        help="cut the link this long after starting")
    parser.add_argument("--cut-for", type=parse_duration, default=parse_duration("3s"))
    parser.add_argument("--cut-mode", choices=CUT_MODES, default="stall",
                        help="after the cut: connections resume (stall) or are reset")
    parser.add_argument("--allow-network", action="store_true",
                        help="listen beyond loopback: whoever reaches --listen reaches --target "
                             "through it (with the target's TLS, end to end, if it has any)")
    return parser


def profiles(args: argparse.Namespace) -> tuple[LinkProfile, LinkProfile]:
    """(up, down) from the options: a direction's own option wins over the shared one."""
    built = []
    for direction, seed in (("up", args.seed), ("down", args.seed + 1)):
        values = {"seed": seed}
        for option, name, _ in _LINK_OPTIONS:
            attribute = option.replace("-", "_")
            own = getattr(args, f"{direction}_{attribute}")
            shared = getattr(args, attribute)
            value = own if own is not None else shared
            if value is not None:
                values[name] = value
        built.append(LinkProfile(**values))
    return built[0], built[1]


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    if not (is_loopback(args.listen) or args.allow_network):
        print(f"impairment: refusing to listen on {args.listen}, beyond loopback: anyone on "
              f"that network would reach {args.target} through it. Listen on 127.0.0.1, or "
              "pass --allow-network", file=sys.stderr)
        return 2
    dump_stacks_on_signal()
    try:
        up, down = profiles(args)
    except ValueError as error:
        print(f"impairment: {error}", file=sys.stderr)
        return 2
    stop, cut_now, tell = threading.Event(), threading.Event(), threading.Event()
    handle_signals({signal.SIGINT: lambda _: stop.set(), signal.SIGTERM: lambda _: stop.set(),
                    signal.SIGUSR1: lambda _: cut_now.set(), signal.SIGUSR2: lambda _: tell.set()})
    with ImpairmentProxy(args.listen, args.target, up, down,
                         report=say) as proxy:
        say_ready("impairment", proxy.address)
        if args.cut_at is not None and not stop.wait(args.cut_at):
            proxy.cut(args.cut_for, args.cut_mode)
        # The handlers only set events: the cut is made here, in the main thread's own time.
        while not stop.is_set():
            if cut_now.wait(0.05):
                cut_now.clear()
                proxy.cut(args.cut_for, args.cut_mode)
            if tell.is_set():
                tell.clear()
                say(f"stats: {proxy.stats}")
        say(f"stopping: {proxy.stats}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
