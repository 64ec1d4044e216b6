"""The basis of Cl(p, q, r): blades as bit masks, their order, names and products.

Basis vectors e1 ... en, n = p + q + r, are ordered as ``clifford.Cl(p, q, r)`` orders
them: the r null vectors first (e_i² = 0), then the p that square to +1, then the q
that square to -1. So in Cl(3, 0, 1) (plane-based geometric algebra) e1 is the null
vector and e2, e3, e4 square to +1. A basis blade is a bit mask (bit i set when e_{i+1}
is a factor), listed by grade then lexicographically, as clifford lists them.

Examples
--------
>>> pga = Basis(3, 0, 1)
>>> pga.metric
(0, 1, 1, 1)
>>> [pga.name(b) for b in pga.blades[:6]]
['1', 'e1', 'e2', 'e3', 'e4', 'e12']
>>> pga.product(0b0011, 0b0011)          # e12 e12 = 0: e1 is null
(0, 0)
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
        """'1', or 'e' followed by the 1-based indices of the blade's vectors.

        Examples
        --------
        >>> Basis(3).name(0b101)
        'e13'
        """
        if not blade:
            return "1"
        return "e" + "".join(str(i + 1) for i in range(self.n) if blade >> i & 1)

    def blade_from_indices(self, indices: tuple[int, ...]) -> tuple[int, int]:
        """(sign, blade) of the product e_i e_j ... of distinct 1-based indices.

        Examples
        --------
        >>> Basis(3).blade_from_indices((3, 1))    # e31 = -e13
        (-1, 5)
        """
        sign, blade = 1, 0
        for i in indices:
            if not 1 <= i <= self.n:
                raise ValueError(f"e{i}: no basis vector e{i} in {self.label()}")
            bit = 1 << (i - 1)
            if blade & bit:
                raise ValueError(f"basis blade repeats e{i}")
            sign *= _reorder_sign(blade, bit)
            blade |= bit
        return sign, blade

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
