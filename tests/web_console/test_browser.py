"""The web console in a real browser against a real station: video, the lock, driving with
the keyboard, the stop button, and a tab closed mid-drive."""

from __future__ import annotations

import contextlib
import os
import signal
import threading
import uuid
from pathlib import Path

import grpc
import pytest

from telerobot.v1 import decision_server_pb2, proxy_robot_pb2, types_pb2
from tests.conftest import wait_for
from tests.processes import scrape_metrics
from tests.web_console.conftest import CHROMIUM, CHROMIUM_ARGS, arm_state

pytestmark = [pytest.mark.e2e, pytest.mark.slow]

STATUS = types_pb2.RobotStatus
# Deadlines for what goes through a browser and the station on a shared 2-core machine (the
# tests pass in seconds; a loaded machine, load average near 30, took several times that).
DEADLINE_S = 30.0


def status_of(robot) -> str:
    """The arm's status as ProxyRobot reports it (GetStatus answers before Connect too)."""
    return STATUS.Name(robot.GetStatus(proxy_robot_pb2.GetStatusRequest(), timeout=5).status)


def open_console(browser, url):
    page = browser.new_page()
    errors: list[str] = []
    page.on("pageerror", lambda error: errors.append(str(error)))
    page.goto(url)
    page.errors = errors
    return page


def text(page, selector: str) -> str:
    return page.locator(selector).text_content() or ""


def take_lock(page) -> None:
    """Queue for the lock (a lease an earlier test left lapses within 5 s) until held."""
    page.click("#lock-queue")
    wait_for(lambda: page.locator("#lock-state").get_attribute("data-held") == "yes",
             timeout_s=DEADLINE_S, what=f"the lock; page says {text(page, '#message')!r}")


def ready_arm(page, robot) -> None:
    """Connect, initialize or reset through the page's buttons until the arm is READY."""
    def step():
        status = status_of(robot)
        if status == "ROBOT_STATUS_READY":
            return True
        button = {"ROBOT_STATUS_NOT_CONNECTED": "#arm-connect",
                  "ROBOT_STATUS_CONNECTED": "#arm-initialize",
                  "ROBOT_STATUS_ESTOPPED": "#arm-reset"}.get(status)
        if button:
            page.click(button)
            wait_for(lambda: status_of(robot) != status, timeout_s=DEADLINE_S,
                     what=f"{button} to change {status}; page says {text(page, '#message')!r}")
        return False
    wait_for(step, timeout_s=60, what="a READY arm")


def start_driving(page) -> None:
    page.click("#drive-toggle")
    wait_for(lambda: text(page, "#drive-state") == "driving", timeout_s=DEADLINE_S,
             what=f"the Teleoperate session; page says {text(page, '#message')!r}")


def tool_z(robot) -> float:
    return arm_state(robot).tool_pose.position_m.z


def test_the_page_shows_live_stereo_video(browser, console_url, robot, shots):
    page = open_console(browser, console_url)
    eyes = [page.locator("#left-eye"), page.locator("#right-eye")]
    first = wait_for(lambda: int(eyes[0].get_attribute("data-sequence")) or None,
                     timeout_s=30, what="a first stereo pair drawn")
    # A later pair replaces it, in both eyes: the sequence moves on and the pixels are there.
    wait_for(lambda: all(int(eye.get_attribute("data-sequence")) > first for eye in eyes),
             timeout_s=DEADLINE_S, what="a newer stereo pair")
    pixels = page.evaluate("""() => [...document.querySelectorAll('.eyes canvas')].map(c =>
        c.getContext('2d').getImageData(0, 0, c.width, c.height).data.some(v => v > 0))""")
    assert pixels == [True, True]
    # The figures, shown (twice a second): the age's median, the rate, the decoder.
    age = wait_for(lambda: text(page, "#video-age").replace("–", ""), timeout_s=DEADLINE_S,
                   what="the video's age shown")
    assert float(age) >= 0
    assert page.locator("#video-stats").get_attribute("data-decoder") == "webcodecs"
    assert page.locator("#estop").is_visible()
    assert page.errors == []
    page.screenshot(path=str(shots / "web_console_video.png"))


