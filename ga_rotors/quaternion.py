r"""Hamilton quaternions as float arrays of shape (..., 4): q = (w, x, y, z), scalar first.

Every function broadcasts over leading axes like a NumPy ufunc; a (4,) input gives a (4,)
output. Batches run in compiled loops over the scalar kernels of
:mod:`ga_rotors._kernels` (one formula each), which check finiteness, and unit norm where a
rotation is required, inside the loop. Addition and subtraction are NumPy's own ``+`` and
``-`` on the arrays.

Unit quaternions are required wherever a rotation is meant (``rotate``, ``angle``,
``slerp``, ...): inputs within :data:`~ga_rotors._validate.UNIT_TOLERANCE` (1e-6) of unit
norm are renormalised, others raise :class:`~ga_rotors.errors.InputError`.

Conventions (``docs/conventions.md``): Hamilton product (:math:`ij = k`, :math:`ijk = -1`),
active rotation :math:`v \mapsto q v q^*`, rotation angles
:math:`2 \operatorname{atan2}(|\vec q|, |w|) \in [0, \pi]`.

Examples
--------
>>> import numpy as np
>>> from ga_rotors import quaternion as Q
>>> q = Q.from_axis_angle([0, 0, 1], np.pi / 2)
>>> np.round(Q.rotate(q, [1.0, 0.0, 0.0]), 15) + 0.0
array([0., 1., 0.])
"""

from __future__ import annotations

import math

import numpy as np

from . import _kernels as K
from . import _quaternion_loops as L
from ._batch import Batch
from ._validate import UNIT_TOLERANCE, as_float_array
from .euler import from_quaternion as to_euler
from .euler import to_quaternion as from_euler
from .matrix import from_quaternion as to_matrix
from .matrix import to_quaternion as from_matrix

__all__ = [
    "angle",
    "axis",
    "conjugate",
    "distance",
    "divide",
    "exp",
    "from_axis_angle",
    "from_euler",
    "from_matrix",
    "from_rotation_vector",
    "from_two_vectors",
    "inverse",
    "latitude_longitude",
    "log",
    "multiply",
    "norm",
    "normalize",
    "rotate",
    "slerp",
    "to_axis_angle",
    "to_euler",
    "to_matrix",
    "to_rotation_vector",
]

_CONJ = np.array([1.0, -1.0, -1.0, -1.0])
_F64 = np.dtype(np.float64)


def _single(a, b, la: int, lb: int):
    """a and b as tuples of floats when both are single float64 arrays, else None.

    One quaternion at a time is dominated by per-call overhead, not arithmetic: this path
    calls one compiled scalar kernel on tuples instead of broadcasting into a batch loop.
    Any non-finite result falls through to the checked path, which then names the bad
    argument.
    """
    if (
        type(a) is np.ndarray
        and type(b) is np.ndarray
        and a.shape == (la,)
        and b.shape == (lb,)
        and a.dtype == _F64
        and b.dtype == _F64
    ):
        return tuple(a.tolist()), tuple(b.tolist())
    return None


def _finite_sum(r) -> bool:
    # inf - inf and nan propagate through the sum; an overflowing sum of finite values
    # only sends the call down the checked path, which is correct either way.
    return math.isfinite(sum(r))


# ---------------------------------------------------------------------------------------
# public API


def multiply(p, q) -> np.ndarray:
    r"""Hamilton product :math:`p \otimes q`, broadcast over leading axes.

    Composition of rotations: rotating by ``multiply(p, q)`` is rotating by q, then by p.

    Parameters
    ----------
    p, q : array_like, shape (..., 4)
        Quaternions (w, x, y, z), any norm.

    Returns
    -------
    ndarray, shape (...broadcast..., 4)

    Examples
    --------
    >>> i, j = [0, 1.0, 0, 0], [0, 0, 1.0, 0]
    >>> multiply(i, j)                       # ij = k
    array([0., 0., 0., 1.])
    >>> multiply(j, i)                       # ji = -k
    array([ 0.,  0.,  0., -1.])
    >>> multiply([[1.0, 0, 0, 0], i], j).shape
    (2, 4)
    """
    single = _single(p, q, 4, 4)
    if single is not None:
        r = K.qmul(*single)
        if _finite_sum(r):
            return np.array(r)
    b = Batch((p, "p", 4), (q, "q", 4))
    out = b.empty(4)
    b.fail(L.multiply_loop(b.flat[0], b.steps[0], b.flat[1], b.steps[1], out), out, what="product")
    return b.shaped(out)


