"""The station's dependencies during a session, as the operator sees them: a line on the terminal
whenever one changes state (the DecisionServer's `dependency_changed` events), and their final
states for summary.json (GetDependencies)."""

from __future__ import annotations

import contextlib
import logging
import threading
from collections.abc import Callable
from typing import Any

from clients.python.decision_server import DecisionClient
from clients.python.values import Dependency, DependencyState, enum_value
from wire.errors import TelerobotError

log = logging.getLogger(__name__)


def describe(dependency: Dependency, previous: str | None = None) -> str:
    """One line for people: "[station] force_sensor SERVING -> NOT_SERVING: UNAVAILABLE: …"."""
    state = _state_name(dependency.state)
    change = f"{previous} -> {state}" if previous else state
    restarts = f" (restarted {dependency.restarts}x)" if dependency.restarts else ""
    reason = f": {dependency.reason}" if dependency.reason else ""
    return f"[station] {dependency.name} {change}{reason}{restarts}"


def as_json(dependency: Dependency) -> dict:
    return {"name": dependency.name, "state": _state_name(dependency.state),
            "reason": dependency.reason, "change_time_ns": dependency.change_time_ns,
            "restarts": dependency.restarts}


class DependencyMonitor:
    """Reads the DecisionServer's events on a thread of its own and calls `show` with a line for
    each dependency that changes state, from start() until stop(). A context manager."""

    def __init__(self, client: DecisionClient, show: Callable[[str], None] = print,
                 on_event: Callable[[Any], Any] | None = None):
        self._client = client
        self._show = show
        self._on_event = on_event  # every event, of any kind (make teleop --mcap records them)
        self._events = None
        self._thread: threading.Thread | None = None
        self.changes: list[Dependency] = []  # every change seen, in order

    def start(self) -> DependencyMonitor:
        self._events = self._client.stream_events()
        self._thread = threading.Thread(target=self._read, name="dependency-events",
                                        daemon=True)
        self._thread.start()
        return self

    def _read(self) -> None:
        try:
            for event in self._events:
                if self._on_event is not None:
                    self._on_event(event)
                if event.WhichOneof("event") != "dependency_changed":
                    continue
                change = event.dependency_changed
                dependency = Dependency.from_proto(change.dependency)
                previous = enum_value(DependencyState, change.previous_state)
                if not previous and dependency.serving:
                    continue  # first seen, and well: nothing to tell
                self.changes.append(dependency)
                self._show(describe(dependency, _state_name(previous) if previous else None))
        except TelerobotError as error:
            # The DecisionServer itself went away: the session's own calls say so too.
            self._show(f"[station] events stopped: {error}")

    def initial(self) -> list[Dependency]:
        """Every dependency's state now ([] if the server cannot say)."""
        try:
            return self._client.get_dependencies()
        except TelerobotError as error:
            log.warning("could not read the dependencies: %s", error)
            return []

    def final(self) -> list[dict]:
        """Every dependency's state now, for the summary ([] if the server cannot say)."""
        return [as_json(d) for d in self.initial()]

    def stop(self) -> None:
        if self._events is not None:
            with contextlib.suppress(Exception):
                self._events.cancel()
        if self._thread is not None:
            self._thread.join(timeout=5.0)

    def __enter__(self) -> DependencyMonitor:
        return self.start()

    def __exit__(self, *exc) -> None:
        self.stop()


def _state_name(value) -> str:
    """An enum member's name, or the number a newer server sent."""
    return getattr(value, "name", str(value))
