"""Contract fuzzing: every RPC of every service, found by server reflection, gets hostile
requests (tests/contracts/hostile.py) on every port of the real station.

The station (world, emergency-stop band, ProxyRobot, ForceSensor, StereoCamera with the pattern
source, DecisionServer) runs once for the module. Each port is asked for its services by gRPC
server reflection (what a client in any language sees; health and reflection themselves are
skipped), and each method gets: a valid baseline request, one hostile field at a time on top
of it, a few all-hostile combinations (seeded), and raw bytes that do not decode. Unary calls
have a 2 s deadline; server streams are cancelled after their first message or 0.25 s (a
stream that got that far accepted the request); Teleoperate gets hostile first messages (each
followed by two hostile commands), then every hostile command and heartbeat one at a time on
sessions opened with a valid init; each message must be answered within 2 s.

Everything runs twice, each time from an arm connected, initialized and READY (so a rejected
command could move it): without a lease (the arm brought up through ProxyRobot's own port,
which has no lock), then with an EXCLUSIVE lease (in the `telerobot-lease-id` metadata on
every call; Teleoperate's init carries it) and the arm brought up through the DecisionServer.

No call is skipped for the lease's sake. The hostile lease ids never name ours, so
ReleaseControl cannot drop it (RenewControl keeps it alive between batches; a lost lease would
be acquired again, and noted). Disconnect and EmergencyStop (on the DecisionServer, on
ProxyRobot's port and on the band) are sent last in their service, and the station is put back
with the lease after them and after every other method that changes it (Connect, Reset,
Initialize, tool frame, sensor configuration, assistance, indexing, replay, recording).
Hostile AcquireControl calls that are granted are released at once. The one skip: once a call
hangs (below), the rest of that field's values and the method's combinations are not sent, in
either run, so one unbounded request does not cost a deadline per value.

Each run fails with one message listing every finding:
- status: a call answered UNKNOWN or INTERNAL (a server bug surfaced as a crash);
- hang: a call that has no reason to wait ran into its deadline (the server works on after
  the client left), or a Teleoperate message got no answer in time. DEADLINE_EXCEEDED is
  accepted (and noted) where the call legitimately waits: AcquireControl with wait=true, a
  busy_work action or a Tare of up to 60 s; and when the server itself answered it early;
- contract: a request with an enum value the contract does not define, or a string past its
  field's (telerobot.v1.max_length) (256 by default), or bytes that do not decode, was not
  refused with INVALID_ARGUMENT (UNIMPLEMENTED on the band, RESOURCE_EXHAUSTED anywhere are
  fine too); a stream that stayed open or a Teleoperate message that was acked counts as
  accepted;
- health: after a service's batch, some server's health check was not SERVING;
- station: the station could not be put back between batches (the run goes on);
- motion: a rejected motion call (MoveJointsIncremental, MoveCartesianIncremental, RunAction,
  StartReplay, a Teleoperate command acked REJECTED) changed the joint target, read with a zero
  MoveJointsIncremental on ProxyRobot's own port, by more than 1e-6 rad; when the arm takes no
  motion (e-stopped, not initialized), or a Teleoperate command ended the stream (whose close
  holds the arm, moving its target to where it stands), its measured joints at rest.
"""

from __future__ import annotations

import collections
import os
import queue
import random
import re
import signal
import threading
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field

import grpc
import numpy as np
import pytest
from google.protobuf import descriptor_pool
from google.protobuf.descriptor import Descriptor, MethodDescriptor, ServiceDescriptor
from google.protobuf.message import Message
from grpc_health.v1 import health_pb2, health_pb2_grpc
from grpc_reflection.v1alpha.proto_reflection_descriptor_database import (
    ProtoReflectionDescriptorDatabase,
)

from services.launcher import GRPC_CHILDREN
from services.runtime.children import Child
from telerobot.v1 import (
    decision_server_pb2,
    decision_server_pb2_grpc,
    force_sensor_pb2,
    force_sensor_pb2_grpc,
    proxy_robot_pb2,
    proxy_robot_pb2_grpc,
    types_pb2,
)
from tests.conftest import wait_for
from tests.contracts import hostile
from tests.processes import pid_alive, start_station, station_env

pytestmark = pytest.mark.e2e

SEED = 20_261_123
UNARY_DEADLINE_S = 2.0
STREAM_BUDGET_S = 0.25  # how long a server stream is read before we cancel it
STREAM_MESSAGES = 1  # the first message shows the request was accepted
MOTION_TOLERANCE_RAD = 1e-6
# Joints this slow are at rest: what is left of the move is then well under the tolerance.
REST_SPEED = 1e-6  # rad/s
LEGIT_WAIT_MAX_S = 60.0
LEASE_KEY = "telerobot-lease-id"
PACKAGE = "telerobot.v1"

# What reflection must find on each port: a port that lists nothing would pass vacuously.
EXPECTED_SERVICES = {
    "decision_server": {"DecisionServer", "ProxyRobot", "ForceSensor", "StereoCamera"},
    "proxy_robot": {"ProxyRobot"},
    "force_sensor": {"ForceSensor"},
    "stereo_camera": {"StereoCamera"},
    "emergency_stop": {"ProxyRobot"},
    "world": set(),
}
PORT_ORDER = ["decision_server", "proxy_robot", "force_sensor", "stereo_camera",
              "emergency_stop", "world"]
SKIPPED_SERVICE_PREFIXES = ("grpc.health.", "grpc.reflection.")

