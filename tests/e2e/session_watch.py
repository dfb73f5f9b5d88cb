"""python -m tests.e2e.session_watch ADDRESS: the DecisionServer's own account of its
Teleoperate sessions, for a test that cannot reach it directly (it runs on the slave host of
test_two_hosts.py). Prints its ready line, then `session {json}` for each TeleopSessionEvent,
and `descended 20 mm` once the tool is 20 mm below where it was when the first session opened
(the peg-in-hole task is under way). TLS as the environment says (TELEROBOT_TLS_DIR,
TELEROBOT_IDENTITY)."""

from __future__ import annotations

import json
import sys
import threading
import time

from google.protobuf.json_format import MessageToDict

from clients.python import DecisionClient
from wire.processes import say_ready

DESCENT_M = 0.02
POLL_S = 0.02


def report_sessions(events, opened: threading.Event) -> None:
    for event in events:
        if event.WhichOneof("event") == "teleop_session":
            opened.set()
            print("session", json.dumps(MessageToDict(event.teleop_session)), flush=True)


def main(address: str) -> int:
    opened = threading.Event()
    with DecisionClient(address, default_timeout=10.0) as client:
        events = client.stream_events()
        threading.Thread(target=report_sessions, args=(events, opened), daemon=True).start()
        say_ready("session_watch", "0:0")
        opened.wait()
        start = client.robot.get_state().tool_pose.translation[2]
        while client.robot.get_state().tool_pose.translation[2] > start - DESCENT_M:
            time.sleep(POLL_S)  # a poll of the arm's state, not an ordering of events
        print(f"descended {DESCENT_M * 1e3:.0f} mm", flush=True)
        threading.Event().wait()  # the sessions go on being reported until the test stops us
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
