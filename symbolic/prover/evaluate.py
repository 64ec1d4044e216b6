"""Evaluate a parsed expression to an :class:`~.element.Element`, in any domain.

The domain (:mod:`.domains`) gives numbers and, for what is not a polynomial in the
symbols' parameters, a symbol with its relation:

* ``exp(X)`` with X² = δ a scalar is C + S X with C² − δ S² = 1 (cos/sin, cosh/sinh or
  1, 1). Arguments that are rational multiples of one expression share one pair, the
  powers of exp(X/q) (so exp(B)² = exp(2B) is proved); a sum of parts with scalar squares
  that commute is the product of their exps (exp(A + B) = exp(A) exp(B) where A B = B A);
  any other exp is *undecided* (:class:`~.orthogonal.Unsupported`);
* ``inverse(x)`` (and x/y, x**-k) is x̃ / (x x̃) where x x̃ is a scalar (vectors, blades,
  versors), a constant where it reduces to one (a rotor: R⁻¹ = R̃);
* ``norm(x)`` = √⟨x x̃⟩₀ where that is real, ``norm2(x)`` = ⟨x x̃⟩₀;
* ``log(R)`` for a rotor R = a + b with b a bivector whose square is a scalar: φ b with φ
  the principal angle over √|b²|, and exp(log(R)) = R.

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

import math
from fractions import Fraction

from .basis import Basis
from .domains import NotInvertible, NotReal
from .element import Element
from .grammar import Binary, Call, Name, Node, Number, Unary, shorten, unparse
from .orthogonal import Unsupported

__all__ = [
    "EvaluationError",
    "Evaluator",
    "constant",
    "evaluate",
    "exp_groups",
    "summands",
    "symbol_keys",
]

_MAX_POWER = 32


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
    >>> constant(parse_expression("2**-2"))
    Fraction(1, 4)
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
        if node.op == "**":
            return None if (a == 0 and b < 0) else a ** int(b)
        return {"+": a + b, "-": a - b, "*": a * b}[node.op]
    return None


def _text(node: Node) -> str:
    return shorten(unparse(node), 40)


# -- exp: which arguments share a pair ----------------------------------------------------------
def summands(node: Node) -> list[Node]:
    """The terms of a sum, a difference's subtrahend negated: a + b − c → [a, b, −c].

    Examples
    --------
    >>> from ga_rotors.symbolic.prover.grammar import parse_expression
    >>> [unparse(t) for t in summands(parse_expression("A + B - 2*C"))]
    ['A', 'B', '-(2 * C)']
    """
    if isinstance(node, Binary) and node.op in "+-":
        right = node.right if node.op == "+" else Unary("-", node.right)
        return [*summands(node.left), right]
    return [node]


def _factor(node: Node) -> tuple[Fraction, Node]:
    """(k, core) with node = k · core, k rational, core free of a numeric factor."""
    k = Fraction(1)
    while True:
        value = constant(node)
        if value is not None:
            return k * value, Number(Fraction(1))
        if isinstance(node, Unary) and node.op in "+-":
            k, node = (k if node.op == "+" else -k), node.operand
        elif isinstance(node, Binary) and node.op == "*" and constant(node.left) is not None:
            k, node = k * constant(node.left), node.right
        elif isinstance(node, Binary) and node.op == "*" and constant(node.right) is not None:
            k, node = k * constant(node.right), node.left
        elif isinstance(node, Binary) and node.op == "/" and constant(node.right):
            k, node = k / constant(node.right), node.left
        else:
            return k, node


def _walk(nodes):
    stack = list(nodes)
    while stack:
        node = stack.pop()
        yield node
        for attr in ("operand", "left", "right"):
            if hasattr(node, attr):
                stack.append(getattr(node, attr))
        if isinstance(node, Call):
            stack.extend(node.args)


def exp_groups(*nodes: Node) -> dict[Node, tuple[Node, int, int]]:
    """atom -> (core, q, n): exp(atom) = exp(core/q)ⁿ, the atoms being every exp argument
    and every term of one that is a sum; atoms that are rational multiples of the same
    core share exp(core/q) (q the common denominator), so their C, S are one pair.

    Examples
    --------
    >>> from ga_rotors.symbolic.prover.grammar import parse_identity
    >>> groups = exp_groups(*parse_identity("exp(B)*exp(B/2) == exp(-3*B/2)"))
    >>> sorted((unparse(a), n) for a, (core, q, n) in groups.items())
    [('((-3) * B) / 2', -3), ('B', 2), ('B / 2', 1)]
    """
    atoms: list[Node] = []
    for node in _walk(nodes):
        if isinstance(node, Call) and node.name == "exp":
            arg = node.args[0]
            for atom in [arg, *summands(arg)] if len(summands(arg)) > 1 else [arg]:
                if atom not in atoms:
                    atoms.append(atom)
    by_core: dict[Node, list[tuple[Node, Fraction]]] = {}
    for atom in atoms:
        k, core = _factor(atom)
        by_core.setdefault(core, []).append((atom, k))
    out: dict[Node, tuple[Node, int, int]] = {}
    for core, members in by_core.items():
        q = math.lcm(*(k.denominator for _, k in members))
        if all(abs(k * q) <= _MAX_POWER for _, k in members):
            for atom, k in members:
                out[atom] = (core, q, int(k * q))
        else:  # too far apart to be powers of one pair: each its own
            for atom, _ in members:
                out[atom] = (atom, 1, 1)
    return out


def symbol_keys(*nodes: Node) -> dict[tuple, tuple[str, ...]]:
    """Names for every symbol an evaluation of ``nodes`` may make, by key.

    Keys: ``("exp", core, q)`` (C, S), ``("inv", node)`` (a reciprocal), ``("root", node)``
    and ``("log", node)`` (φ and 1/φ).

    Examples
    --------
    >>> from ga_rotors.symbolic.prover.grammar import parse_identity
    >>> keys = symbol_keys(*parse_identity("a/b + norm(a) == exp(B)"))
    >>> sorted(names for names in keys.values())
    [('C_1', 'S_1'), ('i_1',), ('r_1',)]
    """
    keys: dict[tuple, tuple[str, ...]] = {}
    counts = {"exp": 0, "inv": 0, "root": 0, "log": 0}

    def add(kind, key, *prefixes):
        if key in keys:
            return
        counts[kind] += 1
        keys[key] = tuple(f"{p}_{counts[kind]}" for p in prefixes)

    for core, q, _ in sorted(set(exp_groups(*nodes).values()), key=lambda g: unparse(g[0])):
        add("exp", ("exp", core, q), "C", "S")
    for node in _walk(nodes):
        if isinstance(node, Call) and node.name == "inverse":
            add("inv", ("inv", node.args[0]), "i")
        elif isinstance(node, Call) and node.name == "down":
            add("inv", ("inv", node), "i")
        elif isinstance(node, Binary) and node.op == "/" and constant(node.right) is None:
            add("inv", ("inv", node.right), "i")
        elif (
            isinstance(node, Binary)
            and node.op == "**"
            and node.right.value < 0
            and constant(node.left) is None
        ):
            add("inv", ("inv", node.left), "i")
        elif isinstance(node, Call) and node.name == "norm":
            add("root", ("root", node.args[0]), "r")
        elif isinstance(node, Call) and node.name == "log":
            add("log", ("log", node), "phi", "iphi")
    return keys


# -- evaluation -------------------------------------------------------------------------------
def _blade(basis: Basis, name: str, one) -> Element | None:
    if name == "I":
        return Element(basis, {basis.full: one})
    if name in ("eo", "einf"):
        pair = basis.conformal_pair()
        if pair is None:
            raise EvaluationError(
                f"{name}: eo and einf are the conformal model's null vectors; they exist in "
                f"Cl(p,1) with p >= 2 (e.g. --signature 4,1), not in {basis.label()}"
            )
        plus, minus = pair
        if name == "einf":
            return Element(basis, {plus: one, minus: one})
        half = one * Fraction(1, 2)
        return Element(basis, {plus: -half, minus: half})
    if name.startswith("e") and name[1:].isdigit():
        if basis.n > 9:
            raise EvaluationError(f"{name}: blade names need n <= 9")
        try:
            sign, blade = basis.blade_from_indices(tuple(int(d) for d in name[1:]))
        except ValueError as exc:
            raise EvaluationError(str(exc)) from None
        return Element(basis, {blade: one if sign > 0 else -one})
    return None


class Evaluator:
    """Evaluates expressions with one set of symbol values in one domain.

    Identical sub-expressions are computed once, across every expression this evaluator
    is called on, and exps whose arguments are rational multiples of one expression share
    one C, S: ``groups`` is :func:`exp_groups` of all of them.

    Examples
    --------
    >>> from fractions import Fraction
    >>> from ga_rotors.symbolic.prover.grammar import parse_expression
    >>> class Exact:
    ...     def const(self, q): return Fraction(q)
    >>> ev = Evaluator({}, Basis(2), Exact())
    >>> ev(parse_expression("e1*e2")), ev(parse_expression("(e1*e2)*(e1*e2)"))
    (e12, -1)
    """

    def __init__(self, env: dict[str, Element], basis: Basis, domain, groups=None):
        self.env, self.basis, self.domain = dict(env), basis, domain
        self.memo: dict[Node, Element] = {}
        self.groups = groups or {}
        self.log_pairs: dict[Node, tuple] = {}

    def define(self, name: str, node: Node) -> None:
        """Evaluate a user definition and make ``name`` stand for its value."""
        self.env[name] = self(node)

    def __call__(self, node: Node) -> Element:
        if node in self.memo:
            return self.memo[node]
        value = self._value(node)
        self.memo[node] = value
        return value

    def one(self) -> Element:
        return Element(self.basis, {0: self.domain.const(1)})

    def _value(self, node: Node) -> Element:
        basis, domain = self.basis, self.domain
        if isinstance(node, Number):
            return Element(basis, {0: domain.const(node.value)})
        if isinstance(node, Name):
            if node.name in self.env:
                return self.env[node.name]
            blade = _blade(basis, node.name, domain.const(1) if domain else 1)
            if blade is None:
                raise EvaluationError(
                    f"{node.name!r} is not declared; declare it with a kind "
                    "(--vectors, --rotors, --scalars, ...) or --define it"
                )
            return blade
        if isinstance(node, Unary):
            x = self(node.operand)
            return {"-": lambda: -x, "+": lambda: x, "~": lambda: ~x}[node.op]()
        if isinstance(node, Binary):
            return self._binary(node)
        if isinstance(node, Call):
            return self._call(node)
        raise EvaluationError(f"cannot evaluate {node!r}")  # pragma: no cover

    def _binary(self, node: Binary) -> Element:
        if node.op == "/":
            divisor = constant(node.right)
            if divisor == 0:
                raise EvaluationError("division by zero")
            if divisor is not None:
                return self(node.left).scale(self.domain.const(1 / divisor))
            return self(node.left) * self._inverse(node.right)
        if node.op == "**":
            power = int(node.right.value)
            x = self._inverse(node.left) if power < 0 else self(node.left)
            result = self.one()
            for _ in range(abs(power)):
                result = result * x
            return result
        a, b = self(node.left), self(node.right)
        if node.op == ">>":
            return a * b * ~a
        return {
            "+": lambda: a + b,
            "-": lambda: a - b,
            "*": lambda: a * b,
            "^": lambda: a ^ b,
            "|": lambda: a | b,
            "&": lambda: a.vee(b),
        }[node.op]()

    # -- functions ----------------------------------------------------------------------------
    def _call(self, node: Call) -> Element:
        name, args = node.name, node.args
        if name == "grade":
            k = constant(args[1])
            if k is None or k.denominator != 1 or k < 0:
                raise EvaluationError("grade(x, k): k must be a non-negative integer")
            return self(args[0]).grade(int(k))
        if name in ("exp", "log", "inverse", "norm", "up", "down"):
            return getattr(self, f"_{name}")(node)
        if len(args) == 2:
            a, b = self(args[0]), self(args[1])
            half = self.domain.const(Fraction(1, 2))
            return {
                "lc": a.lc,
                "rc": a.rc,
                "inner": a.__or__,
                "dot": a.dot,
                "scalar": a.scalar_product,
                "comm": lambda y: (a * y - y * a).scale(half),
                "vee": a.vee,
                "meet": a.__xor__,
                "join": a.vee,
                "sandwich": lambda y: a * y * ~a,
            }[name](b)
        x = self(args[0])
        return {
            "rev": lambda: ~x,
            "involute": x.involute,
            "conj": x.conjugate,
            "dual": x.dual,
            "undual": x.undual,
            "norm2": lambda: (x * ~x).grade(0),
            "even": lambda: Element(
                self.basis, {b: c for b, c in x.terms.items() if not b.bit_count() % 2}
            ),
        }[name]()

    def _inverse(self, arg) -> Element:
        if isinstance(arg, Call) and arg.name == "inverse":  # called as inverse(x)
            arg = arg.args[0]
        x = self(arg)
        lam = self.domain.scalar_value(x * ~x)
        if lam is None:
            raise Unsupported(
                f"inverse({_text(arg)}): its product with its reverse is not a scalar, and "
                "the prover inverts only elements x with x x̃ a scalar (vectors, blades, versors)"
            )
        try:
            return (~x).scale(self.domain.reciprocal(("inv", arg), lam))
        except NotInvertible as exc:
            raise EvaluationError(
                f"inverse({_text(arg)}): not invertible: x x̃ = ⟨x x̃⟩₀ = 0; {exc}"
            ) from None

    def _norm(self, node: Call) -> Element:
        x = self(node.args[0])
        mu = (x * ~x).terms.get(0, self.domain.const(0))
        try:
            return Element(self.basis, {0: self.domain.root(("root", node.args[0]), mu)})
        except NotReal as exc:
            raise EvaluationError(
                f"norm({_text(node.args[0])}): ⟨x x̃⟩₀ is negative, the norm is not real: "
                f"{exc}; use norm2"
            ) from None

    def _exp(self, node: Call) -> Element:
        arg = node.args[0]
        parts = summands(arg)
        domain = self.domain
        if len(parts) > 1:
            values = [self(p) for p in parts]
            if all(domain.is_scalar(v * v) for v in values) and all(
                domain.is_zero(a * b - b * a) for i, a in enumerate(values) for b in values[i + 1 :]
            ):
                result = self.one()
                for p in parts:
                    result = result * self._exp_atom(p)
                return result
        if not domain.is_scalar(self(arg) * self(arg)):
            raise Unsupported(
                f"exp({_text(arg)}): its square is not a scalar in {self.basis.label()} and it "
                "is not written as a sum of commuting parts whose squares are, so exp has no "
                "closed form here (a simple bivector, --blades B:2, or exp(B1 + B2) with "
                "B1*B2 == B2*B1 has one)"
            )
        return self._exp_atom(arg)

    def _exp_atom(self, atom: Node) -> Element:
        core, q, power = self.groups.get(atom, (atom, 1, 1))
        base = self(core)
        if q != 1:
            base = base.scale(self.domain.const(Fraction(1, q)))
        if isinstance(core, Call) and core.name == "log" and q == 1:
            self(core)
            c, s = self.log_pairs[core]
        else:
            delta = self.domain.scalar_value(base * base)
            if delta is None:
                raise Unsupported(
                    f"exp({_text(atom)}): its square is not a scalar, so exp has no closed form"
                )
            c, s = self.domain.exp_pair(("exp", core, q), delta)
        factor = base.scale(s if power >= 0 else -s) + c
        result = self.one()
        for _ in range(abs(power)):
            result = result * factor
        return result

    def _log(self, node: Call) -> Element:
        arg = node.args[0]
        x = self(arg)
        domain = self.domain
        even = [b for b in self.basis.blades if b.bit_count() in (0, 2)]
        if not domain.lies_in(x, set(even)):
            raise Unsupported(
                f"log({_text(arg)}): it has parts of grade 4 or more or of odd grade; the "
                "prover's log is that of a rotor a + b with b a bivector whose square is a "
                "scalar (a simple bivector log)"
            )
        a = x.terms.get(0, domain.const(0))
        b = x.grade(2)
        beta = domain.scalar_value(b * b)
        if beta is None:
            raise Unsupported(
                f"log({_text(arg)}): its bivector part's square is not a scalar, so its log is "
                "not a simple bivector"
            )
        if not domain.is_zero(x * ~x - 1):
            raise Unsupported(
                f"log({_text(arg)}): it is not a rotor (x x̃ = 1 does not follow from the "
                "assumptions); the prover's log is that of rotors"
            )
        phi, inverse = domain.log_factor(("log", node), a, beta)
        self.log_pairs[node] = (a, inverse)
        return b.scale(phi)

    def _conformal_argument(self, node: Call) -> Element:
        """The argument of up or down, once the algebra is known to be conformal."""
        if self.basis.conformal_pair() is None:
            raise EvaluationError(
                f"{node.name}({_text(node.args[0])}): the conformal model is Cl(p,1) with "
                f"p >= 2 (e.g. --signature 4,1), not {self.basis.label()}"
            )
        return self(node.args[0])

    def _up(self, node: Call) -> Element:
        basis, domain = self.basis, self.domain
        arg = node.args[0]
        x = self._conformal_argument(node)
        one = domain.const(1)
        if not domain.lies_in(x, set(basis.euclidean_vectors())):
            raise EvaluationError(
                f"up({_text(arg)}): the argument must be a Euclidean vector (e1 … "
                f"e{basis.p - 1}; declare it with --euclidean)"
            )
        einf, eo = _blade(basis, "einf", one), _blade(basis, "eo", one)
        return x + (x * x).scale(domain.const(Fraction(1, 2))) * einf + eo

    def _down(self, node: Call) -> Element:
        basis, domain = self.basis, self.domain
        arg = node.args[0]
        x = self._conformal_argument(node)
        vectors = {1 << i for i in range(basis.n)}
        if not domain.lies_in(x, vectors):
            raise EvaluationError(f"down({_text(arg)}): the argument must be a vector")
        einf = _blade(basis, "einf", domain.const(1))
        weight = -(x | einf).terms.get(0, domain.const(0))  # −X·einf: 1 for up(x)
        try:
            scale = domain.reciprocal(("inv", node), weight)
        except NotInvertible:
            raise EvaluationError(
                f"down({_text(arg)}): X·einf = 0 for every value: X is not a finite point"
            ) from None
        base = basis.euclidean_vectors()
        return Element(basis, {b: c for b, c in x.terms.items() if b in base}).scale(scale)


def evaluate(node: Node, env: dict[str, Element], basis: Basis, domain) -> Element:
    """The value of one expression with the symbols of ``env`` (see :class:`Evaluator`).

    Examples
    --------
    >>> from fractions import Fraction
    >>> from ga_rotors.symbolic.prover.grammar import parse_expression
    >>> class Exact:
    ...     def const(self, q): return Fraction(q)
    >>> evaluate(parse_expression("grade(e1*e2 + 3, 0)/2"), {}, Basis(2), Exact())
    3/2
    """
    return Evaluator(env, basis, domain, exp_groups(node))(node)
