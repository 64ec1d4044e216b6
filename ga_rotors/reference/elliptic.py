r"""Jacobi elliptic functions and the integrals the exact references need, parameter and
complementary parameter given separately.

Near a separatrix the parameter :math:`m` is within a few ulps of 1, and
:math:`m_1 = 1 - m` carries all the information: scipy's ``ellipj(u, m)`` receives
:math:`m` rounded to float, so :math:`1 - m` has lost most of its digits before the
function starts (:math:`m_1 = 10^{-12}` is known to about :math:`10^{-4}` relative). Every
function here takes both :math:`m` and :math:`m_1`, each computed by the caller without
cancellation, and uses :math:`m_1` wherever :math:`1 - m` would appear.

* :func:`jacobi` — :math:`\operatorname{sn}, \operatorname{cn}, \operatorname{dn}` by the
  descending Gauss transformation on :math:`m_1`, argument reduced modulo :math:`2K`
  (:func:`sncndn_many`: many arguments in lockstep).
* :func:`incomplete_first` — :math:`F(\phi \mid m)` via Carlson's :math:`R_F`, for any
  real :math:`\phi`.
* :func:`jacobi_argument` — the inverse of :func:`jacobi`: :math:`u \in [-2K, 2K]` from
  :math:`(\operatorname{sn} u, \operatorname{cn} u)`, without passing through the
  amplitude :math:`\phi` (well conditioned next to :math:`u = \pm K`, where
  :math:`F(\phi \mid m)` amplifies the rounding of :math:`\phi` by
  :math:`1/\operatorname{dn} \sim 1/\sqrt{m_1}`).
* :func:`pi_integral` — :math:`\int_0^u \mathrm{d}\tau / (1 - n \operatorname{sn}^2\tau)`,
  the elliptic integral of the third kind in Jacobi's argument, via Carlson's :math:`R_J`
  (DLMF 19.25.14), quasi-periodic continuation with the complete integral.
* :class:`JacobiArgument` — arguments :math:`u` reduced once, for :func:`jacobi` and any
  number of :func:`pi_integral` characteristics at the same :math:`u` and :math:`m` (an
  exact reference evaluates all three at every sample: the reduction and the Gauss
  transformation are done once).

The per-argument formulas are compiled scalar functions (:func:`reduce_argument`,
:func:`sncndn_reduced`, :func:`pi_reduced`, :func:`carlson_rj`), which the functions above
loop over and which a reference's own compiled pass calls directly
(:mod:`ga_rotors.reference.heavy_top` evaluates its whole state per sample that way): one
implementation of each. :math:`R_J` is Carlson's duplication algorithm, compiled here rather than
scipy's ``elliprj`` (a ufunc, called per array), its series taken to the 7th degree so
that it stops a duplication step earlier: at most 3.1 ulps against mpmath where the
references call it, scipy's 4.2, and :func:`carlson_rj_pairs` serves the heavy top's two
characteristics at the same :math:`(x, y, z)` with one duplication, many arguments in
lockstep.
"""

from __future__ import annotations

import math
import sys

import numpy as np
from scipy.special import ellipkm1, elliprf

from .._jit import jit

__all__ = [
    "MIN_M1",
    "JacobiArgument",
    "complete_first",
    "incomplete_first",
    "jacobi",
    "jacobi_argument",
    "pi_integral",
]

#: Smallest :math:`1 - m` at which :func:`jacobi` (and what is built on it) keeps its
#: accuracy: the descending Gauss transformation squares a ratio of size
#: :math:`\sim 1/m_1`, which overflows below :math:`\sqrt{\text{smallest normal float}}
#: \approx 1.5 \cdot 10^{-154}`. Measured on the asymmetric top next to its middle axis:
#: orientations 1.4e-8 rad wrong at :math:`1 - m = 2.9 \cdot 10^{-156}` and 0.6 rad at
#: :math:`2.9 \cdot 10^{-246}` under a stated bound of 1e-11; right to 1e-13 at
#: :math:`2.9 \cdot 10^{-150}`. :math:`K(m)` itself (:func:`complete_first`) stays right
#: down to the smallest normal float.
MIN_M1 = math.sqrt(sys.float_info.min)

#: Below this |u|, sn u = u and cn u = dn u = 1 to rounding (the next term is ~u³).
_SMALL_ARGUMENT = 1e-100

_EPS = np.finfo(float).eps


def complete_first(m: float, m1: float) -> float:
    r""":math:`K(m)` from the complementary parameter :math:`m_1 = 1 - m` (exact as
    :math:`m_1 \to 0`).

    Examples
    --------
    >>> round(complete_first(0.0, 1.0), 15) == round(np.pi / 2, 15)
    True
    """
    return float(ellipkm1(m1))


