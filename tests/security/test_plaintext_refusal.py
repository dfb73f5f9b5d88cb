"""No plaintext beyond loopback, for real processes: a service asked to listen on 0.0.0.0 or on a
network namespace's address without TLS refuses to start; with TLS, or with the loudly named
flag, it starts there.

The namespace test makes its own namespace joined to this one by a veth pair (root only), with
addresses of a private /30 that exist nowhere else; it removes them after.
"""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

from services.security.pki import init
from tests.netns import linked_namespaces, python_in_namespace, unavailable_reason
from tests.processes import REPO, start_process, unique_shm_name

pytestmark = pytest.mark.e2e

NAMESPACE_ADDRESS = "10.213.7.2"
HOST_ADDRESS = "10.213.7.1"


def _world_args(address: str) -> list[str]:
    return ["-m", "services.world", "--address", address]


def test_a_service_refuses_to_listen_on_every_interface_in_plaintext():
    result = subprocess.run(
        [sys.executable, *_world_args("0.0.0.0:0")], cwd=REPO, capture_output=True, text=True,
        timeout=60, env={**os.environ, "TELEROBOT_WORLD_SHM": unique_shm_name()})
    assert result.returncode == 2, result.stderr[-2000:]
    assert "refusing to listen on 0.0.0.0:0 without TLS" in result.stderr
    assert "TELEROBOT_READY" not in result.stdout


@pytest.fixture
def namespace():
    if (reason := unavailable_reason()) is not None:
        pytest.skip(reason)
    with linked_namespaces(HOST_ADDRESS, NAMESPACE_ADDRESS,
                           left_in_this_namespace=True) as (_, name):
        yield name


def test_in_a_namespace_plaintext_is_refused_and_tls_or_the_flag_starts(namespace, tmp_path):
    address = f"{NAMESPACE_ADDRESS}:0"
    env = {"TELEROBOT_WORLD_SHM": unique_shm_name()}
    refused = start_process(python_in_namespace(namespace, _world_args(address)), env, "world")
    assert refused.exited.wait(60) and refused.returncode == 2  # its output read to the end
    assert any("refusing to listen on 10.213.7.2:0 without TLS" in line
               for line in refused.lines)

    init(tmp_path / "pki")
    variants = {
        "tls": {"TELEROBOT_TLS_DIR": str(tmp_path / "pki"),
                "TELEROBOT_AUDIT_DIR": str(tmp_path / "audit")},
        "flag": {"TELEROBOT_ALLOW_PLAINTEXT_NETWORK": "1"},
    }
    for what, settings in variants.items():
        world = start_process(python_in_namespace(namespace, _world_args(address)),
                              {**env, **settings, "TELEROBOT_WORLD_SHM": unique_shm_name()},
                              "world")
        try:
            bound = world.wait_ready(timeout_s=60)
            assert bound.startswith(f"{NAMESPACE_ADDRESS}:"), (what, bound)
            warned = any("PLAINTEXT beyond loopback" in line for line in world.lines)
            assert warned == (what == "flag"), (what, world.lines[-20:])
        finally:
            world.stop()
