"""python -m services.launcher (`make serve`): start the slave station, one process per service.

It starts every service in turn, each once the one before answers its health check with
SERVING (dependencies first), prints the addresses, and supervises them. On Ctrl-C or SIGTERM
it stops them all (SIGTERM, then SIGKILL after a deadline) and exits.

If a child ends on its own, the launcher says which and how, shows its last log lines, and
restarts it on the same address after a capped back-off (services.runtime.restart): the arm
holds meanwhile (each layer's watchdog, see docs/operations.md), and the rest of the station,
the stop button and the video included, keeps serving. Two exceptions stop the whole station:
the world (the hardware link: nothing can be commanded without it; on a real arm, ProxyRobot,
which owns that link) and a child that failed too often (5 times within 60 s), which a
supervisor above (systemd) can take over. When several children are down, the emergency-stop
band is restarted first. What the launcher knows about each child is in the file
TELEROBOT_SUPERVISOR_STATE names (services.runtime.supervisor_state), which it sets for its
children: the DecisionServer reports a dependency as restarting from it, and a restarted
ProxyRobot learns from TELEROBOT_RESTARTED_BECAUSE why it was restarted.

Children run in their own process group, so a terminal's Ctrl-C reaches only the launcher, which
then drains each child once; each child also stops by itself if the launcher is killed. Started
with TELEROBOT_PARENT_PID set (by `make teleop`, the tests), the launcher in turn stops the
station if that parent goes away.

Each service listens where its TELEROBOT_<NAME>_ADDRESS says (default: config.DEFAULT_PORTS).
A port 0 there picks a free port: the launcher reads the one bound from the child's ready line
and hands it to the services started after it through the same variable. Once a service is
SERVING the launcher prints its ready line, `TELEROBOT_READY <name> <host:port>`, on stdout,
so whoever started the launcher (`make teleop`, the tests) learns every address; the station is
up once decision_server's line is out, and then the banner follows. The children are supervised
by services.runtime.children.

The arm is simulated by default. `--driver franka --robot-host HOST` drives a Franka instead:
no world is started, and ProxyRobot, first, mirrors the Franka on the station's shared memory
for the sensor, the cameras and the band (services/proxy_robot/arm_mirror.py).
`--driver franka-sim` does the same against franka-sim, which the launcher starts on loopback
as the robot (from .venv-franka; the push on the tool from the joint-impedance spring).
"""

from __future__ import annotations

import argparse
import logging
import os
import signal
import socket
import ssl
import sys
import tempfile
import threading
import time
import urllib.request
from pathlib import Path

import grpc
from grpc_health.v1 import health_pb2, health_pb2_grpc

from discovery.advertise import ADVERTISE_ENV, advertised
from services.franka_sim.process import start_franka_sim
from services.runtime import children
from services.runtime.children import Child, ChildFailed
from services.runtime.config import (
    DEFAULT_GRACE_S,
    add_arm_argument,
    configure_logging,
    select_arm_from,
)
from services.runtime.port_watch import OK as PORT_OK
from services.runtime.port_watch import accepts
from services.runtime.process import metrics_port_name, token_port_name, watch_parent
from services.runtime.restart import RestartPolicy, RestartTracker
from services.runtime.supervisor_state import (
    GAVE_UP,
    RESTARTED_BECAUSE_ENV,
    RESTARTING,
    RUNNING,
    SUPERVISOR_STATE_ENV,
    ChildState,
    write_state,
)
from services.runtime.tls import station_channel_security
from services.web_console.https import certificate_files
from wire.addresses import env_name
from wire.local_call import LOCAL_CALLS_ENV
from wire.observation import ROUTER_ENV, BadEndpoint, address_of, checked_endpoint, endpoint_for
from wire.processes import dump_stacks_on_signal, handle_signals, parse_ready_line, ready_line, say
from wire.tls import IDENTITY_ENV, TLS_DIR_ENV, ChannelSecurity, dialable, open_channel

log = logging.getLogger("launcher")

# Start order: dependencies first (the world stands in for the hardware). Stop order is the
# reverse, so the hardware goes last.
STATION = ["world", "emergency_stop", "proxy_robot", "force_sensor", "stereo_camera",
           "zenoh_router", "decision_server", "web_console", "foxglove", "observation"]
