"""Jacobi elliptic functions and the integrals the exact references need, parameter and
complementary parameter given separately.

Near a separatrix the parameter m is within a few ulps of 1, and m₁ = 1 − m carries all the
information: scipy's ``ellipj(u, m)`` receives m rounded to float, so 1 − m has lost most of
its digits before the function starts (m₁ = 1e-12 is known to about 1e-4 relative). Every
function here takes both m and m₁, each computed by the caller without cancellation, and
uses m₁ wherever 1 − m would appear.

* :func:`jacobi` — sn, cn, dn by the descending Gauss transformation on m₁, argument
  reduced modulo 2K.
* :func:`incomplete_first` — F(φ | m) via Carlson's R_F, for any real φ.
* :func:`jacobi_argument` — the inverse of :func:`jacobi`: u ∈ [−2K, 2K] from (sn u, cn u),
  without passing through the amplitude φ (well conditioned next to u = ±K, where
  F(φ | m) amplifies the rounding of φ by 1/dn ~ 1/√m₁).
* :func:`pi_integral` — ∫₀ᵘ dτ / (1 − n sn²τ), the elliptic integral of the third kind in
  Jacobi's argument, via Carlson's R_J (DLMF 19.25.14), quasi-periodic continuation with
  the complete integral.
* :class:`JacobiArgument` — arguments u reduced once, for :func:`jacobi` and any number of
  :func:`pi_integral` characteristics at the same u and m (an exact reference evaluates
  all three at every sample: the reduction and the Gauss transformation are done once).
"""

from __future__ import annotations

import math
import sys

import numpy as np
from scipy.special import ellipkm1, elliprf, elliprj

__all__ = [
    "MIN_M1",
    "JacobiArgument",
    "complete_first",
    "incomplete_first",
    "jacobi",
    "jacobi_argument",
    "pi_integral",
]

#: Smallest 1 − m at which :func:`jacobi` (and what is built on it) keeps its accuracy:
#: the descending Gauss transformation squares a ratio of size ~1/m₁, which overflows
#: below √(smallest normal float) ≈ 1.5e-154. Measured on the asymmetric top next to its
#: middle axis: orientations 1.4e-8 rad wrong at 1 − m = 2.9e-156 and 0.6 rad at 2.9e-246
#: under a stated bound of 1e-11; right to 1e-13 at 2.9e-150. K(m) itself
#: (:func:`complete_first`) stays right down to the smallest normal float.
MIN_M1 = math.sqrt(sys.float_info.min)

#: Below this |u|, sn u = u and cn u = dn u = 1 to rounding (the next term is ~u³).
_SMALL_ARGUMENT = 1e-100

_EPS = np.finfo(float).eps


def complete_first(m: float, m1: float) -> float:
    """K(m) from the complementary parameter m₁ = 1 − m (exact as m₁ → 0).

    Examples
    --------
    >>> round(complete_first(0.0, 1.0), 15) == round(np.pi / 2, 15)
    True
    """
    return float(ellipkm1(m1))


def _reduce(u, m, m1):
    """u = 2jK + r with r ∈ [−K, K]: returns (j, r, K)."""
    k = complete_first(m, m1)
    u = np.asarray(u, dtype=float)
    j = np.rint(u / (2.0 * k))
    return j, u - 2.0 * k * j, k


def _jacobi_reduced(r, m, m1):
    """sn, cn, dn for r ∈ [−K, K] by the descending Gauss transformation on m₁.

    The recurrence runs on the complementary parameter and on the ratio cn/sn
    (Numerical Recipes' ``sncndn``), never through arcsin: the textbook AGM form
    φ_{n−1} = ½(φ_n + asin((c_n/a_n) sin φ_n)) evaluates arcsin next to 1 when m ≈ 1 and
    loses digits in proportion to 1/cn (1e-13 absolute at m₁ = 1e-14, measured).
    dn is taken as √(m₁ + m cn²), a sum of non-negative terms (dn ≥ √m₁ > 0), so its
    absolute error stays at the ulp level.
    """
    # Next to 0 the ratio cn/sn ~ 1/r below would overflow when squared (r = 5e-167 gave
    # NaN); there sn = r (1 − (1 + m) r²/6 + …) = r and cn = dn = 1 to rounding.
    given = np.asarray(r, dtype=float)
    small = np.abs(given) < _SMALL_ARGUMENT
    r = np.where(small, 0.0, given)
    a, emc = 1.0, m1
    ems, ens = [], []
    while True:
        ems.append(a)
        emc = np.sqrt(emc)
        ens.append(emc)
        c = 0.5 * (a + emc)
        if abs(a - emc) <= 1e-9 * a:  # quadratic convergence: the next mean is exact
            break
        emc *= a
        a = c
    x = np.asarray(r, dtype=float) * c
    sn, cn = np.sin(x), np.cos(x)
    zero = sn == 0.0
    ratio = np.where(zero, 1.0, cn) / np.where(zero, 1.0, sn)
    cc = c * ratio
    d = np.ones_like(x)
    for b, en in zip(reversed(ems), reversed(ens), strict=True):
        ratio = ratio * cc
        cc = cc * d
        d = (en + ratio) / (b + ratio)
        ratio = cc / b
    s_abs = 1.0 / np.sqrt(cc * cc + 1.0)
    sn_new = np.where(sn >= 0.0, s_abs, -s_abs)
    cn_new = cc * sn_new
    sn = np.where(zero, sn, sn_new)
    cn = np.where(zero, cn, cn_new)
    if small.any():
        sn = np.where(small, given, sn)
        cn = np.where(small, 1.0, cn)
    dn = np.sqrt(m1 + m * cn * cn)
    return sn, cn, dn


