"""Find the slave station, or start one: `make teleop` works on a fresh clone."""

from __future__ import annotations

import contextlib
import signal
from collections.abc import Iterator, Mapping

import grpc
from grpc_health.v1 import health_pb2, health_pb2_grpc

from clients.python.errors import UnavailableError
from services.runtime import children
from services.runtime.children import ChildFailed
from services.runtime.config import env_name
from services.runtime.server import is_loopback
from wire.tls import open_channel

STARTUP_TIMEOUT_S = 90.0
STOP_TIMEOUT_S = 10.0
REMOTE_ANSWER_S = 10.0  # after SIGINT, the launcher drains every service well within this


def serving(address: str, timeout_s: float = 1.0) -> bool:
    try:
        with open_channel(address) as channel:  # TLS as the environment says
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
    launcher = children.start("launcher", ["-m", "services.launcher"], env=extra,
                              max_lines=40, stop_grace_s=STOP_TIMEOUT_S)
    try:
        try:
            # The launcher starts decision_server once the inner services serve (and the web
            # console after it, which an operator station does not need).
            launcher.wait_ready("decision_server", timeout_s=STARTUP_TIMEOUT_S)
        except ChildFailed as failed:
            raise RuntimeError(f"the local station did not come up: {failed}") from None
        yield dict(launcher.ready)
    finally:
        launcher.stop(signal.SIGINT)


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
        raise UnavailableError(grpc.StatusCode.UNAVAILABLE,
                               f"no slave station answers at {address}", reason="NO_STATION")
    log(f"nothing answers at {address}: starting a local slave station")
    with local_station(address) as addresses:
        if not serving(address, 5.0):
            raise RuntimeError(f"the local station is up at {addresses['decision_server']}, "
                               f"yet nothing answers at {address}")
        yield True
