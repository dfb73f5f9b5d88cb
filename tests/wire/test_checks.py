"""wire.checks: what a server accepts as a vector or a rotation, and how it repairs one."""

from __future__ import annotations

import numpy as np
import pytest

from wire.checks import (
    ROTATION_TOLERANCE,
    cross3,
    finite_vector,
    gram_schmidt,
    rotation_matrix,
    vector_norm,
)
from wire.errors import InvalidArgumentError


def rotation_z(angle: float) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def test_finite_vector_takes_any_iterable_of_the_right_length():
    array = finite_vector((v for v in (1, 2, 3)), 3, "delta")
    assert array.dtype == float and array.tolist() == [1.0, 2.0, 3.0]


@pytest.mark.parametrize(("values", "reason"), [
    ([1.0, 2.0], "BAD_LENGTH"),
    ([[1.0, 2.0, 3.0]], "BAD_LENGTH"),
    ([1.0, np.nan, 3.0], "NOT_FINITE"),
    ([1.0, 2.0, -np.inf], "NOT_FINITE"),
])
def test_finite_vector_refuses_with_a_reason_naming_the_value(values, reason):
    with pytest.raises(InvalidArgumentError) as error:
        finite_vector(values, 3, "delta_position_m")
    assert error.value.reason == reason and "delta_position_m" in error.value.message
    assert error.value.status_name == "INVALID_ARGUMENT"


def test_an_empty_rotation_is_the_identity():
    np.testing.assert_array_equal(rotation_matrix([], "r"), np.eye(3))


def test_a_rotation_is_kept_and_a_nearly_orthonormal_one_repaired():
    exact = rotation_z(0.3)
    np.testing.assert_allclose(rotation_matrix(exact.reshape(9), "r"), exact, atol=1e-15)
    typed = np.round(exact, 4)  # as typed by hand: off by about 1e-5
    repaired = rotation_matrix(typed.reshape(9), "r")
    np.testing.assert_allclose(repaired.T @ repaired, np.eye(3), atol=1e-12)
    assert np.linalg.det(repaired) == pytest.approx(1.0)
    np.testing.assert_allclose(repaired, exact, atol=1e-4)


@pytest.mark.parametrize("matrix", [
    2 * np.eye(3),  # not orthonormal
    np.diag([1.0, 1.0, -1.0]),  # a reflection: orthonormal, det -1
    np.eye(3) + 2 * ROTATION_TOLERANCE,  # just past the tolerance
])
def test_what_is_not_a_rotation_is_refused(matrix):
    with pytest.raises(InvalidArgumentError) as error:
        rotation_matrix(matrix.reshape(9), "delta_rotation")
    assert error.value.reason == "NOT_A_ROTATION" and "delta_rotation" in error.value.message


def test_a_rotation_needs_nine_finite_values():
    with pytest.raises(InvalidArgumentError) as error:
        rotation_matrix([1.0, 0.0, 0.0, 0.0, 1.0, 0.0], "r")
    assert error.value.reason == "BAD_LENGTH"
    with pytest.raises(InvalidArgumentError) as error:
        rotation_matrix([np.nan] * 9, "r")
    assert error.value.reason == "NOT_FINITE"


def test_gram_schmidt_keeps_the_first_column_and_makes_a_proper_rotation():
    rng = np.random.default_rng(7)
    matrix = rotation_z(1.0) + rng.normal(scale=0.01, size=(3, 3))
    result = gram_schmidt(matrix)
    np.testing.assert_allclose(result.T @ result, np.eye(3), atol=1e-12)
    assert np.linalg.det(result) == pytest.approx(1.0)
    np.testing.assert_allclose(result[:, 0], matrix[:, 0] / np.linalg.norm(matrix[:, 0]))


def test_the_fast_cross_product_is_numpys_to_the_bit():
    generator = np.random.default_rng(7)
    for _ in range(200):
        a, b = generator.normal(scale=10.0, size=(2, 3))
        assert np.array_equal(cross3(a, b), np.cross(a, b))


def test_the_norm_that_keeps_the_lock_is_numpys_within_rounding():
    generator = np.random.default_rng(11)
    for size in (3, 6, 9):
        for _ in range(100):
            vector = generator.normal(scale=10.0, size=size)
            assert vector_norm(vector) == pytest.approx(np.linalg.norm(vector), rel=1e-15)
    assert vector_norm([3.0, 4.0]) == 5.0 and vector_norm(np.zeros(3)) == 0.0


def test_the_gram_schmidt_in_floats_is_numpys_within_rounding():
    generator = np.random.default_rng(5)
    for _ in range(200):
        matrix = generator.normal(size=(3, 3))
        x = matrix[:, 0] / np.linalg.norm(matrix[:, 0])
        y = matrix[:, 1] - (x @ matrix[:, 1]) * x
        y /= np.linalg.norm(y)
        np.testing.assert_allclose(gram_schmidt(matrix), np.column_stack([x, y, np.cross(x, y)]),
                                   rtol=0, atol=1e-14)
