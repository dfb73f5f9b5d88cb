"""Starting franka-sim from the project's own venv: the process runs in `.venv-franka` (make
install makes it), and is up once it says so. Imported by the tests and the bench, never by
franka-sim's own side (__main__.py)."""

from __future__ import annotations

from pathlib import Path

from services.franka_sim.__main__ import READY_LINE
from services.runtime import children

REPO = Path(__file__).resolve().parents[2]
FRANKA_PYTHON = REPO / ".venv-franka" / "bin" / "python"
START_TIMEOUT_S = 60.0


def start_franka_sim(host: str, *args: str, max_lines: int | None = 200) -> children.Child:
    """`python -m services.franka_sim --host HOST ARGS…` from `.venv-franka`, once it serves
    libfranka's port; ChildFailed (and nothing left running) if it does not."""
    sim = children.start("franka_sim", ["-m", "services.franka_sim", "--host", host, *args],
                         cwd=REPO, python=str(FRANKA_PYTHON), own_group=False,
                         max_lines=max_lines)
    try:
        sim.wait_line(READY_LINE, timeout_s=START_TIMEOUT_S)
    except children.ChildFailed:
        sim.stop()
        raise
    return sim
