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

from math import atan2, cos, exp, hypot, inf, log, nan, pi, sin, sqrt

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
def norm2(x, y):
    """|(x, y)| as :func:`qnorm` takes a norm: the plain square root of the sum of squares
    whenever that sum is a normal number, ``hypot`` only where it under- or overflows
    (within an ulp of ``hypot``, which costs about 12 ns a call here against 2)."""
    s = x * x + y * y
    if 1e-290 < s < 1e290:
        return sqrt(s)
    return hypot(x, y)


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
    """a / |a|; all-NaN for a = 0 (the caller's finiteness check reports it).

    Zero is tested explicitly because uncompiled Python raises on division by zero where
    compiled code returns nan; kernels must behave the same both ways.
    """
    n = qnorm(a)
    if n == 0.0:
        return (nan, nan, nan, nan)
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
    if s == inf:  # compiled sin(inf) is nan, plain Python's raises: both give all-NaN
        return (nan, nan, nan, nan)
    f = sin(s) / s
    return (cos(s), f * v[0], f * v[1], f * v[2])


@jit
def qexpm1_pure(v):
    """exp((0, v)) − 1 = (−2 sin²(|v|/2), sin|v| / |v| · v), every component to a few ulps.

    The scalar part cos|v| − 1 is written −2 sin²(|v|/2), so it keeps its relative
    precision at small angles where 1 − cos|v| cancels (the expm1 of rotations). Used by
    :func:`qmul_exp`. Exact at 0 (returns (0, v)); NaN for infinite v, as qexp_pure.
    """
    s = hypot3(v[0], v[1], v[2])
    if s == 0.0:
        return (0.0, v[0], v[1], v[2])
    if s == inf:
        return (nan, nan, nan, nan)
    h = sin(0.5 * s)
    f = sin(s) / s
    return (-2.0 * h * h, f * v[0], f * v[1], f * v[2])


@jit
def qmul_exp(q, v):
    """q ⊗ exp((0, v)), as q + q ⊗ (exp((0, v)) − 1): a step along a rotation of half-angle |v|.

    Why not qmul(q, qexp_pure(v)): over a run that turns by nearly the same angle every
    step (a body spinning steadily, split_sym's symmetric-top flow at its constant |L|),
    cos|v| rounds to the SAME float every step, so |exp| = 1 + δ with one fixed δ ≤ u/2 and
    |q| drifts linearly, (1 + δ)^N (split_sym: 2e-11 in 10⁶ steps). No formula for
    exp((0, v)) avoids it: floats near 1 are spaced u, so the scalar part must carry a
    rounding of up to u/2, and forcing |exp| = 1 (renormalising, or sin from √(1 − cos²))
    either cannot move it or turns the angle by u/(2|v|) instead (both measured). Here the
    increment q ⊗ (exp − 1) is accurate to relative rounding (|exp − 1| ~ |v|, so its
    rounding is u|v|), and the one rounding that matters, of the sum q + increment, falls
    on q's components, which change from step to step: a random walk, not a drift.
    """
    d = qexpm1_pure(v)
    p = qmul(q, d)
    return (q[0] + p[0], q[1] + p[1], q[2] + p[2], q[3] + p[3])


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


@jit
def angle_any_norm(a, b):
    """:func:`geodesic_angle` of a and b whatever their norms; NaN unless both are finite
    and nonzero.

    2·atan2(|vec d|, |scalar d|) of d = a* ⊗ b does not depend on the norms (d scales
    with them): a state whose norm drifted (RK4 over a long or fast run) still has its
    angle. |vec d| is :func:`qnorm`'s (a square root of the sum of squares, scaled only
    where that under- or overflows) rather than two ``hypot`` calls: within an ulp, and
    7x faster in a loop over samples.
    """
    d = qmul(qconj(a), b)
    v, s = qnorm((0.0, d[1], d[2], d[3])), abs(d[0])
    return 2.0 * atan2(v, s) if 0.0 < v + s < inf else nan