# On a real arm ProxyRobot owns the hardware link and the shared memory, in the world's place.
HARDWARE_STATION = ["proxy_robot", *(name for name in STATION
                                     if name not in ("world", "proxy_robot"))]
DRIVERS = ("sim", "franka", "franka-sim")
# The children's own settings (their flags' variables), which they inherit.
DRIVER_ENV = env_name("proxy_robot", "driver")
ROBOT_HOST_ENV = env_name("proxy_robot", "robot_host")
TORQUE_SOURCE_ENV = env_name("proxy_robot", "torque_source")
FORCE_SENSOR_ENV = env_name("force_sensor", "sensor")
FRANKA_SIM_HOST = "127.0.0.1"

# Children that answer HTTP, not gRPC: their health is GET /healthz (the browser console).
HTTP_CHILDREN = {"web_console"}
# Children that speak only WebSocket: they serve once they answer a handshake (the live view).
WEBSOCKET_CHILDREN = {"foxglove"}
# Children that speak only Zenoh: the router serves once it accepts a connection; the
# publisher once it said so (its ready line comes after it joined the router).
ZENOH_CHILDREN = {"zenoh_router", "observation"}
# The gRPC services: health checked over gRPC, each with its Prometheus /metrics port.
GRPC_CHILDREN = tuple(name for name in STATION
                      if name not in HTTP_CHILDREN | WEBSOCKET_CHILDREN | ZENOH_CHILDREN)
STARTUP_TIMEOUT_S = 60.0
# The banner's first line.
UP_LINE = "Slave station is up"
# After SIGTERM, a child has its grace period to drain and this long on top to exit.
STOP_MARGIN_S = 1.5
_LOG_TAIL_LINES = 20


