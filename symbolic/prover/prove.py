"""``prove(lhs, rhs, assumptions)``: an exact verdict on a geometric-algebra identity.

How a verdict is reached, in each case of the construction (the pieces of a null cone,
the generic and radical cases of an orthogonality hub, see :mod:`.symbols`):

1. **Numeric pre-check.** The symbols are drawn at random rational parameters (many
   draws at once, numpy arrays as coefficients) and both sides are compared in floating
   point. A draw where they differ is only a *suspect*.
2. **Exact check of a suspect.** At that draw's rational parameters both sides are
   recomputed exactly (normalisers c = 1/√λ, exp's cos/sin, reciprocals, roots and logs
   kept exact in SymPy). If the difference is not zero the verdict is *refuted*, with
   the counterexample.
3. **Exact proof.** Otherwise every coefficient of lhs − rhs is computed as a
   polynomial over ℚ in the free parameters and reduced modulo the relations
   (c² λ = 1 for each normaliser, C² − δ S² = 1 for each exp, ι λ = 1 for each inverse,
   ρ² = μ for each norm); *proved* means every reduced coefficient is the zero
   polynomial, in every case. No floating point takes part.
4. A nonzero reduced difference with no counterexample found at further exact random
   points is *undecided*, with the reason (for instance an identity that needs more
   of exp than C² − δ S² = 1 and the addition theorem for commuting arguments).

Examples
--------
>>> v = prove("(a^b)|c == a*(b|c) - b*(a|c)", signature=(4, 1), vectors="a,b,c")
>>> v.status, v.exit_code
('proved', 0)
>>> w = prove("B*B == grade(B*B, 0)", signature=(1, 3), bivectors="B")
>>> w.status
'refuted'
>>> prove("R*v*~R == grade(R*v*~R, 1)", signature=(3, 0, 1), rotors="R", vectors="v").status
'proved'
>>> print(prove("T >> up(x) == up(x + t)", signature=(4, 1), euclidean="x,t",
...             define={"T": "1 + einf*t/2"}).report())
proved in Cl(4,1): T >> up(x) == up(x + t)
  read as: T >> up(x) == up(x + t)
  where: T = 1 + ((einf * t) / 2)
  ...
"""

from __future__ import annotations

import gc
import math
import signal
import threading
import time
from collections.abc import Mapping

import numpy as np
import sympy

from .assumptions import AssumptionError, Assumptions, check_name
from .basis import Basis, cached_basis
from .domains import (
    Draws,
    InvalidPoint,
    NotInvertible,
    NotReal,
    Point,
    Polynomials,
    exact_values,
    reduce_modulo,
    to_sympy,
)
from .element import Element
from .evaluate import EvaluationError, Evaluator, exp_groups, symbol_keys
from .grammar import (
    MAX_DEFINITIONS,
    Node,
    ParseError,
    names_in,
    parse_expression,
    parse_identity,
    shorten,
    unparse,
)
from .symbols import Unsupported, build_values, construction_cases, parameter_names
from .verdict import Counterexample, Verdict

__all__ = ["MAX_DRAWS", "elements", "parse_definitions", "parse_signature", "prove"]

_DRAWS = 16
_EXTRA_POINTS = 6

#: Most random draws of the numeric pre-check (10⁵ take about half a second; 10¹² would
#: allocate terabytes).
MAX_DRAWS = 1_000_000
_DIGITS = 50
#: a time limit this long (or infinite) is no limit (the interval timer cannot hold more).
_NO_LIMIT = 1e8


def parse_signature(signature) -> Basis:
    """The algebra of ``(p, q)``, ``(p, q, r)`` or the text ``"p,q[,r]"``.

    Examples
    --------
    >>> parse_signature("3,0,1").label(), parse_signature((1, 3)).label()
    ('Cl(3,0,1)', 'Cl(1,3)')
    >>> parse_signature("3;0")
    Traceback (most recent call last):
    ...
    ValueError: signature: expected p,q or p,q,r (non-negative integers), got '3;0'
    """
    items = signature.split(",") if isinstance(signature, str) else signature
    try:
        numbers = [int(str(x).strip()) for x in items] if len(str(signature)) < 40 else []
    except (TypeError, ValueError):
        numbers = []
    if len(numbers) not in (2, 3) or min(numbers) < 0:
        raise ValueError(
            "signature: expected p,q or p,q,r (non-negative integers), got "
            f"{shorten(repr(signature), 40)}"
        )
    if sum(numbers) == 0 or sum(numbers) > 6:
        raise ValueError(f"signature: n = p + q + r must be 1..6, got {sum(numbers)}")
    return cached_basis(*numbers)


