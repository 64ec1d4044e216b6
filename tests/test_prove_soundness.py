"""Soundness of the prover: never a false *proved*, never a false *refuted*.

A proof is exact for the symbols as the prover builds them (:mod:`.symbols`), so it is a
proof about every element of a kind only if the construction reaches every element of
that kind. Here, in many signatures Cl(p, q, r) with n ≤ 6, degenerate ones included:

* **the construction reaches the kind**: elements drawn in clifford's algebra by the
  kind's own definition (a rotor as a product of exponentials and vectors, orthogonal
  vectors from null spaces, with special configurations on purpose: parallel partners,
  vectors in the null directions, zero) are represented by the construction at parameters
  a recipe finds, within rounding;
* **the construction stays in the kind**: at random parameters it gives unit, null,
  orthogonal vectors, rotors that map vectors to vectors, points of the right grade;
* **false identities are refuted** under each kind of assumption, the three of issue 29
  first, each with a counterexample whose values satisfy the assumptions and whose two
  sides differ when clifford's algebra evaluates them (:mod:`tests.clifford_oracle`).

The default run takes seconds; ``GA_ROTORS_LONG=1`` sweeps every signature with n ≤ 6.
"""

from __future__ import annotations

import math
import os

import clifford_oracle
import numpy as np
import pytest
from clifford_oracle import algebra

from ga_rotors.symbolic.prover import prove
from ga_rotors.symbolic.prover.assumptions import Assumptions
from ga_rotors.symbolic.prover.basis import Basis
from ga_rotors.symbolic.prover.element import Element
from ga_rotors.symbolic.prover.grammar import parse_expression, parse_identity
from ga_rotors.symbolic.prover.orthogonal import cases, plan
from ga_rotors.symbolic.prover.symbols import build_values, construction_cases, grade_of

LONG = os.environ.get("GA_ROTORS_LONG") == "1"
QUICK = [(3, 0, 1), (1, 0, 1), (2, 0, 2), (1, 1, 1), (2, 1, 0), (1, 3, 0), (4, 1, 0)]
ALL = [(n - r - q, q, r) for n in range(1, 7) for r in range(n + 1) for q in range(n - r + 1)]
SIGNATURES = ALL if LONG else QUICK
SAMPLES = 12 if LONG else 4


class Given:
    """A domain whose parameters are the values a recipe found (0 for any other)."""

    def __init__(self, values: dict[str, float], signs: dict[str, float] | None = None):
        self.values, self.signs = values, signs or {}

    def param(self, name):
        return float(self.values.get(name, 0.0))

    def const(self, q):
        return float(q)

    def normaliser(self, name, lam):
        assert lam > 0, name
        return self.signs.get(name, 1.0) / math.sqrt(lam)

    def is_scalar(self, x):
        scale = 1 + max((abs(c) for c in x.terms.values()), default=0)
        return all(abs(c) <= 1e-9 * scale for b, c in x.terms.items() if b)


def _array(x: Element, alg) -> np.ndarray:
    out = alg.zero()
    for blade, c in x.terms.items():
        out[x.basis.index[blade]] = c
    return out


def _close(a, b, tol=1e-8) -> bool:
    return bool(np.max(np.abs(a - b)) <= tol * (1 + np.max(np.abs(b))))


# -- drawing elements of each kind in clifford's algebra --------------------------------------
def _indices(basis, keep):
    return [i for i, b in enumerate(basis.blades) if keep(b.bit_count())]


def _random(alg, rng, keep):
    out = alg.zero()
    idx = [i for i in range(alg.dim) if keep(alg.grades[i])]
    out[idx] = rng.normal(size=len(idx))
    return out


def _draw_unit(alg, rng):
    for _ in range(100):
        v = alg.vector(rng.normal(size=alg.n))
        square = alg.gp(v, v)[0]
        if square > 0.1:
            return v / math.sqrt(square)
    return None


def _draw_null(alg, rng):
    metric = np.array(alg.metric)
    v = np.zeros(alg.n)
    null = np.flatnonzero(metric == 0)
    v[null] = rng.normal(size=len(null))
    pos, neg = np.flatnonzero(metric == 1), np.flatnonzero(metric == -1)
    if len(pos) and len(neg) and rng.random() < 0.8:
        x, y = rng.normal(size=len(pos)), rng.normal(size=len(neg))
        v[pos], v[neg] = x, y * np.linalg.norm(x) / np.linalg.norm(y)
    return alg.vector(v)


