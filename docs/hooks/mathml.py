"""mkdocs hook: the pages' LaTeX formulas as MathML, made when the site is built.

``pymdownx.arithmatex`` (mkdocs.yml) finds the formulas of a page, ``$...$`` inline and
``$$...$$`` on lines of their own, and leaves them as ``<span class="arithmatex">\\(...\\)</span>``
and ``<div class="arithmatex">\\[...\\]</div>``; the API reference's docstrings arrive the same
way (their ``:math:`` roles and ``.. math::`` blocks are turned into these by
docs/hooks/sphinx_roles.py). This hook converts each one with ``latex2mathml`` into a
``<math>`` element, which browsers draw natively: the site ships no JavaScript for
mathematics and loads nothing from elsewhere.

A formula that does not convert (an unbalanced brace, a command latex2mathml does not
know) is logged as a warning naming the page and the formula, so ``mkdocs build --strict``
fails on it instead of showing raw LaTeX.
"""

from __future__ import annotations

import html
import logging
import re

log = logging.getLogger("mkdocs.hooks.math")

#: arithmatex's generic output: inline \(...\) in a span, display \[...\] in a div.
FORMULA = re.compile(
    r'<span class="arithmatex">\\\((?P<inline>.*?)\\\)</span>'
    r'|<div class="arithmatex">\\\[(?P<display>.*?)\\\]</div>',
    re.S,
)
#: Bars written as delimiters, \lvert x \rvert or \lVert x \rVert: each pair is grouped, so
#: the browser draws them as fences around x, not as operators between x and what follows.
BAR = re.compile(r"\\([lr])(vert|Vert)(?![A-Za-z])")
#: A pair of plain bars |x| (not \|, not \left| or \right|): written as \lvert x \rvert.
PLAIN_BARS = re.compile(r"(?<!\\)(?<!\\left)(?<!\\right)\|([^|{}]*?)(?<!\\)\|")
#: Environments latex2mathml knows under another name.
ALIASES = {r"\begin{aligned}": r"\begin{align*}", r"\end{aligned}": r"\end{align*}"}
#: \operatorname{name}, which latex2mathml spells out letter by letter when the name holds a
#: digit (atan2): passed to it as text behind a private-use mark, then made an operator.
OPERATORNAME = re.compile(r"\\operatorname\s*\{\s*([A-Za-z0-9]+)\s*\}")
MARK = "\ue000"
#: A function name (\sin, \exp, ... or an \operatorname), which latex2mathml writes as an
#: identifier or text: drawn as an operator with TeX's thin spaces, none before "(".
FUNCTION = re.compile(
    r"(?:<mi>(?P<name>a?(?:rc)?(?:sin|cos|tan|cot)h?|exp|log|ln|sec|csc)</mi>"
    rf"|<mtext>{MARK}(?P<operator>[A-Za-z0-9]+)</mtext>)"
    r"(?P<paren>(?:<mrow>)?<mo[^>]*>&#x00028;)?"
)
#: A minus or plus right after another operator (other than a closing fence) is a sign.
SIGN = re.compile(
    r"(<mo(?: [^>]*)?>(?!&#x00029;|&#x0005D;|&#x0007D;|&#x0007C;|&#x02016;)[^<]*</mo>)"
    r"<mo>(&#x02212;|&#x0002B;|&#x000B1;)</mo>"
)
#: A command latex2mathml passed through as a name instead of converting it.
UNKNOWN = re.compile(r">(\\[A-Za-z]+)<")


class MathError(ValueError):
    """A formula that does not convert to MathML."""


def to_mathml(latex: str, display: bool = False) -> str:
    """The ``<math>`` element of one LaTeX formula (inline, or displayed as a block).

    Raises :class:`MathError` for a formula latex2mathml cannot read or only half reads.
    """
    from latex2mathml.converter import convert

    try:
        out = convert(_prepared(latex), display="block" if display else "inline")
    except Exception as error:  # latex2mathml raises its own exception per mistake
        raise MathError(f"{type(error).__name__} {error}".strip()) from None
    unknown = UNKNOWN.search(out)
    if unknown:
        raise MathError(f"unknown command {unknown[1]}")
    out = FUNCTION.sub(
        lambda m: (
            f'<mo lspace="0.1667em" rspace="{"0" if m["paren"] else "0.1667em"}">'
            f"{m['name'] or m['operator']}</mo>{m['paren'] or ''}"
        ),
        out,
    )
    return SIGN.sub(r'\1<mo form="prefix">\2</mo>', out)


def _prepared(latex: str) -> str:
    """``latex`` with aliased environments renamed, operator names marked and delimiter
    bars grouped."""
    for alias, name in ALIASES.items():
        latex = latex.replace(alias, name)
    latex = OPERATORNAME.sub(lambda m: rf"\text{{{MARK}{m[1]}}}", latex)
    latex = PLAIN_BARS.sub(r"\\lvert \1\\rvert", latex)
    return BAR.sub(lambda m: "{" + m[0] if m[1] == "l" else m[0] + "}", latex.strip())


def typeset(content: str, where: str) -> str:
    """``content`` (a page's HTML) with every arithmatex formula replaced by MathML."""

    def replace(match: re.Match) -> str:
        display = match["display"] is not None
        latex = html.unescape(match["display"] if display else match["inline"])
        try:
            return to_mathml(latex, display)
        except MathError as error:
            log.warning(f"{where}: the formula {latex.strip()!r} does not typeset: {error}")
            return match[0]

    return FORMULA.sub(replace, content)


def on_page_content(content: str, page, config, files) -> str:
    return typeset(content, page.file.src_uri)
