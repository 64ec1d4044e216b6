"""The generated rotor kernels: in sync with their generator, and equal to clifford's algebra."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from ga_rotors import _generate_rotor_kernels as gen
from ga_rotors import _kernels as K
from ga_rotors import _rotor_kernels as RK

clifford = pytest.importorskip("clifford")
layout, blades = clifford.Cl(3)
EVEN = [i for i, b in enumerate(layout.bladeTupList) if len(b) % 2 == 0]
I = blades["e123"]

finite = st.floats(-10, 10, allow_nan=False)
even4 = st.tuples(finite, finite, finite, finite)
vec3 = st.tuples(finite, finite, finite)


def mv(coeffs):
    """An even multivector from (1, e12, e13, e23) coefficients."""
    v = np.zeros(layout.gaDims)
    v[EVEN] = coeffs
    return layout.MultiVector(v)


def coeffs(m):
    return np.asarray(m.value)[EVEN]


def vector(w):
    return w[0] * blades["e1"] + w[1] * blades["e2"] + w[2] * blades["e3"]


def test_committed_file_is_what_the_generator_writes():
    committed = gen.TARGET.read_text(encoding="utf-8")
    assert committed == gen.generate(), "run: python -m ga_rotors._generate_rotor_kernels"


def test_even_blade_order_is_cliffords():
    assert [layout.bladeTupList[i] for i in EVEN] == [(), (1, 2), (1, 3), (2, 3)]


# Tolerances: each output coefficient is a sum of 4 products of inputs ≤ 10 in magnitude;
# both sides round each product and sum (≤ 4 roundings of values ≤ 400): 1e-12 absolute
# is ~10x that worst case.
@given(even4, even4)
def test_rmul_is_the_geometric_product(a, b):
    assert np.allclose(RK.rmul(a, b), coeffs(mv(a) * mv(b)), rtol=0, atol=1e-12)


@given(even4)
def test_rrev_is_reversion(a):
    assert np.array_equal(RK.rrev(a), coeffs(~mv(a)))


@given(vec3)
def test_omega_bivector_is_minus_i_omega(w):
    expected = -(I * vector(w))
    assert np.array_equal(np.array(RK.omega_bivector(w)), np.asarray(expected.value)[4:7])
    assert np.all(np.asarray(expected.value)[[0, 1, 2, 3, 7]] == 0)


@given(even4, vec3)
def test_rotor_rate_is_half_r_omega(a, w):
    expected = 0.5 * mv(a) * (-(I * vector(w)))
    assert np.allclose(RK.rotor_rate(a, w), coeffs(expected), rtol=0, atol=1e-12)


@given(even4, even4)
def test_quaternion_map_is_an_algebra_isomorphism(p, q):
    # φ(p ⊗ q) = φ(p) φ(q): the map i -> -e23, j -> -e31, k -> -e12 preserves products.
    assert np.allclose(
        RK.rotor_from_quat(K.qmul(p, q)), RK.rmul(RK.rotor_from_quat(p), RK.rotor_from_quat(q)),
        rtol=0, atol=1e-12,
    )  # fmt: skip
    assert RK.quat_from_rotor(RK.rotor_from_quat(p)) == p


@given(even4.filter(lambda a: sum(c * c for c in a) > 1e-3), vec3)
def test_rotor_and_quaternion_rotate_vectors_alike(a, v):
    # R v ~R (clifford) equals q v q* (Hamilton) for the corresponding unit elements.
    n = np.sqrt(sum(c * c for c in a))
    q = tuple(c / n for c in a)
    R = mv(RK.rotor_from_quat(q))
    rotated = R * vector(v) * ~R
    expected = np.array(K.qrotate(q, v))
    got = np.array([rotated[blades[e]] for e in ("e1", "e2", "e3")])
    assert np.allclose(got, expected, rtol=0, atol=1e-12 * (1 + np.abs(v).max()))


@given(even4)
def test_quaternion_map_is_the_isomorphism_table(q):
    from ga_rotors import isomorphism

    full = isomorphism.to_even(q)
    assert np.array_equal(np.array(RK.rotor_from_quat(q)), full[list(isomorphism.EVEN)])


def test_rotor_rate_matches_quaternion_rate_through_the_map():
    rng = np.random.default_rng(4)
    for _ in range(50):
        q = tuple(rng.normal(size=4))
        w = tuple(rng.normal(size=3))
        dq = K.qmul_pure(q, w)
        half = tuple(0.5 * c for c in dq)
        assert np.allclose(RK.rotor_rate(RK.rotor_from_quat(q), w), RK.rotor_from_quat(half),
                           rtol=0, atol=1e-14)  # fmt: skip