def station_services(driver: str, own_router: bool = True) -> list[str]:
    """The station's services in start order, for the arm's `driver`; without the Zenoh
    router when the station joins another one (`own_router` False)."""
    services = STATION if driver == "sim" else HARDWARE_STATION
    return [name for name in services if own_router or name != "zenoh_router"]


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m services.launcher", description=__doc__)
    parser.add_argument("--grace-s", type=float, default=DEFAULT_GRACE_S,
                        help="how long each service may drain in-flight calls on stop")
    parser.add_argument("--log-level", default=os.environ.get("TELEROBOT_LOG_LEVEL", "INFO"))
    add_arm_argument(parser)
    parser.add_argument("--driver", choices=DRIVERS, default=os.environ.get(DRIVER_ENV, "sim"),
                        help=f"the arm's driver: the simulated world (sim), a Franka through "
                             f"libfranka (franka, with --robot-host and --arm fr3), or "
                             f"franka-sim started here as the Franka (franka-sim) (env "
                             f"{DRIVER_ENV})")
    parser.add_argument("--robot-host", default=os.environ.get(ROBOT_HOST_ENV, ""),
                        help=f"the Franka's address for --driver franka (env {ROBOT_HOST_ENV})")
    parser.add_argument("--tls-dir", default=os.environ.get(TLS_DIR_ENV, ""),
                        help=f"run every service with mutual TLS from this directory (env "
                             f"{TLS_DIR_ENV}; `make certs` writes var/pki)")
    parser.add_argument("--max-failures", type=int,
                        default=int(os.environ.get("TELEROBOT_MAX_FAILURES",
                                                   RestartPolicy.max_failures)),
                        help="a child that ends this many times within 60 s is given up on, "
                             "and the station stops (env TELEROBOT_MAX_FAILURES)")
    # Discovery: operator stations on the network find the station (discovery).
    parser.add_argument("--advertise", dest="advertise", action="store_const", const="1",
                        default=os.environ.get(ADVERTISE_ENV) or "auto",
                        help=f"advertise the station over mDNS (_telerobot._tcp) even when its "
                             f"DecisionServer is on loopback (env {ADVERTISE_ENV}=1|0|auto; "
                             "default auto: when it listens beyond loopback)")
    parser.add_argument("--no-advertise", dest="advertise", action="store_const", const="0",
                        help="do not advertise the station")
    parser.add_argument("--zenoh-router", default=os.environ.get(ROUTER_ENV, ""),
                        help="publish the observation through this Zenoh router, tls/HOST:PORT "
                             "(tcp/ on loopback), instead of starting one beside the station "
                             f"(env {ROUTER_ENV})")
    args = parser.parse_args(argv)
    configure_logging("launcher", args.log_level)
    if not select_arm_from(args, log):  # every child inherits the choice
        return 2
    if args.zenoh_router:
        try:
            checked_endpoint(args.zenoh_router, tls=bool(args.tls_dir))
        except BadEndpoint as error:
            log.error("--zenoh-router: %s", error)
            return 2
    dump_stacks_on_signal()
    health_security = station_channel_security(args.tls_dir or None, "launcher")

    stop = threading.Event()  # SIGINT, SIGTERM, or the parent gone
    wake = threading.Event()  # a stop request, or a child ended
    stop_reason: list[str] = []

    def request_stop(reason: str) -> None:
        stop_reason.append(reason)
        stop.set()
        wake.set()

    def on_signal(signum: int) -> None:
        request_stop(f"{signal.Signals(signum).name} received")

    handle_signals({signal.SIGINT: on_signal, signal.SIGTERM: on_signal})
    # Started by a supervisor of its own (`make teleop`, the tests): stop with it.
    watch_parent(lambda: request_stop("the parent process is gone"), stop)

    env = {"TELEROBOT_GRACE_S": str(args.grace_s)}
    if args.tls_dir:
        env[TLS_DIR_ENV] = str(Path(args.tls_dir).resolve())
    robot = None  # franka-sim, when it stands in for the Franka
    if args.driver == "franka-sim":
        try:
            robot = start_franka_sim(FRANKA_SIM_HOST, max_lines=_LOG_TAIL_LINES)
        except ChildFailed as failed:
            log.error("start-up failed: %s", failed)
            return 1
        env.update({ROBOT_HOST_ENV: FRANKA_SIM_HOST, TORQUE_SOURCE_ENV: "impedance"})
    elif args.robot_host:
        env[ROBOT_HOST_ENV] = args.robot_host
    env[DRIVER_ENV] = "sim" if args.driver == "sim" else "franka"
    if args.driver != "sim":  # the Franka's own estimate of the push, mirrored by ProxyRobot
        env[FORCE_SENSOR_ENV] = "franka"
    if args.zenoh_router:  # the publisher joins it (services.observation), the door watches it
        env[ROUTER_ENV] = args.zenoh_router
        env[env_name("zenoh_router", "address")] = address_of(args.zenoh_router)
    services = station_services(args.driver, own_router=not args.zenoh_router)
    with tempfile.TemporaryDirectory(prefix="telerobot-station-") as run_dir:
        env[SUPERVISOR_STATE_ENV] = str(Path(run_dir) / "supervisor.json")
        # The moves between the station's own processes, off gRPC (wire/local_call.py).
        env[LOCAL_CALLS_ENV] = str(Path(run_dir) / "proxy_robot.sock")
        station = _Station(env, health_security, stop, wake,
                           RestartPolicy(max_failures=args.max_failures), services)
        try:
            # One at a time: a service starts once the ones it depends on answer, so its first
            # calls to them do not fail and leave its channels backing off.
            for name in services:
                try:
                    address = station.start(name)
                except ChildFailed as failed:
                    log.error("start-up failed: %s", failed)
                    return 1
                if address is None:  # stopped during start-up
                    return 0
                for other, other_address in station.children[name].ready.items():
                    if other != name:  # its token and metrics ports, if it has them
                        say(ready_line(other, other_address))
                say(ready_line(name, address))
            _print_banner(list(station.children.values()), args.tls_dir)
            door = station.children["decision_server"]
            # Withdrawn on leaving the block, before the children stop: however it ends.
            with advertised(door.address, tls=bool(args.tls_dir), mode=args.advertise,
                            token_address=door.ready.get(token_port_name("decision_server"))):
                failure = station.supervise()
            if failure is not None:
                log.error("%s", failure)
                return 1
            log.info("%s; stopping the station",
                     stop_reason[0] if stop_reason else "stop requested")
            return 0
        finally:
            children.stop_all(reversed(list(station.children.values())),
                              args.grace_s + STOP_MARGIN_S)
            if robot is not None:
                robot.stop(signal.SIGTERM)