def open_streams(metrics_address: str) -> int:
    """The streams open on a service, from its Prometheus metrics."""
    return int(scrape_metrics(metrics_address)[("telerobot_open_streams", frozenset())])


def test_a_closed_tab_leaves_no_stream_open(browser, console_station, console_url):
    """The page's streams (state, wrench, events, video) end at the station when its tab
    closes, quiet ones too: nothing renders, encodes or forwards for a tab that is gone."""
    services = ("decision_server", "stereo_camera")
    metrics = {name: console_station.ready[f"{name}_metrics"] for name in services}
    before = {name: open_streams(address) for name, address in metrics.items()}
    page = open_console(browser, console_url)
    wait_for(lambda: int(page.locator("#left-eye").get_attribute("data-sequence")) or None,
             timeout_s=30, what="a first stereo pair drawn")
    assert open_streams(metrics["decision_server"]) > before["decision_server"]
    page.close()
    wait_for(lambda: all(open_streams(metrics[name]) <= before[name] for name in services),
             timeout_s=DEADLINE_S, what=lambda: f"the streams open before the tab, {before}; "
             f"open: { {name: open_streams(address) for name, address in metrics.items()} }")


def test_take_the_lock_drive_with_keys_and_stop(browser, console_url, robot, decision, shots):
    page = open_console(browser, console_url)
    wait_for(lambda: text(page, "#arm-name") == "puma560 · 6 joints", timeout_s=DEADLINE_S,
             what="the page to say which arm the station drives")
    take_lock(page)
    holders = decision.GetControlState(decision_server_pb2.GetControlStateRequest(),
                                       timeout=5).state.holders
    assert [h.operator_id for h in holders] == ["browser"]
    ready_arm(page, robot)
    page.click("#sensor-start")
    start_driving(page)
    start = arm_state(robot).tool_pose.position_m

    page.keyboard.down("r")  # +Z, base frame, held until the arm has gone 10 mm up
    wait_for(lambda: tool_z(robot) > start.z + 0.010, timeout_s=DEADLINE_S,
             what=f"the arm to rise; page says {text(page, '#message')!r}, "
                  f"outcome {text(page, '#outcome')!r}")
    page.keyboard.up("r")
    moved = arm_state(robot).tool_pose.position_m
    assert abs(moved.x - start.x) < 0.002 and abs(moved.y - start.y) < 0.002
    assert int(text(page, "#acked")) > 0
    assert float(text(page, "#rtt")) > 0  # the command round trip, shown
    page.keyboard.down("s")  # -X while the stop comes
    wait_for(lambda: int(text(page, "#sent")) > 0, timeout_s=DEADLINE_S, what="commands")
    page.screenshot(path=str(shots / "web_console_driving.png"))

    page.click("#estop")
    wait_for(lambda: status_of(robot) == "ROBOT_STATUS_ESTOPPED", timeout_s=DEADLINE_S,
             what="ESTOPPED after the page's STOP")
    page.keyboard.up("s")
    wait_for(lambda: page.locator("#status").get_attribute("data-status") == "ESTOPPED",
             timeout_s=DEADLINE_S, what="the page to show ESTOPPED")
    page.screenshot(path=str(shots / "web_console_estopped.png"))
    ready_arm(page, robot)  # Reset through the page (with the lock)
    page.click("#lock-release")
    wait_for(lambda: not decision.GetControlState(
        decision_server_pb2.GetControlStateRequest(), timeout=5).state.holders,
        timeout_s=DEADLINE_S, what="the lock released")
    assert page.errors == []


def test_closing_the_tab_mid_drive_holds_the_arm(browser, console_url, robot, decision):
    page = open_console(browser, console_url)
    take_lock(page)
    ready_arm(page, robot)
    start_driving(page)
    watch = HoldWatch(decision)  # (from before the drive: see the lost link's test)
    try:
        drive_down(page, robot)  # F (-Z) stays down while the tab closes
        assert status_of(robot) in ("ROBOT_STATUS_MOVING", "ROBOT_STATUS_READY")
        page.close()
        ended = watch.wait_for_session_end("the tab closed")
        watch.wait_for_hold("the tab closed")
    finally:
        watch.close()
    # The session ended with the tab (its end message, or its socket closing), not by silence.
    assert "timeout" not in ended.reason, ended.reason
    assert_held(robot)  # at rest and staying there, without a latch


