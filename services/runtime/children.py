"""Child processes: start them, collect their output, learn where they listen, stop them.

One supervisor for everything that starts processes of this project (the launcher, the bench,
the tests). A child is `python <args>`; its stdout and stderr are read line by line on a thread
of its own (so it never blocks on a full pipe), the last lines are kept for error messages, and
its ready lines (services.runtime.process: `TELEROBOT_READY <name> <host:port>`) are noticed.
A service started with `--address 127.0.0.1:0` binds a free port and reports it there, so the
supervisor never has to pick a port for it.

    child = start_service("emergency_stop")        # python -m services.emergency_stop on :0
    address = child.wait_ready(timeout_s=60)       # "127.0.0.1:41231", or ChildFailed
    ...
    child.stop()                                   # SIGTERM, then SIGKILL after a grace
    child.describe()                               # "emergency_stop (...) exited with code 0; ..."

By default a child runs in its own process group (a terminal's Ctrl-C reaches only the
supervisor, which then stops each child once) and gets PARENT_PID_ENV, so a service stops by
itself if the supervisor is killed outright.
"""

from __future__ import annotations

import collections
import logging
import os
import signal
import socket
import subprocess
import sys
import threading
import time
from collections.abc import Callable, Iterable, Mapping, Sequence
from pathlib import Path

from wire.processes import (
    PARENT_PID_ENV,
    STACKS_LINE,
    STACKS_SIGNAL,
    parse_ready_line,
    runs_a_service,
)

log = logging.getLogger(__name__)

READY_TIMEOUT_S = 60.0
STOP_GRACE_S = 3.0  # SIGTERM to SIGKILL, unless the caller says otherwise
KILL_WAIT_S = 5.0  # how long to wait for a SIGKILLed process to be reaped
STACKS_WAIT_S = 1.0  # how long a hung service has to start writing its threads' stacks
# A dump has no last line: it is taken as written once no line came for this long (it is written
# in one go, from C), and a hung service is killed only then.
STACKS_QUIET_S = 0.1
DESCRIBE_LINES = 20  # how many of a child's last lines an error message shows
_DRAIN_AFTER_EXIT_S = 1.0  # after an exit, how long to wait for the rest of the output
_CANCEL_POLL_S = 0.05


class ChildFailed(RuntimeError):
    """A child exited, or did not get ready in time; the message says how, with its last
    lines."""


