"""A CPU cap for a set of processes (a cgroup of the bench's own), where the host allows it.

The observers_zenoh rows stand many subscribers on this one machine, where each would have a
host of its own: capped together while measured, they take no more of the station's cores than
the cap, and fall behind (Zenoh drops for them) instead. cgroup v2 (cpu.max) or v1's cpu
controller (cpu.cfs_quota_us); none where neither can be made (not root, no cpu controller)."""

from __future__ import annotations

import contextlib
import uuid
from collections.abc import Iterator
from pathlib import Path

PERIOD_US = 100_000
V2_ROOT = Path("/sys/fs/cgroup")
V1_CPU_ROOT = Path("/sys/fs/cgroup/cpu")


class CpuCap:
    """A cgroup's CPU quota: `add(pid)` moves a process in, `lift()` takes the quota away (a
    capped process that is stopping need not take its time)."""

    def __init__(self, path: Path, version: int):
        self._path, self._version = path, version

    def set(self, cores: float | None) -> None:
        quota = "max" if cores is None else str(int(cores * PERIOD_US))
        if self._version == 2:
            (self._path / "cpu.max").write_text(f"{quota} {PERIOD_US}")
        else:
            (self._path / "cpu.cfs_period_us").write_text(str(PERIOD_US))
            (self._path / "cpu.cfs_quota_us").write_text("-1" if cores is None else quota)

    def add(self, pid: int) -> None:
        (self._path / "cgroup.procs").write_text(str(pid))

    def lift(self) -> None:
        self.set(None)


@contextlib.contextmanager
def cpu_capped(cores: float) -> Iterator[CpuCap | None]:
    """A cgroup whose processes together get at most `cores` of CPU time, or None where none
    can be made. Removed on leaving (its processes must have ended by then)."""
    name = f"telerobot_bench_{uuid.uuid4().hex[:8]}"
    version = 2 if (V2_ROOT / "cgroup.controllers").exists() else 1
    path = (V2_ROOT if version == 2 else V1_CPU_ROOT) / name
    try:
        path.mkdir()
        cap = CpuCap(path, version)
        cap.set(cores)
    except OSError:
        with contextlib.suppress(OSError):
            path.rmdir()
        yield None
        return
    try:
        yield cap
    finally:
        with contextlib.suppress(OSError):
            path.rmdir()