def _gauss_coefficients(m1: float):
    """The descending Gauss transformation's means for m₁ (they depend on m₁ alone).

    Returns (a, e, c): the arithmetic means aₙ and the square roots eₙ of the
    complementary parameters, in the order produced, and the last mean c.
    """
    a, emc = 1.0, m1
    ems, ens = [], []
    while True:
        ems.append(a)
        emc = math.sqrt(emc)
        ens.append(emc)
        c = 0.5 * (a + emc)
        if abs(a - emc) <= 1e-9 * a:  # quadratic convergence: the next mean is exact
            break
        emc *= a
        a = c
    return np.array(ems), np.array(ens), c


@jit
def sncndn_reduced(r, m, m1, means, roots, c):
    r""":math:`\operatorname{sn}, \operatorname{cn}, \operatorname{dn}` for one
    :math:`r \in [-K, K]` by the descending Gauss transformation on :math:`m_1` (``means``,
    ``roots``, ``c`` from the transformation's setup for :math:`m_1`).

    The recurrence runs on the complementary parameter and on the ratio
    :math:`\operatorname{cn}/\operatorname{sn}` (Numerical Recipes' ``sncndn``), never
    through arcsin: the textbook AGM form
    :math:`\phi_{n-1} = \tfrac12\bigl(\phi_n + \arcsin((c_n/a_n) \sin\phi_n)\bigr)`
    evaluates arcsin next to 1 when :math:`m \approx 1` and loses digits in proportion to
    :math:`1/\operatorname{cn}` (1e-13 absolute at :math:`m_1 = 10^{-14}`, measured).
    :math:`\operatorname{dn}` is taken as :math:`\sqrt{m_1 + m \operatorname{cn}^2}`, a sum
    of non-negative terms (:math:`\operatorname{dn} \ge \sqrt{m_1} > 0`), so its absolute
    error stays at the ulp level.
    """
    # Next to 0 the ratio cn/sn ~ 1/r below would overflow when squared (r = 5e-167 gave
    # NaN); there sn = r (1 − (1 + m) r²/6 + …) = r and cn = dn = 1 to rounding.
    if abs(r) < _SMALL_ARGUMENT:
        return r, 1.0, math.sqrt(m1 + m * 1.0 * 1.0)
    x = r * c
    sn, cn = math.sin(x), math.cos(x)
    if sn != 0.0:
        ratio = cn / sn
        cc = c * ratio
        d = 1.0
        for i in range(means.shape[0] - 1, -1, -1):
            b = means[i]
            ratio = ratio * cc
            cc = cc * d
            d = (roots[i] + ratio) / (b + ratio)
            ratio = cc / b
        s_abs = 1.0 / math.sqrt(cc * cc + 1.0)
        sn = s_abs if sn >= 0.0 else -s_abs
        cn = cc * sn
    return sn, cn, math.sqrt(m1 + m * cn * cn)


#: Arguments taken in lockstep by :func:`sncndn_many` and :func:`carlson_rj_pairs`: their
#: loops over a block's arguments run at fixed offsets of one scratch array, so that no
#: runtime check of overlapping arrays keeps the compiler from vector instructions; the
#: R_J duplication of a block runs as many steps as its slowest argument (the others'
#: states held).
_LANES = 64


@jit
def sncndn_many(r, m, m1, means, roots, c, sn_out, cn_out, dn_out):
    r""":func:`sncndn_reduced` of every :math:`r` (a 1-d array) into the three arrays, bit
    for bit, :data:`_LANES` at a time: the sine and cosine one by one, the Gauss
    transformation's recurrence a level at a time for all of them (loops that vectorise),
    the choice among its cases (:math:`r` next to 0, :math:`\sin(rc) = 0`) last."""
    w = np.zeros(5 * _LANES)  # rows: cn/sn ratio, cc, d, sin(rc), cos(rc)
    n = r.shape[0]
    for start in range(0, n, _LANES):
        rows = min(_LANES, n - start)
        for i in range(_LANES):  # a short last block repeats its first row
            x = r[start + i if i < rows else start] * c
            w[3 * _LANES + i], w[4 * _LANES + i] = math.sin(x), math.cos(x)
        for i in range(_LANES):
            ratio = w[4 * _LANES + i] / w[3 * _LANES + i]
            w[i], w[_LANES + i], w[2 * _LANES + i] = ratio, c * ratio, 1.0
        for level in range(means.shape[0] - 1, -1, -1):
            b, e = means[level], roots[level]
            for i in range(_LANES):
                ratio = w[i] * w[_LANES + i]
                cc = w[_LANES + i] * w[2 * _LANES + i]
                w[2 * _LANES + i] = (e + ratio) / (b + ratio)
                w[_LANES + i] = cc
                w[i] = cc / b
        for i in range(rows):
            sn, cn = w[3 * _LANES + i], w[4 * _LANES + i]
            if abs(r[start + i]) < _SMALL_ARGUMENT:
                sn, cn = r[start + i], 1.0
            elif sn != 0.0:
                cc = w[_LANES + i]
                s_abs = 1.0 / math.sqrt(cc * cc + 1.0)
                sn = s_abs if sn >= 0.0 else -s_abs
                cn = cc * sn
            sn_out[start + i], cn_out[start + i] = sn, cn
            dn_out[start + i] = math.sqrt(m1 + m * cn * cn)


