"""How each service the DecisionServer depends on is: SERVING, NOT_SERVING or RESTARTING, with a
reason for people. No transport code.

Two sources, combined on every poll:

- whether the dependency answers: the `Slave` port's `health()`, "ok" or why not (over gRPC,
  each dependency's standard health, watched; see backends.py), and for the station's Zenoh
  router, whether its port accepts a connection (services.runtime.port_watch);
- what the station's launcher knows (services.runtime.supervisor_state): whether it is
  restarting the dependency, how its last process ended, how often it restarted it.

A dependency that answers is SERVING. One that does not is RESTARTING while the launcher says
it is restarting it (with the launcher's reason), or for RECONNECT_GRACE_S after the launcher
says a restart is serving again (this server's link reconnects within about a second and a
half), NOT_SERVING otherwise (with the transport's reason).
`DependencyWatch` polls both at 10 Hz on a thread of its own, on an injected clock, and tells
its listeners of every change of state (a new reason or restart count in the same state is
kept, not told): the DecisionServer raises an event and sets its health from them.
"""

from __future__ import annotations

import logging
import threading
from collections.abc import Callable
from dataclasses import dataclass

from services.runtime.clock import SYSTEM_CLOCK, Clock
from services.runtime.supervisor_state import (
    GAVE_UP,
    RESTARTING,
    RUNNING,
    ChildState,
    read_state,
)

log = logging.getLogger(__name__)

POLL_S = 0.1
# A restarted dependency serves on the launcher's side before this server's channel has
# reconnected (its back-off reaches 1 s, the health watch retries every 0.5 s): so long it is
# still RESTARTING, not NOT_SERVING for a moment.
RECONNECT_GRACE_S = 3.0
OK = "ok"  # what health() says of a dependency that answers
SERVING, NOT_SERVING = "SERVING", "NOT_SERVING"
RESTARTING_STATE = "RESTARTING"
UNSPECIFIED = "UNSPECIFIED"  # a dependency not seen before
# The order GetDependencies lists them in; any other name health() reports comes after.
ORDER = ("proxy_robot", "force_sensor", "stereo_camera", "emergency_stop", "zenoh_router")


@dataclass(frozen=True)
class Dependency:
    name: str
    state: str  # SERVING, NOT_SERVING, RESTARTING
    reason: str  # why not serving, for people; empty while serving
    change_time_ns: int  # when it entered this state
    restarts: int  # how often the launcher restarted it (0 without a launcher)


@dataclass(frozen=True)
class DependencyChanged:
    """The event: a dependency changed state."""

    dependency: Dependency
    previous_state: str  # UNSPECIFIED the first time it is seen


def assess(answer: str, supervised: ChildState | None, now_s: float) -> tuple[str, str, int]:
    """(state, reason, restarts) of a dependency from its health `answer` ("ok" or why not)
    and what the launcher knows of it (None: no launcher supervises it), at unix time
    `now_s`."""
    restarts = supervised.restarts if supervised else 0
    if answer == OK:
        return SERVING, "", restarts
    if supervised is not None and supervised.state == RESTARTING:
        # `restarts` counts the restarts done; the one under way is the next.
        cause = f" after it {supervised.last_exit}" if supervised.last_exit else ""
        return RESTARTING_STATE, f"restarting{cause}; restart {restarts + 1}", restarts
    if (supervised is not None and supervised.state == RUNNING and restarts
            and now_s - supervised.since < RECONNECT_GRACE_S):
        return RESTARTING_STATE, (f"restarted (restart {restarts}); reconnecting: "
                                  f"{answer}"), restarts
    if supervised is not None and supervised.state == GAVE_UP:
        return NOT_SERVING, (f"{answer} (the launcher gave up on it after {restarts} restarts; "
                             f"it {supervised.last_exit or 'ended'})"), restarts
    return NOT_SERVING, answer, restarts


def _well_formed(child: ChildState) -> bool:
    """Whether a launcher's entry has the types it should (the file is another process's)."""
    return (isinstance(child.state, str) and isinstance(child.last_exit, str)
            and type(child.restarts) is int and 0 <= child.restarts < 2**31
            and isinstance(child.since, int | float))


Listener = Callable[[DependencyChanged], None]


class DependencyWatch:
    """The dependencies' states, polled from `health` (name -> "ok" or why not) and the
    launcher's `supervisor_state` (default: the file TELEROBOT_SUPERVISOR_STATE names)."""

    def __init__(self, health: Callable[[], dict[str, str]], clock: Clock = SYSTEM_CLOCK,
                 supervisor_state: Callable[[], dict[str, ChildState]] = read_state,
                 period_s: float = POLL_S):
        self._health = health
        self._clock = clock
        self._supervisor_state = supervisor_state
        self._period_s = period_s
        self._lock = threading.RLock()  # a listener may read the states back
        self._states: dict[str, Dependency] = {}
        self._listeners: list[Listener] = []
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None

    def subscribe(self, listener: Listener, current: bool = False) -> None:
        """Call `listener` with every change from now on (under the watch's lock, in order: keep
        it short), after the state each dependency is in now if `current`."""
        with self._lock:
            if current:
                for dependency in self._states.values():
                    listener(DependencyChanged(dependency, dependency.state))
            self._listeners.append(listener)

    def poll(self) -> list[Dependency]:
        """Look once: update every dependency's state, tell the listeners of each change, and
        return them all (in ORDER)."""
        with self._lock:
            # Read under the lock too: two polls at once (the watch's and a GetDependencies')
            # must not let the one that read first write last, and turn a fresh state stale.
            answers = self._health()
            supervised = {name: child for name, child in self._supervisor_state().items()
                          if _well_formed(child)}
            now_ns = self._clock.time_ns()
            for name, answer in answers.items():
                state, reason, restarts = assess(answer, supervised.get(name), now_ns * 1e-9)
                old = self._states.get(name)
                if old is not None and old.state == state:  # said anew, or restarted again
                    self._states[name] = Dependency(name, state, reason, old.change_time_ns,
                                                    restarts)
                    continue
                new = Dependency(name, state, reason, now_ns, restarts)
                self._states[name] = new
                log.log(logging.INFO if state == SERVING else logging.WARNING,
                        "%s: %s%s", name, state, f" ({reason})" if reason else "")
                change = DependencyChanged(new, old.state if old else UNSPECIFIED)
                for listener in self._listeners:
                    try:
                        listener(change)
                    except Exception:
                        log.exception("a dependency listener failed")
            return self._ordered()

    def dependencies(self) -> list[Dependency]:
        """The states as last polled (in ORDER)."""
        with self._lock:
            return self._ordered()

    def _ordered(self) -> list[Dependency]:
        def rank(name: str) -> tuple[int, str]:
            return (ORDER.index(name) if name in ORDER else len(ORDER), name)

        return [self._states[name] for name in sorted(self._states, key=rank)]

    def start(self) -> None:
        """Poll now, then every period on a thread until close()."""
        self.poll()
        self._thread = threading.Thread(target=self._run, name="dependency-watch", daemon=True)
        self._thread.start()

    def _run(self) -> None:
        while not self._clock.wait(self._stop, self._period_s):
            try:
                self.poll()
            except Exception:
                log.exception("polling the dependencies failed; polling on")

    def close(self) -> None:
        self._stop.set()
        if self._thread is not None:
            self._thread.join(timeout=5.0)
