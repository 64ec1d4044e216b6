"""A catalogue of classical identities, each with the signatures where it holds.

Sources: Hestenes & Sobczyk, *Clifford Algebra to Geometric Calculus* (1984) [HS];
Doran & Lasenby, *Geometric Algebra for Physicists* (2003) [DL]; Dorst, Fontijne &
Mann, *Geometric Algebra for Computer Science* (2007) [DFM]; Dorst & De Keninck, *A
Guided Tour to the Plane-Based Geometric Algebra PGA* (2022) [DK]. Every entry states, by
hand and independently of the prover, where it should hold (``holds``); the suite
proves it in each of those signatures and refutes it, with a counterexample, in the
others. ``docs/identities.md`` is generated from a run (``ga-rotors prove --catalogue
--write docs/identities.md``) and a test keeps it current.

Examples
--------
>>> len(CATALOGUE) >= 50
True
>>> entry = CATALOGUE[0]
>>> entry.identity, entry.expected(cached_basis(1, 3))
('a*b == (a|b) + (a^b)', True)
"""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import dataclass, field

from .assumptions import Assumptions
from .basis import Basis, cached_basis
from .prove import Verdict, prove

__all__ = [
    "CATALOGUE",
    "LONG_SIGNATURES",
    "QUICK_SIGNATURES",
    "Identity",
    "Result",
    "markdown",
    "run_catalogue",
    "strip_times",
]

#: signatures the default test suite runs (n ≤ 4).
QUICK_SIGNATURES = ((2, 0, 0), (3, 0, 0), (0, 2, 0), (2, 1, 0), (1, 3, 0), (3, 0, 1))
#: the n = 5 signatures of the long mode.
LONG_SIGNATURES = ((5, 0, 0), (4, 1, 0), (2, 3, 0), (4, 0, 1))


def _all(b: Basis) -> bool:
    return True


def _n_at_most_3(b: Basis) -> bool:
    return b.n <= 3


def _n_odd(b: Basis) -> bool:
    return b.n % 2 == 1


def _i_squared_minus_one(b: Basis) -> bool:
    return b.pseudoscalar_square == -1


def _nondegenerate(b: Basis) -> bool:
    return b.r == 0


def _degenerate(b: Basis) -> bool:
    return b.r > 0


def _projective(b: Basis) -> bool:
    """Projective GA, Cl(p,q,1) with n ≥ 3: points and lines exist."""
    return b.r == 1 and b.n >= 3


def _pga3(b: Basis) -> bool:
    return b.signature == (3, 0, 1)


def _conformal(b: Basis) -> bool:
    return b.conformal_pair() is not None


def _simple_rotors(b: Basis) -> bool:
    """n ≤ 3: every rotor is a + b with b² a scalar (its log is a simple bivector)."""
    return b.n <= 3


@dataclass(frozen=True)
class Identity:
    """One catalogue entry.

    Parameters
    ----------
    key : str
        Short label.
    identity : str
        ``lhs == rhs`` in the grammar of :mod:`.grammar`.
    kinds : dict
        Keywords of :class:`~.assumptions.Assumptions`.
    source : str
        Where it is stated.
    holds : callable
        Basis -> bool: where it should hold (decided by hand, not by the prover).
    applies : callable
        Basis -> bool: where it can be stated at all (the metric dual needs I² ≠ 0,
        points and lines a projective Cl(p,q,1), up and down a conformal Cl(p,1)).
    where : str
        ``holds`` in words.
    notes : tuple of str
        Remarks.
    define : dict
        User definitions the identity uses (``prove(..., define=...)``).

    Examples
    --------
    >>> e = Identity("wedge-anti", "a^b == -(b^a)", {"vectors": "a,b"}, "DFM")
    >>> e.expected(cached_basis(3)), e.assumptions().describe()
    (True, 'vectors a, b')
    """

    key: str
    identity: str
    kinds: dict
    source: str
    holds: Callable[[Basis], bool] = _all
    applies: Callable[[Basis], bool] = _all
    where: str = "every signature"
    notes: tuple[str, ...] = field(default=())
    define: dict = field(default_factory=dict)

    def assumptions(self) -> Assumptions:
        """The entry's declarations as an :class:`~.assumptions.Assumptions`.

        Examples
        --------
        >>> CATALOGUE[0].assumptions().describe()
        'vectors a, b'
        """
        return Assumptions(**self.kinds)

    def describe(self) -> str:
        """The declarations and definitions, as the catalogue page lists them.

        Examples
        --------
        >>> [e.describe() for e in CATALOGUE if e.key == "cga-translator"]
        ['euclidean x, t; T = 1 + einf*t/2']
        """
        text = self.assumptions().describe()
        for name, expression in self.define.items():
            text += f"; {name} = {expression}"
        return text

    def expected(self, basis: Basis) -> bool:
        """Whether the identity should hold in this algebra.

        Examples
        --------
        >>> [e.expected(cached_basis(1, 3)) for e in CATALOGUE if e.key == "bivector-square"]
        [False]
        """
        return self.holds(basis)