def conjugate(q) -> np.ndarray:
    r"""The conjugate :math:`q^* = (w, -x, -y, -z)`.

    Examples
    --------
    >>> conjugate([1.0, 2.0, 3.0, 4.0])
    array([ 1., -2., -3., -4.])
    """
    return as_float_array(q, "q", last=4) * _CONJ


def norm(q) -> np.ndarray | float:
    r"""The norm :math:`|q| = \sqrt{w^2 + x^2 + y^2 + z^2}`, without overflow or underflow;
    shape (...).

    Examples
    --------
    >>> norm([1.0, 2.0, 2.0, 4.0])
    5.0
    >>> norm([[3e-300, 4e-300, 0, 0]])
    array([5.e-300])
    """
    b = Batch((q, "q", 4))
    out = b.empty()
    b.fail(L.norm_loop(b.flat[0], out), out, what="norm")
    r = b.shaped(out)
    return float(r) if r.ndim == 0 else r


def inverse(q) -> np.ndarray:
    r"""The inverse :math:`q^{-1} = q^* / |q|^2` (the notes print :math:`q^* / |q|`, which is
    wrong unless :math:`|q| = 1`).

    Raises
    ------
    InputError
        For q = 0, which has no inverse.

    Examples
    --------
    >>> inverse([0.0, 2.0, 0.0, 0.0])
    array([ 0. , -0.5, -0. , -0. ])
    >>> multiply([1.0, 2.0, 3.0, 4.0], inverse([1.0, 2.0, 3.0, 4.0])).round(15) + 0.0
    array([1., 0., 0., 0.])
    >>> inverse([0.0, 0.0, 0.0, 0.0])
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: q: expected nonzero values, got zero at index ()
    """
    b = Batch((q, "q", 4))
    out = b.empty(4)
    b.fail(L.inverse_loop(b.flat[0], out), out, nonzero=("q",), what="inverse")
    return b.shaped(out)


def divide(p, q) -> np.ndarray:
    """Right division p ⊗ q⁻¹, so that ``divide(multiply(p, q), q) == p``.

    Examples
    --------
    >>> p, q = [1.0, 2.0, 3.0, 4.0], [0.5, -0.5, 0.5, 0.5]
    >>> np.allclose(divide(multiply(p, q), q), p, rtol=0, atol=1e-15)
    True
    """
    b = Batch((p, "p", 4), (q, "q", 4))
    out = b.empty(4)
    ok = L.divide_loop(b.flat[0], b.steps[0], b.flat[1], b.steps[1], out)
    b.fail(ok, out, nonzero=("q",), what="quotient")
    return b.shaped(out)


def normalize(q) -> np.ndarray:
    """q / |q|; zero quaternions are rejected.

    Examples
    --------
    >>> normalize([0.0, 3.0, 0.0, 4.0])
    array([0. , 0.6, 0. , 0.8])
    """
    b = Batch((q, "q", 4))
    out = b.empty(4)
    b.fail(L.normalize_loop(b.flat[0], out), out, nonzero=("q",), what="normalised quaternion")
    return b.shaped(out)


