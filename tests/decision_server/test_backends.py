"""GrpcSlave, the DecisionServer's port to the slave over gRPC, against in-process fakes of
ProxyRobot and ForceSensor on port 0: what acks may show, streams that come and go, and the
moves over ProxyRobot's local socket."""

from __future__ import annotations

import queue
import threading
import time

import numpy as np
import pytest

from services.decision_server import backends
from services.decision_server.backends import GrpcSlave
from services.runtime.server import binding, create_server
from telerobot.v1 import (
    force_sensor_pb2,
    force_sensor_pb2_grpc,
    proxy_robot_pb2,
    proxy_robot_pb2_grpc,
)
from tests.conftest import wait_for
from wire.errors import UnavailableError


class Sensor(force_sensor_pb2_grpc.ForceSensorServicer):
    """Streams every sample a test puts in to every open stream, stamped when it is sent."""

    def __init__(self):
        self._streams: list[queue.Queue] = []
        self._lock = threading.Lock()

    def put(self, force_z: float) -> None:
        with self._lock:
            for stream in self._streams:
                stream.put(force_z)

    def streams(self) -> int:
        with self._lock:
            return len(self._streams)

    def StreamWrench(self, request, context):
        samples: queue.Queue = queue.Queue()
        with self._lock:
            self._streams.append(samples)
        context.add_callback(lambda: self._forget(samples))
        while context.is_active():
            try:
                force_z = samples.get(timeout=0.05)
            except queue.Empty:
                continue
            sample = force_sensor_pb2.WrenchSample(sequence=1)
            sample.wrench.force_n.z = force_z
            sample.sample_time.FromNanoseconds(time.time_ns())
            yield force_sensor_pb2.StreamWrenchResponse(samples=[sample])

    def _forget(self, samples: queue.Queue) -> None:
        with self._lock:
            self._streams.remove(samples)


class Robot(proxy_robot_pb2_grpc.ProxyRobotServicer):
    """A ProxyRobot whose streams send nothing and stay open, or end at once every time (a
    backend that keeps restarting)."""

    def __init__(self):
        self.opened = 0
        self.lock = threading.Lock()
        self._ending = False
        self._open: set[threading.Event] = set()  # one per stream waiting to end

    def end_every_stream(self) -> None:
        """From now on every stream ends as soon as it opens, the ones open now too."""
        with self.lock:
            self._ending = True
            for end in self._open:
                end.set()

    def _stream(self, context):
        end = threading.Event()
        context.add_callback(end.set)  # the client left
        with self.lock:
            self.opened += 1
            if self._ending:
                end.set()
            self._open.add(end)
        end.wait()
        with self.lock:
            self._open.discard(end)
        return
        yield

    def StreamState(self, request, context):
        yield from self._stream(context)

    def StreamRobotEvents(self, request, context):
        yield from self._stream(context)


@pytest.fixture
def slave(monkeypatch):
    monkeypatch.setattr(backends, "RETRY_S", 0.01)  # reconnect at once
    sensor, robot = Sensor(), Robot()
    server, port = create_server("127.0.0.1:0", [
        binding(force_sensor_pb2_grpc, "ForceSensor", sensor),
        binding(proxy_robot_pb2_grpc, "ProxyRobot", robot)])
    server.start()
    slave = GrpcSlave(f"127.0.0.1:{port}", f"127.0.0.1:{port}")
    yield slave, sensor, robot
    slave.close()
    server.stop(0)


def test_a_wrench_that_stopped_coming_leaves_the_acks(slave):
    """Defect: acks showed the last cached wrench for ever after StopReading."""
    slave, sensor, _ = slave
    wait_for(lambda: sensor.streams() == 1, what="the wrench follower to subscribe")
    # A reading sensor streams sample after sample: one alone is fresh for WRENCH_FRESH_S only,
    # which a loaded machine can spend delivering it (CI once did).
    fresh = wait_for(lambda: _reading(sensor, -4.0, slave), what="a wrench sample")
    assert fresh.force_n[2] == -4.0
    # No more samples (the sensor stopped reading): within WRENCH_FRESH_S it is gone.
    wait_for(lambda: slave.wrench() is None, 2, "the stale wrench to be dropped")
    assert wait_for(lambda: _reading(sensor, -5.0, slave), what="a new sample").force_n[2] == -5.0


def _reading(sensor: Sensor, force_z: float, slave):
    """One more sample of `force_z` from the sensor; the slave's wrench if it is that one."""
    sensor.put(force_z)
    wrench = slave.wrench()
    return wrench if wrench is not None and wrench.force_n[2] == force_z else None


