"""Where the numbers come from: the domains a proof, a pre-check and a check compute in.

A domain gives ``param(name)`` (a free parameter), ``const(q)`` (a rational) and, for the
quantities that are not polynomials in the parameters, a symbol tied to them by one
relation (a :class:`Relation`):

============== =========================== ==================================================
method         relation                    used for
============== =========================== ==================================================
normaliser     c² λ = 1                    unit vectors, rotors (c = ±1/√λ)
exp_pair       C² − δ S² = 1               exp(X) = C + S X with X² = δ a scalar
reciprocal     ι λ = 1                     inverse, division, negative powers, down
root           ρ² = μ, ρ ≥ 0               norm(x) = √⟨x x̃⟩₀
log_factor     none (ι φ = 1 for its S)    log(R) = φ ⟨R⟩₂ with exp(log R) = ⟨R⟩₀ + ⟨R⟩₂/…
============== =========================== ==================================================

The domains:

* :class:`Polynomials` — polynomials over ℚ in every parameter and symbol (the exact
  proof); a quantity that reduces to a constant (``R R̃`` of a rotor) is that constant;
* :class:`Draws` — numpy arrays, one column per random rational draw (the pre-check);
* :class:`Point` — one rational point, the symbols kept (the exact check of a suspect);
  :func:`exact_values` then gives each symbol's exact value there.

:func:`reduce_modulo` reduces a polynomial modulo the relations a domain collected (a zero
result proves the polynomial vanishes wherever the relations hold); :func:`value_modulo`
gives an equal polynomial where one exists (a quantity whose value is wanted).

Examples
--------
>>> dom = Polynomials(["x", "c"])
>>> c = dom.normaliser("c", dom.param("x") ** 2)       # c² x² = 1
>>> reduce_modulo(c**2 * dom.param("x") ** 2 - 1, dom)
0
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

import numpy as np
import sympy
from sympy.polys.domains import QQ
from sympy.polys.rings import PolyRing

from .element import Element

__all__ = [
    "Draws",
    "InvalidPoint",
    "NotInvertible",
    "NotReal",
    "Point",
    "Polynomials",
    "Relation",
    "exact_values",
    "reduce_modulo",
    "value_modulo",
]


class NotInvertible(ValueError):
    """A quantity to invert is zero wherever the assumptions hold (the message says which).

    Examples
    --------
    >>> Polynomials(["x"]).reciprocal("i", Polynomials(["x"]).const(0))
    Traceback (most recent call last):
    ...
    ga_rotors.symbolic.prover.domains.NotInvertible: it is 0 for every value of the symbols
    """


class NotReal(ValueError):
    """A square root of a quantity that is negative wherever the assumptions hold.

    Examples
    --------
    >>> Polynomials(["x"]).root("r", Polynomials(["x"]).const(-2))
    Traceback (most recent call last):
    ...
    ga_rotors.symbolic.prover.domains.NotReal: it is -2 < 0 for every value of the symbols
    """


class InvalidPoint(Exception):
    """The point breaks an assumption: λ ≤ 0 for a normaliser, an inverse of 0, a square root
    of a negative number or a rotor without a real log there.

    Examples
    --------
    >>> Point({"x": Fraction(0)}, {}, ["c"]).normaliser("c", Polynomials(["z"]).const(0))
    Traceback (most recent call last):
    ...
    ga_rotors.symbolic.prover.domains.InvalidPoint: c
    """


@dataclass(frozen=True)
class Relation:
    """One symbol (or pair) and the polynomial relation that ties it to the parameters.

    ``kind`` is ``"normaliser"`` (c² λ = 1), ``"exp"`` (C² − δ S² = 1), ``"reciprocal"``
    (ι λ = 1), ``"root"`` (ρ² = μ) or ``"log"`` (φ, no relation: its exact value is the
    principal log's factor, from a = ⟨R⟩₀ and β = ⟨R⟩₂²).

    Examples
    --------
    >>> dom = Polynomials(["x", "i"], {("inv", "x"): ("i",)})
    >>> _ = dom.reciprocal(("inv", "x"), 1 + dom.param("x") ** 2)
    >>> dom.relations[0].kind, dom.relations[0].names
    ('reciprocal', ('i',))
    """

    kind: str
    names: tuple[str, ...]
    polys: tuple


def _ring_value(ring, q: Fraction):
    return ring(QQ(q.numerator, q.denominator))


class Polynomials:
    """Polynomials over ℚ in every free parameter and every symbol of a relation.

    Parameters
    ----------
    names : list of str
        The ring's generators: parameters, normalisers and the symbols of ``symbols``.
    symbols : dict, optional
        ``key -> names`` of the symbols an expression may need (exp pairs, reciprocals,
        roots, log factors), allocated before evaluation by :func:`.evaluate.symbol_keys`.

    Examples
    --------
    >>> dom = Polynomials(["x", "y"])
    >>> dom.param("x") * dom.const(Fraction(1, 2)) + dom.param("y")
    1/2*x + y
    """

    def __init__(self, names: list[str], symbols: dict | None = None):
        self.ring = PolyRing(names, QQ)
        self.gen = dict(zip(names, self.ring.gens, strict=True))
        self.symbols = symbols or {}
        self.relations: list[Relation] = []
        self._shared: dict = {}  # (kind, polynomials) -> the symbols already made for them

    # -- numbers -----------------------------------------------------------------------
    def param(self, name):
        return self.gen[name]

    def const(self, q):
        return _ring_value(self.ring, Fraction(q))

    def _names(self, key, default: tuple[str, ...]) -> tuple[str, ...]:
        return self.symbols.get(key, default)

    def _register(self, kind, names, polys):
        self.relations.append(Relation(kind, tuple(names), tuple(polys)))

    # -- symbols tied by relations ---------------------------------------------------------
    def normaliser(self, name, lam):
        self._register("normaliser", (name,), (lam,))
        return self.gen[name]

    def exp_pair(self, key, delta):
        if not delta:  # X² = 0 identically: exp(X) = 1 + X exactly
            return self.ring.one, self.ring.one
        c, s = self.symbols[key]
        if not any(r.kind == "exp" and r.names[0] == c for r in self.relations):
            self._register("exp", (c, s), (delta,))
        return self.gen[c], self.gen[s]

    def reciprocal(self, key, lam):
        """1/λ: a constant when λ reduces to one, else a symbol ι with ι λ = 1."""
        value = value_modulo(lam, self)
        value = lam if value is None else value
        if value.is_ground:
            if not value:
                raise NotInvertible("it is 0 for every value of the symbols")
            return self.const(1 / Fraction(str(value.LC)))
        if not reduce_modulo(value, self):
            raise NotInvertible("it is 0 for every value of the symbols")
        shared = self._shared.get(("reciprocal", value))
        if shared is not None:
            return shared
        (name,) = self._names(key, (None,))
        if name is None:  # pragma: no cover - symbol_keys allocates every key evaluate uses
            raise KeyError(key)
        self._register("reciprocal", (name,), (value,))
        self._shared[("reciprocal", value)] = self.gen[name]
        return self.gen[name]

    def root(self, key, mu):
        """√μ ≥ 0: a constant when μ reduces to a rational square, else ρ with ρ² = μ."""
        value = value_modulo(mu, self)
        value = mu if value is None else value
        if value.is_ground:
            q = Fraction(str(value.LC)) if value else Fraction(0)
            if q < 0:
                raise NotReal(f"it is {q} < 0 for every value of the symbols")
            num, den = math.isqrt(q.numerator), math.isqrt(q.denominator)
            if num * num == q.numerator and den * den == q.denominator:
                return self.const(Fraction(num, den))
        shared = self._shared.get(("root", value))
        if shared is not None:
            return shared
        (name,) = self._names(key, (None,))
        self._register("root", (name,), (value,))
        self._shared[("root", value)] = self.gen[name]
        return self.gen[name]

    def log_factor(self, key, a, beta):
        """(φ, 1/φ) for log(R) = φ ⟨R⟩₂, R = a + ⟨R⟩₂ with ⟨R⟩₂² = β (shared per (a, β))."""
        a_value = value_modulo(a, self)
        beta_value = value_modulo(beta, self)
        a = a if a_value is None else a_value
        beta = beta if beta_value is None else beta_value
        if beta.is_ground and not beta:  # a null bivector: R = 1 + b, log R = b exactly
            return self.ring.one, self.ring.one
        shared = self._shared.get(("log", a, beta))
        if shared is not None:
            return shared
        phi, inverse = self.symbols[key]
        self._register("log", (phi,), (a, beta))
        self._register("reciprocal", (inverse,), (self.gen[phi],))
        self._shared[("log", a, beta)] = self.gen[phi], self.gen[inverse]
        return self._shared[("log", a, beta)]

    # -- tests on elements, modulo the relations ---------------------------------------------
    def scalar_value(self, x: Element):
        """The scalar part of x when every other part vanishes modulo the relations, else None."""
        if any(b and reduce_modulo(c, self) for b, c in x.terms.items()):
            return None
        return x.terms.get(0, self.ring.zero)

    def is_scalar(self, x: Element) -> bool:
        return self.scalar_value(x) is not None

    def lies_in(self, x: Element, blades) -> bool:
        """True when every part of x outside ``blades`` vanishes modulo the relations."""
        return not any(b not in blades and reduce_modulo(c, self) for b, c in x.terms.items())

    def is_zero(self, x: Element) -> bool:
        return self.lies_in(x, ())


class Draws:
    """Float arrays: column j of every coefficient is random draw j.

    The exact rational value of every draw is kept (``exact``), so a draw where the two
    sides differ can be checked exactly. A draw where an assumption cannot hold (λ ≤ 0 for
    a normaliser, an inverse of about 0, …) is marked invalid in ``valid``; so is one whose
    numbers overflow a float.

    Examples
    --------
    >>> d = Draws(4, seed=0)
    >>> x = d.param("x")
    >>> x.shape, [float(v) for v in d.exact["x"]] == list(x)
    ((4,), True)
    >>> d.const(10**400)
    inf
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
        try:
            return float(q)
        except OverflowError:  # a constant beyond a float: the pre-check cannot use it
            return math.inf if q > 0 else -math.inf

    def _column(self, x):
        return np.broadcast_to(np.asarray(x, dtype=float), (self.count,))

    def normaliser(self, name, lam):
        lam = self._column(lam)
        ok = lam > 1e-6
        self.valid &= ok
        # the sign of c is free (−v is a unit vector, −R a rotor): draw it too
        sign = self.signs.setdefault(name, self.rng.choice([-1.0, 1.0], size=self.count))
        return sign / np.sqrt(np.where(ok, lam, 1.0))

    def reciprocal(self, key, lam):
        lam = self._column(lam)
        ok = np.abs(lam) > 1e-9
        self.valid &= ok
        return 1.0 / np.where(ok, lam, 1.0)

    def root(self, key, mu):
        mu = self._column(mu)
        self.valid &= mu >= -1e-12
        return np.sqrt(np.maximum(mu, 0.0))

    def log_factor(self, key, a, beta):
        a, beta = self._column(a), self._column(beta)
        root = np.sqrt(np.abs(beta))
        safe = np.where(root > 0, root, 1.0)
        elliptic = np.arctan2(root, a) / safe
        hyperbolic = np.arcsinh(root) / safe
        phi = np.where(beta < 0, elliptic, np.where(beta > 0, hyperbolic, 1.0))
        # no real log: a hyperbolic or null rotor on the branch a < 0 (−exp(B)), or −1
        self.valid &= ~((beta >= 0) & (a < 0)) & ~((root == 0) & (np.abs(a - 1) > 1e-9))
        self.valid &= ~((beta < 0) & (root < 1e-12) & (a < 0))
        return phi, 1.0 / phi

    def _valid(self, c) -> np.ndarray:
        """|c| at the draws that satisfy the assumptions (all of them if none does)."""
        column = np.abs(self._column(c))
        return column[self.valid] if self.valid.any() else column

    def _small(self, c, scale) -> bool:
        return bool(np.all(self._valid(c) <= 1e-9 * scale))

    def _scale(self, x: Element) -> float:
        return 1.0 + max((np.max(self._valid(c)) for c in x.terms.values()), default=0.0)

    def scalar_value(self, x: Element):
        scale = self._scale(x)
        if not all(self._small(c, scale) for b, c in x.terms.items() if b):
            return None
        return x.terms.get(0, 0.0)

    def is_scalar(self, x: Element) -> bool:
        return self.scalar_value(x) is not None

    def lies_in(self, x: Element, blades) -> bool:
        scale = self._scale(x)
        return all(self._small(c, scale) for b, c in x.terms.items() if b not in blades)

    def is_zero(self, x: Element) -> bool:
        return self.lies_in(x, ())

    def exp_pair(self, key, delta):
        delta = self._column(delta)
        theta = np.sqrt(np.abs(delta))
        big = theta > 30
        self.valid &= ~big
        theta = np.where(big, 0.0, theta)
        c = np.where(delta < 0, np.cos(theta), np.cosh(theta))
        safe = np.where(theta > 0, theta, 1.0)
        s = np.where(theta > 0, np.where(delta < 0, np.sin(theta), np.sinh(theta)) / safe, 1.0)
        return c, s


class Point(Polynomials):
    """One rational point: free parameters are numbers, the relations' symbols stay symbols.

    Examples
    --------
    >>> pt = Point({"x": Fraction(3, 2)}, {}, ["c"])
    >>> pt.param("x") * pt.normaliser("c", pt.const(4))
    3/2*c
    """

    def __init__(self, values: dict[str, Fraction], signs: dict[str, float], names, symbols=None):
        super().__init__(names, symbols)
        self.values = values
        self.signs = signs

    def param(self, name):
        return self.const(self.values[name])

    def normaliser(self, name, lam):
        if not lam.is_ground or lam.LC <= 0:
            raise InvalidPoint(name)
        return super().normaliser(name, lam)

    def reciprocal(self, key, lam):
        try:
            return super().reciprocal(key, lam)
        except NotInvertible:
            raise InvalidPoint(str(key)) from None

    def root(self, key, mu):
        try:
            return super().root(key, mu)
        except NotReal:
            raise InvalidPoint(str(key)) from None


def _split(f, i: int) -> dict[int, object]:
    """f = Σ_e x_i^e f_e: {e: f_e} with x_i removed from f_e."""
    parts: dict[int, dict] = {}
    for monom, coeff in f.terms():
        e = monom[i]
        parts.setdefault(e, {})[(*monom[:i], 0, *monom[i + 1 :])] = coeff
    return {e: f.ring.from_dict(d) for e, d in parts.items()}


def _reduce(f, domain: Polynomials, exact: bool):
    ring = domain.ring
    for rel in reversed(domain.relations):
        if rel.kind == "log":
            continue  # φ is free: its only relation is its reciprocal's
        gen = domain.gen[rel.names[0]]
        i = ring.gens.index(gen)
        parts = _split(f, i)
        if set(parts) <= {0}:
            continue
        (poly,) = rel.polys
        f = ring.zero
        if rel.kind == "exp":  # C² = 1 + δ S²
            q = 1 + poly * domain.gen[rel.names[1]] ** 2
            for e, fe in parts.items():
                f += gen ** (e % 2) * q ** (e // 2) * fe
        elif rel.kind == "root":  # ρ² = μ
            for e, fe in parts.items():
                f += gen ** (e % 2) * poly ** (e // 2) * fe
        else:  # normaliser c² λ = 1 (keep c, c² = 1/λ) or reciprocal ι λ = 1 (ι = 1/λ)
            step = 2 if rel.kind == "normaliser" else 1
            top = max(e // step for e in parts)
            for e, fe in parts.items():
                keep = gen ** (e % step)
                if exact:
                    quotient, remainder = fe.div(poly ** (e // step))
                    if remainder:
                        return None
                    f += keep * quotient
                else:
                    f += keep * poly ** (top - e // step) * fe
    return f


def reduce_modulo(f, domain: Polynomials):
    """f modulo every relation of the domain, denominators cleared.

    Each symbol is eliminated in the reverse order of its making (a relation only
    mentions symbols made before it): C² = 1 + δ S², ρ² = μ, and c² = 1/λ, ι = 1/λ with
    λ's powers cleared (multiplying by λ, which is nonzero where the relation holds). The
    result is zero only if f vanishes wherever the relations hold (both signs of c and C
    lie on them): a zero result is a proof.

    Examples
    --------
    >>> dom = Polynomials(["x", "c"])
    >>> c = dom.normaliser("c", 1 + dom.param("x") ** 2)
    >>> reduce_modulo(c**3, dom)           # c³ = c / λ, cleared of λ
    c
    """
    return _reduce(f, domain, exact=False)


def value_modulo(f, domain: Polynomials):
    """A polynomial equal to f wherever the relations hold, with the symbols' powers
    reduced, or None when that needs dividing by a λ that does not divide.

    Examples
    --------
    >>> dom = Polynomials(["x", "c"])
    >>> lam = 1 + dom.param("x") ** 2
    >>> c = dom.normaliser("c", lam)
    >>> value_modulo(c**2 * lam, dom), value_modulo(c**2, dom) is None
    (1, True)
    """
    return _reduce(f, domain, exact=True)


def to_sympy(f, values: dict[str, sympy.Expr]) -> sympy.Expr:
    """A polynomial of a domain's ring as a SymPy expression, with ``values`` substituted.

    Examples
    --------
    >>> dom = Polynomials(["x", "y"])
    >>> to_sympy(dom.param("x") * dom.param("y"), {"y": sympy.Integer(3)})
    3*x
    """
    return f.as_expr().subs({sympy.Symbol(n): v for n, v in values.items()}, simultaneous=True)


def exact_values(domain: Point) -> dict[str, sympy.Expr]:
    """The exact value of every symbol of a :class:`Point`'s relations, in order.

    Normalisers are ±1/√λ (the draw's sign), exp's C and S cos/sin, cosh/sinh or 1 of √|δ|,
    reciprocals 1/λ, roots √μ, and a log's φ the principal angle over √|β|.

    Raises
    ------
    InvalidPoint
        A relation has no real solution at this point (an inverse of 0, the square root of a
        negative number, a rotor with no real log).

    Examples
    --------
    >>> pt = Point({}, {}, ["c", "r"], {("root", 0): ("r",)})
    >>> _ = pt.normaliser("c", pt.const(4))
    >>> _ = pt.root(("root", 0), pt.const(2))
    >>> exact_values(pt)
    {'c': 1/2, 'r': sqrt(2)}
    """
    subst: dict[str, sympy.Expr] = {}
    for rel in domain.relations:
        polys = [sympy.nsimplify(sympy.expand(to_sympy(p, subst))) for p in rel.polys]
        if rel.kind == "normaliser":
            sign = int(domain.signs.get(rel.names[0], 1))
            subst[rel.names[0]] = sign / sympy.sqrt(polys[0])
        elif rel.kind == "exp":
            (d,) = polys
            theta = sympy.sqrt(sympy.Abs(d))
            c, s = rel.names
            if d == 0:
                subst[c], subst[s] = sympy.Integer(1), sympy.Integer(1)
            elif d < 0:
                subst[c], subst[s] = sympy.cos(theta), sympy.sin(theta) / theta
            else:
                subst[c], subst[s] = sympy.cosh(theta), sympy.sinh(theta) / theta
        elif rel.kind == "reciprocal":
            (lam,) = polys
            if _is_zero(lam):
                raise InvalidPoint(rel.names[0])
            subst[rel.names[0]] = 1 / lam
        elif rel.kind == "root":
            (mu,) = polys
            if _sign(mu) < 0:
                raise InvalidPoint(rel.names[0])
            subst[rel.names[0]] = sympy.sqrt(mu)
        else:  # log: R = a + b, b² = β
            a, beta = polys
            subst[rel.names[0]] = _log_factor(a, beta, rel.names[0])
    return subst


def _sign(x: sympy.Expr) -> int:
    value = sympy.N(x, 60)
    if abs(value) < sympy.Float(10) ** -50:
        return 0
    return 1 if value > 0 else -1


def _is_zero(x: sympy.Expr) -> bool:
    return _sign(x) == 0


def _log_factor(a, beta, name) -> sympy.Expr:
    s = _sign(beta)
    if s < 0:
        root = sympy.sqrt(-beta)
        return sympy.atan2(root, a) / root
    if s > 0:
        if _sign(a) <= 0:  # −exp(B) for a hyperbolic B: no real log
            raise InvalidPoint(name)
        root = sympy.sqrt(beta)
        return sympy.asinh(root) / root
    if not _is_zero(a - 1):  # a null bivector's exp is 1 + b: a must be 1
        raise InvalidPoint(name)
    return sympy.Integer(1)