@jit
def qinverse(a):
    """a⁻¹ = a* / |a|², divided twice by |a| so that |a| down to 1e-300 does not underflow.

    a = 0 gives all-NaN, which the loops detect and report.
    """
    n = qnorm(a)
    if n == 0.0:
        return (nan, nan, nan, nan)
    return (a[0] / n / n, -a[1] / n / n, -a[2] / n / n, -a[3] / n / n)


@jit
def qunit(a, tol):
    """a / |a| when | |a| - 1 | <= tol, else all-NaN (so a loop's finiteness check flags it).

    NaN and infinite components also give NaN: their norm fails the comparison.
    """
    n = qnorm(a)
    if not abs(n - 1.0) <= tol:
        return (nan, nan, nan, nan)
    return (a[0] / n, a[1] / n, a[2] / n, a[3] / n)


@jit
def qexp(a):
    """exp(a) = e^w (cos|v|, sin|v| v/|v|) for a general quaternion a = (w, v)."""
    # e^w overflows above ln(DBL_MAX); inf is written out because Python's math.exp raises
    # there, and the kernels must behave alike compiled and uncompiled.
    e = inf if a[0] > 709.782712893384 else exp(a[0])
    p = qexp_pure((a[1], a[2], a[3]))
    return (e * p[0], e * p[1], e * p[2], e * p[3])


@jit
def qlog(a):
    """log(a) = (ln|a|, u·atan2(|v|, w)) for nonzero a; at negative reals u is the z axis."""
    n = qnorm(a)
    if n == 0.0:
        return (-inf, nan, nan, nan)
    h = qlog_unit((a[0] / n, a[1] / n, a[2] / n, a[3] / n))
    return (log(n), h[0], h[1], h[2])


@jit
def axis_angle_from_quat(q):
    """(u_x, u_y, u_z, α) of unit q with α = 2·atan2(|q⃗|, |w|) ∈ [0, π].

    q and -q give the same answer (the axis flips with the sign of w). At α = 0 the axis is
    free; +z is returned, never NaN. At α = π (w = 0) both ±u are valid; q⃗/|q⃗| is returned.
    """
    w, x, y, z = q
    if w < 0.0:
        w, x, y, z = -w, -x, -y, -z
    s = hypot3(x, y, z)
    if s == 0.0:
        return (0.0, 0.0, 1.0, 0.0)
    return (x / s, y / s, z / s, 2.0 * atan2(s, w))


@jit
def quat_from_axis_angle(u, angle):
    """Unit quaternion of the rotation by ``angle`` about u/|u| (u ≠ 0; any real angle)."""
    n = hypot3(u[0], u[1], u[2])
    if n == 0.0:
        return (nan, nan, nan, nan)
    return quat_from_rotvec((angle * (u[0] / n), angle * (u[1] / n), angle * (u[2] / n)))


@jit
def qslerp(a, b, t):
    """a ⊗ exp(t · log(a* ⊗ b)) along the shorter arc of rotations (unit a, b).

    Written with the exp/log kernels, which are exact at tiny angles, instead of the
    sin((1-t)Ω)/sin Ω weights, which divide 0 by 0 when a ≈ b. If a* b has w < 0 it is
    negated first (b and -b are the same rotation), so slerp(q, -q, t) = q for every t.
    """
    d = qmul(qconj(a), b)
    if d[0] < 0.0:
        d = (-d[0], -d[1], -d[2], -d[3])
    h = qlog_unit(d)
    return qmul(a, qexp_pure((t * h[0], t * h[1], t * h[2])))


#: |û × v̂| at or below this counts as exactly (anti)parallel: normalising exactly parallel
#: vectors rounds each component by up to ~2 ulp, which leaves a cross product of a few
#: 1e-16; 1e-15 covers that with margin, and the rotation returned then maps û onto v̂ to
#: within the same 1e-15.
PARALLEL_TOLERANCE = 1e-15


