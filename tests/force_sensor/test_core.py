"""ForceSensorCore's sampling arithmetic, without a world: the shortcuts the sampling thread
takes give what the general functions give, to the bit."""

from __future__ import annotations

import numpy as np

from services.force_sensor import wrench_model
from services.force_sensor.core import ForceSensorCore
from services.robot_model import puma560


def test_the_sensor_rotation_is_the_kinematics_frame_pose():
    core = ForceSensorCore(lambda: None, None)  # no link is opened before StartReading
    generator = np.random.default_rng(12)
    for _ in range(50):
        q = puma560.HOME_Q + generator.uniform(-1.5, 1.5, 6)
        expected = core._kinematics.frame_pose(q, puma560.FT_SITE).rotation
        assert np.array_equal(core._sensor_rotation(q), expected)


def test_the_contact_wrench_cross_product_is_numpys():
    generator = np.random.default_rng(7)
    for _ in range(200):
        a, b = generator.normal(scale=10.0, size=(2, 3))
        assert np.array_equal(wrench_model._cross(a, b), np.cross(a, b))
