"""ForceSensor over a real in-process gRPC server, reading the real simulated sensor."""

from __future__ import annotations

import os
import threading
import time

import grpc
import numpy as np
import pytest

from domain.robot_model.puma560 import HOME_Q
from services.force_sensor.core import ForceSensorCore
from services.force_sensor.servicer import ForceSensorServicer
from services.runtime.server import binding, create_server
from services.world.shm_link import SharedMemoryArmLink, SharedMemoryWrenchLink
from telerobot.v1 import force_sensor_pb2 as pb
from telerobot.v1 import force_sensor_pb2_grpc
from tests.conftest import wait_for
from tests.proxy_robot.conftest import send_home

pytestmark = pytest.mark.e2e


# On grpcio's sync server, and on grpc.aio (the service's default), where StreamWrench's
# Wakeups are waited for on the event loop (services/common/wakeup.py).
SERVERS = pytest.mark.parametrize("aio", [False, True], ids=["sync", "aio"])


@pytest.fixture(params=[False, True], ids=["sync", "aio"])
def sensor(world, request):
    send_home(world)
    core = ForceSensorCore(lambda: SharedMemoryWrenchLink(world.shm_name),
                           lambda: SharedMemoryArmLink(world.shm_name))
    server, port = create_server(
        "127.0.0.1:0", [binding(force_sensor_pb2_grpc, "ForceSensor", ForceSensorServicer(core))],
        aio=request.param)
    server.start()
    channel = grpc.insecure_channel(f"127.0.0.1:{port}")
    stub = force_sensor_pb2_grpc.ForceSensorStub(channel)
    stub.core, stub.address = core, f"127.0.0.1:{port}"
    yield stub
    channel.close()
    server.stop(0)
    core.close()


def force(sample: pb.WrenchSample) -> np.ndarray:
    f = sample.wrench.force_n
    return np.array([f.x, f.y, f.z])


def code_of(call) -> grpc.StatusCode:
    with pytest.raises(grpc.RpcError) as error:
        call()
    return error.value.code()


def collect(stream, count: int) -> list[pb.StreamWrenchResponse]:
    messages = []
    for message in stream:
        messages.append(message)
        if len(messages) == count:
            break
    stream.cancel()
    return messages


def wait_at_rest(world, speed_rad_per_s: float = 1e-5) -> None:
    """Until every joint moves slower than `speed_rad_per_s`. send_home stops waiting once the
    arm is within 1e-4 rad of home, still settling: at 5e-4 rad/s the tool's inertia shows as
    0.012 N, against 1e-13 rad/s and no force a moment later."""
    link = SharedMemoryArmLink(world.shm_name)
    try:
        wait_for(lambda: np.max(np.abs(link.read_arm().joint_velocities_rad_per_s))
                 < speed_rad_per_s, 5.0, "the arm at rest")
    finally:
        link.close()


def newer_sample(sensor, sequence: int) -> pb.WrenchSample:
    """The sensor's first sample after `sequence` (fails if none comes)."""
    def newer() -> pb.WrenchSample | None:
        sample = sensor.GetWrench(pb.GetWrenchRequest()).sample
        return sample if sample.sequence > sequence else None
    return wait_for(newer, 5.0, f"a sample after {sequence}")


def test_start_read_stop_and_resume(sensor, world):
    assert code_of(lambda: sensor.GetWrench(pb.GetWrenchRequest())) == (
        grpc.StatusCode.FAILED_PRECONDITION)
    started = sensor.StartReading(pb.StartReadingRequest(), timeout=5)
    assert started.config.reading and started.config.period.nanos == 1_000_000
    wait_at_rest(world)
    first = sensor.GetWrench(pb.GetWrenchRequest()).sample
    second = newer_sample(sensor, first.sequence)
    # No contact, no motion: the tool's weight is removed without any tare.
    assert np.linalg.norm(force(second)) < 0.01
    last = sensor.StopReading(pb.StopReadingRequest()).last_sequence
    # While the world makes 50 new sensor readings (50 ms at 1 kHz), the stopped sensor takes
    # none of them.
    raw = SharedMemoryWrenchLink(world.shm_name)
    try:
        since = raw.read_wrench().sequence
        wait_for(lambda: raw.read_wrench().sequence >= since + 50, 5.0, "50 more world steps")
    finally:
        raw.close()
    assert sensor.GetWrench(pb.GetWrenchRequest()).sample.sequence == last
    sensor.StartReading(pb.StartReadingRequest())
    newer_sample(sensor, last)


