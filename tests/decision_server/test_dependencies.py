"""Each dependency's state (services/decision_server/dependencies.py): from its health and the
launcher's state file, on a fake slave and a fake clock; then through GetDependencies and
StreamEvents on an in-process server."""

from __future__ import annotations

import os
import re
import signal
import socket
import time

import grpc
import pytest
from grpc_health.v1 import health_pb2, health_pb2_grpc

from services.decision_server.backends import GrpcSlave
from services.decision_server.dependencies import (
    NOT_SERVING,
    RECONNECT_GRACE_S,
    RESTARTING_STATE,
    SERVING,
    UNSPECIFIED,
    DependencyChanged,
    DependencyWatch,
    assess,
)
from services.runtime import children
from services.runtime.server import create_server
from services.runtime.supervisor_state import (
    GAVE_UP,
    RESTARTING,
    RUNNING,
    SUPERVISOR_STATE_ENV,
    ChildState,
    read_state,
    write_state,
)
from telerobot.v1 import decision_server_pb2 as pb
from telerobot.v1 import decision_server_pb2_grpc
from tests.conftest import wait_for
from tests.fakes.clock import FakeClock
from tests.fakes.slave import FakeSlave
from tests.processes import start_service, start_station, station_env

REFUSED = "UNAVAILABLE: failed to connect to all addresses; last error: Connection refused"
KILLED = "was killed by signal 9 (SIGKILL)"


@pytest.fixture
def watched(tmp_path):
    """A watch over a fake slave's health and a launcher state file in tmp_path, on a fake
    clock; every change it raised, in order."""
    clock = FakeClock()
    slave = FakeSlave(clock)
    state_file = tmp_path / "supervisor.json"
    watch = DependencyWatch(slave.health, clock, lambda: read_state(state_file))
    changes: list[DependencyChanged] = []
    watch.subscribe(changes.append)
    yield watch, slave, clock, state_file, changes
    watch.close()


def by_name(dependencies) -> dict:
    return {d.name: d for d in dependencies}


def test_assess_combines_the_answer_with_what_the_launcher_knows():
    now = 1_000_000.0
    assert assess("ok", None, now) == (SERVING, "", 0)
    assert assess("ok", ChildState(RUNNING, restarts=2), now) == (SERVING, "", 2)
    # Down and not supervised, or supervised as running: the transport's reason.
    assert assess(REFUSED, None, now) == (NOT_SERVING, REFUSED, 0)
    assert assess(REFUSED, ChildState(RUNNING, 1, KILLED, since=now - 60), now) == (
        NOT_SERVING, REFUSED, 1)
    # Down while the launcher restarts it: its reason, naming the restart under way.
    state, reason, restarts = assess(REFUSED, ChildState(RESTARTING, 1, KILLED), now)
    assert (state, restarts) == (RESTARTING_STATE, 1)
    assert reason == f"restarting after it {KILLED}; restart 2"
    # Restarted and serving on the launcher's side, not reconnected here yet: still restarting
    # for a moment, not a blip of NOT_SERVING.
    state, reason, _ = assess(REFUSED, ChildState(RUNNING, 2, KILLED, since=now - 1), now)
    assert state == RESTARTING_STATE and reason.startswith("restarted (restart 2)")
    assert assess(REFUSED, ChildState(RUNNING, 2, KILLED, since=now - 1 - RECONNECT_GRACE_S),
                  now)[0] == NOT_SERVING
    # The launcher restarting it, but it answers already: serving.
    assert assess("ok", ChildState(RESTARTING, 1, KILLED), now)[0] == SERVING
    # Given up on: not serving, and why the launcher stopped trying.
    state, reason, _ = assess(REFUSED, ChildState(GAVE_UP, 4, KILLED), now)
    assert state == NOT_SERVING and REFUSED in reason and "gave up" in reason


