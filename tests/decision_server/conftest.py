"""DecisionServer tests. `fake_station`: an in-process DecisionServer over a fake slave and a
fake clock (no process, no world). `station` (e2e only): the same server in front of the real
world, ProxyRobot and ForceSensor processes."""

from __future__ import annotations

import queue
import time
from collections.abc import Iterator
from dataclasses import dataclass

import grpc
import numpy as np
import pytest

from domain.robot_model.puma560 import HOME_Q
from services.common import se3
from services.decision_server import arbitration, core, force_control, recordings
from services.decision_server.__main__ import LANES
from services.decision_server.arbitration import ControlMode, Lease
from services.decision_server.assistance import Assistance, ForceControl
from services.decision_server.backends import GrpcSlave
from services.decision_server.core import DecisionCore
from services.decision_server.recording_writer import on_a_thread
from services.decision_server.recordings import RecordingStore
from services.decision_server.servicer import DecisionServerServicer, make_facades
from services.runtime.server import binding, create_server
from telerobot.v1 import decision_server_pb2 as pb
from telerobot.v1 import (
    decision_server_pb2_grpc,
    force_sensor_pb2,
    force_sensor_pb2_grpc,
    proxy_robot_pb2,
    proxy_robot_pb2_grpc,
    stereo_camera_pb2_grpc,
    types_pb2,
)
from tests.conftest import wait_for
from tests.fakes.clock import FakeClock
from tests.fakes.slave import FakeSlave
from tests.processes import refused_address
from wire import convert


@pytest.fixture
def modules_on_the_clock() -> tuple:
    """Tests not marked e2e read no system time in the core (tests/conftest.py's guard also
    keeps them from starting a process or attaching a world)."""
    return (core, force_control, arbitration, recordings)


# The core alone, over a fake slave on a fake clock, with alice holding the lock.
Z_AXIS = np.array([False, False, True, False, False, False])


@dataclass
class Rig:
    clock: FakeClock
    slave: FakeSlave
    core: DecisionCore
    lease: Lease

    def force_control(self, desired_z_n: float = -5.0, gain: float = 2e-3) -> Assistance:
        control = ForceControl(Z_AXIS, np.array([0.0, 0.0, desired_z_n]), np.zeros(3), gain,
                               0.0)
        return self.core.set_assistance(self.lease.lease_id, Assistance(force_control=control))

    def moves(self) -> int:
        return sum(c.kind == "cartesian" for c in self.slave.commands)


@pytest.fixture
def rig(tmp_path):
    clock = FakeClock()
    slave = FakeSlave(clock)
    core = DecisionCore(slave, RecordingStore(tmp_path, clock, on_a_thread), clock)
    lease = core.locks.acquire("alice", ControlMode.EXCLUSIVE)
    yield Rig(clock, slave, core, lease)
    slave.end_wrench_streams()
    core.close()


@dataclass
class Station:
    core: DecisionCore
    channel: grpc.Channel
    decisions: decision_server_pb2_grpc.DecisionServerStub
    robot: proxy_robot_pb2_grpc.ProxyRobotStub
    sensor: force_sensor_pb2_grpc.ForceSensorStub
    address: str
    server: object  # the TelerobotServer, for its lane counters
    servicer: DecisionServerServicer  # for its hooks (the metrics')

    def acquire(self, operator: str = "alice", **fields) -> tuple[str, list]:
        """A lease for `operator`; returns (lease id, metadata carrying it)."""
        fields.setdefault("mode", pb.CONTROL_MODE_EXCLUSIVE)
        reply = self.decisions.AcquireControl(
            pb.AcquireControlRequest(operator_id=operator, **fields), timeout=10)
        return reply.lease_id, [("telerobot-lease-id", reply.lease_id)]

    def ready_at_home(self, metadata) -> None:
        """Connected, initialized, un-latched, with the arm at home."""
        self.robot.Connect(proxy_robot_pb2.ConnectRequest(), metadata=metadata)
        status = self.robot.GetStatus(proxy_robot_pb2.GetStatusRequest()).status
        if status in (types_pb2.ROBOT_STATUS_ESTOPPED, types_pb2.ROBOT_STATUS_FAULT):
            self.robot.Reset(proxy_robot_pb2.ResetRequest(), metadata=metadata)
        if status == types_pb2.ROBOT_STATUS_CONNECTED:
            self.robot.Initialize(proxy_robot_pb2.InitializeRequest(), metadata=metadata)
        # Increments add to the joint target, so steer the target (a zero move reports it),
        # then let the servo settle there.
        move = self.robot.MoveJointsIncremental
        target = np.array(move(proxy_robot_pb2.MoveJointsIncrementalRequest(
            delta_joint_positions_rad=[0.0] * 6), metadata=metadata).target_joint_positions_rad)
        while np.max(np.abs(HOME_Q - target)) > 1e-12:
            step = np.clip(HOME_Q - target, -0.45, 0.45)
            target = np.array(move(proxy_robot_pb2.MoveJointsIncrementalRequest(
                delta_joint_positions_rad=step.tolist()), metadata=metadata)
                .target_joint_positions_rad)
            self.wait_status(types_pb2.ROBOT_STATUS_READY)
        wait_for(lambda: np.max(np.abs(HOME_Q - np.array(self.robot.GetState(
            proxy_robot_pb2.GetStateRequest()).state.joint_positions_rad))) < 1e-4, 5,
            "the arm to settle at home")
        self.wait_status(types_pb2.ROBOT_STATUS_READY)

    def wait_status(self, status: int, timeout_s: float = 10.0) -> None:
        wait_for(lambda: self.robot.GetStatus(proxy_robot_pb2.GetStatusRequest()).status ==
                 status, timeout_s, f"status {types_pb2.RobotStatus.Name(status)}")

    def tool_position(self) -> np.ndarray:
        p = self.robot.GetState(proxy_robot_pb2.GetStateRequest()).state.tool_pose.position_m
        return np.array([p.x, p.y, p.z])

    def tool_pose(self):
        state = self.robot.GetState(proxy_robot_pb2.GetStateRequest()).state
        return se3.pose_from_proto(state.tool_pose, "tool_pose")


