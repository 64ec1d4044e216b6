"""An exact Clifford algebra Cl(p, q) in SymPy, written to be read.

A basis blade is a sorted tuple of vector indices: ``()`` is the scalar 1, ``(1,)`` is
e1, ``(1, 3)`` is e13 = e1 e3. Indices run from 1 to n = p + q; the first p basis
vectors square to +1, the next q to -1 (``clifford.Cl(p, q)`` uses the same order, so
coefficients can be compared blade by blade). Blades are listed by grade, then
lexicographically: 1, e1, e2, e3, e12, e13, e23, e123 for Cl(3, 0). A blade such as
e31 is not a basis element: it is -e13.

Products (for basis blades A of grade r and B of grade s; extended bilinearly):

* geometric product ``A * B``: the whole product;
* outer product ``A ^ B``: the grade r + s part of AB;
* left contraction ``A.lc(B)`` (A ⌋ B): the grade s - r part of AB (zero when r > s);
* right contraction ``A.rc(B)`` (A ⌊ B): the grade r - s part of AB (zero when s > r);
* Hestenes inner product ``A | B``: the grade |r - s| part of AB, and zero when either
  factor is a scalar (this is ``clifford``'s ``|``);
* scalar product ``A.scalar_product(B)``: the grade 0 part of AB.

Involutions: reverse ``~A`` (order of the vector factors reversed: sign
(-1)^(r(r-1)/2)), grade involution ``A.grade_involution()`` (sign (-1)^r), Clifford
conjugate ``A.conjugate()`` (both). Grade projection: ``A.grade(k)``.

Coefficients are SymPy expressions, so multivectors can carry symbols.

Examples
--------
>>> cl3 = CliffordAlgebra(3, 0)
>>> e1, e2, e3 = cl3.basis_vectors()
>>> e1 * e2
e12
>>> e2 * e1
-e12
>>> (e1 * e2) * (e1 * e2)
-1
>>> cl3.blade(3, 1)                 # e31 is not a basis blade
-e13
"""

from __future__ import annotations

from bisect import insort
from collections.abc import Callable, Iterable, Mapping
from functools import cached_property
from itertools import combinations

import sympy

__all__ = ["Blade", "CliffordAlgebra", "Multivector", "blade_name", "blade_product", "latex_sum"]


Blade = tuple[int, ...]


def blade_product(a: Blade, b: Blade, signature: tuple[int, ...]) -> tuple[int, Blade]:
    """Product of two basis blades: (sign, blade) with e_a e_b = sign e_blade.

    The factors of ``b`` are moved one at a time into the sorted list of ``a``: an index
    j passes every index greater than j (one anticommutation, one sign change each)
    and, if e_j is already there, the pair e_j e_j contracts to ``signature[j - 1]``.

    Examples
    --------
    >>> blade_product((2, 3), (1,), (1, 1, 1))      # e23 e1 = e1 e23 = e123
    (1, (1, 2, 3))
    >>> blade_product((1, 2), (1, 2), (-1, -1))     # (e12)^2 in Cl(0, 2)
    (-1, ())
    """
    sign = 1
    indices = list(a)
    for j in b:
        passed = sum(1 for i in indices if i > j)
        if passed % 2:
            sign = -sign
        if j in indices:
            indices.remove(j)
            sign *= signature[j - 1]
        else:
            insort(indices, j)
    return sign, tuple(indices)


def latex_sum(terms: Iterable[tuple[object, str]]) -> str:
    """The LaTeX of a multivector Σ c e_B, from (coefficient, blade name) pairs in order.

    ``blade name`` is as :func:`blade_name` writes it ('1' for the scalar, 'e12', ...);
    a sum as coefficient is put in parentheses.

    Examples
    --------
    >>> x = sympy.Symbol("x")
    >>> print(latex_sum([(sympy.Rational(1, 2), "1"), (x + 1, "e12"), (-3 * x, "e1_10")]))
    \\frac{1}{2} + \\left(x + 1\\right) e_{12} - 3 x e_{1,10}
    """
    out = []
    for c, name in terms:
        expr = c.as_expr() if hasattr(c, "as_expr") else sympy.sympify(c)
        tex = sympy.latex(expr)
        if isinstance(expr, sympy.Add):
            tex = rf"\left({tex}\right)"
        sign = "+"
        if tex.startswith("-"):
            sign, tex = "-", tex[1:].lstrip()
        if name != "1":
            blade = "e_{" + name[1:].replace("_", ",") + "}"
            tex = blade if tex == "1" else f"{tex} {blade}"
        out.append(("-" if sign == "-" else "") + tex if not out else f" {sign} {tex}")
    return "".join(out) or "0"


