"""The slave station a bench run starts for itself, and the set-up calls the bench makes to it.

Its services listen on loopback port 0 (each reports the port it bound) with a shared-memory
name of the run's own, so it never meets a `make serve` or a test. A twin of it may serve
mutual TLS on the same world (bench/run.py starts it when a group with a `*_tls` row runs); one
station drives the world at a time.
"""

from __future__ import annotations

from pathlib import Path

from bench.procs import Child, ChildFailed, ProcessSet
from services.security.audit import AUDIT_DIR_ENV
from telerobot.v1 import (
    force_sensor_pb2,
    force_sensor_pb2_grpc,
    proxy_robot_pb2,
    proxy_robot_pb2_grpc,
    types_pb2,
)
from wire.local_call import LOCAL_CALLS_ENV
from wire.tls import TLS_DIR_ENV, ChannelSecurity, open_channel

SETUP_TIMEOUT_S = 10.0
# With TLS, ProxyRobot's inner port takes commands only from the station's or an admin's
# certificate: the bench's own set-up calls and the command worker present the admin one.
ADMIN_IDENTITY = "admin"
OPERATOR_IDENTITY = "operator"  # Teleoperate needs the operator role (and binds the lease)


class Station:
    """The slave station's processes for this run, and the set-up calls the bench makes.

    With `tls_dir` (a PKI from services.security.pki) its services serve mutual TLS and write
    their audit logs to `audit_dir`, and the bench's calls to them present the admin
    certificate. `world`: a running world to join (its shared memory) instead of starting
    one; only one station drives a world at a time (arm_ready, release)."""

    def __init__(self, procs: ProcessSet, shm_name: str, tls_dir: Path | None = None,
                 audit_dir: Path | None = None, world: Child | None = None):
        self.procs = procs
        self.suffix = "_tls" if tls_dir else ""  # of its processes' names
        self.shm = shm_name
        self.tls_dir = tls_dir
        self.security = ChannelSecurity(tls_dir, ADMIN_IDENTITY)  # plaintext without tls_dir
        # The DecisionServer moves the arm over ProxyRobot's local socket, as `make serve`
        # starts a station.
        self.env = ({TLS_DIR_ENV: str(tls_dir), AUDIT_DIR_ENV: str(audit_dir)} if tls_dir
                    else {})
        self.env[LOCAL_CALLS_ENV] = str(procs.scratch / f"proxy_robot{self.suffix}-{shm_name}"
                                        f".sock")
        self.world = world
        self.address: dict[str, str] = {}  # service -> host:port, from its ready line

    def client_params(self, identity: str) -> dict:
        """A worker's parameters to reach this station: its TLS directory and the identity
        whose certificate to present; none for plaintext."""
        return {"tls_dir": str(self.tls_dir), "identity": identity} if self.tls_dir else {}

    def start(self) -> None:
        if self.world is None:
            self.world, self.address["world"] = self.procs.run_service("world")
        services = ("proxy_robot", "force_sensor", "emergency_stop")
        started = [self.procs.start_service(service, name=service + self.suffix, env=self.env)
                   for service in services]
        for service, child in zip(services, started, strict=True):
            self.address[service] = child.wait_ready(service, timeout_s=60.0)
        self.proxy, self.sensor = started[0], started[1]

    def arm_ready(self) -> None:
        """ProxyRobot connected, initialized and not stopped; the sensor reading. Also brings
        them back after a hiccup (on an overloaded machine a world that has not stepped for
        100 ms counts as gone: the proxy drops its link, the sensor stops sampling)."""
        for child in (self.world, self.proxy, self.sensor):
            if child.process.poll() is not None:
                raise ChildFailed(f"a station process died: {child.describe()}")
        with open_channel(self.address["proxy_robot"], security=self.security) as channel:
            robot = proxy_robot_pb2_grpc.ProxyRobotStub(channel)
            status = robot.GetStatus(proxy_robot_pb2.GetStatusRequest(),
                                     timeout=SETUP_TIMEOUT_S).status
            if status == types_pb2.ROBOT_STATUS_NOT_CONNECTED:
                status = robot.Connect(proxy_robot_pb2.ConnectRequest(),
                                       timeout=SETUP_TIMEOUT_S).status
            if status in (types_pb2.ROBOT_STATUS_ESTOPPED, types_pb2.ROBOT_STATUS_FAULT):
                status = robot.Reset(proxy_robot_pb2.ResetRequest(),
                                     timeout=SETUP_TIMEOUT_S).status
            if status == types_pb2.ROBOT_STATUS_CONNECTED:
                robot.Initialize(proxy_robot_pb2.InitializeRequest(), timeout=SETUP_TIMEOUT_S)
        with open_channel(self.address["force_sensor"], security=self.security) as channel:
            sensor = force_sensor_pb2_grpc.ForceSensorStub(channel)
            sensor.StartReading(force_sensor_pb2.StartReadingRequest(), timeout=SETUP_TIMEOUT_S)

    def release(self) -> None:
        """ProxyRobot disconnected (the world's command record is free for another driver)
        and the sensor stopped (one sampler at a time)."""
        with open_channel(self.address["proxy_robot"], security=self.security) as channel:
            proxy_robot_pb2_grpc.ProxyRobotStub(channel).Disconnect(
                proxy_robot_pb2.DisconnectRequest(), timeout=SETUP_TIMEOUT_S)
        with open_channel(self.address["force_sensor"], security=self.security) as channel:
            force_sensor_pb2_grpc.ForceSensorStub(channel).StopReading(
                force_sensor_pb2.StopReadingRequest(), timeout=SETUP_TIMEOUT_S)
