"""python -m services.decision_server: the operator's one address.

It serves DecisionServer and, as IDecisionServer inherits IProxyRobot and IForceSensor, the
ProxyRobot and ForceSensor services too, forwarded to their own processes with the supervisory
checks in front; StereoCamera is forwarded as well, so one address reaches everything.
"""

from __future__ import annotations

import argparse
import os
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path

import grpc

from services.common.fanout import Subscription
from services.decision_server.backends import GrpcSlave
from services.decision_server.camera_feed import CameraSource
from services.decision_server.core import ControlChanged, DecisionCore
from services.decision_server.dependencies import SERVING, DependencyWatch
from services.decision_server.recordings import RecordingStore
from services.decision_server.servicer import DecisionServerServicer, make_facades
from services.decision_server.writer_process import WriterProcesses
from services.runtime.lanes import DEFAULT_LANES, Lane, LaneConfig
from services.runtime.metrics import ServiceMetrics
from services.runtime.port_watch import PortWatch
from services.runtime.priority import COMMAND_PATH_FIFO_PRIORITY
from services.runtime.process import run_service
from services.runtime.server import ServiceBinding, binding
from services.runtime.service import HealthReporter, Service
from services.runtime.tls import station_channel_security
from telerobot.v1 import decision_server_pb2_grpc, stereo_camera_pb2_grpc
from wire.addresses import address_for, env_name
from wire.local_call import LOCAL_CALLS_ENV
from wire.stereo import LOW_LATENCY_OPTIONS
from wire.tls import open_channel

# Each dependency's health entry on this server: telerobot.v1.DecisionServer/<dependency>.
DEPENDENCY_HEALTH_PREFIX = "telerobot.v1.DecisionServer/"
HEALTH_ANSWER_TIMEOUT_S = 2.0
# Waiting for a lock or at a cobegin barrier holds a medium-lane thread, so give it more.
# The recordings' video: enough for 320x240 per eye at 30 fps with the scene's detail, a
# fraction of the stream an operator watches.
RECORDING_VIDEO_KBIT = 1000
LANES = {**DEFAULT_LANES,
         Lane.MEDIUM: LaneConfig(static_threads=2, max_threads=32, queue_capacity=64)}


@dataclass
class DecisionService(Service):
    args: argparse.Namespace
    lanes: dict = field(default_factory=lambda: LANES)
    operator_door = True  # the one port that takes operators' commands (see services.runtime)
    core: DecisionCore | None = None
    dependencies: DependencyWatch | None = None
    _slave: GrpcSlave | None = None
    _stereo_channel: grpc.Channel | None = None
    _router_watch: PortWatch | None = None
    _servicer: DecisionServerServicer | None = None
    _writers: WriterProcesses | None = None

    def bindings(self) -> Sequence[ServiceBinding]:
        # The inner links present the DecisionServer's own certificate when TLS is on.
        security = station_channel_security(self.args.tls_dir or None, "decision_server")
        slave = GrpcSlave(self.args.proxy_robot_address, self.args.force_sensor_address,
                          self.args.emergency_stop_address or None, security,
                          local_calls=self.args.proxy_robot_local_calls or None)
        # A window of about one pair: the forward then reads a pair only as its client takes
        # one, so it holds no backlog of its own (wire/stereo.py).
        self._stereo_channel = open_channel(self.args.stereo_camera_address,
                                            LOW_LATENCY_OPTIONS, security,
                                            service="stereo_camera")
        slave.watch_health("stereo_camera", self._stereo_channel)
        stereo = stereo_camera_pb2_grpc.StereoCameraStub(self._stereo_channel)
        video = self.args.recording_video
        camera = CameraSource(self.args.stereo_camera_address, self.args.tls_dir or None, *video,
                              RECORDING_VIDEO_KBIT) if video else None
        self._writers = WriterProcesses()  # the MCAP recordings' writers, one started ahead
        self.core = DecisionCore(slave, RecordingStore(Path(self.args.recordings_dir),
                                                       writer=self._writers), camera=camera)
        self._slave = slave
        # Each dependency's state, from its health and the launcher's state file; every change
        # is an event (and, once attached, a health entry).
        health = slave.health
        if self.args.zenoh_router_address:  # the observers' router: is it there?
            router = self._router_watch = PortWatch(self.args.zenoh_router_address)
            health = lambda: {**slave.health(), "zenoh_router": router.answer()}  # noqa: E731
        self.dependencies = DependencyWatch(health, self.core.clock)
        self.dependencies.subscribe(self.core.emit)
        self._servicer = DecisionServerServicer(self.core, self.dependencies)
        return [binding(decision_server_pb2_grpc, "DecisionServer", self._servicer),
                *(binding(module, name, servicer)
                  for module, name, servicer in make_facades(self.core, slave.robot,
                                                             slave.sensor, stereo))]

    def configure(self, health: HealthReporter, metrics: ServiceMetrics | None) -> None:
        """Report each dependency in this server's health, as it is now and as it changes;
        count the events streams' drops and lag, every lease change, and the commands' ages
        on the process's /metrics."""
        self.dependencies.subscribe(
            lambda change: health(DEPENDENCY_HEALTH_PREFIX + change.dependency.name,
                                  change.dependency.state == SERVING), current=True)
        if metrics is None:
            return
        self.core.events.on_dropped = lambda: metrics.dropped("decision_events")
        self.core.events.on_lag = lambda lag_s: metrics.stream_lagged("decision_events", lag_s)
        self._servicer.on_command_age = metrics.command_aged
        self.core.events.attach(_LeaseChanges(self.core.events, metrics))

    def start(self) -> None:
        # The backends are reached per call; their absence is UNAVAILABLE, not a crash. Their
        # first health answers come within milliseconds: wait for them, so the first states
        # are not "no answer yet".
        self._slave.wait_health(HEALTH_ANSWER_TIMEOUT_S)
        if self._router_watch is not None:
            self._router_watch.start()
        self.dependencies.start()
        self._writers.warm()

    def on_emergency_call(self) -> None:
        if self.core is not None:
            self.core.slave.stop_now()

    def close(self) -> None:
        if self.dependencies is not None:
            self.dependencies.close()
        if self._router_watch is not None:
            self._router_watch.close()
        if self.core is not None:
            self.core.close()
            self.core.slave.close()
        if self._stereo_channel is not None:
            self._stereo_channel.close()
        if self._writers is not None:
            self._writers.close()


