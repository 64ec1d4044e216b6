"""The scalar kernels every compiled loop shares, against independent oracles.

Also run uncompiled: ``test_kernels_agree_uncompiled`` re-runs this file in a
subprocess with NUMBA_DISABLE_JIT=1, so the plain-Python kernels are tested too.
"""

from __future__ import annotations

import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

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


@pytest.mark.parametrize("angle", [0.0, 1e-300, 1e-200, 1e-100, 1e-20, 1e-12, 1e-9])
def test_exp_log_exact_at_tiny_angles(angle):
    axis = np.array([2.0, -3.0, 6.0]) / 7.0
    r = tuple(angle * axis)
    q = K.quat_from_rotvec(r)
    assert q[0] == 1.0 or angle > 1e-9
    # vector part is half the rotation vector to full relative precision
    assert np.allclose(q[1:], 0.5 * np.array(r), rtol=1e-15, atol=0)
    back = np.array(K.rotvec_from_quat(q))
    assert np.allclose(back, r, rtol=1e-15, atol=0)


@pytest.mark.parametrize("eps", [0.0, 1e-12, 1e-8])
def test_log_exact_near_half_turn(eps):
    axis = np.array([1.0, 2.0, 2.0]) / 3.0
    angle = math.pi - eps
    q = K.quat_from_rotvec(tuple(angle * axis))
    back = np.array(K.rotvec_from_quat(q))
    # one rounding each in angle*axis, sin/cos, hypot, atan2 and the norm: 4 ulp of pi.
    # (2*acos(w) would be off by ~1e-8 at eps = 1e-12.)
    assert math.isclose(np.linalg.norm(back), angle, rel_tol=0, abs_tol=4 * math.ulp(math.pi))
    assert np.allclose(back / np.linalg.norm(back), axis, atol=1e-15)


def test_log_of_minus_one_chooses_z_axis():
    assert K.qlog_unit((-1.0, 0.0, 0.0, 0.0)) == (0.0, 0.0, math.pi)
    assert K.qlog_unit((1.0, 0.0, 0.0, 0.0)) == (0.0, 0.0, 0.0)
    assert K.rotvec_from_quat((-1.0, 0.0, 0.0, 0.0)) == (0.0, 0.0, 0.0)


@pytest.mark.parametrize("scale", [1e-300, 1e-160, 1.0, 1e160, 1e300])
def test_norm_has_no_overflow_or_underflow(scale):
    q = (3 * scale, 4 * scale, 12 * scale, 84 * scale)
    assert math.isclose(K.qnorm(q), 85 * scale, rel_tol=1e-15)
    assert math.isclose(K.hypot3(3 * scale, 4 * scale, 12 * scale), 13 * scale, rel_tol=1e-15)


@pytest.mark.parametrize("delta", [0.0, 1e-15, 1e-12, 1e-9, 1e-6, 1.0, math.pi - 1e-9, math.pi])
def test_geodesic_angle_resolves_small_and_large(delta):
    a = unit((0.3, -0.5, 0.7, 0.2))
    b = K.qmul(a, K.quat_from_rotvec((0.0, delta, 0.0)))
    # b's components are rounded (half an ulp, ~1e-16 each), so differences are resolved
    # to ~1e-15 rad; 2*acos(.) would bottom out near 1e-8 rad.
    assert math.isclose(K.geodesic_angle(a, b), delta, rel_tol=1e-12, abs_tol=1e-15)
    # the double cover does not matter
    minus_b = tuple(-c for c in b)
    assert math.isclose(K.geodesic_angle(a, minus_b), delta, rel_tol=1e-12, abs_tol=1e-15)


@pytest.mark.skipif(os.environ.get("NUMBA_DISABLE_JIT") == "1", reason="already uncompiled")
def test_kernels_agree_uncompiled():
    env = {**os.environ, "NUMBA_DISABLE_JIT": "1"}
    root = Path(__file__).resolve().parent.parent
    proc = subprocess.run(
        [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", __file__],
        cwd=root, env=env, capture_output=True, text=True,
    )
    assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-3000:]
