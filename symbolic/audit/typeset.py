r"""The audit's formulas as LaTeX for docs/audit.md, from the plain notation it is written in.

Each finding is written once, in the plain notation ``ga-rotors verify`` prints in a
terminal (``q̇0 = −½(q1ωx3 + q2ωy3 + q3ωz3)``, ``q⁻¹ = q*/|q|²``). The page shows the same
text with its formulas typeset: :func:`mark` finds the formulas in a sentence and writes
each as ``$...$`` LaTeX (:func:`latex`), which the site's math hook turns into MathML.

What counts as a formula: a run of symbols (Greek letters, indexed names such as ``q1``,
``e23`` or ``ωx3``, accented names such as ``q̇``, powers, operators, numbers, brackets)
that holds at least one operator, relation, power, accent, index or Greek letter. Prose
words end a formula; a quotation (``'...'``) and code in backticks are left as they are.
The notation read inside a formula:

* a letter followed by digits is indexed: ``q0`` is :math:`q_0`, ``e23`` is :math:`e_{23}`,
  ``e1e2`` is :math:`e_1 e_2`; ``_`` indexes by a name (``I_x3``, ``ω_B3``, ``q_z(ψ)``),
  a Greek letter followed by an axis and digits is indexed too (``ωx3``), and so is the
  paper's shorthand ``cψ``, ``sθ`` for :math:`\cos\psi`, :math:`\sin\theta`;
* combining accents (``q̇``, ``q̂``, ``R̃``), superscripts (``²``, ``⁻¹``, ``ᵀ``, ``⁺``) and
  subscripts (``ℤ₂``, ``C₀,₂``) become their LaTeX forms, a ``*`` after a name is the
  conjugate's star, ``½`` a fraction, ``√(...)`` a root, ``|...|`` bars;
* ``sin``, ``cos``, ``atan2``, ``diag``, ``Cl``, ... are upright operator names;
  ``ij``, ``ijk``, ``iqi``, ``pq`` are products of one-letter names; ``Rz``, ``Ix`` are
  indexed (:math:`R_z`, :math:`I_x`).

Examples
--------
>>> latex("q̇0 = −½(q1ωx3 + q2ωy3)")
'\\dot{q}_{0} = - \\tfrac{1}{2} (q_{1} \\omega_{x3} + q_{2} \\omega_{y3})'
>>> mark("the inverse q⁻¹ = q*/|q|², for every q ≠ 0.")
'the inverse $q^{-1} = q^{*}/\\lvert q\\rvert^{2}$, for every $q \\neq 0$.'
>>> mark("Fig. 5 says it equals 1 (0.44 % low)")  # no formula here
'Fig. 5 says it equals 1 (0.44 % low)'
"""

from __future__ import annotations

import itertools
import re
import unicodedata

__all__ = ["latex", "mark"]

#: Operator names, upright: TeX's own, then the others.
FUNCTIONS = {
    **{name: f"\\{name}" for name in ("sin", "cos", "tan", "exp", "log", "det", "lim")},
    **{name: f"\\{name}" for name in ("arccos", "arcsin", "arctan")},
    **{
        name: f"\\operatorname{{{name}}}"
        for name in ("atan2", "diag", "Exp", "Log", "lat", "lon", "sgn", "trace", "vec", "mod")
    },
    "Cl": "\\mathrm{Cl}",
    "sqrt": "\\sqrt",
}
#: Words that are products of one-letter names.
PRODUCTS = {"ij", "ji", "jk", "kj", "ki", "ik", "ijk", "iqi", "jqj", "kqk", "pq", "qp", "pr"}
PRODUCTS |= {"qr", "ab", "dt", "dq", "dA", "ix"}
#: Words that are a name with an axis index.
INDEXED = {"Rx", "Ry", "Rz", "Ix", "Iy", "Iz"}