@jit
def perpendicular(u):
    """A unit vector ⊥ unit u: u × e_k with e_k the coordinate axis least aligned with u
    (the first such axis on ties), normalised. For u = ±x that is ±z; for u = ±z it is ±y."""
    ax, ay, az = abs(u[0]), abs(u[1]), abs(u[2])
    if ax <= ay and ax <= az:
        p = (0.0, u[2], 0.0 - u[1])  # u × x (0.0 - keeps zeros unsigned)
    elif ay <= az:
        p = (0.0 - u[2], 0.0, u[0])  # u × y
    else:
        p = (u[1], 0.0 - u[0], 0.0)  # u × z
    n = hypot3(p[0], p[1], p[2])
    return (p[0] / n, p[1] / n, p[2] / n)


@jit
def quat_from_two_vectors(u, v):
    """Unit quaternion of the smallest rotation taking the direction of u onto that of v.

    Angle atan2(|û × v̂|, û · v̂) (accurate at 0 and π), axis û × v̂ re-orthogonalised
    against û: near antiparallel vectors the cross product has a relative error of
    ~1e-16/sin(angle), and an axis that is not exactly ⊥ û would move û off v̂ by that
    much; after the projection the error in the image of û stays at round-off.
    Parallel: the identity. Antiparallel: the half-turn about :func:`perpendicular` (û).
    Zero vectors give NaN (the caller reports them).
    """
    nu = hypot3(u[0], u[1], u[2])
    nv = hypot3(v[0], v[1], v[2])
    if nu == 0.0 or nv == 0.0:
        return (nan, nan, nan, nan)
    a = (u[0] / nu, u[1] / nu, u[2] / nu)
    b = (v[0] / nv, v[1] / nv, v[2] / nv)
    c = cross(a, b)
    s = hypot3(c[0], c[1], c[2])
    d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
    if s <= PARALLEL_TOLERANCE:
        if d > 0.0:
            return (1.0, 0.0, 0.0, 0.0)
        p = perpendicular(a)
        return (0.0, p[0], p[1], p[2])
    k = (c[0] / s, c[1] / s, c[2] / s)
    along = k[0] * a[0] + k[1] * a[1] + k[2] * a[2]
    k = (k[0] - along * a[0], k[1] - along * a[1], k[2] - along * a[2])
    nk = hypot3(k[0], k[1], k[2])
    half = 0.5 * atan2(s, d)
    f = sin(half) / nk
    return (cos(half), f * k[0], f * k[1], f * k[2])


@jit
def matrix_from_quat(q):
    """Rotation matrix of unit q, row-major 9-tuple: M v = q v q* (active)."""
    w, x, y, z = q
    return (
        1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y - w * z), 2.0 * (x * z + w * y),
        2.0 * (x * y + w * z), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z - w * x),
        2.0 * (x * z - w * y), 2.0 * (y * z + w * x), 1.0 - 2.0 * (x * x + y * y),
    )  # fmt: skip