def blade_name(blade: Blade) -> str:
    """'1' for the scalar blade, else 'e' followed by the indices ('e13', 'e1_10' when n > 9).

    Examples
    --------
    >>> blade_name((1, 3))
    'e13'
    >>> blade_name(())
    '1'
    """
    if not blade:
        return "1"
    if max(blade) > 9:
        return "e" + "_".join(str(i) for i in blade)
    return "e" + "".join(str(i) for i in blade)


class CliffordAlgebra:
    """Cl(p, q): n = p + q basis vectors, e_i² = +1 for i ≤ p and -1 for i > p.

    Parameters
    ----------
    p, q : int
        Numbers of basis vectors squaring to +1 and to -1.

    Examples
    --------
    >>> cl02 = CliffordAlgebra(0, 2)
    >>> cl02.blades
    ((), (1,), (2,), (1, 2))
    >>> e1, e2 = cl02.basis_vectors()
    >>> e1 * e1
    -1
    """

    def __init__(self, p: int, q: int):
        if not (isinstance(p, int) and isinstance(q, int)) or p < 0 or q < 0:
            raise ValueError(f"p, q: expected non-negative integers, got p={p!r}, q={q!r}")
        self.p, self.q = p, q
        self.n = p + q
        self.signature: tuple[int, ...] = (1,) * p + (-1,) * q
        self.blades: tuple[Blade, ...] = tuple(
            blade for k in range(self.n + 1) for blade in combinations(range(1, self.n + 1), k)
        )

    def __repr__(self) -> str:
        return f"CliffordAlgebra({self.p}, {self.q})"

    def __eq__(self, other) -> bool:
        return isinstance(other, CliffordAlgebra) and (self.p, self.q) == (other.p, other.q)

    def __hash__(self) -> int:
        return hash((self.p, self.q))

    @cached_property
    def _table(self) -> dict[tuple[Blade, Blade], tuple[int, Blade]]:
        return {
            (a, b): blade_product(a, b, self.signature) for a in self.blades for b in self.blades
        }

    def product_of_blades(self, a: Blade, b: Blade) -> tuple[int, Blade]:
        """(sign, blade) with e_a e_b = sign e_blade (table lookup).

        Examples
        --------
        >>> CliffordAlgebra(3, 0).product_of_blades((1, 2), (2, 3))
        (1, (1, 3))
        """
        return self._table[(a, b)]

    def multivector(self, terms: Mapping[Blade, object] | None = None) -> Multivector:
        """A multivector from {blade: coefficient}; blades given unsorted are reordered.

        Examples
        --------
        >>> CliffordAlgebra(3, 0).multivector({(): 2, (3, 1): 5})
        2 - 5*e13
        """
        out: dict[Blade, sympy.Expr] = {}
        for blade, coeff in (terms or {}).items():
            sign, canonical = blade_product((), tuple(blade), self.signature)
            if len(canonical) != len(blade):
                raise ValueError(f"blade {blade!r} repeats an index")
            out[canonical] = out.get(canonical, sympy.S.Zero) + sign * sympy.sympify(coeff)
        return Multivector(self, out)

    def scalar(self, value) -> Multivector:
        """The scalar ``value`` as a multivector.

        Examples
        --------
        >>> CliffordAlgebra(2, 0).scalar(7)
        7
        """
        return self.multivector({(): value})

    def blade(self, *indices: int) -> Multivector:
        """The product e_i e_j ... of the given basis vectors, e.g. ``blade(3, 1)`` = -e13.

        Examples
        --------
        >>> CliffordAlgebra(3, 0).blade(2, 1, 3)
        -e123
        """
        result = self.scalar(1)
        for i in indices:
            if not 1 <= i <= self.n:
                raise ValueError(f"index {i}: expected 1..{self.n}")
            result = result * self.multivector({(i,): 1})
        return result

    def basis_vectors(self) -> tuple[Multivector, ...]:
        """(e1, ..., en).

        Examples
        --------
        >>> CliffordAlgebra(1, 3).basis_vectors()
        (e1, e2, e3, e4)
        """
        return tuple(self.multivector({(i,): 1}) for i in range(1, self.n + 1))

    def pseudoscalar(self) -> Multivector:
        """I = e1 e2 ... en.

        Examples
        --------
        >>> cl = CliffordAlgebra(3, 0)
        >>> cl.pseudoscalar() * cl.pseudoscalar()
        -1
        """
        return self.blade(*range(1, self.n + 1))

    def general(self, name: str, grades: Iterable[int] | None = None, **assumptions) -> Multivector:
        """A multivector whose coefficients are fresh symbols ``name_<blade>``.

        Examples
        --------
        >>> CliffordAlgebra(2, 0).general("a")
        a_1 + a_e1*e1 + a_e2*e2 + a_e12*e12
        """
        keep = set(range(self.n + 1)) if grades is None else set(grades)
        return self.multivector(
            {
                b: sympy.Symbol(f"{name}_{blade_name(b)}", **assumptions)
                for b in self.blades
                if len(b) in keep
            }
        )


