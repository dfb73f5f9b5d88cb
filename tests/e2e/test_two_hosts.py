"""Two hosts and a broken link (#14): the slave station in one network namespace, the operator
station (`python -m clients.teleop`) in another, joined by a veth pair, over TLS, with the
impairment proxy at the slave's edge. The link is cut for 3 s in the middle of the
peg-in-hole run; the session resumes and the task succeeds, and the server's own count of the
commands it processed and applied (its TeleopSessionEvent) equals the operator's count of
acked and applied commands. Where namespaces cannot be made, the same runs on loopback.

Then the failures the operator station must survive without a traceback: a link that stays
down, and a DecisionServer that dies (its supervisor restarts it; the session is gone)."""

from __future__ import annotations

import json
import os
import signal
import subprocess
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import pytest

from services.runtime.children import Child
from services.security import pki
from tests.conftest import wait_for
from tests.netns import linked_namespaces, python_in_namespace, unavailable_reason
from tests.processes import service_pid, start_process, station_env

pytestmark = pytest.mark.e2e

MASTER_IP, SLAVE_IP = "10.213.14.1", "10.213.14.2"  # a private /30 of the test's own
CUT_S = 3.0
ONE_WAY_DELAY = "10ms"  # a campus-like link: 20 ms round trip, with jitter
JITTER = "2ms"


@dataclass
class Hosts:
    """Where each side runs: a namespace each (or None: this one, on loopback)."""

    master: str | None
    slave: str | None
    slave_ip: str

    def python(self, host: str | None, args: list[str]) -> list[str]:
        return python_in_namespace(host, args) if host else args


@pytest.fixture(scope="module")
def hosts() -> Iterator[Hosts]:
    if unavailable_reason() is not None:
        yield Hosts(None, None, "127.0.0.1")  # the same scenarios, on loopback
        return
    with linked_namespaces(MASTER_IP, SLAVE_IP) as (master, slave):
        yield Hosts(master, slave, SLAVE_IP)


@pytest.fixture(scope="module")
def tls_dir(hosts, tmp_path_factory) -> Path:
    directory = tmp_path_factory.mktemp("pki")
    pki.init(directory, hosts=[hosts.slave_ip])
    return directory


@dataclass
class Slave:
    launcher: Child
    watch: Child  # tests.e2e.session_watch, on the slave host
    proxy: Child  # the impairment link; the operator connects to it
    env: dict[str, str]


@pytest.fixture
def slave(hosts, tls_dir) -> Iterator[Slave]:
    """The slave station on its host: the DecisionServer on the host's address (TLS), the
    other services on its loopback; the impairment proxy in front of the DecisionServer."""
    env = station_env(TELEROBOT_DECISION_SERVER_ADDRESS=f"{hosts.slave_ip}:0",
                      TELEROBOT_TLS_DIR=str(tls_dir), TELEROBOT_ADVERTISE="0")
    from services.launcher import STATION, UP_LINE

    launcher = start_process(hosts.python(hosts.slave, ["-m", "services.launcher",
                                                        "--grace-s", "1"]), env, "launcher")
    started = [launcher]
    try:
        launcher.wait_ready(STATION, timeout_s=90)
        launcher.wait_line(UP_LINE, timeout_s=10)
        door = launcher.ready["decision_server"]
        watch = start_process(hosts.python(hosts.slave, ["-m", "tests.e2e.session_watch", door]),
                              {**env, "TELEROBOT_IDENTITY": "observer"}, "session_watch")
        started.append(watch)
        proxy = start_process(hosts.python(hosts.slave, [
            "-m", "services.impairment", "--allow-network", "--listen", f"{hosts.slave_ip}:0",
            "--target", door,
            "--delay", ONE_WAY_DELAY, "--jitter", JITTER, "--seed", "14",
            "--cut-for", f"{CUT_S:g}s", "--cut-mode", "reset"]), env, "impairment")
        started.append(proxy)
        watch.wait_ready("session_watch", timeout_s=30)
        proxy.wait_ready("impairment", timeout_s=30)
        yield Slave(launcher, watch, proxy, env)
    finally:
        for child in reversed(started):
            child.stop(signal.SIGINT)


def operator(hosts: Hosts, slave: Slave, out: Path, address: str | None = None) -> Child:
    """`python -m clients.teleop` on the master host, through the link, over TLS."""
    args = ["-m", "clients.teleop", "--address", address or slave.proxy.address,
            "--modes", "feedback", "--no-video", "--out", str(out)]
    env = {"TELEROBOT_TLS_DIR": slave.env["TELEROBOT_TLS_DIR"],
           "TELEROBOT_IDENTITY": "operator", "PYTHONUNBUFFERED": "1"}
    return start_process(hosts.python(hosts.master, args), env, "teleop")


