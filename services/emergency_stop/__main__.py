"""python -m services.emergency_stop: the emergency-stop band (see __init__.py).

It reaches the arm through the world's shared memory (--shm-name / TELEROBOT_WORLD_SHM), beside
ProxyRobot and without going through it.
"""

from __future__ import annotations

import argparse
import os
import sys
import threading

from services.emergency_stop.servicer import EmergencyStopServicer
from services.runtime.core_service import CoreService
from services.runtime.priority import BAND_FIFO_PRIORITY
from services.runtime.process import run_service
from services.runtime.server import binding
from services.world.shm_layout import add_shm_name_argument
from services.world.shm_link import SharedMemoryEmergencyStop
from telerobot.v1 import proxy_robot_pb2_grpc


def _add_arguments(parser: argparse.ArgumentParser) -> None:
    add_shm_name_argument(parser, "shared-memory segment of the simulated arm's link")


def build(args: argparse.Namespace) -> CoreService:
    _raise_priority()
    servicer = EmergencyStopServicer(lambda: SharedMemoryEmergencyStop(args.shm_name))
    servicer.open()
    return CoreService([binding(proxy_robot_pb2_grpc, "ProxyRobot", servicer)], servicer.close,
                       emergency_latch=servicer.stop_now)


# Threads inherit their creator's nice value, so setting it on the main thread before the
# server starts gives the server's threads the priority: a stop should not wait for a CPU
# behind bulk work. Set in build(), after the arguments are parsed, so that `--help` and
# docs/gen_reference.py (which stops at the parse) leave their caller's priority alone.
BAND_NICE = -10


def _raise_priority() -> None:
    try:
        os.setpriority(os.PRIO_PROCESS, threading.get_native_id(), BAND_NICE)
    except PermissionError:
        print(f"emergency_stop: no privilege for nice {BAND_NICE}; running at the default",
              file=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(run_service(
        "emergency_stop", "The emergency-stop band: ProxyRobot.EmergencyStop past the driver.",
        build, add_arguments=_add_arguments,
        realtime_priority=BAND_FIFO_PRIORITY, reads_arm=False))
