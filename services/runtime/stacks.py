"""Every process of this project's services writes all its threads' stacks to stderr on
STACKS_SIGNAL and runs on (`kill -QUIT <pid>`; Ctrl-\\ in a terminal). It is done in C by
faulthandler, so it answers even when no Python code can run, as in a hang. A supervisor sends
it before it kills a service that did not stop (services.runtime.children), so the log says
where the service was stuck."""

from __future__ import annotations

import faulthandler
import signal
import sys
from collections.abc import Sequence

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