def _draw_rotor(alg, rng):
    """± a product of exponentials of bivectors and of an even number of invertible
    vectors, normalised to R R̃ = 1 (the rotor group's elements, all components)."""
    for _ in range(200):
        rotor = alg.scalar(1.0)
        for _ in range(rng.integers(0, 3)):
            rotor = alg.gp(rotor, alg.exp(0.7 * _random(alg, rng, lambda g: g == 2)))
        for _ in range(2 * rng.integers(0, 3)):
            v = alg.vector(rng.normal(size=alg.n))
            if abs(alg.gp(v, v)[0]) < 0.2:
                break
            rotor = alg.gp(rotor, v)
        else:
            square = alg.gp(rotor, alg.rev(rotor))
            if square[0] > 0.05 and _close(square, alg.scalar(square[0]), 1e-9):
                rotor = rotor / math.sqrt(square[0]) * rng.choice([-1.0, 1.0])
                if abs(rotor[0]) > 0.05:
                    return rotor
    return None


# -- recipes: the parameters at which the construction gives a drawn element -------------------
def _linear(name, x, basis, blades):
    return {f"{name}_{basis.name(b)}": x[basis.index[b]] for b in blades}


def _null_recipe(name, v, basis, alg):
    """s⟨w n₀ w⟩₁ + z = v: z the null part, w = n₀ − u, s = 1/(2 u·n₀) (u the rest)."""
    metric = basis.metric
    null = [i for i, s in enumerate(metric) if s == 0]
    pos = [i for i, s in enumerate(metric) if s == 1]
    neg = [i for i, s in enumerate(metric) if s == -1]
    values = {f"{name}_z{i + 1}": v[1 + i] for i in null}
    u = np.array([0.0 if metric[i] == 0 else v[1 + i] for i in range(basis.n)])
    if not (pos and neg) or not np.any(u):
        return [({}, values)]
    out = []
    for piece in range(2 if len(pos) == 1 and len(neg) == 1 else 1):
        n0 = np.zeros(basis.n)
        n0[pos[0]], n0[neg[0]] = 1.0, -1.0 if piece else 1.0
        dot = sum(metric[i] * u[i] * n0[i] for i in range(basis.n))
        if abs(dot) < 1e-9:
            continue
        w = n0 - u
        found = dict(values)
        found.update({f"{name}_w{i + 1}": w[i] for i in pos + neg})
        found[f"{name}_s"] = 1 / (2 * dot)
        out.append(({name: piece}, found))
    return out


KINDS = ["vector", "euclidean", "unit", "null", "bivector", "kvector", "blade", "point", "line"]
KINDS += ["even", "rotor", "motor", "multivector"]


def _applies(kind, basis):
    if kind in ("point", "line"):
        return basis.r == 1 and basis.n >= 3
    if kind == "euclidean":
        return basis.euclidean_vectors() is not None
    if kind == "blade":
        return basis.n >= 2
    return True


def _declare(kind, basis):
    plural = {"kvector": "kvectors", "blade": "blades"}
    if kind in plural:
        return Assumptions(**{plural[kind]: {"X": 2 if kind == "blade" else min(3, basis.n)}})
    key = {"euclidean": "euclidean"}.get(kind, kind + "s")
    return Assumptions(**{key: "X"})


