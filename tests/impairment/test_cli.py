"""python -m services.impairment: its units, its up/down options and a run by hand."""

from __future__ import annotations

import argparse
import signal
import socket

import grpc
import pytest
from grpc_health.v1 import health_pb2, health_pb2_grpc

from services.impairment.__main__ import (
    build_parser,
    main,
    parse_bandwidth,
    parse_duration,
    profiles,
)
from services.impairment.link import LinkProfile
from services.runtime.server import create_server
from tests.conftest import wait_for
from tests.processes import start_process


@pytest.mark.parametrize("text, seconds", [("50ms", 0.05), ("3s", 3.0), ("0.5s", 0.5),
                                           ("250us", 250e-6), ("0", 0.0), ("10 MS", 0.01)])
def test_durations_need_a_unit(text, seconds):
    assert parse_duration(text) == pytest.approx(seconds)


@pytest.mark.parametrize("text", ["50", "5m", "fast", "-1s"])
def test_a_duration_without_a_known_unit_is_refused(text):
    with pytest.raises(argparse.ArgumentTypeError, match="50ms"):
        parse_duration(text)


def test_bandwidths_are_in_bits_per_second():
    assert parse_bandwidth("1mbit") == 1e6
    assert parse_bandwidth("500kbit") == 5e5
    assert parse_bandwidth("0") == 0.0
    with pytest.raises(argparse.ArgumentTypeError):
        parse_bandwidth("1mbps")  # tc reads bps as bytes: refused rather than guessed


def test_a_direction_s_own_option_wins_over_the_shared_one():
    args = build_parser().parse_args([
        "--listen", "127.0.0.1:0", "--target", "127.0.0.1:1", "--delay", "50ms",
        "--jitter", "5ms", "--down-delay", "80ms", "--up-bandwidth", "1mbit",
        "--stall-prob", "0.01", "--stall-for", "200ms", "--seed", "7"])
    up, down = profiles(args)
    assert up == LinkProfile(delay_s=0.05, jitter_s=0.005, bandwidth_bps=1e6,
                             stall_probability=0.01, stall_s=0.2, seed=7)
    assert down == LinkProfile(delay_s=0.08, jitter_s=0.005, stall_probability=0.01,
                               stall_s=0.2, seed=8)


@pytest.mark.e2e
def test_by_hand_it_says_where_it_listens_what_it_does_and_cuts_on_time():
    server, port = create_server("127.0.0.1:0", [])
    server.start()
    server.set_serving()
    proxy = start_process(["-m", "services.impairment", "--listen", "127.0.0.1:0",
                           "--target", f"127.0.0.1:{port}", "--delay", "20ms",
                           "--cut-at", "300ms", "--cut-for", "200ms", "--cut-mode", "reset"])
    try:
        address = proxy.wait_ready("impairment", timeout_s=30)
        proxy.wait_line("up (client -> target): delay 20 ms, unlimited bandwidth, seed 0")
        with grpc.insecure_channel(address) as channel:
            response = health_pb2_grpc.HealthStub(channel).Check(
                health_pb2.HealthCheckRequest(), timeout=5, wait_for_ready=True)
        assert response.status == health_pb2.HealthCheckResponse.SERVING
        proxy.wait_line("link cut for 0.2 s (reset)", timeout_s=10)
        proxy.wait_line("link back", timeout_s=10)
        assert proxy.stop(signal.SIGTERM) == 0
    finally:
        proxy.stop()
        server.stop(0)


@pytest.mark.e2e
def test_sigusr1_cuts_the_link_when_asked():
    proxy = start_process(["-m", "services.impairment", "--listen", "127.0.0.1:0",
                           "--target", "127.0.0.1:1", "--cut-for", "150ms"])
    try:
        proxy.wait_ready("impairment", timeout_s=30)
        def said(text: str) -> int:
            return sum(text in line for line in proxy.lines)

        for cuts in (1, 2):  # and again: each signal is one cut
            proxy.send_signal(signal.SIGUSR1)
            wait_for(lambda n=cuts: said("link cut for 0.15 s (stall)") == n, 10, f"cut {cuts}")
            wait_for(lambda n=cuts: said("link back") == n, 10, f"the link back after cut {cuts}")
        assert proxy.stop(signal.SIGTERM) == 0
    finally:
        proxy.stop()


@pytest.mark.e2e
def test_sigusr2_prints_what_it_carried_so_far():
    with socket.create_server(("127.0.0.1", 0)) as target:  # (the kernel takes the bytes)
        proxy = start_process(["-m", "services.impairment", "--listen", "127.0.0.1:0",
                               "--target", f"127.0.0.1:{target.getsockname()[1]}"])
        try:
            host, port = proxy.wait_ready("impairment", timeout_s=30).rsplit(":", 1)
            with socket.create_connection((host, int(port)), timeout=5) as connection:
                connection.sendall(b"x" * 1000)

                def told_1000() -> bool:
                    proxy.send_signal(signal.SIGUSR2)
                    return any("'up': 1000" in line for line in proxy.lines
                               if line.startswith("stats:"))

                wait_for(told_1000, 10, "the 1000 bytes in its stats")
            assert proxy.stop(signal.SIGTERM) == 0  # still serving after the signals
        finally:
            proxy.stop()


@pytest.mark.parametrize("listen", ["0.0.0.0:0", "10.0.0.2:50061", "[::]:0"])
def test_beyond_loopback_it_is_refused_unless_allowed(listen, capsys):
    """As every other port of the station: beyond loopback only when told so (it forwards
    whoever reaches it to the target)."""
    assert main(["--listen", listen, "--target", "127.0.0.1:50051"]) == 2
    assert "--allow-network" in capsys.readouterr().err
    assert build_parser().parse_args(
        ["--listen", listen, "--target", "127.0.0.1:50051", "--allow-network"]).allow_network
