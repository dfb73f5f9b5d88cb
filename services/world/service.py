"""WorldService: the simulation, its shared-memory link and the 1 kHz loop, as one service.

The physics thread runs the RealtimeLoop; each step applies the drivers' new commands (in issue
order), steps the simulation and publishes the result. The service serves no telerobot gRPC
contract (its link is shared memory): run_service gives it health, reflection, flags and a
graceful stop.

Priority: the physics thread asks the OS for real-time scheduling, SCHED_FIFO at a modest
priority (``fifo_priority``, default 10), so the 1 kHz loop preempts ordinary work (rendering,
gRPC threads, other processes) the moment its sleep ends. It does so only while the kernel's
real-time throttling is on (/proc/sys/kernel/sched_rt_runtime_us not -1; Linux's default
leaves 50 ms of every second to ordinary threads), so a runaway physics thread cannot lock a
core. Without the privilege (CAP_SYS_NICE, or an RT budget in its cgroup), or with the
throttling off, it falls back to nice -10, and without that to the default; the log says which
it got. The process's other threads run at SCHED_FIFO 5, below it (services/world/__main__.py):
a thread of this process that holds the GIL when the physics thread wants it must get a core
at once, not wait among the host's ordinary processes.
"""

from __future__ import annotations

import logging
import threading
import time
from collections.abc import Callable, Sequence

import mujoco

from services.runtime.metrics import ServiceMetrics
from services.runtime.priority import raise_thread_priority
from services.runtime.server import ServiceBinding
from services.runtime.service import HealthReporter, Service
from services.world.realtime import LoopStats, RealtimeLoop
from services.world.shm_link import Command, WorldPublisher
from services.world.sim import ArmSim
from wire.errors import InvalidArgumentError

log = logging.getLogger(__name__)

STATS_LOG_PERIOD_S = 10.0
FIRST_STEP_TIMEOUT_S = 10.0  # start() waits this long for the loop to run its first step
STOP_TIMEOUT_S = 2.0  # close() waits this long for the physics thread
# The physics thread asks the OS for priority over ordinary work (see the module docstring):
# SCHED_FIFO at this priority (1-99; 0: do not ask), else this nice value (Linux nice is per
# thread), else the default. Both need CAP_SYS_NICE.
PHYSICS_THREAD_FIFO_PRIORITY = 10
PHYSICS_THREAD_NICE = -10
_NOT_SET = object()


