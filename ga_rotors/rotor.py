r"""Rotors in Cl(3,0) as ``clifford`` multivectors: build, convert, compose, apply.

A rotor is an even multivector :math:`R = w - x e_{23} - y e_{31} - z e_{12}` with
:math:`R \tilde R = 1` that rotates vectors by :math:`v \mapsto R v \tilde R`
(:mod:`ga_rotors.isomorphism` gives the map to quaternions). The rotor of the rotation by
:math:`\alpha` about the unit axis :math:`u` is

.. math::

    R = \exp\left(-I u \frac{\alpha}{2}\right) = \cos\frac{\alpha}{2} - I u \sin\frac{\alpha}{2}.

clifford's ``Cl(3)`` layout is created once, on first use (importing clifford takes about
a second), so ``import ga_rotors`` and ``import ga_rotors.rotor`` stay light.

Products and reverses are the geometric product of the even subalgebra
(:mod:`ga_rotors._rotor_kernels`, generated from clifford's multiplication table); the
other formulas (sandwich, exp, log, angles, conversions) are the shared kernels of
:mod:`ga_rotors._kernels`, reached through the isomorphism: exp and log are exact at
angle 0, at tiny angles (1e-300 ... 1e-9), at exactly π and π − 1e-12, and at R = ±1,
where clifford's own ``log_rotor`` fails. One rotor at a time, the kernels run
uncompiled (:func:`ga_rotors._jit.plain`) and the results are built as MultiVectors from
their coefficients, so no function here calls clifford's products: those are compiled
by numba, without a cache, the first time a process uses them (seconds). ``R * S`` on the
returned MultiVectors is still clifford's product and pays that once per process.

Inputs: rotors must be even (odd part, grades 1 and 3, at most UNIT_TOLERANCE) and of
unit norm within UNIT_TOLERANCE (then renormalised); otherwise :class:`InputError`.

Examples
--------
>>> import numpy as np
>>> from ga_rotors import rotor
>>> R = rotor.from_axis_angle([0, 0, 1], np.pi / 2)
>>> np.round(rotor.apply(R, [1.0, 0.0, 0.0]), 15) + 0.0
array([0., 1., 0.])
"""

from __future__ import annotations

import functools
import math

import numpy as np

from . import _kernels as K
from . import _rotor_kernels as RK
from . import euler as _euler
from . import matrix as _matrix
from . import quaternion as _quaternion
from ._jit import plain
from ._validate import UNIT_TOLERANCE, as_float_array, require_unit
from .errors import InputError
from .isomorphism import ISOMORPHISM, from_even, to_even

__all__ = [
    "apply",
    "compose",
    "distance",
    "exp",
    "from_axis_angle",
    "from_euler",
    "from_matrix",
    "from_quaternion",
    "from_rotation_vector",
    "from_two_vectors",
    "inverse",
    "layout",
    "log",
    "normalize",
    "slerp",
    "to_axis_angle",
    "to_euler",
    "to_matrix",
    "to_quaternion",
    "to_rotation_vector",
]

_VECTOR = (1, 2, 3)  # e1, e2, e3 in clifford's blade order
_BIVECTOR = (4, 5, 6)  # e12, e13, e23
_EVEN = [0, 4, 5, 6]  # 1, e12, e13, e23: the order of _rotor_kernels' 4-tuples

# The kernels this module calls, one rotor at a time, uncompiled (see the module docstring).
_rmul, _rrev = plain(RK.rmul), plain(RK.rrev)
_rotor_from_quat = plain(RK.rotor_from_quat)
_qrotate, _qunit, _qnormalize = plain(K.qrotate), plain(K.qunit), plain(K.qnormalize)
_qexp_pure, _qlog_unit, _qslerp = plain(K.qexp_pure), plain(K.qlog_unit), plain(K.qslerp)
_geodesic_angle, _axis_angle = plain(K.geodesic_angle), plain(K.axis_angle_from_quat)
_from_axis_angle, _from_rotvec = plain(K.quat_from_axis_angle), plain(K.quat_from_rotvec)
_to_rotvec, _from_two_vectors = plain(K.rotvec_from_quat), plain(K.quat_from_two_vectors)
_matrix_from_quat = plain(K.matrix_from_quat)


