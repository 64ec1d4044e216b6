"""The scalar kernels every compiled loop shares, against independent oracles.

Also run uncompiled: ``test_kernels_agree_uncompiled`` re-runs this file in a
subprocess with NUMBA_DISABLE_JIT=1 (tests/uncompiled.py), so the plain-Python kernels
are tested too.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation
from uncompiled import uncompiled_twin

from ga_rotors import _kernels as K

finite = st.floats(-1e3, 1e3, allow_nan=False)
quat = st.tuples(finite, finite, finite, finite).filter(lambda q: sum(c * c for c in q) > 1e-6)
vec = st.tuples(finite, finite, finite)
small_vec = st.tuples(*(st.floats(-10, 10, allow_nan=False),) * 3)


def unit(q):
    n = math.sqrt(sum(c * c for c in q))
    return tuple(c / n for c in q)


def as_matrix(q):
    """Independent oracle: scipy wants scalar-last."""
    return Rotation.from_quat([q[1], q[2], q[3], q[0]]).as_matrix()


def test_basis_products_are_hamilton():
    one, i, j, k = (1.0, 0, 0, 0), (0, 1.0, 0, 0), (0, 0, 1.0, 0), (0, 0, 0, 1.0)
    neg = lambda q: tuple(-c for c in q)  # noqa: E731
    assert K.qmul(i, j) == k and K.qmul(j, k) == i and K.qmul(k, i) == j
    assert K.qmul(j, i) == neg(k) and K.qmul(k, j) == neg(i) and K.qmul(i, k) == neg(j)
    for e in (i, j, k):
        assert K.qmul(e, e) == neg(one)
    assert K.qmul(K.qmul(i, j), k) == neg(one)


@given(quat, quat, quat)
def test_product_is_associative_and_norm_multiplicative(a, b, c):
    left = np.array(K.qmul(K.qmul(a, b), c))
    right = np.array(K.qmul(a, K.qmul(b, c)))
    scale = K.qnorm(a) * K.qnorm(b) * K.qnorm(c)
    assert np.allclose(left, right, atol=1e-12 * scale)
    assert math.isclose(K.qnorm(K.qmul(a, b)), K.qnorm(a) * K.qnorm(b), rel_tol=1e-13)


@given(quat, vec)
def test_qmul_pure_is_product_with_zero_scalar(a, v):
    assert np.allclose(K.qmul_pure(a, v), K.qmul(a, (0.0, *v)), rtol=0, atol=1e-9)


@given(quat, vec)
def test_rotate_matches_sandwich_and_scipy(q, v):
    q = unit(q)
    fast = np.array(K.qrotate(q, v))
    sandwich = np.array(K.qmul(K.qmul(q, (0.0, *v)), K.qconj(q))[1:])
    oracle = as_matrix(q) @ np.array(v)
    tol = 1e-12 * (1 + np.linalg.norm(v))
    assert np.allclose(fast, sandwich, atol=tol)
    assert np.allclose(fast, oracle, atol=tol)


@given(small_vec)
def test_rotvec_roundtrip_and_scipy(r):
    q = K.quat_from_rotvec(r)
    assert math.isclose(K.qnorm(q), 1.0, abs_tol=1e-15)
    oracle = Rotation.from_rotvec(r).as_matrix()
    assert np.allclose(as_matrix(q), oracle, atol=1e-12)
    back = K.rotvec_from_quat(q)
    assert np.allclose(as_matrix(K.quat_from_rotvec(back)), oracle, atol=1e-12)
    assert np.linalg.norm(back) <= math.pi + 1e-12


@pytest.mark.parametrize("scale", [1e-300, 1e-160, 1.0, 1e160, 1e300])
def test_norm_has_no_overflow_or_underflow(scale):
    q = (3 * scale, 4 * scale, 12 * scale, 84 * scale)
    assert math.isclose(K.qnorm(q), 85 * scale, rel_tol=1e-15)
    assert math.isclose(K.hypot3(3 * scale, 4 * scale, 12 * scale), 13 * scale, rel_tol=1e-15)
    assert math.isclose(K.norm2(3 * scale, 4 * scale), 5 * scale, rel_tol=1e-15)


@given(st.floats(allow_nan=False, allow_infinity=False), st.floats(allow_nan=False,
       allow_infinity=False))  # fmt: skip
def test_norm2_is_hypot_within_an_ulp(x, y):
    # every magnitude, subnormals and the largest floats included: the sum of squares
    # where it is normal, hypot where it is not
    exact = math.hypot(x, y)
    if math.isinf(exact):  # beyond the largest float: both overflow
        assert K.norm2(x, y) == exact
    else:
        assert abs(K.norm2(x, y) - exact) <= math.ulp(exact)


@given(quat)
def test_inverse_is_conjugate_over_norm_squared(a):
    prod = K.qmul(a, K.qinverse(a))
    # |a|^2 and four products each round once: the identity to ~10 ulp.
    assert np.allclose(prod, (1.0, 0.0, 0.0, 0.0), rtol=0, atol=1e-14)


@pytest.mark.parametrize("scale", [1e-300, 1e-150, 1e150, 1e300])
def test_inverse_of_tiny_and_huge_has_no_underflow(scale):
    a = (0.0, 3 * scale, 0.0, 4 * scale)
    inv = K.qinverse(a)
    assert math.isclose(inv[1], -3 / (25 * scale), rel_tol=1e-15)


@pytest.mark.parametrize("angle", [1e-300, 1e-12, 1e-5, 0.3, 1.0, 1.5, math.pi / 2])
def test_expm1_of_rotation_keeps_relative_precision_of_cos_minus_one(angle):
    import mpmath as mp

    v = tuple(angle * c for c in (2.0 / 7.0, -3.0 / 7.0, 6.0 / 7.0))
    d = K.qexpm1_pure(v)
    with mp.workdps(50):
        s = mp.sqrt(sum(mp.mpf(c) ** 2 for c in v))
        want = [mp.cos(s) - 1] + [mp.sin(s) / s * mp.mpf(c) for c in v]
    # Half-angles up to π/2 (rotations up to π; beyond, sin s/s inherits hypot3's 1 ulp
    # amplified by |s cot s| > 1, the input's conditioning, as in qexp_pure).
    # −2 sin²(s/2): sin to 1 ulp, two products, and s = hypot3 to 1 ulp (entering twice):
    # ≤ 6 ulps relative in every component, where cos(s) − 1 has none left at 1e-12.
    for got, ref in zip(d, want, strict=True):
        assert abs(got - float(ref)) <= 6 * 2.0**-53 * abs(float(ref)) + 1e-320
    assert K.qexpm1_pure((0.0, 0.0, 0.0)) == (0.0, 0.0, 0.0, 0.0)
    assert all(math.isnan(c) for c in K.qexpm1_pure((math.inf, 0.0, 0.0)))


@given(quat, small_vec)
def test_qmul_exp_is_the_product_with_the_exponential(q, v):
    q = unit(q)
    got = np.array(K.qmul_exp(q, v))
    want = np.array(K.qmul(q, K.qexp_pure(v)))
    # Both round each component of a unit quaternion a few times (≤ 4 terms of size ≤ 1,
    # plus the exponential's own ≤ 2 ulps): 16 ulps of 1 covers either.
    assert np.allclose(got, want, rtol=0, atol=16 * 2.0**-53)


@given(quat)
def test_general_exp_inverts_log(a):
    a = tuple(c / 1e3 for c in a)  # keep e^w representable
    back = K.qexp(K.qlog(a))
    assert np.allclose(back, a, rtol=0, atol=1e-14 * K.qnorm(a))


@given(quat)
def test_axis_angle_kernel_matches_scipy_and_ignores_sign(a):
    q = unit(a)
    ux, uy, uz, ang = K.axis_angle_from_quat(q)
    assert 0.0 <= ang <= math.pi
    oracle = Rotation.from_rotvec(ang * np.array([ux, uy, uz])).as_matrix()
    assert np.allclose(oracle, as_matrix(q), atol=1e-13)
    assert K.axis_angle_from_quat(tuple(-c for c in q)) == (ux, uy, uz, ang) or q[0] == 0.0


def test_axis_at_angle_zero_is_plus_z():
    assert K.axis_angle_from_quat((1.0, 0.0, 0.0, 0.0)) == (0.0, 0.0, 1.0, 0.0)
    assert K.axis_angle_from_quat((-1.0, 0.0, 0.0, 0.0)) == (0.0, 0.0, 1.0, 0.0)


@given(vec, st.floats(-10, 10))
def test_axis_angle_quaternion_is_rotvec_quaternion(u, angle):
    n = math.sqrt(sum(c * c for c in u))
    if n < 1e-6:
        return
    q = K.quat_from_axis_angle(u, angle)
    oracle = Rotation.from_rotvec(angle * np.array(u) / n).as_matrix()
    assert np.allclose(as_matrix(q), oracle, atol=1e-13)


@given(quat, quat, st.floats(-2.0, 3.0))
def test_slerp_moves_at_constant_rate_along_shorter_arc(a, b, t):
    a, b = unit(a), unit(b)
    total = K.geodesic_angle(a, b)
    s = K.qslerp(a, b, t)
    # the distance to a is |t| x total while |t| x total <= pi; rounding of log, scaling and
    # exp (a few ulp each of an angle <= pi) gives ~1e-15 rad; 1e-13 is the margin for the
    # ill-conditioning of the angle of a product near a half-turn.
    if abs(t) * total <= math.pi - 1e-6:
        assert math.isclose(K.geodesic_angle(a, s), abs(t) * total, abs_tol=1e-13)
    assert math.isclose(K.qnorm(s), 1.0, abs_tol=1e-15)


@given(vec)
def test_perpendicular_is_unit_and_orthogonal(u):
    n = math.sqrt(sum(c * c for c in u))
    if n < 1e-6:
        return
    u = tuple(c / n for c in u)
    p = K.perpendicular(u)
    assert math.isclose(K.hypot3(*p), 1.0, rel_tol=1e-15)
    assert abs(np.dot(p, u)) < 1e-15


def test_perpendicular_documented_choices():
    assert K.perpendicular((1.0, 0.0, 0.0)) == (0.0, 0.0, 1.0)
    assert K.perpendicular((0.0, 0.0, 1.0)) == (0.0, 1.0, 0.0)
    assert K.perpendicular((0.0, 1.0, 0.0)) == (0.0, 0.0, -1.0)


@given(vec, vec)
def test_two_vectors_maps_u_onto_v_with_the_smallest_angle(u, v):
    nu, nv = np.linalg.norm(u), np.linalg.norm(v)
    if nu < 1e-6 or nv < 1e-6:
        return
    q = K.quat_from_two_vectors(u, v)
    assert math.isclose(K.qnorm(q), 1.0, abs_tol=1e-15)
    image = np.array(K.qrotate(q, tuple(np.array(u) / nu)))
    assert np.allclose(image, np.array(v) / nv, atol=2e-15)
    between = math.atan2(np.linalg.norm(np.cross(u, v)), np.dot(u, v))
    ang = K.axis_angle_from_quat(q)[3]
    assert math.isclose(ang, between, abs_tol=1e-14)


@pytest.mark.parametrize("eps", [1e-4, 1e-8, 1e-10, 1e-13])
def test_two_vectors_nearly_antiparallel_stays_exact(eps):
    u = np.array([0.6, 0.0, 0.8])
    v = -u + eps * np.array([0.8, 0.0, -0.6])
    q = K.quat_from_two_vectors(tuple(u), tuple(v))
    image = np.array(K.qrotate(q, tuple(u)))
    # without re-orthogonalising the axis the error is ~1e-16/eps (1e-3 at eps = 1e-13)
    assert np.allclose(image, v / np.linalg.norm(v), rtol=0, atol=1e-15)


def test_two_vectors_parallel_and_antiparallel_exact():
    assert K.quat_from_two_vectors((1.0, 2.0, 3.0), (2.0, 4.0, 6.0)) == (1.0, 0.0, 0.0, 0.0)
    assert K.quat_from_two_vectors((1.0, 0.0, 0.0), (-5.0, 0.0, 0.0)) == (0.0, 0.0, 0.0, 1.0)
    q = K.quat_from_two_vectors((1.0, 2.0, 3.0), (-1.0, -2.0, -3.0))
    assert q[0] == 0.0 and abs(np.dot(q[1:], (1.0, 2.0, 3.0))) < 1e-15


@given(quat)
def test_matrix_kernels_round_trip_and_match_scipy(a):
    q = unit(a)
    m = K.matrix_from_quat(q)
    assert np.allclose(np.reshape(m, (3, 3)), as_matrix(q), atol=1e-15 * 4)
    back = K.quat_from_matrix(m)
    assert back[0] >= 0.0
    assert K.geodesic_angle(back, q) <= 1e-15 * 8


@pytest.mark.parametrize("angle", [-7.0, -math.pi, 0.0, 1e-300, 0.5, math.pi, 7.0])
@pytest.mark.parametrize("axis", [0, 1, 2])
def test_axis_quat_is_rotation_about_basis_axis(axis, angle):
    r = np.zeros(3)
    r[axis] = angle
    assert K.geodesic_angle(K.axis_quat(axis, angle), K.quat_from_rotvec(tuple(r))) < 1e-15


@pytest.mark.parametrize("x", [-2 * math.pi + 1e-9, -math.pi, -1.0, 0.0, math.pi, 2 * math.pi])
def test_wrap_angle_lands_in_half_open_interval(x):
    y = K.wrap_angle(x)
    assert -math.pi < y <= math.pi
    assert math.isclose(math.cos(y), math.cos(x), abs_tol=1e-15)
    assert math.isclose(math.sin(y), math.sin(x), abs_tol=1e-15)


test_kernels_agree_uncompiled = uncompiled_twin(__file__)