def test_assistance_and_record_replay_from_the_page(browser, console_url, robot, decision):
    page = open_console(browser, console_url)
    take_lock(page)
    ready_arm(page, robot)

    def assistance():
        return decision.GetAssistance(decision_server_pb2.GetAssistanceRequest(),
                                      timeout=5).assistance

    page.check("#assist-scaling")
    wait_for(lambda: assistance().scaling.translation_scale == 0.5, timeout_s=DEADLINE_S,
             what=f"scaling set; page says {text(page, '#message')!r}")
    page.uncheck("#assist-scaling")
    wait_for(lambda: assistance().scaling.translation_scale in (0.0, 1.0), timeout_s=DEADLINE_S,
             what="scaling off")

    name = f"browser-test-{uuid.uuid4().hex[:8]}"  # recordings outlive stations
    page.fill("#rec-name", name)
    page.fill("#rec-task", "raise the tool")  # a demonstration episode (MCAP)
    page.click("#rec-start")
    wait_for(lambda: text(page, "#message") == "record: done", timeout_s=DEADLINE_S,
             what=f"recording; page says {text(page, '#message')!r}")
    start_driving(page)
    start = tool_z(robot)
    page.keyboard.down("r")
    wait_for(lambda: tool_z(robot) > start + 0.005, timeout_s=DEADLINE_S, what="the arm to rise")
    page.keyboard.up("r")
    page.click("#drive-toggle")  # end the session; then the recording
    page.select_option("#rec-outcome", "2")  # failed
    page.click("#rec-stop")
    wait_for(lambda: page.locator(f"#rec-list option[value='{name}']").count() == 1,
             timeout_s=DEADLINE_S,
             what=f"the recording listed; page says {text(page, '#message')!r}")
    episode = next(r for r in decision.ListRecordings(
        decision_server_pb2.ListRecordingsRequest(), timeout=5).recordings if r.name == name)
    assert episode.task == "raise the tool"
    assert episode.format == decision_server_pb2.RECORDING_FORMAT_MCAP
    assert episode.outcome == decision_server_pb2.EPISODE_OUTCOME_FAILED
    page.select_option("#rec-list", name)
    before = tool_z(robot)
    page.click("#replay-start")
    wait_for(lambda: "FINISHED" in text(page, "#replay-state"), timeout_s=30,
             what=f"the replay to finish; page says {text(page, '#message')!r}, "
                  f"{text(page, '#replay-state')!r}, events {text(page, '#events')[:600]!r}")
    assert tool_z(robot) > before + 0.004  # the recorded rise, once more
    page.click("#lock-release")
    assert page.errors == []


class HoldWatch:
    """The DecisionServer's watchdog holds and Teleoperate session changes, from now on.

    When an operator's link goes, two things hold the arm: the gateway ending the stream, and
    the session's watchdog when no command comes. Which is first depends on the machine's load,
    so a test reads why the session ended from its DETACHED or CLOSED event, which says so
    whichever held first."""

    def __init__(self, decision):
        self.holds: list[decision_server_pb2.WatchdogHoldEvent] = []
        self.session_ends: list[decision_server_pb2.TeleopSessionEvent] = []
        # With the arm's state samples, whose first one says the subscription is in place:
        # an event published before that would be missed.
        self._events = decision.StreamEvents(
            decision_server_pb2.StreamEventsRequest(include_data_received=True))
        self._subscribed = threading.Event()
        threading.Thread(target=self._follow, daemon=True).start()
        wait_for(self._subscribed.is_set, timeout_s=DEADLINE_S, what="StreamEvents subscribed")

    def _follow(self):
        ends = (decision_server_pb2.TELEOP_SESSION_STATE_DETACHED,
                decision_server_pb2.TELEOP_SESSION_STATE_CLOSED)
        try:
            for event in self._events:
                self._subscribed.set()
                if event.HasField("watchdog_hold"):
                    self.holds.append(event.watchdog_hold)
                elif event.HasField("teleop_session") and event.teleop_session.state in ends:
                    self.session_ends.append(event.teleop_session)
        except grpc.RpcError:
            pass  # cancelled by close()

    def wait_for_hold(self, after: str, because: str = "") -> decision_server_pb2.WatchdogHoldEvent:
        """The first hold whose reason says `because`. (A loaded station may hold the arm for
        other reasons first: a backlog of commands, a late wrench.)"""
        return wait_for(lambda: next((h for h in self.holds if because in h.reason), None),
                        timeout_s=DEADLINE_S, what=f"a watchdog_hold {because!r} after {after}")

    def wait_for_session_end(self, after: str) -> decision_server_pb2.TeleopSessionEvent:
        return wait_for(lambda: self.session_ends[0] if self.session_ends else None,
                        timeout_s=DEADLINE_S, what=f"the session to end after {after}")

    def close(self):
        self._events.cancel()


