"""The station's observation end to end: `make serve`'s launcher starts a Zenoh router and the
publisher beside the services, and `python -m clients.observe` sees the wrench, the arm's
state and the DecisionServer's events through the router; a router that dies takes nothing
else down, observers are back once the launcher restarted it, and the DecisionServer reports
it among its dependencies."""

from __future__ import annotations

import itertools
import json
import os
import signal
import subprocess
import sys

import grpc
import pytest

from clients.observe import Observer
from services.runtime.port_watch import OK, accepts
from telerobot.v1 import decision_server_pb2 as ds_pb
from telerobot.v1 import (
    decision_server_pb2_grpc,
    force_sensor_pb2,
    force_sensor_pb2_grpc,
    proxy_robot_pb2,
    proxy_robot_pb2_grpc,
)
from tests.conftest import wait_for
from tests.observation.test_c_observer import c_observer, lines_of
from tests.processes import REPO, health_serving, service_pid, start_station, station_env
from wire.observation import client

pytestmark = pytest.mark.e2e

STATION = "lab-3"


@pytest.fixture(scope="module")
def station():
    launcher = start_station(station_env(TELEROBOT_STATION=STATION))
    with grpc.insecure_channel(launcher.ready["proxy_robot"]) as channel:
        robot = proxy_robot_pb2_grpc.ProxyRobotStub(channel)
        robot.Connect(proxy_robot_pb2.ConnectRequest(), timeout=30)
        robot.Initialize(proxy_robot_pb2.InitializeRequest(), timeout=30)
    with grpc.insecure_channel(launcher.ready["force_sensor"]) as channel:
        force_sensor_pb2_grpc.ForceSensorStub(channel).StartReading(
            force_sensor_pb2.StartReadingRequest(), timeout=10)
    yield launcher
    if launcher.process.poll() is None:
        launcher.stop(signal.SIGINT)


def observe(router: str, *args: str) -> subprocess.Popen:
    return subprocess.Popen([sys.executable, "-m", "clients.observe", "--router",
                             f"tcp/{router}", *args], cwd=REPO, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)


def summary_of(process: subprocess.Popen, nothing: bool = False) -> dict:
    """Its --json summary; it exits with 1 when nothing arrived (`nothing`), else 0."""
    out, err = process.communicate(timeout=60)
    assert process.returncode == (1 if nothing else 0), (out, err)
    return json.loads(out.strip().splitlines()[-1])


def test_the_observe_client_sees_every_wrench_sample_and_the_state(station):
    summary = summary_of(observe(station.ready["zenoh_router"], "--station", STATION,
                                 "--seconds", "3", "--json"))
    wrench, state = summary["wrench"], summary["state"]
    assert wrench["samples"] >= 10 * wrench["messages"] > 0  # every sample, 10 a message
    assert state["messages"] > 0
    assert all(summary[t]["undecodable"] == 0 for t in summary)
    assert 0 <= wrench["lag_p50_ms"] < 1000, wrench  # taken on this host's clock


def test_the_c_observer_follows_the_station(station):
    """Zenoh's C client, with the protos' C code, sees the sensor's samples in order (a loaded
    link may drop a message: never the station's time) and the arm."""
    lines = lines_of(c_observer("--router", f"tcp/{station.ready['zenoh_router']}",
                                "--station", STATION, "--topics", "wrench,state",
                                "--seconds", "3"))
    wrench = [line for line in lines if line.get("topic") == "wrench"]
    assert len(wrench) >= 20 and all(line["samples"] == 10 for line in wrench)
    assert all(b["first"] > a["last"] for a, b in itertools.pairwise(wrench)), wrench
    states = [line for line in lines if line.get("topic") == "state"]
    assert states and len(states[-1]["joints_rad"]) == 6
    assert states[-1]["status"] == "ROBOT_STATUS_READY"
    assert lines[-1]["summary"]["wrench"]["undecodable"] == 0


