"""Compiled kernels the Lie-group, splitting and variational templates share.

Plain compiled functions (not templates): they depend on no slot, so generated modules
import them as they are.
"""

from __future__ import annotations

from math import cos, sin

from .._jit import jit
from .._kernels import qmul_exp


@jit
def turn(q, h, v):
    """q ⊗ Exp(h v): q moved along the constant body rate v for a time h.

    Through :func:`ga_rotors._kernels.qmul_exp` (q + q ⊗ (exp − 1)): a steady spin turns by
    the same angle every step, and q ⊗ exp would round |exp| the same way every step.
    """
    return qmul_exp(q, (0.5 * h * v[0], 0.5 * h * v[1], 0.5 * h * v[2]))


@jit
def momenta(w, inertia):
    """L = I ω (principal frame)."""
    return (inertia[0] * w[0], inertia[1] * w[1], inertia[2] * w[2])


@jit
def rates(L, inertia):
    """ω = I⁻¹ L (principal frame)."""
    return (L[0] / inertia[0], L[1] / inertia[1], L[2] / inertia[2])


@jit
def rotate_about(q, L, axis, angle):
    """Exact flow about body axis ``axis`` (0, 1, 2) by ``angle``: q ⊗ r and r* L r.

    r = (cos ½φ, sin ½φ e_axis). Written out per axis: one sin and one cos of the half
    angle, the full-angle cos φ = 1 − 2s², sin φ = 2cs for L, and the 8 products of q ⊗ r
    instead of 16 (a splitting step is dominated by these rotations).

    cos φ as 1 − 2s², not c² − s²: then cos²φ + sin²φ = 1 + 4s²(c² + s² − 1), so the
    rounding of c and s scales |L| by 4s² ε instead of 2ε. It matters because a run turns
    by nearly the same angle every step, so that rounding repeats and adds up linearly:
    c² − s² let |L| drift by 1e-11 in 10⁶ steps of split4/split6, 1 − 2s² leaves a random
    walk of 3e-13 (tests/test_stability_dynamics.py).

    q ⊗ r as q + q ⊗ (r − 1), with c − 1 = −s²/(1 + c) (no cancellation for c > 0), for
    the same reason as :func:`ga_rotors._kernels.qmul_exp`: in a steady spin the angle is
    the same every step, c rounds to the same float every step, and q ⊗ r would scale |q|
    by the same 1 + δ every step (a linear drift of 4e-11 in 10⁶ steps of split_sym).

    L likewise as L + ((cos φ − 1) L + sin φ L⊥), cos φ − 1 = −2s²: cos φ itself is a float
    near 1 and rounds the same way every step when the angle repeats (a nearly spherical
    body, ω nearly constant), which scaled |L| by the same 1 + δ every rotation: split4
    drifted by 4.4e-14 in 100 steps on (1, 1 + 1.5e-5, 1 + 3e-5) at h|L|/I = 1e-4, above
    the random walk (found by tests/test_stability_fuzz.py).
    """
    c = cos(0.5 * angle)
    s = sin(0.5 * angle)
    cm = -s * s / (1.0 + c) if c > 0.0 else c - 1.0
    cfm = -2.0 * s * s
    sf = 2.0 * c * s
    q0, q1, q2, q3 = q
    if axis == 0:
        return (
            (q0 + (q0 * cm - q1 * s), q1 + (q0 * s + q1 * cm), q2 + (q2 * cm + q3 * s),
             q3 + (q3 * cm - q2 * s)),
            (L[0], L[1] + (L[1] * cfm + L[2] * sf), L[2] + (L[2] * cfm - L[1] * sf)),
        )  # fmt: skip
    if axis == 1:
        return (
            (q0 + (q0 * cm - q2 * s), q1 + (q1 * cm - q3 * s), q2 + (q0 * s + q2 * cm),
             q3 + (q1 * s + q3 * cm)),
            (L[0] + (L[0] * cfm - L[2] * sf), L[1], L[2] + (L[0] * sf + L[2] * cfm)),
        )  # fmt: skip
    return (
        (q0 + (q0 * cm - q3 * s), q1 + (q1 * cm + q2 * s), q2 + (q2 * cm - q1 * s),
         q3 + (q0 * s + q3 * cm)),
        (L[0] + (L[0] * cfm + L[1] * sf), L[1] + (L[1] * cfm - L[0] * sf), L[2]),
    )  # fmt: skip


@jit
def solve3(a, b):
    """x with A x = b for a 3×3 A given as a 9-tuple (rows), by Cramer's rule."""
    a00, a01, a02, a10, a11, a12, a20, a21, a22 = a
    c00 = a11 * a22 - a12 * a21
    c01 = a12 * a20 - a10 * a22
    c02 = a10 * a21 - a11 * a20
    det = a00 * c00 + a01 * c01 + a02 * c02
    x0 = b[0] * c00 + b[1] * (a02 * a21 - a01 * a22) + b[2] * (a01 * a12 - a02 * a11)
    x1 = b[0] * c01 + b[1] * (a00 * a22 - a02 * a20) + b[2] * (a02 * a10 - a00 * a12)
    x2 = b[0] * c02 + b[1] * (a01 * a20 - a00 * a21) + b[2] * (a00 * a11 - a01 * a10)
    return (x0 / det, x1 / det, x2 / det)


@jit
def symmetric_pair(inertia):
    """(k, p, r): I_p and I_r the two closest moments (the symmetric top's I⊥ = I_p), k the
    remaining axis (the symmetric top's axis)."""
    d01 = abs(inertia[0] - inertia[1])
    d12 = abs(inertia[1] - inertia[2])
    d02 = abs(inertia[0] - inertia[2])
    if d01 <= d12 and d01 <= d02:
        return 2, 0, 1
    if d12 <= d02:
        return 0, 1, 2
    return 1, 0, 2
