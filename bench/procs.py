"""Child processes of the bench: services, measuring workers and baseline servers.

Every child runs `python -m ...` from the repository root in its own process group (so a
terminal's Ctrl-C reaches only the bench, which then stops each child once: SIGTERM, then
SIGKILL after a deadline), with TELEROBOT_PARENT_PID set so the services stop by themselves if
the bench is killed outright. Output is collected line by line: the services' ready line and
the workers' ready line are noticed, and the last lines are kept for error messages.
"""

from __future__ import annotations

import collections
import json
import os
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import threading
import time
import uuid
from pathlib import Path

from services.runtime.process import PARENT_PID_ENV, READY_LINE_PREFIX

REPO = Path(__file__).resolve().parent.parent
WORKER_READY = "BENCH_READY"
STOP_GRACE_S = 3.0
_TAIL_LINES = 40


def free_port() -> int:
    """A TCP port on 127.0.0.1 that is free now."""
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return sock.getsockname()[1]


def unique_shm_name() -> str:
    """A shared-memory name of this run's own, so a bench never meets another world."""
    return f"telerobot_bench_{os.getpid()}_{uuid.uuid4().hex[:8]}"


class ChildFailed(RuntimeError):
    """A child exited or did not get ready in time; the message carries its last lines."""


class Child:
    """One child process with its output collected."""

    def __init__(self, name: str, args: list[str], env: dict[str, str]):
        self.name = name
        self.tail: collections.deque[str] = collections.deque(maxlen=_TAIL_LINES)
        self.ready: dict[str, str] = {}  # service name -> host:port, from ready lines
        self.worker_ready = threading.Event()
        self._changed = threading.Condition()
        self.process = subprocess.Popen(
            [sys.executable, *args], cwd=REPO, env=env, stdin=subprocess.DEVNULL,
            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, process_group=0)
        threading.Thread(target=self._pump, name=f"out-{name}", daemon=True).start()

    def _pump(self) -> None:
        for line in self.process.stdout:
            line = line.rstrip("\n")
            with self._changed:
                if line.startswith(READY_LINE_PREFIX):
                    _, service, address = line.split()
                    self.ready[service] = address
                elif line.startswith(WORKER_READY):
                    self.worker_ready.set()
                else:
                    self.tail.append(line)
                self._changed.notify_all()
        with self._changed:
            self._changed.notify_all()

    def describe(self) -> str:
        code = self.process.poll()
        state = "running" if code is None else f"exit {code}"
        lines = "\n    ".join(self.tail) or "(no output)"
        return f"{self.name} ({state}); its last lines:\n    {lines}"

    def wait_service_ready(self, service: str, timeout_s: float) -> str:
        """host:port once the service printed its ready line; ChildFailed otherwise."""
        deadline = time.monotonic() + timeout_s
        with self._changed:
            while service not in self.ready:
                if self.process.poll() is not None or time.monotonic() > deadline:
                    raise ChildFailed(f"{service} did not start: {self.describe()}")
                self._changed.wait(0.1)
            return self.ready[service]

    def wait_worker_ready(self, timeout_s: float) -> None:
        deadline = time.monotonic() + timeout_s
        while not self.worker_ready.wait(0.1):
            if self.process.poll() is not None or time.monotonic() > deadline:
                raise ChildFailed(f"{self.name} did not get ready: {self.describe()}")

    def stop(self, grace_s: float = STOP_GRACE_S) -> int | None:
        """SIGTERM, then SIGKILL after grace_s; returns the exit code."""
        if self.process.poll() is None:
            try:
                self.process.send_signal(signal.SIGTERM)
            except ProcessLookupError:
                pass
        try:
            return self.process.wait(grace_s)
        except subprocess.TimeoutExpired:
            self.process.kill()
            return self.process.wait(5)


class ProcessSet:
    """The children of one bench run; stop_all() stops every live one, newest first."""

    def __init__(self, base_env: dict[str, str] | None = None):
        self.children: list[Child] = []
        self.base_env = {**os.environ, PARENT_PID_ENV: str(os.getpid()),
                         "PYTHONUNBUFFERED": "1", "TELEROBOT_LOG_LEVEL": "WARNING",
                         **(base_env or {})}
        self.scratch = Path(tempfile.mkdtemp(prefix="telerobot_bench_"))

    def start(self, name: str, args: list[str], env: dict[str, str] | None = None) -> Child:
        child = Child(name, args, {**self.base_env, **(env or {})})
        self.children.append(child)
        return child

    def start_service(self, service: str, address: str, extra_args: list[str] | None = None,
                      timeout_s: float = 60.0) -> Child:
        """`python -m services.<service>` on `address`, waited for until it is serving."""
        child = self.start(service, ["-m", f"services.{service}", "--address", address,
                                     "--grace-s", "0.5", *(extra_args or [])])
        child.wait_service_ready(service, timeout_s)
        return child

    def run_worker(self, kind: str, params: dict, timeout_s: float,
                   name: str | None = None) -> dict:
        """Run `python -m bench.worker kind` to the end and return its JSON result."""
        child = self.start_worker(kind, params, name)
        return self.finish_worker(child, timeout_s)

    def start_worker(self, kind: str, params: dict, name: str | None = None) -> Child:
        out = self.scratch / f"{kind}_{uuid.uuid4().hex[:8]}.json"
        child = self.start(name or kind, ["-m", "bench.worker", kind, json.dumps(params),
                                          str(out)])
        child.result_path = out  # type: ignore[attr-defined]
        return child

    def finish_worker(self, child: Child, timeout_s: float) -> dict:
        """Wait (bounded) for a worker to end; its result, or ChildFailed."""
        try:
            code = child.process.wait(timeout_s)
        except subprocess.TimeoutExpired:
            child.stop(1.0)
            raise ChildFailed(f"{child.name} took more than {timeout_s:.0f} s: "
                              f"{child.describe()}") from None
        finally:
            self.forget(child)
        path: Path = child.result_path  # type: ignore[attr-defined]
        if code != 0 or not path.exists():
            raise ChildFailed(f"{child.name} failed: {child.describe()}")
        result = json.loads(path.read_text())
        path.unlink()
        return result

    def stop(self, child: Child, grace_s: float = STOP_GRACE_S) -> None:
        child.stop(grace_s)
        self.forget(child)

    def forget(self, child: Child) -> None:
        if child in self.children and child.process.poll() is not None:
            self.children.remove(child)

    def stop_all(self) -> None:
        """Stop every live child (newest first: workers, then services, the world last)."""
        live = [c for c in reversed(self.children) if c.process.poll() is None]
        for child in live:
            try:
                child.process.send_signal(signal.SIGTERM)
            except ProcessLookupError:
                pass
        deadline = time.monotonic() + STOP_GRACE_S
        for child in live:
            try:
                child.process.wait(max(0.0, deadline - time.monotonic()))
            except subprocess.TimeoutExpired:
                child.process.kill()
                child.process.wait(5)
        self.children.clear()
        shutil.rmtree(self.scratch, ignore_errors=True)