def serve_decisions(core: DecisionCore, robot_stub, sensor_stub) -> tuple[Station, callable]:
    """An in-process DecisionServer on port 0 in front of `core`; (station, stop)."""
    nowhere = grpc.insecure_channel(refused_address())  # no camera here
    facades = make_facades(core, robot_stub, sensor_stub,
                           stereo_camera_pb2_grpc.StereoCameraStub(nowhere))
    servicer = DecisionServerServicer(core)
    server, port = create_server(
        "127.0.0.1:0",
        [binding(decision_server_pb2_grpc, "DecisionServer", servicer),
         *(binding(module, name, servicer) for module, name, servicer in facades)],
        lanes=LANES)
    server.start()
    channel = grpc.insecure_channel(f"127.0.0.1:{port}")
    station = Station(core, channel, decision_server_pb2_grpc.DecisionServerStub(channel),
                      proxy_robot_pb2_grpc.ProxyRobotStub(channel),
                      force_sensor_pb2_grpc.ForceSensorStub(channel), f"127.0.0.1:{port}",
                      server, servicer)

    def stop():
        channel.close()
        server.stop(0)
        core.close()
        nowhere.close()

    return station, stop


@pytest.fixture
def fake_station(tmp_path) -> Iterator[tuple[Station, FakeSlave]]:
    """The DecisionServer over a fake slave on a fake clock; ProxyRobot and ForceSensor
    calls that it only forwards find nobody (UNAVAILABLE)."""
    clock = FakeClock()
    slave = FakeSlave(clock)
    core = DecisionCore(slave, RecordingStore(tmp_path / "recordings", clock, on_a_thread), clock)
    with grpc.insecure_channel(refused_address()) as nowhere:
        station, stop = serve_decisions(core, proxy_robot_pb2_grpc.ProxyRobotStub(nowhere),
                                        force_sensor_pb2_grpc.ForceSensorStub(nowhere))
        yield station, slave
        slave.end_wrench_streams()
        stop()


@pytest.fixture
def station(backends, tmp_path) -> Iterator[Station]:
    slave = GrpcSlave(backends.proxy_address, backends.sensor_address, backends.emergency_address)
    core = DecisionCore(slave, RecordingStore(tmp_path / "recordings"))
    station, stop = serve_decisions(core, slave.robot, slave.sensor)
    yield station
    stop()
    slave.close()
    # Leave the sensor stopped and untared for the next test.
    with grpc.insecure_channel(backends.sensor_address) as direct:
        force_sensor_pb2_grpc.ForceSensorStub(direct).StopReading(
            force_sensor_pb2.StopReadingRequest())


class Operator:
    """A Teleoperate stream driven from the test: send() one message, get its reply."""

    def __init__(self, station, lease_id: str, mapping=0, watchdog_s: float = 0.5):
        self._requests: queue.Queue = queue.Queue()
        self._sequence = 0
        init = pb.TeleoperateInit(operator_id="tester", lease_id=lease_id, mapping=mapping,
                                  watchdog_timeout=convert.duration(watchdog_s))
        self._requests.put(pb.TeleoperateRequest(init=init))
        self._replies = station.decisions.Teleoperate(iter(self._requests.get, None), timeout=60)
        self.ready = next(self._replies).ready

    def move(self, dx=(0, 0, 0), rotation=None, clutch=False, send_time_ns: int | None = None
             ) -> pb.CommandAck:
        self._sequence += 1
        command = pb.MasterCommand(sequence=self._sequence,
                                   send_time=convert.timestamp(send_time_ns or time.time_ns()),
                                   delta_position_m=convert.vector3_to_proto(dx),
                                   clutch_engaged=clutch)
        if rotation is not None:
            command.delta_rotation.CopyFrom(convert.rotation_to_proto(rotation))
        self._requests.put(pb.TeleoperateRequest(command=command))
        return next(self._replies).ack

    def close(self):
        self._requests.put(pb.TeleoperateRequest(end=pb.TeleoperateEnd()))
        self._requests.put(None)
        for _ in self._replies:
            pass