IDENTITY_ROW_MAJOR = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]
ZERO_JOINTS = [0.0] * 6
# Valid requests the hostile fields are set on, so a hostile value reaches the deep checks.
# "Service/Method" -> JSON (proto3 JSON mapping). Methods not listed start from {}.
BASELINES: dict[str, dict] = {
    "ProxyRobot/SetToolFrame": {"flangeToTool": {"positionM": {"z": 0.05},
                                                 "rotation": {"rowMajor": IDENTITY_ROW_MAJOR}}},
    "ProxyRobot/MoveJointsIncremental": {"deltaJointPositionsRad": ZERO_JOINTS},
    "ProxyRobot/MoveCartesianIncremental": {
        "deltaPositionM": {"x": 0.0}, "deltaRotation": {"rowMajor": IDENTITY_ROW_MAJOR},
        "frame": "REFERENCE_FRAME_BASE"},
    "ProxyRobot/Hold": {"reason": "fuzz"},
    "ProxyRobot/StreamState": {"period": "0.01s"},
    "ProxyRobot/StreamRobotEvents": {"dataReceivedPeriod": "0.05s"},
    "ProxyRobot/EmergencyStop": {"reason": "fuzz"},
    "ForceSensor/Tare": {"duration": "0.01s"},
    "ForceSensor/SetSensorConfig": {"config": {
        "period": "0.001s", "thresholdForceN": 0.0, "thresholdTorqueNm": 0.0,
        "threadPriority": "SENSOR_THREAD_PRIORITY_NORMAL", "reading": True,
        "flangeToTool": {"positionM": {"z": 0.05}, "rotation": {"rowMajor": IDENTITY_ROW_MAJOR}}},
        "updateMask": "period,thresholdForceN,thresholdTorqueNm,threadPriority"},
    "ForceSensor/StreamWrench": {"decimation": 10, "batchSize": 1, "queueCapacity": 8},
    "StereoCamera/StreamPairs": {"encoding": "IMAGE_ENCODING_JPEG", "jpegQuality": 50,
                                 "maxFps": 5.0, "transferMode":
                                 "TRANSFER_MODE_DOUBLE_BUFFER_CONCURRENT",
                                 "widthPx": 80, "heightPx": 60},
    "StereoCamera/GetSnapshot": {"encoding": "IMAGE_ENCODING_JPEG", "jpegQuality": 50},
    "DecisionServer/SetAssistance": {"assistance": {
        "mapping": "REFERENCE_FRAME_BASE",
        "scaling": {"translationScale": 1.0, "rotationScale": 1.0}}},
    "DecisionServer/AcquireControl": {"operatorId": "fuzz-other", "mode": "CONTROL_MODE_EXCLUSIVE",
                                      "leaseDuration": "1s"},
    "DecisionServer/StartReplay": {"name": "fuzz_base", "speed": 1.0},
    "DecisionServer/BeginCobegin": {"actionCount": 1, "barrierTimeout": "1s"},
    "DecisionServer/RunAction": {"actionId": "fuzz",
                                 "moveJoints": {"deltaJointPositionsRad": ZERO_JOINTS}},
}
TELEOP_INIT = {"operatorId": "fuzz", "mapping": "REFERENCE_FRAME_BASE", "watchdogTimeout": "5s"}
TELEOP_COMMAND = {"sequence": 1, "deltaPositionM": {"x": 0.0},
                  "deltaRotation": {"rowMajor": IDENTITY_ROW_MAJOR}}
EMPTY_RECORDING = "fuzz_base"

MOTION_METHODS = {"ProxyRobot/MoveJointsIncremental", "ProxyRobot/MoveCartesianIncremental",
                  "DecisionServer/RunAction", "DecisionServer/StartReplay"}
# Sent last in their service (in this order), and the station is put back after each.
LAST = ["ProxyRobot/Disconnect", "ProxyRobot/EmergencyStop"]
# Methods whose accepted calls change what later calls see: the station is put back after them.
RESTORE_AFTER = {"ProxyRobot/SetToolFrame", "ProxyRobot/Disconnect", "ProxyRobot/EmergencyStop",
                 "ProxyRobot/Reset", "ForceSensor/StopReading", "ForceSensor/SetSensorConfig",
                 "ForceSensor/Tare", "DecisionServer/SetAssistance", "DecisionServer/SetIndexing",
                 "DecisionServer/StartRecording", "DecisionServer/StartReplay",
                 "DecisionServer/Teleoperate"}
BAD_CODES = {grpc.StatusCode.UNKNOWN, grpc.StatusCode.INTERNAL}
# Codes that satisfy "refused": what validation gives, or a lane/stream limit before it.
REFUSED_CODES = {grpc.StatusCode.INVALID_ARGUMENT, grpc.StatusCode.RESOURCE_EXHAUSTED}
OPEN = "OPEN"  # a server stream that was still streaming (or waiting) when we cancelled it
NO_REPLY = "NO_REPLY"  # a Teleoperate message that got neither a reply nor an end in time
CATEGORIES = ("status", "hang", "contract", "health", "motion", "station")


# -- the station ----------------------------------------------------------------------------

@dataclass(repr=False)
class Station:
    addresses: dict[str, str]  # service name -> host:port, from the launcher's ready lines
    launcher: Child  # its lines are every process's output
    hung: set[tuple[str, str]] = field(default_factory=set)  # (method key, field path)
    hung_methods: set[str] = field(default_factory=set)
    original_tool: types_pb2.Pose | None = None  # as the station started: restore() puts
    original_sensor: force_sensor_pb2.SensorConfig | None = None  # these back

    def __repr__(self) -> str:
        return f"Station({self.addresses})"


