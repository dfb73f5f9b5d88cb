"""The station's shared-memory segment, published by the driver of a real arm.

In simulation the world process owns the segment (services/world/shm_link.py): the force
sensor reads its wrist sensor there, the cameras its joints, and the emergency-stop band latches
its hold through it. On a real arm the driver's process owns it instead, and publishes what the
arm measures every control cycle, so those processes work on the arm unchanged:

- the joints, velocities, target, hold and fault, as the driver reads them;
- for an arm with no wrist F/T sensor, the reading a wrist sensor would give under the arm's
  own estimate of the environment's push: the external joint torques mapped to the sensor site
  (domain/robot_model/external_wrench.py), plus the tool's weight, which the force sensor's
  model takes off again (domain/wrench_model.py);
- the band's stop request comes back from `publish()`, for the driver to latch its hold.
"""

from __future__ import annotations

import numpy as np

from domain.robot_model import names
from domain.robot_model.description import ArmDescription
from domain.robot_model.external_wrench import wrench_at_frame
from domain.robot_model.kinematics import ArmKinematics
from domain.wrench_model import default_payload, wrist_reading
from services.world.link import ArmSample, RawWrench
from services.world.shm_link import WorldPublisher


class ArmMirror:
    """The segment `shm_name` (None: the default), written by one control thread."""

    def __init__(self, arm: ArmDescription, period_s: float, shm_name: str | None):
        self._publisher = WorldPublisher(arm.name, arm.lower, arm.upper, period_s, shm_name)
        self.name = self._publisher.name
        self._kinematics = ArmKinematics(arm=arm)
        self._payload = default_payload()
        self._wrench_sequence = 0

    def publish(self, sample: ArmSample, external_torques: np.ndarray) -> bool:
        """Publish one control cycle's sample, with the wrist reading of `external_torques`
        (N·m, the environment's on each joint); whether the band asked for a stop since."""
        q = sample.joint_positions_rad
        force, torque = wrench_at_frame(self._kinematics, q, names.FT_SITE, external_torques)
        rotation = self._kinematics.frame_pose(q, names.FT_SITE).rotation
        self._wrench_sequence += 1
        reading = RawWrench(self._wrench_sequence, sample.sample_time_ns,
                            *wrist_reading(force, torque, rotation, self._payload))
        self._publisher.publish(sample, reading)
        return any(command.kind == "hold" for command in self._publisher.poll_commands())

    def close(self) -> None:
        """Tell the segment's readers the arm is gone, and remove it."""
        self._publisher.close()
