"""Configuration shared by every process: addresses, flags with environment defaults, logging.

Each service listens on loopback by default. `TELEROBOT_<NAME>_ADDRESS` (for example
TELEROBOT_PROXY_ROBOT_ADDRESS=0.0.0.0:50052) or the `--address` flag changes it; the launcher and
the clients read the same variables, so they always agree on where a service is. The
addresses are defined in ``wire.addresses`` (the clients' side too) and re-exported here.
"""

from __future__ import annotations

import argparse
import logging
import os
import sys

from domain.robot_model.description import (
    ARM_ENV,
    ArmDescriptionError,
    UnknownArmError,
    available_arms,
    select_arm,
    selected_arm_name,
)
from domain.robot_model.model_files import DEFAULT_ARM
from services.runtime.lanes import Lane
from wire.addresses import DEFAULT_HOST as DEFAULT_HOST  # re-exported
from wire.addresses import DEFAULT_PORTS as DEFAULT_PORTS  # re-exported
from wire.addresses import address_for, env_name
from wire.tls import TLS_DIR_ENV

# Set to 1: a service listens without TLS beyond loopback (and warns). Loudly named on purpose.
PLAINTEXT_ENV = "TELEROBOT_ALLOW_PLAINTEXT_NETWORK"

DEFAULT_GRACE_S = 2.0
# Each gRPC service serves Prometheus metrics (plain HTTP, read-only) on loopback at a port of
# its own, fixed so that Prometheus can scrape it (the gRPC port's last two digits after 94),
# unless its TELEROBOT_<NAME>_METRICS_ADDRESS or --metrics-address says otherwise ("off": none).
# A service whose own port is 0 (a free one: the tests' many stations at once) serves its
# metrics on a free port too (FREE_METRICS_ADDRESS).
DEFAULT_METRICS_PORTS = {
    "world": 9450,
    "decision_server": 9451,
    "proxy_robot": 9452,
    "force_sensor": 9453,
    "stereo_camera": 9454,
    "emergency_stop": 9455,
}
FREE_METRICS_ADDRESS = f"{DEFAULT_HOST}:0"
METRICS_OFF = "off"
# Set to 1: a service may serve its metrics beyond loopback (plain HTTP, no authentication).
METRICS_NETWORK_ENV = "TELEROBOT_ALLOW_METRICS_NETWORK"


def default_metrics_address(service: str) -> str:
    """Where `service` serves its metrics unless told otherwise: its fixed port on loopback."""
    return f"{DEFAULT_HOST}:{DEFAULT_METRICS_PORTS.get(service, 0)}"


def metrics_address_for(service: str, address: str) -> str:
    """Where `service`, listening on `address`, serves its metrics when neither its flag nor
    its variable says: its fixed port on loopback, or a free port on loopback when `address`'s
    own port is 0 (so that stations on free ports, many at once, never collide)."""
    if address.rsplit(":", 1)[-1] == "0":
        return FREE_METRICS_ADDRESS
    return default_metrics_address(service)


class _UnsetMetricsAddress(str):
    """--metrics-address's default when its variable is unset: replaced once the arguments are
    parsed by what `metrics_address_for` says for the service's --address."""


class ServiceParser(argparse.ArgumentParser):
    """A service's parser: after parsing, a --metrics-address neither given nor set in the
    environment follows --address (a free port when it is port 0)."""

    service = ""

    def parse_known_args(self, args=None, namespace=None):
        namespace, extras = super().parse_known_args(args, namespace)
        chosen = getattr(namespace, "metrics_address", None)
        if isinstance(chosen, _UnsetMetricsAddress) and hasattr(namespace, "address"):
            namespace.metrics_address = metrics_address_for(self.service, namespace.address)
        return namespace, extras


def add_arm_argument(parser: argparse.ArgumentParser) -> None:
    """--arm: the arm the station drives, one of its description files (see select_arm_from)."""
    parser.add_argument(
        "--arm", default=selected_arm_name(),
        help=f"the arm: {', '.join(available_arms())} (env {ARM_ENV}; default "
             f"{DEFAULT_ARM})")


def select_arm_from(args: argparse.Namespace, log: logging.Logger, read: bool = True) -> bool:
    """Make args.arm this process's arm (its children inherit it); False, with the reason
    logged, when there is no such arm or (`read`: the process loads its model) its file is
    broken."""
    try:
        select_arm(args.arm, read)
    except (UnknownArmError, ArmDescriptionError) as error:
        log.error("not starting: %s", error)
        return False
    return True


