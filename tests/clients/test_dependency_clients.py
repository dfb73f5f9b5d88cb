"""GetDependencies through the Python clients (blocking and asyncio), and the operator station's
dependency lines and summary, against an in-process DecisionServer over a fake slave (no
process)."""

from __future__ import annotations

import asyncio
import io

from clients.python import AsyncDecisionClient, DecisionClient, Dependency, DependencyState
from clients.teleop.__main__ import StatusLine
from clients.teleop.dependencies import DependencyMonitor, as_json, describe
from tests.conftest import wait_for
from tests.decision_server.conftest import fake_station  # noqa: F401  (fixture)

NAMES = ["proxy_robot", "force_sensor", "stereo_camera", "emergency_stop"]
REFUSED = "UNAVAILABLE: failed to connect to all addresses"


def test_get_dependencies_blocking_and_async(fake_station):  # noqa: F811
    station, slave = fake_station
    slave.dependency_health["stereo_camera"] = REFUSED
    with DecisionClient(station.address) as client:
        dependencies = client.get_dependencies()
    assert [d.name for d in dependencies] == NAMES
    assert all(isinstance(d, Dependency) for d in dependencies)
    camera = dependencies[2]
    assert (camera.state, camera.reason, camera.restarts) == (
        DependencyState.NOT_SERVING, REFUSED, 0)
    assert not camera.serving and dependencies[0].serving
    assert camera.change_time_ns > 0

    async def main():
        async with AsyncDecisionClient(station.address) as client:
            return await client.get_dependencies()

    assert asyncio.run(main()) == dependencies  # nothing changed since


def test_the_operator_station_prints_each_change_and_keeps_the_final_states(fake_station):  # noqa: F811
    station, slave = fake_station
    lines: list[str] = []
    with DecisionClient(station.address) as client:
        monitor = DependencyMonitor(client, lines.append).start()
        try:
            wait_for(lambda: station.core.events.subscriber_count >= 1,
                     what="the monitor to subscribe")
            assert all(d.serving for d in monitor.initial())
            slave.dependency_health["force_sensor"] = REFUSED
            client.get_dependencies()  # the server looks (no watch thread here)
            wait_for(lambda: lines, what="a line for the change")
            slave.dependency_health["force_sensor"] = "ok"
            client.get_dependencies()
            wait_for(lambda: len(lines) == 2, what="a line for the recovery")
        finally:
            monitor.stop()
        final = monitor.final()
    assert lines == [f"[station] force_sensor SERVING -> NOT_SERVING: {REFUSED}",
                     "[station] force_sensor NOT_SERVING -> SERVING"]
    assert [d.state for d in monitor.changes] == [DependencyState.NOT_SERVING,
                                                  DependencyState.SERVING]
    assert [(d["name"], d["state"], d["reason"]) for d in final] == [
        (name, "SERVING", "") for name in NAMES]


def test_dependency_lines_for_people():
    restarting = Dependency("stereo_camera", DependencyState.RESTARTING,
                            "restarting after it was killed by signal 9 (SIGKILL); restart 3",
                            1, 2)
    assert describe(restarting, "NOT_SERVING") == (
        "[station] stereo_camera NOT_SERVING -> RESTARTING: restarting after it was killed by "
        "signal 9 (SIGKILL); restart 3 (restarted 2x)")
    assert as_json(restarting)["state"] == "RESTARTING"
    out = io.StringIO()
    status = StatusLine(out)
    status(mode="feedback", clutch=False, force=1.0, commands=10, acks=10, round_trips=[5.0])
    status.note("[station] force_sensor SERVING -> NOT_SERVING")
    status_line, note = out.getvalue().split("\r")[1:]
    # The note covers the whole status line, and ends its own line.
    assert note.endswith("\n") and len(note) - 1 == len(status_line)
    assert note.startswith("[station] force_sensor SERVING -> NOT_SERVING")
