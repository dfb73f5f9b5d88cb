"""A hostile page in headless Chromium tries to drive the arm through the user's console.

Two pages, both on `evil.localhost` (Chromium resolves any *.localhost name to 127.0.0.1, as a
DNS rebinding would resolve the attacker's name to the station):
- re-bound: the page is served as http://evil.localhost:<the console's port>/, so the
  console's routes are same-origin to it: its calls reach the console with Host and Origin
  evil.localhost, exactly as a rebinding's would. Playwright serves the page itself (the
  attacker's server, before the rebinding); its calls go to the real console.
- cross-site: the page is on another port and calls the console's own address (no CORS
  preflight: text/plain, as a form post would).
Every attempt is refused and, asked past the console, the station says nobody took control
and the arm did not move."""

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

ATTACK = """
async (target) => {
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
  out.socket = await new Promise((resolve) => {
    const socket = new WebSocket(target.replace("http", "ws") + "/ws/teleoperate",
                                 "telerobot.v1.teleoperate");
    socket.onopen = () => { socket.close(); resolve("open"); };
    socket.onclose = (event) => resolve("closed " + event.code);
  });
  return out;
}
""".replace("CALLS", json.dumps(CALLS))


def attack_from(browser, page_url: str, target: str) -> dict:
    page = browser.new_page()
    page.route(page_url, lambda route: route.fulfill(
        status=200, content_type="text/html", body="<!doctype html><title>evil</title>"))
    page.goto(page_url)
    try:
        return page.evaluate(ATTACK, target)
    finally:
        page.close()


def nobody_in_control(decision) -> bool:
    state = decision.GetControlState(decision_server_pb2.GetControlStateRequest(), timeout=5)
    return not any(holder.operator_id == "evil" for holder in state.state.holders)


def test_a_rebound_page_and_a_cross_site_page_cannot_drive_the_arm(browser, console_url, robot,
                                                                   decision):
    port = urlsplit(console_url).port
    robot.Connect(proxy_robot_pb2.ConnectRequest(), timeout=10)  # past the console: it reads
    before = wait_for(lambda: (state := arm_state(robot)).status
                      != types_pb2.ROBOT_STATUS_NOT_CONNECTED and state, 10,
                      "a state sample of the connected arm")

    rebound = f"http://evil.localhost:{port}"
    refused = attack_from(browser, f"{rebound}/", rebound)
    calls = {k: v for k, v in refused.items() if k != "socket"}
    assert set(calls.values()) == {403}, refused  # same-origin to the page: statuses visible
    assert refused["socket"].startswith("closed"), refused

    cross_site = attack_from(browser, f"http://evil.localhost:{port + 1}/", console_url)
    assert cross_site["socket"].startswith("closed"), cross_site

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
