"""wire.pose.Pose: a rigid transform with the attributes of a pin.SE3, without Pinocchio."""

from __future__ import annotations

import pickle

import numpy as np
import pytest

from wire.pose import Pose


def rotation_x(angle: float) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


A = Pose(rotation_x(0.4), [0.1, -0.2, 0.3])
B = Pose(rotation_x(-1.1).T, [0.0, 0.5, 0.05])


def test_the_arrays_are_read_only_copies():
    rotation, translation = np.eye(3), np.zeros(3)
    pose = Pose(rotation, translation)
    translation[0] = 1.0  # the caller's array is not the pose's
    assert pose.translation[0] == 0.0
    with pytest.raises(ValueError):
        pose.translation[0] = 2.0
    with pytest.raises(AttributeError):
        pose.translation = np.ones(3)


def test_shapes_are_checked():
    with pytest.raises(ValueError, match="rotation"):
        Pose(np.eye(4), np.zeros(3))
    with pytest.raises(ValueError, match="translation"):
        Pose(np.eye(3), np.zeros(4))


def test_homogeneous_round_trip_and_identity():
    matrix = A.homogeneous
    np.testing.assert_array_equal(matrix[:3, :3], A.rotation)
    np.testing.assert_array_equal(matrix[:3, 3], A.translation)
    np.testing.assert_array_equal(matrix[3], [0, 0, 0, 1])
    assert Pose.from_homogeneous(matrix).isclose(A, atol=0)
    np.testing.assert_array_equal(Pose.identity().homogeneous, np.eye(4))


def test_composition_and_inverse_match_the_homogeneous_matrices():
    np.testing.assert_allclose((A * B).homogeneous, A.homogeneous @ B.homogeneous, atol=1e-15)
    np.testing.assert_allclose(A.inverse().homogeneous, np.linalg.inv(A.homogeneous),
                               atol=1e-15)
    assert (A * A.inverse()).isclose(Pose.identity(), atol=1e-15)


def test_isclose_and_pickle():
    assert A.isclose(Pose(A.rotation, A.translation + 1e-12))
    assert not A.isclose(Pose(A.rotation, A.translation + 1e-6))
    copy = pickle.loads(pickle.dumps(A))
    assert isinstance(copy, Pose) and copy.isclose(A, atol=0)
    assert not copy.rotation.flags.writeable
    assert "translation=[0.1, -0.2, 0.3]" in repr(A)
