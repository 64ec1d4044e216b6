"""``prove(lhs, rhs, assumptions)``: an exact verdict on a geometric-algebra identity.

How a verdict is reached:

1. **Numeric pre-check.** The symbols are drawn at random rational parameters (many
   draws at once, numpy arrays as coefficients) and both sides are compared in floating
   point. A draw where they differ is only a *suspect*.
2. **Exact check of a suspect.** At that draw's rational parameters both sides are
   recomputed exactly (normalisers c = 1/√λ and exp's cos/sin kept exact in SymPy).
   If the difference is not zero the verdict is *refuted*, with the counterexample.
3. **Exact proof.** Otherwise every coefficient of lhs − rhs is computed as a
   polynomial over ℚ in the free parameters and reduced modulo the assumptions
   (c² λ = 1 for each normaliser, C² − δ S² = 1 for each exp); *proved* means every
   reduced coefficient is the zero polynomial. No floating point takes part.
4. A nonzero reduced difference with no counterexample found at further exact random
   points is *undecided*, with the reason (for instance an identity that needs more
   of exp than C² − δ S² = 1, such as exp(B)² = exp(2B)).

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
"""

from __future__ import annotations

import gc
import signal
import threading
import time
from itertools import product

import numpy as np
import sympy

from .assumptions import Assumptions
from .basis import Basis, cached_basis
from .domains import Draws, InvalidPoint, Point, Polynomials, reduce_modulo
from .element import Element
from .evaluate import evaluate
from .grammar import Call, Node, Unary, parse_identity
from .symbols import Unsupported, build_values, null_cases, parameter_names
from .verdict import Counterexample, Verdict

__all__ = ["elements", "parse_signature", "prove"]

_DRAWS = 16
_EXTRA_POINTS = 6

#: Most random draws of the numeric pre-check (10⁵ take about half a second; 10¹² would
#: allocate terabytes).
MAX_DRAWS = 1_000_000
_DIGITS = 50


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
        numbers = [int(str(x).strip()) for x in items]
    except (TypeError, ValueError):
        numbers = []
    if len(numbers) not in (2, 3) or min(numbers) < 0:
        raise ValueError(
            f"signature: expected p,q or p,q,r (non-negative integers), got {signature!r}"
        )
    if sum(numbers) == 0 or sum(numbers) > 6:
        raise ValueError(f"signature: n = p + q + r must be 1..6, got {sum(numbers)}")
    return cached_basis(*numbers)


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


def _exp_nodes(*nodes: Node) -> list[Node]:
    found: list[Node] = []

    def walk(node):
        if isinstance(node, Call):
            for a in node.args:
                walk(a)
            if node.name == "exp":
                arg = node.args[0]
                if isinstance(arg, Unary) and arg.op == "-":  # exp(−X) shares exp(X)'s C, S
                    node = Call("exp", (arg.operand,))
                if node not in found:
                    found.append(node)
        for attr in ("operand", "left", "right"):
            if hasattr(node, attr):
                walk(getattr(node, attr))

    for n in nodes:
        walk(n)
    return found


def _size(x: Element, draws: int) -> np.ndarray:
    """max |coefficient| of x, draw by draw."""
    columns = [np.abs(np.broadcast_to(c, (draws,))) for c in x.terms.values()]
    return np.max(columns, axis=0) if columns else np.zeros(draws)


def _ring_names(free, norms, exps) -> tuple[list[str], dict[Node, tuple[str, str]]]:
    exp_names = {node: (f"C_{k}", f"S_{k}") for k, node in enumerate(exps, 1)}
    return free + norms + [x for pair in exp_names.values() for x in pair], exp_names


def _to_sympy(f, domain: Polynomials, point_values: dict[str, sympy.Expr]) -> sympy.Expr:
    return f.as_expr().subs(
        {sympy.Symbol(name): v for name, v in point_values.items()}, simultaneous=True
    )


