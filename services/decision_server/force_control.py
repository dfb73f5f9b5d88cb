"""Active compliance, the loop: ΔT = A·(F_t − F_d), ΔM = B·(C_t − C_d) on the selected tool
axes, one tool-frame increment per fresh wrench sample. No gRPC here."""

from __future__ import annotations

import logging
import threading
from collections.abc import Callable

import numpy as np
import pinocchio as pin

from domain.geometry import vector_norm
from services.decision_server.assistance import ForceControl
from services.decision_server.slave import Slave
from services.runtime.clock import Clock
from wire.errors import TelerobotError, UnavailableError

log = logging.getLogger(__name__)

RETRY_S = 0.2  # after the sensor's stream ends, subscribe again this often
DECIMATION = 5  # the loop acts on every 5th 1 kHz sample: 200 Hz
MAX_STEP_S = 0.05  # one sample never integrates more than this
# The smallest increment sent. The arm's IK resolves a pose to 1 µm and 1 µrad, so a smaller
# increment moves nothing, and a loop that sent each sample's own would stall short of its
# target (with A = 1.5e-4 m/(N·s) at 200 Hz, anywhere within 1.3 N of it). Smaller ones are
# added up until they count.
MIN_TRANSLATION_STEP_M = 2e-6
MIN_ROTATION_STEP_RAD = 2e-6
# A sample older than this is history, not feedback: the loop skips it to catch up. Acting on
# a backlog (gRPC's transport buffers hold seconds of samples when the loop falls behind on a
# loaded machine) would add that whole delay to the loop, and a contact loop with K ≈ 1e5 N/m
# goes unstable once A·K·delay nears π/2.
MAX_SAMPLE_AGE_NS = 50_000_000


class ForceLoop:
    """One force-control loop on its own thread. It starts only once the loop it replaces
    (`after`) has ended, so two loops never move the arm at once; `stop()` ends it. When it
    ends by itself (the arm refused a step), it calls `on_end(loop, error)` with the refusal."""

    def __init__(self, slave: Slave, control: ForceControl, clock: Clock,
                 after: ForceLoop | None = None,
                 on_end: Callable[[ForceLoop, TelerobotError], None] = lambda loop, e: None):
        self._slave = slave
        self._on_end = on_end
        self._control = control
        self._clock = clock
        self._after = after
        self._stop = threading.Event()
        self._stream = None  # the wrench stream being read, cancelled by stop()
        self._thread = threading.Thread(target=self._run, name="force-control", daemon=True)

    def start(self) -> ForceLoop:
        self._thread.start()
        return self

    def stop(self, wait: bool = True) -> None:
        self._stop.set()
        stream = self._stream
        if stream is not None:
            stream.cancel()  # a loop waiting for a sample ends now, not at the next one
        if wait:
            self.join(2.0)

    def join(self, timeout_s: float | None = None) -> None:
        """Until the loop's thread has ended (if it started, and is not the caller)."""
        if self._thread.ident is not None and self._thread is not threading.current_thread():
            self._thread.join(timeout_s)

    def _run(self) -> None:
        if self._after is not None:
            # Until it has ended, however long its last call takes (a call's own timeout
            # bounds it): two loops must never move the arm at once.
            self._after.stop(wait=False)
            self._after.join()
            self._after = None  # no chain of ended loops
        while not self._stop.is_set():
            try:
                self._steps()
            except UnavailableError as error:  # the sensor stalled: subscribe again once it is back
                log.warning("force control paused: %s", error.message)
                self._clock.wait(self._stop, RETRY_S)
            except TelerobotError as error:
                log.warning("force control stopped: %s", error.message)
                self._on_end(self, error)
                return

    def _steps(self) -> None:
        """Integrate per fresh sample until stopped; UnavailableError when the stream ends."""
        self._stream = self._slave.wrench_stream(DECIMATION)
        try:
            self._act_on(self._stream)
        finally:
            self._stream.cancel()  # whatever ended the loop, the subscription ends with it

    def _act_on(self, stream) -> None:
        if self._stop.is_set():  # stopped while subscribing: stop() may have missed it
            return
        control = self._control
        previous_ns = None
        pending_x, pending_r = np.zeros(3), np.zeros(3)  # integrated, not sent yet
        for sample in stream:
            if self._stop.is_set():
                return
            if self._clock.time_ns() - sample.sample_time_ns > MAX_SAMPLE_AGE_NS:
                previous_ns = None  # the target did not move meanwhile: integrate nothing
                continue
            if previous_ns is None:
                previous_ns = sample.sample_time_ns
                continue
            dt = min((sample.sample_time_ns - previous_ns) * 1e-9, MAX_STEP_S)
            previous_ns = sample.sample_time_ns
            if dt <= 0:
                continue
            force_error = (sample.force_n - control.desired_force_n) * control.axes[:3]
            torque_error = (sample.torque_nm - control.desired_torque_nm) * control.axes[3:]
            pending_x += control.translation_gain_m_per_n_s * force_error * dt
            pending_r += control.rotation_gain_rad_per_nm_s * torque_error * dt
            if (vector_norm(pending_x) < MIN_TRANSLATION_STEP_M
                    and vector_norm(pending_r) < MIN_ROTATION_STEP_RAD):
                continue
            delta_x, delta_m = pending_x, pin.exp3(pending_r)
            pending_x, pending_r = np.zeros(3), np.zeros(3)
            if self._stop.is_set():  # stopped while integrating: no step after the stop
                return
            try:
                self._slave.move_cartesian(delta_x, delta_m, "TOOL")
            except UnavailableError:
                raise
            except TelerobotError as error:
                # A refusal ends the loop: the core stops it on a latch anyway, and a loop that
                # keeps sending refused moves at 200 Hz helps nobody.
                raise type(error)(f"a step was refused: {error.message}",
                                  error.reason) from None
