"""A Zenoh router in the test's own process, and client sessions through it."""

from __future__ import annotations

import pytest
import zenoh

from services.security import pki
from services.zenoh_router.__main__ import listening_on
from wire.observation import SessionPlan, ZenohTls, client

# The tests' puts stand for the station's and must all arrive, whatever the machine's load:
# they wait for room in Zenoh's queue instead of being dropped (the station's own do not).
RELIABLY = zenoh.CongestionControl.BLOCK


def routing(plan: SessionPlan):
    """A router of `plan` in this process: its endpoint (a port 0 made real), until closed."""
    config = plan.config()
    config.insert_json5("adminspace/enabled", "true")  # (read by listening_on)
    session = zenoh.open(config)
    try:
        yield listening_on(session)[0]
    finally:
        session.close()


@pytest.fixture
def router():
    """A router in this process on a free loopback port: its endpoint."""
    yield from routing(SessionPlan("router", listen=("tcp/127.0.0.1:0",)))


@pytest.fixture
def sessions(router):
    """Client sessions through the router, closed after the test."""
    opened = []

    def open_one() -> zenoh.Session:
        opened.append(client(router))
        return opened[-1]

    yield open_one
    for session in opened:
        session.close()


@pytest.fixture(scope="module")
def pki_dir(tmp_path_factory):
    """The station's PKI (`make certs`' certificates) in a directory of the module's."""
    directory = tmp_path_factory.mktemp("pki")
    pki.init(directory)
    return directory


@pytest.fixture
def tls_router(pki_dir):
    """A TLS router in this process, with the access rules: its endpoint."""
    yield from routing(SessionPlan("router", listen=("tls/127.0.0.1:0",),
                                   tls=ZenohTls(pki_dir, "zenoh_router")))
