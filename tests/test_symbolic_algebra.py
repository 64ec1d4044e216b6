"""symbolic.algebra against clifford's layouts, and its algebraic laws.

clifford computes in float64; the random multivectors have small integer coefficients,
so every product is an exact small integer in both packages and the comparison is exact
(no tolerance). clifford's blade order and signature order are the same as ours
(grade, then lexicographic; the first p vectors square to +1), which the first test
pins down, so coefficients compare position by position.
"""

from __future__ import annotations

import clifford
import numpy as np
import pytest
import sympy
from hypothesis import given
from hypothesis import strategies as st

from ga_rotors.symbolic.algebra import CliffordAlgebra, blade_product
from ga_rotors.symbolic.hamilton import UNIT_TABLE, UNITS, mul, symbols, unit

SIGNATURES = [(0, 0), (0, 1), (1, 0), (2, 0), (0, 2), (3, 0), (1, 3), (2, 2), (4, 1), (0, 3)]


def _layout(p, q):
    layout, _ = clifford.Cl(p, q) if p + q else (None, None)
    return layout


@pytest.mark.parametrize("p,q", [s for s in SIGNATURES if sum(s)])
def test_blade_order_and_signature_match_clifford(p, q):
    layout = _layout(p, q)
    algebra = CliffordAlgebra(p, q)
    assert tuple(layout.bladeTupList) == algebra.blades
    assert tuple(int(s) for s in layout.sig) == algebra.signature


def _random_pair(rng, algebra):
    a = rng.integers(-3, 4, size=len(algebra.blades))
    b = rng.integers(-3, 4, size=len(algebra.blades))
    return a, b


def _ours(algebra, coeffs):
    return algebra.multivector(dict(zip(algebra.blades, (int(c) for c in coeffs), strict=True)))


def _as_ints(mv):
    return [int(c) for c in mv.coefficients()]


#: Our product -> the name of clifford's multiplication table for it. clifford's
#: operators (*, ^, |, .lc) are compiled contractions of exactly these tables; compiling
#: them costs ~2 s per layout and product, so the tables are contracted here directly
#: and one test below pins the contraction convention to the real operators in Cl(3,0).
OPERATIONS = {
    "geometric": (lambda a, b: a * b, "gmt"),
    "outer": (lambda a, b: a ^ b, "omt"),
    "left contraction": (lambda a, b: a.lc(b), "lcmt"),
    "Hestenes inner": (lambda a, b: a | b, "imt"),
}
UNARY = {
    "reverse": (lambda a: ~a, lambda a: ~a),
    "grade involution": (lambda a: a.grade_involution(), lambda a: a.gradeInvol()),
    "Clifford conjugate": (lambda a: a.conjugate(), lambda a: a.conjugate()),
}


def _table_product(layout, table, a, b):
    """(a op b)_j = Σ_ik a_i T[i, j, k] b_k, T one of clifford's multiplication tables."""
    dense = getattr(layout, table).todense()
    return np.einsum("i,ijk,k->j", a, dense, b)


def test_table_contraction_is_what_cliffords_operators_compute():
    layout, _ = clifford.Cl(3)
    rng = np.random.default_rng(7)
    a, b = rng.integers(-3, 4, size=8).astype(float), rng.integers(-3, 4, size=8).astype(float)
    A, B = layout.MultiVector(a), layout.MultiVector(b)
    assert np.array_equal(_table_product(layout, "gmt", a, b), (A * B).value)
    assert np.array_equal(_table_product(layout, "omt", a, b), (A ^ B).value)
    assert np.array_equal(_table_product(layout, "imt", a, b), (A | B).value)
    assert np.array_equal(_table_product(layout, "lcmt", a, b), A.lc(B).value)


@pytest.mark.parametrize("p,q", [s for s in SIGNATURES if sum(s)])
@pytest.mark.parametrize("op", sorted(OPERATIONS))
def test_binary_products_agree_with_clifford(p, q, op):
    layout, algebra = _layout(p, q), CliffordAlgebra(p, q)
    ours, table = OPERATIONS[op]
    rng = np.random.default_rng(sum(map(ord, f"{p}{q}{op}")))
    for _ in range(20):
        a, b = _random_pair(rng, algebra)
        expected = _table_product(layout, table, a.astype(float), b.astype(float))
        got = ours(_ours(algebra, a), _ours(algebra, b))
        assert _as_ints(got) == [round(x) for x in expected]


