"""The child-process supervisor (services.runtime.children) with real processes: a real service
on port 0 whose port comes from its ready line, a clean stop, a crash reported, deadlines."""

from __future__ import annotations

import os
import signal
import socket
import threading

import grpc
import pytest
from grpc_health.v1 import health_pb2, health_pb2_grpc

from services.runtime import children
from services.runtime.children import ChildFailed
from tests.processes import REPO, unique_shm_name
from wire.processes import (
    PARENT_PID_ENV,
    STACKS_LINE,
    STACKS_SIGNAL,
    parse_ready_line,
    ready_line,
    runs_a_service,
)


def _serving(address: str) -> bool:
    with grpc.insecure_channel(address) as channel:
        reply = health_pb2_grpc.HealthStub(channel).Check(health_pb2.HealthCheckRequest(),
                                                          timeout=5)
    return reply.status == health_pb2.HealthCheckResponse.SERVING


@pytest.fixture
def started():
    """Children a test starts; whatever still runs is stopped after it."""
    made: list[children.Child] = []

    def start(name: str, args: list[str], **options) -> children.Child:
        made.append(children.start(name, args, cwd=REPO, **options))
        return made[-1]

    yield start
    children.stop_all(made, grace_s=5.0)


def _python(code: str) -> list[str]:
    return ["-c", code]


def test_ready_lines_round_trip():
    assert parse_ready_line(ready_line("world", "127.0.0.1:4321")) == ("world",
                                                                        "127.0.0.1:4321")
    assert parse_ready_line("TELEROBOT_READY world") is None
    assert parse_ready_line("INFO serving world on 127.0.0.1:4321") is None


@pytest.mark.e2e
def test_a_service_on_port_0_reports_its_port_serves_there_and_stops_cleanly():
    exits: list[children.Child] = []
    band = children.start_service("emergency_stop", ["--shm-name", unique_shm_name()],
                                  cwd=REPO, on_exit=exits.append)
    try:
        address = band.wait_ready(timeout_s=60)
        host, port = address.rsplit(":", 1)
        assert host == "127.0.0.1" and int(port) > 0
        assert band.address == address
        assert set(band.ready) == {"emergency_stop", "emergency_stop_metrics"}  # and /metrics
        assert band.ready["emergency_stop_metrics"].startswith("127.0.0.1:")
        assert _serving(address)
    finally:
        code = band.stop(grace_s=10)
    assert code == 0, band.describe()
    assert band.how_it_ended() == "exited with code 0"
    assert band.exited.wait(5) and exits == [band]
    assert any("stopped" in line for line in band.lines)


@pytest.mark.e2e
def test_a_crash_is_reported_with_the_signal_and_the_last_lines(started):
    died = threading.Event()
    child = started("sleeper", _python("import signal; print('about to wait', flush=True); "
                                       "signal.pause()"), on_exit=lambda _child: died.set())
    child.wait_line("about to wait", timeout_s=30)
    os.kill(child.pid, signal.SIGKILL)
    assert died.wait(10)
    assert child.returncode == -signal.SIGKILL
    assert child.how_it_ended() == "was killed by signal 9 (SIGKILL)"
    description = child.describe()
    assert description.startswith(f"sleeper (pid {child.pid}) was killed by signal 9")
    assert "about to wait" in description


@pytest.mark.e2e
def test_a_child_that_exits_before_ready_fails_the_wait_with_its_last_lines(started):
    child = started("broken", _python("print('cannot start: no arm', flush=True); "
                                      "raise SystemExit(3)"))
    with pytest.raises(ChildFailed) as failed:
        child.wait_ready(timeout_s=30)
    message = str(failed.value)
    assert "broken not ready" in message and "exited with code 3" in message
    assert "cannot start: no arm" in message


@pytest.mark.e2e
def test_a_child_that_never_gets_ready_fails_the_wait_at_the_deadline(started):
    child = started("mute", _python("import signal; print('thinking', flush=True); "
                                    "signal.pause()"))
    child.wait_line("thinking", timeout_s=30)
    with pytest.raises(ChildFailed, match=r"mute not ready within 0\.2 s.*is running"):
        child.wait_ready(timeout_s=0.2)


@pytest.mark.e2e
def test_waiting_for_readiness_can_be_cancelled(started):
    child = started("mute", _python("import signal; signal.pause()"))
    cancel = threading.Event()
    threading.Timer(0.05, cancel.set).start()
    assert child.wait_ready(timeout_s=30, cancel=cancel) is None
    assert child.returncode is None


@pytest.mark.e2e
def test_ready_lines_of_several_names_and_a_line_by_predicate(started):
    child = started("pair", _python(
        f"print({ready_line('first', '127.0.0.1:1')!r}); "
        f"print({ready_line('second', '127.0.0.1:2')!r}); print('done 42', flush=True)"))
    assert child.wait_ready(["second", "first"], timeout_s=30) == "127.0.0.1:2"
    assert child.ready == {"first": "127.0.0.1:1", "second": "127.0.0.1:2"}
    assert child.wait_line(lambda line: line.endswith("42"), timeout_s=30) == "done 42"
    assert child.wait(30) == 0