@pytest.fixture(scope="module")
def station(tmp_path_factory):
    """The whole station through the launcher, every service on port 0 (the one place that
    knows how the station is started)."""
    launcher = start_station(station_env(
        TELEROBOT_STEREO_CAMERA_SOURCE="pattern",  # the cheapest source
        TELEROBOT_STEREO_CAMERA_WIDTH="160", TELEROBOT_STEREO_CAMERA_HEIGHT="120",
        TELEROBOT_STEREO_CAMERA_FPS="10",
        TELEROBOT_RECORDINGS_DIR=str(tmp_path_factory.mktemp("recordings")),
        TELEROBOT_LOG_LEVEL="WARNING"))
    pids = [int(pid) for line in launcher.lines for pid in re.findall(r"\(pid (\d+)\)", line)]
    yield Station(dict(launcher.ready), launcher)
    launcher.stop(signal.SIGTERM)  # the launcher stops its children; SIGKILL after a grace
    try:
        wait_for(lambda: not any(pid_alive(pid) for pid in pids), 5, "the station to stop")
    except AssertionError:
        pass
    alive = [pid for pid in pids if pid_alive(pid)]
    for pid in alive:  # ours, and outliving their launcher: do not leave them to burn a core
        os.kill(pid, signal.SIGKILL)
    assert not alive, f"station processes {alive} outlived the launcher's stop"


# -- reflection -------------------------------------------------------------------------------

def reflected_services(channel: grpc.Channel) -> list[ServiceDescriptor]:
    database = ProtoReflectionDescriptorDatabase(channel)
    pool = descriptor_pool.DescriptorPool(database)
    names = [n for n in database.get_services() if not n.startswith(SKIPPED_SERVICE_PREFIXES)]
    return [pool.FindServiceByName(name) for name in sorted(names)]


def method_key(service: ServiceDescriptor, method: MethodDescriptor) -> str:
    return f"{service.name}/{method.name}"


def ordered_methods(service: ServiceDescriptor) -> list[MethodDescriptor]:
    methods = list(service.methods)
    last = [m for key in LAST for m in methods if method_key(service, m) == key]
    return [m for m in methods if m not in last] + last


# -- results ----------------------------------------------------------------------------------

@dataclass
class Outcome:
    code: grpc.StatusCode | str
    details: str = ""
    responses: list[bytes] = field(default_factory=list)
    elapsed_s: float = 0.0

    @property
    def ok(self) -> bool:
        return self.code in (grpc.StatusCode.OK, OPEN)

    @property
    def name(self) -> str:
        return self.code if isinstance(self.code, str) else self.code.name


@dataclass
class Report:
    run: str
    failures: list[tuple[str, str]] = field(default_factory=list)  # (category, line)
    notes: list[str] = field(default_factory=list)
    calls: int = 0
    timings: dict[str, float] = field(default_factory=dict)  # where -> seconds
    counts: collections.Counter = field(default_factory=collections.Counter)  # what was done

    def fail(self, category: str, where: str, what: str, outcome: Outcome | None = None,
             extra: str = "") -> None:
        line = f"{where} | {what}"
        if outcome is not None:
            line += f" -> {outcome.name}: {shorten(outcome.details)}"
        if extra:
            line += f" | {extra}"
        self.failures.append((category, line))

    def message(self) -> str:
        lines = [f"{len(self.failures)} finding(s) in the {self.run} run "
                 f"({self.calls} calls):"]
        for category in CATEGORIES:
            found = sorted({line for c, line in self.failures if c == category})
            if found:
                lines.append(f"\n[{category}] {len(found)}:")
                lines += [f"  {line}" for line in found]
        if self.counts:
            lines.append("\ndone: " + ", ".join(f"{what} {count}"
                                                 for what, count in sorted(self.counts.items())))
        if self.notes:
            lines.append("\nnotes:")
            lines += [f"  {note}" for note in sorted(set(self.notes))]
        return "\n".join(lines)


def shorten(text: str, limit: int = 300) -> str:
    """One line, control characters escaped, at most `limit` characters (and the length)."""
    text = " ".join((text or "").split())
    text = "".join(c if c.isprintable() else repr(c)[1:-1] for c in text)
    return text if len(text) <= limit else text[:limit] + f"... ({len(text)} chars)"


# -- calls ------------------------------------------------------------------------------------

def call_unary(channel: grpc.Channel, path: str, raw: bytes, metadata,
               timeout_s: float = UNARY_DEADLINE_S) -> Outcome:
    method = channel.unary_unary(path)  # no serializers: bytes in, bytes out
    started = time.monotonic()
    try:
        response, _ = method.with_call(raw, timeout=timeout_s, metadata=metadata)
        return Outcome(grpc.StatusCode.OK, "", [response], time.monotonic() - started)
    except grpc.RpcError as error:
        return Outcome(error.code(), error.details() or "", [], time.monotonic() - started)