GREEK = "Α-Ωα-ωϑϕ"
LETTER = f"A-Za-z{GREEK}ℍℝℂℤℕ"
ACCENTS = {"\u0307": "\\dot", "\u0302": "\\hat", "\u0303": "\\tilde", "\u0308": "\\ddot"}
ACCENTS["\u0304"] = "\\bar"
MARKS = "".join(ACCENTS)
SUPERSCRIPTS = dict(zip("⁰¹²³⁴⁵⁶⁷⁸⁹⁻⁺ⁿᵀ", [*"0123456789-+n", "\\mathsf{T}"], strict=True))
SUBSCRIPTS = dict(zip("₀₁₂₃₄₅₆₇₈₉ₙᵢ,", "0123456789ni,", strict=True))
GREEK_NAMES = dict(
    zip(
        "αβγδεζηθικλμνξπρστυφχψωΓΔΘΛΞΠΣΦΨΩϑϕ",
        "alpha beta gamma delta epsilon zeta eta theta iota kappa lambda mu nu xi pi rho "
        "sigma tau upsilon phi chi psi omega Gamma Delta Theta Lambda Xi Pi Sigma Phi Psi "
        "Omega vartheta phi".split(),
        strict=True,
    )
)
#: Symbols with a LaTeX command of their own (ASCII ones pass through).
SYMBOLS = {
    "−": "-", "·": "\\cdot", "×": "\\times", "⊗": "\\otimes", "⊙": "\\odot", "≠": "\\neq",
    "≤": "\\leq", "≥": "\\geq", "∈": "\\in", "∝": "\\propto", "≡": "\\equiv", "≅": "\\cong",
    "≈": "\\approx", "↦": "\\mapsto", "→": "\\to", "->": "\\to", "<->": "\\leftrightarrow",
    "⇒": "\\Rightarrow", "⟹": "\\Longrightarrow", "⟺": "\\Longleftrightarrow", "∧": "\\wedge",
    "∂": "\\partial", "∫": "\\int", "Σ": "\\sum", "…": "\\ldots", "⋯": "\\cdots", "±": "\\pm",
    "∓": "\\mp", "∘": "\\circ", "⊕": "\\oplus", "°": "^{\\circ}", "∞": "\\infty", "∼": "\\sim",
    "∣": "\\mid", "∅": "\\varnothing", "⟨": "\\langle", "⟩": "\\rangle", "½": "\\tfrac{1}{2}",
    "¼": "\\tfrac{1}{4}", "¾": "\\tfrac{3}{4}", "ℍ": "\\mathbb{H}", "ℝ": "\\mathbb{R}",
    "ℂ": "\\mathbb{C}", "ℤ": "\\mathbb{Z}", "ℕ": "\\mathbb{N}", "{": "\\{", "}": "\\}",
    "%": "\\%", "′": "'", "″": "''",
}  # fmt: skip

_NUMBER = r"\d+(?:\.\d+)?(?:[eE][-+]?\d+)?"
_SUP = "".join(SUPERSCRIPTS)
_SUB = "".join(c for c in SUBSCRIPTS if c != ",")
#: A name: letters, digits, accents, indices and powers run together (q̇0, e1e2, I_x3, mR²),
#: or a word with inner hyphens or apostrophes (z-y-z, paper's), which is prose.
_WORD = (
    rf"[{LETTER}](?:[{LETTER}\d{MARKS}{_SUP}{_SUB}′″∅]|,(?=[{_SUB}])|_\{{[^{{}}\s]*\}}|_(?=[{LETTER}\d∅]))*"
    rf"(?:[{_SUB}]+(?:,[{_SUB}]+)*)?"
    rf"(?:[-'’][{LETTER}][{LETTER}′″']*)*'*"
)
TOKEN = re.compile(
    rf"(?P<code>`[^`]*`)"
    rf"|(?P<quote>(?<![{LETTER}])'[^'\s][^']*?'(?![{LETTER}]))"
    rf"|(?P<prose>kg·m²|rad/s|i\.e\.|e\.g\.|'s\b|N\d+\b|(?:RK|CF|RKMK|DOP)\d+\b)"
    rf"|(?P<number>{_NUMBER}[{_SUP}]*)"
    rf"|(?P<word>{_WORD})"
    r"|(?P<space>\s+)"
    r"|(?P<arrow><->|->)"
    r"|(?P<other>.)",
    re.S,
)
#: Symbols that make a run of tokens a formula.
STRONG = set("=≠<>≤≥∈∝≡⟹⟺+−·×⊗⊙↦→∧/^*√½¼¾|∣…⋯≅∂∫≈±∓∘⊕°∼Σ⇒") | {"->", "<->"} | set(SUPERSCRIPTS)
#: Symbols a formula may hold without being one: brackets, separators, an ASCII minus.
NEUTRAL = set("()[]{},;-′″")
#: Operators a formula does not start or end with.
BINARY = set("=≠<>≤≥∈+·×⊗↦→∧/^≅≈∘⊕∣,;") | {"->"}
OPENERS = {"(": ")", "[": "]", "{": "}"}