class Multivector:
    """An element of a :class:`CliffordAlgebra`: a map blade -> SymPy coefficient.

    Zero coefficients are dropped after expansion, so two multivectors are equal
    exactly when their expanded coefficients agree.

    Examples
    --------
    >>> cl = CliffordAlgebra(2, 0)
    >>> x = cl.multivector({(): 1, (1, 2): 3})
    >>> x[(1, 2)], x.grades
    (3, {0, 2})
    """

    __slots__ = ("algebra", "terms")

    def __init__(self, algebra: CliffordAlgebra, terms: Mapping[Blade, sympy.Expr]):
        self.algebra = algebra
        self.terms: dict[Blade, sympy.Expr] = {}
        for blade, coeff in terms.items():
            c = sympy.expand(coeff)
            if c != 0:
                self.terms[blade] = c

    # -- access ------------------------------------------------------------------------
    def __getitem__(self, blade: Blade) -> sympy.Expr:
        """Coefficient of a basis blade (given sorted), zero if absent."""
        return self.terms.get(tuple(blade), sympy.S.Zero)

    def coefficients(self) -> tuple[sympy.Expr, ...]:
        """Coefficients in the algebra's blade order (the order ``clifford`` uses).

        Examples
        --------
        >>> CliffordAlgebra(2, 0).blade(1).coefficients()
        (0, 1, 0, 0)
        """
        return tuple(self[b] for b in self.algebra.blades)

    @property
    def grades(self) -> set[int]:
        """Grades with a nonzero part."""
        return {len(b) for b in self.terms}

    def is_zero(self) -> bool:
        """True when every coefficient expands to zero.

        Examples
        --------
        >>> e1 = CliffordAlgebra(1, 0).blade(1)
        >>> ((1 + e1) * (1 - e1)).is_zero()
        True
        """
        return not self.terms

    # -- linear structure ---------------------------------------------------------------
    def _coerce(self, other) -> Multivector:
        if isinstance(other, Multivector):
            if other.algebra != self.algebra:
                raise ValueError(f"cannot combine elements of {self.algebra} and {other.algebra}")
            return other
        return self.algebra.scalar(other)

    def __add__(self, other) -> Multivector:
        other = self._coerce(other)
        terms = dict(self.terms)
        for b, c in other.terms.items():
            terms[b] = terms.get(b, sympy.S.Zero) + c
        return Multivector(self.algebra, terms)

    __radd__ = __add__

    def __neg__(self) -> Multivector:
        return Multivector(self.algebra, {b: -c for b, c in self.terms.items()})

    def __sub__(self, other) -> Multivector:
        return self + (-self._coerce(other))

    def __rsub__(self, other) -> Multivector:
        return self._coerce(other) - self

    def __eq__(self, other) -> bool:
        try:
            return (self - other).is_zero()
        except (ValueError, TypeError, sympy.SympifyError):
            return NotImplemented

    __hash__ = None  # mutable-looking value type: equality is algebraic, not identity

    # -- products -----------------------------------------------------------------------
    def _graded(self, other, keep: Callable[[int, int, int], bool]) -> Multivector:
        """Sum over blade pairs of the geometric product, kept where keep(r, s, grade)."""
        other = self._coerce(other)
        table = self.algebra._table
        terms: dict[Blade, sympy.Expr] = {}
        for a, ca in self.terms.items():
            for b, cb in other.terms.items():
                sign, blade = table[(a, b)]
                if keep(len(a), len(b), len(blade)):
                    terms[blade] = terms.get(blade, sympy.S.Zero) + sign * ca * cb
        return Multivector(self.algebra, terms)

    def __mul__(self, other) -> Multivector:
        """Geometric product."""
        return self._graded(other, lambda r, s, g: True)

    def __rmul__(self, other) -> Multivector:
        return self._coerce(other) * self

    def __truediv__(self, other) -> Multivector:
        """Division by a scalar only (multivector inverses are not generally defined)."""
        if isinstance(other, Multivector):
            if other.grades - {0}:
                raise ValueError("division by a non-scalar multivector is not defined here")
            other = other[()]
        return Multivector(self.algebra, {b: c / other for b, c in self.terms.items()})

    def __pow__(self, k: int) -> Multivector:
        if not isinstance(k, int) or k < 0:
            raise ValueError(f"power: expected a non-negative integer, got {k!r}")
        result = self.algebra.scalar(1)
        for _ in range(k):
            result = result * self
        return result

    def __xor__(self, other) -> Multivector:
        """Outer (wedge) product A ∧ B."""
        return self._graded(other, lambda r, s, g: g == r + s)

    def __rxor__(self, other) -> Multivector:
        return self._coerce(other) ^ self

    def lc(self, other) -> Multivector:
        """Left contraction A ⌋ B: grade s - r part of A_r B_s.

        Examples
        --------
        >>> cl = CliffordAlgebra(3, 0)
        >>> cl.blade(1).lc(cl.blade(1, 2))
        e2
        >>> cl.blade(1, 2).lc(cl.blade(1))
        0
        """
        return self._graded(other, lambda r, s, g: g == s - r)

    def rc(self, other) -> Multivector:
        """Right contraction A ⌊ B: grade r - s part of A_r B_s.

        Examples
        --------
        >>> cl = CliffordAlgebra(3, 0)
        >>> cl.blade(1, 2).rc(cl.blade(2))
        e1
        """
        return self._graded(other, lambda r, s, g: g == r - s)

    def __or__(self, other) -> Multivector:
        """Hestenes inner product: grade |r - s| part of A_r B_s, zero if r or s is 0."""
        return self._graded(other, lambda r, s, g: r != 0 and s != 0 and g == abs(r - s))

    def __ror__(self, other) -> Multivector:
        return self._coerce(other) | self

    def scalar_product(self, other) -> sympy.Expr:
        """⟨A B⟩₀.

        Examples
        --------
        >>> cl = CliffordAlgebra(0, 2)
        >>> cl.blade(1, 2).scalar_product(cl.blade(1, 2))
        -1
        """
        return (self * other)[()]

    def commutator(self, other) -> Multivector:
        """½(AB - BA).

        Examples
        --------
        >>> cl = CliffordAlgebra(3, 0)
        >>> cl.blade(1, 2).commutator(cl.blade(1))
        -e2
        """
        other = self._coerce(other)
        return (self * other - other * self) / 2

    # -- involutions and projections ---------------------------------------------------
    def _signed(self, sign_of_grade: Callable[[int], int]) -> Multivector:
        return Multivector(
            self.algebra, {b: sign_of_grade(len(b)) * c for b, c in self.terms.items()}
        )

    def reverse(self) -> Multivector:
        """Ã: each blade of grade r gets the sign (-1)^(r(r-1)/2).

        Examples
        --------
        >>> CliffordAlgebra(3, 0).multivector({(1, 2): 1, (1, 2, 3): 1}).reverse()
        -e12 - e123
        """
        return self._signed(lambda r: -1 if (r * (r - 1) // 2) % 2 else 1)

    __invert__ = reverse

    def grade_involution(self) -> Multivector:
        """Â: each blade of grade r gets the sign (-1)^r.

        Examples
        --------
        >>> CliffordAlgebra(3, 0).multivector({(): 1, (1,): 1, (1, 2): 1}).grade_involution()
        1 - e1 + e12
        """
        return self._signed(lambda r: -1 if r % 2 else 1)

    def conjugate(self) -> Multivector:
        """Clifford conjugate: reverse and grade involution together.

        Examples
        --------
        >>> CliffordAlgebra(3, 0).multivector({(1,): 1, (1, 2): 1}).conjugate()
        -e1 - e12
        """
        return self.reverse().grade_involution()

    def grade(self, k: int) -> Multivector:
        """⟨A⟩_k: the grade-k part.

        Examples
        --------
        >>> CliffordAlgebra(2, 0).multivector({(): 4, (1,): 2, (1, 2): 1}).grade(1)
        2*e1
        """
        return Multivector(self.algebra, {b: c for b, c in self.terms.items() if len(b) == k})

    def even(self) -> Multivector:
        """The even-grade part (grades 0, 2, ...).

        Examples
        --------
        >>> CliffordAlgebra(2, 0).multivector({(): 4, (1,): 2, (1, 2): 1}).even()
        4 + e12
        """
        return Multivector(self.algebra, {b: c for b, c in self.terms.items() if len(b) % 2 == 0})

    def subs(self, *args, **kwargs) -> Multivector:
        """Substitute in every coefficient (``sympy.Expr.subs`` arguments).

        Examples
        --------
        >>> a = CliffordAlgebra(1, 0).general("a")
        >>> a.subs({"a_1": 2, "a_e1": 3})
        2 + 3*e1
        """
        return Multivector(
            self.algebra, {b: c.subs(*args, **kwargs) for b, c in self.terms.items()}
        )

    def applyfunc(self, f: Callable[[sympy.Expr], sympy.Expr]) -> Multivector:
        """Apply f to every coefficient.

        Examples
        --------
        >>> import sympy
        >>> x = sympy.Symbol("x")
        >>> CliffordAlgebra(1, 0).scalar((x + 1) ** 2).applyfunc(sympy.factor)
        x**2 + 2*x + 1
        """
        return Multivector(self.algebra, {b: f(c) for b, c in self.terms.items()})

    # -- display -----------------------------------------------------------------------
    def latex(self) -> str:
        """The LaTeX of the multivector (no dollar signs).

        Examples
        --------
        >>> cl = CliffordAlgebra(3, 0)
        >>> theta = sympy.Symbol("theta")
        >>> print((sympy.cos(theta / 2) - cl.blade(1, 2) * sympy.sin(theta / 2)).latex())
        \\cos{\\left(\\frac{\\theta}{2} \\right)} - \\sin{\\left(\\frac{\\theta}{2} \\right)} e_{12}
        """
        ordered = [b for b in self.algebra.blades if b in self.terms]
        return latex_sum((self.terms[b], blade_name(b)) for b in ordered)

    def _repr_latex_(self) -> str:
        """The multivector as LaTeX (Jupyter calls this).

        Examples
        --------
        >>> cl = CliffordAlgebra(0, 2)
        >>> (cl.blade(1) * cl.blade(2) + 1)._repr_latex_()
        '$1 + e_{12}$'
        """
        return f"${self.latex()}$"

    def __repr__(self) -> str:
        if not self.terms:
            return "0"
        parts = []
        for blade in self.algebra.blades:
            if blade not in self.terms:
                continue
            c = self.terms[blade]
            if not blade:
                parts.append(sympy.sstr(c))
                continue
            name = blade_name(blade)
            if c == 1:
                parts.append(name)
            elif c == -1:
                parts.append("-" + name)
            elif isinstance(c, sympy.Add):
                parts.append(f"({sympy.sstr(c)})*{name}")
            else:
                parts.append(f"{sympy.sstr(c)}*{name}")
        text = " + ".join(parts)
        return text.replace("+ -", "- ")