def parse_definitions(define) -> list[tuple[str, Node]]:
    """User definitions, ``{"T": "1 + einf*t/2"}`` or ``["T=1 + einf*t/2", ...]``, parsed.

    Each may use the declared symbols and the definitions before it.

    Examples
    --------
    >>> [(name, unparse(node)) for name, node in parse_definitions(["T = 1 + e1*t/2"])]
    [('T', '1 + ((e1 * t) / 2)')]
    >>> parse_definitions({"T": "S*S", "S": "e1"})
    Traceback (most recent call last):
    ...
    ValueError: define T: uses S, which is defined after it (or is T itself)
    """
    if define is None:
        return []
    if isinstance(define, Mapping):
        items = list(define.items())
    else:
        if isinstance(define, str):
            define = [define]
        items = []
        for item in define:
            if not isinstance(item, str) or "=" not in item:
                raise ValueError(f"define: expected NAME=EXPRESSION, got {shorten(repr(item), 40)}")
            name, _, text = item.partition("=")
            items.append((name.strip(), text))
    if len(items) > MAX_DEFINITIONS:
        raise ValueError(f"define: {len(items)} definitions; at most {MAX_DEFINITIONS}")
    out: list[tuple[str, Node]] = []
    names = [name for name, _ in items]
    for i, (name, text) in enumerate(items):
        if not isinstance(name, str):
            raise ValueError(f"define: expected a name, got {shorten(repr(name), 40)}")
        check_name(name, "define")
        if name in names[:i]:
            raise ValueError(f"define {name}: defined twice")
        if not isinstance(text, str):
            raise ValueError(f"define {name}: expected an expression, got {type(text).__name__}")
        try:
            node = parse_expression(text)
        except ParseError as exc:
            raise ParseError(f"define {name}: {exc}") from None
        later = sorted(names_in(node) & set(names[i:]))
        if later:
            raise ValueError(
                f"define {name}: uses {', '.join(later)}, which is defined after it "
                f"(or is {name} itself)"
            )
        out.append((name, node))
    return out


def elements(signature=(3, 0), assumptions: Assumptions | None = None, **kinds):
    """Symbolic multivectors of each declared kind, to compute with and display.

    Coefficients are exact polynomials over ℚ in the free parameters (SymPy's sparse
    polynomials; ``c_R``-style symbols are the normalisers, with c² λ = 1). In a
    notebook each element renders as LaTeX.

    Examples
    --------
    >>> x = elements((3, 0), vectors="a", bivectors="B")
    >>> x["a"]
    a_1*e1 + a_2*e2 + a_3*e3
    >>> (x["a"] * x["a"]).grades()
    {0}
    >>> x["B"].latex()
    'B_{e12} e_{12} + B_{e13} e_{13} + B_{e23} e_{23}'
    """
    if assumptions is None:
        assumptions = Assumptions(**kinds)
    basis = parse_signature(signature)
    free, norms = parameter_names(assumptions, basis)
    return build_values(assumptions, basis, Polynomials(free + norms))


# -- the prover --------------------------------------------------------------------------------
class _OutOfTime(BaseException):
    """BaseException, like KeyboardInterrupt: library code that catches Exception
    (SymPy has such blocks) must not swallow the time limit."""


def _size(x: Element, draws: int) -> np.ndarray:
    """max |coefficient| of x, draw by draw."""
    columns = [np.abs(np.broadcast_to(c, (draws,))) for c in x.terms.values()]
    return np.max(columns, axis=0) if columns else np.zeros(draws)