def drive_down(page, robot):
    """Hold F (-Z) until the arm is seen moving down; the key stays down."""
    start = tool_z(robot)
    page.keyboard.down("f")
    wait_for(lambda: tool_z(robot) < start - 0.003, timeout_s=DEADLINE_S,
             what="the arm moving down")


def assert_held(robot):
    wait_for(lambda: max(abs(v) for v in arm_state(robot).joint_velocities_rad_per_s) < 1e-3,
             timeout_s=DEADLINE_S, what="the arm at rest")
    rest = arm_state(robot)
    later = wait_for(lambda: (s := arm_state(robot)).sequence > rest.sequence + 20 and s,
                     timeout_s=DEADLINE_S, what="20 more state samples")
    assert abs(later.tool_pose.position_m.z - rest.tool_pose.position_m.z) < 1e-4
    assert status_of(robot) == "ROBOT_STATUS_READY"  # a hold, not an e-stop


def browser_pids(profile: Path) -> list[int]:
    """The Chromium processes this test started: the ones running on its own profile."""
    pids = []
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                cmdline = (entry / "cmdline").read_bytes().split(b"\0")
            except OSError:
                continue
            if cmdline and b"chromium" in cmdline[0] and \
                    f"--user-data-dir={profile}".encode() in cmdline:
                pids.append(int(entry.name))
    return pids


def test_a_frozen_tab_trips_the_watchdog(browser, console_url, robot, decision):
    page = open_console(browser, console_url)
    take_lock(page)
    ready_arm(page, robot)
    start_driving(page)
    drive_down(page, robot)
    watch = HoldWatch(decision)
    try:
        # The page's one thread busy for 2 s: no command, no heartbeat, the socket still open.
        page.evaluate("() => { const t = Date.now(); while (Date.now() - t < 2000) {} }")
        # The page said nothing: the watchdog's timeout holds the arm.
        watch.wait_for_hold("the tab froze", because="watchdog timeout")
    finally:
        page.keyboard.up("f")  # first: a test that failed must not drive the arm on
        watch.close()
    page.click("#drive-toggle")
    page.click("#lock-release")


def test_a_lost_link_mid_drive_holds_the_arm(playwright_driver, tmp_path, console_url, robot,
                                             decision):
    profile = tmp_path / "lost-link-profile"
    context = playwright_driver.chromium.launch_persistent_context(
        str(profile), executable_path=CHROMIUM, args=CHROMIUM_ARGS, headless=True)
    try:
        page = open_console(context, console_url)
        take_lock(page)
        ready_arm(page, robot)
        start_driving(page)
        # Watched from before the drive: a station that stalled mid-drive may have held the
        # arm for silence already, and then the stream's end holds nothing new.
        watch = HoldWatch(decision)
        try:
            drive_down(page, robot)
            # The browser dies mid-drive: no end message, no close frame, the TCP link drops.
            for pid in browser_pids(profile):
                os.kill(pid, signal.SIGKILL)
            detached = watch.wait_for_session_end("the browser died")
            watch.wait_for_hold("the browser died")
        finally:
            watch.close()
        # The gateway saw the socket drop and ended or broke the stream: the session waits to
        # be resumed (an end message would have closed it; the watchdog detaches nothing).
        assert detached.state == decision_server_pb2.TELEOP_SESSION_STATE_DETACHED, detached
        assert_held(robot)
    finally:
        with contextlib.suppress(Exception):
            context.close()