def call_server_stream(channel: grpc.Channel, path: str, raw: bytes, metadata) -> Outcome:
    """Read at most STREAM_MESSAGES messages, for at most STREAM_BUDGET_S, then cancel."""
    started = time.monotonic()
    stream = channel.unary_stream(path)(raw, timeout=STREAM_BUDGET_S + 5, metadata=metadata)
    cancelled = threading.Event()

    def cancel():
        cancelled.set()
        stream.cancel()

    timer = threading.Timer(STREAM_BUDGET_S, cancel)
    timer.start()
    responses: list[bytes] = []
    try:
        for message in stream:
            responses.append(message)
            if len(responses) >= STREAM_MESSAGES:
                cancelled.set()
                stream.cancel()
                return Outcome(OPEN, "", responses, time.monotonic() - started)
        return Outcome(grpc.StatusCode.OK, "", responses, time.monotonic() - started)
    except grpc.RpcError as error:
        if error.code() == grpc.StatusCode.CANCELLED and cancelled.is_set():
            return Outcome(OPEN, "", responses, time.monotonic() - started)
        return Outcome(error.code(), error.details() or "", responses,
                       time.monotonic() - started)
    finally:
        timer.cancel()


class BidiSession:
    """A client-streaming call driven one message at a time: send, then read one reply."""

    def __init__(self, channel: grpc.Channel, path: str, metadata, timeout_s: float = 20.0):
        self._outbox: queue.Queue = queue.Queue()
        self._call = channel.stream_stream(path)(self._requests(), timeout=timeout_s,
                                                 metadata=metadata)
        self.outcome: Outcome | None = None  # set once the stream has ended

    def _requests(self) -> Iterator[bytes]:
        while True:
            item = self._outbox.get()
            if item is None:
                return
            yield item

    def send(self, raw: bytes) -> bytes | None:
        """The reply to `raw`, or None when the stream ended (see `outcome`)."""
        if self.outcome is not None:
            return None
        self._outbox.put(raw)
        return self._next()

    def _next(self) -> bytes | None:
        """The next reply; the call is cancelled (outcome NO_REPLY) if none comes within
        UNARY_DEADLINE_S."""
        started = time.monotonic()
        silent = threading.Event()

        def give_up():
            silent.set()
            self._call.cancel()

        timer = threading.Timer(UNARY_DEADLINE_S, give_up)
        timer.start()
        try:
            return next(self._call)
        except StopIteration:
            self.outcome = Outcome(grpc.StatusCode.OK, "", [], time.monotonic() - started)
        except grpc.RpcError as error:
            code = NO_REPLY if silent.is_set() else error.code()
            self.outcome = Outcome(code, error.details() or "", [], time.monotonic() - started)
        finally:
            timer.cancel()
        self._outbox.put(None)  # ended: grpc's thread reading the requests may stop too
        return None

    def close(self) -> Outcome:
        """Half-close and drain to the final status."""
        self._outbox.put(None)
        while self.outcome is None:
            self._next()
        return self.outcome


# -- the arm: did it move? ------------------------------------------------------------------

@dataclass
class ArmReading:
    target: np.ndarray | None = None  # the joint target, when the arm accepts motion
    measured: np.ndarray | None = None  # joints at rest, when it does not

    def describe(self) -> str:
        if self.target is not None:
            return f"target {np.round(self.target, 6).tolist()}"
        if self.measured is not None:
            return f"measured {np.round(self.measured, 6).tolist()}"
        return "no reading (not connected)"


def moved(before: ArmReading, after: ArmReading) -> float | None:
    """The largest joint change between two readings of the same kind; None if they cannot
    be compared."""
    if before.target is not None and after.target is not None:
        return float(np.max(np.abs(after.target - before.target)))
    if before.measured is not None and after.measured is not None:
        return float(np.max(np.abs(after.measured - before.measured)))
    return None


# -- one run ----------------------------------------------------------------------------------

