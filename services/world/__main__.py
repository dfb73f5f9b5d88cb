"""python -m services.world: the simulated hardware (arm, wrist sensor) behind shared memory.

Serves only health and reflection on its port; drivers reach the arm through the shared-memory
segment named by --shm-name / TELEROBOT_WORLD_SHM (see shm_link.py).
"""

from __future__ import annotations

import argparse
import os
import signal

from services.runtime.priority import COMMAND_PATH_FIFO_PRIORITY, raise_thread_priority
from services.runtime.process import run_service
from services.world.service import PHYSICS_THREAD_FIFO_PRIORITY, WorldService
from services.world.shm_layout import add_shm_name_argument
from wire.addresses import env_name

# The physics thread must get the GIL back soon after its sleep ends, even if a gRPC thread is
# running Python code: 0.5 ms instead of CPython's default 5 ms bounds that wait.
GIL_SWITCH_INTERVAL_S = 0.0005


def _add_arguments(parser: argparse.ArgumentParser) -> None:
    add_shm_name_argument(parser, "shared-memory segment of the hardware link")
    parser.add_argument(
        "--rt-priority", type=int,
        default=int(os.environ.get(env_name("world", "rt_priority"),
                                   PHYSICS_THREAD_FIFO_PRIORITY)),
        choices=range(0, 100), metavar="0-99",
        help=f"SCHED_FIFO priority of the physics thread where the OS allows it (default "
             f"{PHYSICS_THREAD_FIFO_PRIORITY}); 0 asks for nice -10 only "
             f"(env {env_name('world', 'rt_priority')})")


def main(argv: list[str] | None = None) -> int:
    built: list[WorldService] = []

    def build(args: argparse.Namespace) -> WorldService:
        if args.rt_priority:
            # The process's other threads (gRPC's, health, metrics) below the physics thread but
            # real-time too: one of them holding the GIL when the physics thread wants it must
            # get a core at once, not wait its turn among a busy host's ordinary processes
            # (docs/services/world.md). The threads started from here on inherit it.
            raise_thread_priority(min(COMMAND_PATH_FIFO_PRIORITY, args.rt_priority), 0,
                                  what="world's other threads", inherited=True)
        # A crashed physics loop stops the process like a signal would, then exits 1 below.
        service = WorldService(args.shm_name,
                               on_failure=lambda: os.kill(os.getpid(), signal.SIGTERM),
                               fifo_priority=args.rt_priority)
        built.append(service)
        return service

    code = run_service("world", "The simulated PUMA 560 and wrist sensor (shared-memory link).",
                       build, argv, _add_arguments, switch_interval_s=GIL_SWITCH_INTERVAL_S)
    if code == 0 and built and built[0].failed:
        return 1
    return code


if __name__ == "__main__":
    raise SystemExit(main())