@jit
def reduce_argument(u, k):
    r""":math:`u = 2jK + r` with :math:`r \in [-K, K]`: :math:`(j, r)` for one argument
    (:math:`j` a whole float)."""
    j = np.rint(u / (2.0 * k))
    return j, u - 2.0 * k * j


@jit
def half_period_sign(j):
    r""":math:`(-1)^j` for a whole float :math:`j`:
    :math:`\operatorname{sn}(u + 2K) = -\operatorname{sn} u`,
    :math:`\operatorname{cn}(u + 2K) = -\operatorname{cn} u`."""
    return 1.0 - 2.0 * (j - 2.0 * math.floor(0.5 * j))


#: Carlson's stopping constant for a relative truncation error ε/4: the duplication stops
#: once the arguments' relative spread |X| is below 1/_RJ_STOP, and the series of
#: :func:`_rj_finish` runs to the 7th degree, so its first omitted terms are of the 8th:
#: (ε/4)^(1/8). Carlson's series to the 5th degree needs (ε/4)^(1/6), a spread 4.8 times
#: smaller: one more duplication step (square roots and a division) for every argument.
#: The largest 8th- and 9th-degree terms over |X|, |Y|, |Z|, |P| ≤ 1 (sampled) are
#: 0.155 |X|⁸ and 0.061 |X|⁹, so the truncation stays near ε/25, as the 5th-degree
#: series' did near ε/20 (its 6th-degree terms: 0.197 |X|⁶).
_RJ_STOP = (_EPS / 4.0) ** (-1.0 / 8.0)


# The series' rational coefficients as products (a division costs several; each product
# rounds once more, on terms below 1e-3 next to the series' leading 1).
_11 = 1.0 / 11.0
_C2, _C3, _C22, _C4 = -3.0 / 14.0, 1.0 / 6.0, 9.0 / 88.0, -3.0 / 22.0
_C23, _C5, _C33, _C24, _C222 = -9.0 / 52.0, 3.0 / 26.0, 3.0 / 40.0, 3.0 / 20.0, -1.0 / 16.0
_C34, _C25, _C223 = -9.0 / 68.0, -9.0 / 68.0, 45.0 / 272.0


@jit
def _rc_series(e):
    """R_C(1, 1 + e) by its series, truncated after e⁵ (the next term is below ε for
    |e| < 1e-3)."""
    return 1.0 + e * (-1.0 / 3.0 + e * (0.2 + e * (-1.0 / 7.0 + e * (1.0 / 9.0 - e * _11))))


@jit
def _rc_one(e):
    """R_C(1, 1 + e) for e > −1: atan(√e)/√e, atanh(√−e)/√−e, or their series near 0."""
    if abs(e) < 1e-3:
        return _rc_series(e)
    if e > 0.0:
        root = math.sqrt(e)
        return math.atan(root) / root
    root = math.sqrt(-e)
    return math.atanh(root) / root


@jit
def _rj_start(x, y, z, p):
    """Carlson's duplication for R_J(x, y, z, p), before its first step:
    (p, A, 4⁻ᵐ, 4⁻³ᵐ, Σ, going on, A₀, δ, Q)."""
    a = (x + y + z + 2.0 * p) * 0.2
    q = _RJ_STOP * max(abs(a - x), abs(a - y), abs(a - z), abs(a - p))
    return (p, a, 1.0, 1.0, 0.0, q >= abs(a), a, (p - x) * (p - y) * (p - z), q)


@jit
def _rj_term(state, sx, sy, sz):
    """(1/d, e) of a duplication step of :func:`_rj_start`'s state: its R_C term is
    R_C(1, 1 + e)/d, given √x, √y, √z of this step."""
    p, _, _, g, _, _, _, delta, _ = state
    sp = math.sqrt(p)
    inverse = 1.0 / ((sp + sx) * (sp + sy) * (sp + sz))  # 1/d: one division, not two
    return inverse, g * delta * inverse * inverse


@jit
def _rj_advance(state, rc, inverse, lam):
    """The state after a duplication step whose R_C(1, 1 + e) is ``rc`` (:func:`_rj_term`)
    and whose λ is ``lam``."""
    p, a, f, g, total, _, a0, delta, q = state
    total += f * rc * inverse
    a, f = 0.25 * (a + lam), 0.25 * f
    return (0.25 * (p + lam), a, f, g / 64.0, total, f * q >= abs(a), a0, delta, q)


