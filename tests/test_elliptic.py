"""Jacobi elliptic functions and integrals with the complementary parameter, against mpmath
at 30 digits, including m₁ down to 1e-30 where float m = 1 − m₁ has no digit of m₁ left."""

from __future__ import annotations

import warnings

import mpmath as mp
import numpy as np
import pytest

from ga_rotors.reference import elliptic

mp.mp.dps = 30

# Each function is a handful of roundings of arguments of size ≤ |u|: the absolute error
# model is c·ε·(1 + |u|) with c ~ 10; 16 leaves room for the final sqrt/products.
EPS = np.finfo(float).eps


def _bound(u):
    return 16 * EPS * (1 + abs(u))


@pytest.mark.parametrize("m1_text", ["0.7", "1e-3", "1e-8", "1e-14", "1e-30"])
def test_jacobi_near_and_far_from_m_equal_1(m1_text):
    with mp.workdps(70):  # m = 1 − 1e-30 must keep its m₁ digits in the oracle too
        m1 = mp.mpf(m1_text)
        m = 1 - m1
        k = float(mp.ellipk(m))
        for u in np.linspace(-2.6 * k, 4.3 * k, 11):
            sn, cn, dn = elliptic.jacobi(u, float(m), float(m1))
            for got, name in zip((sn, cn, dn), ("sn", "cn", "dn"), strict=True):
                want = mp.ellipfun(name, mp.mpf(u), m=m)
                assert abs(float(got - want)) <= _bound(u), (name, u)


def test_jacobi_separatrix_limit_is_hyperbolic():
    u = np.linspace(-5, 5, 11)
    sn, cn, dn = elliptic.jacobi(u, 1.0, 0.0)
    assert np.allclose(sn, np.tanh(u), rtol=0, atol=1e-16)
    assert np.allclose(cn, 1 / np.cosh(u), rtol=0, atol=1e-16) and np.array_equal(cn, dn)


def _mp_pi(u, n, m):
    k = mp.ellipk(m)
    j = mp.nint(u / (2 * k))
    r = u - 2 * j * k

    def f(t):
        return 1 / (1 - n * mp.ellipfun("sn", t, m=m) ** 2)

    whole = mp.quad(f, [0, k / 2, k]) if j else 0
    return 2 * j * whole + mp.quad(f, [0, r / 2, r])


@pytest.mark.parametrize("m1_text", ["0.3", "1e-6", "1e-14"])
@pytest.mark.parametrize("n", [-3.0, 0.999])
def test_pi_integral_against_quadrature(m1_text, n):
    m1 = mp.mpf(m1_text)
    m = 1 - m1
    k = float(mp.ellipk(m))
    for u in (0.99 * k, -2.4 * k):
        want = _mp_pi(mp.mpf(u), n, m)
        got = elliptic.pi_integral(u, n, float(m), float(m1), 1 - n)
        # Π is a sum of terms of size ≤ |Π| + |u| each carrying a few ulps.
        assert abs(float(want) - got) <= 16 * EPS * (1 + abs(u) + abs(float(want)))


def test_incomplete_first_any_amplitude():
    for m1 in ("0.5", "1e-10"):
        m = 1 - mp.mpf(m1)
        for phi in (0.3, 1.5, 2.9, -4.0, 10.0):
            got = elliptic.incomplete_first(phi, float(m), float(mp.mpf(m1)))
            assert abs(float(mp.ellipf(phi, m)) - got) <= 16 * EPS * (1 + abs(phi)) * 10


def test_pi_integral_rejects_pole():
    with pytest.raises(ValueError, match="n < 1"):
        elliptic.pi_integral(0.1, 1.0, 0.5, 0.5)


@pytest.mark.parametrize("m1_text", ["0.5", "1e-3", "1e-14"])
def test_jacobi_argument_inverts_jacobi_next_to_the_middle_axis(m1_text):
    # u = ±K (sn = ±1, cn → 0) is where F(atan2(sn, cn) | m) multiplied the rounding of
    # the amplitude by 1/dn = 1/√m₁ (measured 6e-10 in u at m₁ = 1e-14). From 70-digit
    # sn, cn rounded once (relative error ε/2 each), the argument must carry the few ulps
    # of |u| + 2K of the Carlson form only (see jacobi_argument's Notes).
    with mp.workdps(70):
        m1 = mp.mpf(m1_text)
        m = 1 - m1
        k = mp.ellipk(m)
        for u in (k, -k, k * (1 - mp.mpf(1e-9)), -k * (1 + mp.mpf(1e-6)), 1.7 * k, 0.3, 0):
            sn, cn = (float(mp.ellipfun(f, u, m=m)) for f in ("sn", "cn"))
            got = elliptic.jacobi_argument(sn, cn, float(m), float(m1))
            assert abs(got - float(u)) <= _bound(abs(float(u)) + 2 * float(k)), (m1_text, u)
    with pytest.raises(ValueError, match="both zero"):
        elliptic.jacobi_argument(0.0, 0.0, 0.5, 0.5)


