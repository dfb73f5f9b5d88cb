"""python -m services.force_sensor: the wrist force/torque sensor service.

The sensor is the simulated one (the world's shared memory) by default, or an ATI Net F/T over
RDT with --sensor rdt --rdt-address host[:port], or a Franka's own estimate of the push on its
tool with --sensor franka: ProxyRobot's Franka driver mirrors it on the station's shared memory as
a wrist sensor's reading (services/proxy_robot/arm_mirror.py). Either way the arm's joint angles
come from the shared memory (read only), to remove the tool's weight in any orientation.
"""

from __future__ import annotations

import argparse
import logging
import os

from services.force_sensor.core import ForceSensorCore
from services.force_sensor.rdt import RDT_PORT, RdtWrenchLink
from services.force_sensor.servicer import ForceSensorServicer
from services.runtime.core_service import CoreService
from services.runtime.priority import COMMAND_PATH_FIFO_PRIORITY
from services.runtime.process import run_service
from services.runtime.server import binding
from services.runtime.supervisor_state import RESTARTED_BECAUSE_ENV
from services.world.shm_layout import add_shm_name_argument
from services.world.shm_link import SharedMemoryArmLink, SharedMemoryWrenchLink
from telerobot.v1 import force_sensor_pb2_grpc
from wire.addresses import env_name

log = logging.getLogger("force_sensor")
SENSOR_ENV = env_name("force_sensor", "sensor")
AIO_SERVER_ENV = env_name("force_sensor", "aio_server")


def _add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--sensor", choices=["sim", "rdt", "franka"],
                        default=os.environ.get(SENSOR_ENV, "sim"),
                        help=f"sim: the world's wrist sensor; rdt: an ATI Net F/T; franka: the "
                             f"Franka's estimate of the push, from ProxyRobot's Franka driver "
                             f"(env {SENSOR_ENV})")
    parser.add_argument("--rdt-address", default=os.environ.get("TELEROBOT_RDT_ADDRESS", ""),
                        help=f"host[:port] of the Net F/T (port {RDT_PORT} by default; "
                             "env TELEROBOT_RDT_ADDRESS)")
    parser.add_argument("--counts-per-force", type=float, default=1e6,
                        help="the Net F/T's counts per newton (its calibration page)")
    parser.add_argument("--counts-per-torque", type=float, default=1e6,
                        help="the Net F/T's counts per newton-metre")
    parser.add_argument(
        "--aio-server", action=argparse.BooleanOptionalAction,
        default=os.environ.get(AIO_SERVER_ENV, "") == "1",
        help=f"serve on grpc.aio: each StreamWrench is a coroutine on the event loop, woken by "
             f"the sampler, with no thread of its own; with 16 or more observers the process "
             f"takes about a fifth less CPU, but the DecisionServer's Teleoperate beside it is "
             f"slower (docs/performance.md; env {AIO_SERVER_ENV}=1)")
    add_shm_name_argument(parser, "the world's shared-memory segment")


def build(args: argparse.Namespace) -> CoreService:
    if args.sensor == "rdt":
        if not args.rdt_address:
            raise SystemExit("--sensor rdt needs --rdt-address host[:port]")
        host, _, port = args.rdt_address.partition(":")

        def wrench_link():
            return RdtWrenchLink(host, int(port or RDT_PORT), args.counts_per_force,
                                 args.counts_per_torque)
    else:  # the world's wrist sensor, or the Franka's estimate mirrored in its place
        def wrench_link():
            return SharedMemoryWrenchLink(args.shm_name)

    # Sampling starts on StartReading, as in the papers; close() releases the links.
    core = ForceSensorCore(wrench_link, lambda: SharedMemoryArmLink(args.shm_name))
    because = os.environ.get(RESTARTED_BECAUSE_ENV)
    return CoreService([binding(force_sensor_pb2_grpc, "ForceSensor", ForceSensorServicer(core))],
                       core.close,
                       on_start=(lambda: _resume_reading(core, because)) if because else None,
                       fanouts={"wrench": core.readings}, aio_server=args.aio_server)


def _resume_reading(core: ForceSensorCore, previous_end: str) -> None:
    """Restarted by the launcher after a crash: read again at once (the DecisionServer holds
    the arm until the wrench flows). What the old process was told is gone with it."""
    core.start_reading()
    log.warning("restarted (the previous ForceSensor %s) and reading again, with the default "
                "settings and tool frame and no tare: Tare again at no load", previous_end)


if __name__ == "__main__":
    raise SystemExit(run_service("force_sensor", "ForceSensor: the wrist F/T sensor.", build,
                                 add_arguments=_add_arguments,
        realtime_priority=COMMAND_PATH_FIFO_PRIORITY))
