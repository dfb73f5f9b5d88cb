"""The real processes: `make serve`'s launcher, reflection through buf curl, the Node.js client,
bad calls against a real service process, and a clean stop with no orphans."""

from __future__ import annotations

import json
import signal
import subprocess
import urllib.request

import cv2
import grpc
import numpy as np
import pytest
from grpc_health.v1 import health_pb2, health_pb2_grpc

from services.launcher import (
    GRPC_CHILDREN,
    HTTP_CHILDREN,
    STATION,
    WEBSOCKET_CHILDREN,
    ZENOH_CHILDREN,
)
from services.runtime.children import refused_address
from services.runtime.process import metrics_port_name
from tests.conftest import wait_for
from tests.processes import BUF, REPO, child_pids, pid_alive, start_station, station_env

pytestmark = pytest.mark.e2e

SERVICES = ["ProxyRobot", "ForceSensor", "StereoCamera", "DecisionServer"]


def _serving(address: str, service: str = "") -> int:
    with grpc.insecure_channel(address) as channel:
        return health_pb2_grpc.HealthStub(channel).Check(
            health_pb2.HealthCheckRequest(service=service), timeout=5).status


def _buf_curl(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([BUF, "curl", "--protocol", "grpc", "--http2-prior-knowledge", *args],
                          capture_output=True, text=True, timeout=30)


# ProxyRobot on grpcio's sync server (the default) and on grpc.aio (--aio-server).
@pytest.fixture(scope="module", params=["", "1"], ids=["sync", "aio-proxy"])
def station(request):
    launcher = start_station(station_env(TELEROBOT_PROXY_ROBOT_AIO_SERVER=request.param))
    yield launcher, launcher.ready
    if launcher.process.poll() is None:
        launcher.stop(signal.SIGKILL)


def test_every_process_is_serving_where_the_launcher_says(station):
    launcher, addresses = station
    # Every service, and each one's Prometheus port beside it.
    assert sorted(addresses) == sorted([*STATION, *map(metrics_port_name, GRPC_CHILDREN)])
    for name in STATION:
        assert not addresses[name].endswith(":0"), addresses
        if name in WEBSOCKET_CHILDREN:  # the live view: WebSocket only (test_the_live_view_…)
            continue
        if name in ZENOH_CHILDREN:  # Zenoh only (tests/observation/test_station_observation.py)
            continue
        if name in HTTP_CHILDREN:  # the web console: HTTP, its health at /healthz
            with urllib.request.urlopen(f"http://{addresses[name]}/healthz", timeout=5) as r:
                assert r.status == 200, name
            continue
        assert _serving(addresses[name]) == health_pb2.HealthCheckResponse.SERVING, name
    banner = "\n".join(launcher.lines)
    assert f"The operator's address is {addresses['decision_server']}" in banner
    assert f"The live view: ws://{addresses['foxglove']}" in banner
    assert f"python -m clients.observe --router tcp/{addresses['zenoh_router']}" in banner
    # The launcher's check that the live view serves shakes hands as a client would: the live
    # view logs no failed handshake for it.
    assert "handshake failed" not in banner


def test_buf_curl_lists_every_rpc_of_all_four_services_on_the_operator_address(station):
    _, addresses = station
    address = addresses["decision_server"]
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


def _call(address: str, method: str, body: str = "{}") -> dict:
    reply = _buf_curl("-d", body, f"http://{address}/telerobot.v1.ProxyRobot/{method}")
    assert reply.returncode == 0, reply.stdout + reply.stderr
    return json.loads(reply.stdout)


def test_drive_the_arm_by_hand_with_buf_curl(station):
    """The README's session: connect, initialize, move, read, stop, reset."""
    _, addresses = station
    address = addresses["proxy_robot"]
    health = _buf_curl(f"http://{address}/grpc.health.v1.Health/Check")
    assert health.returncode == 0 and json.loads(health.stdout) == {"status": "SERVING"}
    assert _call(address, "Connect") == {"status": "ROBOT_STATUS_CONNECTED"}
    assert _call(address, "Initialize") == {"status": "ROBOT_STATUS_READY"}
    before = _call(address, "GetState")["state"]["toolPose"]["positionM"]
    moved = _call(address, "MoveCartesianIncremental",
                  '{"delta_position_m": {"z": 0.02}, "frame": "REFERENCE_FRAME_BASE"}')
    assert abs(moved["targetToolPose"]["positionM"]["z"] - before["z"] - 0.02) < 1e-4
    turned = _call(address, "MoveJointsIncremental",
                   '{"delta_joint_positions_rad": [0.1, 0, 0, 0, 0, 0]}')
    assert len(turned["targetJointPositionsRad"]) == 6
    assert _call(address, "EmergencyStop", '{"reason": "by hand"}')["status"] == (
        "ROBOT_STATUS_ESTOPPED")
    refused = _buf_curl("-d", '{"delta_joint_positions_rad": [0.1, 0, 0, 0, 0, 0]}',
                        f"http://{address}/telerobot.v1.ProxyRobot/MoveJointsIncremental")
    assert refused.returncode != 0 and "failed_precondition" in refused.stdout + refused.stderr
    assert _call(address, "Reset") == {"status": "ROBOT_STATUS_READY"}
    # The same stop through the emergency-stop band, as the README shows it.
    band = addresses["emergency_stop"]
    assert _call(band, "EmergencyStop", '{"reason": "by hand"}')["status"] == (
        "ROBOT_STATUS_ESTOPPED")
    wait_for(lambda: _call(address, "GetStatus")["status"] == "ROBOT_STATUS_ESTOPPED",
             timeout_s=5, what="ProxyRobot to see the band's latch")
    assert _call(address, "Reset") == {"status": "ROBOT_STATUS_READY"}


def test_the_operator_address_forwards_with_the_lock_in_front(station):
    """On the DecisionServer, reads are free and commands need a lease in the metadata."""
    _, addresses = station
    address = addresses["decision_server"]
    state = _call(address, "GetState")["state"]
    assert len(state["jointPositionsRad"]) == 6
    refused = _buf_curl("-d", '{"delta_joint_positions_rad": [0.05, 0, 0, 0, 0, 0]}',
                        f"http://{address}/telerobot.v1.ProxyRobot/MoveJointsIncremental")
    assert refused.returncode != 0 and "control lock" in refused.stdout + refused.stderr
    granted = _buf_curl("-d", '{"operator_id": "hand", "mode": "CONTROL_MODE_EXCLUSIVE"}',
                        f"http://{address}/telerobot.v1.DecisionServer/AcquireControl")
    assert granted.returncode == 0, granted.stderr
    lease = json.loads(granted.stdout)["leaseId"]
    moved = _buf_curl("-H", f"telerobot-lease-id: {lease}",
                      "-d", '{"delta_joint_positions_rad": [0.05, 0, 0, 0, 0, 0]}',
                      f"http://{address}/telerobot.v1.ProxyRobot/MoveJointsIncremental")
    assert moved.returncode == 0, moved.stdout + moved.stderr
    released = _buf_curl("-d", json.dumps({"lease_id": lease}),
                         f"http://{address}/telerobot.v1.DecisionServer/ReleaseControl")
    assert released.returncode == 0


def test_unknown_method_and_malformed_message_on_a_real_process(station):
    _, addresses = station
    address = addresses["decision_server"]
    with grpc.insecure_channel(address) as channel:
        with pytest.raises(grpc.RpcError) as unknown:
            channel.unary_unary("/telerobot.v1.DecisionServer/Fly")(b"", timeout=5)
        assert unknown.value.code() is grpc.StatusCode.UNIMPLEMENTED
        with pytest.raises(grpc.RpcError) as malformed:
            channel.unary_unary("/telerobot.v1.ProxyRobot/MoveCartesianIncremental")(
                b"\x1a\x05\x0a", timeout=5)
        assert malformed.value.code() is grpc.StatusCode.INVALID_ARGUMENT
    assert _serving(address) == health_pb2.HealthCheckResponse.SERVING


def _node_client(address: str) -> dict:
    result = subprocess.run(["node", "clients/node/client.js", address], cwd=REPO,
                            capture_output=True, text=True, timeout=30)
    assert result.returncode == 0, result.stdout + result.stderr
    return json.loads(result.stdout)


def test_node_client_built_from_the_protos_reads_the_robot(station):
    _, addresses = station
    address = addresses["proxy_robot"]
    _call(address, "Connect")  # a no-op if the by-hand test already connected
    report = _node_client(address)
    assert report["health"] == {"(server)": "SERVING", "telerobot.v1.ProxyRobot": "SERVING"}
    assert report["status"]["ok"] and report["status"]["reply"]["status"] in (
        "ROBOT_STATUS_CONNECTED", "ROBOT_STATUS_READY", "ROBOT_STATUS_MOVING")
    arm = report["arm"]["reply"]
    assert arm["name"] == "puma560" and len(arm["joint_names"]) == 6
    state = report["state"]["reply"]["state"]
    assert len(state["joint_positions_rad"]) == len(arm["joint_names"])
    assert len(state["tool_pose"]["rotation"]["row_major"]) == 9


def test_node_client_on_the_operator_address(station):
    _, addresses = station
    report = _node_client(addresses["decision_server"])
    assert report["health"] == {"(server)": "SERVING", "telerobot.v1.ProxyRobot": "SERVING"}
    assert len(report["state"]["reply"]["state"]["joint_positions_rad"]) == 6


def test_node_client_reports_an_unreachable_server():
    result = subprocess.run(["node", "clients/node/client.js", refused_address()],
                            cwd=REPO, capture_output=True, text=True, timeout=30)
    assert result.returncode == 1 and "cannot reach" in result.stdout


def test_the_live_view_streams_the_arm_force_and_cameras_to_a_foxglove_client(station):
    """#17's done-when: a WebSocket client connects to the live server and sees the channels
    advertised and data flowing; the frames are Pinocchio's, the images decode."""
    from foxglove_schemas_protobuf.CompressedImage_pb2 import CompressedImage
    from foxglove_schemas_protobuf.FrameTransforms_pb2 import FrameTransforms
    from foxglove_schemas_protobuf.SceneUpdate_pb2 import SceneUpdate

    from domain.robot_model.kinematics import ArmKinematics
    from services.foxglove.live import LIVE_TOPICS
    from telerobot.v1 import force_sensor_pb2, force_sensor_pb2_grpc, types_pb2
    from tests.foxglove.test_channels import world_poses
    from tests.foxglove.ws_client import FoxgloveClient
    from wire import foxglove as fx

    _, addresses = station
    # The arm's state streams once it is connected; the force, once the sensor reads.
    _call(addresses["proxy_robot"], "Connect")
    with grpc.insecure_channel(addresses["force_sensor"]) as channel:
        force_sensor_pb2_grpc.ForceSensorStub(channel).StartReading(
            force_sensor_pb2.StartReadingRequest(), timeout=10)
    with FoxgloveClient(f"ws://{addresses['foxglove']}") as client:
        client.wait_advertised(LIVE_TOPICS)
        client.subscribe(LIVE_TOPICS)
        # Two of each, so the stream is flowing, not one message that was waiting.
        client.collect(lambda got: all(len(got[t]) >= 2 for t in LIVE_TOPICS), timeout_s=30)
    for topic, messages in client.received.items():
        stamps = [stamp for stamp, _ in messages]
        assert stamps == sorted(stamps), topic
    kinematics = ArmKinematics()
    states = {stamp: types_pb2.RobotState.FromString(data)
              for stamp, data in client.received[fx.ROBOT_STATE]}
    matched = 0
    for stamp, data in client.received[fx.TF]:
        if stamp not in states:
            continue  # a sample whose /robot/state came before the subscription
        q = np.array(states[stamp].joint_positions_rad)
        poses = world_poses(FrameTransforms.FromString(data))
        assert np.allclose(poses[fx.TOOL_FRAME].homogeneous,
                           kinematics.tool_pose(q).homogeneous, atol=1e-6)
        assert {fx.LEFT_CAMERA_FRAME, fx.RIGHT_CAMERA_FRAME} <= set(poses)
        matched += 1
    assert matched >= 1
    image = CompressedImage.FromString(client.received[fx.RIGHT_IMAGE][-1][1])
    decoded = cv2.imdecode(np.frombuffer(image.data, np.uint8), cv2.IMREAD_COLOR)
    assert decoded is not None and decoded.ndim == 3 and decoded.std() > 0
    arrow = SceneUpdate.FromString(client.received[fx.FORCE_ARROW][-1][1])
    assert arrow.entities[0].frame_id == fx.TOOL_FRAME


def test_sigint_stops_the_whole_group_within_5_s_with_no_orphans(station):
    launcher, _ = station
    children = child_pids(launcher.process.pid)
    assert len(children) == len(STATION)
    launcher.process.send_signal(signal.SIGINT)
    assert launcher.wait(timeout_s=5.0) == 0  # TimeoutExpired if it takes longer
    assert not [pid for pid in children if pid_alive(pid)]


def test_children_stop_by_themselves_when_the_launcher_is_killed():
    launcher = start_station(station_env())
    children = child_pids(launcher.process.pid)
    launcher.stop(signal.SIGKILL)
    wait_for(lambda: not any(pid_alive(pid) for pid in children), timeout_s=5,
             what="every child to notice and stop")
