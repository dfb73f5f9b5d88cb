"""Log lines carry client text safely: one line per record, bounded, control characters
escaped, tracebacks intact."""

from __future__ import annotations

import logging

from services.runtime.config import MAX_LOG_MESSAGE_CHARS, OneLineFormatter


def record(message: str, *args, exc_info=None) -> logging.LogRecord:
    return logging.LogRecord("test", logging.WARNING, __file__, 1, message, args, exc_info)


def test_a_clients_text_cannot_forge_a_log_line():
    line = OneLineFormatter("%(levelname)s %(message)s").format(
        record("emergency stop: %s", "oops\nERROR forged line\x1b[2J\x00"))
    assert "\n" not in line and "\x1b" not in line and "\x00" not in line
    assert line == "WARNING emergency stop: oops\\x0aERROR forged line\\x1b[2J\\x00"


def test_a_huge_message_is_cut_and_says_how_long_it_was():
    line = OneLineFormatter("%(message)s").format(record("reason: %s", "x" * 10_000))
    assert len(line) < MAX_LOG_MESSAGE_CHARS + 40
    assert line.endswith("(10008 characters)")


def test_a_traceback_keeps_its_lines():
    try:
        raise ValueError("boom")
    except ValueError:
        import sys

        line = OneLineFormatter("%(message)s").format(record("failed", exc_info=sys.exc_info()))
    assert line.startswith("failed\nTraceback")
    assert "ValueError: boom" in line
