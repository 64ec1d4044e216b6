"""Each declared symbol as an element built from free parameters (see :mod:`.assumptions`).

One construction serves the exact proof, the numeric pre-check and the exact check of a
counterexample: a *domain* supplies the numbers. ``param(name)`` is a free parameter
(a polynomial variable, an array of random draws, or one rational value),
``normaliser(name, lam)`` a c with c² λ = 1, ``const(q)`` a rational constant, and
``is_scalar(x)`` says whether an element is a scalar (within rounding, for draws).

Examples
--------
>>> from fractions import Fraction
>>> from ga_rotors.symbolic.prover.assumptions import Assumptions
>>> from ga_rotors.symbolic.prover.basis import Basis
>>> class Ones:                      # every parameter 1, every normaliser 1
...     def param(self, name): return Fraction(1)
...     def const(self, q): return Fraction(q)
...     def normaliser(self, name, lam): return Fraction(1)
...     def is_scalar(self, x): return not x.grades() - {0}
>>> values = build_values(Assumptions(vectors="a", blades="B:2"), Basis(3), Ones())
>>> values["a"], values["B"]
(e1 + e2 + e3, 0)
"""

from __future__ import annotations

from math import factorial

from .assumptions import Assumptions
from .basis import Basis
from .element import Element

__all__ = ["Unsupported", "build_values", "null_cases", "parameter_names"]


class Unsupported(Exception):
    """The assumptions ask for a construction the prover does not have (the reason).

    Examples
    --------
    >>> raise Unsupported("orthogonality to a null vector")
    Traceback (most recent call last):
    ...
    ga_rotors.symbolic.prover.symbols.Unsupported: orthogonality to a null vector
    """


def _blades_of(basis: Basis, keep) -> list[int]:
    return [b for b in basis.blades if keep(b.bit_count())]


def _grades_of(kind: str, k: int | None):
    """Which grades a generic element of a linear kind has."""
    if kind == "bivector":
        return lambda g: g == 2
    if kind == "kvector":
        return lambda g: g == k
    if kind == "even":
        return lambda g: g % 2 == 0
    return lambda g: True


def _nondegenerate(basis: Basis) -> tuple[list[int], list[int], list[int]]:
    """Indices (0-based) of the null, positive and negative basis vectors."""
    null = [i for i, s in enumerate(basis.metric) if s == 0]
    pos = [i for i, s in enumerate(basis.metric) if s == 1]
    neg = [i for i, s in enumerate(basis.metric) if s == -1]
    return null, pos, neg


def null_cases(basis: Basis) -> int:
    """How many pieces the null cone of the non-degenerate part falls into (1 or 2).

    When the non-degenerate part is Cl(1, 1) the cone is two lines, e1 ± e2 directions,
    and each is proved separately.

    Examples
    --------
    >>> null_cases(Basis(1, 1)), null_cases(Basis(1, 3)), null_cases(Basis(1, 1, 1))
    (2, 1, 2)
    """
    _, pos, neg = _nondegenerate(basis)
    return 2 if len(pos) == 1 and len(neg) == 1 else 1


def parameter_names(assumptions: Assumptions, basis: Basis) -> tuple[list[str], list[str]]:
    """(free parameter names, normaliser names) the symbols are built from.

    Examples
    --------
    >>> from ga_rotors.symbolic.prover.assumptions import Assumptions
    >>> parameter_names(Assumptions(units="n", rotors="R"), Basis(2))
    (['n_1', 'n_2', 'R_e12'], ['c_n', 'c_R'])
    """
    free: list[str] = []
    norms: list[str] = []
    n = basis.n
    null, pos, neg = _nondegenerate(basis)
    for name, kind in assumptions.kinds.items():
        if kind == "scalar":
            free.append(name)
        elif kind in ("vector", "unit"):
            free += [f"{name}_{i + 1}" for i in range(n)]
            if kind == "unit":
                norms.append(f"c_{name}")
        elif kind == "null":
            if pos and neg:
                free += [f"{name}_w{i + 1}" for i in pos + neg] + [f"{name}_s"]
            free += [f"{name}_z{i + 1}" for i in null]
        elif kind == "blade":
            k = assumptions.grade_of(name)
            free += [f"{name}_{j}_{i + 1}" for j in range(1, k + 1) for i in range(n)]
        elif kind == "rotor":
            free += [f"{name}_{basis.name(b)}" for b in _blades_of(basis, lambda g: g == 2)]
            norms.append(f"c_{name}")
        else:
            keep = _grades_of(kind, assumptions.grade_of(name))
            free += [f"{name}_{basis.name(b)}" for b in _blades_of(basis, keep)]
    return free, norms


