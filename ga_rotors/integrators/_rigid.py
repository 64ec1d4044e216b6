"""Compiled kernels the Lie-group, splitting and variational templates share.

Plain compiled functions (not templates): they depend on no slot, so generated modules
import them as they are.
"""

from __future__ import annotations

from .._jit import jit
from .._kernels import qconj, qmul, qrotate, quat_from_rotvec


@jit
def turn(q, h, v):
    """q ⊗ Exp(h v): q moved along the constant body rate v for a time h."""
    return qmul(q, quat_from_rotvec((h * v[0], h * v[1], h * v[2])))


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
    """Exact flow about body axis ``axis`` by ``angle``: q ⊗ r and the body vector r* L r."""
    if axis == 0:
        r = quat_from_rotvec((angle, 0.0, 0.0))
    elif axis == 1:
        r = quat_from_rotvec((0.0, angle, 0.0))
    else:
        r = quat_from_rotvec((0.0, 0.0, angle))
    return qmul(q, r), qrotate(qconj(r), L)


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
