"""The MasterArm: joint readings in, slave increments and motor torques out (no transport).

Each ``update()`` reads the joint angles θ from the source, computes the hand pose
(X⁺, M⁺) = G_M(θ) and, against the reference (X, M):

- **direct teleoperation**: the increment (ΔX, ΔM) (see ``cat.IncrementFrame``), scaled by
  eq. 2, is returned for sending, and the reference becomes the hand pose;
- **indexing** (the clutch engaged, by ``arm.clutch = True`` or by the source's own button):
  nothing is returned, so nothing is sent, and the reference follows the hand, so the hand can
  be repositioned and, once released, only the motion made after the release is sent.

The first reading only sets the reference. ``step(time_s, send)`` is ``update`` plus calling
``send(increment)`` when there is one (the operator station's loop passes its Teleoperate
session's send).

Joint velocities and accelerations for the impedance controller come from the readings by
backward differences (`JointStateEstimator`), as they would from encoders.
``motor_torques(...)`` gives eq. 3's torques at the latest state, with the force feedback
τ_ff = Jᵀ F from the slave's wrench (``impedance.slave_wrench_to_master``).
"""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any

import numpy as np
import pinocchio as pin

from clients.master.cat import Increment, IncrementFrame, hand_increment, scale
from clients.master.impedance import (
    Gain,
    ImpedanceController,
    ImpedanceTorques,
    slave_wrench_to_master,
)
from clients.master.model import MasterModel
from clients.master.sources import JointReading, JointSource, SimulatedHand
from domain.passivity import MasterPassivity


