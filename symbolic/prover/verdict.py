"""Verdicts: proved, refuted with an exact counterexample, or undecided with the reason.

Both display as text (``report``) and as LaTeX in notebooks (``_repr_latex_``).

Examples
--------
>>> from ga_rotors.symbolic.prover import prove
>>> print(prove("a^a == 0", vectors="a").report().splitlines()[0])
proved in Cl(3,0): a^a == 0
"""

from __future__ import annotations

from dataclasses import dataclass, field

import sympy

__all__ = ["Counterexample", "Verdict"]


@dataclass
class Counterexample:
    """Exact values of the symbols where the two sides differ, and both sides' values.

    Values are SymPy numbers (a normaliser is 1/√λ with λ rational, exp keeps cos/sin).

    Examples
    --------
    >>> from ga_rotors.symbolic.prover import prove
    >>> v = prove("a*b == b*a", signature=(2, 0), vectors="a,b")
    >>> sorted(v.counterexample.values)
    ['a', 'b']
    >>> v.counterexample.lhs != v.counterexample.rhs
    True
    """

    values: dict[str, dict[str, sympy.Expr]]
    lhs: dict[str, sympy.Expr]
    rhs: dict[str, sympy.Expr]
    digits: int | None = None  # None: zero-tested exactly; else at this many digits

    @staticmethod
    def _show(coeffs: dict[str, sympy.Expr]) -> str:
        if not coeffs:
            return "0"
        parts = []
        for name, c in coeffs.items():
            text = sympy.sstr(c)
            if name == "1":
                parts.append(text)
            elif c in (1, -1):
                parts.append(name if c == 1 else f"-{name}")
            else:
                atomic = text.lstrip("-").replace("/", "").replace("*", "").isalnum()
                parts.append(f"{text}*{name}" if atomic else f"({text})*{name}")
        return " + ".join(parts).replace("+ -", "- ")

    def lines(self) -> list[str]:
        """The counterexample as text lines.

            Examples
            --------
            >>> from ga_rotors.symbolic.prover import prove
        >>> v = prove("a*a == 1", signature=(2, 0), vectors="a")
            >>> v.counterexample.lines()[0].startswith("a = ")
            True
        """
        out = [f"{name} = {self._show(c)}" for name, c in self.values.items()]
        out.append(f"lhs = {self._show(self.lhs)}")
        out.append(f"rhs = {self._show(self.rhs)}")
        return out

    def _latex(self, coeffs) -> str:
        if not coeffs:
            return "0"
        parts = []
        for name, c in coeffs.items():
            tex = sympy.latex(c)
            if isinstance(c, sympy.Add):
                tex = rf"\left({tex}\right)"
            parts.append(tex if name == "1" else f"{tex}\\, e_{{{name[1:]}}}")
        return " + ".join(parts).replace("+ -", "- ")


@dataclass
class Verdict:
    """The outcome of :func:`prove`: proved, refuted (with a counterexample) or undecided.

    ``bool(verdict)`` is True only when proved; ``exit_code`` is what ``ga-rotors prove``
    returns (0 proved, 1 refuted, 3 undecided). ``reading`` is the identity fully
    parenthesised, as the prover read it, and ``definitions`` the user's definitions
    (``T = ...``), read the same way.

    Examples
    --------
    >>> from ga_rotors.symbolic.prover import prove
    >>> v = prove("a^a == 0", signature=(3, 0), vectors="a")
    >>> bool(v), v.status, v.signature
    (True, 'proved', 'Cl(3,0)')
    >>> print(v.report().splitlines()[0])
    proved in Cl(3,0): a^a == 0
    """

    status: str
    identity: str
    signature: str
    assumptions: str
    seconds: float
    detail: str
    counterexample: Counterexample | None = None
    notes: list[str] = field(default_factory=list)
    reading: str = ""
    definitions: list[str] = field(default_factory=list)

    def __bool__(self) -> bool:
        return self.status == "proved"

    @property
    def exit_code(self) -> int:
        """0 proved, 1 refuted, 3 undecided.

        Examples
        --------
        >>> from ga_rotors.symbolic.prover import prove
        >>> prove("a*b == b*a", signature=(2, 0), vectors="a,b").exit_code
        1
        """
        return {"proved": 0, "refuted": 1, "undecided": 3}[self.status]

    def report(self) -> str:
        """The verdict as text: status, identity, assumptions, the evidence.

        Examples
        --------
        >>> from ga_rotors.symbolic.prover import prove
        >>> print(prove("a*b == b*a", signature=(2, 0), vectors="a,b").report())
        refuted in Cl(2,0): a*b == b*a
          read as: a * b == b * a
          assuming: vectors a, b
          counterexample (exact):
            a = ...
        """
        lines = [f"{self.status} in {self.signature}: {self.identity}"]
        if self.reading:
            lines.append(f"  read as: {self.reading}")
        if self.definitions:
            lines.append(f"  where: {'; '.join(self.definitions)}")
        lines.append(f"  assuming: {self.assumptions}")
        if self.counterexample is not None:
            how = (
                "exact"
                if self.counterexample.digits is None
                else f"checked to {self.counterexample.digits} digits"
            )
            lines.append(f"  counterexample ({how}):")
            lines += ["    " + line for line in self.counterexample.lines()]
        else:
            lines.append(f"  {self.detail}")
        lines += [f"  note: {n}" for n in self.notes]
        lines.append(f"  time: {self.seconds:.3f} s")
        return "\n".join(lines)

    __str__ = report

    def _repr_latex_(self) -> str:
        """The verdict as LaTeX for notebooks: the status, the identity, the evidence.

        Examples
        --------
        >>> from ga_rotors.symbolic.prover import prove
        >>> print(prove("a^a == 0", signature=(3, 0), vectors="a")._repr_latex_())
        $\\begin{array}{l}\\textbf{proved}\\text{ in Cl(3,0): }\\texttt{a\\^{}a == 0} ...
        """
        rows = [
            rf"\textbf{{{self.status}}}\text{{ in {self.signature}: }}"
            rf"\texttt{{{_tex_text(self.identity)}}}",
        ]
        if self.reading:
            rows.append(rf"\text{{read as: }}\texttt{{{_tex_text(self.reading)}}}")
        if self.definitions:
            rows.append(rf"\text{{where: }}\texttt{{{_tex_text('; '.join(self.definitions))}}}")
        rows.append(rf"\text{{assuming {_tex_text(self.assumptions)}}}")
        ce = self.counterexample
        if ce is not None:
            rows += [f"{name} = {ce._latex(c)}" for name, c in ce.values.items()]
            rows += [rf"\text{{lhs}} = {ce._latex(ce.lhs)}", rf"\text{{rhs}} = {ce._latex(ce.rhs)}"]
        else:
            rows.append(rf"\text{{{_tex_text(self.detail)}}}")
        return r"$\begin{array}{l}" + r" \\ ".join(rows) + r"\end{array}$"


def _tex_text(text: str) -> str:
    replacements = [
        ("\\", r"\backslash "),
        ("{", r"\{"),
        ("}", r"\}"),
        ("_", r"\_"),
        ("^", r"\^{}"),
        ("#", r"\#"),
        ("~", r"\~{}"),
        ("&", r"\&"),
        ("%", r"\%"),
    ]
    out = []
    for char in text:
        out.append(next((tex for c, tex in replacements if c == char), char))
    return "".join(out)
