"""Scalar quaternion kernels: every formula written once, compiled, shared by all loops.

Quaternions are 4-tuples ``(w, x, y, z)`` (scalar first, Hamilton product, see
``docs/conventions.md``), vectors are 3-tuples. Tuples keep the kernels free of heap
allocation, so LLVM inlines them into the batched loops and integrators that call them;
they also run unchanged as plain Python (``NUMBA_DISABLE_JIT=1``), which the tests use to
check compiled and uncompiled results agree.

Public, validated, vectorised functions live in :mod:`ga_rotors.quaternion` and friends;
this module is the arithmetic they share.
"""

from __future__ import annotations

from math import atan2, cos, hypot, pi, sin, sqrt

from ._jit import jit


@jit
def qmul(a, b):
    """Hamilton product a ⊗ b (ij = k, ijk = -1)."""
    a0, a1, a2, a3 = a
    b0, b1, b2, b3 = b
    return (
        a0 * b0 - a1 * b1 - a2 * b2 - a3 * b3,
        a0 * b1 + a1 * b0 + a2 * b3 - a3 * b2,
        a0 * b2 - a1 * b3 + a2 * b0 + a3 * b1,
        a0 * b3 + a1 * b2 - a2 * b1 + a3 * b0,
    )


@jit
def qconj(a):
    """Conjugate (w, -x, -y, -z)."""
    return (a[0], -a[1], -a[2], -a[3])


@jit
def qmul_pure(a, v):
    """a ⊗ (0, v): the product the kinematics q̇ = ½ q ⊗ (0, ω) needs, without the zero terms."""
    a0, a1, a2, a3 = a
    v1, v2, v3 = v
    return (
        -a1 * v1 - a2 * v2 - a3 * v3,
        a0 * v1 + a2 * v3 - a3 * v2,
        a0 * v2 - a1 * v3 + a3 * v1,
        a0 * v3 + a1 * v2 - a2 * v1,
    )


@jit
def hypot3(x, y, z):
    """|(x, y, z)| without overflow or underflow (1e-300 and 1e300 components stay exact)."""
    return hypot(hypot(x, y), z)


@jit
def qnorm(a):
    """|a|, exact for components from 1e-300 to 1e300.

    The plain square root is used whenever the sum of squares is a normal number, which
    is every practical case; the scaled path only runs when it under- or overflows.
    """
    s = a[0] * a[0] + a[1] * a[1] + a[2] * a[2] + a[3] * a[3]
    if 1e-290 < s < 1e290:
        return sqrt(s)
    return hypot(hypot(a[0], a[1]), hypot(a[2], a[3]))


@jit
def qnormalize(a):
    """a / |a| (the caller checks |a| > 0)."""
    n = qnorm(a)
    return (a[0] / n, a[1] / n, a[2] / n, a[3] / n)


@jit
def cross(u, v):
    """u × v."""
    return (
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    )


@jit
def qrotate(q, v):
    """q (0, v) q* for unit q, in 15 multiplications instead of two full products.

    With t = 2 q⃗ × v:  q v q* = v + w t + q⃗ × t.
    """
    w = q[0]
    u = (q[1], q[2], q[3])
    c = cross(u, v)
    t = (2.0 * c[0], 2.0 * c[1], 2.0 * c[2])
    d = cross(u, t)
    return (v[0] + w * t[0] + d[0], v[1] + w * t[1] + d[1], v[2] + w * t[2] + d[2])


@jit
def qexp_pure(v):
    """exp((0, v)) = (cos |v|, sin|v| / |v| · v): the unit quaternion of half-angle |v|.

    Exact for every |v| that is representable: the robust norm keeps 1e-300 from
    underflowing, so sin(s)/s is only special-cased at exactly zero.
    """
    s = hypot3(v[0], v[1], v[2])
    if s == 0.0:
        return (1.0, v[0], v[1], v[2])
    f = sin(s) / s
    return (cos(s), f * v[0], f * v[1], f * v[2])


@jit
def qlog_unit(q):
    """Vector part of log q for unit q: u·φ with q = (cos φ, u sin φ), φ = atan2(|q⃗|, w) ∈ [0, π].

    atan2 keeps full relative precision at every angle, where acos(w) loses half the
    digits near 0 and π. At q = -1 the axis is free; the z axis is chosen (documented).
    """
    x, y, z = q[1], q[2], q[3]
    s = hypot3(x, y, z)
    if s == 0.0:
        if q[0] >= 0.0:
            return (0.0, 0.0, 0.0)
        return (0.0, 0.0, pi)
    f = atan2(s, q[0]) / s
    return (f * x, f * y, f * z)


@jit
def quat_from_rotvec(r):
    """Unit quaternion of the rotation by |r| about r/|r| (active, right-handed)."""
    return qexp_pure((0.5 * r[0], 0.5 * r[1], 0.5 * r[2]))


@jit
def rotvec_from_quat(q):
    """Rotation vector of unit q, angle in [0, π] (q and -q give the same answer)."""
    if q[0] < 0.0:
        q = (-q[0], -q[1], -q[2], -q[3])
    h = qlog_unit(q)
    return (2.0 * h[0], 2.0 * h[1], 2.0 * h[2])


@jit
def geodesic_angle(a, b):
    """Rotation angle of a* ⊗ b in [0, π]: the geodesic distance between two rotations.

    2·atan2(|vec|, |scalar|) resolves differences down to 1e-16 rad; 2·acos(·) cannot go
    below ~1e-8 rad.
    """
    d = qmul(qconj(a), b)
    return 2.0 * atan2(hypot3(d[1], d[2], d[3]), abs(d[0]))
