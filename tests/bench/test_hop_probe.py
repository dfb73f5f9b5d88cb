"""bench/probes/hop.py measures what it says: the real move handler takes each step, and each
server kind answers real calls from a process of its own."""

from __future__ import annotations

import re

import numpy as np
import pytest

from bench.probes import hop as hop_probe
from bench.probes.arm import proxy_robot_servicer

pytestmark = pytest.mark.e2e  # the round trips start server processes


def test_the_handler_it_times_really_moves_the_arm():
    servicer = proxy_robot_servicer()
    first = servicer.MoveCartesianIncremental(hop_probe._request(1), None)
    second = servicer.MoveCartesianIncremental(hop_probe._request(-1), None)
    assert first.applied_fraction == 1.0
    # a 1 µm step along base y there and back: the targets differ by about that much
    step = second.target_tool_pose.position_m.y - first.target_tool_pose.position_m.y
    assert step == pytest.approx(-1e-6, abs=1e-7)


def test_every_kind_prints_its_percentiles(capsys):
    assert hop_probe.main(["--calls", "30", "--rate", "500"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert [line.split(":")[0] for line in lines] == [
        "handler, 0.0 ms apart", "handler, 0.5 ms apart", "handler, 2.0 ms apart",
        "round trip at 500 Hz, noop", "same, one open stream, noop",
        "round trip at 500 Hz, bare", "same, one open stream, bare",
        "round trip at 500 Hz, stack", "same, the local socket, noop",
        "same, the local socket, bare"]
    for line in lines:
        p50, p90, p99 = (float(v) for v in re.findall(r"p\d\d ([\d.]+)", line))
        assert np.isfinite(p50) and 0 < p50 <= p90 <= p99