V2 = {"vectors": "a,b"}
V3 = {"vectors": "a,b,c"}
V4 = {"vectors": "a,b,c,d"}
X3 = {"multivectors": "X,Y,Z"}
X2 = {"multivectors": "X,Y"}
AX = {"vectors": "a", "multivectors": "X"}
AXY = {"vectors": "a", "multivectors": "X,Y"}
N3 = "n ≤ 3"

CATALOGUE: tuple[Identity, ...] = (
    # -- vectors: the geometric product and its parts ------------------------------------
    Identity("gp-split", "a*b == (a|b) + (a^b)", V2, "HS 1-1, DL 2"),
    Identity("inner-sym", "a|b == (a*b + b*a)/2", V2, "HS 1-1, DL 2"),
    Identity("outer-anti", "a^b == (a*b - b*a)/2", V2, "HS 1-1, DL 2"),
    Identity("vector-square", "a*a == grade(a*a, 0)", {"vectors": "a"}, "HS 1-1"),
    Identity("wedge-anti", "a^b == -(b^a)", V2, "DFM 2"),
    Identity("wedge-self", "a^a == 0", {"vectors": "a"}, "DFM 2"),
    Identity("wedge-assoc", "(a^b)^c == a^(b^c)", V3, "DFM 2"),
    Identity("inner-vector-bivector", "a|(b^c) == (a|b)*c - (a|c)*b", V3, "HS 1-1, DL 4"),
    Identity("bivector-inner-vector", "(a^b)|c == a*(b|c) - b*(a|c)", V3, "DL 4, issue 15"),
    Identity(
        "inner-vector-trivector",
        "a|(b^c^d) == (a|b)*(c^d) - (a|c)*(b^d) + (a|d)*(b^c)",
        V4,
        "HS 1-1",
    ),
    Identity("bivector-inner", "(a^b)|(c^d) == (a|d)*(b|c) - (a|c)*(b|d)", V4, "HS 1-1, DL 4"),
    Identity("lagrange", "(a^b)*(a^b) == (a|b)*(a|b) - (a*a)*(b*b)", V2, "DL 2"),
    Identity("trivector-part", "a^b^c == (a*b*c - c*b*a)/2", V3, "DL 4"),
    Identity("vector-part-abc", "(a*b*c + c*b*a)/2 == (a|b)*c - (a|c)*b + (b|c)*a", V3, "DL 4"),
    Identity("parity-abc", "grade(a*b*c, 2) == 0", V3, "HS 1-2"),
    Identity("reflection", "a*b*a == 2*(a|b)*a - (a*a)*b", V2, "DL 4, DFM 7"),
    Identity("four-wedge", "a^b^c^d == 0", V4, "DFM 2", holds=_n_at_most_3, where=N3),
    # -- multivectors: contractions and involutions --------------------------------------
    Identity("vector-gp-left", "a*X == lc(a, X) + (a^X)", AX, "DFM 6, HS 1-1"),
    Identity("vector-gp-right", "X*a == rc(X, a) + (X^a)", AX, "DFM 6"),
    Identity("lc-commutator", "lc(a, X) == (a*X - involute(X)*a)/2", AX, "DFM 6, DL 4"),
    Identity("wedge-anticommutator", "a^X == (a*X + involute(X)*a)/2", AX, "DFM 6, DL 4"),
    Identity("lc-derivation", "lc(a, X*Y) == lc(a, X)*Y + involute(X)*lc(a, Y)", AXY, "HS 1-1"),
    Identity(
        "lc-derivation-wedge",
        "lc(a, X^Y) == (lc(a, X)^Y) + (involute(X)^lc(a, Y))",
        AXY,
        "DFM 3",
    ),
    Identity("lc-wedge", "lc(X^Y, Z) == lc(X, lc(Y, Z))", X3, "DFM 3"),
    Identity("rc-wedge", "rc(X, Y^Z) == rc(rc(X, Y), Z)", X3, "DFM 3"),
    Identity("scalar-adjoint", "scalar(X^Y, Z) == scalar(X, lc(Y, Z))", X3, "DFM 3"),
    Identity("scalar-symmetric", "scalar(X, Y) == scalar(Y, X)", X2, "DFM 3"),
    Identity("scalar-reverse", "scalar(X, Y) == scalar(~X, ~Y)", X2, "DFM 3"),
    Identity("scalar-cyclic", "grade(X*Y*Z, 0) == grade(Z*X*Y, 0)", X3, "HS 1-2, DL 4"),
    Identity("reverse-product", "~(X*Y) == ~Y*~X", X2, "HS 1-2, DL 4"),
    Identity("reverse-wedge", "~(X^Y) == ~Y^~X", X2, "DFM 2"),
    Identity("involute-product", "involute(X*Y) == involute(X)*involute(Y)", X2, "HS 1-2"),
    Identity("conjugate-product", "conj(X*Y) == conj(Y)*conj(X)", X2, "HS 1-2"),
    Identity("reverse-twice", "~~X == X", {"multivectors": "X"}, "HS 1-2"),
    Identity("gp-assoc", "(X*Y)*Z == X*(Y*Z)", X3, "HS 1-1"),
    Identity("wedge-assoc-mv", "(X^Y)^Z == X^(Y^Z)", X3, "HS 1-1, DFM 2"),
    # -- bivectors and commutators -----------------------------------------------------------
    Identity("bivector-vector-anti", "B|v == -(v|B)", {"bivectors": "B", "vectors": "v"}, "DL 4"),
    Identity("commutator-vector", "comm(B, v) == B|v", {"bivectors": "B", "vectors": "v"}, "DL 4"),
    Identity(
        "commutator-closed", "comm(A, B) == grade(comm(A, B), 2)", {"bivectors": "A,B"}, "DL 4"
    ),
    Identity(
        "jacobi",
        "comm(A, comm(B, C)) + comm(B, comm(C, A)) + comm(C, comm(A, B)) == 0",
        {"bivectors": "A,B,C"},
        "HS 1-1, DL 4, issue 15",
    ),
    Identity(
        "commutator-trivector",
        "comm(B, T) == grade(comm(B, T), 3)",
        {"bivectors": "B", "kvectors": {"T": 3}},
        "DL 4",
    ),
    Identity(
        "bivector-square",
        "B*B == grade(B*B, 0)",
        {"bivectors": "B"},
        "DL 4",
        holds=_n_at_most_3,
        where=N3,
    ),
    Identity(
        "bivector-wedge-self", "B^B == 0", {"bivectors": "B"}, "DFM 2", holds=_n_at_most_3, where=N3
    ),
    Identity("blade2-square", "B*B == grade(B*B, 0)", {"blades": {"B": 2}}, "DFM 2, HS 1-2"),
    Identity("blade2-wedge-self", "B^B == 0", {"blades": {"B": 2}}, "DFM 2"),
    Identity("blade3-norm", "B*~B == grade(B*~B, 0)", {"blades": {"B": 3}}, "DFM 3"),
    Identity(
        "blade-contains-lc",
        "lc(a, B)^B == 0",
        {"vectors": "a", "blades": {"B": 2}},
        "DFM 3",
    ),
    Identity("pseudoscalar-bivector", "I*B == B*I", {"bivectors": "B"}, "HS 1-2"),
    Identity(
        "pseudoscalar-vector",
        "I*a == a*I",
        {"vectors": "a"},
        "HS 1-2, DL 4",
        holds=_n_odd,
        where="n odd",
    ),
    Identity("vector-pseudoscalar", "a*I == lc(a, I)", {"vectors": "a"}, "DFM 3"),
    # -- even elements and rotors ------------------------------------------------------------
    Identity(
        "even-norm", "E*~E == grade(E*~E, 0)", {"evens": "E"}, "DL 4", holds=_n_at_most_3, where=N3
    ),
    Identity("rotor-normal", "R*~R == 1", {"rotors": "R"}, "DL 4"),
    Identity("rotor-normal-left", "~R*R == 1", {"rotors": "R"}, "DL 4"),
    Identity(
        "rotor-vector",
        "R*v*~R == grade(R*v*~R, 1)",
        {"rotors": "R", "vectors": "v"},
        "DL 4, issue 15",
    ),
    Identity("rotor-inner", "(R*a*~R)|(R*b*~R) == a|b", {"rotors": "R", "vectors": "a,b"}, "DL 4"),
    Identity(
        "rotor-outermorphism",
        "R*(a^b)*~R == (R*a*~R)^(R*b*~R)",
        {"rotors": "R", "vectors": "a,b"},
        "DFM 7",
    ),
    Identity(
        "rotor-bivector", "R*B*~R == grade(R*B*~R, 2)", {"rotors": "R", "bivectors": "B"}, "DL 4"
    ),
    Identity("rotor-group", "(R*S)*~(R*S) == 1", {"rotors": "R,S"}, "DL 4"),
    # -- exponentials ------------------------------------------------------------------------
    Identity("exp-rotor", "exp(B)*~exp(B) == 1", {"blades": {"B": 2}}, "DL 4, DFM 7"),
    Identity(
        "exp-vector",
        "exp(B)*v*~exp(B) == grade(exp(B)*v*~exp(B), 1)",
        {"blades": {"B": 2}, "vectors": "v"},
        "DL 4",
    ),
    Identity("exp-commutes", "exp(B)*B == B*exp(B)", {"blades": {"B": 2}}, "DL 4"),
    Identity("exp-inverse", "exp(B)*exp(-B) == 1", {"blades": {"B": 2}}, "DL 4"),
    # -- unit, null and orthogonal vectors -------------------------------------------------------
    Identity(
        "unit-reflection",
        "-n*a*n == a - 2*(a|n)*n",
        {"units": "n", "vectors": "a"},
        "DL 4, DFM 7",
    ),
    Identity("unit-involution", "n*n*a == a", {"units": "n", "vectors": "a"}, "DL 4"),
    Identity("null-sandwich", "n*a*n == 2*(n|a)*n", {"nulls": "n", "vectors": "a"}, "DL 10"),
    Identity("null-square", "n*n == 0", {"nulls": "n"}, "DL 10"),
    Identity(
        "orthogonal-anticommute",
        "a*b == -(b*a)",
        {"vectors": "a,b", "orthogonal": [("a", "b")]},
        "HS 1-1",
    ),
    Identity(
        "orthogonal-gp-wedge",
        "a*b == a^b",
        {"vectors": "a,b", "orthogonal": [("a", "b")]},
        "DL 2",
    ),
    Identity(
        "orthogonal-square",
        "(a*b)*(a*b) == -(a*a)*(b*b)",
        {"vectors": "a,b", "orthogonal": [("a", "b")]},
        "DL 2",
    ),
    Identity(
        "orthonormal-plane",
        "(u^w)*(u^w) == -1",
        {"units": "u,w", "orthogonal": [("u", "w")]},
        "DL 2",
    ),
    # -- pseudoscalar and duality (where I is invertible) -----------------------------------------
    Identity(
        "pseudoscalar-square", "I*I == -1", {}, "DL 4", holds=_i_squared_minus_one, where="I² = −1"
    ),
    Identity(
        "dual-wedge",
        "dual(a^b) == lc(a, dual(b))",
        V2,
        "DFM 3",
        applies=_nondegenerate,
    ),
    Identity(
        "dual-lc",
        "dual(lc(a, X)) == a^dual(X)",
        AX,
        "DFM 3",
        applies=_nondegenerate,
    ),
    Identity(
        "dual-twice",
        "dual(dual(X)) == -X",
        {"multivectors": "X"},
        "DL 4",
        holds=_i_squared_minus_one,
        applies=_nondegenerate,
        where="I² = −1",
    ),
    Identity(
        "bac-cab",
        "dual(a^dual(b^c)) == b*(a|c) - c*(a|b)",
        V3,
        "HS 1-2, DL 2 (a×(b×c) in 3D)",
        holds=_i_squared_minus_one,
        applies=_nondegenerate,
        where="I² = −1",
    ),
    # -- inverse, division, norms ---------------------------------------------------------------
    Identity("inverse-vector", "a*inverse(a) == 1", {"vectors": "a"}, "DL 2"),
    Identity("inverse-rotor", "inverse(R) == ~R", {"rotors": "R"}, "DL 4"),
    Identity("division", "(a*b)/b == a", V2, "DL 2"),
    Identity("inverse-power", "a**-2 == inverse(a*a)", {"vectors": "a"}, "DL 2"),
    Identity("inverse-blade", "B*inverse(B) == 1", {"blades": {"B": 2}}, "DFM 3"),
    Identity("norm-rotor", "norm(R) == 1", {"rotors": "R"}, "DL 4"),
    Identity("norm2-product", "norm2(a*b) == norm2(a)*norm2(b)", V2, "DFM 7"),
    # -- duality and the regressive product in every metric ------------------------------------
    Identity("undual-dual", "undual(dual(X)) == X", {"multivectors": "X"}, "DFM 3, DK"),
    Identity(
        "vee-complement",
        "X & Y == undual(dual(X)^dual(Y))",
        X2,
        "DK",
        holds=_degenerate,
        where="r > 0 (the dual is the complement)",
    ),
    Identity("vee-assoc", "(X & Y) & Z == X & (Y & Z)", X3, "DFM 5, DK"),
    # -- projective GA: motors, points, lines ---------------------------------------------------
    Identity(
        "motor-compose",
        "(M*N) >> X == M >> (N >> X)",
        {"motors": "M,N", "multivectors": "X"},
        "DK",
        applies=_projective,
    ),
    Identity(
        "motor-meet",
        "M >> (a^b) == (M >> a)^(M >> b)",
        {"motors": "M", "vectors": "a,b"},
        "DK",
        applies=_projective,
    ),
    Identity(
        "motor-join",
        "M >> (P & Q) == (M >> P) & (M >> Q)",
        {"motors": "M", "points": "P,Q"},
        "DK",
        applies=_projective,
    ),
    Identity(
        "motor-point",
        "M >> P == grade(M >> P, 3)",
        {"motors": "M", "points": "P"},
        "DK",
        applies=_pga3,
    ),
    Identity(
        "motor-line",
        "(M >> L)^(M >> L) == 0",
        {"motors": "M", "lines": "L"},
        "DK",
        applies=_projective,
    ),
    Identity("join-anti", "P & Q == -(Q & P)", {"points": "P,Q"}, "DK", applies=_projective),
    Identity("join-is-line", "(P & Q)^(P & Q) == 0", {"points": "P,Q"}, "DK", applies=_projective),
    # -- the conformal model ----------------------------------------------------------------------
    Identity(
        "up-null", "up(x)*up(x) == 0", {"euclidean": "x"}, "DFM 13, DL 10", applies=_conformal
    ),
    Identity(
        "up-distance",
        "up(x)|up(y) == -((x - y)*(x - y))/2",
        {"euclidean": "x,y"},
        "DFM 13, DL 10",
        applies=_conformal,
    ),
    Identity("down-up", "down(up(x)) == x", {"euclidean": "x"}, "DL 10", applies=_conformal),
    Identity(
        "cga-translator",
        "T >> up(x) == up(x + t)",
        {"euclidean": "x,t"},
        "DFM 13, DL 10",
        applies=_conformal,
        define={"T": "1 + einf*t/2"},
    ),
    Identity("eo-einf", "eo|einf == -1", {}, "DFM 13", applies=_conformal),
    # -- exp and log: the addition theorem where it holds -----------------------------------------
    Identity("exp-double", "exp(B)*exp(B) == exp(2*B)", {"blades": {"B": 2}}, "DL 4"),
    Identity("exp-half", "exp(B/2)*exp(B/2) == exp(B)", {"blades": {"B": 2}}, "DL 4"),
    Identity(
        "exp-commuting-sum",
        "exp(s*B + t*B) == exp(s*B)*exp(t*B)",
        {"scalars": "s,t", "blades": {"B": 2}},
        "DL 4",
    ),
    Identity("log-exp", "exp(log(R)) == R", {"rotors": "R"}, "DL 4, DK", applies=_simple_rotors),
    Identity("log-reverse", "log(~R) == -log(R)", {"rotors": "R"}, "DK", applies=_simple_rotors),
)


