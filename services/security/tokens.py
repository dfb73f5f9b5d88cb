"""Bearer tokens for clients that cannot hold a client certificate (browsers, scripts).

A client presents `authorization: Bearer trb_...` over TLS; the runtime passes the token to
`TokenStore.verify`, which answers who it speaks for. The tokens file (JSON, mode 0600) keeps
only each token's SHA-256, so a copy of the file lets nobody in. Every process that opens the
file sees the others' changes: a token revoked from the command line stops working in a
running server at its next call.

    python -m services.security.tokens issue --identity alice --role operator --ttl 8h
    python -m services.security.tokens list
    python -m services.security.tokens revoke alice        # or a token id from `list`
"""

from __future__ import annotations

import argparse
import contextlib
import datetime
import fcntl
import hashlib
import hmac
import json
import logging
import math
import os
import re
import secrets
import sys
import threading
import time
import unicodedata
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path

from services.security.roles import Role
from wire.errors import (
    FailedPreconditionError,
    InvalidArgumentError,
    TelerobotError,
    UnauthenticatedError,
)
from wire.files import replace_file

DEFAULT_TOKENS_FILE = "var/tokens.json"
TOKENS_FILE_ENV = "TELEROBOT_TOKENS_FILE"
TOKEN_PREFIX = "trb_"  # recognisable in a leaked log line or a secret scanner
MAX_IDENTITY_CHARS = 64
TOKEN_ID_CHARS = 8
FORMAT = "telerobot-tokens"
VERSION = 1

_TOKEN_SHAPE = re.compile(re.escape(TOKEN_PREFIX) + r"[A-Za-z0-9_-]{43}")  # token_urlsafe(32)
_DIGEST_SHAPE = re.compile(r"[0-9a-f]{64}")
_CLI = "python -m services.security.tokens"
_log = logging.getLogger(__name__)


def tokens_file() -> Path:
    """The tokens file: env TELEROBOT_TOKENS_FILE, else var/tokens.json under the cwd."""
    return Path(os.environ.get(TOKENS_FILE_ENV) or DEFAULT_TOKENS_FILE)


@dataclass(frozen=True)
class TokenGrant:
    """Who a valid token speaks for."""

    identity: str
    role: Role
    expires_at: float  # unix seconds (wall clock)


@dataclass(frozen=True)
class TokenEntry:
    """One issued token as `list` shows it: never the secret."""

    token_id: str  # the first hex digits of the hash: public, enough to revoke one token
    identity: str
    role: Role
    expires_at: float
    created_at: float


@dataclass(frozen=True)
class _Stored:
    digest: str
    entry: TokenEntry


@dataclass(frozen=True)
class _Snapshot:
    signature: tuple[int, int, int] | None  # (inode, mtime_ns, size); None: no file
    by_digest: dict[str, _Stored]


def _signature_of(status: os.stat_result) -> tuple[int, int, int]:
    # Every write replaces the file, so the inode changes even if mtime and size do not.
    return (status.st_ino, status.st_mtime_ns, status.st_size)


def _signature(path: Path) -> tuple[int, int, int] | None:
    try:
        return _signature_of(os.stat(path))
    except FileNotFoundError:
        return None


def _digest(token: str) -> str:
    # A token carries 256 random bits, so a plain SHA-256 cannot be reversed or guessed:
    # a slow password hash (salt, many rounds) would only make every call slower.
    return hashlib.sha256(token.encode("ascii")).hexdigest()


def token_id_of(token: str) -> str:
    """The public id `list` shows for `token`, and `revoke` takes."""
    return _digest(token)[:TOKEN_ID_CHARS]


def iso_utc(unix_s: float) -> str:
    return datetime.datetime.fromtimestamp(unix_s, datetime.UTC).isoformat(timespec="seconds")


