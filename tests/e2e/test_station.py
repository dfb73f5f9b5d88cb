"""The real processes: `make serve`'s launcher, reflection through buf curl, the Node.js client,
bad calls against a real service process, and a clean stop with no orphans."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import time

import grpc
import pytest
from grpc_health.v1 import health_pb2, health_pb2_grpc

from tests.conftest import BUF, REPO, free_port, start_process

pytestmark = pytest.mark.e2e

STATION = ["proxy_robot", "force_sensor", "stereo_camera", "decision_server"]
SERVICES = ["ProxyRobot", "ForceSensor", "StereoCamera", "DecisionServer"]


def _station_env() -> dict[str, str]:
    return {f"TELEROBOT_{name.upper()}_ADDRESS": f"127.0.0.1:{free_port()}" for name in STATION}


def _pid_alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    # A zombie still answers kill(0); it is gone for our purposes once its parent reaped it.
    with open(f"/proc/{pid}/stat") as stat:
        return stat.read().split()[2] != "Z"


def _child_pids(pid: int) -> list[int]:
    out = subprocess.run(["pgrep", "-P", str(pid)], capture_output=True, text=True).stdout
    return [int(p) for p in out.split()]


def _serving(address: str, service: str = "") -> int:
    with grpc.insecure_channel(address) as channel:
        return health_pb2_grpc.HealthStub(channel).Check(
            health_pb2.HealthCheckRequest(service=service), timeout=5).status


def _buf_curl(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([BUF, "curl", "--protocol", "grpc", "--http2-prior-knowledge", *args],
                          capture_output=True, text=True, timeout=30)


@pytest.fixture(scope="module")
def station():
    env = _station_env()
    launcher = start_process(["-m", "services.launcher", "--grace-s", "1"], env=env)
    deadline = time.monotonic() + 90
    while not any("Slave station is up" in line for line in launcher.lines):
        if launcher.process.poll() is not None or time.monotonic() > deadline:
            pytest.fail("launcher did not come up:\n" + "\n".join(launcher.lines[-40:]))
        time.sleep(0.05)
    yield launcher, env
    if launcher.process.poll() is None:
        launcher.stop(signal.SIGKILL)


def test_every_process_is_serving(station):
    _, env = station
    for name in STATION:
        address = env[f"TELEROBOT_{name.upper()}_ADDRESS"]
        assert _serving(address) == health_pb2.HealthCheckResponse.SERVING, name


def test_buf_curl_lists_every_rpc_of_all_four_services_on_the_operator_address(station):
    _, env = station
    address = env["TELEROBOT_DECISION_SERVER_ADDRESS"]
    listing = _buf_curl("--list-methods", f"http://{address}")
    assert listing.returncode == 0, listing.stderr
    listed = set(listing.stdout.split())
    from google.protobuf import descriptor_pool

    import telerobot.v1.decision_server_pb2  # noqa: F401
    import telerobot.v1.force_sensor_pb2  # noqa: F401
    import telerobot.v1.stereo_camera_pb2  # noqa: F401

    for service in SERVICES:
        methods = descriptor_pool.Default().FindServiceByName(f"telerobot.v1.{service}").methods
        for method in methods:
            assert f"telerobot.v1.{service}/{method.name}" in listed


def test_buf_curl_calls_through_reflection(station):
    _, env = station
    address = env["TELEROBOT_PROXY_ROBOT_ADDRESS"]
    reply = _buf_curl(f"http://{address}/grpc.health.v1.Health/Check")
    assert reply.returncode == 0 and json.loads(reply.stdout) == {"status": "SERVING"}
    unbuilt = _buf_curl("-d", "{}", f"http://{address}/telerobot.v1.ProxyRobot/GetState")
    assert unbuilt.returncode != 0 and '"code": "unimplemented"' in unbuilt.stdout + unbuilt.stderr


def test_unknown_method_and_malformed_message_on_a_real_process(station):
    _, env = station
    address = env["TELEROBOT_DECISION_SERVER_ADDRESS"]
    with grpc.insecure_channel(address) as channel:
        with pytest.raises(grpc.RpcError) as unknown:
            channel.unary_unary("/telerobot.v1.DecisionServer/Fly")(b"", timeout=5)
        assert unknown.value.code() is grpc.StatusCode.UNIMPLEMENTED
        with pytest.raises(grpc.RpcError) as malformed:
            channel.unary_unary("/telerobot.v1.ProxyRobot/MoveCartesianIncremental")(
                b"\x1a\x05\x0a", timeout=5)
        assert malformed.value.code() is grpc.StatusCode.INVALID_ARGUMENT
    assert _serving(address) == health_pb2.HealthCheckResponse.SERVING


def test_node_client_built_from_the_protos(station):
    _, env = station
    address = env["TELEROBOT_DECISION_SERVER_ADDRESS"]
    result = subprocess.run(["node", "clients/node/client.js", address], cwd=REPO,
                            capture_output=True, text=True, timeout=30)
    assert result.returncode == 0, result.stdout + result.stderr
    report = json.loads(result.stdout)
    assert report["health"] == {"(server)": "SERVING", "telerobot.v1.ProxyRobot": "SERVING"}
    # The robot's state is built by the slave-station issue; until then the server must say so.
    for call in ("status", "state"):
        assert report[call]["ok"] or report[call]["code"] == "UNIMPLEMENTED"


def test_node_client_reports_an_unreachable_server():
    result = subprocess.run(["node", "clients/node/client.js", f"127.0.0.1:{free_port()}"],
                            cwd=REPO, capture_output=True, text=True, timeout=30)
    assert result.returncode == 1 and "cannot reach" in result.stdout


def test_sigint_stops_the_whole_group_within_5_s_with_no_orphans(station):
    launcher, _ = station
    children = _child_pids(launcher.process.pid)
    assert len(children) == len(STATION)
    started = time.monotonic()
    code = launcher.stop(signal.SIGINT, timeout_s=5)
    elapsed = time.monotonic() - started
    assert code == 0 and elapsed < 5.0
    assert not [pid for pid in children if _pid_alive(pid)]


def test_a_dying_child_stops_the_station_and_is_named():
    launcher = start_process(["-m", "services.launcher", "--grace-s", "1"], env=_station_env())
    deadline = time.monotonic() + 90
    while not any("Slave station is up" in line for line in launcher.lines):
        assert launcher.process.poll() is None and time.monotonic() < deadline
        time.sleep(0.05)
    children = _child_pids(launcher.process.pid)
    victim = next(pid for pid in children
                  if "services.force_sensor" in open(f"/proc/{pid}/cmdline").read())
    os.kill(victim, signal.SIGKILL)
    assert launcher.process.wait(10) == 1
    output = "\n".join(launcher.lines)
    assert "force_sensor" in output and "was killed by signal 9" in output
    time.sleep(0.2)
    assert not [pid for pid in children if _pid_alive(pid)]


def test_children_stop_by_themselves_when_the_launcher_is_killed():
    launcher = start_process(["-m", "services.launcher", "--grace-s", "1"], env=_station_env())
    deadline = time.monotonic() + 90
    while not any("Slave station is up" in line for line in launcher.lines):
        assert launcher.process.poll() is None and time.monotonic() < deadline
        time.sleep(0.05)
    children = _child_pids(launcher.process.pid)
    launcher.stop(signal.SIGKILL)
    deadline = time.monotonic() + 5
    while any(_pid_alive(pid) for pid in children) and time.monotonic() < deadline:
        time.sleep(0.05)
    assert not [pid for pid in children if _pid_alive(pid)]