class WorldService(Service):
    """The simulated hardware. ``start()`` returns once the loop has stepped; ``failed`` is set
    when the physics thread died (the process should then exit non-zero)."""

    def __init__(self, shm_name: str | None = None,
                 sim_factory: Callable[[], ArmSim] = ArmSim,
                 on_failure: Callable[[], None] | None = None,
                 fifo_priority: int = PHYSICS_THREAD_FIFO_PRIORITY,
                 nice: int = PHYSICS_THREAD_NICE):
        self._shm_name = shm_name
        self._fifo_priority = fifo_priority
        self._nice = nice
        self.physics_priority = "not started"  # what the physics thread got, once it runs
        self._sim_factory = sim_factory
        self._on_failure = on_failure
        self._stop = threading.Event()
        self._stepped = threading.Event()
        self._threads: list[threading.Thread] = []
        self.sim: ArmSim | None = None
        self.publisher: WorldPublisher | None = None
        self.loop: RealtimeLoop | None = None
        self.failed = False
        self._previous_mujoco_warning = _NOT_SET

    def bindings(self) -> Sequence[ServiceBinding]:
        return []

    def configure(self, health: HealthReporter, metrics: ServiceMetrics | None) -> None:
        """The 1 kHz loop's counters on the process's /metrics, read at scrape time."""
        if metrics is None:
            return

        def stat(name: str, scale: float = 1.0) -> Callable[[], float]:
            return lambda: getattr(self.loop.stats() if self.loop else LoopStats(), name) * scale

        metrics.watch("telerobot_world_steps", "Physics steps run", stat("steps"), counter=True)
        metrics.watch("telerobot_world_overruns", "Steps that started a period or more late",
                      stat("overruns"), counter=True)
        metrics.watch("telerobot_world_dropped_steps", "Steps skipped: the loop fell too far "
                      "behind", stat("dropped_steps"), counter=True)
        metrics.watch("telerobot_world_worst_lateness_seconds", "Largest lateness of a step "
                      "(start minus due time)", stat("worst_lateness_ns", 1e-9))
        metrics.watch("telerobot_world_worst_step_seconds", "Longest time one step took",
                      stat("worst_step_ns", 1e-9))

    def start(self) -> None:
        # MuJoCo's default warning handler appends to MUJOCO_LOG.TXT in the working directory;
        # the world's warnings belong in its log (the sim turns a diverged state into a fault).
        self._previous_mujoco_warning = mujoco.get_mju_user_warning()
        mujoco.set_mju_user_warning(_log_mujoco_warning)
        sim = self.sim = self._sim_factory()
        self.publisher = WorldPublisher(sim.arm.name, sim.joint_lower, sim.joint_upper,
                                        sim.period_s, self._shm_name)
        self.publisher.publish(sim.arm_sample(), sim.wrench_sample())  # readable at once
        self.loop = RealtimeLoop(self._step, period_s=sim.period_s)
        self._spawn("physics", self._run_physics)
        self._spawn("loop-stats", self._report_stats)
        if not self._stepped.wait(FIRST_STEP_TIMEOUT_S) or self.failed:
            raise RuntimeError("the physics loop did not start")
        log.info("world running: shared memory %r, servo at %.0f Hz, physics thread at %s",
                 self.publisher.name, 1.0 / sim.period_s, self.physics_priority)

    def close(self) -> None:
        self._stop.set()
        for thread in self._threads:
            thread.join(STOP_TIMEOUT_S)
            if thread.is_alive():
                log.error("thread %s did not stop within %.1f s", thread.name, STOP_TIMEOUT_S)
        if self.loop is not None:
            log.info("loop stats at shutdown: %s", self.loop.stats().describe())
        if self.publisher is not None:
            self.publisher.close()
            self.publisher = None
        if self._previous_mujoco_warning is not _NOT_SET:
            mujoco.set_mju_user_warning(self._previous_mujoco_warning)
            self._previous_mujoco_warning = _NOT_SET

    # -- threads ----------------------------------------------------------------------------

    def _spawn(self, name: str, target: Callable[[], None]) -> None:
        thread = threading.Thread(target=target, name=name, daemon=True)
        self._threads.append(thread)
        thread.start()

    def _run_physics(self) -> None:
        self.physics_priority = raise_thread_priority(self._fifo_priority, self._nice)
        try:
            self.loop.run(self._stop)
        except Exception:
            log.exception("the physics loop crashed; the world stops")
            self.failed = True
            self._stepped.set()
            if self._on_failure is not None:
                self._on_failure()

    def _step(self) -> None:
        sim, publisher = self.sim, self.publisher
        for command in publisher.poll_commands():
            self._apply(sim, command)
        sim.step()
        now = time.time_ns()
        publisher.publish(sim.arm_sample(now), sim.wrench_sample(now), self.loop.stats())
        self._stepped.set()

    @staticmethod
    def _apply(sim: ArmSim, command: Command) -> None:
        if command.kind == "hold":
            sim.hold()
        elif command.kind == "release":
            sim.release_hold()
        else:
            try:
                sim.set_target(command.target, command.duration_s)
            except InvalidArgumentError as exc:  # the driver checks too; never trust shared memory
                log.warning("ignored a bad target: %s", exc)

    def _report_stats(self) -> None:
        while not self._stop.wait(STATS_LOG_PERIOD_S):
            log.info("loop stats: %s", self.loop.stats().describe())


def _log_mujoco_warning(message: str) -> None:
    log.warning("MuJoCo: %s", message.strip())