@functools.cache
def layout():
    """clifford's ``Cl(3)`` layout, created on first call and shared.

    Examples
    --------
    >>> layout().names
    ['', 'e1', 'e2', 'e3', 'e12', 'e13', 'e23', 'e123']
    """
    from clifford import Cl

    return Cl(3)[0]


def _multivector(coefficients):
    from clifford import MultiVector

    return MultiVector(layout(), np.asarray(coefficients, dtype=np.float64))


def _coefficients(x, name: str) -> np.ndarray:
    from clifford import MultiVector

    if not isinstance(x, MultiVector):
        raise InputError(
            f"{name}: expected a clifford MultiVector of Cl(3), got {type(x).__name__}"
        )
    if x.layout != layout():
        raise InputError(
            f"{name}: expected a multivector of Cl(3) (blades {layout().names}), got {x.layout}"
        )
    return as_float_array(x.value, name)


def _quaternion_of(R, name: str = "R", unit: bool = True) -> np.ndarray:
    q = from_even(_coefficients(R, name), name=name)
    return require_unit(q, name, what="rotors") if unit else q


def _unit(R, name: str = "R") -> tuple[float, float, float, float]:
    """The unit quaternion of rotor R as a tuple, validated and renormalised.

    One rotor at a time, NumPy's per-call overhead dominates, so the common case (finite,
    exactly even, norm within tolerance) is accepted with scalar math through the same
    coefficient table; anything else goes through :func:`_quaternion_of`, which raises
    the precise error.
    """
    c = _coefficients(R, name).tolist()
    if math.isfinite(sum(c)) and c[1] == c[2] == c[3] == c[7] == 0.0:
        q = [0.0] * 4
        for component, blade, sign in ISOMORPHISM:
            q[component] = sign * c[blade]
        n = math.hypot(*q)
        if abs(n - 1.0) <= UNIT_TOLERANCE:
            return (q[0] / n, q[1] / n, q[2] / n, q[3] / n)
    return tuple(_quaternion_of(R, name).tolist())


def _rotor(q):
    """The rotor of a unit quaternion (4 floats), without validation."""
    c = np.zeros(8)
    for component, blade, sign in ISOMORPHISM:
        c[blade] = sign * q[component]
    return _multivector(c)


def _even(a):
    """The MultiVector of even coefficients (1, e12, e13, e23), without validation."""
    c = np.zeros(8)
    c[_EVEN] = a
    return _multivector(c)


def _finite(values) -> bool:
    # One sum instead of a test per value: NaN and inf propagate through it, and a sum
    # that overflows from finite values only sends the call down the checked path.
    return math.isfinite(sum(values))


def _vector3(x):
    """x as 3 finite floats when it is one plain vector, else None (the checked path)."""
    if type(x) in (list, tuple) and len(x) == 3:
        items = x
    elif isinstance(x, np.ndarray) and x.shape == (3,) and x.dtype.kind in "fiu":
        items = x.tolist()
    else:
        return None
    if not all(type(v) in (float, int) for v in items):
        return None
    try:
        v = (float(items[0]), float(items[1]), float(items[2]))
    except OverflowError:  # an int beyond float64: the checked slow path refuses it
        return None
    return v if _finite(v) else None


def _number(x):
    """x as a finite float when it is one plain real number, else None."""
    if type(x) in (float, int) or (isinstance(x, np.generic) and x.dtype.kind in "fiu"):
        try:
            x = float(x)
        except OverflowError:  # an int beyond float64: the checked slow path refuses it
            return None
        return x if math.isfinite(x) else None
    return None


def from_quaternion(q):
    """The rotor of unit quaternion q: w − x e23 − y e31 − z e12.

    Examples
    --------
    >>> from_quaternion([0.0, 0.0, 0.0, 1.0])     # k ↦ −e12
    -(1.0^e12)
    """
    q = as_float_array(q, "q", last=4)
    if q.shape != (4,):
        raise InputError(f"q: expected one quaternion of shape (4,), got shape {q.shape}")
    return _multivector(to_even(require_unit(q, "q")))


