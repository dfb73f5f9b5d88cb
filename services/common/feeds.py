"""Feed: one upstream server stream held open by a thread of its own while it is wanted,
cancelled when it is not any more, and reopened after an error (a service restarting) with a
capped back-off. The live view (services.foxglove) and the observation publisher
(services.observation) follow the station's streams with it.
"""

from __future__ import annotations

import logging
import threading
from collections.abc import Callable, Iterator

import grpc

log = logging.getLogger(__name__)

RETRY_MIN_S = 0.5
RETRY_MAX_S = 2.0  # (the arm not connected yet is the usual cause: show it soon after)


class Feed:
    """One upstream server stream, open while wanted. `open_stream()` starts the call (an
    iterator that can be cancelled); `handle(message)` takes each message it yields;
    `on_status(name, why)` hears why the stream ended under a viewer, and (name, None) once
    it flows again."""

    def __init__(self, name: str, open_stream: Callable[[], Iterator], handle: Callable,
                 on_status: Callable[[str, str | None], None] = lambda name, why: None):
        self.name = name
        self._open_stream = open_stream
        self._handle = handle
        self._on_status = on_status
        self._wake = threading.Condition()
        self._wanted = False
        self._stopped = False
        self._call = None
        self.error: str | None = None  # the last error, while it keeps failing
        self._thread = threading.Thread(target=self._run, name=f"live-{name}", daemon=True)

    def start(self) -> Feed:
        self._thread.start()
        return self

    def want(self, wanted: bool) -> None:
        with self._wake:
            self._wanted = wanted
            call = None if wanted else self._call
            self._wake.notify_all()
        if call is not None:
            call.cancel()

    def stop(self) -> None:
        with self._wake:
            self._stopped = True
            call = self._call
            self._wake.notify_all()
        if call is not None:
            call.cancel()
        self._thread.join(timeout=5.0)

    def _run(self) -> None:
        retry_s = RETRY_MIN_S
        while True:
            with self._wake:
                self._wake.wait_for(lambda: self._stopped or self._wanted)
                if self._stopped:
                    return
            call = self._open_stream()  # (outside the lock: it may make a unary call first)
            with self._wake:
                if self._stopped or not self._wanted:
                    call.cancel()
                    continue
                self._call = call
            try:
                for message in call:
                    self._handle(message)
                    if self.error is not None:
                        self.error = None
                        self._on_status(self.name, None)
                    retry_s = RETRY_MIN_S
                ended = "the service ended the stream"
            except grpc.RpcError as error:
                ended = f"{error.code().name}: {error.details()}"
            except Exception as error:  # noqa: BLE001 - a message this view cannot show
                call.cancel()  # start over (after the back-off) rather than lose the feed
                ended = f"{type(error).__name__}: {error}"
            with self._wake:
                self._call = None
                if self._stopped or not self._wanted:
                    continue  # cancelled by want(False) or stop()
                # Ended under a viewer (the service restarting): again after a back-off.
                if ended != self.error:
                    log.warning("the %s feed ended (%s); reopening it in %.1f s",
                                self.name, ended, retry_s)
                    self._on_status(self.name, ended)
                self.error = ended
                self._wake.wait_for(lambda: self._stopped or not self._wanted, retry_s)
            retry_s = min(2 * retry_s, RETRY_MAX_S)
