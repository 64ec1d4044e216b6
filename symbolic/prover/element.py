"""Multivectors of Cl(p, q, r) whose coefficients live in any commutative ring.

The same code computes with SymPy polynomials (the exact proof), with fractions (an
exact counterexample) and with numpy arrays holding many random draws at once (the
pre-check): an :class:`Element` is a map from basis blade to coefficient, and every
product is a sum over blade pairs of the table of :class:`~.basis.Basis`.

Products and operations, for blades A of grade r and B of grade s:

* ``A * B`` geometric product; ``A ^ B`` outer product (grade r + s part);
* ``A.lc(B)`` left contraction A ⌋ B (grade s - r, zero when r > s);
* ``A.rc(B)`` right contraction A ⌊ B (grade r - s, zero when s > r);
* ``A | B`` Hestenes inner product (grade |r - s|, zero when r = 0 or s = 0), as in
  Hestenes & Sobczyk, Doran & Lasenby and ``clifford``;
* ``A.dot(B)`` the "fat dot" of Dorst, Fontijne & Mann (grade |r - s|, scalars included);
* ``A.scalar_product(B)`` ⟨AB⟩₀; ``A.commutator(B)`` ½(AB − BA);
* ``~A`` reverse, ``A.involute()`` grade involution, ``A.conjugate()`` Clifford
  conjugate, ``A.grade(k)`` grade projection;
* ``A.dual()``: A I⁻¹ where I is invertible (r = 0), the Poincaré dual (right complement)
  where it is not (r > 0), as ``clifford``'s ``dual``; ``A.undual()`` its inverse;
* ``A.vee(B)`` the regressive product, from the complements (no metric), as
  ``clifford``'s ``vee`` and ``&``.

Examples
--------
>>> from fractions import Fraction
>>> from ga_rotors.symbolic.prover.basis import Basis
>>> cl3 = Basis(3)
>>> e1, e2, e3 = (Element.blade(cl3, 1 << i, Fraction(1)) for i in range(3))
>>> e1 * e2
e12
>>> (e1 ^ e2) | e2
e1
>>> (e1 * e2 * e3).dual()
1
"""

from __future__ import annotations

from collections.abc import Callable, Mapping

import numpy as np

from .basis import Basis

__all__ = ["Element"]


def _is_zero(c) -> bool:
    if isinstance(c, np.ndarray):
        return not c.any()
    return not c