def to_quaternion(R) -> np.ndarray:
    """The unit quaternion (4,) of rotor R (inverse of :func:`from_quaternion`).

    Examples
    --------
    >>> R = from_axis_angle([1.0, 0, 0], np.pi)
    >>> np.round(to_quaternion(R), 15) + 0.0
    array([0., 1., 0., 0.])
    """
    return np.array(_unit(R))


def normalize(R):
    r"""R / |R| for an even multivector R ≠ 0, with :math:`|R|^2 = \langle R \tilde R \rangle_0`.

    Examples
    --------
    >>> normalize(2.0 + 0.0 * layout().blades["e12"])
    1.0
    """
    q = _quaternion_of(R, unit=False)
    if not q.any():
        raise InputError("R: expected nonzero values (an even multivector), got 0")
    n = _qnormalize(tuple(q.tolist()))
    if not _finite(n):  # only through an overflowing norm; the checked path says why
        return _multivector(to_even(_quaternion.normalize(q)))
    return _rotor(n)


def compose(*rotors):
    """The product R₁ R₂ ⋯ Rₙ: apply Rₙ first, R₁ last (like quaternion products).

    Examples
    --------
    >>> a = from_axis_angle([0, 0, 1.0], 0.3)
    >>> b = from_axis_angle([0, 0, 1.0], 0.4)
    >>> round(to_axis_angle(compose(a, b))[1], 15)
    0.7
    """
    if not rotors:
        raise InputError("rotors: expected at least one rotor")
    out = None
    for n, R in enumerate(rotors):
        a = _rotor_from_quat(_unit(R, f"rotors[{n}]"))
        out = a if out is None else _rmul(out, a)
    return _even(out)


def inverse(R):
    r"""The inverse :math:`R^{-1} = \tilde R` (the reverse) of a unit rotor.

    Examples
    --------
    >>> R = from_axis_angle([0, 1.0, 0], 0.5)
    >>> float((R * inverse(R))[()])
    1.0
    """
    return _even(_rrev(_rotor_from_quat(_unit(R))))


def apply(R, v):
    r"""Rotate vectors actively: :math:`v \mapsto R v \tilde R`.

    Parameters
    ----------
    R : MultiVector
        A unit rotor.
    v : MultiVector (grade 1) or array_like, shape (3,)
        Returned in the same form.

    Examples
    --------
    >>> e1 = layout().blades["e1"]
    >>> apply(from_axis_angle([0, 0, 1.0], np.pi / 2), e1)(1).clean(1e-15)
    (1.0^e2)
    """
    from clifford import MultiVector

    q = _unit(R)
    if isinstance(v, MultiVector):
        c = _coefficients(v, "v")
        if np.any(np.delete(c, _VECTOR) != 0):
            raise InputError("v: expected a vector (grade 1 only)")
        out = np.zeros(8)
        out[list(_VECTOR)] = _rotate(q, tuple(c[list(_VECTOR)].tolist()))
        return _multivector(out)
    fast = _vector3(v)
    if fast is None:
        v = as_float_array(v, "v", last=3)
        if v.shape != (3,):
            raise InputError(f"v: expected one vector of shape (3,), got shape {v.shape}")
        fast = tuple(v.tolist())
    return np.array(_rotate(q, fast))


def _rotate(q, v):
    """q v q* for a unit quaternion and finite v, also when |v| is near the largest float."""
    r = _qrotate(q, v)
    if _finite(r):
        return r
    # The kernel's t = 2 q⃗ × v can overflow where the result does not; rotating is linear
    # and scaling by a power of two is exact, so rotate v / 2^e and scale back.
    e = math.frexp(max(abs(x) for x in v))[1]
    try:
        return tuple(math.ldexp(x, e) for x in _qrotate(q, tuple(math.ldexp(x, -e) for x in v)))
    except OverflowError:
        raise InputError("rotated vector is not finite (overflow of float64)", key="v") from None


