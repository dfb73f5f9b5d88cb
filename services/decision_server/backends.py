"""The DecisionServer's side of ProxyRobot and ForceSensor: a gRPC `Slave`, and forwarding
servicers that put the supervisory checks in front of the dedicated processes."""

from __future__ import annotations

import contextlib
import logging
import threading
import time
from collections.abc import Callable, Iterator

import grpc
import numpy as np
import pinocchio as pin
from google.rpc import error_details_pb2
from grpc_health.v1 import health_pb2, health_pb2_grpc
from grpc_status import rpc_status

from services.common import se3
from services.decision_server.slave import MoveResult, SlaveState, SlaveWrench
from telerobot.v1 import (
    force_sensor_pb2,
    force_sensor_pb2_grpc,
    proxy_robot_pb2,
    proxy_robot_pb2_grpc,
    types_pb2,
)
from wire import convert
from wire.errors import (
    DeadlineExceededError,
    TelerobotError,
    UnavailableError,
    error_for_status,
)
from wire.local_call import NOT_SENT, LocalCallClient, method_path
from wire.metadata import LANE_METADATA_KEY, LEASE_METADATA_KEY
from wire.tls import ChannelSecurity, open_channel

log = logging.getLogger(__name__)

CALL_TIMEOUT_S = 5.0
# The band answers in milliseconds under any load (it is a process of its own at nice -10);
# one that takes longer is down, and ProxyRobot's stop stands without it.
BAND_TIMEOUT_S = 1.0
MAX_FORWARD_TIMEOUT_S = 60.0
RETRY_S = 0.5  # background streams reconnect this often after a failure
STATE_PERIOD_S = 0.01  # the pose and wrench in acks come from 100 Hz streams
STATE_FRESH_S = 0.1  # an older cached pose is fetched anew
# An older cached wrench is left out of acks: the sensor stopped reading or its stream stalled,
# and a stale force shown as current is worse than none.
WRENCH_FRESH_S = 0.05
LOCAL_WARN_EVERY_S = 60.0  # a local socket that cannot be reached is said this often
_PROXY_ROBOT = proxy_robot_pb2.DESCRIPTOR.services_by_name["ProxyRobot"]
# The moves ProxyRobot also answers on its local socket: each one's path and response type.
_LOCAL_MOVES = {name: (method_path(_PROXY_ROBOT, name),
                       getattr(proxy_robot_pb2, f"{name}Response"))
                for name in ("MoveCartesianIncremental", "MoveJointsIncremental")}
_FRAMES = {"BASE": types_pb2.REFERENCE_FRAME_BASE, "WRIST": types_pb2.REFERENCE_FRAME_WRIST,
           "TOOL": types_pb2.REFERENCE_FRAME_TOOL}
# Metadata a forwarded call carries on: the lane and the lease, nothing gRPC-internal.
FORWARDED_METADATA = (LANE_METADATA_KEY, LEASE_METADATA_KEY)


def domain_error(error: grpc.RpcError) -> TelerobotError:
    """The error another service answered with, as a domain error with its own message and
    ErrorInfo reason, so forwarding loses nothing."""
    reason = None
    status = rpc_status.from_call(error) if hasattr(error, "trailing_metadata") else None
    for detail in status.details if status else ():
        info = error_details_pb2.ErrorInfo()
        if detail.Unpack(info):
            reason = info.reason
    return error_for_status(error.code().name, error.details() or error.code().name, reason)


def forwarded_metadata(context: grpc.ServicerContext) -> tuple[tuple[str, str], ...]:
    return tuple((k, v) for k, v in context.invocation_metadata() if k in FORWARDED_METADATA)


def forward_timeout(context: grpc.ServicerContext) -> float:
    """The caller's remaining time (gRPC reports ~9e18 s when there is no deadline), capped."""
    return min(context.time_remaining(), MAX_FORWARD_TIMEOUT_S)


def call(method: Callable, request, metadata=(), timeout: float | None = CALL_TIMEOUT_S):
    try:
        return method(request, metadata=metadata, timeout=timeout)
    except grpc.RpcError as error:
        raise domain_error(error) from None