def wait_mid_task(slave: Slave, teleop: Child) -> None:
    """Until the session is open and has moved the peg 20 mm down (the first stroke)."""
    def moved() -> bool:
        if teleop.exited.is_set():
            raise AssertionError(f"the operator station ended early: {teleop.describe(5)}; "
                                 f"{slave.watch.describe(20)}")
        return any(line == "descended 20 mm" for line in slave.watch.lines)

    try:
        wait_for(moved, 180, "the session to move the arm")
    except AssertionError as error:
        raise AssertionError(f"{error}; {teleop.describe(40)}") from None


def exit_code(teleop: Child, timeout_s: float) -> int:
    try:
        return teleop.process.wait(timeout=timeout_s)
    except subprocess.TimeoutExpired:
        raise AssertionError(f"the operator station still runs: {teleop.describe(30)}") from None


def ended_cleanly(teleop: Child, code: int) -> str:
    """The operator station's output, once checked that it ended early with a message."""
    output = "\n".join(teleop.lines)
    assert code == 3, output
    assert "Traceback" not in output
    assert "teleop: the session ended" in output
    return output


def session_events(watch: Child) -> list[dict]:
    return [json.loads(line.split(" ", 1)[1]) for line in watch.lines
            if line.startswith("session ")]


def test_a_3s_cut_mid_task_is_resumed_and_the_task_succeeds(hosts, slave, tmp_path):
    teleop = operator(hosts, slave, tmp_path)
    try:
        wait_mid_task(slave, teleop)
        slave.proxy.process.send_signal(signal.SIGUSR1)  # cut the link for CUT_S
        teleop.wait_line(lambda line: "link lost" in line, timeout_s=10)
        teleop.wait_line(lambda line: "session resumed" in line, timeout_s=30)
        assert exit_code(teleop, 180) == 0, teleop.describe()
    finally:
        teleop.stop()
    summary = json.loads((tmp_path / "summary.json").read_text())
    (run,) = summary["runs"]
    assert run["success"], run
    assert run["link_interruptions"] == 1
    closed = wait_for(lambda: [e for e in session_events(slave.watch)
                               if e["state"] == "TELEOP_SESSION_STATE_CLOSED"],
                      10, "the server's account of the session")
    server = closed[-1]
    states = [e["state"].removeprefix("TELEOP_SESSION_STATE_")
              for e in session_events(slave.watch) if e["sessionId"] == server["sessionId"]]
    assert states == ["OPENED", "DETACHED", "RESUMED", "CLOSED"]
    # Nothing twice, nothing lost: what the operator sent, it got acked once each, and the
    # server processed (and applied) exactly those, less those the client sent inside a newer
    # one while the link was slower than the operator.
    merged = run["commands_merged"]
    assert run["commands"] == run["commands_acked"] == int(server["commandsProcessed"]) + merged
    # A merged command shares the outcome of the one it went inside: applied with it, or
    # refused with it (a backlog refused around the cut), so only the bounds are exact.
    applied = int(server["commandsApplied"])
    assert applied <= run["commands_applied"] <= applied + merged
    assert int(server["lastSequence"]) == run["commands"]


def test_a_link_that_stays_down_ends_the_operator_station_cleanly(hosts, slave, tmp_path):
    teleop = operator(hosts, slave, tmp_path)
    try:
        wait_mid_task(slave, teleop)
        slave.proxy.stop(signal.SIGKILL)  # the link is gone for good
        code = exit_code(teleop, 60)
    finally:
        teleop.stop()
    assert "the arm holds" in ended_cleanly(teleop, code).lower()


def test_a_dead_decision_server_ends_the_operator_station_cleanly(hosts, slave, tmp_path):
    """Killed mid-task, the DecisionServer is restarted by its supervisor, but the session and
    its lease died with it: the operator station says so and exits, no traceback."""
    teleop = operator(hosts, slave, tmp_path)
    try:
        wait_mid_task(slave, teleop)
        pid = service_pid(slave.launcher, "decision_server")
        assert pid is not None
        os.kill(pid, signal.SIGKILL)
        code = exit_code(teleop, 60)
    finally:
        teleop.stop()
    ended_cleanly(teleop, code)
