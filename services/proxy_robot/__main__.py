"""python -m services.proxy_robot: the ProxyRobot service process (the papers' PUMA component).

It reaches the arm through the hardware link (--driver): in simulation, the world process's
shared memory (--shm-name / TELEROBOT_WORLD_SHM); on a Franka, libfranka (--driver franka
--robot-host HOST, with --arm fr3). Clients Connect and Initialize before moving the arm.

On a Franka this process owns the station's shared memory in the world's place (arm_mirror.py):
the force sensor, the cameras and the emergency-stop band read the Franka there.
"""

from __future__ import annotations

import argparse
import logging
import os

from domain.robot_model.description import arm_description
from services.proxy_robot.core import ProxyRobotCore
from services.proxy_robot.servicer import ProxyRobotServicer, local_moves
from services.runtime.core_service import CoreService
from services.runtime.priority import COMMAND_PATH_FIFO_PRIORITY
from services.runtime.process import run_service
from services.runtime.server import binding
from services.runtime.supervisor_state import RESTARTED_BECAUSE_ENV
from services.security.audit import AuditLog
from services.world.shm_layout import add_shm_name_argument
from services.world.shm_link import SharedMemoryArmLink
from telerobot.v1 import proxy_robot_pb2_grpc
from wire.addresses import env_name
from wire.local_call import LOCAL_CALLS_ENV, LocalCallServer

log = logging.getLogger(__name__)
DRIVER_ENV = env_name("proxy_robot", "driver")
ROBOT_HOST_ENV = env_name("proxy_robot", "robot_host")
TORQUE_SOURCE_ENV = env_name("proxy_robot", "torque_source")


def _add_arguments(parser: argparse.ArgumentParser) -> None:
    add_shm_name_argument(parser, "shared-memory segment of the simulated arm's link")
    parser.add_argument(
        "--driver", choices=("sim", "franka"), default=os.environ.get(DRIVER_ENV, "sim"),
        help=f"the arm's driver: the simulated world (sim), or a Franka through libfranka "
             f"(franka, with --robot-host and --arm fr3) (env {DRIVER_ENV})")
    parser.add_argument(
        "--robot-host", default=os.environ.get(ROBOT_HOST_ENV, ""),
        help=f"the Franka's address (its FCI, port 1337) for --driver franka "
             f"(env {ROBOT_HOST_ENV})")
    parser.add_argument(
        "--torque-source", choices=("robot", "impedance"),
        default=os.environ.get(TORQUE_SOURCE_ENV, "robot"),
        help=f"for --driver franka, where the push on the tool comes from: the robot's own "
             f"estimate (robot: tau_ext_hat_filtered), or its joint-impedance spring "
             f"(impedance: what franka-sim needs, as it estimates nothing) (env "
             f"{TORQUE_SOURCE_ENV})")
    parser.add_argument(
        "--local-calls", default=os.environ.get(LOCAL_CALLS_ENV, ""), metavar="PATH",
        help=f"also answer the moves (MoveCartesianIncremental, MoveJointsIncremental) on an "
             f"owner-only Unix socket at PATH, for the DecisionServer on this host: "
             f"0.1 ms a call instead of gRPC's 0.65 ms (wire/local_call.py; env "
             f"{LOCAL_CALLS_ENV}, which `make serve` sets; audited as the station's moves are)")
    parser.add_argument(
        "--aio-server", action=argparse.BooleanOptionalAction,
        default=os.environ.get("TELEROBOT_PROXY_ROBOT_AIO_SERVER", "") == "1",
        help="serve on grpc.aio: an EmergencyStop sent here under a flood of other calls is "
             "seen 5x sooner, and every other call takes about 0.3 ms longer (docs/"
             "performance.md; env TELEROBOT_PROXY_ROBOT_AIO_SERVER=1)")


def _franka_link_factory(host: str, mirror_segment: str | None, torque_source: str):
    """The Franka driver's link factory, once the robot has answered: a driver that cannot
    reach its robot stops the process here (exit 2), before it serves. With the mirror of
    the Franka on the station's segment, which close() removes."""
    from services.proxy_robot.arm_mirror import ArmMirror
    from services.proxy_robot.franka_link import CONTROL_PERIOD_S, FrankaArmLink, probe_franka

    arm = arm_description()
    problem = (
        "--driver franka needs --robot-host (the Franka's address)" if not host
        else f"--driver franka drives a Franka FR3, and --arm is {arm.name}: use --arm fr3"
        if arm.name != "fr3" else probe_franka(host))
    if problem:
        log.error("not starting: %s", problem)
        raise SystemExit(2)
    mirror = ArmMirror(arm, CONTROL_PERIOD_S, mirror_segment)
    log.info("the Franka at %s is mirrored on the shared memory %r (external torques: %s)",
             host, mirror.name, torque_source)
    return (lambda: FrankaArmLink(host, arm, mirror, torque_source)), mirror.close


def build(args: argparse.Namespace) -> CoreService:
    # The link opens on Connect, as the papers' ConnectRobot does; close() holds the arm.
    if args.driver == "franka":
        link_factory, close_mirror = _franka_link_factory(args.robot_host, args.shm_name,
                                                          args.torque_source)
    else:
        def link_factory():
            return SharedMemoryArmLink(args.shm_name)

        def close_mirror():
            pass
    core = ProxyRobotCore(link_factory)
    servicer = ProxyRobotServicer(core)
    local = (LocalCallServer(args.local_calls, local_moves(servicer)) if args.local_calls
             else None)

    def close() -> None:
        if local is not None:
            local.stop()
        core.close()  # the link first: its control loop publishes on the mirror
        close_mirror()

    def start() -> None:
        # Restarted by the launcher after a crash: take the arm back where it is held, at once.
        because = os.environ.get(RESTARTED_BECAUSE_ENV)
        if because:
            core.reattach(because)
        if local is not None:
            local.start()

    return CoreService([binding(proxy_robot_pb2_grpc, "ProxyRobot", servicer)],
                       close, emergency_latch=core.hold_now, on_start=start,
                       fanouts={"robot_states": core.states, "robot_events": core.events},
                       aio_server=args.aio_server,
                       audit_to=(lambda audit: _audit_local_calls(local, audit)) if local
                       else None)


def _audit_local_calls(local: LocalCallServer, audit: AuditLog | None) -> None:
    """The moves on the local socket are audited as the station's gRPC moves are: summarized,
    a line a minute per method, the first of each outcome in full. The caller is named by its
    user id, as the socket's peer credentials give it: only the station's user can open it."""
    if audit is None:
        return
    peer = f"unix:{local.path}"
    local.on_answered = lambda method, outcome, uid: audit.summarized(
        identity=f"uid {uid}", role="station", method=method, outcome=outcome, peer=peer)


if __name__ == "__main__":
    raise SystemExit(run_service("proxy_robot", "ProxyRobot: the software proxy of the arm.",
                                 build, add_arguments=_add_arguments,
        realtime_priority=COMMAND_PATH_FIFO_PRIORITY))
