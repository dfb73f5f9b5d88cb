"""Latency of the shared-memory hardware link, measured from a driver process.

``measure_link_latency()`` attaches to a running world (in another process) and times:

- ``read_arm()``: one consistent sample, liveness checks and ArmSample construction;
- ``write_target()``: validation and one command write (the arm's current target, so nothing
  moves);
- command round trip: ``write_target()`` until the world reports it applied. The world takes
  commands at the start of each 1 ms step; since each trip here starts right after the world
  published, it waits almost a whole period (~1 ms). An unsynchronised writer waits 0.5 ms on
  average.

``python -m services.world.measure`` prints the result as JSON (world named by
TELEROBOT_WORLD_SHM, default "telerobot_world").
"""

from __future__ import annotations

import argparse
import json
import time
from dataclasses import asdict, dataclass

import numpy as np

from services.world.realtime import LoopStats
from services.world.shm_link import SharedMemoryArmLink
from wire.errors import DeadlineExceededError

DEFAULT_SAMPLES = 5000
DEFAULT_ROUND_TRIPS = 300
ROUND_TRIP_TIMEOUT_S = 0.5


@dataclass(frozen=True)
class Latency:
    """Distribution of one operation's duration (ms)."""

    p50_ms: float
    p99_ms: float
    max_ms: float
    samples: int

    @classmethod
    def of(cls, durations_ns: list[int]) -> Latency:
        values = np.asarray(durations_ns, dtype=float) / 1e6
        p50, p99 = np.percentile(values, [50, 99])
        return cls(float(p50), float(p99), float(values.max()), len(values))


@dataclass(frozen=True)
class LinkLatency:
    read_arm: Latency
    write_target: Latency
    command_round_trip: Latency
    world_loop: LoopStats  # the world's loop counters after the measurement


def measure_link_latency(shm_name: str | None = None, samples: int = DEFAULT_SAMPLES,
                         round_trips: int = DEFAULT_ROUND_TRIPS) -> LinkLatency:
    """Time the link against the running world named ``shm_name`` (default: the environment's).

    UnavailableError when no world is running. Leaves the arm where it was.
    """
    link = SharedMemoryArmLink(shm_name)
    clock = time.perf_counter_ns
    try:
        target = link.read_arm().joint_targets_rad
        reads, writes, trips = [], [], []
        for _ in range(samples):
            start = clock()
            link.read_arm()
            reads.append(clock() - start)
        for _ in range(samples):
            start = clock()
            link.write_target(target)
            writes.append(clock() - start)
        for _ in range(round_trips):
            start = clock()
            link.write_target(target)
            while not link.commands_applied():
                if clock() - start > ROUND_TRIP_TIMEOUT_S * 1e9:
                    raise DeadlineExceededError("the world did not apply a command within "
                                                f"{ROUND_TRIP_TIMEOUT_S} s")
            trips.append(clock() - start)
        return LinkLatency(Latency.of(reads), Latency.of(writes), Latency.of(trips),
                           link.read_loop_stats())
    finally:
        link.close()


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m services.world.measure",
                                     description=__doc__.split("\n\n")[0])
    parser.add_argument("--shm-name", default=None, help="segment (env TELEROBOT_WORLD_SHM)")
    parser.add_argument("--samples", type=int, default=DEFAULT_SAMPLES)
    parser.add_argument("--round-trips", type=int, default=DEFAULT_ROUND_TRIPS)
    args = parser.parse_args(argv)
    result = measure_link_latency(args.shm_name, args.samples, args.round_trips)
    print(json.dumps(asdict(result), indent=2))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
