"""The paper's §5, equations (41)-(47): quaternions as the Clifford algebra C₀,₂.

Checked with the exact algebra of :mod:`symbolic.algebra` and the isomorphisms of
:mod:`symbolic.isomorphisms`.
"""

from __future__ import annotations

from itertools import combinations, combinations_with_replacement, product

from .. import isomorphisms
from ..algebra import CliffordAlgebra, blade_product
from ..derivation import step
from .core import Finding, Reading, verdict_of

# The entries are rows of the audit, reached through ENTRIES (or symbolic.audit.find):
# each builds one Finding and is not an API of its own.
__all__ = ["ENTRIES", "SOURCE"]

SOURCE = "paper"


def eq41() -> Finding:
    euclid = CliffordAlgebra(3, 0)
    e = euclid.basis_vectors()
    squares = all(v * v == 1 for v in e)
    anti = all(e[i] * e[j] == -(e[j] * e[i]) for i in range(3) for j in range(3) if i != j)
    # With e_i² = +1 the paper's §5 construction i = e1, j = e2 does not give i² = −1.
    cl20 = isomorphisms.matrices_from_cl20()
    cl02 = isomorphisms.quaternions_from_cl02()
    quaternion_with_41 = (CliffordAlgebra(2, 0).basis_vectors()[0] ** 2) == -1
    return Finding(
        SOURCE,
        "(41)",
        "defining relations of the basis vectors",
        printed="e i 2 = 1 e i e j = e j e i para i j",
        reading="e_i² = 1,  e_i e_j = −e_j e_i for i ≠ j",
        reconstruction="the minus of −e_j e_i and the ≠ of i ≠ j were lost; '= 1' is kept "
        "because the text says these are relations of the Euclidean space V.",
        readings=(
            Reading(
                "e_i² = +1 (Euclidean, as printed)",
                f"defines Cl(n,0) (relations hold: {squares and anti}); with i = e1, j = e2 "
                f"it gives Cl(2,0) ≅ M₂(ℝ) (i² = +1), not ℍ",
                tested=True,
            ),
            Reading(
                "e_i² = −1 (a lost minus)",
                f"defines Cl(0,n): then C₀,₁ ≅ ℂ and C₀,₂ ≅ ℍ hold ({cl02.ok}), but the text "
                "calls V Euclidean",
            ),
        ),
        verdict=verdict_of(quaternion_with_41, squares and anti and cl20.ok and cl02.ok),
        corrected="(41) is the Euclidean convention, Cl(n,0); the quaternions of (47) live in "
        "the other signature, e_i² = −1 (C₀,₂ in the paper's own (43) naming). Write "
        "e_i² = ±1 by signature, or state §5's construction with e_i² = −1.",
        evidence="in Cl(3,0) e_i² = 1 and e_i e_j = −e_j e_i (exact); in Cl(2,0) e1² = +1 while "
        "i² = −1, and Cl(2,0) has the zero divisor (1 + e1)(1 − e1) = 0; in Cl(0,2) everything "
        "matches ℍ (see the isomorphism derivations).",
        checks=(
            step("Cl(3,0): e_i² = 1, e_i e_j = −e_j e_i", "exact", squares and anti),
            *cl20.steps[-2:],
            cl02.steps[0],
        ),
    )


def eq42() -> Finding:
    ok = True
    for p, q in ((3, 0), (0, 2), (1, 3), (2, 1)):
        algebra = CliffordAlgebra(p, q)
        x = algebra.general("x", grades=[1], real=True)
        form = sum(s * x[(i + 1,)] ** 2 for i, s in enumerate(algebra.signature))
        ok = ok and x * x == form
    return Finding(
        SOURCE,
        "(42)",
        "fundamental relation x² = B(x, x)",
        printed="x 2 = B ( x , x )",
        reading="x² = B(x, x) for every x in V",
        reconstruction="nothing lost.",
        verdict=verdict_of(ok),
        evidence="for a general vector x = Σ xᵢ eᵢ, x² = Σ B(eᵢ, eᵢ) xᵢ² (the cross terms cancel "
        "by anticommutation), computed in Cl(3,0), Cl(0,2), Cl(1,3), Cl(2,1).",
        checks=(step("x² = B(x, x) in four signatures", "symbolic coefficients", ok),),
    )