class Fuzzer:
    def __init__(self, station: Station, report: Report, with_lease: bool):
        self.station = station
        self.report = report
        self.with_lease = with_lease
        self.lease = ""
        self.channels = {name: grpc.insecure_channel(address, options=[
            ("grpc.max_receive_message_length", 64 << 20)])
            for name, address in station.addresses.items()
            # The station's gRPC services: not the web console (HTTP, tests/web_console), the
            # live view (WebSocket, tests/foxglove), nor the services' /metrics ports (HTTP,
            # tests/runtime/test_metrics.py).
            if name in GRPC_CHILDREN}
        inner = self.channels["proxy_robot"]
        operator = self.channels["decision_server"]
        self.inner_robot = proxy_robot_pb2_grpc.ProxyRobotStub(inner)
        self.inner_sensor = force_sensor_pb2_grpc.ForceSensorStub(self.channels["force_sensor"])
        self.ds = decision_server_pb2_grpc.DecisionServerStub(operator)
        self.ds_robot = proxy_robot_pb2_grpc.ProxyRobotStub(operator)

    def close(self) -> None:
        for channel in self.channels.values():
            channel.close()

    @property
    def metadata(self) -> tuple[tuple[str, str], ...]:
        return ((LEASE_KEY, self.lease),) if self.lease else ()

    # -- plumbing: setting the station up and putting it back ------------------------------

    def acquire(self) -> None:
        reply = self.ds.AcquireControl(decision_server_pb2.AcquireControlRequest(
            operator_id="fuzz-operator", mode=decision_server_pb2.CONTROL_MODE_EXCLUSIVE,
            wait=True, wait_timeout={"seconds": 10}, lease_duration={"seconds": 60}),
            timeout=15)
        self.lease = reply.lease_id

    def release(self) -> None:
        if self.lease:
            try:
                self.ds.ReleaseControl(decision_server_pb2.ReleaseControlRequest(
                    lease_id=self.lease), timeout=5)
            except grpc.RpcError:
                pass
            self.lease = ""

    def _quiet(self, method: Callable, request, **kwargs):
        try:
            return method(request, timeout=5, **kwargs)
        except grpc.RpcError as error:
            return error

    def _status(self) -> int:
        return self.inner_robot.GetStatus(proxy_robot_pb2.GetStatusRequest(), timeout=5).status

    def remember_originals(self) -> None:
        station = self.station
        if station.original_tool is None:
            station.original_tool = self.inner_robot.GetToolFrame(
                proxy_robot_pb2.GetToolFrameRequest(), timeout=5).flange_to_tool
        if station.original_sensor is None:
            station.original_sensor = self.inner_sensor.GetSensorConfig(
                force_sensor_pb2.GetSensorConfigRequest(), timeout=5).config

    def restore(self) -> None:
        """Put the station back: lease alive, assistance and indexing off, no replay or
        recording, the arm connected, un-latched, initialized and READY, the tool frame and
        the sensor's configuration as they were. A station that cannot be put back is a
        finding; the run goes on."""
        try:
            self._restore()
        except (grpc.RpcError, AssertionError) as error:
            detail = (f"{error.code().name}: {error.details()}" if isinstance(error, grpc.RpcError)
                      else str(error))
            self.report.fail("station", "restore", f"could not put the station back: {detail}")

    def _restore(self) -> None:
        md = self.metadata
        if self.with_lease:
            renewed = self._quiet(self.ds.RenewControl,
                                  decision_server_pb2.RenewControlRequest(lease_id=self.lease))
            if isinstance(renewed, grpc.RpcError):
                self.report.notes.append(f"our lease was gone ({renewed.details()}); "
                                         "acquired a new one")
                self.acquire()
                md = self.metadata
            self._quiet(self.ds.StopReplay, decision_server_pb2.StopReplayRequest(), metadata=md)
            self._quiet(self.ds.StopRecording, decision_server_pb2.StopRecordingRequest(),
                        metadata=md)
            self._quiet(self.ds.SetIndexing, decision_server_pb2.SetIndexingRequest(engaged=False),
                        metadata=md)
            self._quiet(self.ds.SetAssistance, decision_server_pb2.SetAssistanceRequest(),
                        metadata=md)
        robot = self.ds_robot if self.with_lease else self.inner_robot
        if self._status() == types_pb2.ROBOT_STATUS_NOT_CONNECTED:
            robot.Connect(proxy_robot_pb2.ConnectRequest(), timeout=5, metadata=md)
        if self.with_lease or self._status() in (types_pb2.ROBOT_STATUS_ESTOPPED,
                                                 types_pb2.ROBOT_STATUS_FAULT):
            robot.Reset(proxy_robot_pb2.ResetRequest(), timeout=5, metadata=md)
        if self._status() == types_pb2.ROBOT_STATUS_CONNECTED:
            robot.Initialize(proxy_robot_pb2.InitializeRequest(), timeout=10, metadata=md)
        self._wait_ready()
        original_tool = self.station.original_tool
        tool = self.inner_robot.GetToolFrame(proxy_robot_pb2.GetToolFrameRequest(), timeout=5)
        if tool.flange_to_tool != original_tool:
            self.inner_robot.SetToolFrame(proxy_robot_pb2.SetToolFrameRequest(
                flange_to_tool=original_tool), timeout=5)
        original = self.station.original_sensor
        config = self.inner_sensor.GetSensorConfig(force_sensor_pb2.GetSensorConfigRequest(),
                                                   timeout=5).config
        if config != original:
            self.inner_sensor.SetSensorConfig(force_sensor_pb2.SetSensorConfigRequest(
                config=original), timeout=5)
            if original.reading and not config.reading:
                self.inner_sensor.StartReading(force_sensor_pb2.StartReadingRequest(), timeout=5)

    def _wait_ready(self, timeout_s: float = 5.0) -> None:
        wait_for(lambda: self._status() == types_pb2.ROBOT_STATUS_READY, timeout_s,
                 "the arm to come back to READY")

    def read_arm(self) -> ArmReading:
        """The joint target (a zero increment on ProxyRobot's own port answers it and moves
        nothing), or, when the arm takes no motion, its joints once at rest."""
        try:
            reply = self.inner_robot.MoveJointsIncremental(
                proxy_robot_pb2.MoveJointsIncrementalRequest(
                    delta_joint_positions_rad=ZERO_JOINTS), timeout=5)
            return ArmReading(target=np.array(reply.target_joint_positions_rad))
        except grpc.RpcError:
            pass
        return self.read_at_rest()

    def read_at_rest(self, timeout_s: float = 2.0) -> ArmReading:
        """The joints once at rest (or as they are after `timeout_s`)."""
        def state():
            try:
                return self.inner_robot.GetState(proxy_robot_pb2.GetStateRequest(),
                                                 timeout=5).state
            except grpc.RpcError:
                return None

        def resting():
            current = state()
            return ("unreachable" if current is None else current if max(
                abs(v) for v in current.joint_velocities_rad_per_s) < REST_SPEED else None)

        try:
            found = wait_for(resting, timeout_s, "the arm to rest")
        except AssertionError:
            found = state()
        if found is None or found == "unreachable":
            return ArmReading()
        return ArmReading(measured=np.array(found.joint_positions_rad))

    def check_health(self, after: str) -> None:
        for name, channel in self.channels.items():
            try:
                status = health_pb2_grpc.HealthStub(channel).Check(
                    health_pb2.HealthCheckRequest(service=""), timeout=5).status
                if status != health_pb2.HealthCheckResponse.SERVING:
                    self.report.fail("health", f"{name} after {after}",
                                     health_pb2.HealthCheckResponse.ServingStatus.Name(status))
            except grpc.RpcError as error:
                self.report.fail("health", f"{name} after {after}", "health check failed",
                                 Outcome(error.code(), error.details() or ""))

    # -- the fuzzing ----------------------------------------------------------------------

    def run(self) -> None:
        """Both runs start from an arm connected and initialized (so a rejected command
        could move it, and the no-motion checks mean something), and put the station back
        after each method that changes it and after each service."""
        self.remember_originals()
        if self.with_lease:
            self.acquire()
        try:
            self.restore()
            if self.with_lease:  # a recording StartReplay can name (an empty one)
                md = self.metadata
                self._quiet(self.ds.StartRecording, decision_server_pb2.StartRecordingRequest(
                    name=EMPTY_RECORDING), metadata=md)
                self._quiet(self.ds.StopRecording, decision_server_pb2.StopRecordingRequest(),
                            metadata=md)
            for port in PORT_ORDER:
                self.fuzz_port(port)
        finally:
            self.release()

    def fuzz_port(self, port: str) -> None:
        channel = self.channels[port]
        services = reflected_services(channel)
        found = {s.name for s in services if s.full_name.startswith(PACKAGE + ".")}
        assert found == EXPECTED_SERVICES[port], (
            f"reflection on {port} lists {sorted(found)}, expected "
            f"{sorted(EXPECTED_SERVICES[port])}")
        for service in services:
            for method in ordered_methods(service):
                key = method_key(service, method)
                where = f"{port} {key}"
                started = time.monotonic()
                if method.client_streaming:
                    self.fuzz_client_stream(port, channel, service, method, where)
                else:
                    self.fuzz_method(port, channel, service, method, where)
                if key in RESTORE_AFTER:
                    self.restore()
                self.report.timings[where] = time.monotonic() - started
            self.restore()
            self.check_health(f"{port} {service.name}")

    def fuzz_method(self, port: str, channel: grpc.Channel, service: ServiceDescriptor,
                    method: MethodDescriptor, where: str) -> None:
        key = method_key(service, method)
        path = f"/{service.full_name}/{method.name}"
        rng = random.Random(f"{SEED}:{self.report.run}:{path}")
        streaming = method.server_streaming
        call = call_server_stream if streaming else call_unary

        def do(raw: bytes) -> Outcome:
            return call(channel, path, raw, self.metadata)

        for variant in hostile.variants(method.input_type, BASELINES.get(key), rng):
            if (key, variant.path) in self.station.hung or (
                    variant.path == "*" and key in self.station.hung_methods):
                self.report.notes.append(f"{where}: not sent after a hang on the same path: "
                                         f"{shorten(variant.label, 120)}")
                continue
            self.send(port, key, where, variant.label, variant.message, variant.path, do,
                      streaming)
        for strict, blobs in ((True, hostile.raw_garbage(method.input_type)),
                              (False, hostile.LENIENT_GARBAGE)):
            for raw, label in blobs:
                self.send(port, key, where, label, None, "raw" if strict else "lenient", do,
                          streaming, raw=raw)

    def send(self, port: str, key: str, where: str, label: str, message: Message | None,
             path: str, do: Callable[[bytes], Outcome], streaming: bool,
             raw: bytes | None = None) -> Outcome:
        motion = key in MOTION_METHODS
        started = time.monotonic()
        before = self.read_arm() if motion else None
        probed = time.monotonic()
        outcome = do(message.SerializeToString() if raw is None else raw)
        self.report.calls += 1
        self.report.counts[f"answers {outcome.name}"] += 1
        if path == "raw" or (message is not None and hostile.contract_violations(message)):
            self.report.counts["requests the runtime must refuse"] += 1
        self.judge(port, key, where, label, message, path, outcome, streaming=streaming)
        if key == "DecisionServer/AcquireControl" and outcome.code == grpc.StatusCode.OK:
            self.release_granted(outcome.responses[0])
        if motion and not outcome.ok:
            after = self.read_arm()
            change = moved(before, after)
            self.count_check(before, after)
            if change is not None and change > MOTION_TOLERANCE_RAD:
                self.report.fail("motion", where, label, outcome,
                                 f"rejected, yet the arm moved {change:.3g} rad: "
                                 f"{before.describe()} -> {after.describe()}")
        if time.monotonic() - started > 0.3:
            self.report.notes.append(
                f"slow: {where} {shorten(label, 60)}: probe {probed - started:.2f} s, call "
                f"{outcome.elapsed_s:.2f} s ({outcome.name}), total "
                f"{time.monotonic() - started:.2f} s")
        return outcome

    def count_check(self, before: ArmReading, after: ArmReading) -> None:
        if before.target is not None and after.target is not None:
            kind = "joint target"
        elif moved(before, after) is not None:
            kind = "measured joints"
        else:
            kind = "impossible, not connected"
        self.report.counts[f"no-motion checks on rejections ({kind})"] += 1

    def judge(self, port: str, key: str, where: str, label: str, message: Message | None,
              path: str, outcome: Outcome, streaming: bool) -> None:
        if outcome.code in BAD_CODES:
            self.report.fail("status", where, label, outcome)
            return
        if outcome.code == NO_REPLY:
            self.report.fail("hang", where, label, outcome,
                             f"neither a reply nor the end of the stream within "
                             f"{UNARY_DEADLINE_S:.0f} s")
            return
        if outcome.code == grpc.StatusCode.DEADLINE_EXCEEDED and not streaming:
            reason = legit_wait(key, message)
            if outcome.elapsed_s < UNARY_DEADLINE_S * 0.9:
                pass  # the server's own answer (a barrier or a wait that timed out), not a hang
            elif reason:
                self.report.notes.append(f"{where}: DEADLINE_EXCEEDED accepted, {reason}: "
                                         f"{shorten(label, 120)}")
            else:
                self.report.fail("hang", where, label, outcome,
                                 f"no answer within {UNARY_DEADLINE_S:.0f} s; later values "
                                 "of this path are not sent")
                self.station.hung.add((key, path))
                self.station.hung_methods.add(key)
                return
        refused = outcome.code in REFUSED_CODES or (
            port == "emergency_stop" and outcome.code == grpc.StatusCode.UNIMPLEMENTED)
        if message is None:  # raw bytes that do not decode
            if not refused and path != "lenient":
                self.report.fail("contract", where, label, outcome,
                                 "bytes that do not decode must get INVALID_ARGUMENT")
            return
        violations = hostile.contract_violations(message)
        if key.endswith("/EmergencyStop"):  # never refused for its words: a long reason is cut
            violations = [v for v in violations if "character bound" not in v]
        if violations and not refused:
            self.report.fail("contract", where, label, outcome,
                             "expected INVALID_ARGUMENT naming " + violations[0])

    def release_granted(self, response: bytes) -> None:
        """A hostile AcquireControl that was granted: give it back at once, so it does not
        hold the arm against the next calls."""
        granted = decision_server_pb2.AcquireControlResponse.FromString(response)
        if granted.lease_id and granted.lease_id != self.lease:
            self._quiet(self.ds.ReleaseControl,
                        decision_server_pb2.ReleaseControlRequest(lease_id=granted.lease_id))

    # -- client streams (Teleoperate) ------------------------------------------------------

    def fuzz_client_stream(self, port: str, channel: grpc.Channel, service: ServiceDescriptor,
                           method: MethodDescriptor, where: str) -> None:
        key = method_key(service, method)
        if key != "DecisionServer/Teleoperate":  # a new client stream: one message each
            path = f"/{service.full_name}/{method.name}"
            rng = random.Random(f"{SEED}:{self.report.run}:{path}")
            for variant in hostile.variants(method.input_type, BASELINES.get(key), rng):
                session = BidiSession(channel, path, self.metadata)
                session.send(variant.message.SerializeToString())
                outcome = session.close()
                self.report.calls += 1
                self.judge(port, key, where, variant.label, variant.message, variant.path,
                           outcome, streaming=True)
            return
        self.fuzz_teleoperate(port, channel, service, method, where)

    def fuzz_teleoperate(self, port: str, channel: grpc.Channel, service: ServiceDescriptor,
                         method: MethodDescriptor, where: str) -> None:
        path = f"/{service.full_name}/{method.name}"
        request: Descriptor = method.input_type
        response_class = hostile.message_class(method.output_type)
        rejected = response_class.DESCRIPTOR.fields_by_name["ack"].message_type.fields_by_name[
            "outcome"].enum_type.values_by_name["COMMAND_OUTCOME_REJECTED"].number
        rng = random.Random(f"{SEED}:{self.report.run}:{path}")
        init = dict(TELEOP_INIT, leaseId=self.lease)
        valid_init = hostile.build(request, {"init": init})
        openers = [v for v in hostile.variants(request, {"init": init}, rng)
                   if v.path in ("", "*") or v.path.startswith("init")
                   or v.label in ("command = {} (present, empty)",
                                  "heartbeat = {} (present, empty)")]
        followers = [v for v in hostile.variants(request, {"command": TELEOP_COMMAND}, rng)
                     if not v.path.startswith("init")]
        raw_first = hostile.raw_garbage(request)

        refusals: list[Outcome] = []

        def session_with(first: bytes, first_label: str, first_message: Message | None,
                         first_path: str) -> BidiSession | None:
            session = BidiSession(channel, path, self.metadata)
            reply = session.send(first)
            self.report.calls += 1
            if reply is None:  # refused at once
                refusals.append(session.outcome)
                self.judge(port, "DecisionServer/Teleoperate", where,
                           f"first message: {first_label}", first_message, first_path,
                           session.outcome, streaming=True)
                return None
            violations = (hostile.contract_violations(first_message)
                          if first_message is not None else ["bytes that do not decode"])
            if violations:
                self.report.fail("contract", where, f"first message: {first_label}",
                                 Outcome(OPEN), "the session opened; expected INVALID_ARGUMENT"
                                 f" naming {violations[0]}")
            self.report.counts["teleop sessions opened"] += 1
            return session

        # 1. Hostile first messages, each followed by two hostile commands.
        cursor = 0
        for variant in openers:
            session = session_with(variant.message.SerializeToString(), variant.label,
                                   variant.message, variant.path)
            if session is None:
                continue
            for _ in range(2):
                follower = followers[cursor % len(followers)]
                cursor += 1
                if not self.teleop_step(port, session, follower.label, follower.message,
                                        follower.path, where, response_class, rejected):
                    break
            self.finish_session(session, where, f"after {variant.label}")
        for raw, label in raw_first:
            session = session_with(raw, label, None, "raw")
            if session is not None:
                self.finish_session(session, where, f"after {label}")
        # 2. Every hostile command and heartbeat, one at a time, on valid sessions.
        steps = [(v.label, v.message, v.path) for v in followers]
        steps += [(label, None, raw) for raw, label in raw_first]
        session = None
        for label, message, raw_or_path in steps:
            if session is None:
                session = session_with(valid_init.SerializeToString(), "valid init",
                                       valid_init, "")
                if session is None:
                    if self.with_lease:
                        self.report.fail("station", where, "a valid init with our lease was "
                                         "refused, so no command reached a session",
                                         refusals[-1])
                    else:
                        self.report.notes.append(f"{where}: no lease, so no session opened "
                                                 "and no command reached one")
                    return
            if message is None:
                alive = self.teleop_raw_step(port, session, label, raw_or_path, where)
            else:
                alive = self.teleop_step(port, session, label, message, raw_or_path, where,
                                         response_class, rejected)
            if not alive:
                session = None
        if session is not None:
            self.finish_session(session, where, "after the last command")

    def teleop_step(self, port: str, session: BidiSession, label: str, message: Message,
                    path: str, where: str, response_class, rejected: int) -> bool:
        """Send one message on an open session and judge its ack; False if the stream
        ended."""
        before = self.read_arm()
        before_rest = self.read_at_rest()
        reply = session.send(message.SerializeToString())
        self.report.calls += 1
        label = f"mid-stream: {label}"
        if reply is None:
            outcome = session.outcome
            self.judge(port, "DecisionServer/Teleoperate", where, label, message, path, outcome,
                       streaming=True)
            self.report.counts[f"teleop streams ended by a command ({outcome.name})"] += 1
            if not outcome.ok:
                # The stream ended: the session's close holds the arm where it is, which moves
                # its target to the measured joints; compare those, at rest.
                after = self.read_at_rest()
                self.count_check(before_rest, after)
                change = moved(before_rest, after)
                if change is not None and change > MOTION_TOLERANCE_RAD:
                    self.report.fail("motion", where, label, outcome,
                                     f"the stream ended, yet the arm moved {change:.3g} rad")
            return False
        ack = response_class.FromString(reply)
        self.report.counts["teleop acks " + ack.ack.DESCRIPTOR.fields_by_name["outcome"]
                           .enum_type.values_by_number[ack.ack.outcome].name] += 1
        if hostile.contract_violations(message):
            self.report.fail("contract", where, label, Outcome(OPEN),
                             "acked; expected INVALID_ARGUMENT naming "
                             + hostile.contract_violations(message)[0])
        if ack.WhichOneof("message") == "ack" and ack.ack.outcome == rejected:
            after = self.read_arm()
            self.count_check(before, after)
            change = moved(before, after)
            if change is not None and change > MOTION_TOLERANCE_RAD:
                self.report.fail("motion", where, label,
                                 Outcome(OPEN, f"ack REJECTED: {ack.ack.detail}"),
                                 f"rejected, yet the arm moved {change:.3g} rad: "
                                 f"{before.describe()} -> {after.describe()}")
        return True

    def teleop_raw_step(self, port: str, session: BidiSession, label: str, raw: bytes,
                        where: str) -> bool:
        reply = session.send(raw)
        self.report.calls += 1
        if reply is None:
            self.judge(port, "DecisionServer/Teleoperate", where, f"mid-stream: {label}", None,
                       "raw", session.outcome, streaming=True)
            return False
        self.report.fail("contract", where, f"mid-stream: {label}", Outcome(OPEN),
                         "acked; bytes that do not decode must get INVALID_ARGUMENT")
        return True

    def finish_session(self, session: BidiSession, where: str, label: str) -> None:
        outcome = session.close()
        if outcome.code in BAD_CODES:
            self.report.fail("status", where, f"half-close {label}", outcome)