def check_identity(identity: str) -> None:
    """InvalidArgument unless `identity` is 1-64 printable characters without spaces."""
    if not isinstance(identity, str) or not identity:
        raise InvalidArgumentError("the identity is empty; give a name such as --identity alice",
                                   "BAD_IDENTITY")
    if len(identity) > MAX_IDENTITY_CHARS:
        raise InvalidArgumentError(f"the identity is {len(identity)} characters long; use at most "
                                   f"{MAX_IDENTITY_CHARS}", "BAD_IDENTITY")
    if any(ch.isspace() or unicodedata.category(ch).startswith("C") for ch in identity):
        raise InvalidArgumentError(f"the identity {identity!r} has spaces or control characters; "
                                   "use a single word such as alice or ops-script", "BAD_IDENTITY")


class TokenStore:
    """The tokens file of one station. `verify` is thread-safe and costs one os.stat when the
    file has not changed; `issue` and `revoke` may run in several processes at once."""

    def __init__(self, path: Path, clock: Callable[[], float] = time.time):
        self._path = Path(path).absolute()  # a later chdir must not move the file
        self._clock = clock
        self._reload_lock = threading.Lock()
        self._snapshot = _Snapshot(None, {})

    @property
    def path(self) -> Path:
        return self._path

    def issue(self, identity: str, role: Role, ttl_s: float) -> str:
        """A new token for `identity`, valid `ttl_s` seconds; it is returned here only."""
        check_identity(identity)
        role = Role(role)
        if not (isinstance(ttl_s, int | float) and math.isfinite(ttl_s) and ttl_s > 0):
            raise InvalidArgumentError(
                f"the lifetime {ttl_s!r} s is not positive; give one such as "
                "30m, 8h or 7d", "BAD_TTL")
        token = TOKEN_PREFIX + secrets.token_urlsafe(32)
        digest = _digest(token)
        now = self._clock()
        entry = TokenEntry(token_id_of(token), identity, role, now + ttl_s, now)
        with self._writing() as stored:
            stored.append(_Stored(digest, entry))
        return token

    def revoke(self, identity_or_token_id: str) -> int:
        """Remove every token of that identity, or the token with that id; how many went."""
        key = identity_or_token_id
        with self._writing() as stored:
            kept = [s for s in stored if key not in (s.entry.identity, s.entry.token_id)]
            removed = len(stored) - len(kept)
            stored[:] = kept
        return removed

    def entries(self) -> list[TokenEntry]:
        """Every token in the file, expired ones too, oldest first."""
        _, stored = self._read_strict()
        return sorted((s.entry for s in stored), key=lambda entry: entry.created_at)

    def verify(self, token: str) -> TokenGrant:
        """Who `token` speaks for; UnauthenticatedError if it is malformed, unknown, revoked or
        expired."""
        if not isinstance(token, str) or not _TOKEN_SHAPE.fullmatch(token):
            raise UnauthenticatedError(
                "no valid bearer token: send metadata 'authorization: Bearer trb_...' with a "
                f"token from `{_CLI} issue`", "BAD_TOKEN")
        digest = _digest(token)
        stored = self._current().get(digest)
        # The lookup is by hash, which a caller cannot steer toward a stored one, so its timing
        # tells nothing; the final comparison is constant-time all the same.
        if stored is None or not hmac.compare_digest(stored.digest, digest):
            raise UnauthenticatedError(
                "no valid bearer token: this token is unknown or was revoked; ask an admin "
                f"for a new one (`{_CLI} issue`)", "BAD_TOKEN")
        entry = stored.entry
        if self._clock() >= entry.expires_at:
            raise UnauthenticatedError(
                f"the token for {entry.identity} expired at {iso_utc(entry.expires_at)}; issue "
                f"a new one with {_CLI} issue --identity {entry.identity} --role "
                f"{entry.role.label} --ttl 8h", "TOKEN_EXPIRED")
        return TokenGrant(entry.identity, entry.role, entry.expires_at)

    def _current(self) -> dict[str, _Stored]:
        # One stat per call (about 2 us, against the hundreds an RPC costs) finds a change made
        # by any process; the file is re-read only then.
        signature = _signature(self._path)
        snapshot = self._snapshot  # one read of one attribute: no lock on the hot path
        if snapshot.signature == signature:
            return snapshot.by_digest
        with self._reload_lock:  # one thread re-reads; the others then find it done
            if self._snapshot.signature != signature:
                self._snapshot = self._load_for_verify()
            return self._snapshot.by_digest

    def _load_for_verify(self) -> _Snapshot:
        try:
            signature, stored = self._read_strict()
        except FailedPreconditionError as error:
            # Fail closed: a broken file admits nobody. Keep its signature so the error is
            # logged once per change, not on every call.
            _log.error("%s; every bearer token is refused until it is fixed", error.message)
            return _Snapshot(_signature(self._path), {})
        return _Snapshot(signature, {s.digest: s for s in stored})

    def _read_strict(self) -> tuple[tuple[int, int, int] | None, list[_Stored]]:
        """The file's signature and tokens; FailedPreconditionError if it is not a tokens file."""
        try:
            with open(self._path, "rb") as file:
                signature = _signature_of(os.fstat(file.fileno()))  # of exactly what is read
                raw = file.read()
        except FileNotFoundError:
            return None, []
        except OSError as error:  # unreadable (permissions): refuse, never crash the call
            raise FailedPreconditionError(
                f"the tokens file {self._path} cannot be read ({error}); give this process "
                "read access to it", "TOKENS_FILE_INVALID") from None
        try:
            document = json.loads(raw)
            if document.get("format") != FORMAT or document.get("version") != VERSION:
                raise ValueError(f"not format {FORMAT!r} version {VERSION}")
            stored = [_parse(item) for item in document["tokens"]]
        except (ValueError, KeyError, TypeError, AttributeError) as error:
            raise FailedPreconditionError(
                f"the tokens file {self._path} cannot be read ({error}); restore it or remove "
                "it and issue the tokens again", "TOKENS_FILE_INVALID") from None
        return signature, stored

    @contextlib.contextmanager
    def _writing(self) -> Iterator[list[_Stored]]:
        """The tokens as a list to change in place, written back atomically on exit. A lock
        file keeps two writers (a server and the CLI, two admins) from losing each other's
        change; it is left in place, since removing it would race with the next writer."""
        self._path.parent.mkdir(parents=True, exist_ok=True)
        lock_path = self._path.with_name(self._path.name + ".lock")
        lock_fd = os.open(lock_path, os.O_RDWR | os.O_CREAT, 0o600)
        try:
            fcntl.flock(lock_fd, fcntl.LOCK_EX)
            _, stored = self._read_strict()
            yield stored
            self._write(stored)
        finally:
            os.close(lock_fd)  # releases the flock

    def _write(self, stored: list[_Stored]) -> None:
        document = {"format": FORMAT, "version": VERSION,
                    "tokens": [_unparse(s) for s in stored]}
        text = json.dumps(document, indent=1) + "\n"
        # 0600 from its creation: the hashes are never readable by others, even for a moment.
        replace_file(self._path, text.encode("utf-8"))


