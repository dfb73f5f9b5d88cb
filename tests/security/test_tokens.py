"""Bearer tokens (services.security.tokens) on real files: issue and verify, expiry on a fake
clock, revocation seen by another store on the same file (as a running server would be), the
command line, bad tokens and bad input, and verify from many threads while the file changes."""

from __future__ import annotations

import json
import math
import os
import stat
import subprocess
import sys
import threading

import pytest

from services.security import tokens
from services.security.roles import Role
from services.security.tokens import TokenStore, parse_ttl, token_id_of
from tests.processes import REPO
from wire.errors import FailedPreconditionError, InvalidArgumentError, UnauthenticatedError

START = 1_700_000_000.0


class FakeClock:
    def __init__(self, now: float = START):
        self.now = now

    def __call__(self) -> float:
        return self.now


@pytest.fixture
def path(tmp_path):
    return tmp_path / "var" / "tokens.json"  # its directory does not exist yet


@pytest.fixture
def clock():
    return FakeClock()


@pytest.fixture
def store(path, clock):
    return TokenStore(path, clock)


def run_cli(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "services.security.tokens", *args], cwd=REPO,
                          capture_output=True, text=True, timeout=60)


def test_a_token_verifies_as_its_identity_and_role(store):
    token = store.issue("alice", Role.OPERATOR, 3600)
    grant = store.verify(token)
    assert token.startswith("trb_")
    assert (grant.identity, grant.role, grant.expires_at) == ("alice", Role.OPERATOR, START + 3600)


def test_the_file_is_private_and_holds_only_hashes(store, path):
    token = store.issue("alice", Role.ADMIN, 60)
    text = path.read_text()
    assert token not in text and token.removeprefix("trb_") not in text
    assert json.loads(text)["tokens"][0]["hash"].startswith(token_id_of(token))
    assert stat.S_IMODE(path.stat().st_mode) == 0o600
    assert not [name for name in os.listdir(path.parent) if name.endswith(".tmp")]


def test_entries_list_tokens_without_secrets(store, clock):
    first = store.issue("alice", Role.OPERATOR, 60)
    clock.now += 1
    store.issue("bob", Role.OBSERVER, 120)
    entries = store.entries()
    assert [(e.token_id, e.identity, e.role) for e in entries][0] == (
        token_id_of(first), "alice", Role.OPERATOR)
    assert [e.identity for e in entries] == ["alice", "bob"]
    assert entries[1].expires_at == START + 1 + 120 and entries[1].created_at == START + 1


def test_an_expired_token_is_refused_with_how_to_get_a_new_one(store, clock):
    token = store.issue("alice", Role.OPERATOR, 60)
    clock.now += 59.9
    store.verify(token)
    clock.now += 0.1
    with pytest.raises(UnauthenticatedError) as raised:
        store.verify(token)
    assert raised.value.reason == "TOKEN_EXPIRED"
    assert "alice expired at 2023-11-14T22:14:20+00:00" in raised.value.message
    assert "python -m services.security.tokens issue --identity alice" in raised.value.message


def test_revoke_by_identity_removes_all_its_tokens(store):
    alice = [store.issue("alice", Role.OPERATOR, 60) for _ in range(2)]
    bob = store.issue("bob", Role.OPERATOR, 60)
    assert store.revoke("alice") == 2
    for token in alice:
        with pytest.raises(UnauthenticatedError, match="revoked") as raised:
            store.verify(token)
        assert raised.value.reason == "BAD_TOKEN"
    assert store.verify(bob).identity == "bob"
    assert store.revoke("alice") == 0


def test_revoke_by_token_id_removes_only_that_token(store):
    kept, revoked = store.issue("alice", Role.OPERATOR, 60), store.issue("alice", Role.OPERATOR, 60)
    assert store.revoke(token_id_of(revoked)) == 1
    with pytest.raises(UnauthenticatedError):
        store.verify(revoked)
    assert store.verify(kept).identity == "alice"


def test_a_running_store_sees_another_stores_changes(path, clock):
    server, admin = TokenStore(path, clock), TokenStore(path, clock)
    token = admin.issue("alice", Role.OPERATOR, 60)
    assert server.verify(token).identity == "alice"  # loaded and cached
    admin.revoke("alice")
    with pytest.raises(UnauthenticatedError):
        server.verify(token)
    again = admin.issue("alice", Role.OPERATOR, 60)
    assert server.verify(again).identity == "alice"


@pytest.mark.e2e
def test_the_command_line_issues_lists_and_revokes_for_a_running_store(path):
    server = TokenStore(path)
    issued = run_cli("issue", "--identity", "ops-script", "--role", "station", "--ttl", "15m",
                     "--file", str(path))
    assert issued.returncode == 0, issued.stderr
    token = issued.stdout.strip()
    assert issued.stdout == token + "\n" and "shown only this once" in issued.stderr
    grant = server.verify(token)
    assert (grant.identity, grant.role) == ("ops-script", Role.STATION)

    listed = run_cli("--file", str(path), "list")
    assert listed.returncode == 0, listed.stderr
    assert token_id_of(token) in listed.stdout and "valid" in listed.stdout
    assert token not in listed.stdout

    revoked = run_cli("revoke", token_id_of(token), "--file", str(path))
    assert revoked.returncode == 0, revoked.stderr
    with pytest.raises(UnauthenticatedError):
        server.verify(token)
    assert run_cli("revoke", "ops-script", "--file", str(path)).returncode == 1  # none left


def test_the_command_line_reads_the_file_from_the_environment(path, monkeypatch, capsys):
    monkeypatch.setenv("TELEROBOT_TOKENS_FILE", str(path))
    assert tokens.tokens_file() == path
    assert tokens.main(["issue", "--identity", "alice", "--role", "admin", "--ttl", "60"]) == 0
    token = capsys.readouterr().out.strip()
    assert TokenStore(path).verify(token).role == Role.ADMIN