def jacobi(u, m: float, m1: float):
    """Jacobi elliptic functions sn(u|m), cn(u|m), dn(u|m) with m₁ = 1 − m given exactly.

    Parameters
    ----------
    u : array_like
        Argument(s).
    m, m1 : float
        Parameter and complementary parameter, 0 ≤ m ≤ 1, m + m₁ = 1 up to rounding of
        each (the caller computes both without cancellation). m₁ = 0 gives the
        separatrix limit sn = tanh, cn = dn = sech.

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
    """Jacobi arguments u reduced once: u = 2jK + r, r ∈ [−K, K], with sn, cn, dn of r.

    :func:`jacobi` and :func:`pi_integral` both start from this reduction and from the
    descending Gauss transformation of r; a caller that needs sn, cn, dn and Π for one or
    more characteristics at the same arguments (the heavy top's state: Π for n₊ and n₋)
    builds one and asks it for each, with the same results as the separate functions.

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
        self.j, self.r, self.k = _reduce(self.u, m, m1)
        self.reduced = _jacobi_reduced(self.r, m, m1)

    def jacobi(self):
        """sn(u|m), cn(u|m), dn(u|m) (:func:`jacobi`)."""
        if self.reduced is None:
            sech = 1.0 / np.cosh(self.u)
            return np.tanh(self.u), sech, sech.copy()
        sn, cn, dn = self.reduced
        sign = 1.0 - 2.0 * np.mod(self.j, 2.0)  # sn(u + 2K) = −sn u, cn(u + 2K) = −cn u
        return sign * sn, sign * cn, dn

    def pi_integral(self, n: float, n1: float | None = None):
        """Π(n; am u | m) (:func:`pi_integral`, which see for ``n`` and ``n1``)."""
        if not n < 1.0:
            raise ValueError(f"n: expected n < 1, got {n!r}")
        if n1 is None:
            n1 = 1.0 - n
        if self.reduced is None:
            if n > 0.0:
                raise ValueError("pi_integral: m = 1 is implemented for n ≤ 0 only")
            u, nu = self.u, -n  # ∫ dτ/(1 + ν tanh²τ) = (τ + √ν atan(√ν tanh τ)) / (1 + ν)
            return (u + np.sqrt(nu) * np.arctan(np.sqrt(nu) * np.tanh(u))) / (1.0 + nu)
        s, c, d = self.reduced
        p = n1 + n * c * c if n > 0.0 else 1.0 - n * s * s
        part = self.r + (n / 3.0) * s**3 * elliprj(c * c, d * d, 1.0, p)
        if not np.any(self.j):
            return part
        complete = self.k + (n / 3.0) * elliprj(0.0, self.m1, 1.0, n1)
        return 2.0 * self.j * complete + part


def incomplete_first(phi, m: float, m1: float):
    """F(φ | m) = ∫₀^φ dθ / √(1 − m sin²θ) for any real φ, via Carlson's R_F.

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
    """The Jacobi argument u ∈ [−2K, 2K] with sn(u|m) ∝ ``sn`` and cn(u|m) ∝ ``cn``.

    Parameters
    ----------
    sn, cn : float
        The two values, each with a small *relative* error (normalised here to
        sn² + cn² = 1), not both zero.
    m, m1 : float
        Parameter and complementary parameter, as in :func:`jacobi`.

    Notes
    -----
    With s, c the normalised values and d² = m₁ + m c² (a sum without cancellation),
    u = s R_F(c², d², 1) when c ≥ 0 and u = ±2K − s R_F(c², d², 1) otherwise (the sign
    of s), the Carlson form of F(φ | m) read at sin φ = s, cos φ = c. R_F is homogeneous
    of degree −½ with negative partial derivatives, so |x ∂R_F/∂x| ≤ R_F/2 for each
    argument: relative errors δ in c² and d² change R_F by at most δ R_F relatively, and
    u carries a few ulps of |u| + 2K however close to ±K. Going through φ = atan2(s, c)
    instead rounds φ to an absolute ulp of π/2, which F(φ | m) multiplies by
    1/dn(u) ≈ 1/√m₁ next to u = ±K (measured: an
    error of 6e-10 in u at m₁ = 1e-14).

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
    """Π(n; am u | m) = ∫₀ᵘ dτ / (1 − n sn²(τ|m)), for n < 1.

    Parameters
    ----------
    u : array_like
        Jacobi argument(s).
    n : float
        Characteristic, n < 1 (the integrand has no pole).
    m, m1 : float
        Parameter and complementary parameter.
    n1 : float, optional
        1 − n computed by the caller without cancellation (matters when n → 1).

    Notes
    -----
    With r = u − 2jK ∈ [−K, K], s = sn r, c = cn r, d = dn r (DLMF 19.25.14, F(am r) = r)::

        Π = 2j Π(n|m) + r + (n/3) s³ R_J(c², d², 1, 1 − n s²),
        Π(n|m) = K + (n/3) R_J(0, m₁, 1, 1 − n).

    1 − n s² is formed as n₁ + n c², a sum without cancellation when 0 < n < 1.

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