def _bivector_to_pure(B) -> tuple[float, float, float]:
    """(x, y, z) with B = −x e23 − y e31 − z e12 (the pure quaternion of B)."""
    c = _coefficients(B, "B")
    if np.any(np.delete(c, _BIVECTOR) != 0):
        raise InputError("B: expected a bivector (grade 2 only)")
    q = from_even(c, name="B")
    return (float(q[1]), float(q[2]), float(q[3]))


def _pure_to_bivector(v):
    return _multivector(to_even([0.0, v[0], v[1], v[2]]))


def exp(B):
    r""":math:`\exp B = \cos|B| + B \sin|B| / |B|` for a bivector B; exact at |B| = 0 and tiny |B|.

    :math:`\exp(-I u \alpha/2)` is the rotor of the rotation by :math:`\alpha` about
    :math:`u`.

    Examples
    --------
    >>> e12 = layout().blades["e12"]
    >>> R = exp(-(np.pi / 4) * e12)            # quarter-turn about z
    >>> np.round(apply(R, [1.0, 0, 0]), 15) + 0.0
    array([0., 1., 0.])
    >>> exp(1e-300 * e12).value[[0, 4]]         # (1, e12) coefficients, exact
    array([1.e+000, 1.e-300])
    """
    return _multivector(to_even(_qexp_pure(_bivector_to_pure(B))))


def log(R):
    """The bivector B with exp(B) = R and |B| ∈ [0, π] (the principal logarithm).

    Exact at R = 1 (B = 0), at tiny angles and at half-turns. At R = −1 every B with |B| = π
    works; −π e12 (the z axis, as for quaternions) is returned. R and −R (the same
    rotation) have different logarithms; :func:`to_rotation_vector` identifies them.

    Examples
    --------
    >>> log(from_axis_angle([0, 0, 1.0], 1e-300)).value[4]     # e12 coefficient: −α/2
    np.float64(-5e-301)
    >>> log(-1.0 + 0.0 * layout().blades["e12"])
    -(3.14159^e12)
    """
    return _pure_to_bivector(_qlog_unit(_unit(R)))


def slerp(R0, R1, t: float):
    r"""Interpolation :math:`R_0 \exp\left(t \log(\tilde R_0 R_1)\right)` along the shorter arc
    (:math:`\tilde R_0 R_1` negated if its scalar part is < 0).

    Exact for nearly equal rotors; slerp(R, −R, t) = R. See
    :func:`ga_rotors.quaternion.slerp` for the choices.

    Examples
    --------
    >>> a, b = from_axis_angle([0, 0, 1.0], 0.0), from_axis_angle([0, 0, 1.0], 1.0)
    >>> round(to_axis_angle(slerp(a, b, 0.25))[1], 15)
    0.25
    """
    t = as_float_array(t, "t")
    if t.shape != ():
        raise InputError(f"t: expected one number, got shape {t.shape}")
    return _rotor(_qslerp(_unit(R0, "R0"), _unit(R1, "R1"), float(t)))


def distance(R0, R1) -> float:
    r"""Geodesic angle ∈ [0, π] between the rotations of R0 and R1 (R and −R: distance 0).

    The angle of :math:`D = \tilde R_0 R_1`, resolved to 1e-16 rad:

    .. math::

        2 \operatorname{atan2}(\lvert \langle D \rangle_2 \rvert, \lvert \langle D \rangle_0 \rvert)

    Examples
    --------
    >>> a = from_axis_angle([1.0, 0, 0], 0.2)
    >>> distance(a, compose(a, from_axis_angle([0, 1.0, 0], 1e-12)))
    1e-12
    """
    return _geodesic_angle(_unit(R0, "R0"), _unit(R1, "R1"))


# --- converters: through the unit quaternion of the same rotation --------------------------


def from_axis_angle(axis, angle, degrees: bool = False):
    r"""The rotor :math:`\exp(-I u \alpha/2)` of the rotation by :math:`\alpha` about :math:`u`
    (:math:`u \ne 0`, normalised here).

    Examples
    --------
    >>> from_axis_angle([0, 0, 1.0], 180, degrees=True).clean(1e-15)
    -(1.0^e12)
    """
    u, a = _vector3(axis), _number(angle)
    if u is not None and a is not None:
        q = _from_axis_angle(u, math.radians(a) if degrees else a)
        if _finite(q):  # else a zero axis: the checked path names it
            return from_quaternion(np.array(q))
    return from_quaternion(_quaternion.from_axis_angle(axis, angle, degrees=degrees))