def test_serving_then_down_then_restarting_then_serving_raises_one_event_per_change(watched):
    watch, slave, clock, state_file, changes = watched
    first = by_name(watch.poll())
    assert list(first) == ["proxy_robot", "force_sensor", "stereo_camera", "emergency_stop"]
    assert {d.state for d in first.values()} == {SERVING}
    assert [c.previous_state for c in changes] == [UNSPECIFIED] * 4  # first seen
    changes.clear()
    watch.poll()
    assert changes == []  # nothing changed

    clock.advance(1.0)
    slave.dependency_health["force_sensor"] = REFUSED
    sensor = by_name(watch.poll())["force_sensor"]
    assert (sensor.state, sensor.reason, sensor.restarts) == (NOT_SERVING, REFUSED, 0)
    assert sensor.change_time_ns == clock.time_ns()
    assert [(c.dependency, c.previous_state) for c in changes] == [(sensor, SERVING)]
    # The same state with other words from the transport: no event, the newer reason.
    clock.advance(0.1)
    slave.dependency_health["force_sensor"] = "UNAVAILABLE: Socket closed"
    again = by_name(watch.poll())["force_sensor"]
    assert again.reason == "UNAVAILABLE: Socket closed"
    assert again.change_time_ns == sensor.change_time_ns and len(changes) == 1

    clock.advance(0.1)
    write_state(state_file, {"force_sensor": ChildState(RESTARTING, 0, KILLED)})
    restarting = by_name(watch.poll())["force_sensor"]
    assert restarting.state == RESTARTING_STATE and restarting.restarts == 0
    assert restarting.reason == f"restarting after it {KILLED}; restart 1"
    assert [(c.dependency, c.previous_state) for c in changes[1:]] == [
        (restarting, NOT_SERVING)]

    clock.advance(0.1)
    write_state(state_file, {"force_sensor": ChildState(RUNNING, 1, KILLED, clock.time())})
    assert by_name(watch.poll())["force_sensor"].restarts == 1  # restarted, not here yet:
    assert len(changes) == 2  # still RESTARTING, no event
    slave.dependency_health["force_sensor"] = "ok"
    back = by_name(watch.poll())["force_sensor"]
    assert (back.state, back.reason, back.restarts) == (SERVING, "", 1)
    assert [(c.dependency, c.previous_state) for c in changes[2:]] == [(back, RESTARTING_STATE)]
    assert [c.dependency.name for c in changes] == ["force_sensor"] * 3  # the others: quiet
    assert by_name(watch.dependencies())["proxy_robot"].state == SERVING


def test_a_malformed_launcher_entry_is_ignored(watched):
    watch, slave, _, state_file, _ = watched
    slave.dependency_health["force_sensor"] = REFUSED
    state_file.write_text('{"services": {"force_sensor": {"state": "restarting", '
                          '"restarts": "two", "last_exit": 9}}}')
    sensor = by_name(watch.poll())["force_sensor"]
    assert (sensor.state, sensor.reason, sensor.restarts) == (NOT_SERVING, REFUSED, 0)


def test_without_a_band_there_are_three_and_listeners_can_get_the_current_states(watched):
    watch, slave, _, _, _ = watched
    del slave.dependency_health["emergency_stop"]  # configured without one
    slave.reachable = False
    watch.poll()
    seen = []
    watch.subscribe(seen.append, current=True)
    assert {(c.dependency.name, c.dependency.state) for c in seen} == {
        ("proxy_robot", NOT_SERVING), ("force_sensor", NOT_SERVING),
        ("stereo_camera", SERVING)}


def test_the_thread_polls_on_its_clock(watched):
    watch, slave, clock, _, changes = watched
    watch.start()
    assert len(changes) == 4  # start() looks once at once
    wait_for(lambda: clock.waiters() == 1, what="the watch to wait for its next poll")
    slave.dependency_health["stereo_camera"] = REFUSED
    assert len(changes) == 4  # no time has passed: no look
    clock.advance(0.1)
    wait_for(lambda: len(changes) == 5, what="the change, on the next poll")
    assert changes[-1].dependency.state == NOT_SERVING
    assert changes[-1].dependency.name == "stereo_camera"