def eq43() -> Finding:
    p, q = 1, 1
    literal = {}
    for i in range(1, p + 1):
        literal.setdefault(i, set()).add(+1)
    for i in range(1, q + 1):
        literal.setdefault(i, set()).add(-1)
    contradictory = any(len(v) > 1 for v in literal.values())
    algebra = CliffordAlgebra(p, q)
    e = algebra.basis_vectors()
    convention_ok = [(v * v)[()] for v in e] == [1, -1] and e[0] * e[1] == -(e[1] * e[0])
    return Finding(
        SOURCE,
        "(43)",
        "signature of the bilinear form",
        printed="B ( e i , e i ) = 1, i = 1, 2, …, p − 1, i = 1, 2, …, q",
        reading="B(e_i, e_i) = 1 for i = 1, …, p;  B(e_i, e_i) = −1 for i = 1, …, q",
        reconstruction="nothing lost: '− 1' survived; the two lists are read as printed.",
        readings=(
            Reading(
                "both index lists start at 1, as printed",
                f"for p = q = 1 the vector e1 gets B = {sorted(literal[1])}: contradictory "
                f"({contradictory})",
                tested=True,
            ),
            Reading(
                "the q negative vectors numbered after the positive ones, i = p+1, …, p+q, "
                "with B(e_i, e_j) = 0 for i ≠ j",
                f"the standard Cl(p,q) (Cl(1,1): e1² = 1, e2² = −1: {convention_ok})",
            ),
        ),
        verdict=verdict_of(not contradictory, convention_ok),
        corrected="B(e_i, e_i) = +1 for i = 1, …, p and −1 for i = p+1, …, p+q, B(e_i, e_j) = 0 "
        "for i ≠ j (the text's 'elementos ortogonais entre si'); this is also clifford's "
        "Cl(p, q) order.",
        evidence="Cl(1,1) computed with that convention: e1² = 1, e2² = −1, e1e2 = −e2e1.",
        checks=(step("Cl(1,1) with e_{p+i} negative", "exact", convention_ok),),
    )


def eq44() -> Finding:
    n = 3
    algebra = CliffordAlgebra(n, 0)
    closed = True
    for k in range(5):
        for word in product(range(1, n + 1), repeat=k):
            sign, blade = blade_product((), (), algebra.signature)
            for i in word:
                s, blade = blade_product(blade, (i,), algebra.signature)
                sign *= s
            closed = closed and blade in algebra.blades and sign in (1, -1)
    dimension = len(algebra.blades) == 2**n
    return Finding(
        SOURCE,
        "(44)",
        "general element as a sum over basis blades",
        printed="x = A x A e A",
        reading="x = Σ_A x_A e_A, x_A real, over the 2ⁿ index sets A",
        reconstruction="the summation sign was lost (and, in the text above, the exponent of "
        "'dimensões 2n', which is 2ⁿ).",
        verdict=verdict_of(closed and dimension),
        evidence="every product of basis vectors reduces to ± one blade e_A with A strictly "
        f"increasing (all words of length ≤ 4 in Cl(3,0) checked), and there are 2ⁿ = "
        f"{2**n} of them for n = 3.",
        checks=(
            step(
                "products of basis vectors are ± blades; 2ⁿ blades",
                "exhaustive, n = 3",
                closed and dimension,
            ),
        ),
    )


def _index_sets(n: int, strict_after_first: bool) -> list[tuple[int, ...]]:
    """1 ≤ i1 < i2 ≤ ⋯ ≤ ik ≤ n (printed) or all strict."""
    out = [()]
    for k in range(1, n + 1):
        for idx in combinations_with_replacement(range(1, n + 1), k):
            if strict_after_first and len(set(idx)) != k:
                continue
            if k >= 2 and not idx[0] < idx[1]:
                continue
            out.append(idx)
    return out


def eq45() -> Finding:
    n = 3
    algebra = CliffordAlgebra(n, 0)
    printed = _index_sets(n, strict_after_first=False)
    strict = _index_sets(n, strict_after_first=True)
    repeated = next(a for a in printed if len(set(a)) != len(a))
    sign, reduced = blade_product((), repeated, algebra.signature)
    strict_is_basis = sorted(strict) == sorted(algebra.blades) and len(strict) == 2**n
    return Finding(
        SOURCE,
        "(45)",
        "index sets of the basis blades",
        printed="A = i 1 , i 2 ,⋯ , i k | 1 ≤ i 1 i 2 ≤⋯ ≤ i k ≤ n",
        reading="A = {(i1, …, i_k) ∣ 1 ≤ i1 < i2 ≤ ⋯ ≤ i_k ≤ n}",
        reconstruction="the braces and one relation sign (between i1 and i2, read as <) were "
        "lost; the other relations print as ≤.",
        readings=(
            Reading(
                "≤ after i2, as printed",
                f"{len(printed)} index sets for n = {n}, more than 2ⁿ = {2**n}; e.g. "
                f"e_{''.join(map(str, repeated))} = {sign:+d}·e_{''.join(map(str, reduced))} "
                "repeats a lower blade: not a basis",
                tested=True,
            ),
            Reading(
                "all strict, 1 ≤ i1 < i2 < ⋯ < i_k ≤ n",
                f"exactly the {len(strict)} = 2ⁿ blades ({strict_is_basis})",
            ),
        ),
        verdict=verdict_of(len(printed) == 2**n),
        corrected="A = {(i1, …, i_k) ∣ 1 ≤ i1 < i2 < ⋯ < i_k ≤ n}, as the text itself says before "
        "(42) ('sendo i1 < ⋯ < ik').",
        evidence=f"with ≤ the sets include repeated indices, and e_i e_i = B(e_i, e_i) makes "
        f"those blades multiples of lower ones: {len(printed)} sets for a {2**n}-dimensional "
        "algebra.",
        checks=(
            step(
                "strictly increasing index sets are exactly the basis blades",
                f"{len(strict)} sets",
                strict_is_basis,
            ),
        ),
    )