def _draw_and_recipe(kind, basis, alg, rng, assumptions):
    """(drawn element, [(case, params, signs), ...]) or None when nothing can be drawn."""
    n = basis.n
    if kind == "vector":
        x = alg.vector(rng.normal(size=n))
        return x, [({}, {f"X_{i + 1}": x[1 + i] for i in range(n)}, {})]
    if kind == "unit":
        x = _draw_unit(alg, rng)
        if x is None:
            return None
        return x, [({}, {f"X_{i + 1}": x[1 + i] for i in range(n)}, {})]
    if kind == "null":
        x = _draw_null(alg, rng)
        return x, [(case, values, {}) for case, values in _null_recipe("X", x, basis, alg)]
    if kind == "euclidean":
        blades = basis.euclidean_vectors()
        x = alg.zero()
        for b in blades:
            x[basis.index[b]] = rng.normal()
        return x, [({}, _linear("X", x, basis, blades), {})]
    if kind in ("blade", "line"):
        k = grade_of(assumptions, "X", basis)
        vectors = [rng.normal(size=n) for _ in range(k)]
        x = alg.scalar(1.0)
        for v in vectors:
            x = alg.op(x, alg.vector(v))
        values = {f"X_{j + 1}_{i + 1}": v[i] for j, v in enumerate(vectors) for i in range(n)}
        return x, [({}, values, {})]
    if kind in ("rotor", "motor"):
        x = _draw_rotor(alg, rng)
        if x is None:
            return None
        bivector = x / x[0]
        blades = [b for b in basis.blades if b.bit_count() == 2]
        return x, [({}, _linear("X", bivector, basis, blades), {"c_X": math.copysign(1, x[0])})]
    grade = grade_of(assumptions, "X", basis)
    keep = {
        "bivector": lambda g: g == 2,
        "kvector": lambda g: g == grade,
        "point": lambda g: g == grade,
        "even": lambda g: g % 2 == 0,
        "multivector": lambda g: True,
    }[kind]
    x = _random(alg, rng, keep)
    blades = [b for b in basis.blades if keep(b.bit_count())]
    return x, [({}, _linear("X", x, basis, blades), {})]


@pytest.mark.parametrize("sig", SIGNATURES, ids=str)
def test_every_kind_reaches_elements_drawn_by_its_definition(sig):
    basis, alg = Basis(*sig), algebra(sig)
    rng = np.random.default_rng(sum(sig) * 31 + sig[1] * 7 + sig[2])
    for kind in KINDS:
        if not _applies(kind, basis):
            continue
        assumptions = _declare(kind, basis)
        for _ in range(SAMPLES):
            drawn = _draw_and_recipe(kind, basis, alg, rng, assumptions)
            if drawn is None:
                continue
            x, recipes = drawn
            assert recipes, (kind, sig)
            reached = []
            for case, values, signs in recipes:
                built = build_values(assumptions, basis, Given(values, signs), case)["X"]
                reached.append(_close(_array(built, alg), x))
            assert any(reached), (kind, sig, x)


@pytest.mark.parametrize("sig", SIGNATURES, ids=str)
def test_the_construction_stays_in_its_kind(sig):
    basis, alg = Basis(*sig), algebra(sig)
    rng = np.random.default_rng(7)
    for kind in ("unit", "null", "rotor", "point", "line", "euclidean"):
        if not _applies(kind, basis):
            continue
        assumptions = _declare(kind, basis)
        for case in construction_cases(assumptions, basis):
            for _ in range(SAMPLES):
                values = {name: rng.normal() for name in _all_parameters(assumptions, basis)}
                try:
                    built = build_values(assumptions, basis, Given(values), case)["X"]
                except AssertionError:  # λ ≤ 0: no real unit vector or rotor at these values
                    continue
                x = _array(built, alg)
                if kind == "unit":
                    assert _close(alg.gp(x, x), alg.scalar(1.0))
                elif kind == "null":
                    assert _close(alg.gp(x, x), alg.zero())
                elif kind == "rotor":
                    assert _close(alg.gp(x, alg.rev(x)), alg.scalar(1.0))
                    assert not np.any(x[alg.grades % 2 == 1])
                    for i in range(basis.n):
                        image = alg.gp(alg.gp(x, alg.vector(np.eye(basis.n)[i])), alg.rev(x))
                        assert _close(image, alg.grade(image, 1), 1e-9)
                elif kind == "point":
                    assert not np.any(x[alg.grades != basis.n - 1])
                elif kind == "line":
                    assert _close(alg.op(x, x), alg.zero()) and not np.any(
                        x[alg.grades != basis.n - 2]
                    )
                else:
                    base = {basis.index[b] for b in basis.euclidean_vectors()}
                    assert not any(x[i] for i in range(alg.dim) if i not in base)


def _all_parameters(assumptions, basis):
    from ga_rotors.symbolic.prover.symbols import parameter_names

    free, _ = parameter_names(assumptions, basis)
    return free