def rotate(q, v) -> np.ndarray:
    r"""Rotate vectors actively: :math:`v \mapsto q v q^*` (body to space), shape
    (...broadcast..., 3).

    Parameters
    ----------
    q : array_like, shape (..., 4)
        Unit quaternions (within ``UNIT_TOLERANCE``; renormalised).
    v : array_like, shape (..., 3)

    Examples
    --------
    >>> q = from_axis_angle([0, 0, 1], np.pi / 2)      # a quarter-turn about z
    >>> np.round(rotate(q, [[1.0, 0, 0], [0, 1.0, 0]]), 15) + 0.0
    array([[ 0.,  1.,  0.],
           [-1.,  0.,  0.]])
    >>> rotate([2.0, 0, 0, 0], [1.0, 0, 0])
    Traceback (most recent call last):
    ...
    ga_rotors.errors.InputError: q: expected unit quaternions (| |q| - 1 | <= 1e-06), got norm 2 ...
    """
    single = _single(q, v, 4, 3)
    if single is not None:
        r = L.rotate_one(single[0], single[1], UNIT_TOLERANCE)
        if _finite_sum(r):
            return np.array(r)
    b = Batch((q, "q", 4), (v, "v", 3))
    out = b.empty(3)
    ok = L.rotate_loop(b.flat[0], b.steps[0], b.flat[1], b.steps[1], out, UNIT_TOLERANCE)
    b.fail(ok, out, unit=("q",), what="rotated vector")
    return b.shaped(out)


def _axis_angle(q) -> np.ndarray:
    b = Batch((q, "q", 4))
    out = b.empty(4)
    b.fail(L.axis_angle_loop(b.flat[0], out, UNIT_TOLERANCE), out, unit=("q",))
    return b.shaped(out)


def to_axis_angle(q) -> tuple[np.ndarray, np.ndarray | float]:
    r"""Unit axis (..., 3) and angle (...) ∈ [0, π] of the rotation q.

    The angle is :math:`2 \operatorname{atan2}(|\vec q|, |w|)`: full precision at every angle,
    where the notes' :math:`2 \arccos w` loses half the digits when |w| is near 1 (small
    rotations). q and -q give
    the same axis and angle.
    At angle 0 the axis is free and +z is returned (never NaN); at exactly π both ±u
    describe the rotation and q⃗/|q⃗| is returned.

    Examples
    --------
    >>> u, a = to_axis_angle(from_axis_angle([1.0, 0, 0], 0.25))
    >>> u, a
    (array([1., 0., 0.]), 0.25)
    >>> to_axis_angle([1.0, 0, 0, 0])
    (array([0., 0., 1.]), 0.0)
    """
    r = _axis_angle(q)
    a = r[..., 3]
    return r[..., :3], (float(a) if a.ndim == 0 else a)


def angle(q) -> np.ndarray | float:
    """Rotation angle ∈ [0, π] of unit q: 2·atan2(|q⃗|, |w|) (see :func:`to_axis_angle`).

    Examples
    --------
    >>> angle(from_axis_angle([0, 1.0, 0], 1e-12))
    1e-12
    >>> angle([-1.0, 0, 0, 0])       # -1 is the identity rotation
    0.0
    """
    return to_axis_angle(q)[1]


def axis(q) -> np.ndarray:
    """Unit rotation axis (..., 3) of unit q; +z at angle 0 (see :func:`to_axis_angle`).

    Examples
    --------
    >>> axis([0.0, 0.0, -1.0, 0.0])
    array([ 0., -1.,  0.])
    """
    return to_axis_angle(q)[0]


def latitude_longitude(q, degrees: bool = False) -> tuple[np.ndarray | float, np.ndarray | float]:
    r"""Latitude and longitude of the rotation axis of unit q (the notes' last formulas).

    :math:`\text{lat} = \operatorname{atan2}(u_z, \sqrt{u_x^2 + u_y^2}) \in [-\pi/2, \pi/2]`,
    :math:`\text{lon} = \operatorname{atan2}(u_y, u_x) \in (-\pi, \pi]`, with u
    from :func:`axis` (the axis of the rotation angle in [0, π], so q and -q agree). The
    notes' lon = atan(q₂/q₁) loses the quadrant (it maps axes x and -x to the same
    longitude); atan2 does not. At the poles (and at angle 0, where the axis is +z) the
    longitude is free and atan2 returns 0.

    Examples
    --------
    >>> latitude_longitude(from_axis_angle([-1.0, -1.0, 0.0], 0.5), degrees=True)
    (0.0, -135.0)
    >>> latitude_longitude([1.0, 0, 0, 0], degrees=True)
    (90.0, 0.0)
    """
    u = axis(q)
    lat = np.arctan2(u[..., 2], np.hypot(u[..., 0], u[..., 1]))
    lon = np.arctan2(u[..., 1], u[..., 0])
    if degrees:
        lat, lon = np.degrees(lat), np.degrees(lon)
    if lat.ndim == 0:
        return float(lat), float(lon)
    return lat, lon