def eq46() -> Finding:
    ok = True
    for p, q in ((3, 0), (0, 2), (1, 3)):
        algebra = CliffordAlgebra(p, q)
        for k in range(algebra.n + 1):
            for a in combinations(range(1, algebra.n + 1), k):
                ok = ok and algebra.blade(*a) == algebra.multivector({a: 1})
    return Finding(
        SOURCE,
        "(46)",
        "basis blade as a product of basis vectors",
        printed="e A = e 1 e 2 e i k , e = e 0 = 1",
        reading="e_A = e_{i1} e_{i2} ⋯ e_{i_k},  e_∅ = e_0 = 1",
        reconstruction="the subscripts i1, i2 were flattened, and the ⋯ and ∅ lost.",
        verdict=verdict_of(ok),
        evidence="for strictly increasing A the product e_{i1} ⋯ e_{i_k} is the basis blade e_A "
        "with sign +1 (every A in Cl(3,0), Cl(0,2), Cl(1,3)).",
        checks=(step("e_{i1} ⋯ e_{i_k} = +e_A for increasing A", "exhaustive", ok),),
    )


def eq47() -> Finding:
    d = isomorphisms.quaternions_from_cl02()
    return Finding(
        SOURCE,
        "(47)",
        "general element of C₀,₂ as a quaternion",
        printed="q ^ = q 0 + q 1 e 1 + q 2 e 2 + q 3 e 1 e 2",
        reading="q̂ = q0 + q1 e1 + q2 e2 + q3 e1e2 in C₀,₂",
        reconstruction="nothing lost.",
        verdict=verdict_of(d.ok),
        evidence="with i = e1, j = e2, k = e1e2 the product of two such elements is the Hamilton "
        "product of (2) (general symbolic coefficients), and the map is bijective.",
        checks=d.steps,
    )


def ijk_text() -> Finding:
    cl = CliffordAlgebra(0, 2)
    e1, e2 = cl.basis_vectors()
    values = [e1 * e1, e2 * e2, (e1 * e2) ** 2, e1 * e2 * (e1 * e2)]
    holds = all(v == -1 for v in values)
    literal = all(v == 1 for v in values)
    return Finding(
        SOURCE,
        "§5 ijk",
        "i = e1, j = e2, k = e1e2 satisfy Hamilton's relation",
        printed="se for tomado i=e1, j=e2 e k=e1e2, tem-se a relação fundamental da álgebra dos "
        "quatérnions i2=j2=k2=ijk=1",
        reading="i² = j² = k² = ijk = −1",
        reconstruction="the minus of −1 was lost (as in eq. 1).",
        readings=(
            Reading("= −1", f"holds in C₀,₂: {[str(v) for v in values]}", tested=True),
            Reading("= +1 as printed", f"holds? {literal}"),
        ),
        verdict=verdict_of(holds),
        evidence=f"in Cl(0,2): e1² = {values[0]}, e2² = {values[1]}, (e1e2)² = {values[2]}, "
        f"e1 e2 e1e2 = {values[3]}.",
        checks=(step("i² = j² = k² = ijk = −1 in C₀,₂", str(values), holds),),
    )


def low_dimensions_text() -> Finding:
    ds = (
        isomorphisms.reals_from_cl00(),
        isomorphisms.complex_from_cl01(),
        isomorphisms.quaternions_from_cl02(),
    )
    return Finding(
        SOURCE,
        "§5 C₀,ₙ",
        "C₀,₀ ≅ ℝ, C₀,₁ ≅ ℂ, C₀,₂ ≅ ℍ",
        printed="a álgebra dos reais quando n=0 é uma álgebra de Clifford C0,0≃ ℝ; já quando "
        "n=1, C0,1≃ ℂ e quando n=2, C0,2≃ ℍ",
        reading="C₀,₀ ≅ ℝ, C₀,₁ ≅ ℂ, C₀,₂ ≅ ℍ",
        reconstruction="subscripts flattened.",
        verdict=verdict_of(all(d.ok for d in ds)),
        evidence="each isomorphism checked: homomorphism for general symbolic elements and "
        "bijective (see the isomorphism derivations). With e_i² = +1 instead, C₁,₀ ≅ ℝ⊕ℝ and "
        "C₂,₀ ≅ M₂(ℝ) are not division algebras.",
        checks=tuple(s for d in ds for s in d.steps),
    )


ENTRIES = (eq41, eq42, eq43, eq44, eq45, eq46, eq47, ijk_text, low_dimensions_text)
