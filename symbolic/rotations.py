"""Rotations about coordinate axes and Euler-angle sequences, symbolically.

Two independent constructions are kept side by side so each checks the other:
rotation matrices (active, right-handed: ``axis_matrix('z', a)`` turns x toward y) and
unit quaternions (``axis_quaternion('z', a)`` = cos(a/2) + k sin(a/2)).

Euler sequences follow scipy's naming: upper case = intrinsic (each rotation about the
axis as already moved), lower case = extrinsic (fixed axes). For intrinsic 'ZYZ' with
angles (a, b, c) the body-to-space rotation is Rz(a) Ry(b) Rz(c) and the quaternion
q_z(a) q_y(b) q_z(c); extrinsic 'zyz' applies the same rotations about fixed axes, so
its product runs in the opposite order.

Examples
--------
>>> import sympy
>>> a = sympy.Symbol("a", real=True)
>>> axis_matrix("z", a)
Matrix([
[cos(a), -sin(a), 0],
[sin(a),  cos(a), 0],
[     0,       0, 1]])
>>> axis_quaternion("z", a)
(cos(a/2), 0, 0, sin(a/2))
"""

from __future__ import annotations

from collections.abc import Sequence

import sympy

from . import hamilton

__all__ = [
    "AXES",
    "SEQUENCES",
    "axis_matrix",
    "axis_quaternion",
    "body_rates_by_axes",
    "body_rates_from_matrix",
    "body_rates_from_quaternion",
    "euler_matrix",
    "euler_quaternion",
    "rate_jacobian",
    "skew",
    "time_derivative",
    "unskew",
]


AXES = "xyz"

#: The 12 axis orders (6 proper Euler, first axis = third; 6 Tait-Bryan, all different).
SEQUENCES: tuple[str, ...] = tuple(
    a + b + c for a in AXES for b in AXES for c in AXES if a != b and b != c
)


def _axis_index(axis: str) -> int:
    axis = axis.lower()
    if axis not in AXES:
        raise ValueError(f"axis: expected one of x, y, z, got {axis!r}")
    return AXES.index(axis)


def axis_matrix(axis: str, angle) -> sympy.Matrix:
    """Active right-handed rotation by ``angle`` about a coordinate axis.

    Examples
    --------
    >>> import sympy
    >>> axis_matrix("x", sympy.pi / 2)
    Matrix([
    [1, 0,  0],
    [0, 0, -1],
    [0, 1,  0]])
    """
    k = _axis_index(axis)
    c, s = sympy.cos(angle), sympy.sin(angle)
    m = sympy.eye(3)
    i, j = (k + 1) % 3, (k + 2) % 3
    m[i, i], m[i, j], m[j, i], m[j, j] = c, -s, s, c
    return m


def axis_quaternion(axis: str, angle) -> hamilton.Quat:
    """cos(angle/2) + (unit along axis) sin(angle/2).

    Examples
    --------
    >>> import sympy
    >>> axis_quaternion("y", sympy.pi)
    (0, 0, 1, 0)
    """
    k = _axis_index(axis)
    q = [sympy.cos(angle / 2), sympy.S.Zero, sympy.S.Zero, sympy.S.Zero]
    q[k + 1] = sympy.sin(angle / 2)
    return tuple(q)  # type: ignore[return-value]


def _check_sequence(seq: str) -> None:
    if len(seq) != 3 or not (seq.isupper() or seq.islower()) or seq.lower() not in SEQUENCES:
        raise ValueError(
            f"seq: expected 3 axes, all upper case (intrinsic) or all lower case (extrinsic), "
            f"no axis twice in a row, got {seq!r}"
        )


def _ordered(seq: str, angles: Sequence) -> list[tuple[str, object]]:
    """(axis, angle) factors in the order they multiply, leftmost first."""
    _check_sequence(seq)
    pairs = list(zip(seq.lower(), angles, strict=True))
    return pairs if seq.isupper() else pairs[::-1]


def euler_matrix(seq: str, angles: Sequence) -> sympy.Matrix:
    """Body-to-space rotation matrix of an Euler sequence (scipy's convention).

    Examples
    --------
    >>> import sympy
    >>> euler_matrix("ZYX", (sympy.pi / 2, 0, 0)) == axis_matrix("z", sympy.pi / 2)
    True
    """
    m = sympy.eye(3)
    for axis, angle in _ordered(seq, angles):
        m = m * axis_matrix(axis, angle)
    return m


def euler_quaternion(seq: str, angles: Sequence) -> hamilton.Quat:
    """Body-to-space unit quaternion of an Euler sequence (scipy's convention).

    Examples
    --------
    >>> import sympy
    >>> a, b = sympy.symbols("a b")
    >>> euler_quaternion("ZXZ", (a, 0, b))
    (-sin(a/2)*sin(b/2) + cos(a/2)*cos(b/2), 0, 0, sin(a/2)*cos(b/2) + sin(b/2)*cos(a/2))
    """
    q = hamilton.quat(1, 0, 0, 0)
    for axis, angle in _ordered(seq, angles):
        q = hamilton.mul(q, axis_quaternion(axis, angle))
    return q