# -- orthogonality: configurations drawn from null spaces, special ones on purpose ---------------
GRAPHS = {
    "star2": ("vectors a,b,c", [("a", "c"), ("b", "c")]),
    "star3": ("vectors a,b,c,d", [("a", "d"), ("b", "d"), ("c", "d")]),
    "edge": ("vectors a,b", [("a", "b")]),
    "path": ("vectors a,b,c", [("a", "b"), ("b", "c")]),
    "unit-triangle": ("units u,v,w", [("u", "v"), ("v", "w"), ("u", "w")]),
    "vector-in-unit-triangle": ("units u,v; vectors a", [("u", "v"), ("a", "u"), ("a", "v")]),
    "unit-hub": ("units u; vectors a,b", [("a", "u"), ("b", "u")]),
}


def _graph_assumptions(spec, pairs):
    kinds = {}
    for part in spec.split(";"):
        kind, names = part.split()
        kinds[kind] = names
    return Assumptions(**kinds, orthogonal=pairs)


def _lowered(basis, v):
    return np.array([basis.metric[i] * v[1 + i] for i in range(basis.n)])


def _null_space(rows, n):
    if not rows:
        return np.eye(n)
    _, sv, vt = np.linalg.svd(np.array(rows))
    return vt[int(np.sum(sv > 1e-9)) :]


def _partners(assumptions, name):
    return [b if a == name else a for a, b in assumptions.orthogonal if name in (a, b)]


def _draw_configuration(assumptions, basis, alg, rng):
    """Vectors with the declared orthogonality, drawn in declaration order from the null
    space of the partners drawn before, often special: in a shared small subspace (so
    partners can be parallel), in the null directions, or zero."""
    kinds = assumptions.kinds
    n = basis.n
    shared = rng.normal(size=(rng.integers(1, 3), n))
    null_rows = np.eye(n)[[s == 0 for s in basis.metric]]
    values = {}
    for name in kinds:
        rows = [_lowered(basis, values[o]) for o in _partners(assumptions, name) if o in values]
        space = _null_space(rows, n)  # orthonormal rows: the allowed vectors
        modes = ["free", "shared"] if kinds[name] == "unit" else ["free", "shared", "null", "zero"]
        mode = rng.choice(modes)
        if mode == "shared":  # the shared subspace projected into the allowed one
            space = shared @ space.T @ space
        elif mode == "null":  # null directions are orthogonal to everything
            space = null_rows
        elif mode == "zero":
            space = np.zeros((0, n))
        for _ in range(50):
            v = alg.vector(rng.normal(size=len(space)) @ space if len(space) else np.zeros(n))
            if kinds[name] != "unit":
                break
            square = alg.gp(v, v)[0]
            if square > 0.1:
                v = v / math.sqrt(square)
                break
        else:
            return None
        values[name] = v
    for a, b in assumptions.orthogonal:
        assert abs(alg.ip(values[a], values[b])[0]) < 1e-9
    return values


def _configuration_recipe(assumptions, basis, alg, values):
    """(case, params, signs, target): the case and parameters at which the construction
    gives ``target``, which is ``values`` except that a flat hub (♭v = 0) without a radical
    case (fewer partners than p + q) is moved off the radical by 10⁻³ w, w orthogonal to
    its partners with ♭w ≠ 0: the nearby generic configuration of the limit argument."""
    p = plan(assumptions)
    kinds, n = assumptions.kinds, basis.n
    needs_case = set().union(*cases(p, basis))
    target = {name: v.copy() for name, v in values.items()}
    case, params, signs = {}, {}, {}
    for name in p.order:
        flat = not np.any(np.abs(_lowered(basis, target[name])) > 1e-12)
        if name in needs_case:
            case[name] = "radical" if flat else "generic"
        elif flat and name in p.hubs:
            rows = [_lowered(basis, target[o]) for o in _partners(assumptions, name)]
            moves = [
                w
                for w in _null_space(rows, n)
                if np.any(np.abs(_lowered(basis, alg.vector(w))) > 1e-6)
            ]
            assert moves, f"no generic configuration near {name}: the limit argument fails"
            target[name] = target[name] + 1e-3 * alg.vector(moves[0])
        v = target[name]
        if case.get(name) == "radical":
            params.update({f"{name}_{i + 1}": v[1 + i] for i in range(n)})
            continue
        earlier = [u for u in p.earlier[name] if case.get(u) != "radical"]
        scale = 1.0
        if earlier:
            rows = np.array([_lowered(basis, target[u]) for u in earlier])
            scale = np.linalg.det(rows @ rows.T)
        params.update({f"{name}_{i + 1}": v[1 + i] / scale for i in range(n)})
        if kinds[name] == "unit":
            signs[f"c_{name}"] = 1.0
    return case, params, signs, target