@pytest.mark.parametrize("p,q", [s for s in SIGNATURES if sum(s)])
@pytest.mark.parametrize("op", sorted(UNARY))
def test_involutions_and_grades_agree_with_clifford(p, q, op):
    layout, algebra = _layout(p, q), CliffordAlgebra(p, q)
    ours, theirs = UNARY[op]
    rng = np.random.default_rng(sum(map(ord, f"{p}{q}{op}unary")))
    for _ in range(5):
        a, _ = _random_pair(rng, algebra)
        mv = layout.MultiVector(a.astype(float))
        assert _as_ints(ours(_ours(algebra, a))) == [round(x) for x in theirs(mv).value]
        for k in range(algebra.n + 1):
            assert _as_ints(_ours(algebra, a).grade(k)) == [round(x) for x in mv(k).value]


def test_right_contraction_is_the_mirror_of_left_contraction():
    # A ⌊ B = (B̃ ⌋ Ã)~ for all A, B: the identity that ties the two contractions.
    algebra = CliffordAlgebra(2, 1)
    a, b = algebra.general("a"), algebra.general("b")
    assert a.rc(b) == (~b).lc(~a).reverse()


def test_e13_versus_e31_sign():
    cl3 = CliffordAlgebra(3, 0)
    layout, _ = clifford.Cl(3)
    assert cl3.blade(3, 1) == -cl3.blade(1, 3)
    e1, e3 = np.eye(8)[1], np.eye(8)[3]
    e31 = _table_product(layout, "gmt", e3, e1)
    assert e31[layout.bladeTupList.index((1, 3))] == -1


def test_zero_dimensional_algebra_is_the_reals():
    algebra = CliffordAlgebra(0, 0)
    x, y = sympy.symbols("x y")
    assert (algebra.scalar(x) * algebra.scalar(y))[()] == x * y
    assert algebra.blades == ((),)


def test_symbolic_coefficients_associativity_cl13():
    # The Minkowski algebra Cl(1,3), general elements of grades 1 and 2 (full general
    # elements would be 16 x 16 x 16 symbolic terms; vectors and bivectors already use
    # every sign rule).
    algebra = CliffordAlgebra(1, 3)
    a = algebra.general("a", grades=[1])
    b = algebra.general("b", grades=[2])
    c = algebra.general("c", grades=[1])
    assert (a * b) * c == a * (b * c)


@given(st.data())
def test_geometric_product_laws(data):
    sig = data.draw(st.sampled_from([(2, 0), (0, 2), (3, 0), (1, 3), (2, 1)]))
    algebra = CliffordAlgebra(*sig)
    n = len(algebra.blades)
    a, b, c = (
        _ours(algebra, data.draw(st.lists(st.integers(-4, 4), min_size=n, max_size=n)))
        for _ in range(3)
    )
    assert (a * b) * c == a * (b * c)
    assert ~(a * b) == (~b) * (~a)
    assert (a * b).grade_involution() == a.grade_involution() * b.grade_involution()


@given(st.sampled_from([(1, 0), (2, 0), (0, 2), (3, 0), (1, 3)]))
def test_vector_squares_to_quadratic_form(sig):
    # x² = B(x, x) (the paper's eq. 42) for a general vector with symbolic coefficients.
    algebra = CliffordAlgebra(*sig)
    x = algebra.general("x", grades=[1])
    form = sum(s * x[(i + 1,)] ** 2 for i, s in enumerate(algebra.signature))
    assert x * x == form


def test_blade_product_contracts_repeated_indices_with_signature():
    assert blade_product((1, 2), (2,), (1, -1)) == (-1, (1,))
    assert blade_product((2,), (1, 2), (1, -1)) == (1, (1,))


def test_bad_signature_and_index_rejected():
    with pytest.raises(ValueError, match="p, q"):
        CliffordAlgebra(-1, 2)
    with pytest.raises(ValueError, match="index 4"):
        CliffordAlgebra(3, 0).blade(4)
    with pytest.raises(ValueError, match="repeats"):
        CliffordAlgebra(3, 0).multivector({(1, 1): 2})


def test_hamilton_table_matches_sympy_quaternion():
    from sympy.algebras.quaternion import Quaternion

    q, p = symbols("q"), symbols("p")
    ours = mul(q, p)
    theirs = Quaternion(*q) * Quaternion(*p)
    assert all(
        sympy.expand(a - b) == 0
        for a, b in zip(ours, (theirs.a, theirs.b, theirs.c, theirs.d), strict=True)
    )


def test_hamilton_unit_table_is_associative():
    for a in UNITS:
        for b in UNITS:
            for c in UNITS:
                ua, ub, uc = unit(a), unit(b), unit(c)
                assert mul(mul(ua, ub), uc) == mul(ua, mul(ub, uc))
    assert len(UNIT_TABLE) == 16