def _kind(kind: str, text: str) -> str:
    """'strong', 'weak' (may sit in a formula without making one), 'neutral' or 'prose'."""
    if kind == "number":
        return "strong" if any(c in _SUP for c in text) or "e" in text.lower() else "weak"
    if kind == "word":
        if re.search(r"[-'’]", re.sub(r"_\{[^{}]*\}", "", text)):
            return "prose"
        letters_only = re.fullmatch(r"[A-Za-z]+", text) is not None
        if text.rstrip(_SUP) in FUNCTIONS or text in PRODUCTS or text in INDEXED:
            return "weak" if text in FUNCTIONS and text != "Cl" else "strong"
        if letters_only:
            if len(text) == 1:  # a name, or the article a (a formula only before an operator)
                return "weak" if text in "aA" else "strong"
            return "prose"
        return "strong"
    if kind == "prose":
        return "prose"
    if kind == "arrow" or text in STRONG:
        return "strong"
    if kind == "space" and "\n" not in text:
        return "neutral"
    if text in NEUTRAL:
        return "neutral"
    return "prose"


def _trimmed(run: list[tuple[str, str]], before_word: bool) -> list[tuple[str, str]]:
    """``run`` without separators, binary operators or an article at its ends;
    ``before_word`` tells whether a word follows the run (then a last 'a' is an article)."""
    changed = True
    while run and changed:
        changed = False
        if run[0][0] == "space" or run[0][1] in BINARY or _article(run):
            run, changed = run[1:], True
        elif run[-1][0] == "space" or run[-1][1] in BINARY:
            run, changed = run[:-1], True
        elif run[-1][1] in ("a", "A") and before_word:
            run, changed = run[:-1], True
    return run


def _article(run) -> bool:
    """Whether ``run`` starts with the article a: followed by a word, not an operator."""
    if run[0][1] not in ("a", "A"):
        return False
    rest = [(kind, tok) for kind, tok in run[1:] if kind != "space"]
    return not rest or rest[0][0] == "word"


RELATIONS = set("=≠<>≤≥∈↦→≅≈") | {"->"}


def _pieces(run: list[tuple[str, str]]):
    """``run`` cut into formulas: at unmatched brackets, at a ';' outside brackets, and at
    a ', ' outside brackets between two relations (``i = e1, j = e2``). Yields (piece,
    None) and (None, separator) in order."""
    cuts, stack, depth_zero_commas = set(), [], []
    for i, (_, tok) in enumerate(run):
        if tok in OPENERS:
            stack.append(i)
        elif tok in ")]}":
            if stack:
                stack.pop()  # ( with ] is a half-open interval
            else:
                cuts.add(i)
        elif not stack and tok == ";":
            cuts.add(i)
        elif not stack and tok == "," and i + 1 < len(run) and run[i + 1][0] == "space":
            depth_zero_commas.append(i)
    cuts |= set(stack)
    bounds = [-1, *sorted(cuts | set(depth_zero_commas)), len(run)]
    has_relation = {
        (a, b): any(tok in RELATIONS for _, tok in run[a + 1 : b])
        for a, b in itertools.pairwise(bounds)
    }
    for k, comma in enumerate(bounds[1:-1], start=1):
        if comma in depth_zero_commas:
            before, after = (bounds[k - 1], comma), (comma, bounds[k + 1])
            if has_relation[before] and has_relation[after]:
                cuts.add(comma)
    start = 0
    for i in sorted(cuts):
        yield run[start:i], None
        yield None, run[i][1]
        start = i + 1
    yield run[start:], None


