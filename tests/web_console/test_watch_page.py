"""A watch-only console (`python -m services.web_console --router …`) in a real browser, reading
the whole station's observation through the station's own Zenoh router."""

from __future__ import annotations

import grpc
import pytest

from telerobot.v1 import decision_server_pb2 as ds_pb
from telerobot.v1 import force_sensor_pb2, force_sensor_pb2_grpc, proxy_robot_pb2
from tests.conftest import wait_for
from tests.processes import start_service
from tests.web_console.test_browser import DEADLINE_S, open_console, status_of, text

pytestmark = [pytest.mark.e2e, pytest.mark.slow]

# What a watch-only page does not show: everything that commands the station.
CONTROLS = ("#estop", "#arm-connect", "#lock-acquire", "#drive-panel", "#assist-scaling",
            "#record-panel")


@pytest.fixture
def watcher(console_station):
    """The watch-only console, through the station's router: its address."""
    console = start_service("web_console", "--router",
                            f"tcp/{console_station.ready['zenoh_router']}")
    yield console.address
    console.stop()


def test_a_watch_only_page_follows_the_station_through_its_router(
        browser, console_station, watcher, robot, decision, shots):
    page = open_console(browser, f"http://{watcher}")
    wait_for(lambda: "station 'station' through the router" in text(page, "#watching"),
             timeout_s=DEADLINE_S, what="the page saying what it watches")
    assert not any(page.locator(control).is_visible() for control in CONTROLS)
    # The arm's state, as ProxyRobot reports it (a connected arm's: a station that has no arm
    # yet publishes none).
    if status_of(robot) == "ROBOT_STATUS_NOT_CONNECTED":
        robot.Connect(proxy_robot_pb2.ConnectRequest(), timeout=30)
    wait_for(lambda: text(page, "#joints") != "–", timeout_s=DEADLINE_S, what="the joints")
    wait_for(lambda: f"ROBOT_STATUS_{text(page, '#status')}" == status_of(robot),
             timeout_s=DEADLINE_S, what="the arm's status")
    # The wrench (a sensor that reads), and the stereo video from a key frame on.
    with grpc.insecure_channel(console_station.ready["force_sensor"]) as channel:
        force_sensor_pb2_grpc.ForceSensorStub(channel).StartReading(
            force_sensor_pb2.StartReadingRequest(), timeout=10)
    wait_for(lambda: text(page, "#force-now").endswith(" N"), timeout_s=DEADLINE_S,
             what="a force sample")
    stats = page.locator("#video-stats")
    wait_for(lambda: int(stats.get_attribute("data-frames") or 0) >= 3, timeout_s=DEADLINE_S,
             what=lambda: f"three frames shown; page says {text(page, '#video-info')!r}")
    assert stats.get_attribute("data-decoder") == "webcodecs"
    assert stats.get_attribute("data-decode-errors") == "0"
    # The lock, taken at the station's door, shows up here.
    lease = decision.AcquireControl(ds_pb.AcquireControlRequest(
        operator_id="watched", mode=ds_pb.CONTROL_MODE_EXCLUSIVE, wait=True), timeout=30)
    try:
        wait_for(lambda: text(page, "#lock-holders") == "watched", timeout_s=DEADLINE_S,
                 what="the holder shown")
        page.screenshot(path=str(shots / "web_console_watching.png"))
    finally:
        decision.ReleaseControl(ds_pb.ReleaseControlRequest(lease_id=lease.lease_id), timeout=5)
    wait_for(lambda: text(page, "#lock-holders") == "none", timeout_s=DEADLINE_S,
             what="the lock free again")
    assert page.errors == []
