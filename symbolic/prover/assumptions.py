"""What the symbols of an identity are: their kinds and the assumptions on them.

Kinds, and how each is built from free parameters so that the proof is a polynomial
identity (``p`` marks a free parameter; c is a normaliser with c² λ = 1):

============== ====================================== ====================================
kind           meaning                                built as
============== ====================================== ====================================
scalar         a real number                          p
vector         grade 1                                Σ pᵢ eᵢ
euclidean      a vector of the base space: e1 …       Σ pᵢ eᵢ over those vectors
               e(p-1) of the conformal Cl(p, 1),
               the non-null vectors of Cl(p, 0, r)
unit           vector with v² = +1                    c w, w a vector, c² w² = 1
null           vector with v² = 0                     s·(w n₀ w) + z: n₀ a fixed null vector
                                                      of the non-degenerate part, z in the
                                                      null directions e_i² = 0
bivector       grade 2                                Σ p_ij e_ij
kvector:k      grade k                                Σ p e_A over grade-k blades
blade:k        simple k-vector a₁ ∧ … ∧ a_k           the wedge of k vectors
point          projective GA point: grade n − 1       Σ p e_A over grade-(n−1) blades
               in Cl(p, q, 1) (trivectors in 3D PGA)
line           projective GA line: an (n−2)-blade     the wedge of n − 2 vectors
even           even grades                            Σ p e_A over even blades
rotor          even versor with R R̃ = 1              c·(1 + B + B∧B/2! + …), B a bivector
                                                      (Lipschitz), c² λ = 1, λ = N Ñ
motor          a rotor of Cl(p, q, 1) (PGA's name)    as a rotor
multivector    anything                               Σ p e_A over all blades
============== ====================================== ====================================

Orthogonality ``(a, b)`` between vectors and unit vectors builds each inside the
orthogonal complement of the ones built before it, in the order and the cases of
:mod:`.orthogonal` (so that, in a degenerate metric too, every configuration is reached).

Why these cover everything: the unit, blade and linear forms reach every element of
their kind exactly; Lipschitz's form reaches every rotor with a nonzero scalar part,
a dense subset of the rotor group (checked for n ≤ 6 in every signature), so a polynomial identity
that holds on it holds on all rotors (R = ⟨R⟩₀ (1 + B + B∧B/2 + …) with B = ⟨R⟩₂/⟨R⟩₀;
``tests/test_prove_soundness.py`` checks this on rotors drawn with ``clifford`` as
products of vectors and exponentials of bivectors). In Cl(3, 0, 1) these are the motors of
plane-based GA.

Examples
--------
>>> a = Assumptions(vectors="a, b", rotors="R", orthogonal=[("a", "b")])
>>> a.kinds
{'a': 'vector', 'b': 'vector', 'R': 'rotor'}
>>> Assumptions(vectors="e1")
Traceback (most recent call last):
...
ga_rotors.symbolic.prover.assumptions.AssumptionError: vectors: 'e1' is a basis blade name...
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass, field

from .grammar import FUNCTIONS, RESERVED_NAMES, shorten

__all__ = ["KINDS", "PLURALS", "AssumptionError", "Assumptions", "check_name"]

#: the kinds a symbol can be declared as (``kvector`` and ``blade`` take a grade).
KINDS = (
    "scalar",
    "vector",
    "euclidean",
    "unit",
    "null",
    "bivector",
    "kvector",
    "blade",
    "point",
    "line",
    "even",
    "rotor",
    "motor",
    "multivector",
)

#: the plural keyword (and command-line option) of each kind without a grade.
PLURALS = {
    "scalars": "scalar",
    "vectors": "vector",
    "euclidean": "euclidean",
    "units": "unit",
    "nulls": "null",
    "bivectors": "bivector",
    "points": "point",
    "lines": "line",
    "evens": "even",
    "rotors": "rotor",
    "motors": "motor",
    "multivectors": "multivector",
}

_IDENT = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\Z")
_BLADE_NAME = re.compile(r"e\d+\Z")
_MAX_NAME = 40
#: at most this many symbols in one identity.
MAX_SYMBOLS = 64


class AssumptionError(ValueError):
    """A declaration is malformed; the message names the argument.

    Examples
    --------
    >>> Assumptions(orthogonal=[("a", "b")])
    Traceback (most recent call last):
    ...
    ga_rotors.symbolic.prover.assumptions.AssumptionError: orthogonal: 'a' is not declared...
    """


def _names(value, what: str) -> tuple[str, ...]:
    if value is None:
        return ()
    items = value.split(",") if isinstance(value, str) else list(value)
    out = []
    for item in items:
        if not isinstance(item, str):
            raise AssumptionError(f"{what}: expected names, got {shorten(repr(item), 30)}")
        name = item.strip()
        if not name:
            continue
        check_name(name, what)
        out.append(name)
    return tuple(out)


def check_name(name: str, what: str) -> None:
    """Refuse a symbol or definition name that is not an identifier or is taken.

    Examples
    --------
    >>> check_name("einf", "define")
    Traceback (most recent call last):
    ...
    ga_rotors.symbolic.prover.assumptions.AssumptionError: define: 'einf' is a basis blade name; ...
    """
    if not _IDENT.match(name) or len(name) > _MAX_NAME:
        raise AssumptionError(
            f"{what}: {shorten(name, 30)!r} is not a name (letters, digits, _; at most "
            f"{_MAX_NAME} characters)"
        )
    if _BLADE_NAME.match(name) or name in RESERVED_NAMES:
        raise AssumptionError(f"{what}: {name!r} is a basis blade name; choose another")
    if name in FUNCTIONS:
        raise AssumptionError(f"{what}: {name!r} is a function name; choose another")


def _graded(value, what: str) -> dict[str, int]:
    if value is None:
        return {}
    if isinstance(value, str):
        pairs = []
        for item in value.split(","):
            if not item.strip():
                continue
            name, sep, k = item.partition(":")
            if not sep:
                raise AssumptionError(
                    f"{what}: expected NAME:GRADE, got {shorten(item.strip(), 30)!r}"
                )
            pairs.append((name, k))
    elif isinstance(value, Mapping):
        pairs = list(value.items())
    else:
        raise AssumptionError(
            f"{what}: expected 'NAME:GRADE, ...' or a dict, got {shorten(repr(value), 30)}"
        )
    out = {}
    for name, k in pairs:
        (name,) = _names([name], what)
        try:
            grade = int(str(k).strip())
        except ValueError:
            raise AssumptionError(
                f"{what}: grade of {name!r} must be an integer, got {shorten(repr(k), 30)}"
            ) from None
        if grade < 0:
            raise AssumptionError(f"{what}: grade of {name!r} must be >= 0, got {grade}")
        out[name] = grade
    return out


@dataclass(frozen=True)
class Assumptions:
    """Symbols by kind, and orthogonality between vectors.

    Parameters
    ----------
    scalars, vectors, euclidean, units, nulls, bivectors, points, lines, evens, rotors, motors,
    multivectors : str or list of str
        Names, as a list or one comma-separated string (see :data:`KINDS`).
    kvectors, blades : str or dict
        ``{"T": 3}`` or ``"T:3"``: grade-k elements, and simple k-vectors (k-blades).
    orthogonal : list of pairs
        Pairs of vector names with a · b = 0 (``"a,b"`` strings are accepted too).

    Examples
    --------
    >>> Assumptions(blades="B:2", units="n").kinds
    {'n': 'unit', 'B': 'blade'}
    >>> Assumptions(blades="B:2").grade_of("B")
    2
    """

    scalars: tuple[str, ...] = ()
    vectors: tuple[str, ...] = ()
    euclidean: tuple[str, ...] = ()
    units: tuple[str, ...] = ()
    nulls: tuple[str, ...] = ()
    bivectors: tuple[str, ...] = ()
    points: tuple[str, ...] = ()
    lines: tuple[str, ...] = ()
    evens: tuple[str, ...] = ()
    rotors: tuple[str, ...] = ()
    motors: tuple[str, ...] = ()
    multivectors: tuple[str, ...] = ()
    kvectors: Mapping[str, int] = field(default_factory=dict)
    blades: Mapping[str, int] = field(default_factory=dict)
    orthogonal: tuple[tuple[str, str], ...] = ()

    def __post_init__(self):
        kinds: dict[str, str] = {}
        for attr, kind in PLURALS.items():
            names = _names(getattr(self, attr), attr)
            object.__setattr__(self, attr, names)
            for name in names:
                if name in kinds:
                    raise AssumptionError(f"{attr}: {name!r} is already declared")
                kinds[name] = kind
        for attr, kind in (("kvectors", "kvector"), ("blades", "blade")):
            graded = _graded(getattr(self, attr), attr)
            object.__setattr__(self, attr, graded)
            for name in graded:
                if name in kinds:
                    raise AssumptionError(f"{attr}: {name!r} is already declared")
                kinds[name] = kind
        if len(kinds) > MAX_SYMBOLS:
            raise AssumptionError(f"{len(kinds)} symbols declared; at most {MAX_SYMBOLS}")
        pairs = []
        declared = self.orthogonal or ()
        if isinstance(declared, str):  # "a,b" or "a,b; c,d"
            declared = [item for item in declared.split(";") if item.strip()]
        if len(declared) > MAX_SYMBOLS**2:
            raise AssumptionError(f"orthogonal: {len(declared)} pairs; at most {MAX_SYMBOLS**2}")
        for pair in declared:
            if isinstance(pair, str):
                pair = pair.split(",")
            names = _names(list(pair), "orthogonal")
            if len(names) != 2 or names[0] == names[1]:
                raise AssumptionError(
                    f"orthogonal: expected two different names, got {shorten(repr(pair), 40)}"
                )
            for name in names:
                if name not in kinds:
                    raise AssumptionError(
                        f"orthogonal: {name!r} is not declared; declare it as a vector first"
                    )
                if kinds[name] not in ("vector", "unit", "null", "euclidean"):
                    raise AssumptionError(
                        f"orthogonal: {name!r} is a {kinds[name]}; orthogonality is "
                        "between vectors (vector, unit, null or euclidean)"
                    )
            pair = tuple(names)
            if pair not in pairs and pair[::-1] not in pairs:
                pairs.append(pair)
        object.__setattr__(self, "orthogonal", tuple(pairs))
        object.__setattr__(self, "_kinds", kinds)

    @property
    def kinds(self) -> dict[str, str]:
        """{name: kind} in declaration order.

        Examples
        --------
        >>> Assumptions(scalars="s", multivectors="X").kinds
        {'s': 'scalar', 'X': 'multivector'}
        """
        return dict(self._kinds)

    def grade_of(self, name: str) -> int | None:
        """The declared grade of a kvector or blade symbol, else None.

        Examples
        --------
        >>> Assumptions(kvectors={"T": 3}).grade_of("T")
        3
        """
        return self.kvectors.get(name, self.blades.get(name))

    def orthogonal_to(self, name: str) -> list[str]:
        """The vectors declared before ``name`` that it must be orthogonal to.

        Examples
        --------
        >>> Assumptions(vectors="a,b,c", orthogonal=["a,c", "c,b"]).orthogonal_to("c")
        ['a', 'b']
        """
        order = list(self._kinds)
        mine = order.index(name)
        out = []
        for x, y in self.orthogonal:
            other = y if x == name else x if y == name else None
            if other is not None and order.index(other) < mine:
                out.append(other)
        return sorted(set(out), key=order.index)

    def describe(self) -> str:
        """One line: the declarations, as the command line writes them.

        Examples
        --------
        >>> Assumptions(vectors="a,b", blades="B:2", orthogonal=["a,b"]).describe()
        'vectors a, b; blades B:2; orthogonal a⟂b'
        """
        parts = []
        for attr in PLURALS:
            names = getattr(self, attr)
            if names:
                parts.append(f"{attr} {', '.join(names)}")
        for attr in ("kvectors", "blades"):
            graded = getattr(self, attr)
            if graded:
                parts.append(f"{attr} " + ", ".join(f"{k}:{v}" for k, v in graded.items()))
        if self.orthogonal:
            parts.append("orthogonal " + ", ".join(f"{a}⟂{b}" for a, b in self.orthogonal))
        return "; ".join(parts) if parts else "no symbols"