def _decomposed(text: str) -> str:
    """``text`` with accented letters (ŵ) written as a letter and a combining accent."""
    out = []
    for c in text:
        parts = unicodedata.normalize("NFD", c)
        accented = len(parts) == 2 and parts[1] in ACCENTS and re.match(f"[{LETTER}]", parts[0])
        out.append(parts if accented else c)
    return "".join(out)


def _match(run, start):
    """Where the bracket opened at ``start`` closes, or None."""
    depth = 0
    for i in range(start, len(run)):
        depth += run[i][1] in OPENERS
        depth -= run[i][1] in ")]}"
        if depth == 0:
            return i
    return None


def mark(text: str) -> str:
    r"""``text`` with each formula in it written as ``$LaTeX$`` (prose left as it is).

    Examples
    --------
    >>> mark("q v q* rotates v by α about u (a unit vector)")
    '$q v q^{*}$ rotates $v$ by $\\alpha$ about $u$ (a unit vector)'
    >>> mark("the Klein algebra ℝ[ℤ₂×ℤ₂]; see 'q 2'")
    "the Klein algebra $\\mathbb{R}[\\mathbb{Z}_{2}\\times \\mathbb{Z}_{2}]$; see 'q 2'"
    """
    tokens = [(m.lastgroup, m[0]) for m in TOKEN.finditer(_decomposed(text))]
    out: list[str] = []
    run: list[tuple[str, str]] = []

    def flush(before_word=False):
        nonlocal run
        pieces = list(_pieces(run))
        for n, (piece, bracket) in enumerate(pieces):
            if bracket is not None:
                out.append(bracket)
                continue
            kept = _trimmed(piece, before_word and n == len(pieces) - 1)
            first = _start(piece, kept) if kept else len(piece)
            out.extend(t for _, t in piece[:first])
            formula = "".join(t for _, t in kept)
            if any(_kind(k, t) == "strong" for k, t in kept):
                out.append(f"${latex(formula)}$")
            else:
                out.append(formula)
            out.extend(t for _, t in piece[first + len(kept) :])
        run = []

    for kind, tok in tokens:
        if _kind(kind, tok) == "prose":
            flush(before_word=kind == "word")
            out.append(tok)
        else:
            run.append((kind, tok))
    flush()
    return "".join(out)


def _start(run, kept):
    """Where ``kept`` (a contiguous slice of ``run`` after trimming) begins in ``run``."""
    for i in range(len(run) - len(kept) + 1):
        if run[i : i + len(kept)] == kept:
            return i
    raise AssertionError("a trimmed run is a slice of the run")


_ATOM = re.compile(
    rf"(?P<base>[{LETTER}])(?P<accents>[{MARKS}]*)"
    rf"(?:_\{{(?P<braced>[^{{}}]*)\}}|_(?P<named>[A-Za-z0-9{GREEK}]+|∅)"
    r"|(?P<digits>\d+)"
    rf"|(?:(?<=[{GREEK}IM])|(?<=[{GREEK}IM][{MARKS}]))(?P<axis>[xyz]\d*)(?![A-Za-z])"
    rf"|(?<=[cs])(?P<greek>[{GREEK}]))?"
    rf"(?P<primes>[′″]*)(?P<sub>[{_SUB}]+(?:,[{_SUB}]+)*)?(?P<sup>[{_SUP}]*)"
)


