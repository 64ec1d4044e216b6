"""Each declared symbol as an element built from free parameters (see :mod:`.assumptions`).

One construction serves the exact proof, the numeric pre-check and the exact check of a
counterexample: a *domain* supplies the numbers. ``param(name)`` is a free parameter
(a polynomial variable, an array of random draws, or one rational value),
``normaliser(name, lam)`` a c with c² λ = 1, ``const(q)`` a rational constant, and
``is_scalar(x)`` says whether an element is a scalar (within rounding, for draws).

Each construction reaches every element of its kind (the soundness of a proof rests on
it; ``tests/test_prove_soundness.py`` checks it against elements drawn with ``clifford``):

* linear kinds (scalar, vector, Euclidean vector, bivector, k-vector, point, even,
  multivector): every coefficient is a parameter;
* unit vectors: c w with c² w² = 1 (w = v, c = ±1 gives any v with v² = 1);
* blades and lines: the wedge of k free vectors (a k-blade is such a wedge);
* null vectors: s⟨w n₀ w⟩₁ + z (see :mod:`.assumptions`), one case per piece of the cone;
* rotors and motors: c(1 + B + B∧B/2! + …) with c² N Ñ = 1 (N Ñ is a scalar: Lipschitz's
  exterior exponential is a versor), which is every rotor R with ⟨R⟩₀ ≠ 0 (B = ⟨R⟩₂/⟨R⟩₀,
  c = ⟨R⟩₀), a dense subset of the rotors: checked on rotors drawn in every signature
  with n ≤ 6, degenerate ones included;
* vectors under orthogonality: each inside the orthogonal complement of its earlier
  neighbours, det(G) x − Ωᵀ adj(G) Ω x (Ω the lowered neighbours, G = Ω Ωᵀ), in the
  order and cases of :mod:`.orthogonal`.

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
from .orthogonal import Plan, Unsupported, cases, plan

__all__ = ["Unsupported", "build_values", "construction_cases", "grade_of", "parameter_names"]


def _blades_of(basis: Basis, keep) -> list[int]:
    return [b for b in basis.blades if keep(b.bit_count())]


def grade_of(assumptions: Assumptions, name: str, basis: Basis) -> int | None:
    """The grade of a graded symbol in this algebra: declared (k-vectors, blades), or
    n − 1 for a point and n − 2 for a line (projective GA, r = 1).

    Examples
    --------
    >>> from ga_rotors.symbolic.prover.assumptions import Assumptions
    >>> a = Assumptions(points="P", lines="L", blades="B:3")
    >>> [grade_of(a, x, Basis(3, 0, 1)) for x in "PLB"]
    [3, 2, 3]
    """
    kind = assumptions.kinds[name]
    if kind in ("point", "line"):
        if basis.r != 1:
            raise ValueError(
                f"{kind}s: {name!r} is a projective-GA {kind}; declare it in Cl(p,q,1) "
                f"(e.g. --signature 3,0,1), not {basis.label()}"
            )
        if basis.n < 3:
            raise ValueError(
                f"{kind}s: {name!r} needs a projective space of dimension 2 or more, "
                f"Cl(p,q,1) with n >= 3, not {basis.label()}"
            )
        return basis.n - (1 if kind == "point" else 2)
    return assumptions.grade_of(name)


def _keep(kind: str, k: int | None):
    """Which grades a generic element of a linear kind has."""
    if kind == "bivector":
        return lambda g: g == 2
    if kind in ("kvector", "point"):
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


def _null_pieces(basis: Basis) -> int:
    """How many pieces the null cone of the non-degenerate part falls into (1 or 2).

    When the non-degenerate part is Cl(1, 1) the cone is two lines, e1 ± e2 directions,
    and each is proved separately.
    """
    _, pos, neg = _nondegenerate(basis)
    return 2 if len(pos) == 1 and len(neg) == 1 else 1


def construction_cases(assumptions: Assumptions, basis: Basis) -> list[dict]:
    """The cases a proof runs through: the piece of the null cone of each null vector
    (two in Cl(1, 1, r)) and the generic / radical case of each orthogonality hub.

    Examples
    --------
    >>> from ga_rotors.symbolic.prover.assumptions import Assumptions
    >>> construction_cases(Assumptions(nulls="n"), Basis(1, 1))
    [{'n': 0}, {'n': 1}]
    >>> construction_cases(Assumptions(vectors="a,b", orthogonal=["a,b"]), Basis(2))
    [{}]
    >>> construction_cases(Assumptions(vectors="a,b", orthogonal=["a,b"]), Basis(1, 0, 1))
    [{'a': 'generic'}, {'a': 'radical'}]
    """
    nulls = [n for n, k in assumptions.kinds.items() if k == "null"]
    pieces = _null_pieces(basis)
    out = [{}]
    for name in nulls:
        out = [{**case, name: piece} for case in out for piece in range(pieces)]
    hub_cases = cases(plan(assumptions), basis)
    return [{**a, **b} for a in out for b in hub_cases]


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
        elif kind == "euclidean":
            free += [f"{name}_{basis.name(b)}" for b in _euclidean(basis, name)]
        elif kind == "null":
            if pos and neg:
                free += [f"{name}_w{i + 1}" for i in pos + neg] + [f"{name}_s"]
            free += [f"{name}_z{i + 1}" for i in null]
        elif kind in ("blade", "line"):
            k = grade_of(assumptions, name, basis)
            free += [f"{name}_{j}_{i + 1}" for j in range(1, k + 1) for i in range(n)]
        elif kind in ("rotor", "motor"):
            free += [f"{name}_{basis.name(b)}" for b in _blades_of(basis, lambda g: g == 2)]
            norms.append(f"c_{name}")
        else:
            keep = _keep(kind, grade_of(assumptions, name, basis))
            free += [f"{name}_{basis.name(b)}" for b in _blades_of(basis, keep)]
    return free, norms


def _euclidean(basis: Basis, name: str) -> list[int]:
    blades = basis.euclidean_vectors()
    if blades is None:
        raise ValueError(
            f"euclidean: {name!r} needs a base space: Euclidean vectors live in the conformal "
            f"Cl(p,1) (e1 … e(p-1)) or in Cl(p,0,r) (the vectors squaring to +1), "
            f"not in {basis.label()}"
        )
    return blades


def _vector(basis: Basis, domain, prefix: str, indices) -> Element:
    return Element(basis, {1 << i: domain.param(f"{prefix}{i + 1}") for i in indices})


def _det(m):
    if len(m) == 1:
        return m[0][0]
    total = 0
    for j in range(len(m)):
        minor = [row[:j] + row[j + 1 :] for row in m[1:]]
        term = m[0][j] * _det(minor)
        total = total + term if j % 2 == 0 else total - term
    return total


def _adjugate(m):
    k = len(m)
    if k == 1:
        return [[1]]
    adj = [[0] * k for _ in range(k)]
    for i in range(k):
        for j in range(k):
            minor = [row[:i] + row[i + 1 :] for r, row in enumerate(m) if r != j]
            cofactor = _det(minor)
            adj[i][j] = cofactor if (i + j) % 2 == 0 else -cofactor
    return adj


def _complement(basis: Basis, x: Element, neighbours: list[Element], zero) -> Element:
    """det(G) x − Ωᵀ adj(G) Ω x: x projected into the vectors orthogonal to the neighbours
    (Ω's rows are the lowered neighbours, G = Ω Ωᵀ in coordinates), scaled by det(G)."""
    n = basis.n
    rows = [[u.terms.get(1 << j, zero) * basis.metric[j] for j in range(n)] for u in neighbours]
    coords = [x.terms.get(1 << j, zero) for j in range(n)]

    def dot(a, b):
        total = zero
        for j in range(n):
            if basis.metric[j]:
                total = total + a[j] * b[j]
        return total

    gram = [[dot(a, b) for b in rows] for a in rows]
    det, adj = _det(gram), _adjugate(gram)
    along = [dot(row, coords) for row in rows]
    k = len(rows)
    weights = [sum((adj[i][m] * along[m] for m in range(k)), zero) for i in range(k)]
    out = {}
    for j in range(n):
        value = det * coords[j]
        for i, row in enumerate(rows):
            if basis.metric[j]:
                value = value - weights[i] * row[j]
        out[1 << j] = value
    return Element(basis, out)


def _orthogonal_vectors(
    assumptions: Assumptions, basis: Basis, domain, p: Plan, case: dict
) -> dict[str, Element]:
    kinds = assumptions.kinds
    null = [i for i, s in enumerate(basis.metric) if s == 0]
    zero = domain.const(0)
    raw: dict[str, Element] = {}
    values: dict[str, Element] = {}
    for name in p.order:
        if case.get(name) == "radical":  # ♭v = 0: v in the null directions (0 when r = 0)
            w = _vector(basis, domain, f"{name}_", null)
        else:
            w = _vector(basis, domain, f"{name}_", range(basis.n))
            against = [raw[u] for u in p.earlier[name] if case.get(u) != "radical"]
            if against:
                w = _complement(basis, w, against, zero)
        raw[name] = w
        if kinds[name] == "unit":
            lam = (w * w).terms.get(0, zero)
            w = w.scale(domain.normaliser(f"c_{name}", lam))
        values[name] = w
    return values


def build_values(
    assumptions: Assumptions, basis: Basis, domain, case: dict | None = None
) -> dict[str, Element]:
    """{name: element} for every declared symbol, in the given domain.

    Parameters
    ----------
    assumptions : Assumptions
    basis : Basis
    domain : object
        Supplies ``param(name)``, ``const(fraction)``, ``normaliser(name, lam)`` and
        ``is_scalar(x)``.
    case : dict, optional
        One of :func:`construction_cases`: the piece of the null cone of each null vector
        (0 or 1) and the case of each orthogonality hub (``"generic"``, ``"radical"``).

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
    >>> values["R"], values["v"]            # 1 + B; v = |♭u|² x − (♭u·x) ♭u = 0 here
    (1 + 2*e12, 0)
    """
    case = case or {}
    n = basis.n
    null, pos, neg = _nondegenerate(basis)
    values: dict[str, Element] = {}
    one = domain.const(1)
    graph = plan(assumptions)
    for name, kind in assumptions.kinds.items():
        if name in values:
            continue
        if name in graph.earlier:
            values.update(_orthogonal_vectors(assumptions, basis, domain, graph, case))
        elif kind == "scalar":
            values[name] = Element(basis, {0: domain.param(name)})
        elif kind in ("vector", "unit"):
            w = _vector(basis, domain, f"{name}_", range(n))
            if kind == "unit":
                lam = (w * w).terms.get(0, domain.const(0))
                w = w.scale(domain.normaliser(f"c_{name}", lam))
            values[name] = w
        elif kind == "euclidean":
            values[name] = Element(
                basis, {b: domain.param(f"{name}_{basis.name(b)}") for b in _euclidean(basis, name)}
            )
        elif kind == "null":
            v = _vector(basis, domain, f"{name}_z", null)
            if pos and neg:
                w = _vector(basis, domain, f"{name}_w", pos + neg)
                sign = -1 if case.get(name, 0) else 1
                n0 = Element(basis, {1 << pos[0]: one, 1 << neg[0]: one if sign > 0 else -one})
                v = v + (w * n0 * w).grade(1).scale(domain.param(f"{name}_s"))
            values[name] = v
        elif kind in ("blade", "line"):
            k = grade_of(assumptions, name, basis)
            if k > n:
                values[name] = Element(basis, {})
                continue
            b = Element(basis, {0: one})
            for j in range(1, k + 1):
                b = b ^ _vector(basis, domain, f"{name}_{j}_", range(n))
            values[name] = b
        elif kind in ("rotor", "motor"):
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
                raise Unsupported(  # pragma: no cover - Lipschitz: N Ñ is a scalar
                    f"{kind}s in {basis.label()}: N Ñ is not a scalar for the exterior "
                    f"exponential N, so the prover has no construction of {name}"
                )
            lam = norm.terms.get(0, domain.const(0))
            values[name] = N.scale(domain.normaliser(f"c_{name}", lam))
        else:
            keep = _keep(kind, grade_of(assumptions, name, basis))
            values[name] = Element(
                basis,
                {b: domain.param(f"{name}_{basis.name(b)}") for b in _blades_of(basis, keep)},
            )
    return values