@jit
def quat_from_matrix(m):
    """Unit quaternion (w ≥ 0) of a rotation matrix given as a row-major 9-tuple.

    From M = [[w²+x²-y²-z², 2(xy-wz), 2(xz+wy)], [2(xy+wz), w²-x²+y²-z², 2(yz-wx)],
    [2(xz-wy), 2(yz+wx), w²-x²-y²+z²]]: 4w² = 1 + tr M, 4x² = 1 + m00 - m11 - m22 (and
    cyclic), and the off-diagonal sums and differences give 4wx, 4xy, ... . The component
    whose square is largest (the largest of tr M, m00, m11, m22) is at least 1/2, so it is
    taken from its square root and the others are divided by it: no division by a small
    number anywhere, exact at half-turns where w = 0 (the notes' division by 4w fails).
    """
    m00, m01, m02, m10, m11, m12, m20, m21, m22 = m
    tr = m00 + m11 + m22
    if tr >= m00 and tr >= m11 and tr >= m22:
        r = sqrt(1.0 + tr)
        f = 0.5 / r
        q = (0.5 * r, (m21 - m12) * f, (m02 - m20) * f, (m10 - m01) * f)
    elif m00 >= m11 and m00 >= m22:
        r = sqrt(1.0 + m00 - m11 - m22)
        f = 0.5 / r
        q = ((m21 - m12) * f, 0.5 * r, (m01 + m10) * f, (m02 + m20) * f)
    elif m11 >= m22:
        r = sqrt(1.0 - m00 + m11 - m22)
        f = 0.5 / r
        q = ((m02 - m20) * f, (m01 + m10) * f, 0.5 * r, (m12 + m21) * f)
    else:
        r = sqrt(1.0 - m00 - m11 + m22)
        f = 0.5 / r
        q = ((m10 - m01) * f, (m02 + m20) * f, (m12 + m21) * f, 0.5 * r)
    if q[0] < 0.0:
        q = (-q[0], -q[1], -q[2], -q[3])
    return qnormalize(q)


@jit
def axis_quat(axis, angle):
    """Unit quaternion of the rotation by ``angle`` about coordinate axis 0, 1 or 2 (x, y, z)."""
    h = 0.5 * angle
    if abs(h) == inf:  # as in qexp_pure: all-NaN compiled and uncompiled alike
        return (nan, nan, nan, nan)
    s = sin(h)
    return (cos(h), s if axis == 0 else 0.0, s if axis == 1 else 0.0, s if axis == 2 else 0.0)


@jit
def quat_from_euler(i, j, k, a, b, c):
    """q_i(a) ⊗ q_j(b) ⊗ q_k(c): intrinsic rotations about axes i, then j′, then k″."""
    return qmul(qmul(axis_quat(i, a), axis_quat(j, b)), axis_quat(k, c))


@jit
def wrap_angle(x):
    """x in (-2π, 2π] mapped to (-π, π] by one exact shift of 2π."""
    if x > pi:
        return x - 2.0 * pi
    if x <= -pi:
        return x + 2.0 * pi
    return x


@jit
def euler_from_quat(q, i, j, k, zero_first, tol):
    """Intrinsic angles (a, b, c, locked) with q = ±q_i(a) ⊗ q_j(b) ⊗ q_k(c), q unit.

    With half angles a′ = a/2 (and so on), e_i e_j = ε e_m (ε = ±1, the parity of the
    axis order):

    * proper (i = k, m the third axis):  (w, q_i) = cos b′ (cos(a′+c′), sin(a′+c′)) and
      (q_j, ε q_m) = sin b′ (cos(a′−c′), sin(a′−c′)), so b = 2·atan2(|(q_j, q_m)|, |(w, q_i)|)
      ∈ [0, π];
    * Tait–Bryan (i, j, k distinct):  (w + q_j, q_i + ε q_k) = (cos b′ + sin b′)
      (cos(a′+εc′), sin(a′+εc′)) and (w − q_j, q_i − ε q_k) = (cos b′ − sin b′)
      (cos(a′−εc′), sin(a′−εc′)); sin b = 2(w q_j + ε q_i q_k), cos b = the product of the
      two moduli, b ∈ [−π/2, π/2].

    Both sum and difference come from atan2 (quadrant-correct, no division), a and c in
    (−π, π]. Gimbal lock: when b is within ``tol`` of the value where one of the two pairs
    vanishes, only one combination of a and c is defined; the third angle of the sequence
    as written is set to 0 (``zero_first`` says that is a, which is the case for extrinsic
    sequences computed through their reversed intrinsic twin) and ``locked`` is 1.0.
    Forcing it moves the rotation by at most 2·tol (a commutator of a rotation by tol).
    """
    w = q[0]
    qi = q[1 + i]
    qj = q[1 + j]
    eps = 1.0 if (j - i) % 3 == 1 else -1.0
    if i == k:
        qm = eps * q[4 - i - j]  # index 1 + m with m = 3 - i - j
        b = 2.0 * atan2(norm2(qj, qm), norm2(w, qi))
        plus = atan2(qi, w)
        minus = atan2(qm, qj)
        sc = 1.0
        minus_free = b <= tol
        plus_free = b >= pi - tol
    else:
        qk = eps * q[1 + k]
        p = norm2(w + qj, qi + qk)
        mm = norm2(w - qj, qi - qk)
        b = atan2(2.0 * (w * qj + qi * qk), p * mm)
        plus = atan2(qi + qk, w + qj)
        minus = atan2(qi - qk, w - qj)
        sc = eps
        minus_free = b >= 0.5 * pi - tol
        plus_free = b <= -0.5 * pi + tol
    if minus_free:
        if zero_first:
            return (0.0, b, wrap_angle(sc * 2.0 * plus), 1.0)
        return (wrap_angle(2.0 * plus), b, 0.0, 1.0)
    if plus_free:
        if zero_first:
            return (0.0, b, wrap_angle(-sc * 2.0 * minus), 1.0)
        return (wrap_angle(2.0 * minus), b, 0.0, 1.0)
    return (wrap_angle(plus + minus), b, wrap_angle(sc * (plus - minus)), 0.0)