@dataclass
class Result:
    """One identity in one algebra: the verdict, and whether it is the expected one.

    Examples
    --------
    >>> (r,) = run_catalogue([(2, 0, 0)], keys={"four-wedge"})
    >>> r.signature, r.verdict.status, r.as_expected
    ('Cl(2,0)', 'proved', True)
    """

    identity: Identity
    basis: Basis
    verdict: Verdict

    @property
    def signature(self) -> str:
        """'Cl(p,q)' or 'Cl(p,q,r)'."""
        return self.basis.label()

    @property
    def as_expected(self) -> bool:
        """True when proved where it should hold and refuted where it should not."""
        expected = "proved" if self.identity.expected(self.basis) else "refuted"
        return self.verdict.status == expected


def run_catalogue(signatures=QUICK_SIGNATURES, keys=None, progress=None) -> list[Result]:
    """Prove or refute every entry in each signature where it can be stated.

    Parameters
    ----------
    signatures : sequence of (p, q, r)
    keys : collection of str, optional
        Only these entries.
    progress : callable, optional
        Called with each :class:`Result` as it is decided.

    Examples
    --------
    >>> results = run_catalogue([(3, 0, 0), (1, 3, 0)], keys={"bivector-square"})
    >>> [(r.signature, r.verdict.status, r.as_expected) for r in results]
    [('Cl(3,0)', 'proved', True), ('Cl(1,3)', 'refuted', True)]
    """
    out = []
    for entry in CATALOGUE:
        if keys is not None and entry.key not in keys:
            continue
        for sig in signatures:
            basis = cached_basis(*sig)
            if not entry.applies(basis):
                continue
            verdict = prove(
                entry.identity, signature=sig, define=entry.define or None, **entry.kinds
            )
            result = Result(entry, basis, verdict)
            out.append(result)
            if progress is not None:
                progress(result)
    return out