def _vector(basis: Basis, domain, prefix: str, indices) -> Element:
    return Element(basis, {1 << i: domain.param(f"{prefix}{i + 1}") for i in indices})


def build_values(
    assumptions: Assumptions, basis: Basis, domain, case: dict[str, int] | None = None
) -> dict[str, Element]:
    """{name: element} for every declared symbol, in the given domain.

    Parameters
    ----------
    assumptions : Assumptions
    basis : Basis
    domain : object
        Supplies ``param(name)``, ``const(fraction)`` and ``normaliser(name, lam)``.
    case : dict, optional
        For null vectors in a metric whose non-degenerate part is Cl(1, 1): which of the
        two null lines (0 or 1) each lies on.

    Examples
    --------
    >>> from fractions import Fraction
    >>> from ga_rotors.symbolic.prover.assumptions import Assumptions
    >>> class Twos:                   # every parameter 2; c = 1 whatever λ is
    ...     def param(self, name): return Fraction(2)
    ...     def const(self, q): return Fraction(q)
    ...     def normaliser(self, name, lam): return Fraction(1)
    ...     def is_scalar(self, x): return not x.grades() - {0}
    >>> a = Assumptions(rotors="R", vectors="u, v", orthogonal=["u,v"])
    >>> values = build_values(a, Basis(2), Twos())
    >>> values["R"], values["v"]            # 1 + B, and v = ⟨(w ∧ u) ũ⟩₁ = 0 here
    (1 + 2*e12, 0)
    """
    case = case or {}
    n = basis.n
    null, pos, neg = _nondegenerate(basis)
    raw: dict[str, Element] = {}  # vectors before normalisation (orthogonality uses these)
    values: dict[str, Element] = {}
    one = domain.const(1)
    for name, kind in assumptions.kinds.items():
        if kind == "scalar":
            values[name] = Element(basis, {0: domain.param(name)})
        elif kind in ("vector", "unit"):
            w = _vector(basis, domain, f"{name}_", range(n))
            others = assumptions.orthogonal_to(name)
            if others:
                if any(assumptions.kinds[o] == "null" for o in others):
                    raise Unsupported(f"orthogonality of {name} to a null vector")
                span = raw[others[0]]
                for o in others[1:]:
                    span = span ^ raw[o]
                w = ((w ^ span) * ~span).grade(1)
            raw[name] = w
            if kind == "unit":
                lam = (w * w).terms.get(0, domain.const(0))
                w = w.scale(domain.normaliser(f"c_{name}", lam))
            values[name] = w
        elif kind == "null":
            if assumptions.orthogonal_to(name) or any(
                name in pair for pair in assumptions.orthogonal
            ):
                raise Unsupported(f"orthogonality involving the null vector {name}")
            v = _vector(basis, domain, f"{name}_z", null)
            if pos and neg:
                w = _vector(basis, domain, f"{name}_w", pos + neg)
                sign = -1 if case.get(name, 0) else 1
                n0 = Element(basis, {1 << pos[0]: one, 1 << neg[0]: one if sign > 0 else -one})
                v = v + (w * n0 * w).grade(1).scale(domain.param(f"{name}_s"))
            values[name] = v
            raw[name] = v
        elif kind == "blade":
            k = assumptions.grade_of(name)
            if k > n:
                values[name] = Element(basis, {})
                continue
            b = Element(basis, {0: one})
            for j in range(1, k + 1):
                b = b ^ _vector(basis, domain, f"{name}_{j}_", range(n))
            values[name] = b
        elif kind == "rotor":
            bivector = Element(
                basis,
                {
                    b: domain.param(f"{name}_{basis.name(b)}")
                    for b in _blades_of(basis, lambda g: g == 2)
                },
            )
            # Lipschitz: the exterior exponential 1 + B + B∧B/2! + ... is a versor
            N, power = Element(basis, {0: one}), Element(basis, {0: one})
            for k in range(1, n // 2 + 1):
                power = power ^ bivector
                N = N + power.scale(domain.const(1) / factorial(k))
            norm = N * ~N
            if not domain.is_scalar(norm):
                raise Unsupported(f"{name}: N Ñ is not a scalar for the exterior exponential")
            lam = norm.terms.get(0, domain.const(0))
            values[name] = N.scale(domain.normaliser(f"c_{name}", lam))
        else:
            keep = _grades_of(kind, assumptions.grade_of(name))
            values[name] = Element(
                basis,
                {b: domain.param(f"{name}_{basis.name(b)}") for b in _blades_of(basis, keep)},
            )
    return values
