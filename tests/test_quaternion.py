"""The vectorised quaternion API against scipy, closed forms and algebraic laws.

Tolerances are round-off budgets: a unit quaternion's components carry ~1 ulp (1.1e-16)
each, a product or rotation adds a handful of roundings, so results that pass through
k such steps are compared at a few k x 1e-16; each test says which budget it uses.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from oracles import (
    U,
    from_scipy,
    half_turns,
    random_axes,
    random_unit,
    rotation_error,
    to_scipy,
    unit_quaternions,
    vectors,
)
from scipy.spatial.transform import Rotation, Slerp
from uncompiled import uncompiled_twin

from ga_rotors import quaternion as Q
from ga_rotors.errors import InputError

general = st.tuples(*(st.floats(-1e3, 1e3, allow_nan=False),) * 4).map(np.array)


# --- algebra -------------------------------------------------------------------------


@given(general, general)
def test_norm_is_multiplicative(p, q):
    # |pq| and |p||q| each carry ~3 roundings (products, sums, sqrt): 8 ulp relative.
    assert math.isclose(
        Q.norm(Q.multiply(p, q)), Q.norm(p) * Q.norm(q), rel_tol=8 * U, abs_tol=1e-300
    )


@given(general, general, general)
def test_product_is_associative(p, q, r):
    # each component is a 4-term sum of products of size |p||q||r|: ~8 ulp of that scale.
    scale = Q.norm(p) * Q.norm(q) * Q.norm(r)
    left = Q.multiply(Q.multiply(p, q), r)
    right = Q.multiply(p, Q.multiply(q, r))
    assert np.allclose(left, right, rtol=0, atol=16 * U * scale)


@given(unit_quaternions, unit_quaternions)
def test_composition_matches_scipy(p, q):
    # composing then comparing: ~6 roundings per component; the geodesic angle is 2x that.
    assert rotation_error(Q.multiply(p, q), to_scipy(p) * to_scipy(q)) <= 16 * U


@given(general)
def test_inverse_and_division(q):
    if Q.norm(q) < 1e-3:
        return
    assert np.allclose(Q.multiply(q, Q.inverse(q)), [1, 0, 0, 0], rtol=0, atol=16 * U)
    p = np.array([0.5, -1.0, 2.0, 0.25])
    scale = Q.norm(p)
    assert np.allclose(Q.divide(Q.multiply(p, q), q), p, rtol=0, atol=32 * U * scale)


def test_notes_inverse_is_wrong_for_non_unit_quaternions():
    q = np.array([1.0, 2.0, 3.0, 4.0])
    notes = Q.conjugate(q) / Q.norm(q)  # the notes print q* / |q|
    assert not np.allclose(Q.multiply(q, notes), [1, 0, 0, 0])
    assert np.allclose(Q.multiply(q, Q.inverse(q)), [1, 0, 0, 0], rtol=0, atol=8 * U)


def test_conjugate_reverses_products():
    p, q = np.array([1.0, 2.0, -3.0, 0.5]), np.array([-0.5, 1.0, 4.0, 2.0])
    assert np.allclose(
        Q.conjugate(Q.multiply(p, q)), Q.multiply(Q.conjugate(q), Q.conjugate(p)), rtol=1e-15
    )


def test_addition_and_subtraction_are_array_arithmetic():
    p, q = np.array([1.0, 2.0, 3.0, 4.0]), np.array([0.5, 0.5, 0.5, 0.5])
    assert np.array_equal(p + q, [1.5, 2.5, 3.5, 4.5]) and np.array_equal(
        p - q, [0.5, 1.5, 2.5, 3.5]
    )


# --- rotation of vectors ---------------------------------------------------------------


@given(unit_quaternions, vectors, vectors)
def test_rotation_preserves_length_and_handedness(q, a, b):
    ra, rb = Q.rotate(q, a), Q.rotate(q, b)
    scale = 1.0 + np.linalg.norm(a)
    assert math.isclose(np.linalg.norm(ra), np.linalg.norm(a), rel_tol=0, abs_tol=16 * U * scale)
    # handedness: R(a x b) = R(a) x R(b) (a reflection would flip the sign)
    cross_scale = (1.0 + np.linalg.norm(a)) * (1.0 + np.linalg.norm(b))
    assert np.allclose(
        Q.rotate(q, np.cross(a, b)), np.cross(ra, rb), rtol=0, atol=32 * U * cross_scale
    )


def test_rotate_matches_scipy_on_random_and_half_turns():
    v = np.random.default_rng(3).normal(size=(200, 3))
    for q in (random_unit(1, 200), half_turns(2, 200)):
        assert np.allclose(Q.rotate(q, v), to_scipy(q).apply(v), rtol=0, atol=16 * U * 5)


def test_rotate_is_active_body_to_space():
    q = Q.from_axis_angle([0, 0, 1], np.pi / 2)
    assert np.allclose(Q.rotate(q, [1.0, 0, 0]), [0, 1, 0], atol=2 * U)


# --- broadcasting and shapes ------------------------------------------------------------


def test_single_quaternion_gives_single_result():
    assert Q.multiply([1.0, 0, 0, 0], [0, 1.0, 0, 0]).shape == (4,)
    assert Q.rotate([1.0, 0, 0, 0], [1.0, 2, 3]).shape == (3,)
    assert isinstance(Q.norm([1.0, 0, 0, 0]), float)


def test_mixed_broadcasting_matches_pairwise_products():
    p = random_unit(5, 15).reshape(5, 1, 3, 4)
    q = random_unit(6, 7).reshape(1, 7, 1, 4)
    out = Q.multiply(p, q)
    assert out.shape == (5, 7, 3, 4)
    for a, b, c in [(0, 0, 0), (4, 6, 2), (2, 3, 1)]:
        assert np.array_equal(out[a, b, c], Q.multiply(p[a, 0, c], q[0, b, 0]))


def test_one_quaternion_against_many_vectors_and_empty_batches():
    q = random_unit(7, 1)[0]
    v = np.random.default_rng(8).normal(size=(4, 6, 3))
    assert np.array_equal(Q.rotate(q, v)[2, 3], Q.rotate(q, v[2, 3]))
    assert Q.multiply(np.empty((0, 4)), [1.0, 0, 0, 0]).shape == (0, 4)


def test_non_contiguous_input_is_handled():
    q = random_unit(9, 10)
    view = np.asfortranarray(q)[::2]
    assert np.array_equal(Q.multiply(view, view), Q.multiply(q[::2].copy(), q[::2].copy()))


@pytest.mark.parametrize(
    "call, message",
    [
        (
            lambda: Q.multiply([1.0, 0, 0], [1.0, 0, 0, 0]),
            r"p: expected an array of shape \(\.\.\., 4\)",
        ),
        (
            lambda: Q.multiply([1.0, 0, 0, 0], [[1.0, np.nan, 0, 0]]),
            r"q: contains nan at index \(0, 1\)",
        ),
        (lambda: Q.multiply([np.inf, 0, 0, 0], [1.0, 0, 0, 0]), r"p: contains inf at index \(0,\)"),
        (lambda: Q.multiply(np.ones((2, 4)), np.ones((3, 4))), r"broadcast: p \(2,\), q \(3,\)"),
        (lambda: Q.multiply("wxyz", [1.0, 0, 0, 0]), "p: expected real numbers"),
        (lambda: Q.multiply([1e200, 0, 0, 0], [1e200, 0, 0, 0]), "overflow"),
        (lambda: Q.inverse([[1.0, 0, 0, 0], [0.0, 0, 0, 0]]), r"q: expected nonzero .* \(1,\)"),
        (lambda: Q.divide([1.0, 0, 0, 0], [0.0, 0, 0, 0]), "q: expected nonzero"),
        (lambda: Q.normalize([0.0, 0, 0, 0]), "q: expected nonzero"),
        (lambda: Q.log([0.0, 0, 0, 0]), "q: expected nonzero"),
        (lambda: Q.exp([-np.inf, 0, 0, 0]), "q: contains -inf"),
        (lambda: Q.rotate([1.0, 0, 0, 0], [1.0, np.nan, 0]), "v: contains nan"),
        (lambda: Q.angle([0.5, 0, 0, 0]), "q: expected unit quaternions"),
        (lambda: Q.slerp([1.0, 0, 0, 0], [2.0, 0, 0, 0], 0.5), "q1: expected unit"),
        (lambda: Q.slerp([1.0, 0, 0, 0], [1.0, 0, 0, 0], np.nan), "t: contains nan"),
        (lambda: Q.distance([1.0, 0, 0, 0], [0.0, 0, 0, 0]), "q1: expected unit"),
        (lambda: Q.from_axis_angle([0.0, 0, 0], 1.0), "axis: expected nonzero"),
        (lambda: Q.from_two_vectors([1.0, 0, 0], [0.0, 0, 0]), "v: expected nonzero"),
        (lambda: Q.to_rotation_vector([1.0, 1.0, 0, 0]), "q: expected unit"),
    ],
)
def test_bad_input_raises_input_error_naming_the_argument(call, message):
    with pytest.raises(InputError, match=message):
        call()
    assert issubclass(InputError, ValueError)


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_non_finite_deep_in_a_large_batch_is_found_and_located(bad):
    # the loops check in-loop without an early exit; the slow path must still name the
    # argument and the exact index
    q = random_unit(23, 3000).reshape(3, 1000, 4)
    v = np.random.default_rng(24).normal(size=(3, 1000, 3))
    v[2, 777, 1] = bad
    with pytest.raises(InputError, match=r"v: contains .*inf|v: contains nan") as err:
        Q.rotate(q, v)
    assert "(2, 777, 1)" in str(err.value)
    q[1, 5, 0] = 1.5
    with pytest.raises(InputError, match=r"q: expected unit .* at index \(1, 5\)"):
        Q.rotate(q, np.ones(3))


# --- angle, axis, latitude and longitude ---------------------------------------------------


def test_angle_and_axis_ignore_the_sign_of_q_and_match_scipy():
    q = np.concatenate([random_unit(10, 100), half_turns(11, 20)])
    axis, alpha = Q.to_axis_angle(q)
    assert np.all((0 <= alpha) & (alpha <= math.pi))
    assert np.allclose(alpha, to_scipy(q).magnitude(), rtol=0, atol=8 * U)
    assert np.array_equal(Q.angle(-q[:100]), alpha[:100])
    assert rotation_error(Q.from_axis_angle(axis, alpha), to_scipy(q)).max() <= 16 * U


def test_axis_at_angle_zero_is_documented_plus_z_never_nan():
    axis, alpha = Q.to_axis_angle([[1.0, 0, 0, 0], [-1.0, 0, 0, 0]])
    assert np.array_equal(axis, [[0, 0, 1.0], [0, 0, 1.0]]) and np.array_equal(alpha, [0, 0])


@pytest.mark.parametrize(
    "axis, lat, lon",
    [
        ((1.0, 1.0, 0.0), 0.0, 45.0),
        ((-1.0, 1.0, 0.0), 0.0, 135.0),
        ((-1.0, -1.0, 0.0), 0.0, -135.0),
        ((1.0, -1.0, 0.0), 0.0, -45.0),
        ((0.0, -1.0, math.sqrt(2)), 54.735610317245346, -90.0),
        ((0.0, 0.0, -1.0), -90.0, 0.0),
    ],
)
def test_latitude_longitude_in_every_quadrant(axis, lat, lon):
    q = Q.from_axis_angle(axis, 0.7)
    got = Q.latitude_longitude(q, degrees=True)
    assert got == pytest.approx((lat, lon), abs=1e-12)
    # the same rotation written with -q has the same axis
    assert Q.latitude_longitude(-q, degrees=True) == pytest.approx((lat, lon), abs=1e-12)


def test_notes_longitude_formula_loses_the_quadrant():
    q = Q.from_axis_angle([-1.0, -1.0, 0.0], 0.7)
    notes = math.degrees(math.atan(q[2] / q[1]))
    assert notes == pytest.approx(45.0) and Q.latitude_longitude(q, degrees=True)[
        1
    ] == pytest.approx(-135.0)


def test_latitude_longitude_broadcasts_in_radians():
    lat, lon = Q.latitude_longitude(Q.from_axis_angle(random_axes(12, 6), 0.5))
    u = random_axes(12, 6)
    assert np.allclose(lat, np.arcsin(u[:, 2]), atol=1e-14)
    assert np.allclose(lon, np.arctan2(u[:, 1], u[:, 0]), atol=1e-14)


# --- converters round-trip and agree with scipy -----------------------------------------------


@given(unit_quaternions)
def test_rotation_vector_round_trip(q):
    r = Q.to_rotation_vector(q)
    assert np.linalg.norm(r) <= math.pi + 4 * U * math.pi
    assert rotation_error(Q.from_rotation_vector(r), to_scipy(q)) <= 16 * U


def test_rotation_vector_matches_scipy_on_random_and_half_turns():
    q = np.concatenate([random_unit(13, 100), half_turns(14, 20), [[1.0, 0, 0, 0]]])
    r = Q.to_rotation_vector(q)
    assert rotation_error(q, Rotation.from_rotvec(r)).max() <= 16 * U
    rv = np.random.default_rng(15).normal(size=(50, 3))
    assert rotation_error(Q.from_rotation_vector(rv), Rotation.from_rotvec(rv)).max() <= 16 * U


@given(unit_quaternions)
def test_axis_angle_round_trip(q):
    axis, alpha = Q.to_axis_angle(q)
    assert rotation_error(Q.from_axis_angle(axis, alpha), to_scipy(q)) <= 16 * U


def test_from_axis_angle_accepts_degrees_and_any_axis_length():
    q = Q.from_axis_angle([0.0, 0.0, 5.0], [90.0, -90.0], degrees=True)
    assert np.allclose(
        q, [[math.sqrt(0.5), 0, 0, math.sqrt(0.5)], [math.sqrt(0.5), 0, 0, -math.sqrt(0.5)]]
    )


@given(general)
def test_exp_log_round_trip(q):
    if Q.norm(q) < 1e-3:
        return
    q = q / 100.0  # keep exp(w) in range
    assert np.allclose(Q.exp(Q.log(q)), q, rtol=0, atol=32 * U * Q.norm(q))


def test_exp_of_pure_half_rotation_vector_is_rotation():
    r = np.array([0.3, -1.2, 2.0])
    assert np.allclose(Q.exp(np.concatenate([[0.0], r / 2])), Q.from_rotation_vector(r), atol=2 * U)


# --- slerp and distance ------------------------------------------------------------------


def test_slerp_matches_scipy_on_random_pairs():
    a, b = random_unit(16, 50), random_unit(17, 50)
    for t in (0.0, 0.25, 0.5, 1.0):
        ours = Q.slerp(a, b, t)
        for k in range(0, 50, 7):
            theirs = Slerp([0.0, 1.0], to_scipy(np.stack([a[k], b[k]])))([t])
            assert rotation_error(ours[k], theirs)[0] <= 64 * U


def test_slerp_takes_the_shorter_arc():
    a = Q.from_axis_angle([0, 0, 1.0], 0.0)
    b = -Q.from_axis_angle([0, 0, 1.0], 0.5)  # same rotation as +0.5, other hemisphere
    assert math.isclose(Q.angle(Q.slerp(a, b, 0.5)), 0.25, rel_tol=4 * U)


@given(unit_quaternions, unit_quaternions)
def test_distance_matches_scipy_and_is_symmetric(p, q):
    d = Q.distance(p, q)
    assert math.isclose(d, rotation_error(p, to_scipy(q)), abs_tol=16 * U)
    assert d == Q.distance(q, p) or math.isclose(d, Q.distance(q, p), abs_tol=4 * U)


# --- two vectors --------------------------------------------------------------------------


def test_two_vectors_matches_scipy_align_vectors():
    rng = np.random.default_rng(20)
    u, v = rng.normal(size=(30, 3)), rng.normal(size=(30, 3))
    q = Q.from_two_vectors(u, v)
    for k in range(30):
        oracle, _ = Rotation.align_vectors(v[k : k + 1], u[k : k + 1])
        assert rotation_error(q[k], oracle) <= 16 * U
    unit_u = u / np.linalg.norm(u, axis=1, keepdims=True)
    unit_v = v / np.linalg.norm(v, axis=1, keepdims=True)
    assert np.allclose(Q.rotate(q, unit_u), unit_v, rtol=0, atol=8 * U)


def test_two_vectors_parallel_is_identity_and_antiparallel_is_documented_half_turn():
    assert np.array_equal(Q.from_two_vectors([1.0, 2, 3], [3.0, 6, 9]), [1, 0, 0, 0])
    assert np.array_equal(Q.from_two_vectors([0, 0, 1.0], [0, 0, -2.0]), [0, 0, 1.0, 0])
    u = random_axes(21, 10)
    q = Q.from_two_vectors(u, -u)
    assert np.all(q[:, 0] == 0.0)
    assert np.allclose(Q.rotate(q, u), -u, rtol=0, atol=4 * U)


def test_from_two_vectors_agrees_with_from_matrix_round_trip():
    q = Q.from_two_vectors([1.0, 0, 0], [0, 1.0, 1.0])
    assert Q.distance(Q.from_matrix(Q.to_matrix(q)), q) <= 8 * U


def test_reexported_converters_are_the_module_functions():
    from ga_rotors import euler, matrix

    assert Q.from_matrix is matrix.to_quaternion and Q.to_matrix is matrix.from_quaternion
    assert Q.from_euler is euler.to_quaternion and Q.to_euler is euler.from_quaternion


def test_from_scipy_round_trip_helper_is_consistent():
    q = random_unit(22, 5)
    assert rotation_error(from_scipy(to_scipy(q)), to_scipy(q)).max() <= 4 * U


test_quaternion_agrees_uncompiled = uncompiled_twin(__file__)
