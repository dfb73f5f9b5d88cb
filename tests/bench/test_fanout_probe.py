"""bench/probes/fanout.py measures what it says: every server kind really fans the sampler's
messages out, the operator gets every one, and each observer every tenth."""

from __future__ import annotations

import re

import pytest

from bench.probes import fanout as fanout_probe

pytestmark = pytest.mark.e2e  # servers, observers and the tenant are processes of their own


def test_a_message_carries_the_time_it_was_made():
    message = fanout_probe.pb.StreamWrenchResponse.FromString(fanout_probe._message(7))
    assert message.samples[0].sequence == 7
    assert message.samples[0].sample_time.ToNanoseconds() > 0


def test_every_kind_streams_to_the_operator_and_the_observers(capsys):
    assert fanout_probe.main(["--observers", "3", "--seconds", "1", "--tenant", "0.2"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert [line.split()[0] for line in lines] == ["sync", "aio", "aio-fd"]
    for line in lines:
        assert int(re.search(r"server (\d+)% of a core", line).group(1)) > 0
        rate = float(re.search(r"operator +([\d.]+) Hz", line).group(1))
        p50, p99 = (float(v) for v in re.findall(r"p\d\d ([\d.]+)", line))
        observed = int(re.search(r"observers got (\d+)", line).group(1))
        assert 900 <= rate <= 1100  # one message a millisecond, every one of them received
        assert 0 < p50 <= p99
        # 3 observers at 100 Hz for at least the operator's 1.5 s (warm-up included)
        assert observed >= 3 * 100 * 1.5 * 0.8