def test_a_failing_listener_does_not_stop_the_others(watched):
    watch, slave, _, _, changes = watched

    def broken(change):
        raise RuntimeError("boom")

    watch.subscribe(broken)
    watch.poll()
    assert len(changes) == 4


def test_two_polls_at_once_never_leave_the_older_reading_last():
    """The watch's poll and a GetDependencies' poll run at once: the one that read the health
    first must not write its (older) reading after the other's newer one, or a camera seen
    gone would be SERVING again until the next poll."""
    import threading

    readings = iter([{"stereo_camera": "ok"}, {"stereo_camera": REFUSED}])
    first_reading, release_first = threading.Event(), threading.Event()

    def health() -> dict[str, str]:
        reading = next(readings)
        if reading["stereo_camera"] == "ok":  # the first poll reads, then is descheduled
            first_reading.set()
            release_first.wait(10)
        return reading

    watch = DependencyWatch(health, FakeClock(), lambda: {})

    class Contended:
        """The watch's lock, telling when a poll has to wait for it."""

        def __init__(self, lock):
            self._lock, self.waited = lock, threading.Event()

        def __enter__(self):
            if not self._lock.acquire(blocking=False):
                self.waited.set()
                self._lock.acquire()

        def __exit__(self, *exc):
            self._lock.release()

    lock = Contended(watch._lock)  # noqa: SLF001 - to see the second poll wait
    watch._lock = lock  # noqa: SLF001
    older = threading.Thread(target=watch.poll)
    older.start()
    assert first_reading.wait(10)
    newer = threading.Thread(target=watch.poll)
    newer.start()
    wait_for(lambda: lock.waited.is_set() or not newer.is_alive(), timeout_s=10,
             what="the second poll waiting for the first, or done")
    release_first.set()
    older.join(10)
    newer.join(10)
    assert by_name(watch.dependencies())["stereo_camera"].state == NOT_SERVING


# -- through the DecisionServer's contract ----------------------------------------------------

def test_get_dependencies_and_the_event_through_grpc(fake_station):
    station, slave = fake_station
    reply = station.decisions.GetDependencies(pb.GetDependenciesRequest(), timeout=5)
    assert [(d.name, d.state) for d in reply.dependencies] == [
        (name, pb.DEPENDENCY_STATE_SERVING)
        for name in ("proxy_robot", "force_sensor", "stereo_camera", "emergency_stop")]
    assert all(d.reason == "" and d.change_time.seconds > 0 for d in reply.dependencies)

    stream = station.decisions.StreamEvents(pb.StreamEventsRequest(), timeout=10)
    wait_for(lambda: station.core.events.subscriber_count >= 1,
             what="the event stream to subscribe")
    slave.dependency_health["force_sensor"] = REFUSED
    sensor = station.decisions.GetDependencies(pb.GetDependenciesRequest(),
                                               timeout=5).dependencies[1]
    assert (sensor.name, sensor.state, sensor.reason) == (
        "force_sensor", pb.DEPENDENCY_STATE_NOT_SERVING, REFUSED)
    slave.dependency_health["force_sensor"] = "ok"
    station.decisions.GetDependencies(pb.GetDependenciesRequest(), timeout=5)
    received = [next(stream) for _ in range(2)]
    stream.cancel()
    assert [m.WhichOneof("event") for m in received] == ["dependency_changed"] * 2
    down, up = (m.dependency_changed for m in received)
    assert (down.dependency, down.previous_state) == (sensor, pb.DEPENDENCY_STATE_SERVING)
    assert (up.dependency.name, up.dependency.state, up.previous_state) == (
        "force_sensor", pb.DEPENDENCY_STATE_SERVING, pb.DEPENDENCY_STATE_NOT_SERVING)
    assert received[1].sequence == received[0].sequence + 1


