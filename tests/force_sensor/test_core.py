"""The sampling thread's and the streams' shortcuts, without a world: they give what the general
functions give, to the bit."""

from __future__ import annotations

import numpy as np

from domain.robot_model import puma560
from services.force_sensor.core import ForceSensorCore
from services.force_sensor.servicer import reading_to_proto
from services.force_sensor.subscribers import WrenchReading
from telerobot.v1 import force_sensor_pb2 as pb
from wire import convert


def test_the_sensor_rotation_is_the_kinematics_frame_pose():
    core = ForceSensorCore(lambda: None, None)  # no link is opened before StartReading
    generator = np.random.default_rng(12)
    for _ in range(50):
        q = puma560.HOME_Q + generator.uniform(-1.5, 1.5, 6)
        expected = core._kinematics.frame_pose(q, puma560.FT_SITE).rotation
        assert np.array_equal(core._sensor_rotation(q), expected)


def test_a_sample_converts_as_the_general_conversions_would():
    generator = np.random.default_rng(3)
    for time_ns in (0, 1, 999_999_999, 1_767_225_600_123_456_789, -1, -1_000_000_001):
        force, torque = generator.normal(size=(2, 3))
        force[1], torque[0] = 0.0, -0.0
        reading = WrenchReading(int(generator.integers(1, 2**40)), time_ns, force, torque)
        general = pb.WrenchSample(sequence=reading.sequence,
                                  sample_time=convert.timestamp(time_ns),
                                  wrench=convert.wrench_to_proto(force, torque))
        assert reading_to_proto(reading) == general
        assert reading_to_proto(reading).SerializeToString() == general.SerializeToString()
