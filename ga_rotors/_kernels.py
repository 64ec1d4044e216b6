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
    r"""Hamilton product :math:`a \otimes b` (:math:`ij = k`, :math:`ijk = -1`)."""
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
    r"""Conjugate :math:`(w, -x, -y, -z)`."""
    return (a[0], -a[1], -a[2], -a[3])


@jit
def qmul_pure(a, v):
    r""":math:`a \otimes (0, v)`: the product the kinematics
    :math:`\dot q = \tfrac12 q \otimes (0, \omega)` needs, without the zero terms."""
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
    r""":math:`\lvert (x, y, z) \rvert` without overflow or underflow (1e-300 and 1e300
    components stay exact)."""
    return hypot(hypot(x, y), z)


@jit
def norm2(x, y):
    r""":math:`\lvert (x, y) \rvert` as :func:`qnorm` takes a norm: the plain square root of
    the sum of squares
    whenever that sum is a normal number, ``hypot`` only where it under- or overflows
    (within an ulp of ``hypot``, which costs about 12 ns a call here against 2)."""
    s = x * x + y * y
    if 1e-290 < s < 1e290:
        return sqrt(s)
    return hypot(x, y)


@jit
def qnorm(a):
    r""":math:`\lvert a \rvert`, exact for components from 1e-300 to 1e300.

    The plain square root is used whenever the sum of squares is a normal number, which
    is every practical case; the scaled path only runs when it under- or overflows.
    """
    s = a[0] * a[0] + a[1] * a[1] + a[2] * a[2] + a[3] * a[3]
    if 1e-290 < s < 1e290:
        return sqrt(s)
    return hypot(hypot(a[0], a[1]), hypot(a[2], a[3]))


@jit
def qnormalize(a):
    r""":math:`a / \lvert a \rvert`; all-NaN for :math:`a = 0` (the caller's finiteness check
    reports it).

    Zero is tested explicitly because uncompiled Python raises on division by zero where
    compiled code returns nan; kernels must behave the same both ways.
    """
    n = qnorm(a)
    if n == 0.0:
        return (nan, nan, nan, nan)
    return (a[0] / n, a[1] / n, a[2] / n, a[3] / n)


@jit
def cross(u, v):
    r""":math:`u \times v`."""
    return (
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    )


@jit
def qrotate(q, v):
    r""":math:`q\, (0, v)\, q^*` for unit :math:`q`, in 15 multiplications instead of two
    full products.

    With :math:`t = 2\, \vec q \times v`: :math:`q v q^* = v + w t + \vec q \times t`.
    """
    w = q[0]
    u = (q[1], q[2], q[3])
    c = cross(u, v)
    t = (2.0 * c[0], 2.0 * c[1], 2.0 * c[2])
    d = cross(u, t)
    return (v[0] + w * t[0] + d[0], v[1] + w * t[1] + d[1], v[2] + w * t[2] + d[2])


