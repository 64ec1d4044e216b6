"""Scalar motor kernels that are not products: unit check, normalisation, exp, log, apply.

Motors are 8-tuples in clifford's even blade order (:mod:`ga_rotors._pga`); bivectors
(lines) are 6-tuples (e01, e02, e03, e12, e13, e23). The formulas are written on the two
quaternions of a motor, M = R(r) + e0123 R(d) (:func:`ga_rotors._motor_kernels.dual_parts`,
R the rotor isomorphism w − x e23 − y e31 − z e12), because e0123 = I commutes with every
even element and squares to zero: the motors are the dual quaternions r + ε d with ε = I,
and exp and log are those of dual numbers. With a bivector B = R((0, a)) + I R((0, b))
(Euclidean part −I₃a, ideal part b₁e01 + b₂e02 + b₃e03), θ = |a|::

    B² = −θ² − 2 (a·b) I,
    exp(B) = (cos θ, S a) + I (−S (a·b), S b − T (a·b) a),
    S = sin θ / θ,   T = (sin θ − θ cos θ) / θ³,

which follows from exp(B) = cos Θ + (sin Θ / Θ) B with the dual angle Θ = θ + (a·b)/θ I
(a function of a dual number: f(θ + δI) = f(θ) + δ f′(θ) I). The log inverts it: θ and a
from r (the rotor log, exact at θ = 0 and at half-turns), then a·b = (d⃗·a) cos θ − d₀ θ sin θ
(no division) and b = (d⃗ + T (a·b) a) / S.

Compiled with the package policy (:mod:`ga_rotors._jit`); the loops of
:mod:`ga_rotors.motor._loops` and, later, the integrators call them.
"""

from __future__ import annotations

from math import atan2, cos, inf, nan, pi, sin

from .._jit import jit
from .._kernels import qnorm, qrotate
from .._motor_kernels import dual_parts, from_dual_parts, translation

__all__ = [
    "apply_point",
    "bivector_parts",
    "from_bivector_parts",
    "mexp",
    "mlog",
    "mnormalize",
    "munit",
    "screw_coefficient",
]

_NAN8 = (nan, nan, nan, nan, nan, nan, nan, nan)

#: Below this θ, T(θ) = (sin θ − θ cos θ)/θ³ is summed from its series: the closed form
#: cancels there (sin θ − θ cos θ ≈ θ³/3, a relative error of ~ε/θ²; 3ε at θ = 1), while
#: the series' first omitted term, 20 θ¹⁸/21! ≤ 4e-19, is far below an ulp of T ≈ 1/3.
SERIES_BELOW = 1.0


@jit
def screw_coefficient(theta):
    """T(θ) = (sin θ − θ cos θ)/θ³ = Σₖ (−1)ᵏ 2(k+1) θ²ᵏ/(2k+3)!, accurate at every θ ≥ 0.

    Examples
    --------
    >>> screw_coefficient(0.0), screw_coefficient(1e-3)      # 1/3 − θ²/30 + …
    (0.3333333333333333, 0.33333330000000116)
    """
    if theta < SERIES_BELOW:
        x = theta * theta
        # Horner form of the series through the θ¹⁶ term (2(k+1)/(2k+3)! for k = 0 … 8).
        s = 18.0 / 121645100408832000.0
        s = 16.0 / 355687428096000.0 - x * s
        s = 14.0 / 1307674368000.0 - x * s
        s = 12.0 / 6227020800.0 - x * s
        s = 10.0 / 39916800.0 - x * s
        s = 8.0 / 362880.0 - x * s
        s = 6.0 / 5040.0 - x * s
        s = 4.0 / 120.0 - x * s
        return 2.0 / 6.0 - x * s
    return (sin(theta) - theta * cos(theta)) / (theta * theta * theta)


@jit
def bivector_parts(b):
    """The vectors (a, b) of a bivector B = R((0, a)) + I R((0, b)) given as a 6-tuple."""
    r, d = dual_parts((0.0, b[0], b[1], b[2], b[3], b[4], b[5], 0.0))
    return (r[1], r[2], r[3]), (d[1], d[2], d[3])


@jit
def from_bivector_parts(a, b):
    """The bivector 6-tuple of the vectors (a, b): the inverse of :func:`bivector_parts`."""
    m = from_dual_parts((0.0, a[0], a[1], a[2]), (0.0, b[0], b[1], b[2]))
    return (m[1], m[2], m[3], m[4], m[5], m[6])


@jit
def _normalized(r, d, n, rd):
    """(r, d) scaled so |r| = 1 and made to satisfy r·d = 0 (given n = |r|, rd = r·d).

    One division and eight multiplications by 1/n rather than eight divisions: within an
    ulp of dividing, and the loops that check a unit motor per item spend most of their
    time here otherwise.
    """
    inv = 1.0 / n
    k = rd * inv * inv
    return from_dual_parts(
        (r[0] * inv, r[1] * inv, r[2] * inv, r[3] * inv),
        ((d[0] - k * r[0]) * inv, (d[1] - k * r[1]) * inv, (d[2] - k * r[2]) * inv,
         (d[3] - k * r[3]) * inv),
    )  # fmt: skip