def skew(w: Sequence) -> sympy.Matrix:
    """[w]× with [w]× v = w × v.

    Examples
    --------
    >>> skew((1, 2, 3))
    Matrix([
    [ 0, -3,  2],
    [ 3,  0, -1],
    [-2,  1,  0]])
    """
    return sympy.Matrix([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])


def unskew(m: sympy.Matrix) -> tuple[sympy.Expr, sympy.Expr, sympy.Expr]:
    """w from [w]× (the antisymmetric part's entries).

    Examples
    --------
    >>> unskew(skew((1, 2, 3)))
    (1, 2, 3)
    """
    return (
        sympy.expand((m[2, 1] - m[1, 2]) / 2),
        sympy.expand((m[0, 2] - m[2, 0]) / 2),
        sympy.expand((m[1, 0] - m[0, 1]) / 2),
    )


def time_derivative(expr, angles: Sequence, rates: Sequence):
    """d/dt of an expression (or matrix) in the angles, by the chain rule Σ ∂/∂a · ȧ.

    Examples
    --------
    >>> import sympy
    >>> a, ad = sympy.symbols("a ad")
    >>> time_derivative(sympy.sin(a), [a], [ad])
    ad*cos(a)
    """
    return sum(
        (sympy.diff(expr, a) * r for a, r in zip(angles, rates, strict=True)),
        sympy.zeros(*expr.shape) if isinstance(expr, sympy.MatrixBase) else sympy.S.Zero,
    )


def body_rates_by_axes(seq: str, angles: Sequence, rates: Sequence) -> tuple[sympy.Expr, ...]:
    """ω_body = Σ_k (F_{k+1} ⋯ F_last)ᵀ e_{axis k} ȧ_k, F_k the factors in product order.

    Each rate turns the body about its own axis as that axis sits after the later factors,
    seen from the body: the compact closed form.

    Examples
    --------
    >>> import sympy
    >>> a, b, c = sympy.symbols("a b c")
    >>> ad, bd, cd = sympy.symbols("ad bd cd")
    >>> body_rates_by_axes("ZYZ", (a, b, c), (ad, bd, cd))
    (-ad*sin(b)*cos(c) + bd*sin(c), ad*sin(b)*sin(c) + bd*cos(c), ad*cos(b) + cd)
    """
    factors = _ordered(seq, list(zip(angles, rates, strict=True)))
    omega = sympy.zeros(3, 1)
    for k, (axis, (_, rate)) in enumerate(factors):
        later = sympy.eye(3)
        for axis2, (angle2, _) in factors[k + 1 :]:
            later = later * axis_matrix(axis2, angle2)
        e = sympy.zeros(3, 1)
        e[_axis_index(axis)] = 1
        omega += later.T * e * rate
    return tuple(omega)


def body_rates_from_matrix(seq: str, angles: Sequence, rates: Sequence) -> tuple[sympy.Expr, ...]:
    """Body angular velocity from Euler rates, by [ω]× = Rᵀ Ṙ.

    Examples
    --------
    >>> import sympy
    >>> a, b, c = sympy.symbols("a b c")
    >>> rates = sympy.symbols("ad bd cd")
    >>> w = body_rates_from_matrix("XYZ", (a, b, c), rates)
    >>> from ga_rotors.symbolic.trig import all_identities
    >>> all_identities(w, body_rates_by_axes("XYZ", (a, b, c), rates))
    True
    """
    r = euler_matrix(seq, angles)
    return unskew(r.T * time_derivative(r, angles, rates))


def body_rates_from_quaternion(seq: str, angles: Sequence, rates: Sequence):
    """Body angular velocity from Euler rates, by (0, ω) = 2 q* q̇; returns (ω, scalar part).

    Examples
    --------
    >>> import sympy
    >>> a, b, c = sympy.symbols("a b c")
    >>> ad, bd, cd = sympy.symbols("ad bd cd")
    >>> w, scalar = body_rates_from_quaternion("ZYZ", (a, b, c), (ad, bd, cd))
    >>> from ga_rotors.symbolic.trig import all_identities, is_zero
    >>> all_identities(w, body_rates_by_axes("ZYZ", (a, b, c), (ad, bd, cd))), is_zero(scalar)
    (True, True)
    """
    q = euler_quaternion(seq, angles)
    qdot = tuple(time_derivative(c, angles, rates) for c in q)
    w = hamilton.mul(hamilton.conj(q), qdot)
    return tuple(2 * c for c in w[1:]), 2 * w[0]


def rate_jacobian(omega: Sequence, rates: Sequence) -> sympy.Matrix:
    """J with ω = J (rate vector).

    Examples
    --------
    >>> import sympy
    >>> a, b, c = sympy.symbols("a b c")
    >>> rates = sympy.symbols("ad bd cd")
    >>> rate_jacobian(body_rates_by_axes("ZYZ", (a, b, c), rates), rates).det()
    -sin(b)*sin(c)**2 - sin(b)*cos(c)**2
    """
    return sympy.Matrix(3, 3, lambda r, c: sympy.diff(omega[r], rates[c]))
