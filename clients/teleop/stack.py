"""Find the slave station, or start one: `make teleop` works on a fresh clone.

The operator station starts a local slave station as a program (`python -m services.launcher`)
and learns its addresses from the launcher's ready lines (wire/processes.py), as a program in any
language could: it imports nothing of the station."""

from __future__ import annotations

import collections
import contextlib
import os
import signal
import subprocess
import sys
import threading
from collections.abc import Iterator, Mapping

import grpc
from grpc_health.v1 import health_pb2, health_pb2_grpc

from wire.addresses import env_name, is_loopback
from wire.errors import UnavailableError
from wire.processes import PARENT_PID_ENV, parse_ready_line
from wire.tls import open_channel

STARTUP_TIMEOUT_S = 90.0
STOP_TIMEOUT_S = 10.0
REMOTE_ANSWER_S = 10.0  # after SIGINT, the launcher drains every service well within this
LAST_LINES = 40  # how many of the launcher's last lines an error message shows


def serving(address: str, timeout_s: float = 1.0) -> bool:
    try:
        # TLS as the environment says; over TLS the certificate must be the DecisionServer's.
        with open_channel(address, service="decision_server") as channel:
            reply = health_pb2_grpc.HealthStub(channel).Check(
                health_pb2.HealthCheckRequest(), timeout=timeout_s)
        return reply.status == health_pb2.HealthCheckResponse.SERVING
    except grpc.RpcError:
        return False


@contextlib.contextmanager
def local_station(operator_address: str | None = None,
                  env: Mapping[str, str] | None = None) -> Iterator[dict[str, str]]:
    """Start a slave station (`python -m services.launcher`) and yield every service's address,
    from the launcher's ready lines, once the whole station is up; stop it after (SIGINT: the
    launcher drains every service). `operator_address` is where the DecisionServer listens
    (default: TELEROBOT_DECISION_SERVER_ADDRESS); port 0 there, or in `env`'s addresses, picks
    a free port. RuntimeError, with the launcher's last lines, if it does not come up."""
    extra = dict(env or {})
    if operator_address is not None:
        extra[env_name("decision_server", "address")] = operator_address
    launcher = _Launcher(extra)
    try:
        # The launcher starts decision_server once the inner services serve (and the web
        # console after it, which an operator station does not need).
        if not launcher.ready_for("decision_server", STARTUP_TIMEOUT_S):
            raise RuntimeError(f"the local station did not come up: {launcher.describe()}")
        yield dict(launcher.ready)
    finally:
        launcher.stop()


class _Launcher:
    """`python -m services.launcher` with its output read on a thread: the ready lines seen,
    and the last lines for an error message."""

    def __init__(self, env: Mapping[str, str]):
        # PARENT_PID_ENV: the station stops by itself if this process dies outright.
        full_env = {**os.environ, "PYTHONUNBUFFERED": "1", PARENT_PID_ENV: str(os.getpid()),
                    **env}
        self.process = subprocess.Popen(
            [sys.executable, "-m", "services.launcher"], env=full_env, stdin=subprocess.DEVNULL,
            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, errors="replace",
            process_group=0)  # out of reach of the terminal's Ctrl-C: stop() sends it once
        self.ready: dict[str, str] = {}
        self.lines: collections.deque[str] = collections.deque(maxlen=LAST_LINES)
        self._changed = threading.Condition()
        self._ended = False
        self._reader = threading.Thread(target=self._read, name="launcher-output", daemon=True)
        self._reader.start()

    def _read(self) -> None:
        for line in self.process.stdout:
            with self._changed:
                self.lines.append(line.rstrip("\n"))
                if (ready := parse_ready_line(line)) is not None:
                    self.ready[ready[0]] = ready[1]
                self._changed.notify_all()
        with self._changed:
            self._ended = True
            self._changed.notify_all()

    def ready_for(self, name: str, timeout_s: float) -> bool:
        """Whether `name`'s ready line came within `timeout_s` (False once the launcher ended)."""
        with self._changed:
            self._changed.wait_for(lambda: name in self.ready or self._ended, timeout_s)
            return name in self.ready

    def describe(self) -> str:
        code = self.process.poll()
        state = "still running" if code is None else f"exited with code {code}"
        return f"the launcher {state}; its last lines:\n" + "\n".join(self.lines)

    def stop(self) -> None:
        """SIGINT (the launcher drains every service), then SIGKILL after STOP_TIMEOUT_S."""
        if self.process.poll() is None:
            self.process.send_signal(signal.SIGINT)
            try:
                self.process.wait(STOP_TIMEOUT_S)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()
        self._reader.join(STOP_TIMEOUT_S)  # the rest of its output, then end of file


@contextlib.contextmanager
def station_at(address: str, log=print) -> Iterator[bool]:
    """Yield once a station answers at `address`; start a local one there (and stop it after)
    if nothing does and `address` is on loopback (another host's station is not ours to
    start: UnavailableError). Yields whether it started one. (To start one on a port 0, use
    local_station, which yields the addresses bound.)"""
    local = is_loopback(address)
    # Another host's station gets longer to answer: a TLS handshake across a slow link.
    if serving(address, 1.0 if local else REMOTE_ANSWER_S):
        yield False
        return
    if not local:
        raise UnavailableError(f"no slave station answers at {address}", reason="NO_STATION")
    log(f"nothing answers at {address}: starting a local slave station")
    with local_station(address) as addresses:
        if not serving(address, 5.0):
            raise RuntimeError(f"the local station is up at {addresses['decision_server']}, "
                               f"yet nothing answers at {address}")
        yield True