class GrpcSlave:
    """The `Slave` port over gRPC: the arm and its sensor behind their own services. Follows
    ProxyRobot's state and events and the sensor's wrench on background streams, handing
    each state sample to `on_state` and each event to `on_robot_event`, and each dependency's
    standard health (`health()`): the arm, the sensor, the band, and any channel given to
    `watch_health` (the camera's)."""

    def __init__(self, proxy_address: str, sensor_address: str,
                 emergency_stop_address: str | None = None,
                 security: ChannelSecurity | None = None, local_calls: str | None = None):
        security = security or ChannelSecurity()  # plaintext unless told

        def channel(address: str, service: str) -> grpc.Channel:
            # Over TLS the certificate must name that service, and a backend that restarts is
            # reachable again within a second (wire.tls.open_channel's KEEPALIVE_OPTIONS).
            return open_channel(address, (), security, service=service)

        self.robot_channel = channel(proxy_address, "proxy_robot")
        self.sensor_channel = channel(sensor_address, "force_sensor")
        self.robot = proxy_robot_pb2_grpc.ProxyRobotStub(self.robot_channel)
        # The moves, every command's, over ProxyRobot's local socket when it is on this host
        # (wire/local_call.py); every other call over gRPC.
        self.local_moves = (LocalCallClient(local_calls, CALL_TIMEOUT_S) if local_calls
                            else None)
        self._local_warned_until = 0.0
        self.sensor = force_sensor_pb2_grpc.ForceSensorStub(self.sensor_channel)
        # The emergency-stop band (services/emergency_stop): the same EmergencyStop contract,
        # in a process that no ProxyRobot load can delay.
        self.emergency_channel = (channel(emergency_stop_address, "emergency_stop")
                                  if emergency_stop_address else None)
        self.emergency = (proxy_robot_pb2_grpc.ProxyRobotStub(self.emergency_channel)
                          if self.emergency_channel is not None else None)
        self.on_state: Callable[[SlaveState], None] = lambda state: None
        self.on_robot_event: Callable[[object], None] = lambda message: None
        self._state: SlaveState | None = None
        self._arm_name: str | None = None
        self._wrench: SlaveWrench | None = None
        self._closed = threading.Event()
        self._streams_lock = threading.Lock()
        self._streams: set = set()  # open calls, cancelled on close
        self._health_calls: set = set()  # open health watches, cancelled on close
        self._health: dict[str, str] = {}  # dependency -> "ok" or why not
        self._health_answered: dict[str, threading.Event] = {}  # set at the first answer
        # Thread names within the 15 characters the OS keeps of each (runtime.thread_names).
        for target, name in ((self._follow_state, "follow-state"),
                             (self._follow_wrench, "follow-wrench"),
                             (self._follow_events, "follow-events")):
            threading.Thread(target=target, name=name, daemon=True).start()
        self.watch_health("proxy_robot", self.robot_channel)
        self.watch_health("force_sensor", self.sensor_channel)
        if self.emergency_channel is not None:
            self.watch_health("emergency_stop", self.emergency_channel)

    def close(self) -> None:
        self._closed.set()
        with self._streams_lock:
            streams = [*self._streams, *self._health_calls]
        for stream in streams:
            stream.cancel()
        if self.local_moves is not None:
            self.local_moves.close()
        self.robot_channel.close()
        self.sensor_channel.close()
        if self.emergency_channel is not None:
            self.emergency_channel.close()

    # -- Slave ------------------------------------------------------------------------------

    def move_cartesian(self, delta_position, delta_rotation, frame: str) -> MoveResult:
        reply = self._move("MoveCartesianIncremental",
                           proxy_robot_pb2.MoveCartesianIncrementalRequest(
                               delta_position_m=convert.vector3_to_proto(delta_position),
                               delta_rotation=convert.rotation_to_proto(delta_rotation),
                               frame=_FRAMES[frame]))
        return MoveResult(se3.trusted_pose(reply.target_tool_pose), reply.applied_fraction)

    def move_joints(self, delta_joints_rad) -> MoveResult:
        reply = self._move("MoveJointsIncremental",
                           proxy_robot_pb2.MoveJointsIncrementalRequest(
                               delta_joint_positions_rad=[float(v) for v in delta_joints_rad]))
        return MoveResult(se3.trusted_pose(reply.target_tool_pose), 1.0)

    def _move(self, name: str, request):
        if self.local_moves is not None:
            path, response_type = _LOCAL_MOVES[name]
            try:
                return self.local_moves.call(path, request, response_type)
            except UnavailableError as error:
                if error.reason != NOT_SENT:
                    raise  # it may have moved the arm: never sent twice
                # Not sent (no socket there, not ours to open): the same move over gRPC.
                now = time.monotonic()
                if now >= self._local_warned_until:
                    self._local_warned_until = now + LOCAL_WARN_EVERY_S
                    log.warning("moving over gRPC: ProxyRobot's local socket: %s",
                                error.message)
        return call(getattr(self.robot, name), request)

    def hold(self, reason: str) -> tuple[pin.SE3, pin.SE3]:
        reply = call(self.robot.Hold, proxy_robot_pb2.HoldRequest(reason=reason))
        return (se3.trusted_pose(reply.target_tool_pose),
                se3.trusted_pose(reply.cut_target_tool_pose))

    def sensor_is_reading(self, timeout_s: float) -> bool:
        try:
            reply = call(self.sensor.GetSensorConfig, force_sensor_pb2.GetSensorConfigRequest(),
                         timeout=timeout_s)
        except DeadlineExceededError:
            raise UnavailableError(f"no answer within {timeout_s * 1e3:.0f} ms",
                                   reason="SENSOR_SILENT") from None
        return reply.config.reading

    def emergency_stop(self, reason: str) -> str:
        """Latch through the band and through ProxyRobot at once: the band is fast under any
        ProxyRobot load, ProxyRobot records the reason and is the path left when the band is
        down; neither path delays the other's stop. Returns once both
        have answered (a band stop still in flight could re-latch the arm after a prompt
        Reset), with ProxyRobot's status, or ESTOPPED when only the band confirmed; raises
        only when neither path latched."""
        request = proxy_robot_pb2.EmergencyStopRequest(reason=reason)
        band = (self.emergency.EmergencyStop.future(request, timeout=BAND_TIMEOUT_S)
                if self.emergency is not None else None)
        status, robot_error, band_error = None, None, None
        try:
            status = status_name(call(self.robot.EmergencyStop, request).status)
        except TelerobotError as error:
            robot_error = error
        if band is not None:
            try:
                band.result()
            except grpc.RpcError as error:
                band_error = error.details()
                log.error("the emergency-stop band failed: %s", band_error)
        if robot_error is None:
            return status
        if band is None or band_error is not None:
            raise robot_error  # neither path latched the stop
        log.warning("stop latched by the band; ProxyRobot did not confirm: %s",
                    robot_error.message)
        return "ESTOPPED"

    def stop_now(self) -> None:
        """Send the stop to the band without waiting for it (an EmergencyStop call is arriving;
        emergency_stop() follows with its reason, through both paths)."""
        if self.emergency is not None:
            self.emergency.EmergencyStop.future(
                proxy_robot_pb2.EmergencyStopRequest(
                    reason="an EmergencyStop call arrived at the DecisionServer"),
                timeout=BAND_TIMEOUT_S)

    def reset(self) -> str:
        return status_name(call(self.robot.Reset, proxy_robot_pb2.ResetRequest()).status)

    def arm_name(self) -> str:
        if self._arm_name is None:  # an arm's name does not change while its service runs
            self._arm_name = call(self.robot.GetArmInfo, proxy_robot_pb2.GetArmInfoRequest()).name
        return self._arm_name

    def set_tool_frame(self, flange_to_tool: pin.SE3) -> pin.SE3:
        reply = call(self.robot.SetToolFrame, proxy_robot_pb2.SetToolFrameRequest(
            flange_to_tool=convert.pose_to_proto(flange_to_tool)))
        # Keep the sensor's tool frame equal to the arm's, as the contracts promise.
        call(self.sensor.SetSensorConfig, force_sensor_pb2.SetSensorConfigRequest(
            config=force_sensor_pb2.SensorConfig(flange_to_tool=reply.flange_to_tool),
            update_mask={"paths": ["flange_to_tool"]}))
        return se3.pose_from_proto(reply.flange_to_tool, "flange_to_tool")

    def state(self) -> SlaveState:
        state = self._state
        if state is not None and time.time_ns() - state.sample_time_ns < STATE_FRESH_S * 1e9:
            return state
        reply = call(self.robot.GetStatus, proxy_robot_pb2.GetStatusRequest())
        name = status_name(reply.status)
        if name == "NOT_CONNECTED":
            return SlaveState(pin.SE3.Identity(), name, time.time_ns(), reply.reason)
        return self._state_from(call(self.robot.GetState, proxy_robot_pb2.GetStateRequest())
                                .state)

    def wrench(self) -> SlaveWrench | None:
        wrench = self._wrench
        if wrench is None or time.time_ns() - wrench.sample_time_ns > WRENCH_FRESH_S * 1e9:
            return None  # the sensor stopped reading, or its stream stalled: say nothing
        return wrench

    def wrench_stream(self, decimation: int) -> _WrenchStream:
        """Samples from the sensor every `decimation` readings, until cancelled."""
        return _WrenchStream(self, self.sensor.StreamWrench(
            force_sensor_pb2.StreamWrenchRequest(decimation=decimation, queue_capacity=4)))

    def health(self) -> dict[str, str]:
        return dict(self._health)

    def watch_health(self, name: str, channel: grpc.Channel) -> None:
        """Follow the standard health (grpc.health.v1.Health/Watch, the whole server's) of the
        dependency `name` at the other end of `channel`, on a thread, until close(); health()
        then says "ok" while it reports SERVING, and why not otherwise."""
        self._health[name] = "UNAVAILABLE: no health answer yet"
        self._health_answered[name] = threading.Event()
        stub = health_pb2_grpc.HealthStub(channel)
        threading.Thread(target=self._watch_health, args=(name, stub),
                         name=f"health-{name}", daemon=True).start()

    def wait_health(self, timeout_s: float) -> bool:
        """Wait until every watched dependency answered (or failed to) once; whether all
        did within `timeout_s`."""
        deadline = time.monotonic() + timeout_s
        return all(answered.wait(max(0.0, deadline - time.monotonic()))
                   for answered in list(self._health_answered.values()))

    def open_streams(self) -> int:
        """Calls open now: the three background streams, plus any wrench stream being read."""
        with self._streams_lock:
            return len(self._streams)

    # -- background streams -----------------------------------------------------------------

    @contextlib.contextmanager
    def _opened(self, stream, registry: set | None = None):
        """Track an open call so close() can cancel it; forget it when it ends."""
        registry = self._streams if registry is None else registry
        with self._streams_lock:
            registry.add(stream)
        try:
            yield stream
        finally:
            stream.cancel()
            with self._streams_lock:
                registry.discard(stream)

    def _watch_health(self, name: str, stub: health_pb2_grpc.HealthStub) -> None:
        serving = health_pb2.HealthCheckResponse.SERVING
        while not self._closed.is_set():
            try:
                with self._opened(stub.Watch(health_pb2.HealthCheckRequest()),
                                  self._health_calls) as call:
                    for reply in call:
                        self._health_answered[name].set()
                        if reply.status == serving:
                            self._health[name] = "ok"
                            continue
                        self._health[name] = (
                            f"{health_pb2.HealthCheckResponse.ServingStatus.Name(reply.status)}:"
                            " its health check says it is not serving")
                        # A server says so as it starts to drain: leave (the call would hold
                        # its stop for its whole grace period) and look again later.
                        break
                    else:
                        self._health[name] = "UNAVAILABLE: its health stream ended"
            except grpc.RpcError as error:
                if self._closed.is_set():
                    return
                self._health[name] = f"{error.code().name}: {error.details()}"
            except ValueError:  # its channel was closed under it: the server is stopping
                return
            self._health_answered[name].set()
            self._closed.wait(RETRY_S)

    @staticmethod
    def _state_from(state: types_pb2.RobotState) -> SlaveState:
        return SlaveState(se3.trusted_pose(state.tool_pose), status_name(state.status),
                          state.sample_time.ToNanoseconds(),
                          joint_positions_rad=tuple(state.joint_positions_rad))

    def _follow(self, name: str, open_stream: Callable[[], Iterator],
                on_message: Callable) -> None:
        while not self._closed.is_set():
            try:
                with self._opened(open_stream()) as stream:
                    for message in stream:
                        on_message(message)
            except grpc.RpcError as error:
                if self._closed.is_set():
                    return
                log.debug("%s stream: %s; retrying", name, error.details())
            except (TelerobotError, ValueError) as error:
                log.warning("%s stream: %s", name, error)
            self._closed.wait(RETRY_S)

    def _on_state_message(self, message) -> None:
        self._state = self._state_from(message.state)
        self.on_state(self._state)

    def _follow_state(self) -> None:
        period = {"nanos": int(STATE_PERIOD_S * 1e9)}
        self._follow("proxy_robot", lambda: self.robot.StreamState(
            proxy_robot_pb2.StreamStateRequest(period=period)), self._on_state_message)

    def _follow_wrench(self) -> None:
        decimation = int(STATE_PERIOD_S / 0.001)
        self._follow("force_sensor", lambda: self.sensor.StreamWrench(
            force_sensor_pb2.StreamWrenchRequest(decimation=decimation, queue_capacity=4)),
            lambda m: m.samples and setattr(self, "_wrench", _wrench_from(m.samples[-1])))

    def _follow_events(self) -> None:
        self._follow("proxy_robot events", lambda: self.robot.StreamRobotEvents(
            proxy_robot_pb2.StreamRobotEventsRequest()), lambda m: self.on_robot_event(m))


