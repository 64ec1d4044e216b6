"""Vectors declared orthogonal: the order they are built in, and the cases that cover them.

The vectors with orthogonality declarations form a graph (an edge a—b for a · b = 0).
Each vector is built, in an order chosen here, inside the orthogonal complement of its
neighbours built before it (see :mod:`.symbols`). That complement is parametrised exactly
only when the lowered neighbours ♭u (u's coefficients times the metric: the linear form
v ↦ u · v) are linearly independent, so two things are decided here:

* **the order.** In a tree of the graph each vector has one earlier neighbour, its parent.
  Where a vector has several (a cycle), they must be mutually orthogonal with at most one
  not a unit vector: their lowered forms are then independent (pair a dependence with each
  unit to see it). Any other cycle is *undecided*, with that reason;
* **the cases.** A plain vector u with neighbours built after it can have ♭u = 0: u = 0, or
  in a degenerate metric u in the null directions (c = e0 in Cl(1, 0, 1)). Then u
  constrains nothing, and its later neighbours are free: a configuration the generic
  construction misses (it builds them in the complement of a nonzero ♭u). Such a *hub* is
  proved in two cases, generic and ``radical`` (♭u = 0), unless it has fewer orthogonality
  partners than p + q: then u + εw, with ♭w ≠ 0 orthogonal to all of them (w exists: d < p + q
  conditions leave more than the r null directions), is generic and tends to u, so the
  radical configurations are limits of generic ones and a polynomial identity proved on
  these holds on those. A unit vector never has ♭u = 0 (u² = 1).

Together the cases reach every tuple of vectors with the declared orthogonality (or a
dense subset of it): the proof covers them all.

Examples
--------
>>> from ga_rotors.symbolic.prover.assumptions import Assumptions
>>> from ga_rotors.symbolic.prover.basis import Basis
>>> p = plan(Assumptions(vectors="a,b,c", orthogonal=["a,c", "b,c"]))
>>> p.order, p.earlier["a"], p.hubs          # c first: a and b are built in c's complement
(('c', 'a', 'b'), ('c',), ('c',))
>>> cases(p, Basis(2)), cases(p, Basis(3))   # in the plane a, b ⟂ c ≠ 0 are parallel
([{'c': 'generic'}, {'c': 'radical'}], [{}])
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from itertools import product

from .assumptions import Assumptions
from .basis import Basis

__all__ = ["Plan", "Unsupported", "cases", "plan"]

_BUILT = ("vector", "unit")
#: most hub cases one proof runs through (2^6); more is undecided.
MAX_CASES = 64


class Unsupported(Exception):
    """The assumptions ask for a construction the prover does not have (the reason).

    Examples
    --------
    >>> raise Unsupported("orthogonality to a null vector")
    Traceback (most recent call last):
    ...
    ga_rotors.symbolic.prover.orthogonal.Unsupported: orthogonality to a null vector
    """


@dataclass(frozen=True)
class Plan:
    """The vectors under orthogonality, in construction order.

    Attributes
    ----------
    order : tuple of str
        The constrained vectors, each after the neighbours it is built against.
    earlier : mapping
        name -> its neighbours built before it.
    hubs : tuple of str
        Plain vectors with a neighbour built after them: they may need a radical case.
    degree : mapping
        name -> its number of orthogonality partners.

    Examples
    --------
    >>> Plan().order
    ()
    """

    order: tuple[str, ...] = ()
    earlier: Mapping[str, tuple[str, ...]] = field(default_factory=dict)
    hubs: tuple[str, ...] = ()
    degree: Mapping[str, int] = field(default_factory=dict)


def _components(names, edges) -> list[list[str]]:
    seen, out = set(), []
    for start in names:
        if start in seen:
            continue
        component, stack = [], [start]
        seen.add(start)
        while stack:
            x = stack.pop()
            component.append(x)
            for y in sorted(edges[x], key=names.index):
                if y not in seen:
                    seen.add(y)
                    stack.append(y)
        out.append(sorted(component, key=names.index))
    return out


def _bfs(root, edges, names) -> list[str]:
    order, queue = [root], [root]
    while queue:
        x = queue.pop(0)
        for y in sorted(edges[x], key=names.index):
            if y not in order:
                order.append(y)
                queue.append(y)
    return order


def _fault(order, edges, kinds) -> str | None:
    """Why this order cannot be built exactly, or None."""
    for i, v in enumerate(order):
        earlier = [u for u in order[:i] if u in edges[v]]
        if len(earlier) < 2:
            continue
        loose = [
            (a, b) for j, a in enumerate(earlier) for b in earlier[j + 1 :] if b not in edges[a]
        ]
        plain = [u for u in earlier if kinds[u] != "unit"]
        if loose or len(plain) > 1:
            return (
                f"the orthogonality declarations of {', '.join(sorted(set(earlier) | {v}))} "
                "form a cycle; the prover builds a vector orthogonal to several others exactly "
                "only when those are mutually orthogonal and all but one are unit vectors"
            )
    return None


def plan(assumptions: Assumptions) -> Plan:
    """The construction order and the hubs of the orthogonality graph.

    Raises
    ------
    Unsupported
        A null or Euclidean vector under orthogonality, or a cycle that cannot be built
        exactly (see the module docstring).

    Examples
    --------
    >>> from ga_rotors.symbolic.prover.assumptions import Assumptions
    >>> p = plan(Assumptions(units="u,v,w", orthogonal=["u,v", "v,w", "u,w"]))
    >>> p.order, p.earlier["w"], p.hubs
    (('u', 'v', 'w'), ('u', 'v'), ())
    """
    kinds = assumptions.kinds
    names = list(kinds)
    edges: dict[str, set[str]] = {n: set() for n in names}
    for a, b in assumptions.orthogonal:
        edges[a].add(b)
        edges[b].add(a)
    involved = [n for n in names if edges[n]]
    for n in involved:
        if kinds[n] not in _BUILT:
            raise Unsupported(
                f"orthogonality involving the {kinds[n]} vector {n} (only vectors and unit "
                "vectors are built under orthogonality)"
            )
    order: list[str] = []
    for component in _components(involved, edges):
        best = None
        for root in sorted(component, key=lambda n: (-len(edges[n]), names.index(n))):
            candidate = _bfs(root, edges, names)
            fault = _fault(candidate, edges, kinds)
            hubs = _hubs(candidate, edges, kinds)
            if fault is None and (best is None or len(hubs) < len(best[1])):
                best = (candidate, hubs)
            last_fault = fault
        if best is None:
            raise Unsupported(last_fault)
        order += best[0]
    earlier = {v: tuple(u for u in order[: order.index(v)] if u in edges[v]) for v in order}
    hubs = tuple(_hubs(order, edges, kinds))
    return Plan(tuple(order), earlier, hubs, {v: len(edges[v]) for v in order})


def _hubs(order, edges, kinds) -> list[str]:
    return [
        v
        for i, v in enumerate(order)
        if kinds[v] == "vector" and any(u in edges[v] for u in order[i + 1 :])
    ]


def cases(p: Plan, basis: Basis) -> list[dict[str, str]]:
    """Every generic / radical choice for the hubs that need one (with at least p + q
    orthogonality partners); one empty case when none does.

    Examples
    --------
    >>> from ga_rotors.symbolic.prover.basis import Basis
    >>> two = Plan(hubs=("a", "b"), degree={"a": 2, "b": 3})
    >>> cases(Plan(), Basis(3)), len(cases(two, Basis(2))), len(cases(two, Basis(3)))
    ([{}], 4, 2)
    """
    hubs = [v for v in p.hubs if p.degree[v] >= basis.p + basis.q]
    if 2 ** len(hubs) > MAX_CASES:
        raise Unsupported(
            f"{len(hubs)} vectors ({', '.join(hubs)}) each need a case with ♭v = 0 "
            f"(2^{len(hubs)} cases, at most {MAX_CASES}); declare some of them unit vectors"
        )
    return [
        dict(zip(hubs, combo, strict=True))
        for combo in product(("generic", "radical"), repeat=len(hubs))
    ]