@pytest.mark.parametrize("m1", [0.7, 1e-12, 1e-150])
def test_jacobi_next_to_zero_is_the_identity_not_nan(m1):
    # sn u ≈ u with u = 5e-167 made the ratio cn/sn of the Gauss transformation overflow
    # when squared: NaN, found by drawing ω = (1, 5e-167, 1) for the asymmetric top.
    u = np.array([5e-167, -1e-120, 2e-101, 0.0])
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        sn, cn, dn = elliptic.jacobi(u, 1.0 - m1, m1)
    assert np.array_equal(sn, u) and np.all(cn == 1.0) and np.all(dn == 1.0)
    # and continuous with the general path just above the switch (|u| = 1e-100)
    above = elliptic.jacobi(np.array([1e-99]), 1.0 - m1, m1)
    assert above[0][0] == pytest.approx(1e-99, rel=1e-15) and above[1][0] == 1.0


def _rj_ulps(got, x, y, z, p):
    want = mp.elliprj(x, y, z, p)
    return float(abs((mp.mpf(got) - want) / want)) / EPS


def _rj_arguments(rng, size):
    """R_J's arguments in Π(n; am u | m) = r + (n/3) s³ R_J(c², d², 1, p): m₁ from 1 to
    1e-15, n of either sign (p = 1 − n + n c² or 1 − n s²), n up to 1 − 1e-15."""
    for _ in range(size):
        c, m1 = rng.uniform(0.0, 1.0), 10.0 ** rng.uniform(-15.0, 0.0)
        n = rng.choice([1.0, -1.0]) * 10.0 ** rng.uniform(-6.0, 1.5)
        if n > 0.0:
            n = min(n, 1.0 - 10.0 ** rng.uniform(-15.0, -0.1))
        p = (1.0 - n) + n * c * c if n > 0.0 else 1.0 - n * (1.0 - c * c)
        yield c * c, m1 + (1.0 - m1) * c * c, 1.0, p


def test_carlson_rj_against_mpmath_where_the_references_call_it():
    # Measured on 3000 such draws: at most 3.1 ulps, 0.58 on average (scipy's elliprj: 4.2;
    # with the 5th-degree series and one more duplication step: 2.9 and 0.61); and on 1500
    # complete integrals R_J(0, m₁, 1, 1 − n), n < 0: 2.8 ulps (scipy's: 6.9; before: 3.1).
    rng = np.random.default_rng(13)
    worst = max(_rj_ulps(elliptic.carlson_rj(*a), *a) for a in _rj_arguments(rng, 300))
    assert worst <= 4.0
    for _ in range(100):
        a = (0.0, 10.0 ** rng.uniform(-15.0, 0.0), 1.0, 1.0 + 10.0 ** rng.uniform(-6.0, 2.0))
        assert _rj_ulps(elliptic.carlson_rj(*a), *a) <= 4.0, a


def test_carlson_rj_series_coefficients_from_the_integrand():
    # R_J(1 − X, 1 − Y, 1 − Z, 1 − P) = (3/2) ∫ (t+1−X)^(−½)(t+1−Y)^(−½)(t+1−Z)^(−½)(t+1−P)^(−1) dt:
    # each factor expanded in X/(t+1), … ((½)ₖ/k! for the roots, 1 for p), its degree-K
    # part integrates to (3/2)/(3/2 + K). With X + Y + Z + 2P = 0 (A the mean), it is a
    # polynomial in the elementary symmetric E₂ … E₅ of (X, Y, Z, P, P), whose coefficients
    # _rj_finish uses (degrees 2-5 are Carlson's published ones).
    import itertools

    import sympy as sp

    x, y, p = sp.symbols("x y p")
    z = -x - y - 2 * p
    five = [x, y, z, p, p]
    e = {
        k: sp.expand(sum(sp.prod(c) for c in itertools.combinations(five, k))) for k in (2, 3, 4, 5)
    }
    half = [sp.rf(sp.Rational(1, 2), k) / sp.factorial(k) for k in range(8)]
    expected = {
        (1, 0, 0, 0): elliptic._C2, (0, 1, 0, 0): elliptic._C3, (2, 0, 0, 0): elliptic._C22,
        (0, 0, 1, 0): elliptic._C4, (1, 1, 0, 0): elliptic._C23, (0, 0, 0, 1): elliptic._C5,
        (0, 2, 0, 0): elliptic._C33, (1, 0, 1, 0): elliptic._C24, (3, 0, 0, 0): elliptic._C222,
        (0, 1, 1, 0): elliptic._C34, (1, 0, 0, 1): elliptic._C25, (2, 1, 0, 0): elliptic._C223,
    }  # fmt: skip
    for degree in range(2, 8):
        part = sum(
            half[i] * half[j] * half[k] * x**i * y**j * z**k * p ** (degree - i - j - k)
            for i, j, k in itertools.product(range(degree + 1), repeat=3)
            if i + j + k <= degree
        )
        part = sp.expand(sp.Rational(3, 2) / (sp.Rational(3, 2) + degree) * part)
        powers = [m for m in expected if 2 * m[0] + 3 * m[1] + 4 * m[2] + 5 * m[3] == degree]
        c = sp.symbols(f"c:{len(powers)}")
        ansatz = sum(
            ci * sp.prod(e[k + 2] ** n for k, n in enumerate(m))
            for ci, m in zip(c, powers, strict=True)
        )
        [solved] = sp.solve(sp.Poly(sp.expand(part - ansatz), x, y, p).coeffs(), c, dict=True)
        for ci, m in zip(c, powers, strict=True):
            assert float(solved[ci]) == expected[m], (m, solved[ci])