class _Station:
    """The children, by name, each restarted under the policy when it ends on its own."""

    def __init__(self, env: dict[str, str], security: ChannelSecurity, stop: threading.Event,
                 wake: threading.Event, policy: RestartPolicy, services: list[str]):
        self.env = env  # every child's; a started child's bound address is added to it
        self.children: dict[str, Child] = {}
        self._services = services
        self._hardware = services[0]  # the one that owns the hardware link
        self._security = security
        self._stop = stop
        self._wake = wake
        self._trackers = {name: RestartTracker(policy) for name in services}
        self._states: dict[str, ChildState] = {}
        self._state_path = Path(env[SUPERVISOR_STATE_ENV])

    def start(self, name: str, restarted_because: str | None = None) -> str | None:
        """Start `name` and wait until it serves; its address, or None if a stop came first.
        ChildFailed if it died or did not serve in time."""
        extra = {RESTARTED_BECAUSE_ENV: restarted_because} if restarted_because else {}
        child = children.start(name, ["-m", f"services.{name}"], env={**self.env, **extra},
                               max_lines=_LOG_TAIL_LINES, on_line=_forward,
                               on_exit=lambda _child: self._wake.set())
        self.children[name] = child
        address = _wait_until_serving(child, self._stop, self._security)
        if address is not None:
            # The address it bound (a port 0 becomes a real one): the services started after
            # it find it through its variable, and a restart binds the same one.
            self.env[env_name(name, "address")] = address
            token_address = child.ready.get(token_port_name(name))
            if token_address:  # the DecisionServer's token port, for the web console
                self.env[env_name(name, "token_address")] = token_address
            metrics_address = child.ready.get(metrics_port_name(name))
            if metrics_address:  # a restart serves its metrics where Prometheus scrapes
                self.env[env_name(name, "metrics_address")] = metrics_address
            self._set_state(name, RUNNING, self._trackers[name].restarts)
        return address

    def supervise(self) -> str | None:
        """Restart children that end on their own until a stop request (None), or until the
        world ends or a child fails too often (why the station must stop)."""
        due: dict[str, float] = {}  # child -> when to restart it
        while True:
            timeout = min([1.0, *(t - time.monotonic() for t in due.values())])
            self._wake.wait(max(timeout, 0.0))
            self._wake.clear()
            if self._stop.is_set():
                return None
            now = time.monotonic()
            for name, child in self.children.items():
                if name in due or not child.exited.is_set():
                    continue
                if name == self._hardware:
                    return (f"{child.describe()}\nthe hardware link is gone: stopping the whole "
                            "station")
                delay = self._trackers[name].failed(now)
                if delay is None:
                    self._set_state(name, GAVE_UP, self._trackers[name].restarts,
                                    child.how_it_ended())
                    return (f"{child.describe()}\n{name} failed "
                            f"{self._trackers[name].describe_limit()}: stopping the station")
                log.error("%s\nrestarting %s in %.1f s", child.describe(), name, delay)
                self._set_state(name, RESTARTING, self._trackers[name].restarts,
                                child.how_it_ended())
                due[name] = now + delay
            # The stop button first, then in start order (dependencies first).
            ready = sorted((n for n, t in due.items() if t <= now), key=self._restart_order)
            for name in ready:
                del due[name]
                if not self._restart(name):
                    return None

    def _restart(self, name: str) -> bool:
        """Start `name` again; False if a stop request came first. A restart that fails is
        noticed as another failure by `supervise`."""
        because = self._states[name].last_exit
        self._trackers[name].restarts += 1
        try:
            address = self.start(name, restarted_because=because)
        except ChildFailed as failed:
            log.error("restarting %s failed: %s", name, failed)
            self.children[name].stop()  # if it hangs without serving; then it has exited
            self._wake.set()
            return True
        if address is None:
            return False
        log.warning("%s restarted on %s (restart %d; it %s)", name, address,
                    self._trackers[name].restarts, because)
        return True

    def _restart_order(self, name: str) -> int:
        return -1 if name == "emergency_stop" else self._services.index(name)

    def _set_state(self, name: str, state: str, restarts: int, last_exit: str = "") -> None:
        previous = self._states.get(name)
        self._states[name] = ChildState(state, restarts,
                                        last_exit or (previous.last_exit if previous else ""),
                                        time.time())
        write_state(self._state_path, self._states)