@pytest.mark.parametrize("token", [
    "",
    "garbage",
    "Bearer trb_" + "A" * 43,
    "xyz_" + "A" * 43,
    "trb_" + "A" * 42,
    "trb_" + "A" * 43,  # the right shape, not issued
    "trb_" + "\u00e9" * 43,
    None,
])
def test_bad_tokens_are_refused(store, token):
    store.issue("alice", Role.OPERATOR, 60)
    with pytest.raises(UnauthenticatedError) as raised:
        store.verify(token)
    assert raised.value.reason == "BAD_TOKEN"
    assert "no valid bearer token" in raised.value.message


def test_no_file_means_no_tokens(path):
    with pytest.raises(UnauthenticatedError) as raised:
        TokenStore(path).verify("trb_" + "A" * 43)
    assert raised.value.reason == "BAD_TOKEN"
    assert TokenStore(path).entries() == []
    assert not path.parent.exists()


def test_a_broken_file_admits_nobody_and_is_not_overwritten(store, path, caplog):
    token = store.issue("alice", Role.OPERATOR, 60)
    path.write_text("{not json")
    with pytest.raises(UnauthenticatedError):
        store.verify(token)
    assert "every bearer token is refused" in caplog.text
    with pytest.raises(FailedPreconditionError) as raised:
        store.issue("bob", Role.OPERATOR, 60)
    assert raised.value.reason == "TOKENS_FILE_INVALID"
    assert path.read_text() == "{not json"


@pytest.mark.parametrize(("identity", "ttl_s"), [
    ("", 60),
    ("a" * 65, 60),
    ("alice smith", 60),
    ("alice\n", 60),
    ("al\x00ice", 60),
    ("alice", 0),
    ("alice", -5),
    ("alice", math.nan),
    ("alice", math.inf),
])
def test_issue_refuses_bad_input(store, path, identity, ttl_s):
    with pytest.raises(InvalidArgumentError):
        store.issue(identity, Role.OPERATOR, ttl_s)
    assert not path.exists()


def test_the_longest_identity_is_accepted(store):
    assert store.verify(store.issue("a" * 64, Role.OBSERVER, 60)).identity == "a" * 64


@pytest.mark.parametrize(("text", "seconds"), [
    ("30s", 30), ("15m", 900), ("8h", 28800), ("7d", 604800), ("90", 90), ("1.5h", 5400)])
def test_lifetimes(text, seconds):
    assert parse_ttl(text) == seconds


@pytest.mark.parametrize("argv", [
    ["issue", "--identity", "alice", "--role", "emperor"],
    ["issue", "--identity", "alice", "--role", "operator", "--ttl", "0"],
    ["issue", "--identity", "alice", "--role", "operator", "--ttl", "8w"],
    ["issue", "--identity", "alice", "--role", "operator", "--ttl", "-1h"],
    ["issue", "--identity", "alice smith", "--role", "operator"],
    ["issue", "--role", "operator"],
    ["revoke"],
    ["rotate"],
    [],
])
def test_bad_command_lines_exit_2(path, argv, capsys):
    with pytest.raises(SystemExit) as exited:
        tokens.main([*argv, "--file", str(path)] if argv else [])
    assert exited.value.code == 2
    assert "error:" in capsys.readouterr().err
    assert not path.exists()


@pytest.mark.e2e
def test_a_bad_command_line_exits_2_as_a_process(path):
    result = run_cli("issue", "--identity", "", "--role", "operator", "--file", str(path))
    assert result.returncode == 2
    assert "the identity is empty" in result.stderr and result.stdout == ""


def test_verify_from_threads_while_another_store_issues(path):
    server, admin = TokenStore(path), TokenStore(path)
    standing = admin.issue("standing", Role.OPERATOR, 3600)
    issued: list[str] = []
    failures: list[BaseException] = []
    done = threading.Event()

    def verify_until_done():
        try:
            while not done.is_set():
                assert server.verify(standing).identity == "standing"
                for token in list(issued):
                    assert server.verify(token).identity.startswith("user")
        except BaseException as error:  # reported below, on the test's thread
            failures.append(error)

    threads = [threading.Thread(target=verify_until_done) for _ in range(8)]
    for thread in threads:
        thread.start()
    try:
        for number in range(40):
            issued.append(admin.issue(f"user{number}", Role.OBSERVER, 3600))
    finally:
        done.set()
        for thread in threads:
            thread.join(timeout=30)
    assert not failures, failures[0]
    assert len(server.entries()) == 41


def test_writers_in_parallel_lose_no_token(path):
    stores = [TokenStore(path) for _ in range(4)]

    def issue_some(store):
        for number in range(10):
            store.issue(f"user{number}", Role.OBSERVER, 60)

    threads = [threading.Thread(target=issue_some, args=(store,)) for store in stores]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join(timeout=30)
    assert len(TokenStore(path).entries()) == 40


@pytest.mark.e2e
def test_tokens_and_audit_stay_free_of_grpc():
    code = ("import sys, services.security.tokens, services.security.audit; "
            "sys.exit('grpc' in sys.modules)")
    assert subprocess.run([sys.executable, "-c", code], cwd=REPO, timeout=60).returncode == 0



def test_an_unreadable_file_admits_nobody(store, path):
    token = store.issue("alice", Role.OPERATOR, 60)
    path.unlink()
    path.mkdir()  # opening it fails even for root, as an unreadable file would for others
    with pytest.raises(UnauthenticatedError):
        store.verify(token)
    with pytest.raises(FailedPreconditionError):
        store.entries()
