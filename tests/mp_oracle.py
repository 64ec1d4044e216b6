"""An independent high-precision oracle for rigid-body motion: a Taylor-series integrator in
mpmath (30 significant digits), sharing no code with ga_rotors.

The equations of motion are quadratic polynomials in the state (q, ω), so their Taylor
coefficients follow from Cauchy products of the state's coefficients (automatic
differentiation by recurrence): y_{k+1} = [F(y)]_k / (k + 1). Each step takes the series
to order ``ORDER`` and a step of a quarter of the series' estimated radius of convergence,
so the truncation error is ~4^-ORDER relative, far below 1e-20.
"""

from __future__ import annotations

import mpmath as mp

ORDER = 32
DIGITS = 30


def _cauchy(a, b, k):
    return mp.fdot(a[: k + 1], b[k::-1])


def _rigid_body_coefficient(series, k, inertia, mgl):
    """k-th Taylor coefficient of (q̇, ω̇) for q̇ = ½ q ⊗ (0, ω), I ω̇ = (I ω) × ω + τ,
    τ = mgl · (Z_y, −Z_x, 0) with Z = q* ẑ q (heavy top, centre of mass on body z)."""
    qw, qx, qy, qz, w1, w2, w3 = series
    i1, i2, i3 = inertia

    def c(a, b):
        return _cauchy(a, b, k)

    dq = (
        (-c(qx, w1) - c(qy, w2) - c(qz, w3)) / 2,
        (c(qw, w1) + c(qy, w3) - c(qz, w2)) / 2,
        (c(qw, w2) - c(qx, w3) + c(qz, w1)) / 2,
        (c(qw, w3) + c(qx, w2) - c(qy, w1)) / 2,
    )
    t1 = t2 = 0
    if mgl:
        zx = 2 * (c(qx, qz) - c(qw, qy))
        zy = 2 * (c(qy, qz) + c(qw, qx))
        t1, t2 = mgl * zy, -mgl * zx
    dw = (
        ((i2 - i3) * c(w2, w3) + t1) / i1,
        ((i3 - i1) * c(w3, w1) + t2) / i2,
        (i1 - i2) * c(w1, w2) / i3,
    )
    return dq + dw


def integrate(inertia, q0, w0, times, mgl=0.0, digits=DIGITS, order=ORDER):
    """States (q, ω) at the given increasing non-negative times, as lists of mpf 7-tuples
    (``digits`` significant digits, truncation ~4^-``order`` relative per step)."""
    with mp.workdps(digits):
        inertia = [mp.mpf(x) for x in inertia]
        mgl = mp.mpf(mgl)
        y = [mp.mpf(x) for x in (*q0, *w0)]
        t = mp.mpf(0)
        out = []
        for target in times:
            target = mp.mpf(target)
            while t < target:
                series = [[v] for v in y]
                for k in range(order):
                    coef = _rigid_body_coefficient(series, k, inertia, mgl)
                    for s, d in zip(series, coef, strict=True):
                        s.append(d / (k + 1))
                tail = max(max(abs(s[-1]), abs(s[-2])) for s in series)
                radius = (tail / max(1, max(abs(v) for v in y))) ** (-mp.mpf(1) / order)
                h = min(radius / 4, target - t)
                y = [mp.polyval(s[::-1], h) for s in series]
                t += h
            out.append(tuple(y))
        return out