class JointStateEstimator:
    """q̇ and q̈ from successive (time, q) readings by backward differences. `smoothing` in
    [0, 1) low-pass filters both (each estimate keeps that fraction of the previous one)."""

    def __init__(self, smoothing: float = 0.0):
        if not 0.0 <= smoothing < 1.0:
            raise ValueError(f"smoothing must be in [0, 1), got {smoothing}")
        self.smoothing = smoothing
        self.time_s: float | None = None
        self.q: np.ndarray | None = None
        self.qd: np.ndarray | None = None
        self.qdd: np.ndarray | None = None

    def update(self, time_s: float, q: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        q = np.asarray(q, dtype=float).copy()
        if self.q is None or time_s <= self.time_s:
            qd = np.zeros_like(q) if self.qd is None else self.qd
            qdd = np.zeros_like(q) if self.qdd is None else self.qdd
        else:
            dt = time_s - self.time_s
            k = self.smoothing
            qd = k * self.qd + (1 - k) * (q - self.q) / dt
            qdd = k * self.qdd + (1 - k) * (qd - self.qd) / dt
        self.time_s, self.q, self.qd, self.qdd = time_s, q, qd, qdd
        return q, qd, qdd


class MasterArm:
    """The operator's master arm and its CAT functions; see the module docstring.

    `translation_scale` and `rotation_scale` are eq. 2's s for ΔX and ΔM (rotation: same as
    translation unless given). `alpha`, `beta`: eq. 3's gains (``impedance``). Force feedback
    is scaled by `force_scale`/`torque_scale`, by default the motion scales (the passive
    choice, see ``slave_wrench_to_master``)."""

    def __init__(self, source: JointSource | None = None, model: MasterModel | None = None, *,
                 translation_scale: float = 1.0, rotation_scale: float | None = None,
                 frame: IncrementFrame = IncrementFrame.PAPER, alpha: Gain | str = 0.0,
                 beta: Gain = 0.0, force_feedback: bool = True,
                 force_scale: float | None = None, torque_scale: float | None = None,
                 smoothing: float = 0.0, passivity: MasterPassivity | None = None):
        self.model = model or getattr(source, "model", None) or MasterModel()
        self.source = source if source is not None else SimulatedHand(self.model)
        self.frame = frame
        self.set_scale(translation_scale, rotation_scale)
        self.impedance = ImpedanceController(self.model, alpha, beta)
        self.force_feedback = force_feedback
        self.force_scale, self.torque_scale = force_scale, torque_scale
        self.estimator = JointStateEstimator(smoothing)
        self.clutch = False  # the operator's clutch button (indexing)
        self.indexing = False  # whether the last update was indexed (button or source)
        self.reference: pin.SE3 | None = None  # (X, M)
        self.hand: pin.SE3 | None = None  # (X⁺, M⁺) at the last reading
        self.last_reading: JointReading | None = None
        self.passivity = passivity
        # The hand's motion that reached the channel since the force was last displayed
        # (master metres, base axes): what the passivity observer weighs the force against.
        self._unweighed_step = np.zeros(3)

    # -- settings ---------------------------------------------------------------------------
    def set_scale(self, translation_scale: float, rotation_scale: float | None = None) -> None:
        """Eq. 2's scale factors (operator-controlled, at run time)."""
        rotation_scale = translation_scale if rotation_scale is None else rotation_scale
        if not (translation_scale > 0 and rotation_scale > 0):
            raise ValueError(f"scales must be positive, got {translation_scale}, "
                             f"{rotation_scale}")
        self.translation_scale, self.rotation_scale = float(translation_scale), rotation_scale

    # -- state ------------------------------------------------------------------------------
    @property
    def q(self) -> np.ndarray | None:
        return self.estimator.q

    @property
    def qd(self) -> np.ndarray | None:
        return self.estimator.qd

    @property
    def qdd(self) -> np.ndarray | None:
        return self.estimator.qdd

    # -- the CAT loop -----------------------------------------------------------------------
    def update(self, time_s: float | None = None, q: np.ndarray | None = None
               ) -> Increment | None:
        """Read the master (from the source at `time_s`, or the given joint angles `q`) and
        return the increment to send, or None when there is nothing to send (indexing, or the
        first reading)."""
        time_s = time.monotonic() if time_s is None else float(time_s)
        reading = self.source.read(time_s) if q is None else JointReading(time_s, np.asarray(q))
        self.last_reading = reading
        q, _, _ = self.estimator.update(reading.time_s, reading.q)
        self.hand = self.model.hand_pose(q)
        self.indexing = bool(self.clutch or reading.clutch)
        reference, self.reference = self.reference, self.hand
        if reference is None or self.indexing:
            return None  # the reference follows the hand; nothing is sent
        # (Only motion that is sent moves energy through the channel; indexing moves none.)
        self._unweighed_step = self._unweighed_step + (self.hand.translation
                                                       - reference.translation)
        raw_position, raw_rotation = hand_increment(reference, self.hand, self.frame)
        position, rotation = scale(raw_position, raw_rotation, self.translation_scale,
                                   self.rotation_scale)
        return Increment(position, rotation, raw_position, raw_rotation, reading.time_s,
                         self.frame)

    def step(self, time_s: float | None = None,
             send: Callable[[Increment], Any] | None = None) -> Increment | None:
        """`update`, then ``send(increment)`` if there is one to send."""
        increment = self.update(time_s)
        if increment is not None and send is not None:
            send(increment)
        return increment

    def reset_reference(self) -> None:
        """Take the current hand pose as the reference (nothing accumulated is sent)."""
        self.reference = self.hand

    # -- force feedback and impedance -------------------------------------------------------
    def feedback_wrench(self, force_tool: np.ndarray, torque_tool: np.ndarray,
                        slave_tool_rotation: np.ndarray | None = None,
                        hand_step_m: np.ndarray | None = None) -> np.ndarray:
        """The wrench for the hand (base axes, about the grip) from the slave's measured one;
        see ``slave_wrench_to_master``. Needs a reading first (for TOOL, the hand's
        rotation). With `passivity`, its controller bounds the force by the energy available,
        weighed against the hand's motion since the last call (or `hand_step_m`, master metres
        in base axes, for motion sent without `update`): call it once per control step."""
        if self.hand is None:
            raise RuntimeError("no reading yet: call update() first")
        force_scale = self.translation_scale if self.force_scale is None else self.force_scale
        torque_scale = self.rotation_scale if self.torque_scale is None else self.torque_scale
        wrench = slave_wrench_to_master(force_tool, torque_tool, frame=self.frame,
                                        slave_tool_rotation=slave_tool_rotation,
                                        hand_rotation=self.hand.rotation,
                                        force_scale=force_scale, torque_scale=torque_scale)
        step = self._unweighed_step if hand_step_m is None else np.asarray(hand_step_m, float)
        self._unweighed_step = np.zeros(3)
        if self.passivity is not None:
            wrench[:3] = self.passivity.display(wrench[:3], step)
        return wrench

    def motor_torques(self, force_tool: np.ndarray | None = None,
                      torque_tool: np.ndarray | None = None,
                      slave_tool_rotation: np.ndarray | None = None) -> ImpedanceTorques:
        """Eq. 3's torques for the master's motors at the latest (q, q̇, q̈), with the force
        feedback of the slave's wrench if given and ``force_feedback`` is on."""
        if self.q is None:
            raise RuntimeError("no reading yet: call update() first")
        wrench = None
        if self.force_feedback and force_tool is not None:
            torque = np.zeros(3) if torque_tool is None else torque_tool
            wrench = self.feedback_wrench(force_tool, torque, slave_tool_rotation)
        return self.impedance.torques(self.q, self.qd, self.qdd, wrench)
