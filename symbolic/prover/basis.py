"""The basis of Cl(p, q, r): blades as bit masks, their order, names and products.

The n = p + q + r basis vectors are ordered as ``clifford.Cl(p, q, r)`` orders them: the
r null vectors first (e² = 0), then the p that square to +1, then the q that square to -1.
A basis blade is a bit mask (bit i set when the i-th basis vector is a factor), listed by
grade then lexicographically, as clifford lists them.

Names follow the literature of each kind of algebra:

* r = 1 (projective GA, Cl(3, 0, 1) for 3D PGA): the null vector is **e0** and the others
  e1 … e(n-1), as in the PGA literature and the project's PGA convention (e0² = 0,
  e1, e2, e3 Euclidean; clifford calls the same vectors e1 … e4);
* otherwise e1 … en, clifford's names (with r ≥ 2 the null vectors are e1 … er).

Examples
--------
>>> pga = Basis(3, 0, 1)
>>> pga.metric
(0, 1, 1, 1)
>>> [pga.name(b) for b in pga.blades[:6]]
['1', 'e0', 'e1', 'e2', 'e3', 'e01']
>>> pga.product(0b0011, 0b0011)          # e01 e01 = 0: e0 is null
(0, 0)
>>> pga.name(pga.full), Basis(1, 3).name(Basis(1, 3).full)
('e0123', 'e1234')
"""

from __future__ import annotations

from functools import cache
from itertools import combinations

__all__ = ["Basis", "cached_basis"]


def _reorder_sign(a: int, b: int) -> int:
    """(-1)^(number of swaps) to bring e_a e_b into increasing index order."""
    swaps = 0
    a >>= 1
    while a:
        swaps += (a & b).bit_count()
        a >>= 1
    return -1 if swaps % 2 else 1