@jit
def qexp_pure(v):
    r""":math:`\exp((0, v)) = \bigl(\cos\lvert v \rvert,\ v \sin\lvert v \rvert / \lvert v
    \rvert\bigr)`: the unit quaternion of half-angle :math:`\lvert v \rvert`.

    Exact for every :math:`\lvert v \rvert` that is representable: the robust norm keeps
    1e-300 from underflowing, so :math:`\sin(s)/s` is only special-cased at exactly zero.
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
    r""":math:`\exp((0, v)) - 1 = \bigl(-2 \sin^2(\lvert v \rvert/2),\ v \sin\lvert v \rvert
    / \lvert v \rvert\bigr)`, every component to a few ulps.

    The scalar part :math:`\cos\lvert v \rvert - 1` is written
    :math:`-2 \sin^2(\lvert v \rvert / 2)`, so it keeps its relative precision at small
    angles where :math:`1 - \cos\lvert v \rvert` cancels (the expm1 of rotations). Used by
    :func:`qmul_exp`. Exact at 0 (returns :math:`(0, v)`); NaN for infinite :math:`v`, as
    :func:`qexp_pure`.
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
    r""":math:`q \otimes \exp((0, v))`, as :math:`q + q \otimes (\exp((0, v)) - 1)`: a step
    along a rotation of half-angle :math:`\lvert v \rvert`.

    Why not ``qmul(q, qexp_pure(v))``: over a run that turns by nearly the same angle every
    step (a body spinning steadily, split_sym's symmetric-top flow at its constant
    :math:`\lvert L \rvert`), :math:`\cos\lvert v \rvert` rounds to the SAME float every
    step, so :math:`\lvert \exp \rvert = 1 + \delta` with one fixed :math:`\delta \le u/2`
    and :math:`\lvert q \rvert` drifts linearly, :math:`(1 + \delta)^N` (split_sym: 2e-11 in
    :math:`10^6` steps). No formula for :math:`\exp((0, v))` avoids it: floats near 1 are
    spaced :math:`u`, so the scalar part must carry a rounding of up to :math:`u/2`, and
    forcing :math:`\lvert \exp \rvert = 1` (renormalising, or sin from
    :math:`\sqrt{1 - \cos^2}`) either cannot move it or turns the angle by
    :math:`u / (2 \lvert v \rvert)` instead (both measured). Here the increment
    :math:`q \otimes (\exp - 1)` is accurate to relative rounding
    (:math:`\lvert \exp - 1 \rvert \sim \lvert v \rvert`, so its rounding is
    :math:`u \lvert v \rvert`), and the one rounding that matters, of the sum
    :math:`q + \text{increment}`, falls on :math:`q`'s components, which change from step
    to step: a random walk, not a drift.
    """
    d = qexpm1_pure(v)
    p = qmul(q, d)
    return (q[0] + p[0], q[1] + p[1], q[2] + p[2], q[3] + p[3])


