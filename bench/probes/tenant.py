"""python -m bench.probes.tenant SHARE: a stand-in for the station's world beside a probe's
server: computes SHARE of every millisecond (the world's share of a core is about 0.33), on
absolute deadlines as the world's loop does, until its stdin closes."""

from __future__ import annotations

import subprocess
import sys
import threading
import time

PERIOD_S = 0.001


def compute(share: float) -> None:
    """Compute for `share` of every PERIOD_S until stdin closes (a daemon thread reads it)."""
    done = threading.Event()
    threading.Thread(target=lambda: (sys.stdin.read(), done.set()), daemon=True).start()
    start = time.perf_counter()
    tick = 0
    while not done.is_set():
        tick += 1
        busy_until = time.perf_counter() + share * PERIOD_S
        while time.perf_counter() < busy_until:
            pass
        delay = start + tick * PERIOD_S - time.perf_counter()
        if delay > 0:
            time.sleep(delay)


def start_tenant(share: float) -> subprocess.Popen | None:
    """A tenant process computing `share` of every millisecond (None for 0); it stops when its
    stdin is closed."""
    if share <= 0:
        return None
    return subprocess.Popen([sys.executable, "-m", "bench.probes.tenant", str(share)],
                            stdin=subprocess.PIPE)


if __name__ == "__main__":
    compute(float(sys.argv[1]))