_TIME = re.compile(r"\d+(?:\.\d+)? (?:ms|s)\b")


def strip_times(text: str) -> str:
    """The Markdown with every time replaced by '…', for the staleness check.

    Examples
    --------
    >>> strip_times("proved 12.3 ms, total 4.5 s")
    'proved …, total …'
    """
    return _TIME.sub("…", text)


def _ms(seconds: float) -> str:
    return f"{seconds * 1000:.1f} ms" if seconds < 10 else f"{seconds:.1f} s"


def markdown(results: list[Result], command: str) -> str:
    """docs/identities.md from catalogue results.

    Examples
    --------
    >>> text = markdown(run_catalogue([(3, 0, 0)], keys={"jacobi"}), "cmd")
    >>> "| jacobi |" in text
    True
    """
    signatures = []
    for r in results:
        if r.signature not in signatures:
            signatures.append(r.signature)
    by_key: dict[str, dict[str, Result]] = {}
    for r in results:
        by_key.setdefault(r.identity.key, {})[r.signature] = r
    total = sum(r.verdict.seconds for r in results)
    mark = {"proved": "✓", "refuted": "✗", "undecided": "?"}
    lines = [
        "# Identity catalogue",
        "",
        f"Generated by `{command}`; do not edit by hand",
        "(tests/test_prove_catalogue.py checks it against the catalogue).",
        "",
        "Each identity is proved (✓) exactly in every signature where it holds and refuted (✗)",
        "with an exact counterexample where it does not; a blank cell is a signature where the",
        "identity cannot be stated (the metric dual x I⁻¹ needs I² ≠ 0; points and lines need",
        "projective GA, Cl(p,q,1) with n ≥ 3; up, down, eo and einf the conformal Cl(p,1); a",
        "log that is a simple bivector n ≤ 3). Times are one run of `prove` on one core, on a",
        "shared machine. Signature Cl(p,q,r): p vectors square to +1, q to −1, r to 0 (in",
        "Cl(p,q,1) the null vector is e0). Sources: [HS] Hestenes & Sobczyk, *Clifford Algebra",
        "to Geometric Calculus* (1984), ch. 1; [DL] Doran & Lasenby, *Geometric Algebra for",
        "Physicists* (2003); [DFM] Dorst, Fontijne & Mann, *Geometric Algebra for Computer",
        "Science* (2007); [DK] Dorst & De Keninck, *A Guided Tour to the Plane-Based Geometric",
        "Algebra PGA* (2022); numbers after a source are chapters.",
        "",
        f"{len(by_key)} identities, {len(results)} verdicts, {_ms(total)} in all; "
        + ", ".join(
            f"{sum(r.verdict.status == s for r in results)} {s}"
            for s in ("proved", "refuted", "undecided")
        )
        + "; "
        + f"{sum(not r.as_expected for r in results)} not as expected.",
        "",
        "Prove your own (the Python block below runs in the test suite):",
        "",
        "```python",
        "from ga_rotors.symbolic.prover import prove",
        "",
        'verdict = prove("(a^b)|c == a*(b|c) - b*(a|c)", signature=(1, 3), vectors="a,b,c")',
        'assert verdict.status == "proved"',
        "```",
        "",
        "| key | identity | symbols | holds | source | " + " | ".join(signatures) + " |",
        "|---|---|---|---|---|" + "---|" * len(signatures),
    ]
    for entry in CATALOGUE:
        if entry.key not in by_key:
            continue
        cells = []
        for sig in signatures:
            r = by_key[entry.key].get(sig)
            if r is None:
                cells.append("")
            else:
                flag = "" if r.as_expected else " **unexpected**"
                cells.append(f"{mark[r.verdict.status]} {_ms(r.verdict.seconds)}{flag}")
        ident = entry.identity.replace("|", "\\|")
        symbols = entry.describe().replace("|", "\\|")
        lines.append(
            f"| {entry.key} | `{ident}` | {symbols} | {entry.where} | {entry.source} | "
            + " | ".join(cells)
            + " |"
        )
    refuted = [r for r in results if r.verdict.status == "refuted"]
    if refuted:
        lines += ["", "## Counterexamples", ""]
        for r in refuted:
            ce = r.verdict.counterexample
            lines.append(
                f"- **{r.identity.key}** in {r.signature}: "
                + "; ".join(line.replace("|", "\\|") for line in ce.lines())
            )
    return "\n".join(lines) + "\n"