def from_axis_angle(axis, angle, degrees: bool = False) -> np.ndarray:
    """Unit quaternion (cos(α/2), sin(α/2) u) of the rotation by α about axis u.

    Parameters
    ----------
    axis : array_like, shape (..., 3)
        Nonzero axes; normalised here.
    angle : array_like, shape (...)
        Any real angle (right-handed about the axis).
    degrees : bool
        Angles in degrees.

    Examples
    --------
    >>> from_axis_angle([0, 0, 2.0], 180, degrees=True)
    array([6.123234e-17, 0.000000e+00, 0.000000e+00, 1.000000e+00])
    >>> from_axis_angle([[1.0, 0, 0], [0, 1.0, 0]], [0.0, np.pi]).shape
    (2, 4)
    """
    if degrees:
        angle = np.radians(as_float_array(angle, "angle"))
    b = Batch((axis, "axis", 3), (angle, "angle", None))
    out = b.empty(4)
    ok = L.from_axis_angle_loop(b.flat[0], b.steps[0], b.flat[1], b.steps[1], out)
    b.fail(ok, out, nonzero=("axis",))
    return b.shaped(out)


def from_rotation_vector(r) -> np.ndarray:
    """Unit quaternion exp(r/2) of the rotation by |r| about r/|r| (exact at |r| = 0 and tiny).

    Examples
    --------
    >>> from_rotation_vector([0.0, 0.0, 1e-300])
    array([1.e+000, 0.e+000, 0.e+000, 5.e-301])
    """
    b = Batch((r, "r", 3))
    out = b.empty(4)
    b.fail(L.from_rotvec_loop(b.flat[0], out), out)
    return b.shaped(out)


def to_rotation_vector(q) -> np.ndarray:
    """Rotation vector (angle ∈ [0, π] times unit axis) of unit q; q and -q agree.

    Examples
    --------
    >>> to_rotation_vector(from_rotation_vector([0.1, -0.2, 0.3]))
    array([ 0.1, -0.2,  0.3])
    """
    b = Batch((q, "q", 4))
    out = b.empty(3)
    b.fail(L.to_rotvec_loop(b.flat[0], out, UNIT_TOLERANCE), out, unit=("q",))
    return b.shaped(out)


def exp(q) -> np.ndarray:
    """Quaternion exponential e^w (cos|v|, sin|v| v/|v|) of q = (w, v); exact at v = 0.

    For a pure quaternion (0, r/2) this is the unit quaternion of rotation vector r.

    Examples
    --------
    >>> exp([0.0, np.pi / 2, 0.0, 0.0]).round(15) + 0.0
    array([0., 1., 0., 0.])
    """
    b = Batch((q, "q", 4))
    out = b.empty(4)
    b.fail(L.exp_loop(b.flat[0], out), out, what="exponential")
    return b.shaped(out)


def log(q) -> np.ndarray:
    r"""Principal quaternion logarithm :math:`(\ln|q|, u \operatorname{atan2}(|v|, w))`, with the
    vector part's length in :math:`[0, \pi]`.

    Inverse of :func:`exp` on nonzero q. At negative real q the direction u is free and
    the z axis is chosen: log(-1) = (0, 0, 0, π).

    Examples
    --------
    >>> log([-1.0, 0.0, 0.0, 0.0])
    array([0.        , 0.        , 0.        , 3.14159265])
    >>> np.allclose(exp(log([1.0, 2.0, 3.0, 4.0])), [1.0, 2.0, 3.0, 4.0], rtol=1e-15)
    True
    """
    b = Batch((q, "q", 4))
    out = b.empty(4)
    b.fail(L.log_loop(b.flat[0], out), out, nonzero=("q",), what="logarithm")
    return b.shaped(out)