# -- a real dependency killed (e2e) -----------------------------------------------------------

def _dependencies(stub) -> dict:
    reply = stub.GetDependencies(pb.GetDependenciesRequest(), timeout=5)
    return {d.name: d for d in reply.dependencies}


def _health(channel, dependency: str | None) -> int:
    """The DecisionServer's health entry for `dependency`, or its own (None)."""
    service = f"telerobot.v1.DecisionServer/{dependency}" if dependency else ""
    return health_pb2_grpc.HealthStub(channel).Check(health_pb2.HealthCheckRequest(
        service=service), timeout=5).status


@pytest.mark.e2e
def test_a_killed_sensor_is_not_serving_then_restarting_then_serving(world, backends,
                                                                      tmp_path):
    """A DecisionServer process in front of the real ProxyRobot and band, and a ForceSensor and
    a StereoCamera of this test's own: SIGKILL the sensor, and GetDependencies, the health
    service and the events say so; the launcher's state file (written here as the launcher
    would) makes it RESTARTING; a new sensor on the same address makes it SERVING again."""
    sensor_env = {"TELEROBOT_WORLD_SHM": world.shm_name}
    sensor = start_service("force_sensor", env=sensor_env)
    started = [sensor]
    try:
        started.append(start_service(
            "stereo_camera", "--source", "pattern", "--width", "64", "--height", "48",
            "--fps", "5"))
        state_file = tmp_path / "supervisor.json"
        started.append(start_service(
            "decision_server", "--proxy-robot-address", backends.proxy_address,
            "--force-sensor-address", sensor.address,
            "--stereo-camera-address", started[1].address,
            "--emergency-stop-address", backends.emergency_address,
            "--recordings-dir", str(tmp_path / "recordings"),
            env={SUPERVISOR_STATE_ENV: str(state_file)}))
        with grpc.insecure_channel(started[2].address) as channel:
            stub = decision_server_pb2_grpc.DecisionServerStub(channel)
            wait_for(lambda: {d.state for d in _dependencies(stub).values()} == {
                pb.DEPENDENCY_STATE_SERVING}, 10, "every dependency to serve")
            assert list(_dependencies(stub)) == [
                "proxy_robot", "force_sensor", "stereo_camera", "emergency_stop"]
            assert _health(channel, "force_sensor") == health_pb2.HealthCheckResponse.SERVING
            events = stub.StreamEvents(pb.StreamEventsRequest(), timeout=60)
            # An event of another kind, to know the stream has subscribed.
            lease = stub.AcquireControl(pb.AcquireControlRequest(
                operator_id="watcher", mode=pb.CONTROL_MODE_EXCLUSIVE), timeout=5).lease_id
            stub.ReleaseControl(pb.ReleaseControlRequest(lease_id=lease), timeout=5)
            assert next(events).WhichOneof("event") == "control_changed"

            os.kill(sensor.pid, signal.SIGKILL)
            down = wait_for(lambda: (d := _dependencies(stub)["force_sensor"]).state ==
                            pb.DEPENDENCY_STATE_NOT_SERVING and d, 10, "the sensor down")
            assert down.reason.startswith("UNAVAILABLE"), down.reason
            assert _health(channel, "force_sensor") == \
                health_pb2.HealthCheckResponse.NOT_SERVING
            assert _health(channel, None) == health_pb2.HealthCheckResponse.SERVING  # itself
            assert _dependencies(stub)["proxy_robot"].state == pb.DEPENDENCY_STATE_SERVING

            write_state(state_file, {"force_sensor": ChildState(
                RESTARTING, 0, KILLED, time.time())})
            restarting = wait_for(lambda: (d := _dependencies(stub)["force_sensor"]).state ==
                                  pb.DEPENDENCY_STATE_RESTARTING and d, 10, "restarting")
            assert restarting.reason == f"restarting after it {KILLED}; restart 1"

            # (its metrics on a free port: its address is fixed, the default one may be taken)
            started.append(start_service("force_sensor", "--address", sensor.address,
                                         "--metrics-address", "127.0.0.1:0", env=sensor_env))
            write_state(state_file, {"force_sensor": ChildState(RUNNING, 1, KILLED,
                                                                 time.time())})
            back = wait_for(lambda: (d := _dependencies(stub)["force_sensor"]).state ==
                            pb.DEPENDENCY_STATE_SERVING and d, 10, "the sensor back")
            assert back.restarts == 1 and back.reason == ""
            assert _health(channel, "force_sensor") == health_pb2.HealthCheckResponse.SERVING

            changes = []
            for event in events:
                if event.WhichOneof("event") == "dependency_changed":
                    changes.append(event.dependency_changed)
                    if changes[-1].dependency.state == pb.DEPENDENCY_STATE_SERVING:
                        break
            events.cancel()
            assert [(c.dependency.name, c.previous_state, c.dependency.state)
                    for c in changes] == [
                ("force_sensor", pb.DEPENDENCY_STATE_SERVING, pb.DEPENDENCY_STATE_NOT_SERVING),
                ("force_sensor", pb.DEPENDENCY_STATE_NOT_SERVING,
                 pb.DEPENDENCY_STATE_RESTARTING),
                ("force_sensor", pb.DEPENDENCY_STATE_RESTARTING, pb.DEPENDENCY_STATE_SERVING)]
    finally:
        children.stop_all(started)


