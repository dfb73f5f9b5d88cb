"""The audit log: one JSON line per command-class call (lock, move, stop, reset, assistance,
config, recording) saying when, who, with what role, which method and how it ended.

Each service writes its own file, <audit dir>/<service>.jsonl (rotated by size through the
standard RotatingFileHandler), since rotation is safe only with one writing process per file.
Writing never raises: a full disk must not fail a stop, so a failed write is logged as a
warning instead, once per run of failures.
"""

from __future__ import annotations

import datetime
import itertools
import json
import logging
import os
import queue
import threading
import time
from collections.abc import Callable
from logging.handlers import RotatingFileHandler
from pathlib import Path

from services.common.inbox import queued_now

DEFAULT_AUDIT_DIR = "var/audit"
AUDIT_DIR_ENV = "TELEROBOT_AUDIT_DIR"
MAX_DETAIL_CHARS = 500
# The writer gathers the records made over this long and writes them together: at 1 kHz of
# commands, a wake-up and a write (a seek and a flush, each handing the interpreter lock
# away) per record cost the calls more than the records do.
GATHER_S = 0.005

_log = logging.getLogger(__name__)
_instance_numbers = itertools.count()


def audit_dir() -> Path:
    """The audit directory: env TELEROBOT_AUDIT_DIR, else var/audit under the cwd."""
    return Path(os.environ.get(AUDIT_DIR_ENV) or DEFAULT_AUDIT_DIR)


def audit_log_for(service: str) -> AuditLog:
    """The audit log of one service ("decision_server"): <audit dir>/<service>.jsonl."""
    if not service or service != Path(service).name or service.startswith("."):
        raise ValueError(f"the service name {service!r} must be a plain file name")
    return AuditLog(audit_dir() / f"{service}.jsonl")


def _open_private(path: str, flags: int) -> int:
    return os.open(path, flags, 0o600)  # owner only, the first file and each one after rotation


class _AuditFileHandler(RotatingFileHandler):
    """A RotatingFileHandler whose files are 0600, and which reports a failed write as one
    warning per run of failures instead of a traceback on stderr for each record."""

    def __init__(self, path: Path, max_bytes: int, backups: int):
        self._failing = False
        self._failed_this_record = False
        super().__init__(path, maxBytes=max_bytes, backupCount=backups, encoding="utf-8")

    def _open(self):
        return open(self.baseFilename, self.mode, encoding=self.encoding, errors=self.errors,
                    opener=_open_private)

    def emit(self, record: logging.LogRecord) -> None:
        self._failed_this_record = False
        super().emit(record)  # calls handleError instead of raising
        if not self._failed_this_record:
            self._failing = False

    def handleError(self, record: logging.LogRecord) -> None:
        self._failed_this_record = True
        if not self._failing:
            self._failing = True
            _log.warning("cannot write the audit log %s; records are lost until it can",
                         self.baseFilename, exc_info=True)


class AuditLog:
    """Appends audit records to `path`, thread-safe. A call hands its record to a writer
    thread and goes on: the file's system calls (a stat and a seek for rotation, the write,
    the flush) each give the interpreter lock away and cost a command about 0.3 ms of round
    trip when done on the call's own thread (measured at 1 kHz on ProxyRobot). The writer
    gathers the records of GATHER_S and writes them together. `flush()` waits until
    everything recorded so far is written."""

    def __init__(self, path: Path, max_bytes: int = 10_000_000, backups: int = 5,
                 clock: Callable[[], float] = time.time):
        if max_bytes <= 0 or backups < 1:
            # the stdlib handler never rotates with either at 0: the file would grow forever
            raise ValueError(f"max_bytes ({max_bytes}) and backups ({backups}) must be positive")
        path = Path(path)
        path.parent.mkdir(parents=True, exist_ok=True)
        self._clock = clock
        self._handler = _AuditFileHandler(path, max_bytes, backups)
        self._chunk_bytes = max(1, max_bytes // 4)
        self._handler.setFormatter(logging.Formatter("%(message)s"))
        # A logger of its own, outside the logging tree (not registered by name, no parent):
        # audit lines never reach the console, and no other handler reaches this file.
        self._logger = logging.Logger(f"{__name__}.{next(_instance_numbers)}", logging.INFO)
        self._logger.propagate = False
        self._logger.addHandler(self._handler)
        self._pending: queue.SimpleQueue = queue.SimpleQueue()
        self._closed = False
        self._writer = threading.Thread(target=self._write_records, daemon=True,
                                        name=f"audit-{path.stem}")
        self._writer.start()

    @property
    def path(self) -> Path:
        return Path(self._handler.baseFilename)

    def record(self, *, identity: str, role: str, method: str, outcome: str, peer: str = "",
               detail: str = "") -> None:
        """Append one record (on the writer thread). Never raises: auditing must not fail the
        call it records."""
        if not self._closed:
            self._pending.put((self._clock(), identity, role, method, outcome, peer, detail))

    def flush(self, timeout_s: float = 5.0) -> None:
        """Wait until every record made before this call is written."""
        written = threading.Event()
        self._pending.put(written)
        written.wait(timeout_s)

    def close(self) -> None:
        """Write what is pending and close the file; later records are dropped."""
        if self._closed:
            return
        self._closed = True
        self._pending.put(None)
        self._writer.join(5.0)
        self._logger.removeHandler(self._handler)
        self._handler.close()

    def _write_records(self) -> None:
        while True:
            items = [self._pending.get()]
            if isinstance(items[0], tuple):
                time.sleep(GATHER_S)  # let the calls meanwhile join this write
            items += queued_now(self._pending)
            lines: list[str] = []
            for item in items:
                if isinstance(item, tuple):
                    lines += self._line(*item)
                    continue
                self._write(lines)  # what came before a flush or the close is written first
                lines = []
                if item is None:
                    return
                item.set()
            self._write(lines)

    def _line(self, when, identity, role, method, outcome, peer, detail) -> list[str]:
        """One record as its JSON line ([] if it cannot be made: said as a warning)."""
        try:
            return [json.dumps({
                "time": datetime.datetime.fromtimestamp(when, datetime.UTC)
                .isoformat(timespec="microseconds"),
                "identity": str(identity), "role": str(role), "method": str(method),
                "outcome": str(outcome), "peer": str(peer),
                "detail": str(detail)[:MAX_DETAIL_CHARS],
            })]  # json escapes newlines and quotes, so a client's string cannot forge a line
        except Exception:
            _log.warning("cannot make an audit record for %r", method, exc_info=True)
            return []

    def _write(self, lines: list[str]) -> None:
        """`lines` in as few writes as keep each file under its size: a write is at most a
        quarter of it, so the handler's rollover, which checks before each write, still
        holds."""
        chunk: list[str] = []
        size = 0
        for line in lines:
            if chunk and size + len(line) + 1 > self._chunk_bytes:
                self._logger.info("\n".join(chunk))
                chunk, size = [], 0
            chunk.append(line)
            size += len(line) + 1
        if chunk:
            self._logger.info("\n".join(chunk))