# ------------------------------------------------------- Euler angles, Euler's equations


@jit
def zyz_rates(angles, w):
    """(ψ̇, θ̇, φ̇) from ZYZ angles (ψ, θ, φ) and body ω; divides by sin θ (caller's care).

    The checked, vectorised form is :func:`ga_rotors.kinematics.zyz_rates_from_body_omega`.

    Examples
    --------
    A spin about the body axis only turns φ:

    >>> zyz_rates((0.1, 0.5, 0.3), (0.0, 0.0, 10.0))
    (0.0, 0.0, 10.0)

    The inverse of :func:`zyz_omega` wherever sin θ ≠ 0:

    >>> angles = (0.1, 0.5, 0.3)
    >>> zyz_omega(angles, zyz_rates(angles, (0.2, 0.1, 10.0)))
    (0.2, 0.1, 10.0)
    """
    st = sin(angles[1])
    ct = cos(angles[1])
    sp = sin(angles[2])
    cp = cos(angles[2])
    psi_dot = (w[1] * sp - w[0] * cp) / st
    return (psi_dot, w[0] * sp + w[1] * cp, w[2] - psi_dot * ct)


@jit
def zyz_omega(angles, rates):
    """Body ω from ZYZ angles (ψ, θ, φ) and their rates (ψ̇, θ̇, φ̇); regular everywhere.

    The checked, vectorised form is :func:`ga_rotors.kinematics.body_omega_from_zyz_rates`.

    Examples
    --------
    Precession ψ̇ at nutation θ = 90°, φ = 0, seen in the body: about −x.

    >>> import math
    >>> [round(c, 12) for c in zyz_omega((0.0, math.pi / 2, 0.0), (2.0, 0.0, 0.0))]
    [-2.0, 0.0, 0.0]

    At θ = 0 it is still defined (ψ̇ and φ̇ add up):

    >>> zyz_omega((0.0, 0.0, 0.0), (2.0, 0.0, 3.0))
    (-0.0, 0.0, 5.0)
    """
    st = sin(angles[1])
    ct = cos(angles[1])
    sp = sin(angles[2])
    cp = cos(angles[2])
    dpsi, dtheta, dphi = rates
    return (
        -dpsi * st * cp + dtheta * sp,
        dpsi * st * sp + dtheta * cp,
        dpsi * ct + dphi,
    )


