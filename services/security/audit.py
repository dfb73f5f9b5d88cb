"""The audit log: one JSON line per command-class call (lock, move, stop, reset, assistance,
config, recording) saying when, who, with what role, which method and how it ended.

Each service writes its own files (rotated by size through the standard RotatingFileHandler,
since rotation is safe only with one writing process per file):

- <audit dir>/<service>.jsonl holds the commands: every one in full (`record`), except the
  calls that come at up to 1 kHz from one source, which are summarized (`summarized`): the
  station's own calls on its inner ports (the DecisionServer's moves to ProxyRobot), and, in
  plaintext, where the station cannot be told from anyone else, every caller's on those ports.
  These are counted per source (identity, or the peer's address when it has none), the peer's
  host, method and interval (SUMMARY_INTERVAL_S from the first call): the first call of each
  outcome is written in full at once, and the interval's calls as one summary line when it
  ends (the count, the method, the outcomes, a few peers, the first and last time);
- <audit dir>/<service>.refusals.jsonl holds the refused calls (no credentials, a bad token, a
  role too low, no room), summarized per source and interval the same way (`refused`): the
  first refusal of each kind (method and outcome) is written in full at once, up to MAX_KINDS
  kinds, then one summary line (the count, the methods, the outcomes, a few peers, the first
  and last time).

A flood of refusals so never rotates a command out: it has its own files, and it writes at most
MAX_KINDS + 1 lines per source per interval, from at most MAX_SOURCES sources (the others are
summed as one). Summarized calls write at most MAX_KINDS + 1 lines per source, host and method
per interval, from at most MAX_SOURCES of them.

Writing never raises: a full disk must not fail a stop, so a failed write is logged as a
warning instead, once per run of failures.
"""

from __future__ import annotations

import collections
import datetime
import itertools
import json
import logging
import math
import os
import queue
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from logging.handlers import RotatingFileHandler
from pathlib import Path

from services.common.inbox import queued_now

DEFAULT_AUDIT_DIR = "var/audit"
AUDIT_DIR_ENV = "TELEROBOT_AUDIT_DIR"
MAX_DETAIL_CHARS = 500
MAX_BYTES = 10_000_000  # each file rotates at this size
BACKUPS = 5  # and this many rotated files are kept, for commands and refusals each
# The writer gathers the records made over this long and writes them together: at 1 kHz of
# commands, a wake-up and a write (a seek and a flush, each handing the interpreter lock
# away) per record cost the calls more than the records do.
GATHER_S = 0.005
# Refusals: one summary per source per interval; at most this many sources an interval.
SUMMARY_INTERVAL_S = 60.0
MAX_SOURCES = 256
MAX_KINDS = 8  # refusals of a source written in full in an interval: the first of each kind
OTHER_SOURCES = "(other sources)"
MAX_METHODS = 32  # distinct methods a summary names; the rest are counted under OTHER_METHODS
OTHER_METHODS = "(other methods)"
MAX_PEERS = 8  # peers a summary names
# While summaries are open, the writer looks at the clock this often (real time) to write those
# whose interval ended, when no record comes to do it.
POLL_S = 1.0

_log = logging.getLogger(__name__)
_instance_numbers = itertools.count()


def audit_dir() -> Path:
    """The audit directory: env TELEROBOT_AUDIT_DIR, else var/audit under the cwd."""
    return Path(os.environ.get(AUDIT_DIR_ENV) or DEFAULT_AUDIT_DIR)


def audit_log_for(service: str) -> AuditLog:
    """The audit log of one service ("decision_server"): <audit dir>/<service>.jsonl, and its
    refusals in <service>.refusals.jsonl."""
    if not service or service != Path(service).name or service.startswith("."):
        raise ValueError(f"the service name {service!r} must be a plain file name")
    return AuditLog(audit_dir() / f"{service}.jsonl")


def refusals_path_for(path: Path) -> Path:
    """Where the refusals of the audit log at `path` go: <stem>.refusals<suffix>."""
    path = Path(path)
    return path.with_name(f"{path.stem}.refusals{path.suffix}")


def _open_private(path: str, flags: int) -> int:
    return os.open(path, flags, 0o600)  # owner only, the first file and each one after rotation


def _iso(when: float) -> str:
    return datetime.datetime.fromtimestamp(when, datetime.UTC).isoformat(timespec="microseconds")


