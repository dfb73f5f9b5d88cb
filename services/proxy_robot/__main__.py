"""python -m services.proxy_robot: the ProxyRobot service process (the papers' PUMA component).

It reaches the arm through the hardware link: in simulation, the world process's shared memory
(--shm-name / TELEROBOT_WORLD_SHM). Clients Connect and Initialize before moving the arm.
"""

from __future__ import annotations

import argparse

from services.proxy_robot.core import ProxyRobotCore
from services.proxy_robot.servicer import ProxyRobotServicer
from services.runtime.core_service import CoreService
from services.runtime.process import run_service
from services.runtime.server import binding
from services.world.shm_layout import add_shm_name_argument
from services.world.shm_link import SharedMemoryArmLink
from telerobot.v1 import proxy_robot_pb2_grpc


def _add_arguments(parser: argparse.ArgumentParser) -> None:
    add_shm_name_argument(parser, "shared-memory segment of the simulated arm's link")


def build(args: argparse.Namespace) -> CoreService:
    # The link opens on Connect, as the papers' ConnectRobot does; close() holds the arm.
    core = ProxyRobotCore(lambda: SharedMemoryArmLink(args.shm_name))
    return CoreService([binding(proxy_robot_pb2_grpc, "ProxyRobot", ProxyRobotServicer(core))],
                       core.close, on_emergency_call=core.hold_now)


if __name__ == "__main__":
    raise SystemExit(run_service("proxy_robot", "ProxyRobot: the software proxy of the arm.",
                                 build, add_arguments=_add_arguments))