def slerp(q0, q1, t) -> np.ndarray:
    r"""Spherical linear interpolation :math:`q_0 \otimes \exp(t \log(q_0^* \otimes q_1))` along
    the shorter arc.

    Uses the exp/log kernels, so nearly equal rotations interpolate exactly (the textbook
    sin((1-t)Ω)/sin Ω weights divide 0 by 0 there). q1 and -q1 are the same rotation: the
    path is the shorter one between the rotations, so ``slerp(q, -q, t)`` is q for every t
    and the result lies on q0's side. Two rotations exactly π apart have two shortest
    paths; the one about the axis of q0* ⊗ q1 (as given) is taken. t outside [0, 1]
    extrapolates along the same geodesic.

    Examples
    --------
    >>> a, b = from_axis_angle([0, 0, 1.0], 0.0), from_axis_angle([0, 0, 1.0], 1.0)
    >>> angle(slerp(a, b, 0.25))
    0.25
    >>> slerp(a, -a, 0.5)
    array([1., 0., 0., 0.])
    """
    b = Batch((q0, "q0", 4), (q1, "q1", 4), (t, "t", None))
    out = b.empty(4)
    f, s = b.flat, b.steps
    ok = L.slerp_loop(f[0], s[0], f[1], s[1], f[2], s[2], out, UNIT_TOLERANCE)
    b.fail(ok, out, unit=("q0", "q1"))
    return b.shaped(out)


def distance(q0, q1) -> np.ndarray | float:
    r"""Geodesic angle ∈ [0, π] between the rotations q0 and q1 (the angle of
    :math:`q_0^* \otimes q_1`).

    :math:`2 \operatorname{atan2}(|\operatorname{vec}|, |\operatorname{scalar}|)`: resolves
    differences down to ~1e-16 rad, where 2·acos(·)
    cannot go below ~1e-8 rad. q and -q are at distance 0.

    Examples
    --------
    >>> a = from_axis_angle([1.0, 2.0, 3.0], 0.7)
    >>> distance(a, multiply(a, from_axis_angle([0, 1.0, 0], 1e-12)))
    1e-12
    >>> distance(a, -a)
    0.0
    """
    b = Batch((q0, "q0", 4), (q1, "q1", 4))
    out = b.empty()
    ok = L.distance_loop(b.flat[0], b.steps[0], b.flat[1], b.steps[1], out, UNIT_TOLERANCE)
    b.fail(ok, out, unit=("q0", "q1"))
    r = b.shaped(out)
    return float(r) if r.ndim == 0 else r


def from_two_vectors(u, v) -> np.ndarray:
    """The smallest rotation taking the direction of u onto the direction of v.

    Exact for parallel vectors (the identity) and antiparallel ones, where every axis
    ⊥ u gives a half-turn and the choice is documented: the axis is u × e_k, normalised,
    with e_k the coordinate axis least aligned with u (the first on ties), so x ↦ -x is
    the half-turn about z and z ↦ -z the half-turn about y. Nearly antiparallel vectors
    stay accurate: the axis is re-orthogonalised against u (see the kernel).

    Parameters
    ----------
    u, v : array_like, shape (..., 3)
        Nonzero vectors (any lengths).

    Examples
    --------
    >>> q = from_two_vectors([1.0, 0, 0], [0, 2.0, 0])
    >>> np.round(rotate(q, [1.0, 0, 0]), 15) + 0.0
    array([0., 1., 0.])
    >>> from_two_vectors([1.0, 0, 0], [-3.0, 0, 0])    # half-turn about z
    array([0., 0., 0., 1.])
    """
    b = Batch((u, "u", 3), (v, "v", 3))
    out = b.empty(4)
    b.fail(
        L.two_vectors_loop(b.flat[0], b.steps[0], b.flat[1], b.steps[1], out),
        out,
        nonzero=("u", "v"),
    )
    return b.shaped(out)