class _LeaseChanges(Subscription):
    """Counts the lease changes among the DecisionServer's events as they are published; keeps
    nothing."""

    def __init__(self, fanout, metrics: ServiceMetrics):
        super().__init__(fanout, 1)
        self._metrics = metrics

    def offer(self, item) -> None:
        if isinstance(item.payload, ControlChanged):
            self._metrics.event("lease_change")


def _add_arguments(parser: argparse.ArgumentParser) -> None:
    for name in ("proxy_robot", "force_sensor", "stereo_camera", "emergency_stop"):
        parser.add_argument(f"--{name.replace('_', '-')}-address", default=address_for(name),
                            help=f"where {name} listens (env TELEROBOT_{name.upper()}_ADDRESS)"
                                 + ("; empty: stop through ProxyRobot only"
                                    if name == "emergency_stop" else ""))
    parser.add_argument("--zenoh-router-address",
                        default=os.environ.get(env_name("zenoh_router", "address"), ""),
                        help="the station's Zenoh router (host:port), reported among the "
                             "dependencies (env TELEROBOT_ZENOH_ROUTER_ADDRESS, which the "
                             "launcher sets; empty: none)")
    parser.add_argument("--proxy-robot-local-calls", metavar="PATH",
                        default=os.environ.get(LOCAL_CALLS_ENV, ""),
                        help="move the arm through ProxyRobot's local socket at PATH (its "
                             "--local-calls, on this host) instead of gRPC: 0.1 ms a call "
                             f"instead of 0.65 ms (env {LOCAL_CALLS_ENV}; empty: gRPC)")
    parser.add_argument("--recordings-dir",
                        default=os.environ.get("TELEROBOT_RECORDINGS_DIR", "var/recordings"),
                        help="where recordings are kept (env TELEROBOT_RECORDINGS_DIR)")
    parser.add_argument("--recording-video", type=_video_size,
                        default=_video_size(os.environ.get(
                            "TELEROBOT_DECISION_SERVER_RECORDING_VIDEO", "320x240")),
                        help="the stereo video MCAP recordings keep, per eye: WxH (default "
                             f"320x240, H.264 at {RECORDING_VIDEO_KBIT} kbit/s), or off (env "
                             "TELEROBOT_DECISION_SERVER_RECORDING_VIDEO)")


def _video_size(text: str) -> tuple[int, int] | None:
    """WxH, even and positive (H.264), or None for off."""
    if text.lower() == "off":
        return None
    width, _, height = text.lower().partition("x")
    try:
        size = int(width), int(height)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is neither WxH (320x240) nor off") from None
    if any(side < 2 or side % 2 for side in size):
        raise argparse.ArgumentTypeError(f"{text!r}: H.264 needs an even, positive width and "
                                         "height")
    return size


if __name__ == "__main__":
    raise SystemExit(run_service(
        "decision_server", "DecisionServer: supervisory control and arbitration.",
        DecisionService, add_arguments=_add_arguments,
        realtime_priority=COMMAND_PATH_FIFO_PRIORITY))
