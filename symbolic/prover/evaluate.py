"""Evaluate a parsed expression to an :class:`~.element.Element`, in any domain.

The domain gives numbers (``const``) and the two exponential coefficients of
``exp(X) = C + S X`` (``exp_pair(node, delta)`` with δ = X², which must be a scalar:
C = cosh √δ, S = sinh √δ / √δ for δ > 0, cos and sin for δ < 0, C = S = 1 for δ = 0;
in every case C² − δ S² = 1).

Examples
--------
>>> from fractions import Fraction
>>> from ga_rotors.symbolic.prover.basis import Basis
>>> from ga_rotors.symbolic.prover.grammar import parse_expression
>>> class Exact:
...     def const(self, q): return Fraction(q)
>>> e1 = Element.blade(Basis(3), 1, Fraction(1))
>>> evaluate(parse_expression("(a + e2)*(a - e2) + I"), {"a": e1}, Basis(3), Exact())
-2*e12 + e123
"""

from __future__ import annotations

from fractions import Fraction

from .basis import Basis
from .element import DegenerateDualError, Element
from .grammar import Binary, Call, Name, Node, Number, Unary

__all__ = ["EvaluationError", "constant", "evaluate"]


class EvaluationError(ValueError):
    """The expression cannot be formed from the declared symbols (the message says why).

    Examples
    --------
    >>> from ga_rotors.symbolic.prover.grammar import parse_expression
    >>> evaluate(parse_expression("x + 1"), {}, Basis(2), None)
    Traceback (most recent call last):
    ...
    ga_rotors.symbolic.prover.evaluate.EvaluationError: 'x' is not declared; declare it ...
    """


def constant(node: Node) -> Fraction | None:
    """The value of an expression built from numbers alone, else None.

    Examples
    --------
    >>> from ga_rotors.symbolic.prover.grammar import parse_expression
    >>> constant(parse_expression("-(1 + 2)/4")), constant(parse_expression("2*a"))
    (Fraction(-3, 4), None)
    """
    if isinstance(node, Number):
        return node.value
    if isinstance(node, Unary) and node.op in "+-":
        v = constant(node.operand)
        return None if v is None else (v if node.op == "+" else -v)
    if isinstance(node, Binary) and node.op in ("+", "-", "*", "/", "**"):
        a, b = constant(node.left), constant(node.right)
        if a is None or b is None:
            return None
        if node.op == "/":
            return None if b == 0 else a / b
        return {"+": a + b, "-": a - b, "*": a * b, "**": a**b if b >= 0 else None}[node.op]
    return None


def _blade(basis: Basis, name: str, one) -> Element | None:
    if name == "I":
        return Element(basis, {basis.full: one})
    if name.startswith("e") and name[1:].isdigit():
        if basis.n > 9:
            raise EvaluationError(f"{name}: blade names need n <= 9")
        try:
            sign, blade = basis.blade_from_indices(tuple(int(d) for d in name[1:]))
        except ValueError as exc:
            raise EvaluationError(str(exc)) from None
        return Element(basis, {blade: one if sign > 0 else -one})
    return None


def evaluate(node: Node, env: dict[str, Element], basis: Basis, domain, memo=None) -> Element:
    """The value of ``node`` with the symbols of ``env``.

    Identical sub-expressions are computed once (``memo``), and ``exp`` of the same
    sub-expression gets the same C and S.

    Examples
    --------
    >>> from fractions import Fraction
    >>> from ga_rotors.symbolic.prover.grammar import parse_expression
    >>> class Exact:
    ...     def const(self, q): return Fraction(q)
    >>> evaluate(parse_expression("grade(e1*e2 + 3, 0)/2"), {}, Basis(2), Exact())
    3/2
    """
    memo = {} if memo is None else memo
    if node in memo:
        return memo[node]
    value = _evaluate(node, env, basis, domain, memo)
    memo[node] = value
    return value


def _evaluate(node, env, basis, domain, memo) -> Element:
    ev = lambda n: evaluate(n, env, basis, domain, memo)  # noqa: E731
    if isinstance(node, Number):
        return Element(basis, {0: domain.const(node.value)})
    if isinstance(node, Name):
        if node.name in env:
            return env[node.name]
        blade = _blade(basis, node.name, domain.const(1) if domain else 1)
        if blade is None:
            raise EvaluationError(
                f"{node.name!r} is not declared; declare it with a kind "
                "(--vectors, --rotors, --scalars, ...)"
            )
        return blade
    if isinstance(node, Unary):
        x = ev(node.operand)
        return {"-": lambda: -x, "+": lambda: x, "~": lambda: ~x}[node.op]()
    if isinstance(node, Binary):
        if node.op == "/":
            divisor = constant(node.right)
            if divisor is None:
                raise EvaluationError("division is only by a number (there is no general inverse)")
            if divisor == 0:
                raise EvaluationError("division by zero")
            return ev(node.left).scale(domain.const(1 / divisor))
        if node.op == "**":
            x, result = ev(node.left), Element(basis, {0: domain.const(1)})
            for _ in range(int(node.right.value)):
                result = result * x
            return result
        a, b = ev(node.left), ev(node.right)
        return {
            "+": lambda: a + b,
            "-": lambda: a - b,
            "*": lambda: a * b,
            "^": lambda: a ^ b,
            "|": lambda: a | b,
        }[node.op]()
    if isinstance(node, Call):
        return _call(node, ev, basis, domain)
    raise EvaluationError(f"cannot evaluate {node!r}")  # pragma: no cover


def _call(node: Call, ev, basis: Basis, domain) -> Element:
    name, args = node.name, node.args
    if name == "grade":
        k = constant(args[1])
        if k is None or k.denominator != 1 or k < 0:
            raise EvaluationError("grade(x, k): k must be a non-negative integer")
        return ev(args[0]).grade(int(k))
    if len(args) == 2:
        a, b = ev(args[0]), ev(args[1])
        return {
            "lc": a.lc,
            "rc": a.rc,
            "inner": a.__or__,
            "dot": a.dot,
            "scalar": a.scalar_product,
            "comm": lambda y: (a * y - y * a).scale(domain.const(Fraction(1, 2))),
        }[name](b)
    x = ev(args[0])
    if name == "dual":
        try:
            return x.dual()
        except DegenerateDualError as exc:
            raise EvaluationError(str(exc)) from None
    if name == "exp":
        # exp(−X) = C − S X with the C, S of exp(X): one pair for both, so that
        # exp(X) exp(−X) = C² − δS² = 1 is seen
        flip = isinstance(args[0], Unary) and args[0].op == "-"
        if flip:
            node, x = Call("exp", (args[0].operand,)), -x
        square = x * x
        delta = square.terms.get(0, domain.const(0))
        if not domain.is_scalar(square):
            raise EvaluationError(
                f"exp({_text(args[0])}): its square is not a scalar in {basis.label()}, so "
                "exp has no closed form here; use a simple bivector (--blades B:2)"
            )
        c, s = domain.exp_pair(node, delta)
        return x.scale(-s if flip else s) + c
    return {
        "rev": lambda: ~x,
        "involute": x.involute,
        "conj": x.conjugate,
        "even": lambda: Element(basis, {b: c for b, c in x.terms.items() if not b.bit_count() % 2}),
    }[name]()


def _text(node: Node) -> str:
    if isinstance(node, Name):
        return node.name
    return "..."