@jit
def _rj_step(state, sx, sy, sz, lam):
    """One duplication step of :func:`_rj_start`'s state, given √x, √y, √z and λ of this
    step; a finished state is returned as it is."""
    if not state[5]:
        return state
    inverse, e = _rj_term(state, sx, sy, sz)
    return _rj_advance(state, _rc_one(e), inverse, lam)


@jit
def _rj_finish(state, x, y, z):
    """R_J from a finished duplication of the arguments x, y, z (their initial values):
    the series to the 7th degree at the last step (Carlson 1995, DLMF 19.36.ii; the 6th
    and 7th degrees' terms −E₂³/16 + 3E₃²/40 + 3E₂E₄/20 + 45E₂²E₃/272 − 9(E₃E₄ + E₂E₅)/68
    from the integrand's expansion, ``tests/test_elliptic.py``), plus the R_C sum."""
    _, a, f, _, total, _, a0, _, _ = state
    root = math.sqrt(a)
    inverse = 1.0 / (a * root)  # A^(−3/2); 1/A = √A · A^(−3/2)
    scale = f * (root * inverse)
    xx, yy, zz = (a0 - x) * scale, (a0 - y) * scale, (a0 - z) * scale
    pp = -0.5 * (xx + yy + zz)
    xyz, p2 = xx * yy * zz, pp * pp
    e2 = xx * yy + xx * zz + yy * zz - 3.0 * p2
    e3 = xyz + 2.0 * e2 * pp + 4.0 * p2 * pp
    e4 = (2.0 * xyz + e2 * pp + 3.0 * p2 * pp) * pp
    e5 = xyz * p2
    series = 1.0 + (
        e2 * (_C2 + e2 * (_C22 + e2 * _C222) + e4 * _C24)
        + e3 * (_C3 + e2 * (_C23 + e2 * _C223) + e3 * _C33 + e4 * _C34)
        + e4 * _C4
        + e5 * (_C5 + e2 * _C25)
    )
    return f * series * inverse + 6.0 * total


# the scratch array's rows: the arguments, the shared duplication's, then for each p its
# state (:func:`_rj_start`'s nine values, ``going`` as 1.0 or 0.0) and its result
_X, _Y, _Z, _U, _V, _W, _SU, _SV, _SW, _LAM, _E, _INV, _RC = range(13)
_STATE = (13, 23)
_ROWS = 33


@jit
def _lane_state(w, o, i):
    """Lane i's state (:func:`_rj_start`'s tuple) from the rows at ``o``."""
    return (w[o * _LANES + i], w[(o + 1) * _LANES + i], w[(o + 2) * _LANES + i],
            w[(o + 3) * _LANES + i], w[(o + 4) * _LANES + i], w[(o + 5) * _LANES + i] != 0.0,
            w[(o + 6) * _LANES + i], w[(o + 7) * _LANES + i], w[(o + 8) * _LANES + i])  # fmt: skip


@jit
def _put_lane_state(w, o, i, state):
    p, a, f, g, total, going, a0, delta, q = state
    w[o * _LANES + i], w[(o + 1) * _LANES + i], w[(o + 2) * _LANES + i] = p, a, f
    w[(o + 3) * _LANES + i], w[(o + 4) * _LANES + i] = g, total
    w[(o + 5) * _LANES + i] = 1.0 if going else 0.0
    w[(o + 6) * _LANES + i], w[(o + 7) * _LANES + i], w[(o + 8) * _LANES + i] = a0, delta, q


@jit
def _lanes_start(w, k):
    """:func:`_rj_start` of every lane, for p number ``k`` (its state's rows hold p)."""
    o = _STATE[k]
    for i in range(_LANES):
        state = _rj_start(w[_X * _LANES + i], w[_Y * _LANES + i], w[_Z * _LANES + i],
                          w[o * _LANES + i])  # fmt: skip
        _put_lane_state(w, o, i, state)


@jit
def _lanes_roots(w):
    """√x, √y, √z and λ of this step, every lane."""
    for i in range(_LANES):
        su = math.sqrt(w[_U * _LANES + i])
        sv = math.sqrt(w[_V * _LANES + i])
        sw = math.sqrt(w[_W * _LANES + i])
        w[_SU * _LANES + i], w[_SV * _LANES + i], w[_SW * _LANES + i] = su, sv, sw
        w[_LAM * _LANES + i] = su * sv + su * sw + sv * sw