def _forward(_child: Child, line: str) -> None:
    """A child's log line, to the launcher's stderr (its ready line is the launcher's to say)."""
    if parse_ready_line(line) is None:
        say(line, sys.stderr)


def _wait_until_serving(child: Child, stop: threading.Event,
                        security: ChannelSecurity) -> str | None:
    """The child's address once it printed its ready line and answers its health check with
    SERVING; None if a stop was requested first; ChildFailed if it died or took too long."""
    deadline = time.monotonic() + STARTUP_TIMEOUT_S
    address = child.wait_ready(timeout_s=STARTUP_TIMEOUT_S, cancel=stop)
    serving = (_http_serving if child.name in HTTP_CHILDREN
               else _websocket_serving if child.name in WEBSOCKET_CHILDREN
               else _zenoh_serving if child.name in ZENOH_CHILDREN else _is_serving)
    while address is not None and not serving(address, security, child.name):
        if child.returncode is not None:
            raise ChildFailed(child.describe())
        if time.monotonic() > deadline:
            hint = (" (over TLS its certificate must name it: `make certs` reissues a PKI "
                    "made before service names)" if security.secure else "")
            raise ChildFailed(f"{child.name} not serving after {STARTUP_TIMEOUT_S:.0f} s"
                              f"{hint}: {child.describe()}")
        if stop.wait(0.05):
            return None
    if address is not None:
        log.info("%s is serving on %s", child.name, address)
    return address


def _is_serving(address: str, security: ChannelSecurity, service: str) -> bool:
    try:
        # Over TLS the certificate must name the service: a PKI made before service names
        # fails here, and `make certs` reissues it.
        with open_channel(address, security=security, service=service) as channel:
            reply = health_pb2_grpc.HealthStub(channel).Check(
                health_pb2.HealthCheckRequest(service=""), timeout=1.0)
        return reply.status == health_pb2.HealthCheckResponse.SERVING
    except grpc.RpcError:
        return False


def _http_serving(address: str, security: ChannelSecurity, _service: str) -> bool:
    """Whether the web console answers /healthz: over HTTPS when the TLS directory has its
    certificate (as the console itself decides), else HTTP."""
    https = security.secure and certificate_files(security.tls_dir) is not None
    context = None
    if https:
        # Its chain is checked (the station's CA, or one this host trusts), not its names: the
        # launcher dials the address its own child reported, by IP, which a certificate for
        # browsers' names need not carry.
        context = ssl.create_default_context(cafile=str(security.tls_dir / "ca.pem"))
        context.load_default_certs()
        context.check_hostname = False
    url = f"{'https' if https else 'http'}://{dialable(address)}/healthz"
    try:
        with urllib.request.urlopen(url, timeout=1.0, context=context) as reply:
            return reply.status == 200
    except OSError:  # (ssl.SSLError and urllib's URLError are)
        return False


def _zenoh_serving(address: str, _security: ChannelSecurity, service: str) -> bool:
    """Whether the router accepts a TCP connection at `address`; the publisher serves once its
    ready line is out (it joined the router first)."""
    return service != "zenoh_router" or accepts(address) == PORT_OK


