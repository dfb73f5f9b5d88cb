"""The client SDK and the contracts' Python side load without the slave station's libraries:
an operator needs only grpcio, protobuf, numpy and the generated code."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

pytestmark = pytest.mark.e2e

ROOT = Path(__file__).resolve().parents[2]
HEAVY = ("pinocchio", "mujoco", "cv2")


@pytest.mark.parametrize("module", ["clients.python", "wire"])
def test_importing_loads_no_heavy_library(module):
    code = (f"import json, sys; import {module}; "
            f"print(json.dumps(sorted(m for m in {HEAVY!r} if m in sys.modules)))")
    result = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True,
                            text=True, timeout=60)
    assert result.returncode == 0, result.stderr
    assert json.loads(result.stdout.strip().splitlines()[-1]) == []