@jit
def _lanes_step(w, k):
    """:func:`_rj_step` of every lane for p number ``k`` (a finished lane's state kept):
    the R_C series for every lane, the few beyond it one by one; returns how many lanes
    go on."""
    o = _STATE[k]
    for i in range(_LANES):
        inverse, e = _rj_term(_lane_state(w, o, i), w[_SU * _LANES + i], w[_SV * _LANES + i],
                              w[_SW * _LANES + i])  # fmt: skip
        w[_INV * _LANES + i], w[_E * _LANES + i] = inverse, e
        w[_RC * _LANES + i] = _rc_series(e)
    for i in range(_LANES):
        if w[(o + 5) * _LANES + i] != 0.0 and not abs(w[_E * _LANES + i]) < 1e-3:
            w[_RC * _LANES + i] = _rc_one(w[_E * _LANES + i])
    going = 0.0
    for i in range(_LANES):
        state = _lane_state(w, o, i)
        after = _rj_advance(state, w[_RC * _LANES + i], w[_INV * _LANES + i],
                            w[_LAM * _LANES + i])  # fmt: skip
        _put_lane_state(w, o, i, after if state[5] else state)
        going += 1.0 if state[5] and after[5] else 0.0
    return going


@jit
def _lanes_advance(w):
    for i in range(_LANES):
        lam = w[_LAM * _LANES + i]
        w[_U * _LANES + i] = 0.25 * (w[_U * _LANES + i] + lam)
        w[_V * _LANES + i] = 0.25 * (w[_V * _LANES + i] + lam)
        w[_W * _LANES + i] = 0.25 * (w[_W * _LANES + i] + lam)


@jit
def carlson_rj_pairs(x, y, z, p1, p2, out1, out2):
    r"""Carlson's :math:`R_J(x, y, z, p_1)` and :math:`R_J(x, y, z, p_2)` of every row of
    the 1-d arrays (:math:`x, y, z \ge 0`, at most one zero; :math:`p_1, p_2 > 0`) into
    ``out1``, ``out2``: each what :func:`carlson_rj` gives for its arguments alone, bit for
    bit, with one duplication of :math:`x, y, z` for both :math:`p`. :data:`_LANES` rows go
    in lockstep: each :math:`p` of each row stops at its own step, but a block runs the
    steps of its slowest, so that its loops over the rows vectorise."""
    w = np.zeros(_ROWS * _LANES)
    n = x.shape[0]
    for start in range(0, n, _LANES):
        rows = min(_LANES, n - start)
        for i in range(_LANES):  # a short last block repeats its first row
            r = start + i if i < rows else start
            w[_X * _LANES + i], w[_U * _LANES + i] = x[r], x[r]
            w[_Y * _LANES + i], w[_V * _LANES + i] = y[r], y[r]
            w[_Z * _LANES + i], w[_W * _LANES + i] = z[r], z[r]
            w[_STATE[0] * _LANES + i], w[_STATE[1] * _LANES + i] = p1[r], p2[r]
        _lanes_start(w, 0)
        _lanes_start(w, 1)
        going = 1.0
        while going > 0.0:
            _lanes_roots(w)
            going = _lanes_step(w, 0) + _lanes_step(w, 1)
            _lanes_advance(w)
        for k, out in ((0, out1), (1, out2)):
            for i in range(rows):
                state = _lane_state(w, _STATE[k], i)
                out[start + i] = _rj_finish(state, x[start + i], y[start + i], z[start + i])


@jit
def carlson_rj(x, y, z, p):
    r"""Carlson's symmetric elliptic integral of the third kind :math:`R_J(x, y, z, p)`,
    :math:`x, y, z \ge 0` with at most one zero, :math:`p > 0`, by duplication (Carlson
    1995; DLMF 19.36.ii)."""
    state = _rj_start(x, y, z, p)
    u, v, w = x, y, z
    while state[5]:
        su, sv, sw = math.sqrt(u), math.sqrt(v), math.sqrt(w)
        lam = su * sv + su * sw + sv * sw
        state = _rj_step(state, su, sv, sw, lam)
        u, v, w = 0.25 * (u + lam), 0.25 * (v + lam), 0.25 * (w + lam)
    return _rj_finish(state, x, y, z)


@jit
def _pi_terms(r, j, s, c, n, n1):
    """(p, the factor of R_J) in Π = r + (n/3) s³ R_J(c², d², 1, p) (+ 2j Π(n|m))."""
    return (n1 + n * c * c if n > 0.0 else 1.0 - n * s * s), (n / 3.0) * s**3.0


@jit
def pi_reduced(r, j, s, c, d, n, n1, complete):
    r""":math:`\Pi(n; \operatorname{am} u \mid m)` for :math:`u = 2jK + r` from
    :math:`\operatorname{sn}, \operatorname{cn}, \operatorname{dn}` of :math:`r`
    (:func:`pi_integral`'s formula); ``complete`` is :math:`\Pi(n \mid m)`, used only when
    :math:`j \ne 0`."""
    p, factor = _pi_terms(r, j, s, c, n, n1)
    part = r + factor * carlson_rj(c * c, d * d, 1.0, p)
    return part if j == 0.0 else 2.0 * j * complete + part


