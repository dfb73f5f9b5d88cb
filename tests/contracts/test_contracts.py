"""The contracts: generated code is current, buf lint passes, every RPC declares a lane."""

from __future__ import annotations

import filecmp
import subprocess

import pytest
from google.protobuf import descriptor_pool

from telerobot.v1 import (  # noqa: F401 - importing registers the descriptors
    decision_server_pb2,
    force_sensor_pb2,
    options_pb2,
    proxy_robot_pb2,
    stereo_camera_pb2,
)
from tests.processes import BUF, REPO

SERVICES = ["ProxyRobot", "ForceSensor", "StereoCamera", "DecisionServer"]


def _tree_differences(left, right) -> list[str]:
    """Paths that differ between two directory trees, new and missing files included."""
    compare = filecmp.dircmp(left, right, ignore=["__pycache__"])
    diffs = [f"only in {left}: {n}" for n in compare.left_only]
    diffs += [f"only in {right}: {n}" for n in compare.right_only]
    diffs += [f"differs: {n}" for n in compare.diff_files]
    _, mismatch, errors = filecmp.cmpfiles(left, right, compare.common_files, shallow=False)
    diffs += [f"differs: {n}" for n in mismatch + errors if f"differs: {n}" not in diffs]
    for sub in compare.common_dirs:
        diffs += _tree_differences(left / sub, right / sub)
    return diffs


@pytest.mark.e2e
def test_generated_code_is_what_make_gen_writes(tmp_path):
    subprocess.run(["make", "--no-print-directory", "-s", "gen", f"GEN_OUT={tmp_path}"],
                   cwd=REPO, check=True, capture_output=True)
    diffs = _tree_differences(REPO / "gen", tmp_path)
    assert not diffs, "gen/ is stale; run `make gen` and commit:\n" + "\n".join(diffs)


@pytest.mark.e2e
def test_buf_lint_passes():
    if not BUF.exists():
        pytest.fail("node_modules/.bin/buf is missing: run `make install`")
    result = subprocess.run([BUF, "lint"], cwd=REPO, capture_output=True, text=True)
    assert result.returncode == 0, result.stdout + result.stderr


@pytest.mark.parametrize("service", SERVICES)
def test_every_rpc_declares_its_lane(service):
    descriptor = descriptor_pool.Default().FindServiceByName(f"telerobot.v1.{service}")
    for method in descriptor.methods:
        lane = method.GetOptions().Extensions[options_pb2.default_lane]
        assert lane != options_pb2.LANE_UNSPECIFIED, f"{service}.{method.name} has no lane"


def test_only_emergency_stop_runs_on_the_emergency_lane():
    emergency = [
        f"{service}.{method.name}"
        for service in SERVICES
        for method in descriptor_pool.Default().FindServiceByName(f"telerobot.v1.{service}").methods
        if method.GetOptions().Extensions[options_pb2.default_lane] == options_pb2.LANE_EMERGENCY
    ]
    assert emergency == ["ProxyRobot.EmergencyStop"]