@pytest.mark.e2e
def test_stop_kills_a_child_that_ignores_sigterm_after_the_grace(started):
    child = started("stubborn", _python(
        "import signal; signal.signal(signal.SIGTERM, signal.SIG_IGN); "
        "print('ignoring SIGTERM', flush=True); signal.pause()"))
    child.wait_line("ignoring SIGTERM", timeout_s=30)
    assert child.stop(grace_s=0.2) == -signal.SIGKILL


@pytest.mark.e2e
def test_stop_all_stops_the_willing_and_kills_the_stubborn(started):
    willing = started("willing", _python("import signal; print('up', flush=True); "
                                         "signal.pause()"))
    stubborn = started("stubborn", _python(
        "import signal; signal.signal(signal.SIGTERM, signal.SIG_IGN); "
        "print('up', flush=True); signal.pause()"))
    for child in (willing, stubborn):
        child.wait_line("up", timeout_s=30)
    assert children.stop_all([stubborn, willing], grace_s=0.3) == [stubborn]
    assert willing.returncode == -signal.SIGTERM and stubborn.returncode == -signal.SIGKILL


# A service-like child that ignores SIGTERM, stuck in a function whose name its stacks show.
_HUNG_SERVICE = (
    "import signal, threading\n"
    "from wire.processes import dump_stacks_on_signal\n"
    "dump_stacks_on_signal()\n"
    "signal.signal(signal.SIGTERM, signal.SIG_IGN)\n"
    "def stuck_in_here():\n"
    "    print('up', flush=True)\n"
    "    threading.Event().wait()\n"
    "stuck_in_here()\n")


@pytest.mark.e2e
@pytest.mark.parametrize("stopped_by", ["stop", "stop_all"])
def test_a_hung_service_is_killed_and_the_log_says_where_it_was_stuck(started, caplog,
                                                                     stopped_by):
    child = started("hung", _python(_HUNG_SERVICE))
    child.dumps_stacks = True  # as for `-m services.<name>`, which runs the same call
    child.wait_line("up", timeout_s=30)
    if stopped_by == "stop":
        assert child.stop(grace_s=0.2) == -signal.SIGKILL
    else:
        assert children.stop_all([child], grace_s=0.2) == [child]
        assert child.returncode == -signal.SIGKILL
    assert any("stuck_in_here" in line for line in child.lines), child.lines
    warning = next(r.getMessage() for r in caplog.records if "did not stop" in r.getMessage())
    assert "killed it. Its threads were at:" in warning and "stuck_in_here" in warning


def test_only_this_projects_services_are_asked_for_their_stacks():
    assert runs_a_service(["-m", "services.world", "--address", "127.0.0.1:0"])
    assert runs_a_service(["-m", "services.launcher"])
    assert not runs_a_service(["-m", "services.security.pki", "--dir", "pki"])
    assert not runs_a_service(["-m", "bench.worker", "network"])
    assert not runs_a_service(["-c", "import services"])


@pytest.mark.e2e
def test_a_service_writes_its_stacks_on_the_signal_and_serves_on(started):
    band = started("emergency_stop", ["-m", "services.emergency_stop", "--address",
                                      "127.0.0.1:0", "--shm-name", unique_shm_name()])
    assert band.dumps_stacks
    address = band.wait_ready(timeout_s=60)
    band.send_signal(STACKS_SIGNAL)
    band.wait_line(STACKS_LINE, timeout_s=10)
    band.wait_line("in run_service", timeout_s=10)  # the main thread, waiting to stop
    assert _serving(address)
    assert band.stop(grace_s=10) == 0, band.describe()


@pytest.mark.e2e
def test_a_child_gets_its_own_group_the_parent_pid_and_the_extra_environment(started):
    child = started("env", _python(
        "import os; print(os.getpgid(0), os.environ['TELEROBOT_PARENT_PID'], "
        "os.environ['EXTRA'], os.environ['PYTHONUNBUFFERED'])"), env={"EXTRA": "yes"})
    assert child.wait(30) == 0
    child.exited.wait(5)
    pgid, parent, extra, unbuffered = child.lines[0].split()
    assert int(pgid) == child.pid != os.getpgid(0)
    assert (int(parent), extra, unbuffered) == (os.getpid(), "yes", "1")
    assert PARENT_PID_ENV == "TELEROBOT_PARENT_PID"


@pytest.mark.e2e
def test_a_child_may_stay_in_our_group_and_keep_every_line(started):
    child = started("chatty", _python("import os; [print(i) for i in range(500)]; "
                                      "print(os.getpgid(0))"), own_group=False, max_lines=None)
    assert child.wait(30) == 0
    assert child.exited.wait(5)
    assert len(child.lines) == 501 and int(child.lines[-1]) == os.getpgid(0)


def test_refused_address_refuses_connections_and_cannot_be_bound():
    address = children.refused_address()
    host, port = address.rsplit(":", 1)
    with socket.socket() as probe, pytest.raises(ConnectionRefusedError):
        probe.connect((host, int(port)))
    with socket.socket() as other, pytest.raises(OSError):
        other.bind((host, int(port)))
    with grpc.insecure_channel(address) as channel, pytest.raises(grpc.RpcError) as error:
        health_pb2_grpc.HealthStub(channel).Check(health_pb2.HealthCheckRequest(), timeout=5)
    assert error.value.code() is grpc.StatusCode.UNAVAILABLE
