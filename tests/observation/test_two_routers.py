"""Observers behind a second router, across a delayed link between two network namespaces:
the station (with mutual TLS) and its router on this host, a router on the observers' host
joined to it through the impairment proxy at the papers' 183 ms round trip, and 64 observers
behind that router. One copy of the station's stream crosses the link, every observer gets
every sample, and the median sample reaches them within the one-way delay plus 20 ms.

The p95 of that lag is printed, not judged: here it is 106-118 ms, around issue #33's bound
of the one-way delay plus 20 ms (111.5 ms), and what moves it is this host's CPU, which the
station, two routers, the proxy and 64 Python subscribers share (docs/observers.md)."""

from __future__ import annotations

import json
import re
import signal

import pytest

from services.security import pki
from telerobot.v1 import force_sensor_pb2, force_sensor_pb2_grpc
from tests.netns import linked_namespaces, python_in_namespace, unavailable_reason
from tests.observation.observers_process import READY
from tests.processes import start_process, start_station, station_env
from wire.tls import ChannelSecurity, open_channel

pytestmark = [pytest.mark.e2e,
              pytest.mark.skipif(unavailable_reason() is not None,
                                 reason=unavailable_reason() or "")]

STATION_IP, OBSERVERS_IP = "10.213.33.1", "10.213.33.2"  # a private /30 of the test's own
STATION = "campus"
ONE_WAY_DELAY_MS = 91.5  # the papers' campus route: 183 ms round trip
OBSERVERS = 64
OBSERVE_S = 6.0


def test_one_copy_crosses_to_a_remote_router_and_its_64_observers_keep_up(tmp_path):
    tls_dir = tmp_path / "pki"
    pki.init(tls_dir, hosts=[STATION_IP])
    started = []
    try:
        with linked_namespaces(STATION_IP, OBSERVERS_IP, left_in_this_namespace=True) as (
                _, remote):
            station = start_station(station_env(TELEROBOT_TLS_DIR=str(tls_dir),
                                                TELEROBOT_STATION=STATION,
                                                TELEROBOT_ADVERTISE="0"))
            started.append(station)
            _start_reading(station.ready, tls_dir)
            link = start_process([
                "-m", "services.impairment", "--allow-network", "--listen", f"{STATION_IP}:0",
                "--target", station.ready["zenoh_router"], "--delay",
                f"{ONE_WAY_DELAY_MS}ms"], name="impairment")
            started.append(link)
            link_address = link.wait_ready("impairment", timeout_s=30)
            router = start_process(python_in_namespace(remote, [
                "-m", "services.zenoh_router", "--address", "127.0.0.1:0", "--tls-dir",
                str(tls_dir), "--connect", f"tls/{link_address}"]), name="remote_router")
            started.append(router)
            router_address = router.wait_ready("zenoh_router", timeout_s=30)
            observers = start_process(python_in_namespace(remote, [
                "-m", "tests.observation.observers_process", "--router",
                f"tls/{router_address}", "--tls-dir", str(tls_dir), "--station", STATION,
                "--count", str(OBSERVERS), "--seconds", str(OBSERVE_S)]), name="observers")
            started.append(observers)
            observers.wait_line(READY, timeout_s=90)
            assert observers.wait(OBSERVE_S + 60) == 0, observers.describe()
            result = json.loads(observers.lines[-1])
            link.stop(signal.SIGINT)
            carried = _bytes_down(link)
    finally:
        for child in reversed(started):
            child.stop(signal.SIGINT)
    each = result["observers"]
    assert len(each) == OBSERVERS and all(o["messages"] > 0 for o in each)
    most = max(o["bytes"] for o in each)
    print(f"the link carried {carried} B; an observer got {most} B; lag p50 "
          f"{result['lag_p50_ms']:.1f} ms, p95 {result['lag_p95_ms']:.1f} ms")
    # One copy: the station -> remote router direction carried about what one observer got
    # (with Zenoh's framing), not 64 times it.
    assert most <= carried < 2 * most, (carried, most)
    assert sum(o["lost"] for o in each) == 0
    assert result["lag_p50_ms"] <= ONE_WAY_DELAY_MS + 20, result["lag_p50_ms"]


def _start_reading(ready: dict[str, str], tls_dir) -> None:
    with open_channel(ready["force_sensor"], security=ChannelSecurity(tls_dir, "admin"),
                      service="force_sensor") as channel:
        force_sensor_pb2_grpc.ForceSensorStub(channel).StartReading(
            force_sensor_pb2.StartReadingRequest(), timeout=10)


def _bytes_down(link) -> int:
    """The bytes the impairment proxy carried from its target (the station's router) to its
    client (the remote router), from the stats it prints on stopping."""
    link.exited.wait(10)
    for line in reversed(link.lines):
        match = re.search(r"bytes=\{'up': \d+, 'down': (\d+)\}", line)
        if match:
            return int(match.group(1))
    raise AssertionError(f"no stats line: {link.describe()}")