@pytest.mark.parametrize("m1", [0.9, 1e-3, 1e-9, 1e-15, 1e-150])
def test_sncndn_many_is_each_sncndn_reduced_bit_for_bit(m1):
    # many arguments in lockstep (blocks of 64, a short last one), each as alone: next to
    # 0 (below 1e-100, where sn = r), at 0 and ±0, at ±K
    g = elliptic.GaussTransform(1.0 - m1, m1)
    r = np.random.default_rng(3).uniform(-g.k, g.k, 200)
    r[:8] = [0.0, -0.0, 1e-101, -1e-120, 1e-99, g.k, -g.k, 5e-167]
    sn, cn, dn = np.empty(r.size), np.empty(r.size), np.empty(r.size)
    elliptic.sncndn_many(r, *g.args, sn, cn, dn)
    for i, x in enumerate(r):
        assert (sn[i], cn[i], dn[i]) == elliptic.sncndn_reduced(x, *g.args), i


@pytest.mark.parametrize("rows", [0, 1, 63, 64, 65, 200])
def test_carlson_rj_pairs_are_each_single_bit_for_bit(rows):
    # in lockstep blocks of 64 rows (a short last one): each row's two R_J as alone
    rng = np.random.default_rng(rows)
    x, y, z, p = np.array(list(_rj_arguments(rng, rows))).reshape(rows, 4).T.copy()
    other = p[::-1].copy()
    out1, out2 = np.full(rows, np.nan), np.full(rows, np.nan)
    elliptic.carlson_rj_pairs(x, y, z, p, other, out1, out2)
    for i in range(rows):
        assert out1[i] == elliptic.carlson_rj(x[i], y[i], z[i], p[i]), i
        assert out2[i] == elliptic.carlson_rj(x[i], y[i], z[i], other[i]), i


def test_pi_pairs_are_each_pi_reduced_bit_for_bit():
    rng = np.random.default_rng(8)
    m1 = 10.0 ** rng.uniform(-15.0, 0.0)
    g = elliptic.GaussTransform(1.0 - m1, m1)
    u = rng.uniform(-30.0, 30.0, 300)
    u[:3] = [0.0, g.k, -2.0 * g.k]  # sn = 0, cn = 0, a whole period
    j, r = (np.array(v) for v in zip(*(elliptic.reduce_argument(x, g.k) for x in u), strict=True))
    s, c, d = (np.array(v) for v in zip(
        *(elliptic.sncndn_reduced(x, *g.args) for x in r), strict=True))  # fmt: skip
    n_a, n_b = 1.0 - 1e-9, -30.0  # one of each sign
    pi_a, pi_b = np.empty(u.size), np.empty(u.size)
    args_a = (n_a, 1e-9, g.complete_pi(n_a, 1e-9))
    args_b = (n_b, 1.0 - n_b, g.complete_pi(n_b, 1.0 - n_b))
    elliptic.pi_pairs(r, j, s, c, d, *args_a, *args_b, pi_a, pi_b)
    for i in range(u.size):
        assert pi_a[i] == elliptic.pi_reduced(r[i], j[i], s[i], c[i], d[i], *args_a), i
        assert pi_b[i] == elliptic.pi_reduced(r[i], j[i], s[i], c[i], d[i], *args_b), i