@pytest.mark.e2e
def test_the_observers_router_is_a_dependency_that_goes_and_comes_back(backends, tmp_path):
    """A DecisionServer told of the station's Zenoh router (a port of this test's own here)
    lists it last, NOT_SERVING while nothing accepts on its port, SERVING when it does again."""
    router = socket.create_server(("127.0.0.1", 0))
    address = f"127.0.0.1:{router.getsockname()[1]}"
    door = start_service(
        "decision_server", "--proxy-robot-address", backends.proxy_address,
        "--force-sensor-address", backends.sensor_address,
        "--emergency-stop-address", backends.emergency_address,
        "--zenoh-router-address", address, "--recordings-dir", str(tmp_path / "recordings"))
    try:
        with grpc.insecure_channel(door.address) as channel:
            stub = decision_server_pb2_grpc.DecisionServerStub(channel)
            wait_for(lambda: _dependencies(stub)["zenoh_router"].state ==
                     pb.DEPENDENCY_STATE_SERVING, 10, "the router serving")
            assert list(_dependencies(stub))[-1] == "zenoh_router"
            router.close()
            gone = wait_for(lambda: (d := _dependencies(stub)["zenoh_router"]).state ==
                            pb.DEPENDENCY_STATE_NOT_SERVING and d, 10, "the router gone")
            assert gone.reason.startswith("UNAVAILABLE") and address in gone.reason
            assert _health(channel, "zenoh_router") == \
                health_pb2.HealthCheckResponse.NOT_SERVING
            assert _health(channel, None) == health_pb2.HealthCheckResponse.SERVING  # itself
            router = socket.create_server(("127.0.0.1", int(address.rsplit(":", 1)[1])))
            wait_for(lambda: _dependencies(stub)["zenoh_router"].state ==
                     pb.DEPENDENCY_STATE_SERVING, 10, "the router back")
    finally:
        router.close()
        door.stop()


# -- GrpcSlave's health watches, against an in-process server ----------------------------------

