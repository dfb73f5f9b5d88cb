"""A whole station through the launcher (the web console included) and headless Chromium from
Debian's `chromium` package, driven by Playwright (its own browser download cannot reach its
servers here; `make test` installs the package when it is missing)."""

from __future__ import annotations

import os
import signal
from pathlib import Path

import grpc
import pytest

from telerobot.v1 import decision_server_pb2_grpc, proxy_robot_pb2, proxy_robot_pb2_grpc
from tests.processes import start_station, station_env
from tests.video.conftest import video_station  # noqa: F401 (a fixture: a pattern camera's station)

CHROMIUM = "/usr/bin/chromium"
CHROMIUM_ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
                 "--no-first-run", "--disable-background-networking",
                 "--disable-component-update", "--disable-sync"]
# The stations' sim camera renders 5 pairs a second: at its own rate (a 640x480 pair takes
# 45-85 ms) it takes a whole core of a 2-core machine while a page is open, and these tests
# need the video shown, not fast (`make bench ONLY=video` measures that).
CAMERA_SETTINGS = {"TELEROBOT_STEREO_CAMERA_FPS": "5"}
# Screenshots go here when set (docs/ for the README's), else to the test's tmp_path.
SHOTS_ENV = "TELEROBOT_WEB_CONSOLE_SHOTS"


@pytest.hookimpl(wrapper=True)
def pytest_runtest_makereport(item, call):
    """A failed browser test shows the station's last log lines: what the station saw (a
    refusal, a lost link, a restart) is what the page's text rarely says."""
    report = yield
    if report.when == "call" and report.failed:
        for name in ("console_station", "https_station"):
            station = item.funcargs.get(name)
            launcher = station[0] if isinstance(station, tuple) else station
            if launcher is not None:
                report.sections.append((f"{name}'s last lines", launcher.describe(200)))
    return report


_console_stations = []  # the running console_station, for its last user to stop


@pytest.fixture(scope="session")
def console_station(tmp_path_factory):
    """The station, started by the launcher like `make serve`; `.ready` has every address.
    Its recordings go to a directory of its own. It stops after the last test that uses it."""
    recordings = tmp_path_factory.mktemp("recordings")
    launcher = start_station(station_env(TELEROBOT_RECORDINGS_DIR=str(recordings),
                                         **CAMERA_SETTINGS))
    _console_stations.append(launcher)
    yield launcher
    _console_stations.remove(launcher)
    launcher.stop(signal.SIGINT)


@pytest.hookimpl(trylast=True)
def pytest_runtest_teardown(item, nextitem):
    """Stop the shared station once no later test uses it, not at the session's end: an idle
    station's world steps at 1 kHz (a third of a core) under every test after it."""
    if not _console_stations:
        return
    items = item.session.items
    later = items[items.index(item) + 1:]
    if not any("console_station" in other.fixturenames for other in later):
        for launcher in _console_stations:
            launcher.stop(signal.SIGINT)


@pytest.fixture(scope="session")
def console_url(console_station) -> str:
    return f"http://{console_station.ready['web_console']}"


@pytest.fixture(scope="session")
def playwright_driver():
    if not Path(CHROMIUM).exists():
        pytest.fail(f"{CHROMIUM} is missing: `make test` installs Debian's chromium package "
                    "(apt-get install -y chromium)")
    from playwright.sync_api import sync_playwright

    with sync_playwright() as driver:
        yield driver


@pytest.fixture
def browser(playwright_driver, tmp_path):
    """A fresh Chromium (its own user-data-dir), closed after the test."""
    context = playwright_driver.chromium.launch_persistent_context(
        str(tmp_path / "profile"), executable_path=CHROMIUM, args=CHROMIUM_ARGS, headless=True,
        viewport={"width": 1400, "height": 1000})
    yield context
    context.close()


@pytest.fixture
def shots(tmp_path) -> Path:
    directory = Path(os.environ.get(SHOTS_ENV) or tmp_path)
    directory.mkdir(parents=True, exist_ok=True)
    return directory


@pytest.fixture
def robot(console_station):
    """ProxyRobot on its own port: the arm as the station knows it, past the console."""
    with grpc.insecure_channel(console_station.ready["proxy_robot"]) as channel:
        yield proxy_robot_pb2_grpc.ProxyRobotStub(channel)


@pytest.fixture
def decision(console_station):
    with grpc.insecure_channel(console_station.ready["decision_server"]) as channel:
        yield decision_server_pb2_grpc.DecisionServerStub(channel)


def arm_state(robot) -> proxy_robot_pb2.GetStateResponse:
    return robot.GetState(proxy_robot_pb2.GetStateRequest(), timeout=5).state