def to_axis_angle(R) -> tuple[np.ndarray, float]:
    """Unit axis and angle ∈ [0, π] of the rotation of R (+z at angle 0).

    Examples
    --------
    >>> to_axis_angle(from_axis_angle([0, 2.0, 0], 0.5))
    (array([0., 1., 0.]), 0.5)
    """
    r = _axis_angle(_qunit(_unit(R), UNIT_TOLERANCE))
    return np.array(r[:3]), r[3]


def from_rotation_vector(r):
    r"""The rotor :math:`\exp(-I r/2)` of the rotation by :math:`|r|` about :math:`r/|r|`.

    Examples
    --------
    >>> from_rotation_vector([0.0, 0.0, 0.0])
    1.0
    """
    v = _vector3(r)
    if v is not None:
        q = _from_rotvec(v)
        if _finite(q):
            return from_quaternion(np.array(q))
    return from_quaternion(_quaternion.from_rotation_vector(r))


def to_rotation_vector(R) -> np.ndarray:
    """Rotation vector (angle ∈ [0, π] times axis) of R; R and −R agree.

    Examples
    --------
    >>> to_rotation_vector(from_rotation_vector([0.1, 0.2, 0.3]))
    array([0.1, 0.2, 0.3])
    """
    return np.array(_to_rotvec(_qunit(_unit(R), UNIT_TOLERANCE)))


def from_two_vectors(u, v):
    """The smallest rotation taking u's direction onto v's (see
    :func:`ga_rotors.quaternion.from_two_vectors` for parallel and antiparallel vectors).

    Examples
    --------
    >>> R = from_two_vectors([1.0, 0, 0], [0, 0, 3.0])
    >>> np.round(apply(R, [1.0, 0, 0]), 15) + 0.0
    array([0., 0., 1.])
    """
    a, b = _vector3(u), _vector3(v)
    if a is not None and b is not None:
        q = _from_two_vectors(a, b)
        if _finite(q):  # else a zero vector: the checked path names it
            return from_quaternion(np.array(q))
    return from_quaternion(_quaternion.from_two_vectors(u, v))


def from_matrix(m):
    """The rotor of a rotation matrix (3, 3) (exact at half-turns).

    Examples
    --------
    >>> from_matrix(np.diag([-1.0, -1.0, 1.0]))
    -(1.0^e12)
    """
    return from_quaternion(_matrix.to_quaternion(m))


def to_matrix(R) -> np.ndarray:
    r"""The rotation matrix :math:`M` of :math:`R`: :math:`M v = R v \tilde R`.

    Examples
    --------
    >>> to_matrix(from_matrix(np.eye(3)))
    array([[1., 0., 0.],
           [0., 1., 0.],
           [0., 0., 1.]])
    """
    return np.array(_matrix_from_quat(_qunit(_unit(R), UNIT_TOLERANCE))).reshape(3, 3)


def from_euler(seq: str, angles, degrees: bool = False):
    """The rotor of Euler angles (3,) in sequence ``seq`` (scipy's naming).

    Examples
    --------
    >>> R = from_euler("ZYZ", [0.3, 0.2, 0.1])
    >>> to_euler(R, "ZYZ")
    array([0.3, 0.2, 0.1])
    """
    return from_quaternion(_euler.to_quaternion(seq, angles, degrees=degrees))


def to_euler(R, seq: str, degrees: bool = False, return_gimbal: bool = False):
    """Euler angles of R in sequence ``seq``; gimbal lock as in :mod:`ga_rotors.euler`.

    Examples
    --------
    >>> to_euler(from_axis_angle([0, 0, 1.0], 0.5), "zyx")
    array([0.5, 0. , 0. ])
    """
    return _euler.from_quaternion(
        to_quaternion(R), seq, degrees=degrees, return_gimbal=return_gimbal
    )