def test_tare_reads_near_zero_while_the_arm_moves_slowly(sensor, world):
    sensor.StartReading(pb.StartReadingRequest())
    tare = sensor.Tare(pb.TareRequest(duration={"nanos": 100_000_000}), timeout=5)
    # An average, not one sample: about 100 at 1 kHz, fewer when a loaded machine delays steps.
    assert tare.sample_count >= 10
    stream = sensor.StreamWrench(pb.StreamWrenchRequest(decimation=10), timeout=10)
    peaks: list[float] = []
    reader = threading.Thread(target=lambda: peaks.extend(
        np.linalg.norm(force(s)) for m in collect(stream, 60) for s in m.samples))
    reader.start()
    link = SharedMemoryArmLink(world.shm_name)
    try:
        # A slow ramp (0.1 rad/s) of the wrist, fed the way a teleoperation stream would. The
        # servo's reference still accelerates at its cap (10 rad/s²) whenever a target arrives
        # late, so the tool's own inertia shows: about 0.1 kg × 10 rad/s² × its lever arm.
        # Wrist joints keep that lever arm to a few centimetres.
        step = np.array([0, 0, 0, 1e-4, 1e-4, 1e-4])
        target = HOME_Q.copy()
        for _ in range(500):
            target += step
            link.write_target(target)
            # The fake operator's pace (1 kHz), as a teleoperation client would send: it sets
            # the ramp's speed and orders nothing (the reader ends after its 60 messages).
            time.sleep(0.001)
        moved = link.read_arm().joint_positions_rad - HOME_Q
    finally:
        link.close()
    reader.join(5)
    assert not reader.is_alive()  # all its samples are in peaks
    assert moved[3] > 0.02  # it did move
    # What is left is the tool's own inertia: well under a tenth of its 0.98 N weight.
    assert max(peaks) < 0.1, max(peaks)


def test_each_subscriber_gets_its_own_rate_and_batch_size(sensor):
    sensor.StartReading(pb.StartReadingRequest())
    stream = sensor.StreamWrench(pb.StreamWrenchRequest(decimation=10, batch_size=5), timeout=10)
    messages = collect(stream, 4)
    for message in messages:
        sequences = [s.sequence for s in message.samples]
        assert len(sequences) == 5
        assert all(b - a == 10 for a, b in zip(sequences, sequences[1:], strict=False))


def test_sensor_threshold_streams_only_changes(sensor):
    sensor.StartReading(pb.StartReadingRequest())
    reply = sensor.SetSensorConfig(pb.SetSensorConfigRequest(
        config=pb.SensorConfig(threshold_force_n=100.0),
        update_mask={"paths": ["threshold_force_n"]}))
    assert reply.config.threshold_force_n == 100.0
    before = sensor.GetWrench(pb.GetWrenchRequest()).sample.sequence
    stream = sensor.StreamWrench(pb.StreamWrenchRequest(), timeout=0.5)
    received = []
    with pytest.raises(grpc.RpcError) as ended:
        for message in stream:
            received.extend(message.samples)
    assert ended.value.code() is grpc.StatusCode.DEADLINE_EXCEEDED
    # At rest nothing changes by 100 N: at most the sample that opened the stream arrives.
    assert len(received) <= 1
    assert sensor.GetWrench(pb.GetWrenchRequest()).sample.sequence > before + 10  # sampling on


def test_a_stalled_subscriber_does_not_slow_another(sensor):
    sensor.StartReading(pb.StartReadingRequest())
    # Its own connection, with HTTP/2 window growth off, so gRPC's buffers fill in ~0.5 s.
    slow_channel = grpc.insecure_channel(sensor.address, options=[("grpc.http2.bdp_probe", 0)])
    stalled = force_sensor_pb2_grpc.ForceSensorStub(slow_channel).StreamWrench(
        pb.StreamWrenchRequest(queue_capacity=4), timeout=20)
    next(stalled)  # subscribed, then not read while the other one runs
    # 2 s at 1 kHz: enough to fill gRPC's own flow-control buffers behind the stalled stream.
    healthy = collect(sensor.StreamWrench(pb.StreamWrenchRequest(batch_size=10), timeout=20),
                      200)
    sequences = [s.sequence for m in healthy for s in m.samples]
    assert sequences == list(range(sequences[0], sequences[0] + 2000))  # every sample, no gap
    assert all(m.dropped_count == 0 for m in healthy)
    # The stalled subscriber lost samples once gRPC's buffers were full too, and says so:
    # every gap in its sequence numbers is counted in dropped_count.
    late = [message for _, message in zip(range(4000), stalled, strict=False)]
    stalled.cancel()
    slow_channel.close()
    late_sequences = [m.samples[0].sequence for m in late]
    gaps = sum(b - a - 1 for a, b in zip(late_sequences, late_sequences[1:], strict=False))
    assert late[-1].dropped_count > 0
    assert gaps == late[-1].dropped_count - late[0].dropped_count