def _parse(item: dict) -> _Stored:
    digest = item["hash"]
    if not isinstance(digest, str) or not _DIGEST_SHAPE.fullmatch(digest):
        raise ValueError(f"a token hash is not 64 hex digits: {digest!r}")
    entry = TokenEntry(digest[:TOKEN_ID_CHARS], str(item["identity"]), Role.parse(item["role"]),
                       float(item["expires_at"]), float(item["created_at"]))
    return _Stored(digest, entry)


def _unparse(stored: _Stored) -> dict:
    entry = stored.entry
    return {"hash": stored.digest, "identity": entry.identity, "role": entry.role.label,
            "expires_at": entry.expires_at, "created_at": entry.created_at}


# --- command line -------------------------------------------------------------------------

_TTL_UNITS = {"": 1, "s": 1, "m": 60, "h": 3600, "d": 86400}
_TTL_SHAPE = re.compile(r"(\d+(?:\.\d+)?)([smhd]?)")


def parse_ttl(text: str) -> float:
    """Seconds from "30s", "15m", "8h", "7d" or plain seconds ("90")."""
    match = _TTL_SHAPE.fullmatch(text.strip().lower())
    seconds = float(match[1]) * _TTL_UNITS[match[2]] if match else 0.0
    if seconds <= 0:
        raise argparse.ArgumentTypeError(
            f"invalid lifetime {text!r}: give a positive number with s, m, h or d, e.g. 8h")
    return seconds