class Child:
    """One child process with its output collected. Made by `start()`."""

    def __init__(self, name: str, process: subprocess.Popen, max_lines: int | None,
                 on_line: Callable[[Child, str], None] | None,
                 on_exit: Callable[[Child], None] | None, stop_grace_s: float = STOP_GRACE_S,
                 dumps_stacks: bool = False):
        self.name = name
        self.process = process
        self.stop_grace_s = stop_grace_s  # stop()'s default
        self.dumps_stacks = dumps_stacks  # STACKS_SIGNAL makes it write its threads' stacks
        self.ready: dict[str, str] = {}  # name -> host:port, from the ready lines seen
        self.exited = threading.Event()  # set once the process ended and its output is read
        self._lines: collections.deque[str] = collections.deque(maxlen=max_lines)
        self._last_line_at = time.monotonic()
        self._changed = threading.Condition()
        self._on_line, self._on_exit = on_line, on_exit
        self._pump = threading.Thread(target=self._read_output, name=f"out-{name}", daemon=True)
        self._pump.start()
        threading.Thread(target=self._wait_for_exit, name=f"wait-{name}", daemon=True).start()

    # -- what it said ----------------------------------------------------------------------

    @property
    def pid(self) -> int:
        return self.process.pid

    @property
    def returncode(self) -> int | None:
        """None while it runs; negative: killed by that signal."""
        return self.process.poll()

    @property
    def lines(self) -> list[str]:
        """The output lines collected so far (the last `max_lines` of them), ready lines too."""
        with self._changed:
            return list(self._lines)

    @property
    def address(self) -> str | None:
        """host:port from the child's own ready line (the one named like the child)."""
        return self.ready.get(self.name)

    def _read_output(self) -> None:
        for raw in self.process.stdout:
            line = raw.rstrip("\n")
            ready = parse_ready_line(line)
            with self._changed:
                self._lines.append(line)
                self._last_line_at = time.monotonic()
                if ready:
                    self.ready[ready[0]] = ready[1]
                self._changed.notify_all()
            if self._on_line is not None:
                self._on_line(self, line)
        self.process.stdout.close()

    def _wait_for_exit(self) -> None:
        self.process.wait()
        # The output may still be in the pipe: read it, so waiters and descriptions see the
        # child's last words (bounded: a grandchild could hold the pipe open).
        self._pump.join(_DRAIN_AFTER_EXIT_S)
        with self._changed:
            self.exited.set()
            self._changed.notify_all()
        if self._on_exit is not None:
            self._on_exit(self)

    # -- waiting ---------------------------------------------------------------------------

    def _wait_until(self, found: Callable[[], object], timeout_s: float, what: str,
                    cancel: threading.Event | None = None):
        """found()'s first true value; None if `cancel` was set; ChildFailed if the child
        exited or `timeout_s` passed first."""
        deadline = time.monotonic() + timeout_s
        with self._changed:
            while True:
                value = found()
                if value:
                    return value
                if cancel is not None and cancel.is_set():
                    return None
                if self.exited.is_set():
                    raise ChildFailed(f"{what}: {self.describe()}")
                left = deadline - time.monotonic()
                if left <= 0:
                    raise ChildFailed(f"{what} within {timeout_s:.1f} s: {self.describe()}")
                self._changed.wait(min(left, _CANCEL_POLL_S) if cancel is not None else left)

    def wait_ready(self, names: str | Iterable[str] | None = None,
                   timeout_s: float = READY_TIMEOUT_S,
                   cancel: threading.Event | None = None) -> str | None:
        """Wait until every one of `names` (default: the child's own name) printed its ready
        line; returns the first one's host:port. ChildFailed if the child exits or the time is
        up first; None (only) if `cancel` is set first."""
        wanted = [self.name] if names is None else [names] if isinstance(names, str) else list(
            names)
        found = self._wait_until(lambda: all(n in self.ready for n in wanted), timeout_s,
                                 f"{', '.join(wanted)} not ready", cancel)
        return self.ready[wanted[0]] if found else None

    def wait_line(self, match: str | Callable[[str], bool],
                  timeout_s: float = READY_TIMEOUT_S) -> str:
        """The first collected line containing `match` (or for which `match(line)` is true),
        waiting for it if need be; ChildFailed if the child exits or the time is up first."""
        test = match if callable(match) else (lambda line: match in line)
        what = getattr(match, "__name__", None) if callable(match) else repr(match)

        def first():
            return next((line for line in self._lines if test(line)), None)

        return self._wait_until(first, timeout_s, f"no line {what}")

    def wait(self, timeout_s: float | None = None) -> int:
        """The exit code once the child ended (subprocess.TimeoutExpired after `timeout_s`)."""
        return self.process.wait(timeout_s)

    # -- stopping --------------------------------------------------------------------------

    def send_signal(self, sig: int) -> None:
        """Send `sig` if the child still runs."""
        if self.process.poll() is None:
            try:
                self.process.send_signal(sig)
            except ProcessLookupError:
                pass

    def stop(self, sig: int = signal.SIGTERM, grace_s: float | None = None) -> int:
        """Send `sig` (SIGTERM: a service drains and exits), SIGKILL after `grace_s` (default:
        the child's stop_grace_s); returns the exit code (negative: the signal that ended it)."""
        grace_s = self.stop_grace_s if grace_s is None else grace_s
        self.send_signal(sig)
        try:
            return self.process.wait(grace_s)
        except subprocess.TimeoutExpired:
            asked = self.ask_for_stacks()
            self.process.kill()
            code = self.process.wait(KILL_WAIT_S)
            self._report_killed(grace_s, asked)
            return code

    def ask_for_stacks(self) -> bool:
        """Before a hung service is killed: have it write its threads' stacks, which land in
        its lines; waits up to STACKS_WAIT_S for them to begin. Whether they did."""
        if not self.dumps_stacks:
            return False
        self.send_signal(STACKS_SIGNAL)
        try:
            self.wait_line(STACKS_LINE, STACKS_WAIT_S)
        except ChildFailed:
            return False
        deadline = time.monotonic() + STACKS_WAIT_S
        with self._changed:  # until the dump is written: no new line for STACKS_QUIET_S
            while not self.exited.is_set():
                now = time.monotonic()
                quiet_at = self._last_line_at + STACKS_QUIET_S
                if now >= quiet_at or now >= deadline:
                    break
                self._changed.wait(min(quiet_at, deadline) - now)
        return True

    def _report_killed(self, grace_s: float, asked_for_stacks: bool) -> None:
        """Log the kill, with the child's last stack dump if it was asked for one (once its
        output has been read)."""
        stacks = ""
        if asked_for_stacks:
            self.exited.wait(_DRAIN_AFTER_EXIT_S + 1.0)
            lines = self.lines
            starts = [i for i, line in enumerate(lines) if STACKS_LINE in line]
            if starts:
                stacks = ". Its threads were at:\n" + "\n".join(lines[starts[0]:])
        log.warning("%s (pid %d) did not stop within %.1f s; killed it%s", self.name, self.pid,
                    grace_s, stacks)

    # -- telling what happened -------------------------------------------------------------

    def how_it_ended(self) -> str:
        """'exited with code 1', 'was killed by signal 9 (SIGKILL)' or 'is running'."""
        code = self.process.poll()
        if code is None:
            return "is running"
        if code < 0:
            try:
                name = signal.Signals(-code).name
            except ValueError:
                return f"was killed by signal {-code}"
            return f"was killed by signal {-code} ({name})"
        return f"exited with code {code}"

    def describe(self, last: int = DESCRIBE_LINES) -> str:
        """Name, where it listened (or its pid), how it ended, and its last lines."""
        tail = "\n    ".join(self.lines[-last:]) or "(no output)"
        where = self.address or f"pid {self.pid}"
        return f"{self.name} ({where}) {self.how_it_ended()}; its last lines:\n    {tail}"

    def __repr__(self) -> str:
        return f"<Child {self.name} pid {self.pid} {self.how_it_ended()}>"


