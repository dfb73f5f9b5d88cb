"""ForceSensorCore: the sampling thread and its subscribers, with no transport code.

Every `period` (TimerValue) the thread reads the sensor, turns the reading into the contact
wrench at the tool point (wrench_model.py), keeps it as the latest sample, and publishes it to
the subscribers when it changed by more than the sensor's ThresholdValue. Each subscriber then
applies its own decimation, change filter and batch size (subscribers.py).

Where the time goes with many subscribers (py-spy --gil at 500 Hz for 8 s on this process,
during the bench's observers_32: the operator at 1 kHz and 32 observers at 100 Hz, each its own
gRPC client, on the shared 2-core VM):

- Before (527e7e9): this thread held 74 % of the GIL's time. A third of it (32 %) went to
  waking subscribers: Condition.notify releases a lock with the GIL held, and on a busy machine
  the kernel often runs the woken thread at once, so the sampler waits off the CPU while every
  other thread waits for its GIL. The contact wrench took 22 % (np.cross alone 17 %, ~20 us a
  call), the change filters' arithmetic 5 % (done even with zero thresholds), the sensor
  frame's pose 5 %; every stream encoded its own copy of each message (3-5 %); gRPC's send
  path and polling thread most of the rest. The GIL was held only ~40 % of the time: the
  process was short of CPU, shared with the world, the clients and the rest of the box.
- After: one encoding per distinct batch (6 %, on the first stream to send it), streams woken
  through an eventfd written without the GIL (5 %), the fastest subscriber first, and the
  arithmetic of a sample (contact wrench, sensor frame, the change filters of 33 subscribers
  with zero thresholds) at ~9 us instead of ~110. This thread now holds 41 % of the GIL's time,
  the streams 39 % (gRPC's send path 23 %), gRPC's polling thread 16 %.
- On grpcio's synchronous server each message cost its stream's thread two wake-ups (for the
  batch, then when the polling thread had completed the send) and the polling thread one, ~13
  thread hand-offs per ms with 33 streams; the sampling step (some 40 us of its own work) then
  took 0.4-1.8 ms at p50 and 3-13 ms at p99, so ticks were missed. On grpc.aio (--aio-server,
  off by default) each stream is a coroutine that the event loop wakes when the subscription's
  eventfd is written (loop.add_reader, services/common/wakeup.py), with no thread of its own:
  at 32 observers this process takes about a fifth less CPU and the operator's stream keeps
  1 kHz, but the DecisionServer's Teleoperate beside it is slower (docs/performance.md).
"""

from __future__ import annotations

import logging
import os
import threading
import time
from collections.abc import Callable

import numpy as np
import pinocchio as pin

from domain.robot_model import names
from domain.robot_model.kinematics import ArmKinematics
from domain.wrench_model import ContactWrench, Payload, contact_wrench, default_payload
from services.common.fanout import Fanout
from services.force_sensor.settings import SensorSettings, ThreadPriority
from services.force_sensor.subscribers import (
    StreamOptions,
    WrenchFanout,
    WrenchReading,
    WrenchSubscription,
    changed_enough,
)
from services.world.link import ArmLink, WrenchLink
from services.world.realtime import RealtimeLoop
from wire.errors import (
    FailedPreconditionError,
    InvalidArgumentError,
    ResourceExhaustedError,
    UnavailableError,
)

log = logging.getLogger(__name__)

MAX_TARE_S = 1.0
# A stalled sensor (a busy machine, a world that stopped stepping) may miss samples for this
# long before it is reported down: GetWrench and streams then answer UNAVAILABLE, while the
# sampler keeps trying and recovers by itself. A sensor that shut down stops sampling at once.
SENSOR_DOWN_AFTER_S = 0.5
_STALLED = "WORLD_STALE"
MAX_SUBSCRIBERS = 128
STOP_TIMEOUT_S = 2.0
_IDENTITY = np.eye(3)  # the sensor's rotation when no arm link tells it
_IDENTITY.setflags(write=False)