@jit
def pi_pairs(r, j, s, c, d, n_a, n1_a, complete_a, n_b, n1_b, complete_b, out_a, out_b):
    r""":func:`pi_reduced` of every row (1-d arrays :math:`r`, :math:`j`, and
    :math:`\operatorname{sn}, \operatorname{cn}, \operatorname{dn}` of :math:`r`) for two
    characteristics at once, bit for bit, with one duplication of :math:`R_J`'s shared
    arguments (:func:`carlson_rj_pairs`)."""
    rows = r.shape[0]
    x, y, z, p_a, p_b = (
        np.empty(rows),
        np.empty(rows),
        np.ones(rows),
        np.empty(rows),
        np.empty(rows),
    )
    f_a, f_b, rj_a, rj_b = np.empty(rows), np.empty(rows), np.empty(rows), np.empty(rows)
    for i in range(rows):
        x[i], y[i] = c[i] * c[i], d[i] * d[i]
        p_a[i], f_a[i] = _pi_terms(r[i], j[i], s[i], c[i], n_a, n1_a)
        p_b[i], f_b[i] = _pi_terms(r[i], j[i], s[i], c[i], n_b, n1_b)
    carlson_rj_pairs(x, y, z, p_a, p_b, rj_a, rj_b)
    for i in range(rows):
        part_a, part_b = r[i] + f_a[i] * rj_a[i], r[i] + f_b[i] * rj_b[i]
        if j[i] == 0.0:
            out_a[i], out_b[i] = part_a, part_b
        else:
            out_a[i] = 2.0 * j[i] * complete_a + part_a
            out_b[i] = 2.0 * j[i] * complete_b + part_b


@jit
def _reduced_loop(u, k, m, m1, means, roots, c, j_out, r_out, sn_out, cn_out, dn_out):
    for i in range(u.shape[0]):
        j_out[i], r_out[i] = reduce_argument(u[i], k)
    sncndn_many(r_out, m, m1, means, roots, c, sn_out, cn_out, dn_out)


@jit
def _pi_loop(r, j, sn, cn, dn, n, n1, complete, out):
    for i in range(r.shape[0]):
        out[i] = pi_reduced(r[i], j[i], sn[i], cn[i], dn[i], n, n1, complete)


class GaussTransform:
    r"""What :math:`\operatorname{sn}, \operatorname{cn}, \operatorname{dn}` and :math:`\Pi`
    at any argument need for one parameter :math:`m` (with :math:`m_1 = 1 - m`):
    :math:`K(m)` and the descending Gauss transformation's means; ``args`` is the tuple
    compiled code takes after :math:`r` (:func:`sncndn_reduced`).

    Examples
    --------
    >>> g = GaussTransform(0.5, 0.5)
    >>> round(g.k, 12), len(g.args)
    (1.854074677301, 5)
    """

    def __init__(self, m: float, m1: float):
        self.m, self.m1 = m, m1
        self.k = complete_first(m, m1)
        means, roots, c = _gauss_coefficients(m1)
        self.args = (float(m), float(m1), means, roots, float(c))

    def complete_pi(self, n: float, n1: float) -> float:
        r""":math:`\Pi(n \mid m) = K + \tfrac{n}{3} R_J(0, m_1, 1, 1 - n)`."""
        return self.k + (n / 3.0) * carlson_rj(0.0, self.m1, 1.0, n1)


def jacobi(u, m: float, m1: float):
    r"""Jacobi elliptic functions :math:`\operatorname{sn}(u \mid m)`,
    :math:`\operatorname{cn}(u \mid m)`, :math:`\operatorname{dn}(u \mid m)` with
    :math:`m_1 = 1 - m` given exactly.

    Parameters
    ----------
    u : array_like
        Argument(s).
    m, m1 : float
        Parameter and complementary parameter, :math:`0 \le m \le 1`, :math:`m + m_1 = 1` up
        to rounding of each (the caller computes both without cancellation). :math:`m_1 = 0`
        gives the separatrix limit :math:`\operatorname{sn} = \tanh`,
        :math:`\operatorname{cn} = \operatorname{dn} = \operatorname{sech}`.

    Examples
    --------
    >>> sn, cn, dn = jacobi(0.3, 0.0, 1.0)
    >>> bool(np.isclose(sn, np.sin(0.3)) and np.isclose(dn, 1.0))
    True
    >>> sn, cn, dn = jacobi(0.7, 1.0, 0.0)
    >>> bool(np.isclose(sn, np.tanh(0.7)) and np.isclose(cn, 1 / np.cosh(0.7)))
    True
    """
    return JacobiArgument(u, m, m1).jacobi()