def start(name: str, args: Sequence[str], *, env: Mapping[str, str] | None = None,
          cwd: str | Path | None = None, own_group: bool = True, watch_parent: bool = True,
          max_lines: int | None = 200, on_line: Callable[[Child, str], None] | None = None,
          on_exit: Callable[[Child], None] | None = None,
          stop_grace_s: float = STOP_GRACE_S, python: str = sys.executable) -> Child:
    """Start `python <args>` (this interpreter, or `python`: another venv's) as the child `name`.

    env: added to this process' environment (PYTHONUNBUFFERED=1 always, so lines arrive as
    they are printed). own_group: in a process group of its own, out of reach of a terminal's
    Ctrl-C. watch_parent: sets PARENT_PID_ENV to this process, so a service stops by itself if
    this process dies. max_lines: how many output lines to keep (None: all). on_line(child,
    line) is called on the reading thread for every line, on_exit(child) once the child ended.
    stop_grace_s: how long Child.stop() waits after its signal before SIGKILL, by default.
    A child that runs one of this project's services (`-m services.<name>`) is asked for its
    threads' stacks before it is killed (wire.processes), and the log shows them.
    """
    full_env = {**os.environ, "PYTHONUNBUFFERED": "1", **(env or {})}
    if watch_parent:
        full_env[PARENT_PID_ENV] = str(os.getpid())
    process = subprocess.Popen(
        [python, *args], cwd=cwd, env=full_env, stdin=subprocess.DEVNULL,
        stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, errors="replace",
        process_group=0 if own_group else None)
    return Child(name, process, max_lines, on_line, on_exit, stop_grace_s,
                 dumps_stacks=runs_a_service(args))


def start_service(service: str, args: Sequence[str] = (), *, address: str = "127.0.0.1:0",
                  **options) -> Child:
    """Start `python -m services.<service> --address <address> <args>` (port 0 by default: it
    binds a free one and reports it on its ready line); `options` as for start(). Call
    `wait_ready()` on the result for its address."""
    return start(service, ["-m", f"services.{service}", "--address", address, *args], **options)


def stop_all(children: Iterable[Child], grace_s: float | None = None) -> list[Child]:
    """SIGTERM every live child (in the order given) at once, then SIGKILL whatever is still
    running `grace_s` later (default: the longest stop_grace_s among them); returns the ones
    that had to be killed."""
    live = [child for child in children if child.returncode is None]
    if grace_s is None:
        grace_s = max((child.stop_grace_s for child in live), default=STOP_GRACE_S)
    for child in live:
        child.send_signal(signal.SIGTERM)
    deadline = time.monotonic() + grace_s
    hung = []
    for child in live:
        try:
            child.process.wait(max(0.0, deadline - time.monotonic()))
        except subprocess.TimeoutExpired:
            hung.append(child)
    asked = {child: child.ask_for_stacks() for child in hung}
    killed = [child for child in hung if child.returncode is None]
    for child in killed:
        child.process.kill()
    for child in killed:
        try:
            child.process.wait(KILL_WAIT_S)
        except subprocess.TimeoutExpired:
            log.error("%s (pid %d) outlived SIGKILL for %.0f s", child.name, child.pid,
                      KILL_WAIT_S)
        child._report_killed(grace_s, asked[child])
    return killed


_refusing_sockets: list[socket.socket] = []


def refused_address(host: str = "127.0.0.1") -> str:
    """host:port where connections are refused for as long as this process lives: for a
    dependency that is deliberately absent. The port is held by a socket bound here that never
    listens, so no other process can take it (not a free port handed out and hoped for)."""
    sock = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    sock.bind((host, 0))
    _refusing_sockets.append(sock)
    return f"{host}:{sock.getsockname()[1]}"
