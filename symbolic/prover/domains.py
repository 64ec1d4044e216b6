"""Where the numbers come from: the domains a proof, a pre-check and a check compute in.

A domain gives ``param(name)`` (a free parameter), ``const(q)`` (a rational),
``normaliser(name, lam)`` (a c with c² λ = 1), ``exp_pair(node, delta)`` (the C, S of
exp(X) = C + S X, C² − δ S² = 1) and ``is_scalar(x)``:

* :class:`Polynomials` — polynomials over ℚ in every parameter (the exact proof);
* :class:`Draws` — numpy arrays, one column per random rational draw (the pre-check);
* :class:`Point` — one rational point, normalisers and exp kept symbolic (the exact
  check of a counterexample).

:func:`reduce_modulo` reduces a polynomial modulo the relations a domain collected.

Examples
--------
>>> dom = Polynomials(["x", "c"])
>>> c = dom.normaliser("c", dom.param("x") ** 2)       # c² x² = 1
>>> reduce_modulo(c**2 * dom.param("x") ** 2 - 1, dom)
0
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
from sympy.polys.domains import QQ
from sympy.polys.rings import PolyRing

from .element import Element
from .grammar import Node

__all__ = ["Draws", "InvalidPoint", "Point", "Polynomials", "reduce_modulo"]


class Polynomials:
    """Polynomials over ℚ in every free parameter, normaliser and exp coefficient.

    Examples
    --------
    >>> dom = Polynomials(["x", "y"])
    >>> dom.param("x") * dom.const(Fraction(1, 2)) + dom.param("y")
    1/2*x + y
    """

    def __init__(self, names: list[str], exp_names: dict[Node, tuple[str, str]] | None = None):
        self.ring = PolyRing(names, QQ)
        self.gen = dict(zip(names, self.ring.gens, strict=True))
        self.norms: list[tuple[str, object]] = []  # (normaliser, λ)
        self.exps: list[tuple[str, str, object]] = []  # (C, S, δ)
        self.exp_names = exp_names or {}  # exp(X) node -> names of its C and S

    def param(self, name):
        return self.gen[name]

    def const(self, q):
        q = Fraction(q)
        return self.ring(QQ(q.numerator, q.denominator))

    def normaliser(self, name, lam):
        self.norms.append((name, lam))
        return self.gen[name]

    def is_scalar(self, x: Element) -> bool:
        return not x.grades() - {0}

    def exp_pair(self, node, delta):
        if not delta:  # X² = 0 identically: exp(X) = 1 + X exactly
            return self.ring.one, self.ring.one
        c, s = self.exp_names[node]
        if not any(c == name for name, _, _ in self.exps):
            self.exps.append((c, s, delta))
        return self.gen[c], self.gen[s]


class Draws:
    """Float arrays: column j of every coefficient is random draw j.

    The exact rational value of every draw is kept (``exact``), so a draw where the two
    sides differ can be checked exactly.

    Examples
    --------
    >>> d = Draws(4, seed=0)
    >>> x = d.param("x")
    >>> x.shape, [float(v) for v in d.exact["x"]] == list(x)
    ((4,), True)
    """

    def __init__(self, count: int, seed: int):
        self.count = count
        self.rng = np.random.default_rng(seed)
        self.exact: dict[str, list[Fraction]] = {}
        self.signs: dict[str, np.ndarray] = {}
        self.valid = np.ones(count, dtype=bool)

    def param(self, name):
        if name not in self.exact:
            num = self.rng.integers(-5, 6, size=self.count)
            den = self.rng.integers(1, 4, size=self.count)
            self.exact[name] = [Fraction(int(a), int(b)) for a, b in zip(num, den, strict=True)]
        return np.array([float(x) for x in self.exact[name]])

    def const(self, q):
        return float(q)

    def normaliser(self, name, lam):
        lam = np.broadcast_to(np.asarray(lam, dtype=float), (self.count,))
        ok = lam > 1e-6
        self.valid &= ok
        # the sign of c is free (−v is a unit vector, −R a rotor): draw it too
        sign = self.signs.setdefault(name, self.rng.choice([-1.0, 1.0], size=self.count))
        return sign / np.sqrt(np.where(ok, lam, 1.0))

    def is_scalar(self, x: Element) -> bool:
        scale = 1.0 + max((np.max(np.abs(c)) for c in x.terms.values()), default=0.0)
        return all(np.max(np.abs(c)) <= 1e-9 * scale for b, c in x.terms.items() if b)

    def exp_pair(self, node, delta):
        delta = np.broadcast_to(np.asarray(delta, dtype=float), (self.count,))
        theta = np.sqrt(np.abs(delta))
        big = theta > 30
        self.valid &= ~big
        theta = np.where(big, 0.0, theta)
        c = np.where(delta < 0, np.cos(theta), np.cosh(theta))
        safe = np.where(theta > 0, theta, 1.0)
        s = np.where(theta > 0, np.where(delta < 0, np.sin(theta), np.sinh(theta)) / safe, 1.0)
        return c, s


class InvalidPoint(Exception):
    """The point has λ ≤ 0 for a normaliser: no real unit vector or rotor there.

    Examples
    --------
    >>> Point({"x": Fraction(0)}, {}, ["c"]).normaliser("c", Polynomials(["z"]).const(0))
    Traceback (most recent call last):
    ...
    ga_rotors.symbolic.prover.domains.InvalidPoint: c
    """


class Point(Polynomials):
    """One rational point: free parameters are numbers, normalisers and exp stay symbols.

    Examples
    --------
    >>> pt = Point({"x": Fraction(3, 2)}, {}, ["c"])
    >>> pt.param("x") * pt.normaliser("c", pt.const(4))
    3/2*c
    """

    def __init__(
        self,
        values: dict[str, Fraction],
        signs: dict[str, float],
        names: list[str],
        exp_names: dict[Node, tuple[str, str]] | None = None,
    ):
        super().__init__(names, exp_names)
        self.values = values
        self.signs = signs

    def param(self, name):
        return self.const(self.values[name])

    def normaliser(self, name, lam):
        if not lam.is_ground or lam.LC <= 0:
            raise InvalidPoint(name)
        return super().normaliser(name, lam)


def _split(f, i: int) -> dict[int, object]:
    """f = Σ_e x_i^e f_e: {e: f_e} with x_i removed from f_e."""
    parts: dict[int, dict] = {}
    for monom, coeff in f.terms():
        e = monom[i]
        parts.setdefault(e, {})[(*monom[:i], 0, *monom[i + 1 :])] = coeff
    return {e: f.ring.from_dict(d) for e, d in parts.items()}


def reduce_modulo(f, domain: Polynomials):
    """f modulo C² = 1 + δ S² (each exp) and c² λ = 1 (each normaliser, cleared of λ).

    The result has degree ≤ 1 in every C and c, and is zero exactly when f vanishes on
    the variety of the relations (both signs of c and of C lie on it).

    Examples
    --------
    >>> dom = Polynomials(["x", "c"])
    >>> c = dom.normaliser("c", 1 + dom.param("x") ** 2)
    >>> reduce_modulo(c**3, dom)           # c³ = c / λ, cleared of λ
    c
    """
    ring = domain.ring
    for c, s, delta in reversed(domain.exps):
        i = ring.gens.index(domain.gen[c])
        q = 1 + delta * domain.gen[s] ** 2
        parts = _split(f, i)
        f = ring.zero
        for e, fe in parts.items():
            f += domain.gen[c] ** (e % 2) * q ** (e // 2) * fe
    for c, lam in domain.norms:
        i = ring.gens.index(domain.gen[c])
        parts = _split(f, i)
        top = max((e // 2 for e in parts), default=0)
        f = ring.zero
        for e, fe in parts.items():
            f += domain.gen[c] ** (e % 2) * lam ** (top - e // 2) * fe
    return f
