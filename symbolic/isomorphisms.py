"""Small Clifford algebras identified with familiar ones, each claim checked exactly.

* Cl(0,0) ≅ ℝ, Cl(0,1) ≅ ℂ, Cl(0,2) ≅ ℍ (i = e1, j = e2, k = e1e2): the paper's §5.
* The contrast: Cl(1,0) ≅ ℝ⊕ℝ and Cl(2,0) ≅ M₂(ℝ), each with an explicit zero divisor,
  so neither is a division algebra although both have the same dimensions as ℂ and ℍ.
* Cl⁺(3,0) ≅ ℍ: all 48 signed assignments of i, j, k to the bivectors e23, e31, e12,
  each classified as an isomorphism, an anti-isomorphism, or neither.

An isomorphism φ is checked by (a) φ(ab) = φ(a)φ(b) for two general multivectors with
symbolic coefficients (so for all of them at once), and (b) the images of the basis
blades being linearly independent (so φ is bijective: the dimensions agree).

Examples
--------
>>> quaternions_from_cl02().ok
True
>>> result = even_cl3_assignments()
>>> result.counts
{'isomorphism': 24, 'anti-isomorphism': 24, 'neither': 0}
>>> result.numeric_choice.kind
'isomorphism'
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from functools import cache
from itertools import permutations, product

import sympy

from . import hamilton
from .algebra import CliffordAlgebra, Multivector, blade_name
from .derivation import Derivation, Step, show, step


@dataclass(frozen=True)
class Isomorphism(Derivation):
    """A checked algebra map Cl(p,q) -> target, with the images of the basis blades.

    Examples
    --------
    >>> complex_from_cl01().images
    (('1', '1'), ('e1', 'i'))
    """

    images: tuple[tuple[str, str], ...] = ()
    zero_divisor: tuple[str, str] | None = None


def _general_pair(algebra: CliffordAlgebra) -> tuple[Multivector, Multivector]:
    return algebra.general("a", real=True), algebra.general("b", real=True)


def _homomorphism_step(
    algebra: CliffordAlgebra,
    phi: Callable[[Multivector], object],
    mul: Callable[[object, object], object],
    equal: Callable[[object, object], bool],
    target: str,
) -> Step:
    a, b = _general_pair(algebra)
    holds = equal(phi(a * b), mul(phi(a), phi(b)))
    return step(
        f"φ(ab) = φ(a) φ(b) for all a, b in Cl({algebra.p},{algebra.q})",
        f"a = {a}\nb = {b}\nφ(a b) and φ(a) φ(b) expanded in {target}: identical",
        holds,
    )


def _bijective_step(algebra: CliffordAlgebra, coordinates: Sequence[Sequence]) -> Step:
    m = sympy.Matrix(coordinates)
    rank = m.rank()
    return step(
        "φ is bijective (images of the basis blades are linearly independent)",
        f"coordinates of φ(basis) as rows: {m.tolist()}; rank {rank} = 2^{algebra.n}",
        rank == len(algebra.blades) == m.shape[1],
    )


@cache
def reals_from_cl00() -> Isomorphism:
    """Cl(0,0) ≅ ℝ: the algebra of a zero-dimensional space is its scalars.

    Examples
    --------
    >>> reals_from_cl00().ok
    True
    """
    cl = CliffordAlgebra(0, 0)
    steps = (
        step("Cl(0,0) has the single basis blade 1", f"blades: {cl.blades}", cl.blades == ((),)),
        _homomorphism_step(
            cl, lambda m: m[()], lambda x, y: x * y, lambda x, y: sympy.expand(x - y) == 0, "ℝ"
        ),
        _bijective_step(cl, [[1]]),
    )
    return Isomorphism(
        "Cl(0,0) ≅ ℝ",
        "With no basis vectors, multivectors are real numbers and the geometric product is "
        "the product of reals: φ(a) = a.",
        steps,
        critical=False,
        images=(("1", "1"),),
    )


@cache
def complex_from_cl01() -> Isomorphism:
    """Cl(0,1) ≅ ℂ with φ(a + b e1) = a + b i.

    Examples
    --------
    >>> complex_from_cl01().ok
    True
    """
    cl = CliffordAlgebra(0, 1)
    (e1,) = cl.basis_vectors()

    def phi(m: Multivector):
        return m[()] + sympy.I * m[(1,)]

    x = sympy.symbols("x0:2", real=True)
    z = cl.multivector({(): x[0], (1,): x[1]})
    steps = (
        step("e1² = -1, like i² = -1", f"e1 e1 = {e1 * e1}", e1 * e1 == -1),
        _homomorphism_step(cl, phi, lambda u, v: u * v, lambda u, v: sympy.expand(u - v) == 0, "ℂ"),
        _bijective_step(cl, [[1, 0], [0, 1]]),
        step(
            "no zero divisors: z z̄ = |z|² (z̄ the Clifford conjugate) vanishes only at z = 0",
            f"z = {z};  z z̄ = {z * z.conjugate()}",
            (z * z.conjugate()) == x[0] ** 2 + x[1] ** 2,
        ),
    )
    return Isomorphism(
        "Cl(0,1) ≅ ℂ",
        "One basis vector squaring to -1 plays the imaginary unit: φ(a + b e1) = a + b i.",
        steps,
        critical=False,
        images=(("1", "1"), ("e1", "i")),
    )


def _cl02_to_h(m: Multivector) -> hamilton.Quat:
    """Cl(0,2) -> ℍ with i = e1, j = e2, k = e1e2 (the paper's eq. 47)."""
    return (m[()], m[(1,)], m[(2,)], m[(1, 2)])


@cache
def quaternions_from_cl02() -> Isomorphism:
    """Cl(0,2) ≅ ℍ with i = e1, j = e2, k = e1e2 (the paper's §5, with the signs restored).

    Examples
    --------
    >>> print(quaternions_from_cl02().steps[0].shown)
    i² = e1 e1 = -1, j² = e2 e2 = -1, k² = e12 e12 = -1, ijk = e1 e2 e12 = -1
    """
    cl = CliffordAlgebra(0, 2)
    e1, e2 = cl.basis_vectors()
    e12 = e1 * e2
    squares = (e1 * e1, e2 * e2, e12 * e12, e1 * e2 * e12)
    units = {"1": cl.scalar(1), "i": e1, "j": e2, "k": e12}
    table_ok = all(
        _cl02_to_h(units[a] * units[b]) == hamilton.mul(hamilton.unit(a), hamilton.unit(b))
        for a in hamilton.UNITS
        for b in hamilton.UNITS
    )
    x = cl.general("q", real=True)
    norm = sum(c**2 for c in x.coefficients())
    steps = (
        step(
            "i² = j² = k² = ijk = -1",
            f"i² = e1 e1 = {squares[0]}, j² = e2 e2 = {squares[1]}, "
            f"k² = e12 e12 = {squares[2]}, ijk = e1 e2 e12 = {squares[3]}",
            all(s == -1 for s in squares),
        ),
        step(
            "the 16 products of 1, i, j, k reproduce Hamilton's table (ij = k = -ji, ...)",
            f"ij = {e1 * e2}, ji = {e2 * e1}, jk = {e2 * e12}, kj = {e12 * e2}, "
            f"ki = {e12 * e1}, ik = {e1 * e12}",
            table_ok,
        ),
        _homomorphism_step(cl, _cl02_to_h, hamilton.mul, hamilton.is_equal, "ℍ"),
        _bijective_step(cl, [[int(r == c) for c in range(4)] for r in range(4)]),
        step(
            "division algebra: q q̄ = |q|² (q̄ the Clifford conjugate = quaternion conjugate)",
            f"q q̄ = {x * x.conjugate()}",
            (x * x.conjugate()) == norm,
        ),
    )
    return Isomorphism(
        "Cl(0,2) ≅ ℍ",
        "Two anticommuting basis vectors squaring to -1 are i and j; their product e1e2 is "
        "k. (With e_i² = +1 instead, the same construction gives Cl(2,0) ≅ M₂(ℝ).)",
        steps,
        critical=False,
        images=(("1", "1"), ("e1", "i"), ("e2", "j"), ("e12", "k")),
    )


@cache
def split_complex_from_cl10() -> Isomorphism:
    """Cl(1,0) ≅ ℝ⊕ℝ with φ(a + b e1) = (a + b, a - b), and the zero divisor (1 + e1)(1 - e1).

    Examples
    --------
    >>> split_complex_from_cl10().zero_divisor
    ('1 + e1', '1 - e1')
    """
    cl = CliffordAlgebra(1, 0)
    (e1,) = cl.basis_vectors()

    def phi(m: Multivector):
        return (m[()] + m[(1,)], m[()] - m[(1,)])

    zd = (1 + e1) * (1 - e1)
    steps = (
        step("e1² = +1", f"e1 e1 = {e1 * e1}", e1 * e1 == 1),
        _homomorphism_step(
            cl,
            phi,
            lambda u, v: (u[0] * v[0], u[1] * v[1]),
            lambda u, v: all(sympy.expand(s - t) == 0 for s, t in zip(u, v, strict=True)),
            "ℝ⊕ℝ (componentwise product)",
        ),
        _bijective_step(cl, [[1, 1], [1, -1]]),
        step(
            "zero divisor: (1 + e1)(1 - e1) = 0 with both factors nonzero",
            f"(1 + e1)(1 - e1) = {zd}",
            zd.is_zero(),
        ),
        step(
            "idempotents: ((1 ± e1)/2)² = (1 ± e1)/2",
            f"((1 + e1)/2)² = {((1 + e1) / 2) ** 2}",
            ((1 + e1) / 2) ** 2 == (1 + e1) / 2,
        ),
    )
    return Isomorphism(
        "Cl(1,0) ≅ ℝ⊕ℝ",
        "A basis vector squaring to +1 gives the split-complex numbers, which are two copies "
        "of ℝ side by side (coordinates along the idempotents (1 ± e1)/2): not a field.",
        steps,
        critical=False,
        images=(("1", "(1, 1)"), ("e1", "(1, -1)")),
        zero_divisor=("1 + e1", "1 - e1"),
    )


#: The matrix representation of Cl(2,0) used below (Pauli-like, real).
CL20_MATRICES: dict[str, sympy.Matrix] = {
    "1": sympy.eye(2),
    "e1": sympy.Matrix([[1, 0], [0, -1]]),
    "e2": sympy.Matrix([[0, 1], [1, 0]]),
    "e12": sympy.Matrix([[0, 1], [-1, 0]]),
}


@cache
def matrices_from_cl20() -> Isomorphism:
    """Cl(2,0) ≅ M₂(ℝ) through e1 -> diag(1, -1), e2 -> [[0, 1], [1, 0]].

    Examples
    --------
    >>> matrices_from_cl20().ok
    True
    """
    cl = CliffordAlgebra(2, 0)
    e1, e2 = cl.basis_vectors()
    names = {(): "1", (1,): "e1", (2,): "e2", (1, 2): "e12"}

    def phi(m: Multivector) -> sympy.Matrix:
        return sum((m[b] * CL20_MATRICES[names[b]] for b in cl.blades), sympy.zeros(2, 2))

    zd = (1 + e1) * (1 - e1)
    coords = [list(CL20_MATRICES[names[b]]) for b in cl.blades]
    steps = (
        step(
            "e1² = e2² = +1, (e1e2)² = -1",
            f"e1 e1 = {e1 * e1}, e2 e2 = {e2 * e2}, e12 e12 = {(e1 * e2) ** 2}",
            e1 * e1 == 1 and e2 * e2 == 1 and (e1 * e2) ** 2 == -1,
        ),
        step(
            "the matrices satisfy the same relations and e1 e2 -> the matrix of e12",
            f"E1 E2 = {(CL20_MATRICES['e1'] * CL20_MATRICES['e2']).tolist()}",
            CL20_MATRICES["e1"] * CL20_MATRICES["e2"] == CL20_MATRICES["e12"]
            and CL20_MATRICES["e1"] ** 2 == sympy.eye(2)
            and CL20_MATRICES["e2"] ** 2 == sympy.eye(2),
        ),
        _homomorphism_step(
            cl,
            phi,
            lambda u, v: u * v,
            lambda u, v: (u - v).applyfunc(sympy.expand).is_zero_matrix,
            "M₂(ℝ)",
        ),
        _bijective_step(cl, coords),
        step(
            "zero divisor: (1 + e1)(1 - e1) = 0, i.e. diag(2, 0) diag(0, 2) = 0",
            f"(1 + e1)(1 - e1) = {zd}; φ(1 + e1) = {phi(1 + e1).tolist()}, "
            f"φ(1 - e1) = {phi(1 - e1).tolist()}",
            zd.is_zero() and (phi(1 + e1) * phi(1 - e1)).is_zero_matrix,
        ),
        step(
            "so e1 has no quaternion image: i² = -1 but e1² = +1",
            f"e1 e1 = {e1 * e1}",
            e1 * e1 != -1,
        ),
    )
    return Isomorphism(
        "Cl(2,0) ≅ M₂(ℝ)",
        "Two basis vectors squaring to +1 generate all real 2×2 matrices: the same dimension "
        "as ℍ but with zero divisors, so Euclidean signature does not give the quaternions "
        "(only its even part Cl⁺(2,0) = span{1, e12} ≅ ℂ is a field).",
        steps,
        critical=False,
        images=tuple((k, str(v.tolist())) for k, v in CL20_MATRICES.items()),
        zero_divisor=("1 + e1", "1 - e1"),
    )


# -- Cl⁺(3,0) and the 48 signed assignments ------------------------------------------------

CL3 = CliffordAlgebra(3, 0)

#: The three bivectors in the cyclic order the conventions use (e31 = -e13).
BIVECTORS: tuple[tuple[str, Multivector], ...] = (
    ("e23", CL3.blade(2, 3)),
    ("e31", CL3.blade(3, 1)),
    ("e12", CL3.blade(1, 2)),
)


@dataclass(frozen=True)
class Assignment:
    """i -> signs[0]·B[perm[0]], j -> signs[1]·B[perm[1]], k -> signs[2]·B[perm[2]].

    Examples
    --------
    >>> classify_assignment((1, 1, 1), (0, 1, 2))
    Assignment(signs=(1, 1, 1), perm=(0, 1, 2), kind='anti-isomorphism', det=1)
    """

    signs: tuple[int, int, int]
    perm: tuple[int, int, int]
    kind: str  # 'isomorphism', 'anti-isomorphism' or 'neither'
    det: int  # determinant of the signed permutation in the basis (e23, e31, e12)

    def images(self) -> tuple[str, str, str]:
        """The images of i, j, k as blade names.

        Examples
        --------
        >>> classify_assignment((-1, 1, 1), (1, 0, 2)).images()
        ('-e31', 'e23', 'e12')
        """
        return tuple(
            ("-" if s < 0 else "") + BIVECTORS[p][0]
            for s, p in zip(self.signs, self.perm, strict=True)
        )  # type: ignore[return-value]

    def label(self) -> str:
        """The assignment as one line of text.

        Examples
        --------
        >>> classify_assignment((-1, -1, -1), (0, 1, 2)).label()
        'i -> -e23, j -> -e31, k -> -e12'
        """
        i, j, k = self.images()
        return f"i -> {i}, j -> {j}, k -> {k}"


def _assignment_map(signs, perm) -> dict[str, Multivector]:
    m = {"1": CL3.scalar(1)}
    for unit, s, p in zip("ijk", signs, perm, strict=True):
        m[unit] = s * BIVECTORS[p][1]
    return m


def _linear(images: dict[str, Multivector], q: Sequence) -> Multivector:
    return sum((c * images[u] for u, c in zip(hamilton.UNITS, q, strict=True)), CL3.scalar(0))


def classify_assignment(signs, perm) -> Assignment:
    """Check all 16 unit products: φ(a)φ(b) = φ(ab) (iso) or = φ(ba) (anti).

    Examples
    --------
    >>> classify_assignment((1, 1, -1), (0, 1, 2)).kind
    'isomorphism'
    """
    images = _assignment_map(signs, perm)

    def phi_unit(a: str, b: str) -> Multivector:
        sign, c = hamilton.UNIT_TABLE[(a, b)]
        return sign * images[c]

    pairs = [(a, b) for a in hamilton.UNITS for b in hamilton.UNITS]
    iso = all(images[a] * images[b] == phi_unit(a, b) for a, b in pairs)
    anti = all(images[a] * images[b] == phi_unit(b, a) for a, b in pairs)
    kind = "isomorphism" if iso else "anti-isomorphism" if anti else "neither"
    m = sympy.zeros(3, 3)
    for col, (s, p) in enumerate(zip(signs, perm, strict=True)):
        m[p, col] = s
    return Assignment(tuple(signs), tuple(perm), kind, int(m.det()))


@dataclass(frozen=True)
class EvenSubalgebra(Derivation):
    """Cl⁺(3,0) ≅ ℍ: every signed assignment classified, and the numeric package's choice.

    Examples
    --------
    >>> even_cl3_assignments().obvious_choice.kind
    'anti-isomorphism'
    """

    assignments: tuple[Assignment, ...] = ()
    numeric_choice: Assignment | None = None
    obvious_choice: Assignment | None = None

    @property
    def counts(self) -> dict[str, int]:
        """How many assignments of each kind.

        Examples
        --------
        >>> even_cl3_assignments().counts
        {'isomorphism': 24, 'anti-isomorphism': 24, 'neither': 0}
        """
        kinds = ("isomorphism", "anti-isomorphism", "neither")
        return {k: sum(a.kind == k for a in self.assignments) for k in kinds}


#: The map the numeric package uses: i -> -e23, j -> -e31, k -> -e12.
NUMERIC_SIGNS, NUMERIC_PERM = (-1, -1, -1), (0, 1, 2)


def quaternion_to_rotor(q: Sequence) -> Multivector:
    """φ(q) = w - x e23 - y e31 - z e12 (the numeric package's map ℍ -> Cl⁺(3,0)).

    Examples
    --------
    >>> from ga_rotors.symbolic import hamilton
    >>> quaternion_to_rotor(hamilton.quat(1, 2, 3, 4))
    1 - 4*e12 + 3*e13 - 2*e23
    """
    return _linear(_assignment_map(NUMERIC_SIGNS, NUMERIC_PERM), q)


def rotor_to_quaternion(r: Multivector) -> hamilton.Quat:
    """φ⁻¹: read (w, x, y, z) off the even blades of a Cl(3,0) multivector.

    Examples
    --------
    >>> from ga_rotors.symbolic import hamilton
    >>> rotor_to_quaternion(quaternion_to_rotor(hamilton.quat(1, 2, 3, 4)))
    (1, 2, 3, 4)
    """
    if r.grades - {0, 2}:
        raise ValueError(f"not an even multivector: {r}")
    return (r[()], -r[(2, 3)], r[(1, 3)], -r[(1, 2)])


@cache
def even_cl3_assignments() -> EvenSubalgebra:
    """All 48 signed assignments of i, j, k to e23, e31, e12, classified.

    The bivectors satisfy e23 e31 = -e12 (cyclically): the *opposite* of ij = k. So the
    sign-free assignment i -> e23, j -> e31, k -> e12 reverses products (anti-isomorphism),
    and flipping all three signs fixes it. In general an assignment is an isomorphism
    exactly when its signed-permutation matrix has determinant -1.

    Examples
    --------
    >>> print(even_cl3_assignments().details[1])
       1 i -> e23, j -> e31, k -> e12          +1   anti-isomorphism
    """
    assignments = tuple(
        classify_assignment(signs, perm)
        for perm in permutations(range(3))
        for signs in product((1, -1), repeat=3)
    )
    chosen = next(a for a in assignments if (a.signs, a.perm) == (NUMERIC_SIGNS, NUMERIC_PERM))
    obvious = next(a for a in assignments if (a.signs, a.perm) == ((1, 1, 1), (0, 1, 2)))
    e23, e31, e12 = (b for _, b in BIVECTORS)
    q = hamilton.symbols("q")
    p = hamilton.symbols("p")
    hom = quaternion_to_rotor(hamilton.mul(q, p)) == quaternion_to_rotor(q) * quaternion_to_rotor(p)
    counts = {k: sum(a.kind == k for a in assignments) for k in ("isomorphism", "anti-isomorphism")}
    steps = (
        step(
            "the bivectors square to -1 and multiply like reversed quaternion units",
            f"e23² = {e23 * e23}, e31² = {e31 * e31}, e12² = {e12 * e12}; "
            f"e23 e31 = {e23 * e31}, e31 e12 = {e31 * e12}, e12 e23 = {e12 * e23}",
            all(b * b == -1 for b in (e23, e31, e12)) and e23 * e31 == -e12,
        ),
        step(
            "48 signed assignments: 24 isomorphisms, 24 anti-isomorphisms, none neither",
            f"counts: {counts}",
            counts == {"isomorphism": 24, "anti-isomorphism": 24},
        ),
        step(
            "isomorphism exactly when det(signed permutation) = -1",
            "det = -1 for every isomorphism, +1 for every anti-isomorphism",
            all((a.kind == "isomorphism") == (a.det == -1) for a in assignments),
        ),
        step(
            "the numeric package's map i -> -e23, j -> -e31, k -> -e12 is an isomorphism",
            chosen.label() + f": {chosen.kind}",
            chosen.kind == "isomorphism",
        ),
        step(
            "... for general quaternions: φ(q p) = φ(q) φ(p)",
            f"φ(q) = {quaternion_to_rotor(q)}",
            hom,
        ),
        step(
            "the 'obvious' map i -> e23, j -> e31, k -> e12 is an anti-isomorphism",
            obvious.label() + f": {obvious.kind}",
            obvious.kind == "anti-isomorphism",
        ),
        step(
            "in clifford's blade order e31 = -e13, so φ(q) = w - x e23 + y e13 - z e12",
            f"e3 e1 = {CL3.blade(3, 1)}",
            CL3.blade(3, 1) == -CL3.blade(1, 3),
        ),
    )
    table = ["  #  assignment                            det  kind"]
    for n, a in enumerate(assignments, 1):
        table.append(f"  {n:2d} {a.label():37s} {a.det:+d}   {a.kind}")
    return EvenSubalgebra(
        "Cl⁺(3,0) ≅ ℍ",
        "The even subalgebra span{1, e23, e31, e12} of Cl(3,0) is a copy of ℍ, but which "
        "signed assignment of i, j, k to the bivectors preserves products has to be checked: "
        "half of them reverse every product instead.",
        steps,
        critical=True,
        details=tuple(table),
        assignments=assignments,
        numeric_choice=chosen,
        obvious_choice=obvious,
    )


def all_isomorphisms() -> tuple[Derivation, ...]:
    """Every derivation of this module, in teaching order.

    Examples
    --------
    >>> [d.title for d in all_isomorphisms()][:3]
    ['Cl(0,0) ≅ ℝ', 'Cl(0,1) ≅ ℂ', 'Cl(0,2) ≅ ℍ']
    """
    return (
        reals_from_cl00(),
        complex_from_cl01(),
        quaternions_from_cl02(),
        split_complex_from_cl10(),
        matrices_from_cl20(),
        even_cl3_assignments(),
    )


__all__ = [
    "BIVECTORS",
    "CL20_MATRICES",
    "Assignment",
    "EvenSubalgebra",
    "Isomorphism",
    "all_isomorphisms",
    "blade_name",
    "classify_assignment",
    "complex_from_cl01",
    "even_cl3_assignments",
    "matrices_from_cl20",
    "quaternion_to_rotor",
    "quaternions_from_cl02",
    "reals_from_cl00",
    "rotor_to_quaternion",
    "show",
    "split_complex_from_cl10",
]