def _host(peer: str) -> str:
    """A peer without its port ("ipv4:10.0.0.2:5000" -> "ipv4:10.0.0.2"): a client's
    connections are one source."""
    if peer.startswith(("ipv4:", "ipv6:")) and peer.count(":") >= 2:
        return peer.rsplit(":", 1)[0]
    return peer


class _AuditFileHandler(RotatingFileHandler):
    """A RotatingFileHandler whose files are 0600, and which reports a failed write as one
    warning per run of failures instead of a traceback on stderr for each record."""

    def __init__(self, path: Path, max_bytes: int, backups: int, delay: bool = False):
        self._failing = False
        self._failed_this_record = False
        super().__init__(path, maxBytes=max_bytes, backupCount=backups, encoding="utf-8",
                         delay=delay)

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


class _File:
    """One rotated file of the log, written through a logger of its own."""

    def __init__(self, path: Path, max_bytes: int, backups: int, delay: bool):
        self.handler = _AuditFileHandler(path, max_bytes, backups, delay)
        self.handler.setFormatter(logging.Formatter("%(message)s"))
        self._chunk_bytes = max(1, max_bytes // 4)
        # A logger of its own, outside the logging tree (not registered by name, no parent):
        # audit lines never reach the console, and no other handler reaches this file.
        self._logger = logging.Logger(f"{__name__}.{next(_instance_numbers)}", logging.INFO)
        self._logger.propagate = False
        self._logger.addHandler(self.handler)

    def write(self, lines: list[str]) -> None:
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

    def close(self) -> None:
        self._logger.removeHandler(self.handler)
        self.handler.close()


@dataclass
class _Window:
    """The calls of one source (and, for summarized commands, one host and method) in one
    interval."""

    first: float
    source: str
    identity: str
    role: str
    last: float = 0.0
    count: int = 0
    methods: collections.Counter = field(default_factory=collections.Counter)
    outcomes: collections.Counter = field(default_factory=collections.Counter)
    peers: list[str] = field(default_factory=list)
    detail: str = ""
    kinds: set[tuple[str, str]] = field(default_factory=set)  # (method, outcome) in full

    def first_of_its_kind(self, method: str, outcome: str) -> bool:
        """Whether a call of this (method, outcome) is to be written in full."""
        if (method, outcome) in self.kinds or len(self.kinds) >= MAX_KINDS:
            return False
        self.kinds.add((method, outcome))
        return True

    def add(self, when: float, method: str, outcome: str, peer: str, detail: str) -> None:
        self.last = max(self.last, when)
        self.count += 1
        if method in self.methods or len(self.methods) < MAX_METHODS:
            self.methods[method[:MAX_DETAIL_CHARS]] += 1
        else:
            self.methods[OTHER_METHODS] += 1
        self.outcomes[outcome[:MAX_DETAIL_CHARS]] += 1
        if peer and len(self.peers) < MAX_PEERS and peer not in self.peers:
            self.peers.append(peer[:MAX_DETAIL_CHARS])
        self.detail = detail


class _Summaries:
    """Calls counted per key and interval (a key's interval starts at its first call), and the
    lines they make: the first call of each kind (method, outcome) of a key's interval in full,
    then one summary line when the interval ends (none when every call was in full). At most
    `max_keys` keys an interval; the calls of any further ones are summed as OTHER_SOURCES.

    Thread-safe: summarized commands are counted on their calls' own threads (at 1 kHz, a
    hand-over to the writer per call would cost more than the count), refusals on the
    writer's."""

    def __init__(self, interval_s: float, max_keys: int):
        self._interval_s = interval_s
        self._max_keys = max_keys
        self._lock = threading.Lock()
        self._windows: collections.OrderedDict[tuple, _Window] = collections.OrderedDict()

    def __bool__(self) -> bool:  # whether a summary is open
        return bool(self._windows)

    def count(self, when: float, key: tuple, source: str, identity, role, method, outcome,
              peer, detail) -> list[str]:
        """The lines one call makes: the summaries it ends, and itself in full when it is the
        first of its kind in its key's interval."""
        method, outcome, peer, detail = str(method), str(outcome), str(peer), str(detail)
        with self._lock:
            lines = self._expire(when)
            window = self._windows.get(key)
            if window is None and len(self._windows) >= self._max_keys:
                key = (OTHER_SOURCES,)
                window = self._windows.get(key)
            if window is None:
                if key == (OTHER_SOURCES,):
                    window = _Window(when, OTHER_SOURCES, "", "")
                else:
                    window = _Window(when, source, str(identity), str(role))
                self._windows[key] = window
            if window.first_of_its_kind(method, outcome):
                lines += _line(when, identity, role, method, outcome, peer, detail)
            window.add(when, method, outcome, peer, detail)
        return lines

    def expire(self, now: float) -> list[str]:
        """The summaries of the intervals that ended by `now`, which are then closed."""
        with self._lock:
            return self._expire(now)

    def _expire(self, now: float) -> list[str]:
        lines = []
        while self._windows:
            key, window = next(iter(self._windows.items()))
            if window.first + self._interval_s > now:
                break
            del self._windows[key]
            if window.count > len(window.kinds):  # else every one is already in full
                lines += _summary(window)
        return lines


class AuditLog:
    """Appends audit records to `path`, and summaries of refusals to `refusals_path`,
    thread-safe. A call hands its record to a writer thread and goes on: the file's system
    calls (a stat and a seek for rotation, the write, the flush) each give the interpreter lock
    away and cost a command about 0.3 ms of round trip when done on the call's own thread
    (measured at 1 kHz on ProxyRobot). The writer gathers the records of GATHER_S and writes
    them together. A summarized call is only counted on its own thread; the writer hears of it
    only when it makes a line. `flush()` waits until everything recorded so far is written
    (and the summaries whose interval has ended by `clock`).

    `clock` gives the records' times (wall-clock seconds) and ends the summaries' intervals."""

    def __init__(self, path: Path, max_bytes: int = MAX_BYTES, backups: int = BACKUPS,
                 clock: Callable[[], float] = time.time,
                 summary_interval_s: float = SUMMARY_INTERVAL_S, max_sources: int = MAX_SOURCES):
        if max_bytes <= 0 or backups < 1:
            # the stdlib handler never rotates with either at 0: the file would grow forever
            raise ValueError(f"max_bytes ({max_bytes}) and backups ({backups}) must be positive")
        if summary_interval_s <= 0 or max_sources < 1:
            raise ValueError(f"summary_interval_s ({summary_interval_s}) and max_sources "
                             f"({max_sources}) must be positive")
        path = Path(path)
        path.parent.mkdir(parents=True, exist_ok=True)
        self._clock = clock
        self._commands = _File(path, max_bytes, backups, delay=False)
        # Opened at the first refusal: a station nobody knocks at has no refusals file.
        self._refusals = _File(refusals_path_for(path), max_bytes, backups, delay=True)
        self._handler = self._commands.handler
        # The open summaries: of refusals (the writer thread's alone), and of summarized
        # commands (counted on the calls' threads).
        self._refused = _Summaries(summary_interval_s, max_sources)
        self._summarized = _Summaries(summary_interval_s, max_sources)
        self._pending: queue.SimpleQueue = queue.SimpleQueue()
        self._closed = False
        self._writer = threading.Thread(target=self._write_records, daemon=True,
                                        name=f"audit-{path.stem}")
        self._writer.start()

    @property
    def path(self) -> Path:
        return Path(self._commands.handler.baseFilename)

    @property
    def refusals_path(self) -> Path:
        return Path(self._refusals.handler.baseFilename)

    def record(self, *, identity: str, role: str, method: str, outcome: str, peer: str = "",
               detail: str = "") -> None:
        """Append one command record, in full (on the writer thread). Never raises: auditing
        must not fail the call it records."""
        if not self._closed:
            self._pending.put((_RECORD, self._clock(), identity, role, method, outcome, peer,
                               detail))

    def summarized(self, *, identity: str, role: str, method: str, outcome: str,
                   peer: str = "", detail: str = "") -> None:
        """Count one command in the commands' summary of its source (its identity, or its
        peer's address when it has none), its peer's host and its method; the first of each
        outcome in the interval is also written in full. For calls that come at up to 1 kHz
        from one source (the station's own). Never raises."""
        if self._closed:
            return
        try:
            host = _host(str(peer))
            source = str(identity) or host or "(unknown)"
            lines = self._summarized.count(self._clock(), (source, host, str(method)), source,
                                           identity, role, method, outcome, peer, detail)
        except Exception:
            _log.warning("cannot count a call of %r", method, exc_info=True)
            return
        if lines:
            self._pending.put((_LINES, lines))

    def refused(self, *, identity: str, role: str, method: str, outcome: str, peer: str = "",
                detail: str = "") -> None:
        """Count one refused call in its source's summary (its identity, or its peer's address
        when it has none); the first of its kind (method, outcome) in the source's interval is
        also written in full. Never raises."""
        if not self._closed:
            self._pending.put((_REFUSED, self._clock(), identity, role, method, outcome, peer,
                               detail))

    def flush(self, timeout_s: float = 5.0) -> None:
        """Wait until every record made before this call is written, and every summary whose
        interval has ended."""
        written = threading.Event()
        self._pending.put(written)
        written.wait(timeout_s)

    def close(self) -> None:
        """Write what is pending and every open summary, and close the files; later records are
        dropped."""
        if self._closed:
            return
        self._closed = True
        self._pending.put(None)
        self._writer.join(5.0)
        self._commands.close()
        self._refusals.close()

    def _write_records(self) -> None:
        while True:
            try:
                first = self._pending.get(
                    timeout=POLL_S if self._refused or self._summarized else None)
            except queue.Empty:  # quiet: the summaries whose interval ended are due
                now = self._clock()
                self._commands.write(self._summarized.expire(now))
                self._refusals.write(self._refused.expire(now))
                continue
            if isinstance(first, tuple):
                time.sleep(GATHER_S)  # let the calls meanwhile join this write
            commands: list[str] = []
            refusals: list[str] = []
            for item in [first, *queued_now(self._pending)]:
                if isinstance(item, tuple):
                    if item[0] is _RECORD:
                        commands += _line(*item[1:])
                    elif item[0] is _REFUSED:
                        refusals += self._refusal(*item[1:])
                    else:  # _LINES: made on a call's thread
                        commands += item[1]
                    continue
                # what came before a flush or the close is written first
                now = math.inf if item is None else self._clock()
                commands += self._summarized.expire(now)
                refusals += self._refused.expire(now)
                self._commands.write(commands)
                self._refusals.write(refusals)
                commands, refusals = [], []
                if item is None:
                    return
                item.set()
            self._commands.write(commands)
            self._refusals.write(refusals)

    def _refusal(self, when, identity, role, method, outcome, peer, detail) -> list[str]:
        """The lines one refusal makes: the summaries it ends, and itself in full when it is the
        first of its kind in its source's interval."""
        try:
            source = str(identity) or _host(str(peer)) or "(unknown)"
            return self._refused.count(when, (source,), source, identity, role, method,
                                       outcome, peer, detail)
        except Exception:
            _log.warning("cannot count a refusal of %r", method, exc_info=True)
            return []


# What the writer's queue carries: a record to write in full, a refusal to count, or lines
# made on a call's thread (a summarized call's).
_RECORD, _REFUSED, _LINES = "record", "refused", "lines"


def _summary(window: _Window) -> list[str]:
    """An interval's summary as its JSON line ([] if it cannot be made: said as a warning)."""
    try:
        return [json.dumps({
            "first": _iso(window.first), "last": _iso(window.last),
            "source": window.source[:MAX_DETAIL_CHARS],
            "identity": window.identity[:MAX_DETAIL_CHARS], "role": window.role,
            "count": window.count, "methods": dict(window.methods),
            "outcomes": dict(window.outcomes), "peers": window.peers,
            "detail": window.detail[:MAX_DETAIL_CHARS],
        })]
    except Exception:
        _log.warning("cannot make the summary of %r", window.source, exc_info=True)
        return []


def _line(when, identity, role, method, outcome, peer, detail) -> list[str]:
    """One record as its JSON line ([] if it cannot be made: said as a warning)."""
    try:
        return [json.dumps({
            "time": _iso(when),
            "identity": str(identity), "role": str(role), "method": str(method),
            "outcome": str(outcome), "peer": str(peer),
            "detail": str(detail)[:MAX_DETAIL_CHARS],
        })]  # json escapes newlines and quotes, so a client's string cannot forge a line
    except Exception:
        _log.warning("cannot make an audit record for %r", method, exc_info=True)
        return []
