"""Ready lines: said whole, and read back. Signals: acted on outside Python's handler."""

from __future__ import annotations

import subprocess
import sys
import textwrap

import pytest

from tests.processes import REPO
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


# The main thread holds a lock and runs bytecode when SIGTERM comes; the handler takes that
# lock. Run by Python's own handler (on the main thread, right there) it would wait for itself
# forever, as setting an Event from a handler does while the main thread is in Event.wait().
_HANDLER_TAKES_THE_MAIN_THREADS_LOCK = textwrap.dedent("""
    import os, signal, threading
    from wire.processes import handle_signals

    lock, handled = threading.Lock(), threading.Event()

    def on_term(signum):
        with lock:
            print("handled", signal.Signals(signum).name, "on", threading.current_thread().name)
        handled.set()

    handle_signals({signal.SIGTERM: on_term})
    with lock:
        os.kill(os.getpid(), signal.SIGTERM)
        total = sum(range(100_000))  # bytecode, where Python runs its handlers
    print("handled in time" if handled.wait(10) else "not handled")
""")


@pytest.mark.e2e
def test_a_signal_handler_runs_on_its_own_thread_and_may_take_the_main_threads_lock():
    done = subprocess.run([sys.executable, "-c", _HANDLER_TAKES_THE_MAIN_THREADS_LOCK],
                          cwd=REPO, capture_output=True, text=True, timeout=30)
    assert done.returncode == 0, done.stderr
    assert done.stdout.split("\n")[:2] == ["handled SIGTERM on signals", "handled in time"]
