"""The identity language: a hand-written tokenizer and recursive-descent parser.

Nothing is evaluated as Python: the text becomes a tree of :class:`Node` objects, and
anything outside the grammar is a :class:`ParseError` naming the column.

Operators, from loosest to tightest binding (this is the GA literature's convention —
Hestenes & Sobczyk, Doran & Lasenby: inner and outer products bind tighter than the
geometric product, so ``a|b*c`` is (a·b)c and ``a^b*c`` is (a∧b)c — NOT Python's, where
``^`` binds loosest of all):

====== ============================================= ===============================
level  operators                                     notes
====== ============================================= ===============================
1      ``==``                                        exactly one, between the sides
2      ``+`` ``-``                                   left to right
3      ``*`` (geometric) ``/`` (by a number only)    left to right
4      ``^`` (outer), ``|`` (Hestenes inner)         ``^`` chains (it is associative);
                                                     ``|`` does not chain, and ``^``
                                                     next to ``|`` needs parentheses
5      unary ``-`` ``+`` ``~`` (reverse)             ``~a*b`` is (ã)b
6      ``**`` non-negative integer power             ``-a**2`` is −(a²)
7      numbers, names, ``f(...)``, ``( ... )``
====== ============================================= ===============================

Names: declared symbols; basis blades ``e1``, ``e12``, ``e31`` (= −e13) and ``I`` (the
pseudoscalar e1 e2 … en). Functions: ``grade(x, k)``, ``lc(a, b)``, ``rc(a, b)``,
``inner(a, b)`` (= ``a|b``), ``dot(a, b)`` (fat dot), ``scalar(a, b)`` (⟨ab⟩₀),
``comm(a, b)`` (½(ab − ba)), ``rev(x)`` (= ``~x``), ``involute(x)``, ``conj(x)``,
``dual(x)``, ``even(x)``, ``exp(x)`` (x² must be a scalar, e.g. a simple bivector).

Examples
--------
>>> parse_identity("(a^b)|c == a*(b|c) - b*(a|c)")[0]
Binary(op='|', left=Binary(op='^', left=Name(name='a'), right=Name(name='b')), right=Name(name='c'))
>>> parse_identity("a^b*c == 0")[0].op      # (a^b)*c
'*'
>>> parse_identity("a^b|c == 0")
Traceback (most recent call last):
...
ga_rotors.symbolic.prover.grammar.ParseError: column 4: '|' next to '^' is ambiguous; add ...
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from fractions import Fraction

__all__ = [
    "FUNCTIONS",
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
    "even": 1,
    "exp": 1,
}

_MAX_LENGTH = 2000
_MAX_DEPTH = 60
_TOKEN = re.compile(
    r"\s*(?:(?P<number>\d+(?:\.\d*)?|\.\d+)|(?P<name>[A-Za-z_][A-Za-z0-9_]*)"
    r"|(?P<op>\*\*|==|[-+*/^|~(),]))"
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
    """A symbol, a basis blade such as ``e12`` or the pseudoscalar ``I``.

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
    """``+ - * / ^ | **`` between two operands.

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
        out.append((kind, m.group(kind), m.start(kind) + 1))
        pos = m.end()
    out.append(("end", "end of input", len(text) + 1))
    return out


class _Parser:
    def __init__(self, text: str):
        self.tokens = _tokens(text)
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
        if text != value or kind not in ("op",):
            raise ParseError(f"column {col}: expected {value!r}, found {text!r}")

    def at(self, *values: str) -> bool:
        kind, text, _ = self.peek()
        return kind == "op" and text in values

    def nested(self):
        self.depth += 1
        if self.depth > _MAX_DEPTH:
            raise ParseError(f"column {self.peek()[2]}: nested more than {_MAX_DEPTH} deep")

    def sum(self) -> Node:
        node = self.product()
        while self.at("+", "-"):
            op = self.take()[1]
            node = Binary(op, node, self.product())
        return node

    def product(self) -> Node:
        node = self.wedge()
        while self.at("*", "/"):
            op = self.take()[1]
            node = Binary(op, node, self.wedge())
        return node

    def wedge(self) -> Node:
        node = self.unary()
        first = None
        while self.at("^", "|"):
            _, op, col = self.take()
            if first is not None and (op == "|" or first == "|"):
                other = "^" if op == "|" else "|"
                if op == first:
                    raise ParseError(
                        f"column {col}: '|' does not chain (it is not associative); add parentheses"
                    )
                raise ParseError(
                    f"column {col}: '{op}' next to '{other}' is ambiguous; add parentheses"
                )
            first = op
            node = Binary(op, node, self.unary())
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
            kind, text, _ = self.take()
            if kind != "number" or not text.isdigit():
                raise ParseError(f"column {col}: '**' needs a non-negative integer exponent")
            if int(text) > 32:
                raise ParseError(f"column {col}: exponent {text} is larger than 32")
            node = Binary("**", node, Number(Fraction(int(text))))
        return node

    def primary(self) -> Node:
        kind, text, col = self.take()
        if kind == "number":
            return Number(Fraction(text))
        if kind == "name":
            if self.at("("):
                if text not in FUNCTIONS:
                    raise ParseError(
                        f"column {col}: unknown function {text!r}; known: "
                        + ", ".join(sorted(FUNCTIONS))
                    )
                self.take()
                self.nested()
                args = [self.sum()]
                while self.at(","):
                    self.take()
                    args.append(self.sum())
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
            node = self.sum()
            self.expect(")")
            self.depth -= 1
            return node
        raise ParseError(f"column {col}: expected a number, a name or '(', found {text!r}")


def parse_expression(text: str) -> Node:
    """Parse one multivector expression.

    Examples
    --------
    >>> parse_expression("-a**2")
    Unary(op='-', operand=Binary(op='**', left=Name(name='a'), right=Number(value=Fraction(2, 1))))
    """
    parser = _Parser(text)
    node = parser.sum()
    kind, tok, col = parser.peek()
    if kind != "end":
        raise ParseError(f"column {col}: unexpected {tok!r}")
    return node


def parse_identity(text: str) -> tuple[Node, Node]:
    """Parse ``lhs == rhs`` into its two sides.

    Examples
    --------
    >>> lhs, rhs = parse_identity("R*~R == 1")
    >>> rhs
    Number(value=Fraction(1, 1))
    """
    if not isinstance(text, str):
        raise ParseError(f"identity: expected a string, got {type(text).__name__}")
    parser = _Parser(text)
    lhs = parser.sum()
    kind, tok, col = parser.peek()
    if tok != "==" or kind != "op":
        if kind == "end":
            raise ParseError("expected 'lhs == rhs': no '==' found")
        raise ParseError(f"column {col}: unexpected {tok!r}")
    parser.take()
    rhs = parser.sum()
    kind, tok, col = parser.peek()
    if kind != "end":
        raise ParseError(f"column {col}: unexpected {tok!r}")
    return lhs, rhs


def names_in(node: Node) -> set[str]:
    """Every name the expression mentions (symbols, blades, I).

    Examples
    --------
    >>> sorted(names_in(parse_expression("grade(R*v*~R, 1) + e12")))
    ['R', 'e12', 'v']
    """
    if isinstance(node, Name):
        return {node.name}
    if isinstance(node, Unary):
        return names_in(node.operand)
    if isinstance(node, Binary):
        return names_in(node.left) | names_in(node.right)
    if isinstance(node, Call):
        return set().union(*(names_in(a) for a in node.args))
    return set()