@jit
def mnormalize(m):
    """The unit motor of m: M (1 − (r·d/|r|²) I)/|r|, so that M M̃ = 1; NaN when r = 0.

    With M M̃ = |r|² + 2 (r·d) I (I = e0123 central, I² = 0), multiplying by the central
    f = (1 − (r·d/|r|²) I)/|r| gives f² M M̃ = 1: r is scaled to unit length and d loses its
    component along r (the Study condition r·d = 0).
    """
    r, d = dual_parts(m)
    n = qnorm(r)
    if n == 0.0 or n == inf:
        return _NAN8
    rd = r[0] * d[0] + r[1] * d[1] + r[2] * d[2] + r[3] * d[3]
    return _normalized(r, d, n, rd)


@jit
def munit(m, tol):
    """m normalised (:func:`mnormalize`) when it is a unit motor within ``tol``, else all-NaN.

    Within tol: | |r| − 1 | ≤ tol and |r·d| ≤ tol |r| max(1, |d|) (the Study condition).
    d carries a length (|d| = |t|/2), so its violation is measured relative to |d| and, for
    short translations, against one length unit: a motor computed with cancellation
    (M M⁻¹, whose d is rounding noise) must pass, and relative to |d| alone it would not.
    NaN and infinite components give NaN: they fail the comparisons.
    """
    r, d = dual_parts(m)
    n = qnorm(r)
    rd = r[0] * d[0] + r[1] * d[1] + r[2] * d[2] + r[3] * d[3]
    if not (abs(n - 1.0) <= tol and abs(rd) <= tol * n * max(1.0, qnorm(d))):
        return _NAN8
    return _normalized(r, d, n, rd)


@jit
def mexp(b):
    """exp(B) of a bivector B (6-tuple): exact at B = 0 and for pure translations.

    Examples
    --------
    >>> mexp((-0.5, 0.0, 0.0, 0.0, 0.0, 0.0))   # exp(−½ e0 t), t = x: the translator
    (1.0, -0.5, 0.0, 0.0, 0.0, 0.0, 0.0, -0.0)
    """
    a, v = bivector_parts(b)
    theta = qnorm((0.0, a[0], a[1], a[2]))
    if theta == inf:
        return _NAN8
    c, s = 1.0, 1.0
    if theta != 0.0:
        c, s = cos(theta), sin(theta) / theta
    t = screw_coefficient(theta)
    ab = a[0] * v[0] + a[1] * v[1] + a[2] * v[2]
    return from_dual_parts(
        (c, s * a[0], s * a[1], s * a[2]),
        (-s * ab, s * v[0] - t * ab * a[0], s * v[1] - t * ab * a[1], s * v[2] - t * ab * a[2]),
    )


@jit
def mlog(m):
    """The bivector B (6-tuple) with exp(B) = m for a unit motor m, rotor angle θ ∈ [0, π].

    θ = atan2(|r⃗|, r₀), so sin θ = |r⃗| and cos θ = r₀ need no trigonometry. Exact at
    m = 1, for translators, and at half-turns (θ = π/2). At θ = π (rotor part −1) the
    motor is −T(t) and the axis is taken along t (the z axis for t = 0, as the quaternion
    log); near it the log is ill-conditioned, as every log is near its cut.
    """
    r, d = dual_parts(m)
    dv = (d[1], d[2], d[3])
    s = qnorm((0.0, r[1], r[2], r[3]))
    if s == 0.0:
        if r[0] >= 0.0:
            return from_bivector_parts((0.0, 0.0, 0.0), dv)
        n = qnorm((0.0, dv[0], dv[1], dv[2]))
        if n == 0.0:
            return from_bivector_parts((0.0, 0.0, pi), dv)
        return from_bivector_parts((pi * dv[0] / n, pi * dv[1] / n, pi * dv[2] / n),
                                   (-dv[0], -dv[1], -dv[2]))  # fmt: skip
    theta = atan2(s, r[0])
    f = theta / s  # 1 / (sin θ / θ)
    a = (f * r[1], f * r[2], f * r[3])
    ab = (dv[0] * a[0] + dv[1] * a[1] + dv[2] * a[2]) * r[0] - d[0] * theta * s
    t = screw_coefficient(theta) * ab
    return from_bivector_parts(
        a, ((dv[0] + t * a[0]) * f, (dv[1] + t * a[1]) * f, (dv[2] + t * a[2]) * f)
    )


@jit
def apply_point(m, x):
    """The image R x R̃ + t of the Euclidean point x (3-tuple) under the unit motor m = T(t) R.

    The same as the sandwich of the PGA point of x, in 27 multiplications instead of 64.
    """
    r, _ = dual_parts(m)
    t = translation(m)
    v = qrotate(r, x)
    return (v[0] + t[0], v[1] + t[1], v[2] + t[2])
