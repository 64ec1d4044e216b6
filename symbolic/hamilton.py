"""Hamilton's quaternions, exactly, from their defining rules.

A quaternion is a 4-tuple (w, x, y, z) = w + x i + y j + z k of SymPy expressions
(scalar first, as in the numeric package). The product is built from the unit table
below, which is Hamilton's i² = j² = k² = ijk = -1 spelled out; nothing else is
assumed. :mod:`symbolic.isomorphisms` derives the same table from Clifford algebras,
and the tests compare it with ``sympy.algebras.Quaternion``.

Examples
--------
>>> I, J, K = unit("i"), unit("j"), unit("k")
>>> mul(I, J) == K
True
>>> mul(mul(I, J), K)
(-1, 0, 0, 0)
"""

from __future__ import annotations

from collections.abc import Sequence

import sympy

__all__ = [
    "UNITS",
    "UNIT_TABLE",
    "Quat",
    "add",
    "conj",
    "is_equal",
    "left_matrix",
    "mul",
    "norm2",
    "pure",
    "quat",
    "right_matrix",
    "rotate",
    "rotation_matrix",
    "scale",
    "sub",
    "symbols",
    "unit",
    "vector",
]


Quat = tuple[sympy.Expr, sympy.Expr, sympy.Expr, sympy.Expr]

UNITS = ("1", "i", "j", "k")

#: (a, b) -> (sign, c) with a b = sign c, for a, b in 1, i, j, k (Hamilton, 1843).
UNIT_TABLE: dict[tuple[str, str], tuple[int, str]] = {
    ("1", "1"): (1, "1"),
    ("1", "i"): (1, "i"),
    ("1", "j"): (1, "j"),
    ("1", "k"): (1, "k"),
    ("i", "1"): (1, "i"),
    ("i", "i"): (-1, "1"),
    ("i", "j"): (1, "k"),
    ("i", "k"): (-1, "j"),
    ("j", "1"): (1, "j"),
    ("j", "i"): (-1, "k"),
    ("j", "j"): (-1, "1"),
    ("j", "k"): (1, "i"),
    ("k", "1"): (1, "k"),
    ("k", "i"): (1, "j"),
    ("k", "j"): (-1, "i"),
    ("k", "k"): (-1, "1"),
}


def quat(w, x, y, z) -> Quat:
    """(w, x, y, z) with every entry sympified.

    Examples
    --------
    >>> quat(1, 0, "x", 2)
    (1, 0, x, 2)
    """
    return tuple(sympy.sympify(c) for c in (w, x, y, z))  # type: ignore[return-value]


def unit(name: str) -> Quat:
    """The unit '1', 'i', 'j' or 'k' as a quaternion.

    Examples
    --------
    >>> unit("j")
    (0, 0, 1, 0)
    """
    return tuple(sympy.S.One if u == name else sympy.S.Zero for u in UNITS)  # type: ignore[return-value]


def pure(v: Sequence) -> Quat:
    """(0, v): a vector as a pure quaternion.

    Examples
    --------
    >>> pure([1, 2, 3])
    (0, 1, 2, 3)
    """
    return quat(0, *v)


def symbols(name: str, **assumptions) -> Quat:
    """(name0, name1, name2, name3) as real symbols.

    Examples
    --------
    >>> symbols("q")
    (q0, q1, q2, q3)
    """
    return tuple(sympy.symbols(f"{name}0:4", real=True, **assumptions))  # type: ignore[return-value]


def mul(a: Sequence, b: Sequence) -> Quat:
    """Hamilton product a b, by distributing over the unit table.

    Examples
    --------
    >>> mul(unit("j"), unit("i"))
    (0, 0, 0, -1)
    >>> mul(quat(1, 2, 3, 4), quat(5, 6, 7, 8))
    (-60, 12, 30, 24)
    """
    out = dict.fromkeys(UNITS, sympy.S.Zero)
    for ua, ca in zip(UNITS, a, strict=True):
        for ub, cb in zip(UNITS, b, strict=True):
            sign, uc = UNIT_TABLE[(ua, ub)]
            out[uc] += sign * ca * cb
    return tuple(sympy.expand(out[u]) for u in UNITS)  # type: ignore[return-value]