def base_parser(service: str, description: str) -> argparse.ArgumentParser:
    """Flags every service process takes; each default comes from the environment first."""
    parser = ServiceParser(prog=f"python -m services.{service}", description=description)
    parser.service = service
    parser.add_argument(
        "--address", default=address_for(service),
        help=f"host:port to listen on (env {env_name(service, 'address')}); "
             "port 0 picks a free one",
    )
    parser.add_argument(
        "--log-level", default=os.environ.get("TELEROBOT_LOG_LEVEL", "INFO"),
        help="DEBUG, INFO, WARNING or ERROR (env TELEROBOT_LOG_LEVEL)",
    )
    add_arm_argument(parser)
    parser.add_argument(
        "--grace-s", type=float,
        default=float(os.environ.get("TELEROBOT_GRACE_S", DEFAULT_GRACE_S)),
        help="on SIGINT/SIGTERM, how long in-flight calls may finish (env TELEROBOT_GRACE_S)",
    )
    parser.add_argument(
        "--tls-dir", default=os.environ.get(TLS_DIR_ENV, ""),
        help=f"serve mutual TLS with <name>.pem/.key and ca.pem from this directory (env "
             f"{TLS_DIR_ENV}; `make certs` writes var/pki); unset: plaintext, loopback only",
    )
    parser.add_argument(
        "--token-address", default=os.environ.get(env_name(service, "token_address"), ""),
        help="with --tls-dir, also listen here (TLS without client certificates) for callers "
             f"with bearer tokens (env {env_name(service, 'token_address')})",
    )
    parser.add_argument(
        "--allow-plaintext-network", action="store_true",
        default=os.environ.get(PLAINTEXT_ENV, "") == "1",
        help="DANGEROUS: listen without TLS on a non-loopback address, so that anyone who "
             f"reaches the port can command the arm (env {PLAINTEXT_ENV}=1)",
    )
    parser.add_argument(
        "--metrics-address",
        default=os.environ.get(env_name(service, "metrics_address"),
                               _UnsetMetricsAddress(default_metrics_address(service))),
        help="host:port to serve Prometheus metrics on, at /metrics (env "
             f"{env_name(service, 'metrics_address')}; default "
             f"{default_metrics_address(service)}, or a free port on loopback when --address's "
             f"port is 0; {METRICS_OFF!r}: none)",
    )
    parser.add_argument(
        "--allow-metrics-network", action="store_true",
        default=os.environ.get(METRICS_NETWORK_ENV, "") == "1",
        help="serve the metrics beyond loopback (plain HTTP: anyone who reaches the port reads "
             f"them; they command nothing) (env {METRICS_NETWORK_ENV}=1)",
    )
    parser.add_argument(
        "--client-lane-limit", type=Lane.parse,
        default=Lane.parse(os.environ.get("TELEROBOT_CLIENT_LANE_LIMIT", "high")),
        help="highest lane a client may ask for in telerobot-lane metadata "
             "(env TELEROBOT_CLIENT_LANE_LIMIT)",
    )
    return parser


# A record's message never exceeds this, whatever text a client managed to get into it.
MAX_LOG_MESSAGE_CHARS = 2000
_CONTROL_CHARACTERS = {c: f"\\x{c:02x}" for c in (*range(0x20), 0x7f)}


class OneLineFormatter(logging.Formatter):
    """One line per record: control characters in the message (newlines, escapes, NULs from
    a client's string) are escaped and the message is cut at MAX_LOG_MESSAGE_CHARS, so no
    client text can forge log lines or flood the log. Tracebacks stay as they are."""

    def formatMessage(self, record: logging.LogRecord) -> str:  # noqa: N802 - logging's name
        record.message = loggable(record.message)
        return super().formatMessage(record)


def loggable(text: str) -> str:
    """`text` escaped to one line and cut to MAX_LOG_MESSAGE_CHARS."""
    text = text.translate(_CONTROL_CHARACTERS)
    if len(text) > MAX_LOG_MESSAGE_CHARS:
        text = f"{text[:MAX_LOG_MESSAGE_CHARS]}… ({len(text)} characters)"
    return text


def configure_logging(service: str, level: str) -> None:
    """One line per record on stderr, tagged with the service name and pid."""
    handler = logging.StreamHandler(sys.stderr)
    handler.setFormatter(OneLineFormatter(
        f"%(asctime)s {service}[%(process)d] %(levelname)s %(name)s: %(message)s"))
    logging.basicConfig(level=level.upper(), handlers=[handler])
