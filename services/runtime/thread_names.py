"""Each thread of a service process named for the OS as it is in Python.

Python 3.11 leaves every thread's OS name ("comm") as the process's, so `top -H`, `ps -L`,
`perf` and /proc/PID/task/*/comm cannot tell a lane's handler from the thread following the arm's
state stream. `name_os_threads()` hooks the threading module (threading.setprofile: the hook runs
once in each new thread, before its target) so that every thread started after it gives the OS
its Python name, cut to the 15 bytes Linux keeps.
"""

from __future__ import annotations

import ctypes
import sys
import threading

_PR_SET_NAME = 15  # prctl(2): the calling thread's name
OS_NAME_BYTES = 15  # Linux's TASK_COMM_LEN, 16 with the terminating NUL


def name_os_threads() -> bool:
    """Name every thread started from now on; False where the OS has no prctl (not Linux)."""
    try:
        prctl = ctypes.CDLL(None, use_errno=True).prctl
    except (AttributeError, OSError):
        return False

    def name_this_thread(*_) -> None:
        sys.setprofile(None)  # once: the rest of the thread runs unhooked
        name = threading.current_thread().name.encode(errors="replace")[:OS_NAME_BYTES]
        prctl(_PR_SET_NAME, ctypes.c_char_p(name), 0, 0, 0)

    threading.setprofile(name_this_thread)
    return True