class _Problem:
    """One identity with its assumptions, definitions and symbol names: evaluated in any
    domain and case."""

    def __init__(self, left, right, assumptions, basis, definitions):
        self.left, self.right = left, right
        self.assumptions, self.basis = assumptions, basis
        self.definitions = definitions
        nodes = [left, right, *(node for _, node in definitions)]
        self.groups = exp_groups(*nodes)
        self.keys = symbol_keys(*nodes)
        self.free, self.norms = parameter_names(assumptions, basis)
        self.symbol_names = [name for names in self.keys.values() for name in names]

    def sides(self, domain, case) -> tuple[dict, Element, Element]:
        env = build_values(self.assumptions, self.basis, domain, case)
        ev = Evaluator(env, self.basis, domain, self.groups)
        for name, node in self.definitions:
            ev.define(name, node)
        return env, ev(self.left), ev(self.right)

    def polynomials(self) -> Polynomials:
        return Polynomials(self.free + self.norms + self.symbol_names, self.keys)

    def point(self, draws: Draws, j: int) -> Point:
        values = {name: xs[j] for name, xs in draws.exact.items()}
        signs = {name: s[j] for name, s in draws.signs.items()}
        return Point(values, signs, self.norms + self.symbol_names, self.keys)


def _exact_check(problem: _Problem, case, draws: Draws, j: int) -> Counterexample | None:
    """The exact counterexample at draw j, or None when the sides agree there."""
    dom = problem.point(draws, j)
    try:
        env, left, right = problem.sides(dom, case)
        subst = exact_values(dom)
    except InvalidPoint:
        return None
    numeric = any(r.kind != "normaliser" for r in dom.relations)
    digits = _DIGITS if numeric else None
    difference = left - right
    nonzero = False
    for coeff in difference.terms.values():
        expr = sympy.expand(to_sympy(reduce_modulo(coeff, dom), subst))
        if digits is None:
            nonzero = expr != 0
        else:
            nonzero = abs(sympy.N(expr, digits)) > sympy.Float(10) ** (10 - digits)
        if nonzero:
            break
    if not nonzero:
        return None
    basis = problem.basis

    def show(x: Element) -> dict[str, sympy.Expr]:
        out = {}
        for blade in basis.blades:
            if blade in x.terms:
                v = sympy.expand(to_sympy(x.terms[blade], subst))
                if v != 0:
                    out[basis.name(blade)] = v
        return out

    return Counterexample(
        values={name: show(env[name]) for name in problem.assumptions.kinds},
        lhs=show(left),
        rhs=show(right),
        digits=digits,
    )


def _check_timeout(timeout):
    if timeout is None:
        return None
    if isinstance(timeout, bool) or not isinstance(timeout, int | float) or math.isnan(timeout):
        raise ValueError(f"timeout: expected a positive number of seconds, got {timeout!r}")
    if timeout <= 0:
        raise ValueError(f"timeout: expected a positive number of seconds, got {timeout!r}")
    return None if timeout >= _NO_LIMIT else float(timeout)


def _notes(problem: _Problem, dom: Polynomials, cases, any_valid) -> list[str]:
    notes = []
    if len(cases) > 1:
        notes.append(f"proved in each of the {len(cases)} cases of the construction")
    kinds = {r.kind for r in dom.relations}
    inverses = [r for r in dom.relations if r.kind == "reciprocal" and r.names[0].startswith("i_")]
    where = []
    if inverses:
        where.append("the inverses in it exist")
    if "root" in kinds:
        where.append("the norms in it are real")
    if "log" in kinds:
        where.append("the rotors in it have a real log")
    if where:
        notes.append("holds wherever " + " and ".join(where))
    if not any_valid:
        notes.append(
            "no random draw satisfied the assumptions over the reals; "
            "the identity may hold vacuously"
        )
    assumptions, basis = problem.assumptions, problem.basis
    zero = [
        f"{name} (grade {k})"
        for name, k in {**assumptions.kvectors, **assumptions.blades}.items()
        if k > basis.n
    ]
    if zero:  # a grade above n declared by mistake would make any identity hold
        one = len(zero) == 1
        notes.append(
            f"{', '.join(zero)} {'is' if one else 'are'} 0 in {basis.label()} (no "
            f"grade above n = {basis.n}): the identity holds vacuously for "
            f"{'it' if one else 'them'}"
        )
    return notes