class _WrenchStream:
    """One StreamWrench call as a `WrenchStream`."""

    def __init__(self, slave: GrpcSlave, call):
        self._slave = slave
        self._call = call

    def __iter__(self) -> Iterator[SlaveWrench]:
        with self._slave._opened(self._call):  # noqa: SLF001 - the slave's stream registry
            try:
                for message in self._call:
                    for sample in message.samples:
                        yield _wrench_from(sample)
            except grpc.RpcError as error:
                if error.code() != grpc.StatusCode.CANCELLED:
                    raise domain_error(error) from None
                return
        raise UnavailableError("the sensor's stream ended", reason="SENSOR_STREAM_ENDED")

    def cancel(self) -> None:
        self._call.cancel()


def status_name(status: int) -> str:
    return types_pb2.RobotStatus.Name(status).removeprefix("ROBOT_STATUS_")


def _wrench_from(sample: force_sensor_pb2.WrenchSample) -> SlaveWrench:
    f, t = sample.wrench.force_n, sample.wrench.torque_nm
    return SlaveWrench(np.array([f.x, f.y, f.z]), np.array([t.x, t.y, t.z]), sample.sequence,
                       sample.sample_time.ToNanoseconds())


def forwarding_servicer(servicer_base: type, stub, service_descriptor,
                        guard: Callable[[str, grpc.ServicerContext], None],
                        overrides: type | None = None,
                        answered: Callable[[str, object], None] | None = None):
    """A servicer that forwards every RPC of `service_descriptor` to `stub`, after
    `guard(method_name, context)` (which raises to refuse). Methods of `overrides` win.
    `answered(method_name, reply)` sees each unary reply before the caller does."""

    def unary(name: str):
        def method(self, request, context):
            guard(name, context)
            reply = call(getattr(stub, name), request, forwarded_metadata(context),
                         forward_timeout(context))
            if answered is not None:
                answered(name, reply)
            return reply
        return method

    def server_stream(name: str):
        def method(self, request, context):
            guard(name, context)
            stream = getattr(stub, name)(request, metadata=forwarded_metadata(context))
            context.add_callback(stream.cancel)
            try:
                yield from stream
            except grpc.RpcError as error:
                if error.code() != grpc.StatusCode.CANCELLED:
                    raise domain_error(error) from None
        return method

    methods = {m.name: (server_stream(m.name) if m.server_streaming else unary(m.name))
               for m in service_descriptor.methods}
    bases = (overrides, servicer_base) if overrides else (servicer_base,)
    for name in vars(overrides or object):
        methods.pop(name, None)
    cls = type(f"Forwarding{servicer_base.__name__}", bases, methods)
    return cls
