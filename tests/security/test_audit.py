"""The audit log (services.security.audit) on real files: one JSON line per record, client
strings that cannot forge lines, rotation by size, private files, many threads, and a failed
write that warns instead of raising."""

from __future__ import annotations

import errno
import json
import logging
import stat
import threading

import pytest

from services.security.audit import MAX_DETAIL_CHARS, AuditLog, audit_log_for

FIELDS = ["time", "identity", "role", "method", "outcome", "peer", "detail"]


@pytest.fixture
def path(tmp_path):
    return tmp_path / "audit" / "decision_server.jsonl"  # its directory does not exist yet


def lines(path) -> list[dict]:
    return [json.loads(line) for line in path.read_text().splitlines()]


def record(log: AuditLog, **overrides) -> None:
    fields = {"identity": "alice", "role": "operator", "method": "/telerobot.v1.X/Stop",
              "outcome": "OK"} | overrides
    log.record(**fields)


def test_each_record_is_one_json_line_with_every_field(path):
    log = AuditLog(path, clock=lambda: 1_700_000_000.25)
    record(log, peer="ipv4:10.0.0.2:5000", detail="speed 0.1")
    record(log, outcome="PERMISSION_DENIED")
    log.close()
    first, second = lines(path)
    assert list(first) == FIELDS
    assert first == {"time": "2023-11-14T22:13:20.250000+00:00", "identity": "alice",
                     "role": "operator", "method": "/telerobot.v1.X/Stop", "outcome": "OK",
                     "peer": "ipv4:10.0.0.2:5000", "detail": "speed 0.1"}
    assert (second["outcome"], second["peer"], second["detail"]) == ("PERMISSION_DENIED", "", "")


def test_a_client_string_cannot_forge_a_line(path):
    log = AuditLog(path)
    forged = 'x"}\n{"identity": "admin", "outcome": "OK"}\u2028\r'
    record(log, identity=forged, detail=forged)
    log.close()
    assert len(path.read_bytes().splitlines()) == 1
    assert lines(path)[0]["identity"] == forged


def test_the_detail_is_cut(path):
    log = AuditLog(path)
    record(log, detail="d" * 5000)
    log.close()
    assert lines(path)[0]["detail"] == "d" * MAX_DETAIL_CHARS


def test_the_files_are_private(path):
    log = AuditLog(path, max_bytes=300, backups=2)
    assert stat.S_IMODE(path.stat().st_mode) == 0o600  # before the first record
    for _ in range(5):
        record(log)
    log.close()
    for file in [path, path.with_name(path.name + ".1")]:
        assert stat.S_IMODE(file.stat().st_mode) == 0o600


def test_rotation_keeps_the_newest_files_under_the_size(path):
    log = AuditLog(path, max_bytes=1000, backups=2)
    for number in range(100):
        record(log, detail=f"record {number}")
    log.close()
    files = sorted(file.name for file in path.parent.iterdir())
    assert files == [path.name, path.name + ".1", path.name + ".2"]
    kept = []
    for name in reversed(files):
        file = path.parent / name
        assert file.stat().st_size <= 1000
        kept += [entry["detail"] for entry in lines(file)]
    assert kept == [f"record {number}" for number in range(100 - len(kept), 100)]


def test_records_from_many_threads_all_arrive_whole(path):
    log = AuditLog(path)

    def write_some(thread_number):
        for number in range(200):
            record(log, identity=f"t{thread_number}", detail=str(number))

    threads = [threading.Thread(target=write_some, args=(n,)) for n in range(8)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join(timeout=30)
    log.close()
    entries = lines(path)
    assert len(entries) == 8 * 200
    for n in range(8):
        assert [e["detail"] for e in entries if e["identity"] == f"t{n}"] == [
            str(number) for number in range(200)]


class FullDisk:
    """A stream whose every write fails as on a full disk."""

    def write(self, text):
        raise OSError(errno.ENOSPC, "No space left on device")

    def flush(self):
        pass

    def seek(self, offset, whence=0):
        return 0

    def tell(self):
        return 0

    def close(self):
        pass


def test_a_failed_write_warns_once_per_outage_and_never_raises(path, caplog):
    log = AuditLog(path)
    working = log._handler.stream
    log._handler.stream = FullDisk()
    with caplog.at_level(logging.WARNING, logger="services.security.audit"):
        record(log, detail="lost 1")
        record(log, detail="lost 2")
        log.flush()
        assert len(caplog.records) == 1 and "cannot write the audit log" in caplog.text
        log._handler.stream = working
        record(log, detail="kept")
        log.flush()
        log._handler.stream = FullDisk()
        record(log, detail="lost 3")
        log.flush()
        assert len(caplog.records) == 2
    log._handler.stream = working
    log.close()
    assert [entry["detail"] for entry in lines(path)] == ["kept"]


def test_records_after_close_are_dropped(path):
    log = AuditLog(path)
    record(log, detail="kept")
    log.close()
    record(log, detail="dropped")
    assert [entry["detail"] for entry in lines(path)] == ["kept"]


def test_each_service_has_its_file_in_the_audit_dir(tmp_path, monkeypatch):
    monkeypatch.setenv("TELEROBOT_AUDIT_DIR", str(tmp_path / "audit"))
    log = audit_log_for("proxy_robot")
    record(log)
    log.close()
    assert len(lines(tmp_path / "audit" / "proxy_robot.jsonl")) == 1
    for bad in ["", "../x", "a/b", ".hidden"]:
        with pytest.raises(ValueError):
            audit_log_for(bad)


def test_a_flush_writes_the_gathered_records_before_it_returns(path):
    """The writer gathers records for a few ms before it writes them; flush() does not wait
    for that: what was recorded before it is in the file when it returns, in order."""
    log = AuditLog(path)
    for number in range(5):
        record(log, detail=f"first {number}")
    log.flush()
    assert [entry["detail"] for entry in lines(path)] == [f"first {n}" for n in range(5)]
    record(log, detail="after")
    log.close()
    assert lines(path)[-1]["detail"] == "after"