def test_grpc_slave_watches_each_dependency_s_health():
    """One server (health only) plays the arm, the sensor, the band and the camera: its
    health changes reach health() for each, and so does its end."""
    server, port = create_server("127.0.0.1:0", [])
    server.start()
    server.set_serving()
    address = f"127.0.0.1:{port}"
    slave = GrpcSlave(address, address, address)
    camera = grpc.insecure_channel(address)
    try:
        slave.watch_health("stereo_camera", camera)
        assert slave.wait_health(5.0)
        names = {"proxy_robot", "force_sensor", "emergency_stop", "stereo_camera"}
        wait_for(lambda: slave.health() == dict.fromkeys(names, "ok"), what="all ok")
        server.health.set("", health_pb2.HealthCheckResponse.NOT_SERVING)
        wait_for(lambda: set(slave.health().values()) == {
            "NOT_SERVING: its health check says it is not serving"}, what="not serving")
        server.stop(0)
        wait_for(lambda: all(v.startswith("UNAVAILABLE") for v in slave.health().values()),
                 what="unavailable")
    finally:
        slave.close()
        camera.close()
        server.stop(0)


@pytest.mark.e2e
def test_through_the_launcher_a_killed_camera_is_restarting_then_serving(tmp_path):
    """The whole station (the launcher restarts a child that dies, and says so in its state
    file): SIGKILL the camera, and the DecisionServer reports it RESTARTING with the
    launcher's reason, then SERVING with one restart, in its events and its health."""
    launcher = start_station(station_env(
        TELEROBOT_STEREO_CAMERA_SOURCE="pattern", TELEROBOT_STEREO_CAMERA_WIDTH="64",
        TELEROBOT_STEREO_CAMERA_HEIGHT="48", TELEROBOT_STEREO_CAMERA_FPS="5",
        TELEROBOT_RECORDINGS_DIR=str(tmp_path / "recordings"), TELEROBOT_LOG_LEVEL="WARNING"))
    try:
        pid = next(int(match.group(1)) for line in launcher.lines
                   if (match := re.search(r"^\s*stereo_camera\s.*\(pid (\d+)\)", line)))
        with grpc.insecure_channel(launcher.ready["decision_server"]) as channel:
            stub = decision_server_pb2_grpc.DecisionServerStub(channel)
            wait_for(lambda: {d.state for d in _dependencies(stub).values()} == {
                pb.DEPENDENCY_STATE_SERVING}, 10, "every dependency to serve")
            events = stub.StreamEvents(pb.StreamEventsRequest(), timeout=120)
            lease = stub.AcquireControl(pb.AcquireControlRequest(
                operator_id="watcher", mode=pb.CONTROL_MODE_EXCLUSIVE), timeout=5).lease_id
            stub.ReleaseControl(pb.ReleaseControlRequest(lease_id=lease), timeout=5)
            assert next(events).WhichOneof("event") == "control_changed"  # subscribed

            os.kill(pid, signal.SIGKILL)
            restarting = wait_for(lambda: (d := _dependencies(stub)["stereo_camera"]).state ==
                                  pb.DEPENDENCY_STATE_RESTARTING and d, 10, "restarting")
            assert "killed by signal 9" in restarting.reason, restarting.reason
            assert _health(channel, "stereo_camera") == \
                health_pb2.HealthCheckResponse.NOT_SERVING
            back = wait_for(lambda: (d := _dependencies(stub)["stereo_camera"]).state ==
                            pb.DEPENDENCY_STATE_SERVING and d, 60, "the camera back")
            assert back.restarts == 1
            assert _health(channel, "stereo_camera") == health_pb2.HealthCheckResponse.SERVING

            states = []
            for event in events:
                if event.WhichOneof("event") == "dependency_changed":
                    change = event.dependency_changed
                    assert change.dependency.name == "stereo_camera"  # the others: quiet
                    states.append(change.dependency.state)
                    if change.dependency.state == pb.DEPENDENCY_STATE_SERVING:
                        break
            events.cancel()
            # The health watch may see the camera gone before the launcher writes its state.
            assert states in ([pb.DEPENDENCY_STATE_RESTARTING, pb.DEPENDENCY_STATE_SERVING],
                              [pb.DEPENDENCY_STATE_NOT_SERVING, pb.DEPENDENCY_STATE_RESTARTING,
                               pb.DEPENDENCY_STATE_SERVING]), states
    finally:
        launcher.stop(signal.SIGINT)