class JacobiArgument:
    r"""Jacobi arguments :math:`u` reduced once: :math:`u = 2jK + r`, :math:`r \in [-K, K]`,
    with :math:`\operatorname{sn}, \operatorname{cn}, \operatorname{dn}` of :math:`r`.

    :func:`jacobi` and :func:`pi_integral` both start from this reduction and from the
    descending Gauss transformation of :math:`r`; a caller that needs
    :math:`\operatorname{sn}, \operatorname{cn}, \operatorname{dn}` and :math:`\Pi` for one
    or more characteristics at the same arguments (the heavy top's state: :math:`\Pi` for
    :math:`n_+` and :math:`n_-`) builds one and asks it for each, with the same results as
    the separate functions.

    Parameters
    ----------
    u : array_like
        Argument(s).
    m, m1 : float
        Parameter and complementary parameter, as in :func:`jacobi`.

    Examples
    --------
    >>> arg = JacobiArgument([0.4, 5.0], 0.3, 0.7)
    >>> sn, cn, dn = arg.jacobi()
    >>> bool(np.array_equal(sn, jacobi([0.4, 5.0], 0.3, 0.7)[0]))
    True
    >>> bool(np.array_equal(arg.pi_integral(-0.5), pi_integral([0.4, 5.0], -0.5, 0.3, 0.7)))
    True
    """

    def __init__(self, u, m: float, m1: float):
        self.u = np.asarray(u, dtype=float)
        self.m, self.m1 = m, m1
        if m1 == 0.0:  # the separatrix limit: closed forms, nothing to reduce
            self.j = self.r = self.k = self.reduced = None
            return
        self.gauss = GaussTransform(m, m1)
        self.k = self.gauss.k
        flat = np.ascontiguousarray(self.u.reshape(-1))
        self.j, self.r, sn, cn, dn = (np.empty_like(flat) for _ in range(5))
        _reduced_loop(flat, self.k, *self.gauss.args, self.j, self.r, sn, cn, dn)
        self.reduced = sn, cn, dn

    def _shaped(self, a):
        return a.reshape(self.u.shape)

    def jacobi(self):
        r""":math:`\operatorname{sn}(u \mid m)`, :math:`\operatorname{cn}(u \mid m)`,
        :math:`\operatorname{dn}(u \mid m)` (:func:`jacobi`)."""
        if self.reduced is None:
            sech = 1.0 / np.cosh(self.u)
            return np.tanh(self.u), sech, sech.copy()
        sn, cn, dn = self.reduced
        sign = 1.0 - 2.0 * np.mod(self.j, 2.0)  # sn(u + 2K) = −sn u, cn(u + 2K) = −cn u
        return self._shaped(sign * sn), self._shaped(sign * cn), self._shaped(dn.copy())

    def pi_integral(self, n: float, n1: float | None = None):
        r""":math:`\Pi(n; \operatorname{am} u \mid m)` (:func:`pi_integral`, which see for
        ``n`` and ``n1``)."""
        if not n < 1.0:
            raise ValueError(f"n: expected n < 1, got {n!r}")
        if n1 is None:
            n1 = 1.0 - n
        if self.reduced is None:
            if n > 0.0:
                raise ValueError("pi_integral: m = 1 is implemented for n ≤ 0 only")
            u, nu = self.u, -n  # ∫ dτ/(1 + ν tanh²τ) = (τ + √ν atan(√ν tanh τ)) / (1 + ν)
            return (u + np.sqrt(nu) * np.arctan(np.sqrt(nu) * np.tanh(u))) / (1.0 + nu)
        complete = self.gauss.complete_pi(n, n1) if np.any(self.j) else 0.0
        out = np.empty_like(self.r)
        _pi_loop(self.r, self.j, *self.reduced, float(n), float(n1), complete, out)
        return self._shaped(out)


def incomplete_first(phi, m: float, m1: float):
    r""":math:`F(\phi \mid m) = \int_0^\phi \mathrm{d}\theta / \sqrt{1 - m \sin^2\theta}` for
    any real :math:`\phi`, via Carlson's :math:`R_F`.

    Examples
    --------
    >>> bool(np.isclose(incomplete_first(np.pi / 2, 0.5, 0.5), complete_first(0.5, 0.5)))
    True
    """
    phi = np.asarray(phi, dtype=float)
    j = np.rint(phi / np.pi)
    rem = phi - np.pi * j
    s, c = np.sin(rem), np.cos(rem)
    part = s * elliprf(c * c, m1 + m * c * c, 1.0)
    if m1 == 0.0:
        if np.any(j != 0):
            raise ValueError("F(φ | 1) diverges at |φ| ≥ π/2")
        return part
    return 2.0 * j * complete_first(m, m1) + part


