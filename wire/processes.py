"""How a process of this project and whoever started it talk: ready lines, the parent's pid,
and stack dumps on a signal. Any program can start the station this way
(`python -m services.launcher`), in any language.

- Once SERVING, a process prints one line on stdout per port, with the address it actually
  bound (so a process started on port 0 tells its parent where it listens):
  `TELEROBOT_READY <name> <host:port>`.
- A parent sets PARENT_PID_ENV to its own pid; the process then stops cleanly when that parent
  goes away, even if the parent was killed without a chance to stop it (no orphans).
- Every process writes all its threads' stacks to stderr on STACKS_SIGNAL and runs on
  (`kill -QUIT <pid>`; Ctrl-\\ in a terminal). faulthandler does it in C, so it answers even
  when no Python code can run, as in a hang. A supervisor sends it before it kills a process
  that did not stop (services.runtime.children), so the log says where it was stuck.
- A process acts on its stop signals (SIGINT, SIGTERM) on a thread of its own
  (`handle_signals`), never inside Python's signal handler.
"""

from __future__ import annotations

import faulthandler
import os
import signal
import sys
import threading
from collections.abc import Callable, Sequence

READY_LINE_PREFIX = "TELEROBOT_READY"
PARENT_PID_ENV = "TELEROBOT_PARENT_PID"


def ready_line(name: str, address: str) -> str:
    """The line a process prints once `name` serves on `address` (host:port)."""
    return f"{READY_LINE_PREFIX} {name} {address}"


_OUTPUT = threading.Lock()


def say(text: str, stream=None) -> None:
    """`text` and a newline in one write (stdout by default), one writer at a time. print()
    writes the text and the newline apart, so when stdout and stderr share one pipe (as a
    supervisor reads them) and Python runs unbuffered, a log line written meanwhile from
    another thread can land inside the line and hide it."""
    stream = stream or sys.stdout
    with _OUTPUT:
        stream.write(text + "\n")
        stream.flush()


def say_ready(name: str, address: str) -> None:
    """Print the ready line of `name` serving on `address`, whole."""
    say(ready_line(name, address))


def parse_ready_line(line: str) -> tuple[str, str] | None:
    """(name, host:port) from a ready line; None for any other line."""
    fields = line.split()
    if len(fields) != 3 or fields[0] != READY_LINE_PREFIX:
        return None
    return fields[1], fields[2]


STACKS_SIGNAL = signal.SIGQUIT
# In the header of each thread's stack in such a dump.
STACKS_LINE = "(most recent call first)"


def dump_stacks_on_signal() -> None:
    """Call once, early in a service's main(). The dump goes to the process's own stderr (file
    descriptor 2), also when sys.stderr has been replaced, as a test's capture does."""
    faulthandler.register(STACKS_SIGNAL, file=sys.__stderr__, all_threads=True)


def runs_a_service(args: Sequence[str]) -> bool:
    """Whether `python <args>` runs one of this project's processes, `-m services.<name>`
    (a service, the launcher, the live view...), each of which calls dump_stacks_on_signal();
    not a tool deeper down such as `-m services.security.pki`."""
    return (len(args) >= 2 and args[0] == "-m" and args[1].startswith("services.")
            and args[1].count(".") == 1)


_signal_handlers: dict[int, Callable[[int], None]] = {}


def handle_signals(handlers: dict[int, Callable[[int], None]]) -> None:
    """Call `handlers[signum](signum)` on the "signals" thread each time the process gets
    `signum`. Main thread only.

    Python runs a signal handler on the main thread between two bytecodes, which may be while
    that thread holds the very lock the handler needs: inside `Event.wait()` it holds the
    Event's own lock, so a handler that sets the Event waits for itself forever. Here Python's
    C-level handler only writes the signal's number to a pipe (signal.set_wakeup_fd), and the
    thread reading the pipe runs the handler, which may take any lock."""
    if not _signal_handlers:
        read_end, write_end = os.pipe()
        os.set_blocking(write_end, False)  # set_wakeup_fd's C handler must never block
        signal.set_wakeup_fd(write_end, warn_on_full_buffer=False)
        threading.Thread(target=_dispatch_signals, args=(read_end,), name="signals",
                         daemon=True).start()
    for signum, handler in handlers.items():
        _signal_handlers[signum] = handler
        signal.signal(signum, _on_main_thread)


def _on_main_thread(_signum, _frame) -> None:
    """Python's handler: nothing, the signals thread acts (and it must not: see above)."""


def _dispatch_signals(read_end: int) -> None:
    while True:
        for signum in os.read(read_end, 64):
            handler = _signal_handlers.get(signum)
            if handler is not None:
                handler(signum)