def test_bad_configuration_is_refused_and_nothing_changes(sensor):
    before = sensor.GetSensorConfig(pb.GetSensorConfigRequest()).config
    bad = [
        pb.SetSensorConfigRequest(config=pb.SensorConfig(period={}),
                                  update_mask={"paths": ["period"]}),
        pb.SetSensorConfigRequest(config=pb.SensorConfig(period={"seconds": 5}),
                                  update_mask={"paths": ["period"]}),
        pb.SetSensorConfigRequest(config=pb.SensorConfig(period={"nanos": -1000}),
                                  update_mask={"paths": ["period"]}),
        pb.SetSensorConfigRequest(config=pb.SensorConfig(threshold_force_n=float("nan"))),
        pb.SetSensorConfigRequest(config=pb.SensorConfig(thread_priority=9),
                                  update_mask={"paths": ["thread_priority"]}),
        pb.SetSensorConfigRequest(config=pb.SensorConfig(threshold_force_n=1.0),
                                  update_mask={"paths": ["threshold_force_n", "color"]}),
        # A valid period with a NaN threshold: all or none, so the period must not change.
        pb.SetSensorConfigRequest(config=pb.SensorConfig(period={"nanos": 5_000_000},
                                                         threshold_torque_nm=float("nan"))),
    ]
    for request in bad:
        assert code_of(lambda r=request: sensor.SetSensorConfig(r)) == (
            grpc.StatusCode.INVALID_ARGUMENT)
    assert sensor.GetSensorConfig(pb.GetSensorConfigRequest()).config == before


def test_a_new_period_takes_effect(sensor):
    sensor.StartReading(pb.StartReadingRequest())
    sensor.SetSensorConfig(pb.SetSensorConfigRequest(
        config=pb.SensorConfig(period={"nanos": 10_000_000}), update_mask={"paths": ["period"]}))
    samples = [s for m in collect(sensor.StreamWrench(pb.StreamWrenchRequest(), timeout=10), 41)
               for s in m.samples]
    times = [s.sample_time.seconds + s.sample_time.nanos * 1e-9 for s in samples]
    gaps = np.diff(times)
    # Sample times are the world's 1 ms ticks, so single gaps jitter by a tick, and a loaded
    # machine delays samples and world steps (even two samples of one tick): judge the typical
    # gap, within 25 %, against the old period's 1 ms.
    assert 0.0075 <= np.median(gaps) <= 0.0125, gaps
    assert 0.0075 < np.mean(gaps) < 0.0125, gaps


@pytest.mark.skipif(os.geteuid() != 0, reason="raising a thread's priority needs privilege")
def test_thread_priority_sets_the_sampling_thread_nice_value(sensor):
    sensor.StartReading(pb.StartReadingRequest())
    for name, nice in (("HIGHEST", -10), ("LOWEST", 10), ("NORMAL", 0)):
        sensor.SetSensorConfig(pb.SetSensorConfigRequest(
            config=pb.SensorConfig(thread_priority=pb.SensorThreadPriority.Value(
                f"SENSOR_THREAD_PRIORITY_{name}")),
            update_mask={"paths": ["thread_priority"]}))
        thread_id = sensor.core._thread_id  # noqa: SLF001 - the OS thread to inspect
        assert os.getpriority(os.PRIO_PROCESS, thread_id) == nice


@SERVERS
def test_sensor_down_ends_streams_with_unavailable(world_factory, aio):
    world = world_factory()
    core = ForceSensorCore(lambda: SharedMemoryWrenchLink(world.shm_name),
                           lambda: SharedMemoryArmLink(world.shm_name))
    server, port = create_server(
        "127.0.0.1:0", [binding(force_sensor_pb2_grpc, "ForceSensor", ForceSensorServicer(core))],
        aio=aio)
    server.start()
    try:
        with grpc.insecure_channel(f"127.0.0.1:{port}") as channel:
            stub = force_sensor_pb2_grpc.ForceSensorStub(channel)
            stub.StartReading(pb.StartReadingRequest())
            stream = stub.StreamWrench(pb.StreamWrenchRequest(), timeout=10)
            next(stream)
            world.running.stop()  # returns once the world has exited
            with pytest.raises(grpc.RpcError) as ended:
                for _ in stream:
                    pass
            assert ended.value.code() is grpc.StatusCode.UNAVAILABLE
            assert code_of(lambda: stub.GetWrench(pb.GetWrenchRequest())) == (
                grpc.StatusCode.UNAVAILABLE)
    finally:
        server.stop(0)
        core.close()