def jacobi_argument(sn: float, cn: float, m: float, m1: float) -> float:
    r"""The Jacobi argument :math:`u \in [-2K, 2K]` with
    :math:`\operatorname{sn}(u \mid m) \propto` ``sn`` and
    :math:`\operatorname{cn}(u \mid m) \propto` ``cn``.

    Parameters
    ----------
    sn, cn : float
        The two values, each with a small *relative* error (normalised here to
        :math:`\operatorname{sn}^2 + \operatorname{cn}^2 = 1`), not both zero.
    m, m1 : float
        Parameter and complementary parameter, as in :func:`jacobi`.

    Notes
    -----
    With :math:`s, c` the normalised values and :math:`d^2 = m_1 + m c^2` (a sum without
    cancellation),

    .. math::

        u = \begin{cases}
        s\, R_F(c^2, d^2, 1), & c \ge 0, \\
        \pm 2K - s\, R_F(c^2, d^2, 1) \ (\text{the sign of } s), & c < 0,
        \end{cases}

    the Carlson form of :math:`F(\phi \mid m)` read at :math:`\sin\phi = s`,
    :math:`\cos\phi = c`. :math:`R_F` is homogeneous of degree :math:`-\tfrac12` with
    negative partial derivatives, so
    :math:`\lvert x\, \partial R_F / \partial x \rvert \le R_F / 2` for each argument:
    relative errors :math:`\delta` in :math:`c^2` and :math:`d^2` change :math:`R_F` by at
    most :math:`\delta R_F` relatively, and :math:`u` carries a few ulps of
    :math:`\lvert u \rvert + 2K` however close to :math:`\pm K`. Going through
    :math:`\phi = \operatorname{atan2}(s, c)` instead rounds :math:`\phi` to an absolute ulp
    of :math:`\pi/2`, which :math:`F(\phi \mid m)` multiplies by
    :math:`1/\operatorname{dn}(u) \approx 1/\sqrt{m_1}` next to :math:`u = \pm K`
    (measured: an error of 6e-10 in :math:`u` at :math:`m_1 = 10^{-14}`).

    Examples
    --------
    >>> sn, cn, dn = jacobi(0.8, 0.5, 0.5)
    >>> round(jacobi_argument(float(sn), float(cn), 0.5, 0.5), 12)
    0.8
    >>> sn, cn, dn = jacobi(-2.5, 0.5, 0.5)
    >>> round(jacobi_argument(float(sn), float(cn), 0.5, 0.5), 12)
    -2.5
    """
    r = float(np.hypot(sn, cn))
    if not r > 0.0:
        raise ValueError("jacobi_argument: sn and cn are both zero")
    s, c = sn / r, cn / r
    part = s * float(elliprf(c * c, m1 + m * c * c, 1.0))
    if c >= 0.0:
        return part
    if m1 == 0.0:
        raise ValueError("jacobi_argument: cn < 0 has no argument at m = 1 (cn = sech > 0)")
    return float(np.copysign(2.0 * complete_first(m, m1), s)) - part


def pi_integral(u, n: float, m: float, m1: float, n1: float | None = None):
    r""":math:`\Pi(n; \operatorname{am} u \mid m) = \int_0^u \mathrm{d}\tau /
    (1 - n \operatorname{sn}^2(\tau \mid m))`, for :math:`n < 1`.

    Parameters
    ----------
    u : array_like
        Jacobi argument(s).
    n : float
        Characteristic, :math:`n < 1` (the integrand has no pole).
    m, m1 : float
        Parameter and complementary parameter.
    n1 : float, optional
        :math:`1 - n` computed by the caller without cancellation (matters when
        :math:`n \to 1`).

    Notes
    -----
    With :math:`r = u - 2jK \in [-K, K]`, :math:`s = \operatorname{sn} r`,
    :math:`c = \operatorname{cn} r`, :math:`d = \operatorname{dn} r` (DLMF 19.25.14,
    :math:`F(\operatorname{am} r) = r`):

    .. math::

        \begin{aligned}
        \Pi &= 2j\, \Pi(n \mid m) + r + \tfrac{n}{3} s^3 R_J(c^2, d^2, 1, 1 - n s^2), \\
        \Pi(n \mid m) &= K + \tfrac{n}{3} R_J(0, m_1, 1, 1 - n).
        \end{aligned}

    :math:`1 - n s^2` is formed as :math:`n_1 + n c^2`, a sum without cancellation when
    :math:`0 < n < 1`.

    Examples
    --------
    >>> bool(np.isclose(pi_integral(0.4, 0.0, 0.3, 0.7), 0.4))
    True
    >>> bool(np.isclose(pi_integral(0.4, -0.5, 0.0, 1.0),
    ...      np.arctan(np.sqrt(1.5) * np.tan(0.4)) / np.sqrt(1.5)))
    True
    """
    if not n < 1.0:  # before any work
        raise ValueError(f"n: expected n < 1, got {n!r}")
    return JacobiArgument(u, m, m1).pi_integral(n, n1)