def _role_argument(text: str) -> Role:
    try:
        return Role.parse(text)
    except ValueError as error:
        raise argparse.ArgumentTypeError(str(error)) from None


def _parser() -> argparse.ArgumentParser:
    # --file on the parent and on each command, so it may come before or after the command.
    file_option = argparse.ArgumentParser(add_help=False)
    file_option.add_argument("--file", type=Path, default=argparse.SUPPRESS,
                             help=f"tokens file (default: ${TOKENS_FILE_ENV} or "
                                  f"{DEFAULT_TOKENS_FILE})")
    parser = argparse.ArgumentParser(prog=_CLI, parents=[file_option],
                                     description=__doc__.split("\n\n")[0])
    commands = parser.add_subparsers(dest="command", required=True)
    issue = commands.add_parser("issue", parents=[file_option],
                                help="issue a token; prints it once on stdout")
    issue.add_argument("--identity", required=True, help="who the token speaks for")
    issue.add_argument("--role", required=True, type=_role_argument,
                       help=", ".join(role.label for role in Role))
    issue.add_argument("--ttl", default="8h", type=parse_ttl,
                       help="lifetime: 30s, 15m, 8h, 7d or seconds (default 8h)")
    commands.add_parser("list", parents=[file_option], help="list the tokens (never secrets)")
    revoke = commands.add_parser("revoke", parents=[file_option],
                                 help="remove an identity's tokens, or one token by its id")
    revoke.add_argument("target", metavar="IDENTITY_OR_TOKEN_ID")
    return parser


def _print_table(entries: list[TokenEntry], now: float) -> None:
    rows = [("TOKEN ID", "IDENTITY", "ROLE", "EXPIRES (UTC)", "STATUS")]
    rows += [(e.token_id, e.identity, e.role.label, iso_utc(e.expires_at),
              "expired" if now >= e.expires_at else "valid") for e in entries]
    widths = [max(len(row[i]) for row in rows) for i in range(len(rows[0]))]
    for row in rows:
        print("  ".join(cell.ljust(width) for cell, width in zip(row, widths, strict=True))
              .rstrip())


def main(argv: list[str] | None = None) -> int:
    parser = _parser()
    args = parser.parse_args(argv)
    store = TokenStore(getattr(args, "file", None) or tokens_file())
    try:
        if args.command == "issue":
            try:
                token = store.issue(args.identity, args.role, args.ttl)
            except InvalidArgumentError as error:
                parser.error(error.message)  # exits 2, like any other bad argument
            print(token)  # alone on stdout, so a script can capture it
            print(f"issued token {token_id_of(token)} for {args.identity} ({args.role.label}), "
                  f"valid until about {iso_utc(time.time() + args.ttl)}. It is shown only this "
                  f"once; {store.path} keeps just its hash.", file=sys.stderr)
        elif args.command == "list":
            entries = store.entries()
            if not entries:
                print(f"no tokens in {store.path}", file=sys.stderr)
            else:
                _print_table(entries, time.time())
        else:
            removed = store.revoke(args.target)
            if not removed:
                print(f"no token of identity or with id {args.target!r} in {store.path}; "
                      f"see `{_CLI} list`", file=sys.stderr)
                return 1
            print(f"revoked {removed} token(s) of {args.target!r}", file=sys.stderr)
    except TelerobotError as error:
        print(f"{parser.prog}: error: {error.message}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
