"""python -m bench.worker KIND PARAMS_JSON OUT_PATH: one measuring client, in its own process.

Every client of the bench runs here, apart from the orchestrator, so the orchestrator's own
threads never share an interpreter (and its GIL) with a measurement. Kinds and their
parameters are in KINDS below. A long-running worker (observers, load, events) prints
BENCH_READY once it is up and runs until SIGTERM or its `max_s`. The result is written as
JSON to OUT_PATH. A teleop worker given `record_dir` has the DecisionServer record each
session as MCAP there, a force worker given `mcap_path` records the samples it receives
(recording.py). The command and teleop kinds reach a TLS station given `tls_dir` and
`identity` (which of the directory's certificates to present), explicitly: never from the
environment.

Every worker sets the interpreter's switch interval to 0.5 ms (from 5 ms), as the world process
does, so a thread woken by the network gets the GIL back soon: the same for the project's
clients and the baselines' clients.
"""

from __future__ import annotations

import json
import os
import signal
import sys
import threading
from pathlib import Path

from bench.procs import WORKER_READY
from services.runtime.process import watch_parent
from wire.tls import ChannelSecurity

SWITCH_INTERVAL_S = 0.0005


def _ready() -> None:
    print(WORKER_READY, flush=True)


def _stop_on_signal() -> threading.Event:
    stop = threading.Event()
    signal.signal(signal.SIGTERM, lambda *_: stop.set())
    return stop


def _channel_security(p: dict) -> dict:
    """{"security": ...} for a gRPC client of a TLS station (`tls_dir`, and the `identity`
    whose certificate it presents); nothing for a plaintext one."""
    if not p.get("tls_dir"):
        return {}
    return {"security": ChannelSecurity(Path(p["tls_dir"]), p["identity"])}


def _command(p: dict) -> dict:
    from bench.command import measure

    return measure(p["transport"], p["address"], p["shm"], p["rates"], p["duration_s"],
                   **_channel_security(p))


def _teleop(p: dict) -> dict:
    from bench.teleop import measure
    from services.runtime.priority import COMMAND_PATH_FIFO_PRIORITY, raise_thread_priority

    # The sender keeps its 1 kHz deadlines as a haptic master's loop does: real-time where
    # the host allows it (its threads started later do not inherit it).
    raise_thread_priority(COMMAND_PATH_FIFO_PRIORITY, -10, what="master's sender")

    options = {key: p[key] for key in ("swing", "window_s", "drain_s", "first_sign",
                                       "record_dir", "server_pid", "proxy_pid", "episode_task")
               if p.get(key)}
    if p.get("watchdog_s"):  # the session's watchdog (the soak's); else teleop's own
        options["watchdog_s"] = p["watchdog_s"]
    return measure(p["transport"], p["address"], p.get("shm"), p["rates"], p["duration_s"],
                   **options, **_channel_security(p))


def _force(p: dict) -> dict:
    from bench.force import measure_stream
    from services.runtime.priority import COMMAND_PATH_FIFO_PRIORITY, raise_thread_priority

    # The operator's force feedback is a haptic master's 1 kHz loop: real-time where the host
    # allows it, with the threads its stream's client starts.
    raise_thread_priority(COMMAND_PATH_FIFO_PRIORITY, -10, what="operator's wrench reader",
                          inherited=True)

    return measure_stream(p["transport"], p["address"], p["decimation"], p["duration_s"],
                          mcap_path=p.get("mcap_path"), watch_pids=p.get("watch_pids"))


def _observers(p: dict) -> dict:
    from bench.force import observe

    stop = _stop_on_signal()
    return observe(p["address"], p["count"], p["decimation"], p["max_s"], _ready, stop)


def _zenoh_observers(p: dict) -> dict:
    from bench.zenoh_observers import observe_zenoh

    stop = _stop_on_signal()
    return observe_zenoh(p["router"], p["station"], p["count"], p["max_s"], _ready, stop)


def _estop(p: dict) -> dict:
    from bench.estop import run_estop
    from services.runtime.priority import BAND_FIFO_PRIORITY, raise_thread_priority

    # An emergency-stop button is not a process the station's load can starve: its sender
    # runs at the band's real-time priority where the host allows it.
    raise_thread_priority(BAND_FIFO_PRIORITY, -10, what="emergency-stop sender")

    return run_estop(p["address"], p["shm"], p["trials"], p["label"],
                     p.get("decision_server", False), p.get("stop_address"), p.get("lease_id"))


def _load(p: dict) -> dict:
    from bench.estop import run_load

    return run_load(p["address"], p["concurrency"], p["max_s"], _ready,
                    p.get("target", "proxy_robot"), p.get("lease_id", ""))


def _closed_loop(p: dict) -> dict:
    from bench.closed_loop import run_closed_loop

    return run_closed_loop(p["proxy_address"], p["force_address"], p["trials"])


def _stereo(p: dict) -> dict:
    from bench.stereo import run_stereo, run_stereo_for

    if p.get("duration_s"):  # the soak's: for a time, not a number of pairs
        return run_stereo_for(p["address"], p["mode"], p["duration_s"], p["source_fps"])
    return run_stereo(p["address"], p["mode"], p["pairs"], p["source_fps"])


def _events(p: dict) -> dict:
    from bench.soak import follow_events

    stop = _stop_on_signal()
    return follow_events(p["address"], p["max_s"], _ready, stop)


def _overload(p: dict) -> dict:
    from bench.overload import operate

    return operate(p, _ready)  # BENCH_READY once its Teleoperate session is open


def _network(p: dict) -> dict:
    from bench.network import task

    return task(p, _ready)  # BENCH_READY once the task starts: a cut is timed from it


def _video(p: dict) -> dict:
    from bench.video import measure

    return measure(p)  # clients.video_probe through the link, and the CPU meanwhile


def _video_console(p: dict) -> dict:
    from bench.video import measure_console

    return measure_console(p)  # the console's page in Chromium through the link


def _franka(p: dict) -> dict:
    from bench.franka import measure

    return measure(p["duration_s"], p["mirrored"])


KINDS = {"command": _command, "teleop": _teleop, "force": _force, "observers": _observers,
         "zenoh_observers": _zenoh_observers,
         "estop": _estop, "load": _load, "closed_loop": _closed_loop, "stereo": _stereo,
         "events": _events, "overload": _overload, "network": _network, "video": _video,
         "video_console": _video_console, "franka": _franka}


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    if len(argv) != 3 or argv[0] not in KINDS:
        print(f"usage: python -m bench.worker {{{','.join(KINDS)}}} PARAMS_JSON OUT_PATH",
              file=sys.stderr)
        return 2
    kind, params, out = argv[0], json.loads(argv[1]), argv[2]
    sys.setswitchinterval(SWITCH_INTERVAL_S)
    watch_parent(lambda: os._exit(3))  # the bench is gone: nobody wants the result
    result = KINDS[kind](params)
    with open(out, "w") as handle:
        json.dump(result, handle)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
