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
    """(w, x, y, z) with every entry sympified."""
    return tuple(sympy.sympify(c) for c in (w, x, y, z))  # type: ignore[return-value]


def unit(name: str) -> Quat:
    """The unit '1', 'i', 'j' or 'k' as a quaternion."""
    return tuple(sympy.S.One if u == name else sympy.S.Zero for u in UNITS)  # type: ignore[return-value]


def pure(v: Sequence) -> Quat:
    """(0, v): a vector as a pure quaternion."""
    return quat(0, *v)


def symbols(name: str, **assumptions) -> Quat:
    """(name0, name1, name2, name3) as real symbols."""
    return tuple(sympy.symbols(f"{name}0:4", real=True, **assumptions))  # type: ignore[return-value]


def mul(a: Sequence, b: Sequence) -> Quat:
    """Hamilton product a b, by distributing over the unit table."""
    out = dict.fromkeys(UNITS, sympy.S.Zero)
    for ua, ca in zip(UNITS, a, strict=True):
        for ub, cb in zip(UNITS, b, strict=True):
            sign, uc = UNIT_TABLE[(ua, ub)]
            out[uc] += sign * ca * cb
    return tuple(sympy.expand(out[u]) for u in UNITS)  # type: ignore[return-value]


def conj(a: Sequence) -> Quat:
    """a* = w - x i - y j - z k."""
    return (a[0], -a[1], -a[2], -a[3])


def add(a: Sequence, b: Sequence) -> Quat:
    return tuple(sympy.expand(x + y) for x, y in zip(a, b, strict=True))  # type: ignore[return-value]


def sub(a: Sequence, b: Sequence) -> Quat:
    return tuple(sympy.expand(x - y) for x, y in zip(a, b, strict=True))  # type: ignore[return-value]


def scale(s, a: Sequence) -> Quat:
    return tuple(sympy.expand(s * x) for x in a)  # type: ignore[return-value]


def norm2(a: Sequence) -> sympy.Expr:
    """|a|² = w² + x² + y² + z²."""
    return sympy.expand(sum(c**2 for c in a))


def vector(a: Sequence) -> tuple[sympy.Expr, sympy.Expr, sympy.Expr]:
    return (a[1], a[2], a[3])


def rotate(q: Sequence, v: Sequence) -> tuple[sympy.Expr, sympy.Expr, sympy.Expr]:
    """Vector part of q (0, v) q* (the scalar part is identically zero)."""
    return vector(mul(mul(q, pure(v)), conj(q)))


def rotation_matrix(q: Sequence) -> sympy.Matrix:
    """The matrix M with q (0, v) q* = (0, M v), entries read off as ∂/∂v (no unit assumption)."""
    v = sympy.symbols("v1:4", real=True)
    image = rotate(q, v)
    return sympy.Matrix(3, 3, lambda r, c: sympy.expand(sympy.diff(image[r], v[c])))


def left_matrix(q: Sequence) -> sympy.Matrix:
    """L(q) with q p = L(q) p for every p (columns: q times each unit)."""
    cols = [mul(q, unit(u)) for u in UNITS]
    return sympy.Matrix(4, 4, lambda r, c: cols[c][r])


def right_matrix(q: Sequence) -> sympy.Matrix:
    """R(q) with p q = R(q) p for every p."""
    cols = [mul(unit(u), q) for u in UNITS]
    return sympy.Matrix(4, 4, lambda r, c: cols[c][r])


def is_equal(a: Sequence, b: Sequence) -> bool:
    """Exact equality after expansion."""
    return all(sympy.expand(x - y) == 0 for x, y in zip(a, b, strict=True))
