"""Ready lines: said whole, and read back."""

from __future__ import annotations

from wire.processes import parse_ready_line, ready_line, say


class Stream:
    def __init__(self):
        self.writes = []

    def write(self, text):
        self.writes.append(text)

    def flush(self):
        pass


def test_a_line_is_one_write_with_its_newline():
    """A ready line printed while another thread logs to stderr, both read from one pipe (as
    a supervisor reads a process): each line must be one write, or the log line can land
    between the text and its newline and hide the ready line."""
    stream = Stream()
    say(ready_line("foxglove", "127.0.0.1:8765"), stream)
    assert stream.writes == ["TELEROBOT_READY foxglove 127.0.0.1:8765\n"]
    assert parse_ready_line(stream.writes[0]) == ("foxglove", "127.0.0.1:8765")


def test_a_ready_line_with_something_glued_to_it_is_no_ready_line():
    assert parse_ready_line("TELEROBOT_READY decision_server 127.0.0.1:335632026-12-07 00:16:13,996"
                            " decision_server[24905] WARNING ...") is None
