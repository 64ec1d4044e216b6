"""Rotation matrices ↔ quaternions against scipy, at random rotations and at half-turns."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from oracles import (
    U,
    half_turns,
    random_unit,
    rotation_error,
    to_scipy,
    unit_quaternions,
)
from scipy.spatial.transform import Rotation
from uncompiled import uncompiled_twin

from ga_rotors import matrix
from ga_rotors import quaternion as Q
from ga_rotors.errors import InputError


@given(unit_quaternions)
def test_round_trip_through_matrix(q):
    # M has ~3 roundings per entry; back to q: a sqrt, a division, a normalisation.
    # The geodesic angle is twice the component error: 16 ulp.
    assert Q.distance(matrix.to_quaternion(matrix.from_quaternion(q)), q) <= 16 * U


def test_from_quaternion_matches_scipy():
    q = np.concatenate([random_unit(30, 100), half_turns(31, 20), [[1.0, 0, 0, 0]]])
    assert np.allclose(matrix.from_quaternion(q), to_scipy(q).as_matrix(), rtol=0, atol=8 * U)


def test_to_quaternion_matches_scipy_on_random_rotations():
    r = Rotation.from_quat(random_unit(32, 200))
    q = matrix.to_quaternion(r.as_matrix())
    assert np.all(q[:, 0] >= 0)
    assert rotation_error(q, r).max() <= 16 * U


def test_identity_is_exact():
    assert np.array_equal(matrix.to_quaternion(np.eye(3)), [1.0, 0, 0, 0])
    assert np.array_equal(matrix.from_quaternion([1.0, 0, 0, 0]), np.eye(3))


def test_batched_shapes():
    m = Rotation.from_quat(random_unit(34, 6)).as_matrix().reshape(2, 3, 3, 3)
    assert matrix.to_quaternion(m).shape == (2, 3, 4)
    assert matrix.from_quaternion(random_unit(35, 6).reshape(3, 2, 4)).shape == (3, 2, 3, 3)


@pytest.mark.parametrize(
    "m, message",
    [
        (np.diag([1.0, 1.0, -1.0]), "det -1"),
        (np.diag([1.0, -1.0, -1.0]) * -1.0, "det -1"),
        (1.00001 * np.eye(3), "orthonormal"),
        ([[1.0, 0.1, 0], [0, 1.0, 0], [0, 0, 1.0]], "orthonormal"),
        (np.eye(4), r"shape \(\.\.\., 3, 3\)"),
        (np.ones(3), r"shape \(\.\.\., 3, 3\)"),
        ([[np.nan, 0, 0], [0, 1.0, 0], [0, 0, 1.0]], "m: contains nan"),
    ],
)
def test_bad_matrices_are_rejected(m, message):
    with pytest.raises(InputError, match=message):
        matrix.to_quaternion(m)


test_matrix_agrees_uncompiled = uncompiled_twin(__file__)
