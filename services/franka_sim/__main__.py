"""python -m services.franka_sim: a simulated Franka FR3 that speaks libfranka's own protocol.

The FR3 of this project's description file (``domain/robot_model/arms/fr3/scene.xml``: the arm
in its work cell) served by franka-sim (PyPI), a MuJoCo server of libfranka's network protocol,
on HOST's port 1337 (libfranka's). ProxyRobot's Franka driver (``--driver franka --robot-host
HOST``) drives it as it would drive a real FR3.

franka-sim pins numpy 1.26 and mujoco < 3.3, so it runs from a venv of its own: ``make
franka-sim`` makes ``.venv-franka``, and ``.venv-franka/bin/python -m services.franka_sim`` runs
it. This module imports nothing of the project's for that reason, but wire.processes, which
needs only the standard library.

A robot's controller runs in real time, and so does this one where the host allows it: every
thread at SCHED_FIFO (--rt-priority, 10 as the world's physics thread), only while the kernel
throttles real-time threads. Left to ordinary scheduling on a loaded machine, franka-sim's
physics and network threads beat against each other: its servo's velocity feedforward then
runs ahead of the commands, and the arm leads its setpoints by a push's worth (measured: the
joint-impedance estimate of the push read p50 14 N in free air during `make teleop`, 2 N in
real time).
"""

from __future__ import annotations

import argparse
import os
import signal
import sys
import threading
import time
from pathlib import Path

from wire.processes import PARENT_PID_ENV, handle_signals

FR3_SCENE = (Path(__file__).resolve().parents[2] / "domain" / "robot_model" / "arms" / "fr3"
             / "scene.xml")
COMMAND_PORT = 1337  # libfranka's: a client cannot choose another
READY_LINE = "franka-sim ready"
RT_PRIORITY_ENV = "TELEROBOT_FRANKA_SIM_RT_PRIORITY"
DEFAULT_RT_PRIORITY = 10
RT_RUNTIME_PATH = "/proc/sys/kernel/sched_rt_runtime_us"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m services.franka_sim",
                                     description=__doc__.splitlines()[0])
    parser.add_argument("--host", default="127.0.0.1",
                        help="address to listen on (default 127.0.0.1: loopback only)")
    parser.add_argument("--model", type=Path, default=Path(os.environ.get("FR3_MJCF", FR3_SCENE)),
                        help="the FR3's MJCF (env FR3_MJCF; default: the project's FR3 cell)")
    parser.add_argument("--enforce-comm-constraints", action="store_true",
                        help="abort a motion with communication_constraints_violation after 20 "
                             "lost command cycles, as the real FCI does (a reflex)")
    parser.add_argument("--rt-priority", type=int,
                        default=int(os.environ.get(RT_PRIORITY_ENV, DEFAULT_RT_PRIORITY)),
                        help=f"SCHED_FIFO priority of every thread where the host allows it (0: "
                             f"ordinary scheduling) (env {RT_PRIORITY_ENV})")
    args = parser.parse_args(argv)
    print(f"franka_sim: {_go_real_time(args.rt_priority)}", flush=True)  # before any thread
    if not args.model.is_file():
        print(f"franka_sim: no model at {args.model}", file=sys.stderr)
        return 2
    os.environ["FR3_MJCF"] = str(args.model)  # franka-sim would download its own otherwise
    from franka_sim import FrankaSimServer

    server = FrankaSimServer(host=args.host, port=COMMAND_PORT, enable_gripper=False,
                             enforce_comm_constraints=args.enforce_comm_constraints)
    stop = threading.Event()
    handle_signals({signal.SIGINT: lambda _: stop.set(), signal.SIGTERM: lambda _: stop.set()})
    _stop_with_parent(stop)
    thread = threading.Thread(target=server.start, name="franka-sim", daemon=True)
    thread.start()
    if not _listening(server, thread, stop):
        print(f"franka_sim: nothing listens on {args.host}:{COMMAND_PORT}", file=sys.stderr)
        server.stop()
        return 1
    print(f"{READY_LINE} on {args.host}:{COMMAND_PORT} with {args.model}", flush=True)
    stop.wait()
    server.stop()
    return 0


def _go_real_time(priority: int) -> str:
    """SCHED_FIFO at `priority` for this thread and every thread it starts after, where the
    host allows it and the kernel throttles real-time threads (so a runaway cannot lock a core);
    what it got, for the log."""
    if priority <= 0:
        return "ordinary scheduling (--rt-priority 0)"
    try:
        with open(RT_RUNTIME_PATH) as runtime:
            if int(runtime.read()) < 0:
                return "ordinary scheduling: real-time throttling is off on this host"
        os.sched_setscheduler(0, os.SCHED_FIFO, os.sched_param(priority))
    except (OSError, ValueError, AttributeError) as error:
        return f"ordinary scheduling: SCHED_FIFO refused ({error})"
    return f"every thread at SCHED_FIFO {priority}"


def _stop_with_parent(stop: threading.Event) -> None:
    """Started by a supervisor (the tests, a launcher): stop when it is gone, as every service
    does (TELEROBOT_PARENT_PID), so port 1337 is never left taken."""
    parent = os.environ.get(PARENT_PID_ENV)
    if not parent:
        return

    def watch() -> None:
        while not stop.wait(0.5):
            if os.getppid() != int(parent):
                stop.set()

    threading.Thread(target=watch, name="parent-watch", daemon=True).start()


def _listening(server, thread: threading.Thread, stop: threading.Event,
               timeout_s: float = 30.0) -> bool:
    """Whether the server has bound its port within `timeout_s` (its `server_socket`; a
    connection to look would be a client it logs as broken)."""
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline and not stop.is_set() and thread.is_alive():
        if getattr(server, "server_socket", None) is not None:
            return True
        stop.wait(0.05)
    return False


if __name__ == "__main__":
    raise SystemExit(main())