def _exact_check(lhs, rhs, assumptions, basis, case, draws: Draws, j: int, free, norms, exps):
    """The exact counterexample at draw j, or None when the sides agree there."""
    values = {name: xs[j] for name, xs in draws.exact.items()}
    signs = {name: s[j] for name, s in draws.signs.items()}
    names, exp_names = _ring_names([], norms, exps)
    dom = Point(values, signs, names, exp_names)
    try:
        env = build_values(assumptions, basis, dom, case)
        memo: dict = {}
        left = evaluate(lhs, env, basis, dom, memo)
        right = evaluate(rhs, env, basis, dom, memo)
    except InvalidPoint:
        return None
    # exact values of the normalisers and of exp's C, S at this point
    subst: dict[str, sympy.Expr] = {}
    for c, lam in dom.norms:
        subst[c] = int(signs.get(c, 1)) / sympy.sqrt(sympy.Rational(str(lam.LC)))
    for c, s, delta in dom.exps:
        d = sympy.nsimplify(_to_sympy(delta, dom, subst))
        theta = sympy.sqrt(sympy.Abs(d))
        if d == 0:
            subst[c], subst[s] = sympy.Integer(1), sympy.Integer(1)
        elif d < 0:
            subst[c], subst[s] = sympy.cos(theta), sympy.sin(theta) / theta
        else:
            subst[c], subst[s] = sympy.cosh(theta), sympy.sinh(theta) / theta
    digits = _DIGITS if dom.exps else None
    difference = left - right
    nonzero = False
    for coeff in difference.terms.values():
        expr = sympy.expand(_to_sympy(reduce_modulo(coeff, dom), dom, subst))
        if digits is None:
            nonzero = expr != 0
        else:
            nonzero = abs(sympy.N(expr, digits)) > sympy.Float(10) ** (10 - digits)
        if nonzero:
            break
    if not nonzero:
        return None

    def show(x: Element) -> dict[str, sympy.Expr]:
        out = {}
        for blade in basis.blades:
            if blade in x.terms:
                v = sympy.expand(_to_sympy(x.terms[blade], dom, subst))
                if v != 0:
                    out[basis.name(blade)] = v
        return out

    return Counterexample(
        values={name: show(x) for name, x in env.items()},
        lhs=show(left),
        rhs=show(right),
        digits=digits,
    )


