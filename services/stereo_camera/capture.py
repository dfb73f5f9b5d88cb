"""CaptureHub: one capture thread per source, shared by every client, and the two transfer modes.

The capture thread is the only thread that touches the source (open, grab, close), because
MuJoCo's GL context and cv2.VideoCapture belong to the thread that made them. Each capture
tick it grabs both eyes, passes them through the camera-status flags (source.PairAssembler),
and publishes the pair as the *newest pair*: one slot, replaced every tick, never a queue.
Pairs are immutable (each tick gets new arrays), so a client may keep encoding or sending the
pair it holds while the capture thread fills the next one: the paper's two buffers, with no
copy and no tearing.

Clients take pairs through a ``StreamView``, in one of the paper's two schemes:

- double buffer, concurrent (``view.next()``): the capture thread runs free at the source's
  rate while such a view is open, capturing into the back buffer while the client encodes and
  sends the front one. ``next()`` returns the newest pair the client has not had yet, at once
  if there is one: a slow client skips the pairs it could not take (gaps in the sequence
  numbers), and is never handed a backlog.
- single buffer, serialized (``view.fresh()``): the client asks for a pair and gets the first
  one whose capture *started after it asked*; it then encodes and sends it, and only then asks
  again. Capture never overlaps its own transfer, even when other clients keep the capture
  thread running (it then waits for the next tick to start: sequence gaps show the ticks that
  passed). If it is the only client, the source captures only on its requests, as in the paper.

What the server holds for a client is one pair: the one it is sending. What the transport
holds is up to the client's HTTP/2 receive window: a client that reports receipts is paced to
its path by the servicer (pacing.py); one that does not should open its channel with
client.LOW_LATENCY_OPTIONS (about one pair in flight), or gRPC's default window growth lets
megabytes of older pairs queue in the transport (see client.py).

Demand drives the thread. A source that can be triggered (pattern, sim) captures only while a
double-buffer view is open or a fresh pair is wanted, and otherwise sleeps (no rendering for
nobody). A live source (device, recording) is grabbed continuously while any view is open, so
its frames never go stale in the driver's queue, and is released after IDLE_RELEASE_S with no
view. Ticks never come faster than the source's rate (SourceGeometry.rate_hz).

Failures: an error from the source (FailedPreconditionError on open, UnavailableError on grab) is
handed to every client waiting since before it, and the thread retries no sooner than RETRY_AFTER_S
later, only if a client still wants pairs. Nothing here knows about gRPC.
"""

from __future__ import annotations

import contextlib
import itertools
import logging
import threading
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass

from services.stereo_camera.source import (
    LEFT,
    RIGHT,
    PairAssembler,
    SourceGeometry,
    StereoFrame,
    StereoSource,
)
from wire.errors import TelerobotError, UnavailableError

log = logging.getLogger(__name__)

RETRY_AFTER_S = 0.5  # after a source error, the earliest next attempt
IDLE_RELEASE_S = 2.0  # a live source with no view for this long is released
JOIN_TIMEOUT_S = 5.0

_STOP, _OPEN, _CAPTURE, _RELEASE = "stop", "open", "capture", "release"


@dataclass(frozen=True)
class HubStats:
    ticks: int  # capture ticks started
    pairs: int  # pairs published
    failures: int  # ticks or opens that failed
    mismatched: int  # eye frames dropped by the camera-status flags (ticks that disagreed)


def _copy(error: TelerobotError) -> TelerobotError:
    """A fresh exception per waiting thread (each raise writes its own traceback)."""
    return type(error)(error.message, reason=error.reason)