@pytest.mark.parametrize("graph", list(GRAPHS), ids=str)
@pytest.mark.parametrize("sig", SIGNATURES, ids=str)
def test_orthogonal_vectors_reach_every_configuration(sig, graph):
    basis, alg = Basis(*sig), algebra(sig)
    assumptions = _graph_assumptions(*GRAPHS[graph])
    rng = np.random.default_rng([*sig, len(graph)])
    for _ in range(3 * SAMPLES):
        values = _draw_configuration(assumptions, basis, alg, rng)
        if values is None:
            continue
        case, params, signs, target = _configuration_recipe(assumptions, basis, alg, values)
        built = build_values(assumptions, basis, Given(params, signs), case)
        for name, x in target.items():
            assert _close(_array(built[name], alg), x, 1e-7), (graph, sig, name, case)


# -- false identities: refuted, with counterexamples clifford's algebra confirms ---------------
ORTHOGONAL_3 = [("a", "c"), ("b", "c")]
FALSE = [
    # issue 29: vectors orthogonal to everything in a degenerate metric were built as 0
    ("c == 0", (1, 0, 1), {"vectors": "a,b,c", "orthogonal": ORTHOGONAL_3}),
    (
        "d == 0",
        (2, 0, 1),
        {"vectors": "a,b,c,d", "orthogonal": [("a", "d"), ("b", "d"), ("c", "d")]},
    ),
    (
        "f*a == a*f",
        (3, 0, 1),
        {"vectors": "a,b,c,d,f", "orthogonal": [(x, "f") for x in "abcd"]},
    ),
    # orthogonality: a hub that is 0 (non-degenerate too), a partner in the null directions
    ("a^b == 0", (2, 0, 0), {"vectors": "a,b,c", "orthogonal": ORTHOGONAL_3}),
    ("b*b == 0", (1, 0, 1), {"vectors": "a,b", "orthogonal": [("a", "b")]}),
    ("(a^b)*(a^b) == 0", (3, 0, 1), {"vectors": "a,b", "orthogonal": [("a", "b")]}),
    ("u*v == v*u", (2, 2, 0), {"units": "u,v", "orthogonal": [("u", "v")]}),
    ("w == u^v", (3, 0, 0), {"units": "u,v,w", "orthogonal": [("u", "v"), ("v", "w"), ("u", "w")]}),
    # unit and null vectors
    ("n*n*a == -a", (3, 0, 1), {"units": "n", "vectors": "a"}),
    ("n == e1", (3, 0, 0), {"units": "n"}),
    ("n == 0", (3, 0, 1), {"nulls": "n"}),
    ("n*a == a*n", (1, 3, 0), {"nulls": "n", "vectors": "a"}),
    ("n*e12 == n", (1, 1, 0), {"nulls": "n"}),
    # rotors and motors
    ("R == 1", (3, 0, 0), {"rotors": "R"}),
    ("inverse(R) == R", (1, 3, 0), {"rotors": "R"}),
    ("R*a*~R == a", (2, 0, 2), {"rotors": "R", "vectors": "a"}),
    ("M*P == P*M", (3, 0, 1), {"motors": "M", "points": "P"}),
    ("M >> L == L", (3, 0, 1), {"motors": "M", "lines": "L"}),
    # linear kinds
    ("s*s == s", (3, 0, 0), {"scalars": "s"}),
    ("T*T == grade(T*T, 0)", (4, 1, 0), {"kvectors": {"T": 3}}),
    ("E*~E == grade(E*~E, 0)", (3, 0, 1), {"evens": "E"}),
    ("X*Y == Y*X", (2, 0, 1), {"multivectors": "X,Y"}),
    # blades, points, lines, duality
    ("B*B == 1", (3, 0, 1), {"blades": {"B": 2}}),
    ("lc(a, B) == 0", (2, 1, 0), {"blades": {"B": 2}, "vectors": "a"}),
    ("P & Q == Q & P", (3, 0, 1), {"points": "P,Q"}),
    ("L*L == 0", (3, 0, 1), {"lines": "L"}),
    ("dual(X) == undual(X)", (3, 0, 1), {"multivectors": "X"}),
    ("vee(X, Y) == X^Y", (2, 1, 0), {"multivectors": "X,Y"}),
    # the conformal model, with and without a definition
    ("up(x)|up(y) == 0", (4, 1, 0), {"euclidean": "x,y"}),
    ("down(up(x)) == 2*x", (4, 1, 0), {"euclidean": "x"}),
    ("T >> up(x) == up(x - t)", (4, 1, 0), {"euclidean": "x,t", "define": {"T": "1 + einf*t/2"}}),
    # inverse, division, norms, exp and log
    ("inverse(a + b) == inverse(a) + inverse(b)", (3, 0, 0), {"vectors": "a,b"}),
    ("a/b == b/a", (2, 1, 0), {"vectors": "a,b"}),
    ("a**-2 == a**2", (3, 0, 1), {"vectors": "a"}),
    ("norm(a + b) == norm(a) + norm(b)", (3, 0, 0), {"vectors": "a,b"}),
    ("log(exp(B)) == B", (3, 0, 0), {"blades": {"B": 2}}),
    ("exp(A)*exp(B) == exp(A + B)", (3, 0, 0), {"blades": {"A": 2, "B": 2}}),
    ("exp(B/2)*exp(B/2) == exp(B)*exp(B)", (3, 0, 1), {"blades": {"B": 2}}),
]