class Basis:
    """Basis blades of Cl(p, q, r) and the multiplication table of their products.

    Parameters
    ----------
    p, q, r : int
        Numbers of basis vectors squaring to +1, -1 and 0 (r null vectors come first).

    Examples
    --------
    >>> sta = Basis(1, 3)
    >>> sta.n, sta.metric
    (4, (1, -1, -1, -1))
    >>> sta.product(0b0001, 0b0010)      # e1 e2 = e12
    (1, 3)
    >>> sta.pseudoscalar_square
    -1
    """

    def __init__(self, p: int, q: int = 0, r: int = 0):
        for name, value in (("p", p), ("q", q), ("r", r)):
            if not isinstance(value, int) or isinstance(value, bool) or value < 0:
                raise ValueError(f"signature: {name} must be a non-negative integer, got {value!r}")
        if p + q + r > 9:
            raise ValueError(f"signature: n = p + q + r = {p + q + r}, at most 9 supported")
        self.p, self.q, self.r = p, q, r
        self.n = p + q + r
        self.metric: tuple[int, ...] = (0,) * r + (1,) * p + (-1,) * q
        self.blades: tuple[int, ...] = tuple(
            sum(1 << i for i in combo)
            for k in range(self.n + 1)
            for combo in combinations(range(self.n), k)
        )
        self.index = {b: i for i, b in enumerate(self.blades)}
        null = sum(1 << i for i, s in enumerate(self.metric) if s == 0)
        size = 1 << self.n
        # _sign[a][b]: the sign s with e_a e_b = s e_(a xor b) (0 when a null factor meets itself)
        self._sign = [[0] * size for _ in range(size)]
        for a in range(size):
            row = self._sign[a]
            for b in range(size):
                common = a & b
                if common & null:
                    continue
                s = _reorder_sign(a, b)
                c, i = common, 0
                while c:
                    if c & 1:
                        s *= self.metric[i]
                    c >>= 1
                    i += 1
                row[b] = s
        self.full = size - 1
        self.pseudoscalar_square = self._sign[self.full][self.full]
        #: the index written for the first basis vector: 0 (e0) in Cl(p, q, 1), else 1.
        self.first_index = 0 if r == 1 else 1

    def __repr__(self) -> str:
        return f"Basis({self.p}, {self.q}, {self.r})"

    def __eq__(self, other) -> bool:
        return isinstance(other, Basis) and self.signature == other.signature

    def __hash__(self) -> int:
        return hash(self.signature)

    @property
    def signature(self) -> tuple[int, int, int]:
        """(p, q, r).

        Examples
        --------
        >>> Basis(2, 1).signature
        (2, 1, 0)
        """
        return (self.p, self.q, self.r)

    def label(self) -> str:
        """'Cl(p,q)' or 'Cl(p,q,r)' when r > 0.

        Examples
        --------
        >>> Basis(3, 0, 1).label(), Basis(1, 3).label()
        ('Cl(3,0,1)', 'Cl(1,3)')
        """
        return f"Cl({self.p},{self.q},{self.r})" if self.r else f"Cl({self.p},{self.q})"

    def product(self, a: int, b: int) -> tuple[int, int]:
        """(sign, blade) with e_a e_b = sign e_blade; sign 0 when the product vanishes.

        Examples
        --------
        >>> Basis(3).product(0b110, 0b001)   # e23 e1 = e123
        (1, 7)
        """
        return self._sign[a][b], a ^ b

    @staticmethod
    def grade(blade: int) -> int:
        """Number of basis vectors in the blade.

        Examples
        --------
        >>> Basis.grade(0b1011)
        3
        """
        return blade.bit_count()

    def name(self, blade: int) -> str:
        """'1', or 'e' followed by the indices of the blade's vectors (e0 first when r = 1).

        Examples
        --------
        >>> Basis(3).name(0b101), Basis(2, 0, 1).name(0b101)
        ('e13', 'e02')
        """
        if not blade:
            return "1"
        first = self.first_index
        return "e" + "".join(str(i + first) for i in range(self.n) if blade >> i & 1)

    def blade_from_indices(self, indices: tuple[int, ...]) -> tuple[int, int]:
        """(sign, blade) of the product e_i e_j ... of distinct indices, as the names write them.

        Examples
        --------
        >>> Basis(3).blade_from_indices((3, 1))    # e31 = -e13
        (-1, 5)
        >>> Basis(3, 0, 1).blade_from_indices((0, 3))    # e03 in PGA
        (1, 9)
        """
        sign, blade = 1, 0
        first = self.first_index
        for i in indices:
            if not first <= i < self.n + first:
                raise ValueError(
                    f"e{i}: no basis vector e{i} in {self.label()}{self._names_hint()}"
                )
            bit = 1 << (i - first)
            if blade & bit:
                raise ValueError(f"basis blade repeats e{i}")
            sign *= _reorder_sign(blade, bit)
            blade |= bit
        return sign, blade

    def _names_hint(self) -> str:
        last = self.n - 1 + self.first_index
        return f" (its basis vectors are e{self.first_index} … e{last})"

    def complement_sign(self, blade: int, right: bool = True) -> int:
        """The sign s of the complement of a basis blade e_A: s e_Ā with Ā the other vectors.

        The right complement has e_A ∧ (s e_Ā) = I, the left one (s e_Ā) ∧ e_A = I
        (Lengyel's complements; clifford's ``right_complement_func`` and
        ``left_complement_func``). Neither uses the metric, so both exist when r > 0.

        Examples
        --------
        >>> pga = Basis(3, 0, 1)
        >>> pga.complement_sign(0b0010), pga.complement_sign(0b0010, right=False)   # e1
        (-1, 1)
        """
        other = self.full ^ blade
        return _reorder_sign(blade, other) if right else _reorder_sign(other, blade)

    def conformal_pair(self) -> tuple[int, int] | None:
        """Bit masks (e₊, e₋) of the conformal model's extra vectors, or None.

        In Cl(p, 1) with p ≥ 2 (r = 0), the conformal model of the Euclidean space spanned
        by e1 … e(p-1): e₊ = e_p squares to +1, e₋ = e_(p+1) to −1, and, as in
        ``clifford.cga`` and ``clifford.g3c``, eo = (e₋ − e₊)/2 and einf = e₊ + e₋.

        Examples
        --------
        >>> Basis(4, 1).conformal_pair(), Basis(3, 0, 1).conformal_pair()
        ((8, 16), None)
        """
        if self.r or self.q != 1 or self.p < 2:
            return None
        return 1 << (self.p - 1), 1 << self.p

    def euclidean_vectors(self) -> list[int] | None:
        """Bit masks of the base space's vectors: e1 … e(p-1) in the conformal Cl(p, 1),
        the vectors squaring to +1 when q = 0 (e1 … ep in PGA); None elsewhere.

        Examples
        --------
        >>> Basis(4, 1).euclidean_vectors(), Basis(3, 0, 1).euclidean_vectors()
        ([1, 2, 4], [2, 4, 8])
        >>> Basis(1, 3).euclidean_vectors() is None
        True
        """
        pair = self.conformal_pair()
        if pair is not None:
            return [1 << i for i in range(self.p - 1)]
        if self.q == 0:
            return self.positive_vectors()
        return None

    def positive_vectors(self) -> list[int]:
        """Bit masks of the basis vectors squaring to +1.

        Examples
        --------
        >>> Basis(1, 1, 1).positive_vectors()
        [2]
        """
        return [1 << i for i, s in enumerate(self.metric) if s == 1]


@cache
def cached_basis(p: int, q: int = 0, r: int = 0) -> Basis:
    """The :class:`Basis` of Cl(p, q, r), built once per process (its table has 4^n entries).

    Examples
    --------
    >>> cached_basis(3, 0, 1) is cached_basis(3, 0, 1)
    True
    """
    return Basis(p, q, r)