def _reverse_sign(k: int) -> int:
    return -1 if (k * (k - 1) // 2) % 2 else 1


class Element:
    """An element of Cl(p, q, r): {blade bit mask: coefficient}, zero coefficients dropped.

    Parameters
    ----------
    basis : Basis
        The algebra.
    terms : mapping of int to coefficient
        Coefficients by blade; any commutative ring that supports ``+``, ``-``, ``*``.

    Examples
    --------
    >>> from ga_rotors.symbolic.prover.basis import Basis
    >>> x = Element(Basis(2), {0: 3, 0b11: 2})
    >>> x, x.grades()
    (3 + 2*e12, {0, 2})
    >>> x * x
    5 + 12*e12
    """

    __slots__ = ("basis", "terms")

    def __init__(self, basis: Basis, terms: Mapping[int, object]):
        self.basis = basis
        self.terms = {b: c for b, c in terms.items() if not _is_zero(c)}

    @classmethod
    def blade(cls, basis: Basis, blade: int, coefficient) -> Element:
        """coefficient · e_blade.

        Examples
        --------
        >>> from ga_rotors.symbolic.prover.basis import Basis
        >>> Element.blade(Basis(3), 0b101, -2)
        -2*e13
        """
        return cls(basis, {blade: coefficient})

    # -- linear structure ------------------------------------------------------------
    def _lift(self, other) -> Element:
        if isinstance(other, Element):
            return other
        return Element(self.basis, {0: other})

    def __add__(self, other) -> Element:
        other = self._lift(other)
        terms = dict(self.terms)
        for b, c in other.terms.items():
            terms[b] = terms[b] + c if b in terms else c
        return Element(self.basis, terms)

    __radd__ = __add__

    def __neg__(self) -> Element:
        return Element(self.basis, {b: -c for b, c in self.terms.items()})

    def __sub__(self, other) -> Element:
        return self + (-self._lift(other))

    def __rsub__(self, other) -> Element:
        return self._lift(other) - self

    def scale(self, factor) -> Element:
        """Every coefficient times ``factor`` (a ring element).

        Examples
        --------
        >>> from ga_rotors.symbolic.prover.basis import Basis
        >>> Element(Basis(1), {0: 1, 1: 2}).scale(3)
        3 + 6*e1
        """
        return Element(self.basis, {b: c * factor for b, c in self.terms.items()})

    def is_zero(self) -> bool:
        """True when every coefficient is zero.

        Examples
        --------
        >>> from ga_rotors.symbolic.prover.basis import Basis
        >>> e1 = Element.blade(Basis(1), 1, 1)
        >>> (e1 * e1 - 1).is_zero()
        True
        """
        return not self.terms

    def grades(self) -> set[int]:
        """Grades with a nonzero part.

        Examples
        --------
        >>> from ga_rotors.symbolic.prover.basis import Basis
        >>> Element(Basis(3), {0: 1, 0b111: 1}).grades()
        {0, 3}
        """
        return {b.bit_count() for b in self.terms}

    # -- products ----------------------------------------------------------------------
    def _product(self, other, keep: Callable[[int, int], bool] | None) -> Element:
        other = self._lift(other)
        sign = self.basis._sign
        out: dict[int, object] = {}
        for a, ca in self.terms.items():
            row = sign[a]
            for b, cb in other.terms.items():
                s = row[b]
                if not s or (keep is not None and not keep(a, b)):
                    continue
                blade = a ^ b
                term = ca * cb
                if blade in out:
                    out[blade] = out[blade] + term if s > 0 else out[blade] - term
                else:
                    out[blade] = term if s > 0 else -term
        return Element(self.basis, out)

    def __mul__(self, other) -> Element:
        return self._product(other, None)

    def __rmul__(self, other) -> Element:
        return self._lift(other) * self

    def __xor__(self, other) -> Element:
        return self._product(other, lambda a, b: not a & b)

    def __rxor__(self, other) -> Element:
        return self._lift(other) ^ self

    def lc(self, other) -> Element:
        """Left contraction A ⌋ B.

        Examples
        --------
        >>> from ga_rotors.symbolic.prover.basis import Basis
        >>> e = [Element.blade(Basis(3), 1 << i, 1) for i in range(3)]
        >>> e[0].lc(e[0] ^ e[1]), (e[0] ^ e[1]).lc(e[0])
        (e2, 0)
        """
        return self._product(other, lambda a, b: not a & ~b)

    def rc(self, other) -> Element:
        """Right contraction A ⌊ B.

        Examples
        --------
        >>> from ga_rotors.symbolic.prover.basis import Basis
        >>> e = [Element.blade(Basis(3), 1 << i, 1) for i in range(3)]
        >>> (e[0] ^ e[1]).rc(e[1])
        e1
        """
        return self._product(other, lambda a, b: not b & ~a)

    def __or__(self, other) -> Element:
        return self._product(other, lambda a, b: a and b and (not a & ~b or not b & ~a))

    def __ror__(self, other) -> Element:
        return self._lift(other) | self

    def dot(self, other) -> Element:
        """The fat dot (Dorst, Fontijne & Mann): grade |r − s| part, scalars included.

        Examples
        --------
        >>> from ga_rotors.symbolic.prover.basis import Basis
        >>> e1 = Element.blade(Basis(2), 1, 1)
        >>> e1.dot(3), e1 | 3
        (3*e1, 0)
        """
        return self._product(other, lambda a, b: not a & ~b or not b & ~a)

    def scalar_product(self, other) -> Element:
        """⟨A B⟩₀ as a grade-0 element.

        Examples
        --------
        >>> from ga_rotors.symbolic.prover.basis import Basis
        >>> e12 = Element.blade(Basis(2), 3, 1)
        >>> e12.scalar_product(e12)
        -1
        """
        return self._product(other, lambda a, b: a == b)

    def commutator(self, other) -> Element:
        """The commutator product ½(AB − BA).

        Examples
        --------
        >>> from fractions import Fraction
        >>> from ga_rotors.symbolic.prover.basis import Basis
        >>> e = [Element.blade(Basis(2), 1 << i, Fraction(1)) for i in range(2)]
        >>> e[0].commutator(e[1])
        e12
        """
        other = self._lift(other)
        return Element(
            self.basis,
            {b: c / 2 for b, c in (self * other - other * self).terms.items()},
        )

    # -- involutions, projections, dual --------------------------------------------------
    def _signed(self, sign_of_grade: Callable[[int], int]) -> Element:
        return Element(
            self.basis,
            {b: c if sign_of_grade(b.bit_count()) > 0 else -c for b, c in self.terms.items()},
        )

    def __invert__(self) -> Element:
        return self._signed(_reverse_sign)

    def involute(self) -> Element:
        """Grade involution: (−1)^r on grade r.

        Examples
        --------
        >>> from ga_rotors.symbolic.prover.basis import Basis
        >>> Element(Basis(2), {0: 1, 1: 1, 3: 1}).involute()
        1 - e1 + e12
        """
        return self._signed(lambda k: -1 if k % 2 else 1)

    def conjugate(self) -> Element:
        """Clifford conjugate: reverse and grade involution.

        Examples
        --------
        >>> from ga_rotors.symbolic.prover.basis import Basis
        >>> Element(Basis(2), {1: 1, 3: 1}).conjugate()
        -e1 - e12
        """
        return self._signed(lambda k: _reverse_sign(k) * (-1 if k % 2 else 1))

    def grade(self, k: int) -> Element:
        """⟨A⟩_k.

        Examples
        --------
        >>> from ga_rotors.symbolic.prover.basis import Basis
        >>> Element(Basis(2), {0: 4, 1: 2, 3: 1}).grade(1)
        2*e1
        """
        return Element(self.basis, {b: c for b, c in self.terms.items() if b.bit_count() == k})

    def complement(self, right: bool = True) -> Element:
        """The right (or left) complement: e_A ↦ s e_Ā with e_A ∧ s e_Ā = I (s e_Ā ∧ e_A = I).

        Metric-free, so defined in every signature; the left complement undoes the right.

        Examples
        --------
        >>> from ga_rotors.symbolic.prover.basis import Basis
        >>> e1 = Element.blade(Basis(3, 0, 1), 0b0010, 1)
        >>> e1.complement(), e1.complement().complement(right=False)
        (-e023, e1)
        """
        basis = self.basis
        return Element(
            basis,
            {
                basis.full ^ b: c if basis.complement_sign(b, right) > 0 else -c
                for b, c in self.terms.items()
            },
        )

    def dual(self) -> Element:
        """A I⁻¹ when I² ≠ 0 (r = 0); the Poincaré dual (right complement) when r > 0.

        In a degenerate metric I² = 0 and A I⁻¹ does not exist; plane-based GA (and
        ``clifford``'s ``dual`` in such a layout) uses the metric-free right complement
        instead, for which e_A ∧ dual(e_A) = I on every basis blade.

        Examples
        --------
        >>> from ga_rotors.symbolic.prover.basis import Basis
        >>> Element.blade(Basis(3), 0b001, 1).dual()    # e1 I⁻¹ = −e1 e123
        -e23
        >>> Element.blade(Basis(3, 0, 1), 0b0001, 1).dual()   # e0 ↦ e123 in PGA
        e123
        """
        basis = self.basis
        square = basis.pseudoscalar_square
        if not square:
            return self.complement(right=True)
        # I⁻¹ = I / I² and I² = ±1, so I⁻¹ = I² · I.
        return self * Element(basis, {basis.full: square})

    def undual(self) -> Element:
        """The inverse of :meth:`dual`: A I when r = 0, the left complement when r > 0.

        Examples
        --------
        >>> from ga_rotors.symbolic.prover.basis import Basis
        >>> x = Element(Basis(3, 0, 1), {0b0001: 2, 0b0110: 3})
        >>> x.dual().undual().terms == x.terms, Element(Basis(1, 3), {1: 1}).dual().undual()
        (True, e1)
        """
        basis = self.basis
        if not basis.pseudoscalar_square:
            return self.complement(right=False)
        return self * Element(basis, {basis.full: 1})

    def vee(self, other) -> Element:
        """The regressive product A ∨ B = undual-by-complement(Ā ∧ B̄), metric-free.

        Defined as ``clifford`` defines ``vee`` (and ``&``): the left complement of the
        outer product of the right complements, in every signature.

        Examples
        --------
        >>> from ga_rotors.symbolic.prover.basis import Basis
        >>> b = Basis(3)
        >>> e12, e23 = Element.blade(b, 0b011, 1), Element.blade(b, 0b110, 1)
        >>> e12.vee(e23)          # the xy and yz planes meet in the y axis
        e2
        """
        other = self._lift(other)
        return (self.complement() ^ other.complement()).complement(right=False)

    # -- display -----------------------------------------------------------------------
    def _parts(self, show: Callable[[object], str]) -> list[tuple[str, str]]:
        parts = []
        for blade in self.basis.blades:
            if blade in self.terms:
                parts.append((show(self.terms[blade]), self.basis.name(blade)))
        return parts

    def __repr__(self) -> str:
        if not self.terms:
            return "0"
        text = []
        for coeff, name in self._parts(str):
            atomic = not any(op in coeff.lstrip("-") for op in "+- ")
            if name == "1":
                text.append(coeff)
            elif coeff == "1":
                text.append(name)
            elif coeff == "-1":
                text.append("-" + name)
            else:
                text.append(f"{coeff}*{name}" if atomic else f"({coeff})*{name}")
        return " + ".join(text).replace("+ -", "- ")

    def _repr_latex_(self) -> str:
        """The element as LaTeX (Jupyter calls this).

        Examples
        --------
        >>> from ga_rotors.symbolic.prover.basis import Basis
        >>> Element(Basis(2), {0: 2, 3: -1})._repr_latex_()
        '$2 - e_{12}$'
        """
        return f"${self.latex()}$"

    def latex(self) -> str:
        """The LaTeX of the element (no dollar signs).

        Examples
        --------
        >>> from ga_rotors.symbolic.prover.basis import Basis
        >>> Element(Basis(3), {1: 3, 0b110: 1}).latex()
        '3 e_{1} + e_{23}'
        """
        from ..algebra import latex_sum  # sympy only when LaTeX is asked for

        ordered = [b for b in self.basis.blades if b in self.terms]
        return latex_sum((self.terms[b], self.basis.name(b)) for b in ordered)