def conj(a: Sequence) -> Quat:
    """a* = w - x i - y j - z k.

    Examples
    --------
    >>> conj(quat(1, 2, 3, 4))
    (1, -2, -3, -4)
    """
    return (a[0], -a[1], -a[2], -a[3])


def add(a: Sequence, b: Sequence) -> Quat:
    """a + b, componentwise.

    Examples
    --------
    >>> add(unit("i"), unit("j"))
    (0, 1, 1, 0)
    """
    return tuple(sympy.expand(x + y) for x, y in zip(a, b, strict=True))  # type: ignore[return-value]


def sub(a: Sequence, b: Sequence) -> Quat:
    """a − b, componentwise.

    Examples
    --------
    >>> sub(unit("i"), unit("i"))
    (0, 0, 0, 0)
    """
    return tuple(sympy.expand(x - y) for x, y in zip(a, b, strict=True))  # type: ignore[return-value]


def scale(s, a: Sequence) -> Quat:
    """s a for a scalar s.

    Examples
    --------
    >>> scale(2, quat(1, 0, 0, 1))
    (2, 0, 0, 2)
    """
    return tuple(sympy.expand(s * x) for x in a)  # type: ignore[return-value]


def norm2(a: Sequence) -> sympy.Expr:
    """|a|² = w² + x² + y² + z².

    Examples
    --------
    >>> norm2(quat(1, 2, 3, 4))
    30
    """
    return sympy.expand(sum(c**2 for c in a))


def vector(a: Sequence) -> tuple[sympy.Expr, sympy.Expr, sympy.Expr]:
    """The vector part (x, y, z).

    Examples
    --------
    >>> vector(quat(1, 2, 3, 4))
    (2, 3, 4)
    """
    return (a[1], a[2], a[3])


def rotate(q: Sequence, v: Sequence) -> tuple[sympy.Expr, sympy.Expr, sympy.Expr]:
    """Vector part of q (0, v) q* (the scalar part is identically zero).

    Examples
    --------
    >>> import sympy
    >>> h = sympy.sqrt(2) / 2
    >>> rotate((h, 0, 0, h), (1, 0, 0))  # 90° about z
    (0, 1, 0)
    """
    return vector(mul(mul(q, pure(v)), conj(q)))


def rotation_matrix(q: Sequence) -> sympy.Matrix:
    """The matrix M with q (0, v) q* = (0, M v), entries read off as ∂/∂v (no unit assumption).

    Examples
    --------
    >>> rotation_matrix(unit("k"))  # half-turn about z
    Matrix([
    [-1,  0, 0],
    [ 0, -1, 0],
    [ 0,  0, 1]])
    """
    v = sympy.symbols("v1:4", real=True)
    image = rotate(q, v)
    return sympy.Matrix(3, 3, lambda r, c: sympy.expand(sympy.diff(image[r], v[c])))


def left_matrix(q: Sequence) -> sympy.Matrix:
    """L(q) with q p = L(q) p for every p (columns: q times each unit).

    Examples
    --------
    >>> left_matrix(quat(1, 2, 3, 4))
    Matrix([
    [1, -2, -3, -4],
    [2,  1, -4,  3],
    [3,  4,  1, -2],
    [4, -3,  2,  1]])
    """
    cols = [mul(q, unit(u)) for u in UNITS]
    return sympy.Matrix(4, 4, lambda r, c: cols[c][r])


def right_matrix(q: Sequence) -> sympy.Matrix:
    """R(q) with p q = R(q) p for every p.

    Examples
    --------
    >>> right_matrix(quat(1, 2, 3, 4))
    Matrix([
    [1, -2, -3, -4],
    [2,  1,  4, -3],
    [3, -4,  1,  2],
    [4,  3, -2,  1]])
    """
    cols = [mul(unit(u), q) for u in UNITS]
    return sympy.Matrix(4, 4, lambda r, c: cols[c][r])


def is_equal(a: Sequence, b: Sequence) -> bool:
    """Exact equality after expansion.

    Examples
    --------
    >>> is_equal(mul(unit("i"), unit("j")), unit("k"))
    True
    """
    return all(sympy.expand(x - y) == 0 for x, y in zip(a, b, strict=True))