class ForceSensorCore:
    """The wrist sensor. Thread-safe."""

    def __init__(self, wrench_link_factory: Callable[[], WrenchLink],
                 arm_link_factory: Callable[[], ArmLink] | None,
                 payload: Payload | None = None):
        self._wrench_link_factory = wrench_link_factory
        self._arm_link_factory = arm_link_factory
        self._payload = payload or default_payload()
        self._kinematics = ArmKinematics()  # used by the sampling thread only
        home = self._kinematics.home_q  # any configuration: both frames ride on the last link
        self._flange_to_sensor = self._kinematics.flange_pose(home).actInv(
            self._kinematics.frame_pose(home, names.FT_SITE))
        self._flange_to_tool = self._kinematics.flange_T_tool
        self._sensor_frame = self._kinematics.frame_id(names.FT_SITE)
        self._sensor_to_tool = self._flange_to_sensor.actInv(self._flange_to_tool)
        self._lock = threading.Lock()
        self._settings = SensorSettings()
        self._bias: ContactWrench | None = None
        self._sequence = 0
        self._latest: WrenchReading | None = None
        self._last_published: WrenchReading | None = None
        self._failure: str | None = None
        self._wrench_link: WrenchLink | None = None
        self._arm_link: ArmLink | None = None
        self._thread: threading.Thread | None = None
        self._thread_id: int | None = None
        self._stop = threading.Event()
        self._loop: RealtimeLoop | None = None
        self._failing_since: float | None = None
        self.readings = WrenchFanout()
        self._unbiased: Fanout[ContactWrench] = Fanout()  # only while a tare averages

    # -- configuration ----------------------------------------------------------------------

    @property
    def settings(self) -> SensorSettings:
        return self._settings

    @property
    def reading(self) -> bool:
        return self._thread is not None and self._thread.is_alive()

    @property
    def failure(self) -> str | None:
        """Why sampling stopped on its own, until the next StartReading."""
        return self._failure

    def configure(self, settings: SensorSettings) -> SensorSettings:
        """Replace the settings, all or none; a new period restarts the sampling loop."""
        settings.validated()
        with self._lock:
            previous, self._settings = self._settings, settings
            running = self.reading
        if running and settings.period_s != previous.period_s:
            self._stop_thread()
            self._start_thread()
        elif running and settings.thread_priority != previous.thread_priority:
            self._apply_priority()
        return settings

    @property
    def tool_frame(self) -> pin.SE3:
        """The tool frame in the flange frame, in which samples are expressed."""
        return pin.SE3(self._flange_to_tool)

    def set_tool_frame(self, flange_to_tool: pin.SE3) -> None:
        with self._lock:
            self._flange_to_tool = pin.SE3(flange_to_tool)
            self._sensor_to_tool = self._flange_to_sensor.actInv(self._flange_to_tool)
            self._bias = None  # a bias taken about another tool point means nothing now

    # -- reading ----------------------------------------------------------------------------

    def start_reading(self) -> SensorSettings:
        """Open the links if needed and start sampling. UnavailableError if the sensor is down."""
        with self._lock:
            if self.reading:
                return self._settings
            self._failure = None
            if self._wrench_link is None:
                self._wrench_link = self._wrench_link_factory()
            if self._arm_link is None and self._arm_link_factory is not None:
                self._arm_link = self._arm_link_factory()
            self._sample_once()  # fail here, in the caller, if the sensor does not answer
        self._start_thread()
        return self._settings

    def stop_reading(self) -> int:
        """Stop sampling; returns the last sequence number taken."""
        self._stop_thread()
        return self._sequence

    def latest(self) -> WrenchReading:
        if self._failure:
            raise UnavailableError(f"the sensor stopped: {self._failure}; StartReading again",
                                   reason="SENSOR_DOWN")
        if self._latest is None:
            raise FailedPreconditionError("no sample yet: call StartReading first",
                                          reason="NOT_READING")
        return self._latest

    def tare(self, duration_s: float) -> tuple[ContactWrench, int]:
        """Average the contact wrench over duration_s (0: the next sample) and subtract it from
        now on. Returns (bias, samples averaged)."""
        if not 0 <= duration_s <= MAX_TARE_S:
            raise InvalidArgumentError(
                f"tare duration must be 0..{MAX_TARE_S} s", reason="BAD_TARE")
        if not self.reading:
            raise FailedPreconditionError("the sensor is not reading: call StartReading first",
                                          reason="NOT_READING")
        samples: list[ContactWrench] = []
        deadline = time.monotonic() + duration_s
        with self._unbiased.subscribe(capacity=10_000) as unbiased:
            while not samples or time.monotonic() < deadline:
                sample = unbiased.get(0.5)
                if sample is None:
                    raise UnavailableError("no samples arrived while taring", reason="SENSOR_DOWN")
                samples.append(sample)
        bias = ContactWrench(np.mean([s.force_n for s in samples], axis=0),
                             np.mean([s.torque_nm for s in samples], axis=0))
        with self._lock:
            self._bias = bias
        return bias, len(samples)

    def subscribe(self, options: StreamOptions) -> WrenchSubscription:
        if self.readings.subscriber_count >= MAX_SUBSCRIBERS:
            raise ResourceExhaustedError(f"{MAX_SUBSCRIBERS} subscribers already; retry later",
                                         reason="TOO_MANY_SUBSCRIBERS")
        return self.readings.subscribe(options)

    def close(self) -> None:
        self._stop_thread()
        self.readings.close_all()
        for link in (self._wrench_link, self._arm_link):
            if link is not None:
                link.close()
        self._wrench_link = self._arm_link = None

    # -- the sampling thread ----------------------------------------------------------------

    def _start_thread(self) -> None:
        self._stop = threading.Event()
        self._loop = RealtimeLoop(self._step, period_s=self._settings.period_s,
                                  max_catch_up_s=0.0)  # a late sample is skipped, not replayed
        self._thread = threading.Thread(target=self._run, args=(self._loop, self._stop),
                                        name="force-sampler", daemon=True)
        self._thread.start()

    def _stop_thread(self) -> None:
        self._stop.set()
        thread = self._thread
        if thread is not None and thread is not threading.current_thread():
            thread.join(STOP_TIMEOUT_S)

    def _run(self, loop: RealtimeLoop, stop: threading.Event) -> None:
        self._thread_id = threading.get_native_id()
        self._apply_priority()
        try:
            loop.run(stop)
        except UnavailableError as exc:
            self._failure = exc.message
            log.error("sampling stopped: %s", exc.message)
        log.info("sampling loop: %s", loop.stats().describe())

    def _apply_priority(self) -> None:
        priority = self._settings.thread_priority
        if self._thread_id is None:
            return
        try:
            os.setpriority(os.PRIO_PROCESS, self._thread_id, priority.value)
        except PermissionError:
            log.warning("no privilege for thread priority %s; the sampler stays NORMAL",
                        priority.name)
            os.setpriority(os.PRIO_PROCESS, self._thread_id, ThreadPriority.NORMAL.value)

    def _step(self) -> None:
        try:
            reading = self._sample_once()
        except UnavailableError as error:
            if error.reason != _STALLED:
                raise  # gone for good: the loop ends and the failure is reported
            now = time.monotonic()
            self._failing_since = self._failing_since or now
            if now - self._failing_since > SENSOR_DOWN_AFTER_S:
                self._failure = error.message
            return  # skip this sample; the sequence numbers show the gap
        self._failing_since = None
        self._failure = None
        settings = self._settings
        if changed_enough(reading, self._last_published, settings.threshold_force_n,
                          settings.threshold_torque_nm):
            self._last_published = reading
            self.readings.publish(reading)

    def _sensor_rotation(self, q: np.ndarray) -> np.ndarray:
        """The sensor frame's axes in the world at q: kinematics.frame_pose(q, FT_SITE).rotation,
        with the frame looked up once and only its own placement updated (1 us, not 5)."""
        model, data = self._kinematics.model, self._kinematics.data
        pin.forwardKinematics(model, data, np.asarray(q, float))
        return pin.updateFramePlacement(model, data, self._sensor_frame).rotation

    def _sample_once(self) -> WrenchReading:
        raw = self._wrench_link.read_wrench()
        if self._arm_link is not None:
            q = self._arm_link.read_arm().joint_positions_rad
            rotation = self._sensor_rotation(q)
        else:
            rotation = _IDENTITY
        sensor_to_tool, bias = self._sensor_to_tool, self._bias
        if self._unbiased.subscriber_count:
            self._unbiased.publish(contact_wrench(raw.force_n, raw.torque_nm, rotation,
                                                  sensor_to_tool, self._payload))
        wrench = contact_wrench(raw.force_n, raw.torque_nm, rotation, sensor_to_tool,
                                self._payload, bias)
        self._sequence += 1
        reading = WrenchReading(self._sequence, raw.sample_time_ns, wrench.force_n,
                                wrench.torque_nm)
        self._latest = reading
        return reading