class CaptureHub:
    """Owns a source and its capture thread; hands pairs to any number of StreamViews."""

    def __init__(self, source: StereoSource, *, retry_after_s: float = RETRY_AFTER_S,
                 idle_release_s: float = IDLE_RELEASE_S):
        self._source = source
        self._retry_ns = round(retry_after_s * 1e9)
        self._idle_release_ns = round(idle_release_s * 1e9)
        self._cond = threading.Condition()
        self._thread: threading.Thread | None = None
        self._stopping = False
        self._closed = False
        self._assembler = PairAssembler()
        self._geometry: SourceGeometry | None = getattr(source, "geometry", None)
        self._latest: StereoFrame | None = None
        self._failure: tuple[TelerobotError, int] | None = None  # error, monotonic ns
        self._last_logged = ""
        self._next_tick = 1
        self._next_due_ns = 0
        self._views = 0
        self._free_run_views = 0
        self._fresh_requests: dict[int, int] = {}  # token -> monotonic ns of the request
        self._tokens = itertools.count()
        self._open_requests = 0
        self._live_open = False
        self._last_view_ns = 0
        self._ticks = self._pairs = self._failures = 0

    # -- life cycle -------------------------------------------------------------------------

    def start(self) -> None:
        """Start the capture thread (it opens the source when a client first wants pairs)."""
        with self._cond:
            if self._thread is not None:
                return
            self._thread = threading.Thread(target=self._run, name="stereo-capture",
                                            daemon=True)
        self._thread.start()

    def close(self) -> None:
        """Stop the capture thread and release the source; waiting clients get UnavailableError."""
        with self._cond:
            self._stopping = True
            thread = self._thread
            self._cond.notify_all()
        if thread is None:
            self._source.close()
            with self._cond:
                self._closed = True
            return
        thread.join(JOIN_TIMEOUT_S)
        if thread.is_alive():
            log.warning("the capture thread did not stop within %.0f s (a grab is stuck); "
                        "leaving it", JOIN_TIMEOUT_S)

    @property
    def stats(self) -> HubStats:
        with self._cond:
            return HubStats(self._ticks, self._pairs, self._failures,
                            self._assembler.mismatched)

    @property
    def source(self) -> StereoSource:
        return self._source

    # -- clients ----------------------------------------------------------------------------

    def geometry(self, timeout_s: float) -> SourceGeometry:
        """The source's size, calibration and rate; opens it if that is the only way to know.
        FailedPreconditionError when it cannot be opened."""
        since = time.monotonic_ns()
        with self._cond:
            self._open_requests += 1
            self._cond.notify_all()
        try:
            geometry = self._wait(lambda: self._geometry, since, timeout_s)
        finally:
            with self._cond:
                self._open_requests -= 1
        if geometry is None:
            raise UnavailableError(f"the camera source did not open within {timeout_s:.0f} s",
                                   reason="SOURCE_TIMEOUT")
        return geometry

    @contextlib.contextmanager
    def view(self, free_run: bool) -> Iterator[StreamView]:
        """A client's access to pairs for the life of a stream (see the module docstring).
        free_run: keep capturing while the view is open (double buffer)."""
        free_run = free_run or self._source.live
        view = StreamView(self, time.monotonic_ns(), next(self._tokens))
        with self._cond:
            self._views += 1
            self._free_run_views += free_run
            self._cond.notify_all()
        try:
            yield view
        finally:
            with self._cond:
                self._fresh_requests.pop(view._token, None)
                self._views -= 1
                self._free_run_views -= free_run
                self._last_view_ns = time.monotonic_ns()
                self._cond.notify_all()

    def snapshot(self, timeout_s: float) -> StereoFrame | None:
        """A pair captured after this call; None if none came within timeout_s."""
        with self.view(free_run=False) as view:
            return view.fresh(timeout_s)

    def _wait(self, ready: Callable[[], object], since_ns: int, timeout_s: float):
        """ready()'s value once it is not None; None after timeout_s. Raises the source's
        error if one happened at or after since_ns, UnavailableError once the hub stops."""
        deadline = time.monotonic() + timeout_s
        with self._cond:
            while True:
                value = ready()
                if value is not None:
                    return value
                if self._stopping or self._closed or self._thread is None:
                    raise UnavailableError("the camera service is not running (starting or "
                                           "stopping); retry", reason="SHUTTING_DOWN")
                if self._failure_since(since_ns):
                    raise _copy(self._failure[0])
                remaining = deadline - time.monotonic()
                if remaining <= 0:
                    return None
                self._cond.wait(remaining)

    def _newest_after(self, sequence: int, started_after_ns: int) -> StereoFrame | None:
        latest = self._latest
        if latest is not None and latest.sequence > sequence \
                and latest.started_ns >= started_after_ns:
            return latest
        return None

    def _fresh(self, view: StreamView, timeout_s: float) -> StereoFrame | None:
        """The first pair whose capture started after the view asked. The request stands
        until it is met (or the view closes), so a short timeout_s only polls: a capture that
        takes longer than timeout_s still answers it."""
        with self._cond:
            if view._asked_ns is None:
                view._asked_ns = time.monotonic_ns()
                self._fresh_requests[view._token] = view._asked_ns
                self._cond.notify_all()
            asked = view._asked_ns
        answered = True
        try:
            frame = self._wait(lambda: self._newest_after(0, asked), asked, timeout_s)
            answered = frame is not None
            return frame
        finally:  # answered, or failed: the next fresh() asks anew
            if answered:
                with self._cond:
                    view._asked_ns = None
                    self._fresh_requests.pop(view._token, None)

    def _failure_since(self, since_ns: int) -> bool:
        return self._failure is not None and self._failure[1] >= since_ns

    # -- the capture thread -----------------------------------------------------------------

    def _run(self) -> None:
        try:
            while True:
                with self._cond:
                    job = self._next_job()
                if job == _STOP:
                    return
                if job == _RELEASE:
                    self._release()
                else:
                    self._attempt(capture=job == _CAPTURE)
        except BaseException:
            log.exception("the capture thread failed")
            raise
        finally:
            try:
                self._source.close()
            except Exception:
                log.exception("closing the camera source failed")
            with self._cond:
                self._closed = True
                self._live_open = False
                self._cond.notify_all()

    def _next_job(self) -> str:
        """What to do next; waits (holding the condition) until there is something."""
        while True:
            if self._stopping:
                return _STOP
            now = time.monotonic_ns()
            retry_at = self._failure[1] + self._retry_ns if self._failure else 0
            wait_ns = None
            if self._capture_wanted():
                due = max(self._next_due_ns, retry_at)
                if now >= due:
                    return _CAPTURE
                wait_ns = due - now
            elif self._open_requests and self._geometry is None:
                if now >= retry_at:
                    return _OPEN
                wait_ns = retry_at - now
            elif self._live_open and self._views == 0:
                release_at = self._last_view_ns + self._idle_release_ns
                if now >= release_at:
                    return _RELEASE
                wait_ns = release_at - now
            self._cond.wait(None if wait_ns is None else wait_ns / 1e9)

    def _capture_wanted(self) -> bool:
        if self._free_run_views > 0:
            return True
        # A request stands until a published pair answers it (a tick whose eyes disagreed
        # published nothing, so it is captured again).
        answered = self._latest.started_ns if self._latest is not None else -1
        return any(asked > answered for asked in self._fresh_requests.values())

    def _attempt(self, capture: bool) -> None:
        """Open the source if needed and, when `capture`, capture and publish one tick."""
        started = time.monotonic_ns()
        rate = 0.0
        if capture:
            with self._cond:
                tick = self._next_tick
                self._next_tick += 1
                self._ticks += 1
                rate = self._geometry.rate_hz if self._geometry else 0.0
                self._next_due_ns = started + (round(1e9 / rate) if rate > 0 else 0)
        try:
            geometry = self._source.open()
            with self._cond:
                self._geometry = geometry
                self._live_open = self._source.live
                if not capture:
                    self._failure = None
                    self._cond.notify_all()
            if not capture:
                return
            if rate <= 0 < geometry.rate_hz:  # first tick: the rate was not known yet
                with self._cond:
                    self._next_due_ns = started + round(1e9 / geometry.rate_hz)
            left, right = self._source.grab(tick)
            self._assembler.offer(LEFT, left)
            pair = self._assembler.offer(RIGHT, right)
        except TelerobotError as error:
            self._fail(error)
            return
        except Exception as exc:
            log.exception("the camera source failed")
            self._fail(UnavailableError(f"the camera source failed: {exc}", reason="SOURCE_FAILED"))
            return
        if pair is None:
            return  # the eyes disagreed on the tick: no pair this time (a sequence gap)
        frame = StereoFrame(tick, pair[0].image, pair[1].image, pair[0].capture_time_ns,
                            pair[1].capture_time_ns, started, pair[0].render_scale)
        with self._cond:
            self._latest = frame
            self._pairs += 1
            self._failure = None
            self._last_logged = ""
            self._cond.notify_all()

    def _fail(self, error: TelerobotError) -> None:
        with self._cond:
            self._failure = (error, time.monotonic_ns())
            self._failures += 1
            self._live_open = False
            self._cond.notify_all()
            if error.message != self._last_logged:
                self._last_logged = error.message
                log.warning("camera source: %s", error.message)

    def _release(self) -> None:
        log.info("no client for %.1f s: releasing %s", self._idle_release_ns / 1e9,
                 self._geometry.description if self._geometry else "the camera source")
        self._source.close()
        with self._cond:
            self._live_open = False
            self._last_view_ns = time.monotonic_ns()


class StreamView:
    """One client's access to the hub's pairs (see the CaptureHub docstring)."""

    def __init__(self, hub: CaptureHub, opened_ns: int, token: int):
        self._hub = hub
        self._opened_ns = opened_ns
        self._token = token
        self._asked_ns: int | None = None  # a standing single-buffer request, guarded by hub
        self.last_sequence = 0

    def next(self, timeout_s: float) -> StereoFrame | None:
        """Double buffer: the newest pair not yet returned (captured since the view opened),
        at once if there is one; None if none came within timeout_s."""
        hub = self._hub
        frame = hub._wait(lambda: hub._newest_after(self.last_sequence, self._opened_ns),
                          self._opened_ns, timeout_s)
        if frame is not None:
            self.last_sequence = frame.sequence
        return frame

    def fresh(self, timeout_s: float) -> StereoFrame | None:
        """Single buffer: a pair whose capture started after the first fresh() call since the
        last pair this returned; None if none came within timeout_s (call again: the request
        stands)."""
        frame = self._hub._fresh(self, timeout_s)
        if frame is not None:
            self.last_sequence = frame.sequence
        return frame
