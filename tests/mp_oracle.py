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


def _quaternion_of(m):
    """The unit quaternion of the rotation matrix ``m`` (mpmath), Shepperd's branches."""
    trace = m[0, 0] + m[1, 1] + m[2, 2]
    k = max(range(4), key=lambda i: (trace, m[0, 0], m[1, 1], m[2, 2])[i])
    if k == 0:
        w = mp.sqrt(1 + trace) / 2
        return [w, (m[2, 1] - m[1, 2]) / (4 * w), (m[0, 2] - m[2, 0]) / (4 * w),
                (m[1, 0] - m[0, 1]) / (4 * w)]  # fmt: skip
    i, j, l = ((0, 1, 2), (1, 2, 0), (2, 0, 1))[k - 1]
    a = mp.sqrt(1 + m[i, i] - m[j, j] - m[l, l]) / 2
    out = [None] * 4
    out[0] = (m[l, j] - m[j, l]) / (4 * a)
    out[1 + i] = a
    out[1 + j] = (m[i, j] + m[j, i]) / (4 * a)
    out[1 + l] = (m[i, l] + m[l, i]) / (4 * a)
    return out


def _qmul(a, b):
    aw, ax, ay, az = a
    bw, bx, by, bz = b
    return [
        aw * bw - ax * bx - ay * by - az * bz,
        aw * bx + ax * bw + ay * bz - az * by,
        aw * by - ax * bz + ay * bw + az * bx,
        aw * bz + ax * by - ay * bx + az * bw,
    ]


def integrate_tensor(tensor, q0, w0, times, digits=40, order=ORDER):
    """Orientations (unit quaternions, mpf 4-lists) at ``times`` of the body whose inertia is
    the symmetric ``tensor`` (in the frame q0 and w0 are given in), diagonalised here in
    ``digits`` digits (mpmath's eigsy), integrated by :func:`integrate` in its principal
    frame and answered in the tensor's."""
    with mp.workdps(digits):
        t = mp.matrix([[(mp.mpf(tensor[i][j]) + mp.mpf(tensor[j][i])) / 2 for j in range(3)]
                       for i in range(3)])  # fmt: skip
        values, vectors = mp.eigsy(t)
        order_ = sorted(range(3), key=lambda i: values[i])
        values = [values[i] for i in order_]
        axes = mp.matrix([[vectors[r, c] for c in order_] for r in range(3)])
        if mp.det(axes) < 0:
            for r in range(3):
                axes[r, 2] = -axes[r, 2]
        p = _quaternion_of(axes)  # principal axes -> the tensor's frame
        w = [sum(axes[r, c] * mp.mpf(w0[r]) for r in range(3)) for c in range(3)]
        q = _qmul([mp.mpf(x) for x in q0], p)
        back = [p[0], -p[1], -p[2], -p[3]]
        states = integrate(values, q, w, times, digits=digits, order=order)
        return [_qmul(list(y[:4]), back) for y in states]
