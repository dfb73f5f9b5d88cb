"""Discovery across two hosts: a real advertisement in one network namespace, a real browser
in another, joined by a veth pair with addresses of a private /30 (tests/netns.py). Nothing is
sent on this machine's own interfaces: every process of these tests runs in a namespace the
test made. Events are ordered by waiting for lines with a deadline, never by sleeping.
"""

from __future__ import annotations

import signal

import pytest

from discovery.__main__ import ADVERTISED_LINE
from services.runtime.children import Child
from tests.netns import linked_namespaces, python_in_namespace, unavailable_reason
from tests.processes import start_process, station_env

pytestmark = pytest.mark.e2e

SLAVE_ADDRESS = "10.213.9.1"  # the slave station's namespace
MASTER_ADDRESS = "10.213.9.2"  # the operator's
LINE_TIMEOUT_S = 20.0  # generous: a loaded 2-core machine


@pytest.fixture
def hosts():
    """(slave, master) namespace names."""
    if (reason := unavailable_reason()) is not None:
        pytest.skip(reason)
    with linked_namespaces(SLAVE_ADDRESS, MASTER_ADDRESS) as pair:
        yield pair


@pytest.fixture
def run():
    """Factory: `python -m discovery <args>` in a namespace; stopped after."""
    started: list[Child] = []

    def start(namespace: str, *args: str, module: str = "discovery",
              env: dict[str, str] | None = None) -> Child:
        child = start_process(python_in_namespace(namespace, ["-m", module, *args]), env,
                              module.rsplit(".", 1)[-1])
        started.append(child)
        return child

    yield start
    for child in started:
        child.stop()


def advertise(run, slave: str, *args: str) -> tuple[Child, str]:
    """An advertiser in `slave`, once its advertisement is out; and the name it got."""
    child = run(slave, "advertise", *args)
    line = child.wait_line(ADVERTISED_LINE, timeout_s=LINE_TIMEOUT_S)
    return child, line.split(ADVERTISED_LINE, 1)[1].strip()


def finished(child: Child) -> tuple[int, list[str]]:
    """Exit code and output lines of a child that ends by itself."""
    return child.wait(LINE_TIMEOUT_S), child.lines


def test_a_station_advertised_on_one_host_is_listed_and_picked_from_the_other(hosts, run):
    slave, master = hosts
    # On every address: the advertisement names the slave's real address, not loopback.
    advertise(run, slave, "--address", "0.0.0.0:50051", "--tls", "--token-port", "50061",
              "--name", "lab-slave")

    code, lines = finished(run(master, "list", "--timeout", "3"))
    assert code == 0, lines
    assert lines == [f"lab-slave  {SLAVE_ADDRESS}:50051  TLS  telerobot.v1  "
                     "tokens on port 50061"]

    # discovered_address: by name (it returns once heard, so a long timeout costs nothing),
    # and without a name the only one (it listens the whole timeout, to know it is the only).
    for args in (["lab-slave", "--timeout", "20"], ["--timeout", "3"]):
        code, lines = finished(run(master, "address", *args))
        assert (code, lines) == (0, [f"{SLAVE_ADDRESS}:50051"])


def test_nothing_advertised_is_a_clear_error(hosts, run):
    _, master = hosts
    code, lines = finished(run(master, "list", "--timeout", "1"))
    assert code == 1
    assert lines == ["no slave station heard within 1 s (_telerobot._tcp.local.)"]
    code, lines = finished(run(master, "address", "--timeout", "1"))
    assert code == 1
    assert "no slave station found (_telerobot._tcp.local. on the local network)" in lines[0]


def test_with_two_stations_an_operator_must_choose(hosts, run):
    slave, master = hosts
    advertise(run, slave, "--address", f"{SLAVE_ADDRESS}:50051", "--name", "left")
    advertise(run, slave, "--address", f"{SLAVE_ADDRESS}:50151", "--name", "right")

    code, lines = finished(run(master, "address", "--timeout", "3"))
    assert code == 1
    assert "2 slave stations found ('left', 'right'): name the one to use" in lines[0], lines
    code, lines = finished(run(master, "address", "right", "--timeout", "20"))
    assert (code, lines) == (0, [f"{SLAVE_ADDRESS}:50151"])


def test_a_withdrawn_station_leaves_the_list_at_once(hosts, run):
    slave, master = hosts
    watch = run(master, "watch")
    watch.wait_line("watching for", timeout_s=LINE_TIMEOUT_S)
    advertiser, _ = advertise(run, slave, "--address", f"{SLAVE_ADDRESS}:50051", "--name",
                              "lab-slave")
    watch.wait_line(f"+ lab-slave  {SLAVE_ADDRESS}:50051  plaintext  telerobot.v1",
                    timeout_s=LINE_TIMEOUT_S)
    advertiser.send_signal(signal.SIGINT)
    assert advertiser.wait(LINE_TIMEOUT_S) == 0
    assert "withdrawn" in advertiser.lines
    # The records live 120 s in a cache: leaving within seconds is the goodbye's doing.
    watch.wait_line("- lab-slave", timeout_s=5.0)


@pytest.mark.slow
def test_the_launcher_advertises_the_station_and_withdraws_it_on_ctrl_c(hosts, run):
    slave, master = hosts
    watch = run(master, "watch")
    watch.wait_line("watching for", timeout_s=LINE_TIMEOUT_S)
    # The DecisionServer on the slave's network address (plaintext, so no certificate
    # needs that address); the station's inner services stay on its loopback.
    env = station_env(TELEROBOT_DECISION_SERVER_ADDRESS=f"{SLAVE_ADDRESS}:0",
                      TELEROBOT_ALLOW_PLAINTEXT_NETWORK="1",
                      TELEROBOT_STATION_NAME="ns-station",
                      TELEROBOT_ADVERTISE="auto")  # the default: beyond loopback, advertised
    launcher = run(slave, "--grace-s", "1", module="services.launcher", env=env)
    port = launcher.wait_ready("decision_server", timeout_s=90).rsplit(":", 1)[1]
    watch.wait_line(f"+ ns-station  {SLAVE_ADDRESS}:{port}  plaintext  telerobot.v1",
                    timeout_s=LINE_TIMEOUT_S)

    launcher.send_signal(signal.SIGINT)  # what a terminal's Ctrl-C sends it
    watch.wait_line("- ns-station", timeout_s=5.0)
    assert launcher.wait(LINE_TIMEOUT_S) == 0, launcher.describe()
    assert any("withdrew the station's advertisement" in line for line in launcher.lines)


def test_make_teleop_discovers_the_station_by_name(hosts, run):
    """`python -m clients.teleop --discover NAME` on the master host connects to the address
    the slave host advertised. (Only an advertisement answers there: the operator station
    then says that no station answers at that address and exits 3, which is what shows the
    address it took.)"""
    slave, master = hosts
    advertise(run, slave, "--address", f"{SLAVE_ADDRESS}:50051", "--name", "lab-slave")
    code, lines = finished(run(master, "--discover", "lab-slave", "--no-video",
                               module="clients.teleop"))
    output = "\n".join(lines)
    assert code == 3, output
    assert f"found the slave station at {SLAVE_ADDRESS}:50051" in output
    assert f"no slave station answers at {SLAVE_ADDRESS}:50051" in output
    assert "Traceback" not in output


def test_make_teleop_says_when_no_station_is_found(hosts, run):
    _, master = hosts
    code, lines = finished(run(master, "--discover", module="clients.teleop"))
    assert code == 3 and "Traceback" not in "\n".join(lines)
    assert any("no" in line.lower() and "station" in line.lower() for line in lines), lines
