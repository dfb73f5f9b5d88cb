"""The impairment proxy on loopback, in front of a real gRPC health server and a plain TCP
echo server. Lower bounds on time are tight (the link must not be faster than its profile);
upper bounds are loose, as the machine is shared."""

from __future__ import annotations

import os
import socket
import threading
import time

import grpc
import pytest
from grpc_health.v1 import health_pb2, health_pb2_grpc

from services.impairment import ImpairmentProxy, LinkProfile
from services.runtime.server import create_server
from tests.conftest import wait_for
from tests.processes import refused_address

SERVING = health_pb2.HealthCheckResponse.SERVING
ONE_WAY_S = 0.05
CUT_S = 0.5


@pytest.fixture
def health_server():
    """A gRPC server with only health, SERVING; yields its host:port."""
    server, port = create_server("127.0.0.1:0", [])
    server.start()
    server.set_serving()
    yield f"127.0.0.1:{port}"
    server.stop(0)


@pytest.fixture
def delayed_proxy(health_server):
    """The health server behind a 50 ms delay each way."""
    link = LinkProfile(delay_s=ONE_WAY_S)
    with ImpairmentProxy("127.0.0.1:0", health_server, up=link, down=link) as proxy:
        yield proxy


@pytest.fixture
def health(delayed_proxy):
    """A health stub on a channel through the proxy, its connection already open; the
    channel's connectivity states from then on are in `stub.states`."""
    with grpc.insecure_channel(delayed_proxy.address) as channel:
        stub = health_pb2_grpc.HealthStub(channel)
        assert stub.Check(health_pb2.HealthCheckRequest(), timeout=5).status == SERVING
        stub.states = []
        channel.subscribe(stub.states.append)
        yield stub
        channel.unsubscribe(stub.states.append)


def timed_check(stub, **kwargs) -> float:
    started = time.monotonic()
    assert stub.Check(health_pb2.HealthCheckRequest(), **kwargs).status == SERVING
    return time.monotonic() - started


def test_a_call_takes_at_least_the_round_trip(health, delayed_proxy):
    for _ in range(3):
        assert 2 * ONE_WAY_S <= timed_check(health, timeout=5) < 1.0
    assert delayed_proxy.stats.connections == 1
    assert delayed_proxy.stats.bytes["up"] > 0 and delayed_proxy.stats.bytes["down"] > 0


def test_a_reset_cut_fails_the_open_stream_and_a_new_call_then_succeeds(health, delayed_proxy):
    stream = health.Watch(health_pb2.HealthCheckRequest(), timeout=10)
    assert next(stream).status == SERVING
    started = time.monotonic()
    delayed_proxy.cut(CUT_S, mode="reset")
    with pytest.raises(grpc.RpcError) as failure:
        next(stream)
    assert failure.value.code() == grpc.StatusCode.UNAVAILABLE
    assert time.monotonic() - started >= CUT_S
    assert not delayed_proxy.cutting  # the reset comes when the cut ends
    assert delayed_proxy.stats.reset_by_cuts == 1
    # A call made before the channel has seen its connection go can still be written to it and
    # fail ("Stream removed"); once it has, the next call reconnects.
    wait_for(lambda: any(state != grpc.ChannelConnectivity.READY for state in health.states),
             timeout_s=5,
             what=lambda: f"the channel to see the reset (states {health.states})")
    assert timed_check(health, timeout=5, wait_for_ready=True) >= 2 * ONE_WAY_S
    assert delayed_proxy.stats.connections == 2  # the channel reconnected


def test_a_stall_cut_delays_a_call_without_failing_it(health, delayed_proxy):
    started = time.monotonic()
    delayed_proxy.cut(CUT_S, mode="stall")
    assert delayed_proxy.cutting
    timed_check(health, timeout=CUT_S + 3)
    assert CUT_S <= time.monotonic() - started < CUT_S + 1.0
    assert delayed_proxy.stats.connections == 1  # the same connection resumed
    assert delayed_proxy.stats.reset_by_cuts == 0


def test_a_connection_opened_during_a_cut_is_held_until_it_ends(delayed_proxy):
    started = time.monotonic()
    delayed_proxy.cut(CUT_S, mode="reset")
    with grpc.insecure_channel(delayed_proxy.address) as channel:
        stub = health_pb2_grpc.HealthStub(channel)
        timed_check(stub, timeout=CUT_S + 3)
    assert time.monotonic() - started >= CUT_S + 2 * ONE_WAY_S
    assert delayed_proxy.stats.held == 1
    assert delayed_proxy.stats.reset_by_cuts == 0  # it was not open when the cut began


def test_a_refused_target_is_unavailable_to_the_client():
    with ImpairmentProxy("127.0.0.1:0", refused_address()) as proxy, \
            grpc.insecure_channel(proxy.address) as channel:
        with pytest.raises(grpc.RpcError) as failure:
            health_pb2_grpc.HealthStub(channel).Check(health_pb2.HealthCheckRequest(),
                                                     timeout=5)
        assert failure.value.code() == grpc.StatusCode.UNAVAILABLE
        wait_for(lambda: proxy.stats.refused_by_target >= 1, what="the refusal counted")


@pytest.fixture
def echo_server():
    """A plain TCP server that reads until EOF, sends it all back and closes."""
    listener = socket.create_server(("127.0.0.1", 0))

    def serve():
        with listener:
            try:
                connection, _ = listener.accept()
            except OSError:
                return
            with connection:
                received = bytearray()
                while chunk := connection.recv(65536):
                    received += chunk
                connection.sendall(received)

    thread = threading.Thread(target=serve, daemon=True)
    thread.start()
    yield f"127.0.0.1:{listener.getsockname()[1]}"
    listener.close()
    thread.join(timeout=5)


def test_bytes_pass_unchanged_in_order_at_the_capped_bandwidth(echo_server):
    payload = os.urandom(25_000)  # 0.2 s at 1 Mbit/s
    up = LinkProfile(bandwidth_bps=1e6, jitter_s=0.005, seed=2)
    with ImpairmentProxy("127.0.0.1:0", echo_server, up=up) as proxy:
        host, port = proxy.address.split(":")
        started = time.monotonic()
        with socket.create_connection((host, int(port)), timeout=5) as client:
            client.sendall(payload)
            client.shutdown(socket.SHUT_WR)  # the half-close travels, after the bytes
            echoed = bytearray()
            while chunk := client.recv(65536):
                echoed += chunk
        elapsed = time.monotonic() - started
    assert bytes(echoed) == payload
    assert 0.2 <= elapsed < 2.0
