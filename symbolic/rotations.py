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
    """Active right-handed rotation by ``angle`` about a coordinate axis."""
    k = _axis_index(axis)
    c, s = sympy.cos(angle), sympy.sin(angle)
    m = sympy.eye(3)
    i, j = (k + 1) % 3, (k + 2) % 3
    m[i, i], m[i, j], m[j, i], m[j, j] = c, -s, s, c
    return m


def axis_quaternion(axis: str, angle) -> hamilton.Quat:
    """cos(angle/2) + (unit along axis) sin(angle/2)."""
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
    """Body-to-space rotation matrix of an Euler sequence (scipy's convention)."""
    m = sympy.eye(3)
    for axis, angle in _ordered(seq, angles):
        m = m * axis_matrix(axis, angle)
    return m


def euler_quaternion(seq: str, angles: Sequence) -> hamilton.Quat:
    """Body-to-space unit quaternion of an Euler sequence (scipy's convention)."""
    q = hamilton.quat(1, 0, 0, 0)
    for axis, angle in _ordered(seq, angles):
        q = hamilton.mul(q, axis_quaternion(axis, angle))
    return q


def skew(w: Sequence) -> sympy.Matrix:
    """[w]× with [w]× v = w × v."""
    return sympy.Matrix([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])


def unskew(m: sympy.Matrix) -> tuple[sympy.Expr, sympy.Expr, sympy.Expr]:
    """w from [w]× (the antisymmetric part's entries)."""
    return (
        sympy.expand((m[2, 1] - m[1, 2]) / 2),
        sympy.expand((m[0, 2] - m[2, 0]) / 2),
        sympy.expand((m[1, 0] - m[0, 1]) / 2),
    )


def time_dependent(names: Sequence[str]):
    """Angles as functions of t, with symbols for the angles and their rates.

    Returns (t, functions, angle symbols, rate symbols, to_symbols) where ``to_symbols``
    replaces each function and its first derivative by plain symbols, so that results
    are ordinary expressions in (angle, rate) pairs.
    """
    t = sympy.Symbol("t", real=True)
    funcs = [sympy.Function(n, real=True)(t) for n in names]
    angles = sympy.symbols(list(names), real=True)
    rates = sympy.symbols([f"{n}dot" for n in names], real=True)

    def to_symbols(expr):
        expr = sympy.sympify(expr)
        expr = expr.subs({sympy.Derivative(f, t): r for f, r in zip(funcs, rates, strict=True)})
        return expr.subs(dict(zip(funcs, angles, strict=True)))

    return t, funcs, angles, rates, to_symbols


def body_rates_from_matrix(seq: str, names: Sequence[str] = ("a", "b", "c")):
    """Body angular velocity from Euler rates, by [ω]× = Rᵀ Ṙ.

    Returns (angles, rates, ω) with ω a 3-tuple of expressions.
    """
    t, funcs, angles, rates, to_symbols = time_dependent(names)
    r = euler_matrix(seq, funcs)
    omega = unskew((r.T * r.diff(t)).applyfunc(to_symbols))
    return angles, rates, omega


def body_rates_from_quaternion(seq: str, names: Sequence[str] = ("a", "b", "c")):
    """Body angular velocity from Euler rates, by (0, ω) = 2 q* q̇."""
    t, funcs, angles, rates, to_symbols = time_dependent(names)
    q = euler_quaternion(seq, funcs)
    qdot = tuple(sympy.diff(c, t) for c in q)
    w = hamilton.mul(hamilton.conj(q), qdot)
    omega = tuple(sympy.expand(to_symbols(2 * c)) for c in w[1:])
    scalar = sympy.expand(to_symbols(2 * w[0]))
    return angles, rates, omega, scalar


def rate_jacobian(omega: Sequence, rates: Sequence) -> sympy.Matrix:
    """J with ω = J (rate vector)."""
    return sympy.Matrix(3, 3, lambda r, c: sympy.diff(omega[r], rates[c]))
