"""Child processes of the bench: services, measuring workers and baseline servers.

Every child is supervised by services.runtime.children: `python -m ...` from the repository
root in its own process group (so a terminal's Ctrl-C reaches only the bench, which then stops
each child once: SIGTERM, then SIGKILL after a deadline), with TELEROBOT_PARENT_PID set so the
services stop by themselves if the bench is killed outright. Services listen on port 0 and
report the port they bound on their ready line; workers print WORKER_READY once they are up.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import tempfile
import uuid
from pathlib import Path

from services.runtime import children
from services.runtime.children import Child, ChildFailed
from wire.tls import TLS_DIR_ENV

__all__ = ["Child", "ChildFailed", "ProcessSet", "WORKER_READY", "unique_shm_name"]

REPO = Path(__file__).resolve().parent.parent
WORKER_READY = "BENCH_READY"
STOP_GRACE_S = 3.0
SERVICE_GRACE_S = "0.5"  # --grace-s of the bench's services: nothing in flight is worth more
_TAIL_LINES = 40


def unique_shm_name() -> str:
    """A shared-memory name of this run's own, so a bench never meets another world."""
    return f"telerobot_bench_{os.getpid()}_{uuid.uuid4().hex[:8]}"


def worker_sizes(count: int, per_worker: int) -> list[int]:
    """How `count` subscribers (or observers) split over worker processes of at most
    `per_worker` each: [32, 32, 6] for 70 by 32."""
    return [min(per_worker, count - start) for start in range(0, count, per_worker)]


class ProcessSet:
    """The children of one bench run; stop_all() stops every live one, newest first."""

    def __init__(self, base_env: dict[str, str] | None = None):
        self.children: list[Child] = []
        # Plaintext unless a child is given a TLS directory: a TELEROBOT_TLS_DIR in the
        # caller's shell must not turn the bench's plaintext station into a TLS one.
        self.base_env = {"TELEROBOT_LOG_LEVEL": "WARNING", TLS_DIR_ENV: "", **(base_env or {})}
        self.scratch = Path(tempfile.mkdtemp(prefix="telerobot_bench_"))
        self._result_paths: dict[Child, Path] = {}

    def start(self, name: str, args: list[str], env: dict[str, str] | None = None) -> Child:
        child = children.start(name, args, env={**self.base_env, **(env or {})}, cwd=REPO,
                               max_lines=_TAIL_LINES, stop_grace_s=STOP_GRACE_S)
        self.children.append(child)
        return child

    def start_service(self, service: str, extra_args: list[str] | None = None,
                      name: str | None = None, env: dict[str, str] | None = None) -> Child:
        """`python -m services.<service>` on 127.0.0.1:0 (`env` on top of the base one, e.g.
        a TLS directory); `wait_ready()` it for its address."""
        return self.start(name or service, [
            "-m", f"services.{service}", "--address", "127.0.0.1:0",
            "--grace-s", SERVICE_GRACE_S, *(extra_args or [])], env)

    def run_service(self, service: str, extra_args: list[str] | None = None,
                    timeout_s: float = 60.0, name: str | None = None,
                    env: dict[str, str] | None = None) -> tuple[Child, str]:
        """start_service, waited for until it is serving: (child, its host:port). ChildFailed
        (the child stopped) if it does not get there."""
        child = self.start_service(service, extra_args, name, env)
        try:
            return child, child.wait_ready(service, timeout_s=timeout_s)
        except ChildFailed:
            self.stop(child)
            raise

    def run_worker(self, kind: str, params: dict, timeout_s: float,
                   name: str | None = None) -> dict:
        """Run `python -m bench.worker kind` to the end and return its JSON result."""
        child = self.start_worker(kind, params, name)
        return self.finish_worker(child, timeout_s)

    def start_worker(self, kind: str, params: dict, name: str | None = None) -> Child:
        out = self.scratch / f"{kind}_{uuid.uuid4().hex[:8]}.json"
        child = self.start(name or kind, ["-m", "bench.worker", kind, json.dumps(params),
                                          str(out)])
        self._result_paths[child] = out
        return child

    @staticmethod
    def wait_worker_ready(child: Child, timeout_s: float) -> None:
        """Once a long-running worker (observers, load) said it is up; ChildFailed if not."""
        child.wait_line(WORKER_READY, timeout_s)

    def finish_worker(self, child: Child, timeout_s: float) -> dict:
        """Wait (bounded) for a worker to end; its result, or ChildFailed."""
        path = self._result_paths.pop(child)
        try:
            code = child.wait(timeout_s)
        except subprocess.TimeoutExpired:
            child.stop(grace_s=1.0)
            raise ChildFailed(f"{child.name} took more than {timeout_s:.0f} s: "
                              f"{child.describe()}") from None
        finally:
            self.forget(child)
        if code != 0 or not path.exists():
            child.exited.wait(1.0)  # its last lines, for the message
            raise ChildFailed(f"{child.name} failed: {child.describe()}")
        result = json.loads(path.read_text())
        path.unlink()
        return result

    def stop(self, child: Child, grace_s: float = STOP_GRACE_S) -> None:
        child.stop(grace_s=grace_s)
        self.forget(child)

    def forget(self, child: Child) -> None:
        if child in self.children and child.returncode is not None:
            self.children.remove(child)

    def stop_all(self) -> None:
        """Stop every live child (newest first: workers, then services, the world last)."""
        children.stop_all(reversed(self.children), STOP_GRACE_S)
        self.children.clear()
        self._result_paths.clear()
        shutil.rmtree(self.scratch, ignore_errors=True)