def prove(
    lhs: str,
    rhs: str | None = None,
    assumptions: Assumptions | None = None,
    *,
    signature=(3, 0),
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
    draws : int
        Random draws of the numeric pre-check.
    seed : int
        Seed of the draws (verdicts do not depend on it; counterexamples may).
    timeout : float, optional
        Give up after this many seconds with an *undecided* verdict (main thread only:
        it uses SIGALRM). A long identity in a large algebra can grow polynomials of
        millions of terms; this bounds the wait.

    Returns
    -------
    Verdict

    Raises
    ------
    ValueError
        Bad input: a syntax error (column named), an undeclared symbol, a malformed
        declaration, an operation the metric does not allow (dual when I² = 0).

    Examples
    --------
    >>> prove("R*~R", "1", rotors="R", signature=(1, 3)).status
    'proved'
    >>> print(prove("n*a*n == a", signature=(3, 0), units="n", vectors="a").status)
    refuted
    """
    start = time.perf_counter()
    text = lhs if rhs is None else f"{lhs} == {rhs}"
    left, right = parse_identity(text)
    if assumptions is None:
        assumptions = Assumptions(**kinds)
    elif kinds:
        raise ValueError("give the symbols either as an Assumptions or as keywords, not both")
    basis = parse_signature(signature)
    if not isinstance(draws, int) or not 1 <= draws <= MAX_DRAWS:
        raise ValueError(f"draws: expected an integer from 1 to {MAX_DRAWS}, got {draws!r}")
    free, norms = parameter_names(assumptions, basis)
    exps = _exp_nodes(left, right)
    nulls = [n for n, k in assumptions.kinds.items() if k == "null"]
    cases = [
        dict(zip(nulls, combo, strict=True))
        for combo in product(*(range(null_cases(basis)) for _ in nulls))
    ]

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
        )

    if timeout is not None and (not isinstance(timeout, int | float) or timeout <= 0):
        raise ValueError(f"timeout: expected a positive number of seconds, got {timeout!r}")

    def decide() -> Verdict:
        try:
            # 1-2: numeric pre-check, exact check of the suspects
            any_valid = False
            for case in cases:
                sample = Draws(draws, seed)
                with np.errstate(all="ignore"):
                    env = build_values(assumptions, basis, sample, case)
                    memo: dict = {}
                    a = evaluate(left, env, basis, sample, memo)
                    b = evaluate(right, env, basis, sample, memo)
                err, scale = _size(a - b, draws), 1.0 + _size(a, draws) + _size(b, draws)
                valid = sample.valid & np.isfinite(err) & np.isfinite(scale)
                any_valid |= bool(valid.any())
                order = np.argsort(-err / scale)
                suspects = [j for j in order if valid[j] and err[j] > 1e-9 * scale[j]]
                for j in suspects[:3]:
                    ce = _exact_check(
                        left, right, assumptions, basis, case, sample, int(j), free, norms, exps
                    )
                    if ce is not None:
                        return verdict("refuted", "counterexample", ce)

            # 3: exact proof
            terms = 0
            for case in cases:
                names, exp_names = _ring_names(free, norms, exps)
                dom = Polynomials(names, exp_names)
                env = build_values(assumptions, basis, dom, case)
                memo = {}
                difference = evaluate(left, env, basis, dom, memo) - evaluate(
                    right, env, basis, dom, memo
                )
                terms += sum(len(c) for c in difference.terms.values())
                residue = {b: reduce_modulo(c, dom) for b, c in difference.terms.items()}
                residue = {b: c for b, c in residue.items() if c}
                if residue:
                    break
            else:
                what = {"rotor": "N Ñ, N = exp∧(B)", "unit": "w·w"}
                relations = [
                    f"{c}²·λ = 1 (λ = {what[assumptions.kinds[c[2:]]]})" for c, _ in dom.norms
                ] + [f"{c}² − δ·{s}² = 1" for c, s, _ in dom.exps]
                how = f" modulo {', '.join(relations)}" if relations else ""
                notes = []
                if len(cases) > 1:
                    notes.append(f"proved on each of the {len(cases)} pieces of the null cone")
                if not any_valid:
                    notes.append(
                        "no random draw satisfied the assumptions over the reals; "
                        "the identity may hold vacuously"
                    )
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
                detail = (
                    f"lhs − rhs = 0: {terms} polynomial terms over ℚ in {len(free)} parameters "
                    f"reduce to 0{how}"
                    if terms
                    else f"lhs − rhs expands to 0 in {len(free)} parameters (nothing to reduce)"
                )
                return verdict("proved", detail, notes=notes)

            # 4: a nonzero residue: look for an exact counterexample at more points
            for attempt in range(_EXTRA_POINTS):
                sample = Draws(draws, seed + 1 + attempt)
                with np.errstate(all="ignore"):
                    build_values(assumptions, basis, sample, case)
                for j in np.flatnonzero(sample.valid)[:2]:
                    ce = _exact_check(
                        left, right, assumptions, basis, case, sample, int(j), free, norms, exps
                    )
                    if ce is not None:
                        return verdict("refuted", "counterexample", ce)
            some = next(iter(residue.values()))
            reason = (
                "the difference reduces to a nonzero polynomial but no exact counterexample "
                f"was found at {draws + 2 * _EXTRA_POINTS} random points"
            )
            if exps:
                reason = (
                    "the difference does not reduce to 0 using only C² − δS² = 1 for each exp "
                    "(the prover does not use addition theorems such as exp(B)² = exp(2B)), and "
                    "no counterexample was found"
                )
            return verdict("undecided", reason + f" (a residual coefficient has {len(some)} terms)")
        except Unsupported as exc:
            return verdict("undecided", f"not supported: {exc}")

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