@jit
def qlog_unit(q):
    r"""Vector part of :math:`\log q` for unit :math:`q`: :math:`u \phi` with
    :math:`q = (\cos\phi, u \sin\phi)`,
    :math:`\phi = \operatorname{atan2}(\lvert \vec q \rvert, w) \in [0, \pi]`.

    atan2 keeps full relative precision at every angle, where :math:`\arccos w` loses half
    the digits near 0 and :math:`\pi`. At :math:`q = -1` the axis is free; the z axis is
    chosen (documented).
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
    r"""Unit quaternion of the rotation by :math:`\lvert r \rvert` about
    :math:`r / \lvert r \rvert` (active, right-handed)."""
    return qexp_pure((0.5 * r[0], 0.5 * r[1], 0.5 * r[2]))


@jit
def rotvec_from_quat(q):
    r"""Rotation vector of unit :math:`q`, angle in :math:`[0, \pi]` (:math:`q` and
    :math:`-q` give the same answer)."""
    if q[0] < 0.0:
        q = (-q[0], -q[1], -q[2], -q[3])
    h = qlog_unit(q)
    return (2.0 * h[0], 2.0 * h[1], 2.0 * h[2])


@jit
def geodesic_angle(a, b):
    r"""Rotation angle of :math:`a^* \otimes b` in :math:`[0, \pi]`: the geodesic distance
    between two rotations.

    :math:`2 \operatorname{atan2}(\lvert \text{vector} \rvert, \lvert \text{scalar} \rvert)`
    resolves differences down to 1e-16 rad; :math:`2 \arccos(\cdot)` cannot go below
    ~1e-8 rad.
    """
    d = qmul(qconj(a), b)
    return 2.0 * atan2(hypot3(d[1], d[2], d[3]), abs(d[0]))


@jit
def angle_any_norm(a, b):
    r""":func:`geodesic_angle` of :math:`a` and :math:`b` whatever their norms; NaN unless
    both are finite and nonzero.

    :math:`2 \operatorname{atan2}(\lvert \vec d \rvert, \lvert d_0 \rvert)` of
    :math:`d = a^* \otimes b` does not depend on the norms (:math:`d` scales with them): a
    state whose norm drifted (RK4 over a long or fast run) still has its angle.
    :math:`\lvert \vec d \rvert` is :func:`qnorm`'s (a square root of the sum of squares,
    scaled only where that under- or overflows) rather than two ``hypot`` calls: within an
    ulp, and 7x faster in a loop over samples.
    """
    d = qmul(qconj(a), b)
    v, s = qnorm((0.0, d[1], d[2], d[3])), abs(d[0])
    return 2.0 * atan2(v, s) if 0.0 < v + s < inf else nan


@jit
def qinverse(a):
    r""":math:`a^{-1} = a^* / \lvert a \rvert^2`, divided twice by :math:`\lvert a \rvert` so
    that :math:`\lvert a \rvert` down to 1e-300 does not underflow.

    :math:`a = 0` gives all-NaN, which the loops detect and report.
    """
    n = qnorm(a)
    if n == 0.0:
        return (nan, nan, nan, nan)
    return (a[0] / n / n, -a[1] / n / n, -a[2] / n / n, -a[3] / n / n)


@jit
def qunit(a, tol):
    r""":math:`a / \lvert a \rvert` when :math:`\lvert a \rvert` is within ``tol`` of 1, else
    all-NaN (so a loop's finiteness check flags it).

    NaN and infinite components also give NaN: their norm fails the comparison.
    """
    n = qnorm(a)
    if not abs(n - 1.0) <= tol:
        return (nan, nan, nan, nan)
    return (a[0] / n, a[1] / n, a[2] / n, a[3] / n)


@jit
def qexp(a):
    r""":math:`\exp a = e^w \bigl(\cos\lvert v \rvert,\ v \sin\lvert v \rvert / \lvert v
    \rvert\bigr)` for a general quaternion :math:`a = (w, v)`."""
    # e^w overflows above ln(DBL_MAX); inf is written out because Python's math.exp raises
    # there, and the kernels must behave alike compiled and uncompiled.
    e = inf if a[0] > 709.782712893384 else exp(a[0])
    p = qexp_pure((a[1], a[2], a[3]))
    return (e * p[0], e * p[1], e * p[2], e * p[3])


@jit
def qlog(a):
    r""":math:`\log a = \bigl(\ln\lvert a \rvert,\ u \operatorname{atan2}(\lvert v \rvert,
    w)\bigr)` for nonzero :math:`a = (w, v)`, :math:`u = v / \lvert v \rvert`; at negative
    reals :math:`u` is the z axis."""
    n = qnorm(a)
    if n == 0.0:
        return (-inf, nan, nan, nan)
    h = qlog_unit((a[0] / n, a[1] / n, a[2] / n, a[3] / n))
    return (log(n), h[0], h[1], h[2])


@jit
def axis_angle_from_quat(q):
    r""":math:`(u_x, u_y, u_z, \alpha)` of unit :math:`q` with
    :math:`\alpha = 2 \operatorname{atan2}(\lvert \vec q \rvert, \lvert w \rvert) \in [0, \pi]`.

    :math:`q` and :math:`-q` give the same answer (the axis flips with the sign of
    :math:`w`). At :math:`\alpha = 0` the axis is free; :math:`+z` is returned, never NaN.
    At :math:`\alpha = \pi` (:math:`w = 0`) both :math:`\pm u` are valid;
    :math:`\vec q / \lvert \vec q \rvert` is returned.
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
    r"""Unit quaternion of the rotation by ``angle`` about :math:`u / \lvert u \rvert`
    (:math:`u \ne 0`; any real angle)."""
    n = hypot3(u[0], u[1], u[2])
    if n == 0.0:
        return (nan, nan, nan, nan)
    return quat_from_rotvec((angle * (u[0] / n), angle * (u[1] / n), angle * (u[2] / n)))


@jit
def qslerp(a, b, t):
    r""":math:`a \otimes \exp\bigl(t \log(a^* \otimes b)\bigr)` along the shorter arc of
    rotations (unit :math:`a, b`).

    Written with the exp/log kernels, which are exact at tiny angles, instead of the
    :math:`\sin((1 - t)\Omega) / \sin\Omega` weights, which divide 0 by 0 when
    :math:`a \approx b`. If :math:`a^* b` has :math:`w < 0` it is negated first (:math:`b`
    and :math:`-b` are the same rotation), so :math:`\operatorname{slerp}(q, -q, t) = q` for
    every :math:`t`.
    """
    d = qmul(qconj(a), b)
    if d[0] < 0.0:
        d = (-d[0], -d[1], -d[2], -d[3])
    h = qlog_unit(d)
    return qmul(a, qexp_pure((t * h[0], t * h[1], t * h[2])))


#: :math:`\lvert \hat u \times \hat v \rvert` at or below this counts as exactly
#: (anti)parallel: normalising exactly parallel vectors rounds each component by up to
#: ~2 ulp, which leaves a cross product of a few 1e-16; 1e-15 covers that with margin, and
#: the rotation returned then maps :math:`\hat u` onto :math:`\hat v` to within the same
#: 1e-15.
PARALLEL_TOLERANCE = 1e-15


@jit
def perpendicular(u):
    r"""A unit vector :math:`\perp` unit :math:`u`: :math:`u \times e_k` with :math:`e_k` the
    coordinate axis least aligned with :math:`u` (the first such axis on ties), normalised.
    For :math:`u = \pm x` that is :math:`\pm z`; for :math:`u = \pm z` it is :math:`\pm y`."""
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
    r"""Unit quaternion of the smallest rotation taking the direction of :math:`u` onto that
    of :math:`v`.

    Angle :math:`\operatorname{atan2}(\lvert \hat u \times \hat v \rvert, \hat u \cdot \hat v)`
    (accurate at 0 and :math:`\pi`), axis :math:`\hat u \times \hat v` re-orthogonalised
    against :math:`\hat u`: near antiparallel vectors the cross product has a relative error
    of :math:`\sim 10^{-16} / \sin(\text{angle})`, and an axis that is not exactly
    :math:`\perp \hat u` would move :math:`\hat u` off :math:`\hat v` by that much; after the
    projection the error in the image of :math:`\hat u` stays at round-off. Parallel: the
    identity. Antiparallel: the half-turn about :func:`perpendicular` (:math:`\hat u`).
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
    r"""Rotation matrix of unit :math:`q`, row-major 9-tuple: :math:`M v = q v q^*`
    (active)."""
    w, x, y, z = q
    return (
        1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y - w * z), 2.0 * (x * z + w * y),
        2.0 * (x * y + w * z), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z - w * x),
        2.0 * (x * z - w * y), 2.0 * (y * z + w * x), 1.0 - 2.0 * (x * x + y * y),
    )  # fmt: skip


@jit
def quat_from_matrix(m):
    r"""Unit quaternion (:math:`w \ge 0`) of a rotation matrix given as a row-major 9-tuple.

    From

    .. math::

        M = \begin{pmatrix}
        w^2 + x^2 - y^2 - z^2 & 2(xy - wz) & 2(xz + wy) \\
        2(xy + wz) & w^2 - x^2 + y^2 - z^2 & 2(yz - wx) \\
        2(xz - wy) & 2(yz + wx) & w^2 - x^2 - y^2 + z^2
        \end{pmatrix}:

    :math:`4w^2 = 1 + \operatorname{tr} M`, :math:`4x^2 = 1 + m_{00} - m_{11} - m_{22}` (and
    cyclic), and the off-diagonal sums and differences give :math:`4wx, 4xy, \ldots`. The
    component whose square is largest (the largest of :math:`\operatorname{tr} M, m_{00},
    m_{11}, m_{22}`) is at least :math:`1/2`, so it is taken from its square root and the
    others are divided by it: no division by a small number anywhere, exact at half-turns
    where :math:`w = 0` (the notes' division by :math:`4w` fails).
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
    r""":math:`q_i(a) \otimes q_j(b) \otimes q_k(c)`: intrinsic rotations about axes
    :math:`i`, then :math:`j'`, then :math:`k''`."""
    return qmul(qmul(axis_quat(i, a), axis_quat(j, b)), axis_quat(k, c))


@jit
def wrap_angle(x):
    r""":math:`x \in (-2\pi, 2\pi]` mapped to :math:`(-\pi, \pi]` by one exact shift of
    :math:`2\pi`."""
    if x > pi:
        return x - 2.0 * pi
    if x <= -pi:
        return x + 2.0 * pi
    return x


@jit
def euler_from_quat(q, i, j, k, zero_first, tol):
    r"""Intrinsic angles (a, b, c, locked) with
    :math:`q = \pm q_i(a) \otimes q_j(b) \otimes q_k(c)`, :math:`q` unit.

    With half angles :math:`a' = a/2` (and so on), :math:`e_i e_j = \varepsilon e_m`
    (:math:`\varepsilon = \pm 1`, the parity of the axis order):

    * proper (:math:`i = k`, :math:`m` the third axis):
      :math:`(w, q_i) = \cos b' \bigl(\cos(a' + c'), \sin(a' + c')\bigr)` and
      :math:`(q_j, \varepsilon q_m) = \sin b' \bigl(\cos(a' - c'), \sin(a' - c')\bigr)`, so
      :math:`b = 2 \operatorname{atan2}\bigl(\lvert (q_j, q_m) \rvert, \lvert (w, q_i) \rvert\bigr)
      \in [0, \pi]`;
    * Tait–Bryan (:math:`i, j, k` distinct):
      :math:`(w + q_j, q_i + \varepsilon q_k) = (\cos b' + \sin b')
      \bigl(\cos(a' + \varepsilon c'), \sin(a' + \varepsilon c')\bigr)` and
      :math:`(w - q_j, q_i - \varepsilon q_k) = (\cos b' - \sin b')
      \bigl(\cos(a' - \varepsilon c'), \sin(a' - \varepsilon c')\bigr)`;
      :math:`\sin b = 2(w q_j + \varepsilon q_i q_k)`, :math:`\cos b` the product of the two
      moduli, :math:`b \in [-\pi/2, \pi/2]`.

    Both sum and difference come from atan2 (quadrant-correct, no division), :math:`a` and
    :math:`c` in :math:`(-\pi, \pi]`. Gimbal lock: when :math:`b` is within ``tol`` of the
    value where one of the two pairs vanishes, only one combination of :math:`a` and
    :math:`c` is defined; the third angle of the sequence as written is set to 0
    (``zero_first`` says that is :math:`a`, which is the case for extrinsic sequences
    computed through their reversed intrinsic twin) and ``locked`` is 1.0. Forcing it moves
    the rotation by at most twice ``tol`` (a commutator of a rotation by ``tol``).
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
    r""":math:`(\dot\psi, \dot\theta, \dot\phi)` from ZYZ angles :math:`(\psi, \theta, \phi)`
    and body :math:`\omega`; divides by :math:`\sin\theta` (caller's care).

    The checked, vectorised form is :func:`ga_rotors.kinematics.zyz_rates_from_body_omega`.

    Examples
    --------
    A spin about the body axis only turns :math:`\phi`:

    >>> zyz_rates((0.1, 0.5, 0.3), (0.0, 0.0, 10.0))
    (0.0, 0.0, 10.0)

    The inverse of :func:`zyz_omega` wherever :math:`\sin\theta \ne 0`:

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
    r"""Body :math:`\omega` from ZYZ angles :math:`(\psi, \theta, \phi)` and their rates
    :math:`(\dot\psi, \dot\theta, \dot\phi)`; regular everywhere.

    The checked, vectorised form is :func:`ga_rotors.kinematics.body_omega_from_zyz_rates`.

    Examples
    --------
    Precession :math:`\dot\psi` at nutation :math:`\theta = 90^\circ`, :math:`\phi = 0`,
    seen in the body: about :math:`-x`.

    >>> import math
    >>> [round(c, 12) for c in zyz_omega((0.0, math.pi / 2, 0.0), (2.0, 0.0, 0.0))]
    [-2.0, 0.0, 0.0]

    At :math:`\theta = 0` it is still defined (:math:`\dot\psi` and :math:`\dot\phi` add
    up):

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
    r"""What Euler's equations divide by:
    :math:`\bigl((I_2 - I_3)/I_1, (I_3 - I_1)/I_2, (I_1 - I_2)/I_3\bigr)` and
    :math:`(1/I_1, 1/I_2, 1/I_3)`, from the principal moments.

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
    r""":math:`\dot\omega` of the torque-free body:
    :math:`\mathsf{I} \dot\omega = (\mathsf{I} \omega) \times \omega`, principal frame, tuples
    in and out.

    Unchecked (compiled loops call it); the checked form is
    :meth:`ga_rotors.body.RigidBody.angular_acceleration`.

    Written :math:`\bigl((I_2 - I_3)/I_1\bigr)\, \omega_2 \omega_3` so the inertia ratios
    (:func:`euler_coefficients`)
    depend on loop invariants only: a compiled loop computes them once instead of
    dividing in every stage.

    Examples
    --------
    >>> free_euler_rates((1.0, 2.0, 3.0), (1.0, 1.0, 1.0))  # ((2-3)/1, (3-1)/2, (1-2)/3)
    (-1.0, 1.0, -0.3333333333333333)

    About a principal axis the body spins steadily: :math:`\dot\omega = 0`.

    >>> free_euler_rates((1.0, 2.0, 3.0), (0.0, 5.0, 0.0))
    (0.0, 0.0, 0.0)
    """
    c = euler_coefficients(inertia)
    w1, w2, w3 = w
    return (c[0] * w2 * w3, c[1] * w3 * w1, c[2] * w1 * w2)


@jit
def euler_rates(inertia, w, tau):
    r""":math:`\dot\omega` from Euler's equations:
    :math:`\mathsf{I} \dot\omega = (\mathsf{I} \omega) \times \omega + \tau`, principal
    frame, tuples in and out.

    :math:`\tau / I` is taken as :math:`\tau \cdot (1/I)` (hoisted out of loops, at most
    1 ulp more rounding).

    Examples
    --------
    The free rates of :func:`free_euler_rates` plus :math:`\tau / I`:

    >>> euler_rates((1.0, 2.0, 3.0), (1.0, 1.0, 1.0), (1.0, 2.0, 3.0))
    (0.0, 2.0, 0.6666666666666667)
    """
    g = free_euler_rates(inertia, w)
    c = euler_coefficients(inertia)
    return (g[0] + tau[0] * c[3], g[1] + tau[1] * c[4], g[2] + tau[2] * c[5])


# ------------------------------------------------------------ energy under gravity


@jit
def kinetic_energy(w, moments):
    r""":math:`\tfrac12 \sum_k I_k \omega_k^2` in the principal frame, summed as
    ``RigidBody.energy``'s einsum sums it
    (the run's energy columns and the summary's drift are the same numbers).

    Examples
    --------
    >>> kinetic_energy((1.0, 0.0, 2.0), (2.0, 1.0, 3.0))     # ½ (2·1² + 3·2²)
    7.0
    """
    return 0.5 * ((w[0] * moments[0] * w[0] + w[1] * moments[1] * w[1]) + w[2] * moments[2] * w[2])


@jit
def gravity_potential(q, r, weight):
    r""":math:`-(q r q^*) \cdot (m g)` for unit :math:`q`: the lever :math:`r` from the pivot
    to the centre of mass (body) turned into space, against the weight :math:`m g`; summed
    as numpy's matrix-vector product sums it.

    Examples
    --------
    >>> gravity_potential((1.0, 0.0, 0.0, 0.0), (0.0, 0.0, 0.5), (0.0, 0.0, -9.81))  # m g l
    4.905
    """
    lever = qrotate(q, r)
    return -((lever[0] * weight[0] + lever[1] * weight[1]) + lever[2] * weight[2])
