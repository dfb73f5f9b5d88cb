"""Network namespaces for the tests that need a second host: made by the test, removed after.

    with linked_namespaces("10.213.9.1", "10.213.9.2") as (left, right):
        start_process(python_in_namespace(left, ["-m", "services.world", ...]), env)

Two namespaces (or this one and a new one, `left_in_this_namespace=True`) joined by a veth
pair, each end with its address of a private /30 that exists nowhere else, loopback up in each
new namespace. Root and iproute2 only: `unavailable_reason()` says why not, for a skip.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import uuid
from collections.abc import Iterator
from contextlib import contextmanager


def unavailable_reason() -> str | None:
    """Why namespaces cannot be made here, or None when they can."""
    if os.geteuid() != 0:
        return "network namespaces need root"
    if shutil.which("ip") is None:
        return "network namespaces need iproute2 (`ip`)"
    return None


@contextmanager
def linked_namespaces(left_address: str, right_address: str, *, prefix: int = 30,
                      left_in_this_namespace: bool = False) -> Iterator[tuple[str | None, str]]:
    """(left, right) namespace names, joined by a veth pair with `left_address` on the left
    end and `right_address` on the right. With `left_in_this_namespace`, the left end stays in
    this process' namespace and `left` is None. Everything made is removed on exit."""
    tag = uuid.uuid4().hex[:6]
    left = None if left_in_this_namespace else f"trt-{tag}-l"
    right = f"trt-{tag}-r"
    left_link, right_link = f"vl{tag}", f"vr{tag}"  # interface names are at most 15 bytes
    made = [ns for ns in (left, right) if ns is not None]

    def ip(namespace: str | None, *args: str) -> list[str]:
        return ["ip", *(["-n", namespace] if namespace else []), *args]

    steps = [["ip", "netns", "add", ns] for ns in made]
    steps.append(["ip", "link", "add", left_link, "type", "veth", "peer", "name", right_link])
    for namespace, link, address in ((left, left_link, left_address),
                                     (right, right_link, right_address)):
        if namespace is not None:
            steps += [["ip", "link", "set", link, "netns", namespace],
                      ip(namespace, "link", "set", "lo", "up")]
        steps += [ip(namespace, "addr", "add", f"{address}/{prefix}", "dev", link),
                  ip(namespace, "link", "set", link, "up")]
    try:
        for step in steps:
            subprocess.run(step, check=True, capture_output=True, text=True)
        yield left, right
    finally:
        # Deleting either end deletes the pair; a namespace's end goes with the namespace.
        if left is None:
            subprocess.run(["ip", "link", "del", left_link], capture_output=True)
        for namespace in made:
            subprocess.run(["ip", "netns", "del", namespace], capture_output=True)


def python_in_namespace(namespace: str, args: list[str]) -> list[str]:
    """Arguments for `python` that run `python -m <module> <rest>` (`args` is ["-m", module,
    ...]) inside `namespace`: the `ip netns exec` of a child started by services.runtime.
    children, which runs this interpreter. It joins the namespace (setns) first thing, before
    anything starts a thread or opens a socket."""
    if args[:1] != ["-m"] or len(args) < 2:
        raise ValueError(f"expected ['-m', module, ...], not {args!r}")
    enter = (
        "import ctypes, os, runpy, sys\n"
        f"fd = os.open('/run/netns/{namespace}', os.O_RDONLY)\n"
        "if ctypes.CDLL(None, use_errno=True).setns(fd, 0x40000000) != 0:\n"  # CLONE_NEWNET
        "    raise OSError(ctypes.get_errno(), 'setns')\n"
        f"sys.argv = {['python', *args[2:]]!r}\n"
        f"runpy.run_module({args[1]!r}, run_name='__main__', alter_sys=True)\n")
    return ["-c", enter]
