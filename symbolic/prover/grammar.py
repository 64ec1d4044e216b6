"""The identity language: a hand-written tokenizer and two precedence-climbing readings.

Nothing is evaluated as Python: the text becomes a tree of :class:`Node` objects, and
anything outside the grammar is a :class:`ParseError` naming the column.

**No silent precedence surprise.** Users come to the prover from two habits that read
``a*b^c`` differently: Python's operator precedence, which ``clifford``, ``galgebra`` and
``kingdon`` inherit (``*`` before ``^`` before ``|``: ``(a*b)^c``), and the GA literature's
(Hestenes & Sobczyk, Doran & Lasenby: outer and inner products before the geometric
product: ``a*(b^c)``). Every expression is read both ways; where the two trees agree the
expression is accepted, where they differ it is refused with both readings fully
parenthesised, so a user of either habit never gets a verdict on an identity they did not
mean. Python's precedence, loosest first:

===== ================================== ==============================================
level Python (clifford, galgebra, kingdon) GA convention
===== ================================== ==============================================
1     ``|``                              ``>>`` (does not chain)
2     ``^``                              ``+`` ``-``
3     ``&``                              ``*`` ``/``
4     ``>>``                             ``^`` ``|`` ``&`` (``|`` does not chain; two
                                         different ones need parentheses)
5     ``+`` ``-``                        unary ``-`` ``+`` ``~``
6     ``*`` ``/``                        ``**``
7     unary ``-`` ``+`` ``~``
8     ``**``
===== ================================== ==============================================

``==`` separates the two sides (exactly one). ``**`` takes an integer exponent, negative
ones included (``a**-1``; ``-a**2`` is −(a²) in both readings). All binary operators are
left-associative. So ``a + b*c``, ``(a^b)*c``, ``a^b^c``, ``~a*b`` and ``R*S >> x`` are
read alike and accepted, while ``a*b^c``, ``a^b + c`` (Python: a^(b+c)) and ``a & b*c``
are refused with both readings.

Names: declared symbols; basis blades (``e1``, ``e12``, ``e31`` = −e13; ``e0`` … in
Cl(p, q, 1)); ``I`` (the pseudoscalar); ``eo`` and ``einf`` (the conformal model's null
vectors). Functions are listed in :data:`FUNCTIONS`.

Examples
--------
>>> parse_identity("(a^b)|c == a*(b|c) - b*(a|c)")[0]
Binary(op='|', left=Binary(op='^', left=Name(name='a'), right=Name(name='b')), right=Name(name='c'))
>>> unparse(parse_expression("(a^b^c) + ~a*b"))
'((a ^ b) ^ c) + ((~a) * b)'
>>> parse_expression("a*b^c")
Traceback (most recent call last):
...
ga_rotors.symbolic.prover.grammar.ParseError: expression: the readings differ: Python's ...
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from decimal import Decimal
from fractions import Fraction

__all__ = [
    "FUNCTIONS",
    "MAX_DEFINITIONS",
    "RESERVED_NAMES",
    "Binary",
    "Call",
    "Name",
    "Node",
    "Number",
    "ParseError",
    "Unary",
    "names_in",
    "parse_expression",
    "parse_identity",
    "shorten",
    "unparse",
]

#: function name -> number of arguments.
FUNCTIONS: dict[str, int] = {
    "grade": 2,
    "lc": 2,
    "rc": 2,
    "inner": 2,
    "dot": 2,
    "scalar": 2,
    "comm": 2,
    "rev": 1,
    "involute": 1,
    "conj": 1,
    "dual": 1,
    "undual": 1,
    "even": 1,
    "exp": 1,
    "log": 1,
    "inverse": 1,
    "norm2": 1,
    "norm": 1,
    "vee": 2,
    "meet": 2,
    "join": 2,
    "sandwich": 2,
    "up": 1,
    "down": 1,
}

#: names that are not blades but mean a fixed element: the conformal model's null vectors.
RESERVED_NAMES = ("I", "eo", "einf")
#: at most this many user definitions in one identity.
MAX_DEFINITIONS = 50

_MAX_LENGTH = 2000
_MAX_DEPTH = 60  # parentheses, calls and unary operators
_MAX_HEIGHT = 200  # the tree: a chain of 200 operators counts as 200 levels
_MAX_EXPONENT = 32
_ECHO = 60  # characters of the input an error message repeats at most
_MAX_NAME = 40
_TOKEN = re.compile(
    r"\s*(?:(?P<number>\d+(?:\.\d*)?|\.\d+)|(?P<name>[A-Za-z_][A-Za-z0-9_]*)"
    r"|(?P<op>\*\*|==|>>|[-+*/^|&~(),]))"
)


class ParseError(ValueError):
    """The text is not an identity of the grammar; the message names the column.

    Examples
    --------
    >>> parse_identity("a * == b")
    Traceback (most recent call last):
    ...
    ga_rotors.symbolic.prover.grammar.ParseError: column 5: expected a number, a name or '(', ...
    """


def shorten(text: str, limit: int = _ECHO) -> str:
    """``text`` cut to ``limit`` characters with an ellipsis, for one-line messages.

    Examples
    --------
    >>> shorten("a" * 100, 10)
    'aaaaaaaaa…'
    """
    return text if len(text) <= limit else text[: limit - 1] + "…"


class Node:
    """Base class of the syntax tree.

    Examples
    --------
    >>> isinstance(parse_expression("a"), Node)
    True
    """

    __slots__ = ()


@dataclass(frozen=True)
class Number(Node):
    """An exact rational constant (decimals are read exactly: 0.1 is 1/10).

    Examples
    --------
    >>> parse_expression("0.25")
    Number(value=Fraction(1, 4))
    """

    value: Fraction


@dataclass(frozen=True)
class Name(Node):
    """A symbol, a basis blade such as ``e12``, ``I``, ``eo`` or ``einf``.

    Examples
    --------
    >>> parse_expression("R")
    Name(name='R')
    """

    name: str


@dataclass(frozen=True)
class Unary(Node):
    """``-x``, ``+x`` or ``~x``.

    Examples
    --------
    >>> parse_expression("~R")
    Unary(op='~', operand=Name(name='R'))
    """

    op: str
    operand: Node


@dataclass(frozen=True)
class Binary(Node):
    """``+ - * / ^ | & >> **`` between two operands (``**``: an integer :class:`Number`).

    Examples
    --------
    >>> parse_expression("a*b").op
    '*'
    """

    op: str
    left: Node
    right: Node


@dataclass(frozen=True)
class Call(Node):
    """A function of :data:`FUNCTIONS` applied to its arguments.

    Examples
    --------
    >>> parse_expression("grade(x, 2)")
    Call(name='grade', args=(Name(name='x'), Number(value=Fraction(2, 1))))
    """

    name: str
    args: tuple[Node, ...]


@dataclass(frozen=True)
class _Level:
    ops: frozenset[str]
    mix: bool = True  # may two different operators of the level follow each other
    chain: frozenset[str] = frozenset()  # operators that may repeat without parentheses


_LEFT = frozenset("+-*/^|&") | {">>"}

#: Python's precedence (clifford, galgebra, kingdon), loosest first; unary and ** follow.
PYTHON = (
    _Level(frozenset({"|"}), chain=_LEFT),
    _Level(frozenset({"^"}), chain=_LEFT),
    _Level(frozenset({"&"}), chain=_LEFT),
    _Level(frozenset({">>"}), chain=_LEFT),
    _Level(frozenset({"+", "-"}), chain=_LEFT),
    _Level(frozenset({"*", "/"}), chain=_LEFT),
)
#: the GA literature's convention, loosest first.
GA = (
    _Level(frozenset({">>"})),
    _Level(frozenset({"+", "-"}), chain=frozenset({"+", "-"})),
    _Level(frozenset({"*", "/"}), chain=frozenset({"*", "/"})),
    _Level(frozenset({"^", "|", "&"}), mix=False, chain=frozenset({"^", "&"})),
)


def _tokens(text: str) -> list[tuple[str, str, int]]:
    if len(text) > _MAX_LENGTH:
        raise ParseError(f"expression is {len(text)} characters long; at most {_MAX_LENGTH}")
    out, pos = [], 0
    while True:
        while pos < len(text) and text[pos].isspace():
            pos += 1
        if pos == len(text):
            break
        m = _TOKEN.match(text, pos)
        if not m or m.end() == pos:
            raise ParseError(f"column {pos + 1}: unexpected character {text[pos]!r}")
        kind = m.lastgroup
        if kind == "name" and len(m.group(kind)) > _MAX_NAME:
            raise ParseError(
                f"column {m.start(kind) + 1}: the name {shorten(m.group(kind), 20)!r} is longer "
                f"than {_MAX_NAME} characters"
            )
        out.append((kind, m.group(kind), m.start(kind) + 1))
        pos = m.end()
    out.append(("end", "end of input", len(text) + 1))
    return out


class _Parser:
    def __init__(self, tokens: list[tuple[str, str, int]], levels: tuple[_Level, ...]):
        self.tokens = tokens
        self.levels = levels
        self.i = 0
        self.depth = 0

    def peek(self) -> tuple[str, str, int]:
        return self.tokens[self.i]

    def take(self) -> tuple[str, str, int]:
        tok = self.tokens[self.i]
        self.i += 1
        return tok

    def expect(self, value: str) -> None:
        kind, text, col = self.take()
        if text != value or kind != "op":
            raise ParseError(f"column {col}: expected {value!r}, found {shorten(text)!r}")

    def at(self, *values: str) -> bool:
        kind, text, _ = self.peek()
        return kind == "op" and text in values

    def nested(self):
        self.depth += 1
        if self.depth > _MAX_DEPTH:
            raise ParseError(f"column {self.peek()[2]}: nested more than {_MAX_DEPTH} deep")

    def expression(self, level: int = 0) -> Node:
        if level == len(self.levels):
            return self.unary()
        spec = self.levels[level]
        node = self.expression(level + 1)
        first = None
        while self.at(*spec.ops):
            _, op, col = self.take()
            if first is not None:
                if op != first and not spec.mix:
                    raise ParseError(
                        f"column {col}: '{op}' next to '{first}' is ambiguous; add parentheses"
                    )
                if op == first and op not in spec.chain:
                    raise ParseError(
                        f"column {col}: '{op}' does not chain (it is not associative); "
                        "add parentheses"
                    )
            first = op
            node = Binary(op, node, self.expression(level + 1))
        return node

    def unary(self) -> Node:
        if self.at("-", "+", "~"):
            op = self.take()[1]
            self.nested()
            node = Unary(op, self.unary())
            self.depth -= 1
            return node
        return self.power()

    def power(self) -> Node:
        node = self.primary()
        if self.at("**"):
            col = self.take()[2]
            sign = -1 if self.at("-") else 1
            if self.at("-", "+"):
                self.take()
            kind, text, _ = self.take()
            if kind != "number" or not text.isdigit():
                raise ParseError(f"column {col}: '**' needs an integer exponent")
            if int(text) > _MAX_EXPONENT:
                raise ParseError(f"column {col}: exponent {shorten(text)} is larger than 32")
            if self.at("**"):
                raise ParseError(f"column {self.peek()[2]}: '**' does not chain; add parentheses")
            node = Binary("**", node, Number(Fraction(sign * int(text))))
        return node

    def primary(self) -> Node:
        kind, text, col = self.take()
        if kind == "number":
            return Number(Fraction(text))
        if kind == "name":
            if self.at("("):
                if text not in FUNCTIONS:
                    raise ParseError(
                        f"column {col}: unknown function {shorten(text)!r}; known: "
                        + ", ".join(sorted(FUNCTIONS))
                    )
                self.take()
                self.nested()
                args = [self.expression()]
                while self.at(","):
                    self.take()
                    args.append(self.expression())
                self.expect(")")
                self.depth -= 1
                if len(args) != FUNCTIONS[text]:
                    raise ParseError(
                        f"column {col}: {text}() takes {FUNCTIONS[text]} argument(s), "
                        f"got {len(args)}"
                    )
                return Call(text, tuple(args))
            if text in FUNCTIONS:
                raise ParseError(f"column {col}: {text!r} is a function; write {text}(...)")
            return Name(text)
        if kind == "op" and text == "(":
            self.nested()
            node = self.expression()
            self.expect(")")
            self.depth -= 1
            return node
        raise ParseError(f"column {col}: expected a number, a name or '(', found {shorten(text)!r}")


def _height(node: Node) -> int:
    # iterative: a tree this function refuses must not exhaust the stack first
    best, stack = 0, [(node, 1)]
    while stack:
        n, h = stack.pop()
        best = max(best, h)
        stack.extend((child, h + 1) for child in _children(n))
    return best


def _children(node: Node) -> tuple[Node, ...]:
    if isinstance(node, Unary):
        return (node.operand,)
    if isinstance(node, Binary):
        return (node.left, node.right)
    if isinstance(node, Call):
        return node.args
    return ()


def _differing(a: Node, b: Node) -> tuple[Node, Node]:
    """The smallest subtrees at which two readings of the same text differ."""
    while True:
        ca, cb = _children(a), _children(b)
        if type(a) is not type(b) or len(ca) != len(cb) or _label(a) != _label(b):
            return a, b
        unequal = [(x, y) for x, y in zip(ca, cb, strict=True) if x != y]
        if len(unequal) != 1:
            return a, b
        a, b = unequal[0]


def _label(node: Node):
    return getattr(node, "op", None) or getattr(node, "name", None) or getattr(node, "value", None)


def _read(tokens: list[tuple[str, str, int]], start: int, stop: set[str], where: str):
    """Both readings of the tokens from ``start`` up to a stop token: (node, next index)."""
    out = []
    for levels in (PYTHON, GA):
        parser = _Parser(tokens, levels)
        parser.i = start
        try:
            node = parser.expression()
            kind, tok, col = parser.peek()
            if not (kind == "end" or (kind == "op" and tok in stop)):
                raise ParseError(f"column {col}: unexpected {shorten(tok)!r}")
            out.append((node, parser.i, None))
        except ParseError as exc:
            out.append((None, None, exc))
    (py, py_end, py_err), (ga, ga_end, ga_err) = out
    if ga_err is not None:
        if py is not None and ("ambiguous" in str(ga_err) or "chain" in str(ga_err)):
            raise ParseError(
                f"{ga_err} (Python's precedence, as in clifford, galgebra and kingdon, "
                f"reads {shorten(unparse(py))})"
            )
        raise ga_err
    if py_err is not None:
        raise py_err
    for node in (py, ga):
        height = _height(node)
        if height > _MAX_HEIGHT:
            raise ParseError(f"{where} is nested {height} operators deep; at most {_MAX_HEIGHT}")
    if py != ga or py_end != ga_end:
        left, right = _differing(py, ga)
        raise ParseError(
            f"{where}: the readings differ: Python's precedence (clifford, galgebra, "
            f"kingdon) reads {shorten(unparse(left))}, the GA convention (outer and inner "
            f"products before the geometric product) reads {shorten(unparse(right))}; "
            "add parentheses"
        )
    return ga, ga_end


def parse_expression(text: str) -> Node:
    """Parse one multivector expression (both readings must agree).

    Examples
    --------
    >>> parse_expression("-a**2")
    Unary(op='-', operand=Binary(op='**', left=Name(name='a'), right=Number(value=Fraction(2, 1))))
    >>> unparse(parse_expression("R >> a*b"))
    'R >> (a * b)'
    """
    if not isinstance(text, str):
        raise ParseError(f"expression: expected a string, got {type(text).__name__}")
    tokens = _tokens(text)
    node, end = _read(tokens, 0, set(), "expression")
    kind, tok, col = tokens[end]
    if kind != "end":
        raise ParseError(f"column {col}: unexpected {shorten(tok)!r}")
    return node


def parse_identity(text: str) -> tuple[Node, Node]:
    """Parse ``lhs == rhs`` into its two sides (both readings must agree on each).

    Examples
    --------
    >>> lhs, rhs = parse_identity("R*~R == 1")
    >>> rhs
    Number(value=Fraction(1, 1))
    """
    if not isinstance(text, str):
        raise ParseError(f"identity: expected a string, got {type(text).__name__}")
    tokens = _tokens(text)
    lhs, end = _read(tokens, 0, {"=="}, "left side")
    kind, tok, col = tokens[end]
    if tok != "==" or kind != "op":
        if kind == "end":
            raise ParseError("expected 'lhs == rhs': no '==' found")
        raise ParseError(f"column {col}: unexpected {shorten(tok)!r}")
    rhs, end = _read(tokens, end + 1, set(), "right side")
    kind, tok, col = tokens[end]
    if kind != "end":
        raise ParseError(f"column {col}: unexpected {shorten(tok)!r}")
    return lhs, rhs


def _number_text(value: Fraction) -> str:
    if value.denominator == 1:
        return str(value.numerator)
    den = value.denominator
    while den % 2 == 0:
        den //= 2
    while den % 5 == 0:
        den //= 5
    if den == 1:  # a finite decimal, as the literal was written
        text = format(Decimal(value.numerator) / Decimal(value.denominator), "f")
        return text
    return f"({value.numerator}/{value.denominator})"


def unparse(node: Node) -> str:
    """The expression fully parenthesised: every operation in its own parentheses.

    The outermost operation is left bare; this is the text a verdict prints as "read as".

    Examples
    --------
    >>> unparse(parse_expression("a*(b|c) - b*(a|c)"))
    '(a * (b | c)) - (b * (a | c))'
    >>> unparse(parse_expression("-a**-1 + grade(2.5*x, 1)"))
    '(-(a ** -1)) + grade(2.5 * x, 1)'
    """
    return _unparse(node, top=True)


def _unparse(node: Node, top: bool = False) -> str:
    if isinstance(node, Number):
        return _number_text(node.value)
    if isinstance(node, Name):
        return node.name
    if isinstance(node, Call):
        return f"{node.name}({', '.join(_unparse(a, top=True) for a in node.args)})"
    if isinstance(node, Unary):
        text = f"{node.op}{_unparse(node.operand)}"
    else:
        text = f"{_unparse(node.left)} {node.op} {_unparse(node.right)}"
    return text if top else f"({text})"


def names_in(node: Node) -> set[str]:
    """Every name the expression mentions (symbols, blades, I, eo, einf).

    Examples
    --------
    >>> sorted(names_in(parse_expression("grade(R*v*~R, 1) + e12")))
    ['R', 'e12', 'v']
    """
    out: set[str] = set()
    stack = [node]
    while stack:
        n = stack.pop()
        if isinstance(n, Name):
            out.add(n.name)
        stack.extend(_children(n))
    return out
