"""Writing a file so that nobody reads it half-written or before its mode is set (secrets,
the operator's saved camera identification)."""

from __future__ import annotations

import os
import tempfile
from pathlib import Path


def replace_file(path: Path, data: bytes, mode: int = 0o600) -> None:
    """Replace `path` with `data`: through a new file of a random name beside it (mkstemp:
    created exclusively and 0600, so no link or file planted there is followed or reused, and
    nobody reads it meanwhile), flushed to disk, given `mode`, then renamed into place, so a
    reader never sees half a file and a crash leaves the old one."""
    handle, temporary = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        with os.fdopen(handle, "wb") as file:
            file.write(data)
            file.flush()
            os.fsync(file.fileno())
        if mode != 0o600:
            os.chmod(temporary, mode)
        os.replace(temporary, path)
    except BaseException:
        Path(temporary).unlink(missing_ok=True)
        raise
