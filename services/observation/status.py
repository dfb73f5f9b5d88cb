"""The status topic's stream: the session's status (telerobot.v1.SessionStatus) as the
DecisionServer answers it, read again after each change its events tell of and every
STATUS_PERIOD_S, so that an observer who joins late knows who holds control, the assistance in
force and each dependency's state without the events that led there.

The arm's own events (motion, status) change none of it and are not waited on; a burst of
events is read once.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable, Iterator

import grpc

from telerobot.v1 import decision_server_pb2 as ds_pb
from telerobot.v1 import decision_server_pb2_grpc
from wire.observation import STATUS_PERIOD_S

READ_TIMEOUT_S = 2.0
# The events after which the status is read again: those of the lock, the assistance, the
# dependencies and the sessions (not the arm's own, `robot`).
STATUS_EVENTS = frozenset({"control_changed", "assistance_changed", "dependency_changed",
                           "watchdog_hold", "teleop_session"})


class StatusStream:
    """SessionStatus messages from `door` (a DecisionServer stub): one at once, then one after
    each change and every `period_s`. Ends with the events stream's error (an RpcError), so a
    Feed reopens it; cancellable, as Feed needs."""

    def __init__(self, door: decision_server_pb2_grpc.DecisionServerStub,
                 period_s: float = STATUS_PERIOD_S, clock_ns: Callable[[], int] = time.time_ns):
        self._door, self._period_s, self._clock_ns = door, period_s, clock_ns
        self._events = door.StreamEvents(ds_pb.StreamEventsRequest())
        self._changed = threading.Event()
        self._ended: list[BaseException | None] = []  # the events stream's end, once it ended
        threading.Thread(target=self._follow, name="status-events", daemon=True).start()

    def _follow(self) -> None:
        try:
            for event in self._events:
                if event.WhichOneof("event") in STATUS_EVENTS:
                    self._changed.set()
            self._ended.append(None)
        except grpc.RpcError as error:
            self._ended.append(error)
        self._changed.set()

    def __iter__(self) -> Iterator[ds_pb.SessionStatus]:
        try:
            while True:
                yield self.read()
                self._changed.wait(self._period_s)
                self._changed.clear()
                if self._ended:
                    if self._ended[0] is not None:
                        raise self._ended[0]
                    return
        finally:  # a read that failed ends the events stream too
            self._events.cancel()

    def read(self) -> ds_pb.SessionStatus:
        status = ds_pb.SessionStatus(
            control=self._door.GetControlState(ds_pb.GetControlStateRequest(),
                                               timeout=READ_TIMEOUT_S).state,
            assistance=self._door.GetAssistance(ds_pb.GetAssistanceRequest(),
                                                timeout=READ_TIMEOUT_S).assistance)
        status.dependencies.extend(self._door.GetDependencies(
            ds_pb.GetDependenciesRequest(), timeout=READ_TIMEOUT_S).dependencies)
        status.status_time.FromNanoseconds(self._clock_ns())
        return status

    def cancel(self) -> None:
        self._events.cancel()