def _satisfies(assumptions, basis, alg, values):
    kinds = assumptions.kinds
    for name, kind in kinds.items():
        x = values[name]
        grade = grade_of(assumptions, name, basis)
        if kind in ("vector", "unit", "null", "euclidean"):
            assert not np.any(x[alg.grades != 1]), name
        if kind == "unit":
            assert _close(alg.gp(x, x), alg.scalar(1.0)), name
        if kind == "null":
            assert _close(alg.gp(x, x), alg.zero(), 1e-9), name
        if kind == "euclidean":
            base = {basis.index[b] for b in basis.euclidean_vectors()}
            assert not any(x[i] for i in range(alg.dim) if i not in base), name
        if kind in ("rotor", "motor"):
            assert _close(alg.gp(x, alg.rev(x)), alg.scalar(1.0)), name
            assert not np.any(x[alg.grades % 2 == 1]), name
            for i in range(basis.n):
                image = alg.gp(alg.gp(x, alg.vector(np.eye(basis.n)[i])), alg.rev(x))
                assert _close(image, alg.grade(image, 1)), name
        if kind in ("blade", "line", "point", "kvector"):
            assert not np.any(x[alg.grades != grade]), name
        if kind in ("blade", "line") and grade == 2:
            assert _close(alg.op(x, x), alg.zero()), name
    for a, b in assumptions.orthogonal:
        assert abs(alg.ip(values[a], values[b])[0]) < 1e-9, (a, b)


@pytest.mark.parametrize("identity, sig, kinds", FALSE, ids=[f"{i} {s}" for i, s, _ in FALSE])
def test_false_identities_are_refuted_with_counterexamples_clifford_confirms(identity, sig, kinds):
    kinds = dict(kinds)
    define = kinds.pop("define", None)
    verdict = prove(identity, signature=sig, define=define, **kinds)
    assert verdict.status == "refuted", verdict.report()
    ce = verdict.counterexample
    basis, alg = Basis(*sig), algebra(sig)
    assumptions = Assumptions(**kinds)
    values = {name: alg.from_names(coeffs) for name, coeffs in ce.values.items()}
    assert set(values) == set(assumptions.kinds)
    _satisfies(assumptions, basis, alg, values)
    env = dict(values)
    for name, text in (define or {}).items():
        env[name] = clifford_oracle.evaluate(parse_expression(text), env, alg)
    lhs, rhs = (clifford_oracle.evaluate(side, env, alg) for side in parse_identity(identity))
    assert not _close(lhs, rhs, 1e-6), (lhs, rhs)
    # and the sides the prover printed are clifford's
    assert _close(alg.from_names(ce.lhs), lhs, 1e-9) and _close(alg.from_names(ce.rhs), rhs, 1e-9)