def test_the_decision_servers_events_reach_observers(station):
    session = client(f"tcp/{station.ready['zenoh_router']}")
    observer = Observer(session, STATION, ("state", "events"))
    try:
        # The publisher follows the streams once it sees the subscribers: the state shows
        # when they flow.
        wait_for(lambda: observer.counts["state"].messages > 0, timeout_s=10,
                 what="the state flowing")
        with grpc.insecure_channel(station.ready["decision_server"]) as channel:
            door = decision_server_pb2_grpc.DecisionServerStub(channel)
            lease = door.AcquireControl(ds_pb.AcquireControlRequest(
                operator_id="observed", mode=ds_pb.CONTROL_MODE_EXCLUSIVE), timeout=5)
            door.ReleaseControl(ds_pb.ReleaseControlRequest(lease_id=lease.lease_id),
                                timeout=5)
        wait_for(lambda: observer.counts["events"].messages >= 2, timeout_s=10,
                 what="the lock's two changes")
    finally:
        observer.close()
        session.close()


def test_an_observer_gets_the_sessions_status_at_once_and_as_the_lock_changes(station):
    session = client(f"tcp/{station.ready['zenoh_router']}")
    statuses: list[ds_pb.SessionStatus] = []
    observer = Observer(session, STATION, ("status",),
                        on_message=lambda topic, status: statuses.append(status))
    try:
        # The first status comes as the stream opens, with every dependency of the station.
        wait_for(lambda: statuses, timeout_s=10, what="a status")
        assert {d.name: d.state for d in statuses[0].dependencies} == {
            name: ds_pb.DEPENDENCY_STATE_SERVING for name in (
                "proxy_robot", "force_sensor", "stereo_camera", "emergency_stop",
                "zenoh_router")}
        assert not statuses[0].control.holders
        with grpc.insecure_channel(station.ready["decision_server"]) as channel:
            door = decision_server_pb2_grpc.DecisionServerStub(channel)
            lease = door.AcquireControl(ds_pb.AcquireControlRequest(
                operator_id="observed", mode=ds_pb.CONTROL_MODE_EXCLUSIVE), timeout=5)
            held = wait_for(lambda: next((s for s in list(statuses) if s.control.holders),
                                         None), timeout_s=10, what="the holder in a status")
            assert [h.operator_id for h in held.control.holders] == ["observed"]
            assert held.control.mode == ds_pb.CONTROL_MODE_EXCLUSIVE
            seen = len(statuses)
            door.ReleaseControl(ds_pb.ReleaseControlRequest(lease_id=lease.lease_id),
                                timeout=5)
        wait_for(lambda: any(not s.control.holders for s in list(statuses)[seen:]),
                 timeout_s=10, what="the lock free again in a status")
    finally:
        observer.close()
        session.close()


def test_observers_of_another_station_name_get_nothing(station):
    summary = summary_of(observe(station.ready["zenoh_router"], "--station", "elsewhere",
                                 "--seconds", "1", "--json"), nothing=True)
    assert all(count["messages"] == 0 for count in summary.values())


def test_a_killed_router_takes_nothing_else_down_and_observers_come_back(station):
    router = station.ready["zenoh_router"]
    victim = service_pid(station, "zenoh_router")
    publisher = service_pid(station, "observation")
    os.kill(victim, signal.SIGKILL)
    assert health_serving(station.ready["decision_server"])
    assert health_serving(station.ready["force_sensor"])
    wait_for(lambda: service_pid(station, "zenoh_router") not in (None, victim)
             and accepts(router) == OK, timeout_s=10, what="the router restarted on its address")
    assert service_pid(station, "observation") == publisher  # it rejoined by itself
    summary = summary_of(observe(router, "--station", STATION, "--topics", "wrench",
                                 "--seconds", "2", "--json"))
    assert summary["wrench"]["messages"] > 0
    assert station.process.poll() is None
    # The DecisionServer reports the router among its dependencies, restarted once.
    with grpc.insecure_channel(station.ready["decision_server"]) as channel:
        door = decision_server_pb2_grpc.DecisionServerStub(channel)
        back = wait_for(lambda: next(
            (d for d in door.GetDependencies(ds_pb.GetDependenciesRequest(),
                                             timeout=5).dependencies
             if d.name == "zenoh_router" and d.state == ds_pb.DEPENDENCY_STATE_SERVING
             and d.restarts == 1), None), 10, "the router serving, restarted once")
    assert back.reason == ""