def legit_wait(key: str, message: Message | None) -> str | None:
    """Why a call may legitimately run into its deadline, or None."""
    if message is None:
        return None
    if key == "DecisionServer/AcquireControl" and message.wait:
        return "AcquireControl with wait=true queues behind the holder"
    duration = None
    if key == "DecisionServer/RunAction" and message.WhichOneof("action") == "busy_work":
        duration, what = message.busy_work.duration, "busy_work asked for {:.3g} s of computing"
    elif key == "ForceSensor/Tare":
        duration, what = message.duration, "Tare asked to average {:.3g} s of samples"
    if duration is not None:
        seconds = duration.seconds + duration.nanos * 1e-9
        if 0 < seconds <= LEGIT_WAIT_MAX_S:
            return what.format(seconds)
    return None


def _run(station: Station, with_lease: bool) -> Report:
    report = Report("lease" if with_lease else "no-lease")
    fuzzer = Fuzzer(station, report, with_lease)
    started = time.monotonic()
    try:
        fuzzer.run()
    finally:
        fuzzer.close()
    report.notes.append(f"{report.calls} calls in {time.monotonic() - started:.1f} s")
    crashes = [line for line in station.launcher.lines if "Exception calling application" in line
               or "Traceback" in line]
    if crashes:
        report.notes.append(f"{len(crashes)} server-side exception lines in the station's log "
                            f"so far, first: {shorten(crashes[0], 200)}")
    print(report.message())
    slowest = sorted(report.timings.items(), key=lambda item: -item[1])[:12]
    print("slowest:", ", ".join(f"{where} {seconds:.1f} s" for where, seconds in slowest))
    return report


def test_hostile_requests_without_a_lease(station):
    report = _run(station, with_lease=False)
    assert not report.failures, report.message()


def test_hostile_requests_with_a_lease_and_an_initialized_arm(station):
    report = _run(station, with_lease=True)
    assert not report.failures, report.message()