@jit
def euler_coefficients(inertia):
    """What Euler's equations divide by: ((I₂ − I₃)/I₁, (I₃ − I₁)/I₂, (I₁ − I₂)/I₃) and
    (1/I₁, 1/I₂, 1/I₃), from the principal moments.

    The one place these six numbers are computed. A single run's loop computes them once
    (they depend on loop invariants only); a batched loop with one inertia per body
    computes them once per body with this same function and keeps them, instead of six
    divisions per body and step (:mod:`ga_rotors.ensemble`); :func:`free_euler_rates` and
    :func:`euler_rates` take them from here, so both give the same numbers bit for bit.

    Examples
    --------
    >>> euler_coefficients((1.0, 2.0, 4.0))
    (-2.0, 1.5, -0.25, 1.0, 0.5, 0.25)
    """
    i1, i2, i3 = inertia[0], inertia[1], inertia[2]
    return ((i2 - i3) / i1, (i3 - i1) / i2, (i1 - i2) / i3, 1.0 / i1, 1.0 / i2, 1.0 / i3)


@jit
def free_euler_rates(inertia, w):
    """ω̇ of the torque-free body: I ω̇ = (I ω) × ω, principal frame, tuples in and out.

    Unchecked (compiled loops call it); the checked form is
    :meth:`ga_rotors.body.RigidBody.angular_acceleration`.

    Written ((I₂ − I₃)/I₁)·ω₂·ω₃ so the inertia ratios (:func:`euler_coefficients`)
    depend on loop invariants only: a compiled loop computes them once instead of
    dividing in every stage.

    Examples
    --------
    >>> free_euler_rates((1.0, 2.0, 3.0), (1.0, 1.0, 1.0))  # ((2-3)/1, (3-1)/2, (1-2)/3)
    (-1.0, 1.0, -0.3333333333333333)

    About a principal axis the body spins steadily: ω̇ = 0.

    >>> free_euler_rates((1.0, 2.0, 3.0), (0.0, 5.0, 0.0))
    (0.0, 0.0, 0.0)
    """
    c = euler_coefficients(inertia)
    w1, w2, w3 = w
    return (c[0] * w2 * w3, c[1] * w3 * w1, c[2] * w1 * w2)


@jit
def euler_rates(inertia, w, tau):
    """ω̇ from Euler's equations: I ω̇ = (I ω) × ω + τ, principal frame, tuples in and out.

    τ/I is taken as τ·(1/I) (hoisted out of loops, ≤ 1 ulp more rounding).

    Examples
    --------
    The free rates of :func:`free_euler_rates` plus τ/I:

    >>> euler_rates((1.0, 2.0, 3.0), (1.0, 1.0, 1.0), (1.0, 2.0, 3.0))
    (0.0, 2.0, 0.6666666666666667)
    """
    g = free_euler_rates(inertia, w)
    c = euler_coefficients(inertia)
    return (g[0] + tau[0] * c[3], g[1] + tau[1] * c[4], g[2] + tau[2] * c[5])


# ------------------------------------------------------------ energy under gravity


@jit
def kinetic_energy(w, moments):
    """½ Σ Iₖ ωₖ² in the principal frame, summed as ``RigidBody.energy``'s einsum sums it
    (the run's energy columns and the summary's drift are the same numbers).

    Examples
    --------
    >>> kinetic_energy((1.0, 0.0, 2.0), (2.0, 1.0, 3.0))     # ½ (2·1² + 3·2²)
    7.0
    """
    return 0.5 * ((w[0] * moments[0] * w[0] + w[1] * moments[1] * w[1]) + w[2] * moments[2] * w[2])


@jit
def gravity_potential(q, r, weight):
    """−(q r q*)·(m g) for unit q: the lever r from the pivot to the centre of mass (body)
    turned into space, against the weight m g; summed as numpy's matrix-vector product
    sums it.

    Examples
    --------
    >>> gravity_potential((1.0, 0.0, 0.0, 0.0), (0.0, 0.0, 0.5), (0.0, 0.0, -9.81))  # m g l
    4.905
    """
    lever = qrotate(q, r)
    return -((lever[0] * weight[0] + lever[1] * weight[1]) + lever[2] * weight[2])