def _name(word: str) -> str:
    """LaTeX for one name-like word (see the module's notation)."""
    if word in FUNCTIONS:
        return FUNCTIONS[word]
    limit = re.fullmatch(r"([A-Za-z]+)_(?:\{(.*)\}|(\w+))", word)
    if limit and limit[1] in FUNCTIONS:  # lim_{Δt->0}, the notes' cos_2
        return f"{FUNCTIONS[limit[1]]}_{{{latex(limit[2] or limit[3])}}}"
    stem = word.rstrip(_SUP + _SUB + ",")
    if stem in FUNCTIONS and stem != word:  # Cl⁺, sin²
        return FUNCTIONS[stem] + _name("x" + word[len(stem) :])[1:]
    if word in INDEXED:
        return f"{word[0]}_{{{word[1]}}}"
    if word in PRODUCTS:
        return " ".join(word)
    parts, pos = [], 0
    while pos < len(word):
        m = _ATOM.match(word, pos)
        if m is None or m.end() == pos:  # a digit or mark that belongs to no letter
            parts.append(_symbol(word[pos]))
            pos += 1
            continue
        base = _letter(m["base"])
        for accent in m["accents"]:
            base = f"{ACCENTS[accent]}{{{base}}}"
        index = m["named"] or m["digits"] or m["axis"] or m["greek"]
        if m["braced"]:
            base += f"_{{{_name(m['braced'])}}}"
        elif index:
            base += f"_{{{''.join(_letter(c) for c in index)}}}"
        base += "".join(SYMBOLS[p] for p in m["primes"])
        if m["sub"]:
            base += f"_{{{''.join(SUBSCRIPTS[c] for c in m['sub'])}}}"
        if m["sup"]:
            base += f"^{{{''.join(SUPERSCRIPTS[c] for c in m['sup'])}}}"
        parts.append(base)
        pos = m.end()
    return " ".join(parts)


def _letter(c: str) -> str:
    if c in GREEK_NAMES:
        return f"\\{GREEK_NAMES[c]} "
    return SYMBOLS.get(c, c)


def _symbol(c: str) -> str:
    if c in SUPERSCRIPTS:
        return f"^{{{SUPERSCRIPTS[c]}}}"
    return SYMBOLS.get(c, c)


def latex(formula: str) -> str:
    r"""LaTeX for one formula in the audit's plain notation.

    Examples
    --------
    >>> latex("|q̂| = √(q0² + q1²)")
    '\\lvert \\hat{q}\\rvert = \\sqrt{q_{0}^{2} + q_{1}^{2}}'
    >>> latex("R = Rz(ψ) Ry(θ), cψsθ = 1.63E-15")
    'R = R_{z}(\\psi) R_{y}(\\theta), c_{\\psi} s_{\\theta} = 1.63 \\times 10^{-15}'
    """
    tokens = [(m.lastgroup, m[0]) for m in TOKEN.finditer(formula)]
    out: list[str] = []
    bars = 0
    i = 0
    while i < len(tokens):
        kind, tok = tokens[i]
        if kind == "word" and tok != "sqrt":
            out.append(_name(tok))
        elif kind == "number":
            digits = tok.rstrip(_SUP)
            mantissa, _, exponent = digits.replace("e", "E").partition("E")
            out.append(mantissa + (f" \\times 10^{{{int(exponent)}}}" if exponent else ""))
            if len(digits) < len(tok):
                out.append("^{" + "".join(SUPERSCRIPTS[c] for c in tok[len(digits) :]) + "}")
        elif kind == "space":
            out.append("\\quad " if len(tok) > 1 else " ")
        elif tok == "*":
            out.append("^{*}")
        elif tok == "|":
            out.append("\\lvert " if bars % 2 == 0 else "\\rvert")
            bars += 1
        elif tok == "√" or (kind == "word" and tok == "sqrt"):
            if i + 1 < len(tokens) and tokens[i + 1][1] == "(":
                end = _match(tokens, i + 1)
                if end is not None:
                    inner = "".join(t for _, t in tokens[i + 2 : end])
                    out.append(f"\\sqrt{{{latex(inner)}}}")
                    i = end + 1
                    continue
            if i + 1 < len(tokens):
                out.append(f"\\sqrt{{{latex(tokens[i + 1][1])}}}")
                i += 2
                continue
            out.append("\\surd")
        elif tok in SUPERSCRIPTS:
            run = tok
            while i + 1 < len(tokens) and tokens[i + 1][1] in SUPERSCRIPTS:
                i += 1
                run += tokens[i][1]
            out.append("^{" + "".join(SUPERSCRIPTS[c] for c in run) + "}")
        else:
            out.append(SYMBOLS.get(tok, tok) + (" " if tok in SYMBOLS and tok[0] != "{" else ""))
        i += 1
    text = "".join(out)
    text = re.sub(r" +", " ", text).strip()
    return re.sub(r" (?=[)\]}^_,;])", "", text)
