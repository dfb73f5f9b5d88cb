"""A hostile page in headless Chromium tries to drive the arm through the user's console.

Two pages, both on `evil.localhost` (Chromium resolves any *.localhost name to 127.0.0.1, as a
DNS rebinding would resolve the attacker's name to the station):
- re-bound: the page is served as http://evil.localhost:<the console's port>/, so the
  console's routes are same-origin to it: its calls reach the console with Host and Origin
  evil.localhost, exactly as a rebinding's would. Playwright serves the page itself (the
  attacker's server, before the rebinding); its calls go to the real console.
- cross-site: the page is on another port and calls the console's own address (no CORS
  preflight: text/plain, as a form post would).
Both also open the Foxglove live view's WebSocket, by the re-bound name and by 127.0.0.1, as
Foxglove does (subprotocol foxglove.sdk.v1): a page that could would watch the arm and the
cameras.
Every attempt is refused and, asked past the console, the station says nobody took control
and the arm did not move. A page of the Foxglove app's origin does open the live view: the
refusals are the live view's, by Origin, not the browser's."""

from __future__ import annotations

import json
from urllib.parse import urlsplit

import numpy as np
import pytest

from telerobot.v1 import decision_server_pb2, proxy_robot_pb2, types_pb2
from tests.conftest import wait_for
from tests.web_console.conftest import arm_state

pytestmark = [pytest.mark.e2e, pytest.mark.slow]

# The calls the page tries: take the lock, move the arm, stop and reset it.
CALLS = {
    "/telerobot.v1.DecisionServer/AcquireControl":
        {"operatorId": "evil", "mode": "CONTROL_MODE_EXCLUSIVE"},
    "/telerobot.v1.ProxyRobot/MoveJointsIncremental":
        {"deltaJointPositionsRad": [0.1, 0, 0, 0, 0, 0]},
    "/telerobot.v1.ProxyRobot/Initialize": {},
}

OPEN_SOCKET = """
(url, protocol) => new Promise((resolve) => {
  const socket = new WebSocket(url, protocol);
  socket.onopen = () => { socket.close(); resolve("open"); };
  socket.onclose = (event) => resolve("closed " + event.code);
})
"""

ATTACK = """
async ({target, live}) => {
  const openSocket = OPEN_SOCKET;
  const out = {};
  for (const [path, body] of Object.entries(CALLS)) {
    for (const type of ["application/json", "text/plain"]) {
      try {
        const reply = await fetch(target + path, {method: "POST", mode: "no-cors",
          headers: {"content-type": type}, body: JSON.stringify(body)});
        out[path + " " + type] = reply.type === "opaque" ? "opaque" : reply.status;
      } catch (error) {
        out[path + " " + type] = "failed";
      }
    }
  }
  out.socket = await openSocket(target.replace("http", "ws") + "/ws/teleoperate",
                                "telerobot.v1.teleoperate");
  for (const url of live) {
    out["live " + url] = await openSocket(url, "foxglove.sdk.v1");
  }
  return out;
}
""".replace("CALLS", json.dumps(CALLS)).replace("OPEN_SOCKET", OPEN_SOCKET.strip())


def page_at(browser, page_url: str):
    """A new tab showing a page the test serves itself at `page_url` (for the attacker's, as
    the attacker's server would). The page may reach loopback: Chromium's Local Network Access
    would otherwise refuse a served page's sockets to 127.0.0.1 itself (the page's address is
    not known to be local), before they reach the station, and the test would show nothing of
    the station's own refusals (a browser without it, or a user who clicked "allow", lets them
    through)."""
    origin = "{0.scheme}://{0.netloc}".format(urlsplit(page_url))
    browser.grant_permissions(["local-network-access"], origin=origin)
    page = browser.new_page()
    page.route(page_url, lambda route: route.fulfill(
        status=200, content_type="text/html", body="<!doctype html><title>evil</title>"))
    page.goto(page_url)
    return page


def attack_from(browser, page_url: str, target: str, live: list[str]) -> dict:
    page = page_at(browser, page_url)
    try:
        return page.evaluate(ATTACK, {"target": target, "live": live})
    finally:
        page.close()


def foxglove_app_opens(browser, url: str) -> str:
    """What a page of the Foxglove app's origin gets when it opens the live view at `url`."""
    page = page_at(browser, "https://app.foxglove.dev/")
    try:
        return page.evaluate(f"(url) => ({OPEN_SOCKET.strip()})(url, 'foxglove.sdk.v1')", url)
    finally:
        page.close()


def live_view_urls(console_station) -> list[str]:
    """The live view by the re-bound name and by its address."""
    port = urlsplit(f"//{console_station.ready['foxglove']}").port
    return [f"ws://evil.localhost:{port}", f"ws://127.0.0.1:{port}"]


def nobody_in_control(decision) -> bool:
    state = decision.GetControlState(decision_server_pb2.GetControlStateRequest(), timeout=5)
    return not any(holder.operator_id == "evil" for holder in state.state.holders)


def test_a_rebound_page_and_a_cross_site_page_cannot_drive_the_arm(browser, console_url, robot,
                                                                   decision, console_station):
    port = urlsplit(console_url).port
    live = live_view_urls(console_station)
    robot.Connect(proxy_robot_pb2.ConnectRequest(), timeout=10)  # past the console: it reads
    before = wait_for(lambda: (state := arm_state(robot)).status
                      != types_pb2.ROBOT_STATUS_NOT_CONNECTED and state, 10,
                      "a state sample of the connected arm")

    rebound = f"http://evil.localhost:{port}"
    refused = attack_from(browser, f"{rebound}/", rebound, live)
    calls = {k: v for k, v in refused.items() if k.startswith("/")}
    assert set(calls.values()) == {403}, refused  # same-origin to the page: statuses visible
    sockets = {k: v for k, v in refused.items() if not k.startswith("/")}
    assert len(sockets) == 3 and all(v.startswith("closed") for v in sockets.values()), refused

    cross_site = attack_from(browser, f"http://evil.localhost:{port + 1}/", console_url, live)
    sockets = {k: v for k, v in cross_site.items() if not k.startswith("/")}
    assert len(sockets) == 3 and all(v.startswith("closed") for v in sockets.values()), \
        cross_site
    # The Foxglove web app's origin, which the live view allows, does get its socket: what
    # refused the pages above was the live view, by their Origin, not the browser.
    assert foxglove_app_opens(browser, live[1]) == "open"

    # Past the console: no lease was taken and the arm is where it was.
    assert nobody_in_control(decision)
    after = arm_state(robot)
    assert after.status == before.status
    # A refused 0.1 rad move would show; a held arm stays within a milliradian.
    np.testing.assert_allclose(after.joint_positions_rad, before.joint_positions_rad, atol=1e-3)


def test_the_consoles_own_page_still_reaches_the_station(browser, console_url):
    """The same calls from the console's own origin get through the host and origin checks
    (GetControlState answers: the station was reached)."""
    page = browser.new_page()
    page.goto(console_url)
    status = page.evaluate("""async () => (await fetch("/telerobot.v1.DecisionServer/"
        + "GetControlState", {method: "POST", headers: {"content-type": "application/json"},
        body: "{}"})).status""")
    page.close()
    assert status == 200