def _relations_text(problem: _Problem, dom: Polynomials) -> str:
    what = {"rotor": "N Ñ, N = exp∧(B)", "motor": "N Ñ, N = exp∧(B)", "unit": "w·w"}
    out = []
    for r in dom.relations:
        name = r.names[0]
        if r.kind == "normaliser":
            out.append(f"{name}²·λ = 1 (λ = {what[problem.assumptions.kinds[name[2:]]]})")
        elif r.kind == "exp":
            out.append(f"{name}² − δ·{r.names[1]}² = 1")
        elif r.kind == "reciprocal":
            out.append(f"{name}·λ = 1")
        elif r.kind == "root":
            out.append(f"{name}² = μ")
    return f" modulo {', '.join(dict.fromkeys(out))}" if out else ""


def prove(
    lhs: str,
    rhs: str | None = None,
    assumptions: Assumptions | None = None,
    *,
    signature=(3, 0),
    define=None,
    draws: int = _DRAWS,
    seed: int = 0,
    timeout: float | None = None,
    **kinds,
) -> Verdict:
    """Decide ``lhs == rhs`` for every value of the symbols allowed by ``assumptions``.

    Parameters
    ----------
    lhs : str
        The left side, or the whole identity ``"lhs == rhs"`` when ``rhs`` is None.
    rhs : str, optional
        The right side.
    assumptions : Assumptions, optional
        The symbols' kinds; or give them as keywords (``vectors="a,b"``, ``rotors="R"``,
        ``blades={"B": 2}``, ``orthogonal=[("a", "b")]``...), see :class:`Assumptions`.
    signature : tuple or str
        (p, q) or (p, q, r): p vectors square to +1, q to −1, r to 0 (null first).
    define : dict or list of str, optional
        Names for expressions, ``{"T": "1 + einf*t/2"}`` or ``["T=1 + einf*t/2"]``; each
        may use the symbols and the definitions before it (``--define`` on the command
        line).
    draws : int
        Random draws of the numeric pre-check.
    seed : int
        Seed of the draws (verdicts do not depend on it; counterexamples may).
    timeout : float, optional
        Give up after this many seconds with an *undecided* verdict (main thread only:
        it uses SIGALRM; ``inf`` is no limit). A long identity in a large algebra can grow
        polynomials of millions of terms; this bounds the wait.

    Returns
    -------
    Verdict

    Raises
    ------
    ValueError
        Bad input: a syntax error (column named), precedence that Python and the GA
        convention read differently, an undeclared symbol, a malformed declaration or
        definition, an operation that cannot be formed (the inverse of a null vector).

    Examples
    --------
    >>> prove("R*~R", "1", rotors="R", signature=(1, 3)).status
    'proved'
    >>> print(prove("n*a*n == a", signature=(3, 0), units="n", vectors="a").status)
    refuted
    >>> prove("a*inverse(a) == 1", vectors="a").status, prove("R/R == 1", rotors="R").status
    ('proved', 'proved')
    """
    start = time.perf_counter()
    text = lhs if rhs is None else f"{lhs} == {rhs}"
    left, right = parse_identity(text)
    if assumptions is None:
        assumptions = Assumptions(**kinds)
    elif kinds:
        raise ValueError("give the symbols either as an Assumptions or as keywords, not both")
    basis = parse_signature(signature)
    if isinstance(draws, bool) or not isinstance(draws, int) or not 1 <= draws <= MAX_DRAWS:
        raise ValueError(
            f"draws: expected an integer from 1 to {MAX_DRAWS}, got {shorten(repr(draws), 30)}"
        )
    timeout = _check_timeout(timeout)
    definitions = parse_definitions(define)
    for name, _ in definitions:
        if name in assumptions.kinds:
            raise AssumptionError(f"define {name}: {name!r} is already declared as a symbol")
    problem = _Problem(left, right, assumptions, basis, definitions)
    reading = f"{unparse(left)} == {unparse(right)}"
    where = [f"{name} = {unparse(node)}" for name, node in definitions]

    def verdict(status, detail, counterexample=None, notes=()):
        return Verdict(
            status,
            text,
            basis.label(),
            assumptions.describe(),
            time.perf_counter() - start,
            detail,
            counterexample,
            list(notes),
            reading=reading,
            definitions=where,
        )

    def decide() -> Verdict:
        try:
            cases = construction_cases(assumptions, basis)
            # 1-2: numeric pre-check, exact check of the suspects
            any_valid = False
            for case in cases:
                sample = Draws(draws, seed)
                with np.errstate(all="ignore"):  # a constant beyond a float is inf here
                    build_values(assumptions, basis, sample, case)
                    any_valid |= bool(sample.valid.any())
                    _, a, b = problem.sides(sample, case)
                    err, scale = _size(a - b, draws), 1.0 + _size(a, draws) + _size(b, draws)
                    valid = sample.valid & np.isfinite(err) & np.isfinite(scale)
                    order = np.argsort(-err / scale)
                suspects = [j for j in order if valid[j] and err[j] > 1e-9 * scale[j]]
                for j in suspects[:3]:
                    ce = _exact_check(problem, case, sample, int(j))
                    if ce is not None:
                        return verdict("refuted", "counterexample", ce)

            # 3: exact proof
            terms = 0
            for case in cases:
                dom = problem.polynomials()
                _, a, b = problem.sides(dom, case)
                difference = a - b
                terms += sum(len(c) for c in difference.terms.values())
                residue = {k: reduce_modulo(c, dom) for k, c in difference.terms.items()}
                residue = {k: c for k, c in residue.items() if c}
                if residue:
                    break
            else:
                how = _relations_text(problem, dom)
                detail = (
                    f"lhs − rhs = 0: {terms} polynomial terms over ℚ in {len(problem.free)} "
                    f"parameters reduce to 0{how}"
                    if terms
                    else f"lhs − rhs expands to 0 in {len(problem.free)} parameters "
                    "(nothing to reduce)"
                )
                return verdict("proved", detail, notes=_notes(problem, dom, cases, any_valid))

            # 4: a nonzero residue: look for an exact counterexample at more points
            for attempt in range(_EXTRA_POINTS):
                sample = Draws(draws, seed + 1 + attempt)
                with np.errstate(all="ignore"):
                    build_values(assumptions, basis, sample, case)
                for j in np.flatnonzero(sample.valid)[:2]:
                    ce = _exact_check(problem, case, sample, int(j))
                    if ce is not None:
                        return verdict("refuted", "counterexample", ce)
            some = next(iter(residue.values()))
            reason = (
                "the difference reduces to a nonzero polynomial but no exact counterexample "
                f"was found at {draws + 2 * _EXTRA_POINTS} random points"
            )
            kinds_used = {r.kind for r in dom.relations}
            if "exp" in kinds_used or "log" in kinds_used:
                reason = (
                    "the difference does not reduce to 0 using C² − δS² = 1 for each exp and "
                    "the addition theorem for arguments that are multiples of one another or "
                    "commuting parts of a sum, and no counterexample was found"
                )
            return verdict("undecided", reason + f" (a residual coefficient has {len(some)} terms)")
        except Unsupported as exc:
            return verdict("undecided", f"not supported: {exc}")
        except (NotInvertible, NotReal) as exc:  # pragma: no cover - evaluate names them
            raise EvaluationError(str(exc)) from None

    if timeout is None or threading.current_thread() is not threading.main_thread():
        return decide()
    armed = [True]

    def out_of_time(signum, frame):
        if armed[0]:
            raise _OutOfTime

    previous = signal.signal(signal.SIGALRM, out_of_time)
    # An exception raised in a garbage-collector callback is lost (hypothesis installs
    # one), so the collector pauses while the limit is armed; and the alarm repeats
    # every 0.1 s until disarmed, in case code elsewhere swallowed one.
    collecting = gc.isenabled()
    gc.disable()
    signal.setitimer(signal.ITIMER_REAL, timeout, 0.1)
    try:
        try:
            return decide()
        finally:
            armed[0] = False  # a signal still pending after this is ignored
            signal.setitimer(signal.ITIMER_REAL, 0)
    except _OutOfTime:
        return verdict("undecided", f"no decision within the time limit of {timeout:g} s")
    finally:
        signal.signal(signal.SIGALRM, previous)
        if collecting:
            gc.enable()
