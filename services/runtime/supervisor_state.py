"""What the launcher knows about each child, shared with the station's services as a file.

The launcher (`make serve`) writes it whenever a child starts, ends, waits to restart or is
given up on; the DecisionServer reads it to say that a dependency it cannot reach is being
restarted (and how often it was), not merely unreachable. The file is JSON, replaced by rename
so a reader never sees half of it, at the path in TELEROBOT_SUPERVISOR_STATE (the launcher sets
it for its children). No grpc here.

    {"services": {"proxy_robot": {"state": "restarting", "restarts": 2,
                                  "last_exit": "killed by signal 9", "since": 1795449195.1}}}
"""

from __future__ import annotations

import json
import os
import tempfile
from dataclasses import asdict, dataclass
from pathlib import Path

SUPERVISOR_STATE_ENV = "TELEROBOT_SUPERVISOR_STATE"
# Set for a restarted child: how its previous process ended ("was killed by signal 9 (SIGKILL)").
RESTARTED_BECAUSE_ENV = "TELEROBOT_RESTARTED_BECAUSE"

RUNNING = "running"  # started and serving (or starting for the first time)
RESTARTING = "restarting"  # ended on its own; waiting for its back-off or starting again
GAVE_UP = "gave_up"  # failed too often: the station stops


@dataclass(frozen=True)
class ChildState:
    state: str
    restarts: int = 0  # how many times the launcher restarted it
    last_exit: str = ""  # how its last process ended, for people
    since: float = 0.0  # unix time of the last change


def write_state(path: Path, children: dict[str, ChildState]) -> None:
    """Replace the file with `children`' states (atomically)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    data = json.dumps({"services": {name: asdict(s) for name, s in children.items()}})
    fd, temporary = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.")
    with os.fdopen(fd, "w") as file:
        file.write(data)
    os.replace(temporary, path)


def read_state(path: Path | None = None) -> dict[str, ChildState]:
    """The children's states from `path` (default: TELEROBOT_SUPERVISOR_STATE); empty when no
    launcher supervises this process or the file is missing or unreadable."""
    if path is None:
        configured = os.environ.get(SUPERVISOR_STATE_ENV)
        if not configured:
            return {}
        path = Path(configured)
    try:
        services = json.loads(path.read_text())["services"]
        return {name: ChildState(**fields) for name, fields in services.items()}
    except (OSError, ValueError, KeyError, TypeError):
        return {}