def test_streams_reopened_after_a_reconnect_are_not_kept(slave):
    """Defect: every re-opened background stream was added to a list and never removed."""
    slave, _, robot = slave
    wait_for(lambda: robot.opened >= 2, what="the state and event streams to open")
    robot.end_every_stream()  # the open ones end too (CI once set a flag they never saw)
    wait_for(lambda: robot.opened >= 20, 10, "the streams to reopen 20 times")
    assert slave.open_streams() <= 3  # state, wrench and events, at most


def test_a_wrench_stream_is_forgotten_when_cancelled(slave):
    slave, sensor, _ = slave
    wait_for(lambda: slave.open_streams() == 3, what="the three background streams")
    before = 3
    stream = slave.wrench_stream(1)
    samples = iter(stream)
    wait_for(lambda: sensor.streams() == 2, what="the wrench stream to open")  # and the follower
    sensor.put(1.0)
    assert next(samples).force_n[2] == 1.0
    assert slave.open_streams() == before + 1
    stream.cancel()
    assert list(samples) == []
    assert slave.open_streams() == before


class Mover(Robot):
    """A Robot that answers moves over gRPC, counting them."""

    def __init__(self):
        super().__init__()
        self.moves = 0

    def MoveCartesianIncremental(self, request, context):
        self.moves += 1
        return proxy_robot_pb2.MoveCartesianIncrementalResponse(applied_fraction=1.0)


def test_moves_go_over_the_local_socket_and_over_grpc_only_when_it_cannot_be_reached(
        tmp_path, caplog):
    from wire.local_call import LocalCallServer

    robot = Mover()
    server, port = create_server("127.0.0.1:0", [
        binding(proxy_robot_pb2_grpc, "ProxyRobot", robot)])
    server.start()
    local_moves: list[object] = []
    path = tmp_path / "moves.sock"

    def local_move(request):
        local_moves.append(request)
        return proxy_robot_pb2.MoveCartesianIncrementalResponse(applied_fraction=0.5)

    local = LocalCallServer(path, {
        "/telerobot.v1.ProxyRobot/MoveCartesianIncremental":
            (proxy_robot_pb2.MoveCartesianIncrementalRequest, local_move)})
    local.start()
    slave = GrpcSlave(f"127.0.0.1:{port}", f"127.0.0.1:{port}", local_calls=str(path))
    step = (np.array([0.0, 0.0, 0.001]), np.eye(3), "BASE")
    try:
        assert slave.move_cartesian(*step).applied_fraction == 0.5
        assert (len(local_moves), robot.moves) == (1, 0)
        local.stop()  # no socket there any more: the move was never sent, so gRPC takes it
        assert slave.move_cartesian(*step).applied_fraction == 1.0
        assert slave.move_cartesian(*step).applied_fraction == 1.0
        assert (len(local_moves), robot.moves) == (1, 2)
        warnings = [r for r in caplog.records if "moving over gRPC" in r.getMessage()]
        assert len(warnings) == 1  # said once, not per move
    finally:
        slave.close()
        server.stop(0)


def test_a_local_move_whose_reply_was_lost_is_not_sent_over_grpc(tmp_path):
    from wire.local_call import LocalCallServer

    robot = Mover()
    server, port = create_server("127.0.0.1:0", [
        binding(proxy_robot_pb2_grpc, "ProxyRobot", robot)])
    server.start()
    path = tmp_path / "moves.sock"
    holder: list[LocalCallServer] = []

    def dies_mid_call(request):
        holder[0].stop()  # the move is taken, then ProxyRobot goes before it replies
        return proxy_robot_pb2.MoveCartesianIncrementalResponse(applied_fraction=1.0)

    local = LocalCallServer(path, {
        "/telerobot.v1.ProxyRobot/MoveCartesianIncremental":
            (proxy_robot_pb2.MoveCartesianIncrementalRequest, dies_mid_call)})
    holder.append(local)
    local.start()
    slave = GrpcSlave(f"127.0.0.1:{port}", f"127.0.0.1:{port}", local_calls=str(path))
    try:
        with pytest.raises(UnavailableError) as lost:
            slave.move_cartesian(np.zeros(3), np.eye(3), "BASE")
        assert lost.value.reason == "LOCAL_CALL_LOST"
        assert robot.moves == 0  # never sent a second time
    finally:
        slave.close()
        server.stop(0)