def _websocket_serving(address: str, security: ChannelSecurity, _service: str) -> bool:
    """Whether a Foxglove WebSocket server answers a handshake at `address` (wss:// with the
    station's CA when TLS is on); it is closed at once, as a client that leaves. A bare TCP
    connect would do, but the server logs every connection that never shakes hands as an
    error."""
    host, _, port = dialable(address).rpartition(":")
    host = host.strip("[]")
    request = (f"GET / HTTP/1.1\r\nHost: {host}:{port}\r\nUpgrade: websocket\r\n"
               "Connection: Upgrade\r\nSec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\n"
               "Sec-WebSocket-Version: 13\r\nSec-WebSocket-Protocol: foxglove.sdk.v1\r\n\r\n")
    try:
        with socket.create_connection((host, int(port)), timeout=1.0) as raw:
            stream = raw
            if security.secure:
                context = ssl.create_default_context(cafile=str(security.tls_dir / "ca.pem"))
                stream = context.wrap_socket(raw, server_hostname=host)
            stream.sendall(request.encode())
            answered = stream.recv(12).startswith(b"HTTP/1.1 101")
            if answered:
                stream.sendall(b"\x88\x80\x00\x00\x00\x00")  # a close frame (masked, empty)
            return answered
    except OSError:  # (ssl.SSLError is one)
        return False


def _print_banner(station: list[Child], tls_dir: str) -> None:
    operator = next(c.address for c in station if c.name == "decision_server")
    extra_ports = [(name, address) for c in station for name, address in c.ready.items()
                   if name == token_port_name(c.name)]
    metrics = [(c.name, c.ready[metrics_port_name(c.name)]) for c in station
               if metrics_port_name(c.name) in c.ready]
    width = max(len(name) for name in [*(c.name for c in station), *dict(extra_ports)])
    lines = ["", f"{UP_LINE}{' with mutual TLS' if tls_dir else ''}. Ctrl-C stops it.", ""]
    lines += [f"  {c.name:<{width}}  {c.address}  (pid {c.pid})" for c in station]
    lines += [f"  {name:<{width}}  {address}  (bearer tokens)" for name, address in extra_ports]
    if metrics:
        lines += ["", "Prometheus metrics (scrape these; TELEROBOT_<NAME>_METRICS_ADDRESS moves "
                      "one):"]
        lines += [f"  {name:<{width}}  http://{address}/metrics" for name, address in metrics]
    console = next((c.address for c in station if c.name == "web_console"), None)
    if console and certificate_files(tls_dir) is not None:
        lines += ["", f"The web console: https://{dialable(console)}/ (a browser that trusts "
                      f"{tls_dir.rstrip('/')}/ca.pem; sign in with a token from `python -m "
                      "services.security.tokens issue`)"]
    elif console:
        lines += ["", f"The web console: http://{console}/ (in any browser on this host)"]
    live = next((c.address for c in station if c.name == "foxglove"), None)
    if live:
        lines += [f"The live view: {'wss' if tls_dir else 'ws'}://{live} (Foxglove or "
                  "Lichtblick: Open connection > Foxglove WebSocket; layout "
                  "docs/foxglove_layout.json)"]
    router = next((c.address for c in station if c.name == "zenoh_router"), None)
    if router:
        lines += [f"Observers: python -m clients.observe --router "
                  f"{endpoint_for(router, tls=bool(tls_dir))} (Zenoh; docs/observers.md)"]
    lines += ["", f"The operator's address is {operator} (set "
                  f"{env_name('decision_server', 'address')} to move it). Try:"]
    if tls_dir:
        pki = tls_dir.rstrip("/")
        files = (f"{pki}/ca.pem", f"{pki}/operator.pem", f"{pki}/operator.key")
        grpcurl = "grpcurl -cacert {} -cert {} -key {}".format(*files)
        lines += [
            f"  {grpcurl} {operator} list",
            f"  {grpcurl} {operator} grpc.health.v1.Health/Check",
            "or, without grpcurl:",
            "  npx buf curl --protocol grpc --list-methods --cacert {} --cert {} --key {} "
            .format(*files) + f"https://{operator}",
            f"Clients: {TLS_DIR_ENV}={pki} (and {IDENTITY_ENV}=observer|operator|admin) "
            "make teleop",
        ]
    else:
        lines += [
            f"  grpcurl -plaintext {operator} list",
            f"  grpcurl -plaintext {operator} grpc.health.v1.Health/Check",
            "or, without grpcurl:",
            f"  npx buf curl --protocol grpc --http2-prior-knowledge --list-methods "
            f"http://{operator}",
        ]
    say("\n".join([*lines, ""]))


if __name__ == "__main__":
    raise SystemExit(main())
