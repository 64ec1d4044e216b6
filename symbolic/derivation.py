"""The shape every derivation returns: a list of checked steps and a readable report.

A :class:`Step` states a claim, shows the computation that settles it, and records
whether it held. A :class:`Derivation` is a titled list of steps; ``critical`` marks
the derivations the numeric package relies on (``ga-rotors verify`` exits non-zero if
one of those fails).

Examples
--------
>>> d = Derivation("tiny", "1 + 1 = 2", (Step("sum", "1 + 1 -> 2", True),), critical=False)
>>> d.ok
True
>>> print(d.report())
tiny
====
1 + 1 = 2
<BLANKLINE>
  [ok] sum
       1 + 1 -> 2
<BLANKLINE>
result: holds
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

import sympy

__all__ = ["Derivation", "Step", "show", "step"]


@dataclass(frozen=True)
class Step:
    """One checked claim: what is claimed, the computation shown, and whether it held.

    Examples
    --------
    >>> Step("1 + 1 = 2", "exact", True).holds
    True
    """

    claim: str
    shown: str
    holds: bool


@dataclass(frozen=True)
class Derivation:
    """A titled sequence of checked steps.

    ``critical`` marks the derivations the numeric package relies on; ``details`` are
    extra lines printed after the steps.

    Examples
    --------
    >>> import sympy
    >>> x = sympy.Symbol("x", real=True)
    >>> holds = sympy.expand((1 + x) ** 2 - (1 + 2 * x + x**2)) == 0
    >>> checks = (step("expands", show(sympy.expand((1 + x) ** 2)), holds),)
    >>> d = Derivation("square", "(1 + x)² = 1 + 2x + x²", checks)
    >>> d.ok, d.critical, d.failures()
    (True, True, [])
    """

    title: str
    statement: str
    steps: tuple[Step, ...]
    critical: bool = True
    details: tuple[str, ...] = field(default=())

    @property
    def ok(self) -> bool:
        """True when every step holds.

        Examples
        --------
        >>> Derivation("t", "s", (Step("a", "", True), Step("b", "", False))).ok
        False
        """
        return all(s.holds for s in self.steps)

    def failures(self) -> list[Step]:
        """The steps that failed.

        Examples
        --------
        >>> Derivation("t", "s", (Step("a", "", True), Step("b", "", False))).failures()
        [Step(claim='b', shown='', holds=False)]
        """
        return [s for s in self.steps if not s.holds]

    def report(self) -> str:
        """Plain-text report: statement, each step with its computation, extra details.

        Examples
        --------
        >>> print(Derivation("t", "s", (Step("a", "shown", True),)).report())
        t
        =
        s
        <BLANKLINE>
          [ok] a
               shown
        <BLANKLINE>
        result: holds
        """
        lines = [self.title, "=" * len(self.title), self.statement, ""]
        for s in self.steps:
            lines.append(f"  [{'ok' if s.holds else 'FAILED'}] {s.claim}")
            lines.extend(f"       {line}" for line in s.shown.splitlines())
        if self.details:
            lines.append("")
            lines.extend(self.details)
        lines.append("")
        lines.append(f"result: {'holds' if self.ok else 'FAILS'}")
        return "\n".join(lines)


_SUPERSCRIPTS = str.maketrans("0123456789", "⁰¹²³⁴⁵⁶⁷⁸⁹")


def show(expr) -> str:
    """A one-line rendering of a SymPy object: products as ·, small powers as superscripts.

    Examples
    --------
    >>> import sympy
    >>> x, y = sympy.symbols("x y")
    >>> show(2 * x**2 * y - 1)
    '2·x²·y - 1'
    """
    text = sympy.sstr(expr)
    text = re.sub(r"\*\*(\d+)", lambda m: m.group(1).translate(_SUPERSCRIPTS), text)
    return text.replace("*", "·")


def step(claim: str, shown: str, holds) -> Step:
    """A :class:`Step` with ``holds`` coerced to a plain bool.

    Examples
    --------
    >>> import sympy
    >>> step("holds", "", sympy.Integer(1) == 1)
    Step(claim='holds', shown='', holds=True)
    """
    return Step(claim, shown, bool(holds))
