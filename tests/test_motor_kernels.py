"""The generated motor kernels: in sync with their generator, and equal to clifford's Cl(3,0,1).

clifford's own MultiVector products are the oracle here; the motors fed to the sandwiches
are built in clifford too, as T R from a quaternion and a translation, so nothing of
ga_rotors' motor code is used to make the inputs it is checked on.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from ga_rotors import _generate_motor_kernels as gen
from ga_rotors import _motor_kernels as MK
from ga_rotors import _pga

clifford = pytest.importorskip("clifford")
from clifford import pga  # noqa: E402  (after the importorskip)

layout, blades = pga.layout, pga.blades
e0, e1, e2, e3 = (blades[n] for n in ("e0", "e1", "e2", "e3"))
I = blades["e0123"]

finite = st.floats(-10, 10, allow_nan=False)
even8 = st.tuples(*[finite] * 8)
vec3 = st.tuples(finite, finite, finite)
quat = st.tuples(finite, finite, finite, finite).filter(lambda q: sum(c * c for c in q) > 1e-2)


def mv(coeffs, indices):
    v = np.zeros(16)
    v[list(indices)] = coeffs
    return layout.MultiVector(v)


def coeffs(m, indices=_pga.MOTOR):
    return np.asarray(m.value)[list(indices)]


def rotor_of(q):
    """w − x e23 − y e31 − z e12 of a quaternion, written with clifford's blades."""
    w, x, y, z = q
    return w - x * blades["e23"] + y * blades["e13"] - z * blades["e12"]


def translator(t):
    """1 − ½ e0 t, written with clifford's blades."""
    return 1 - 0.5 * (e0 * (t[0] * e1 + t[1] * e2 + t[2] * e3))  # e0 t = e0 ∧ t: e0 ⊥ t


def unit_motor(q, t):
    n = np.sqrt(sum(c * c for c in q))
    return translator(t) * rotor_of([c / n for c in q])


def point_mv(x):
    """The point of the PGA literature: e123 + x e032 + y e013 + z e021."""
    e032, e013, e021 = (blades["e0"] * blades["e3"] * blades["e2"], blades["e013"],
                        blades["e0"] * blades["e2"] * blades["e1"])  # fmt: skip
    return blades["e123"] + x[0] * e032 + x[1] * e013 + x[2] * e021


def test_committed_file_is_what_the_generator_writes():
    committed = gen.TARGET.read_text(encoding="utf-8")
    assert committed == gen.generate(), "run: python -m ga_rotors._generate_motor_kernels"


def test_the_blade_table_is_cliffords_pga_layout():
    assert tuple(n or "1" for n in layout.names) == _pga.BLADES
    assert _pga.layout() == layout and layout.sig.tolist() == [0, 1, 1, 1]
    grades = [len(b) for b in layout.bladeTupList]
    assert [i for i, g in enumerate(grades) if g % 2 == 0] == list(_pga.MOTOR)
    for indices, grade in ((_pga.PLANE, 1), (_pga.LINE, 2), (_pga.POINT, 3)):
        assert [i for i, g in enumerate(grades) if g == grade] == list(indices)
    assert (e0 * e0) == 0 and (e1 * e1) == 1


# Tolerances: each output coefficient sums at most 8 products of inputs ≤ 10 (≤ 8 roundings
# of values ≤ 100 on each side): 1e-12 absolute is ~20x the worst case.
@given(even8, even8)
def test_mmul_is_the_geometric_product(a, b):
    expected = coeffs(mv(a, _pga.MOTOR) * mv(b, _pga.MOTOR))
    assert np.allclose(MK.mmul(a, b), expected, rtol=0, atol=1e-12)


@given(even8, st.tuples(*[finite] * 6))
def test_mmul_line_is_the_product_with_a_bivector(a, b):
    expected = coeffs(mv(a, _pga.MOTOR) * mv(b, _pga.LINE))
    assert np.allclose(MK.mmul_line(a, b), expected, rtol=0, atol=1e-12)


@given(st.tuples(*[finite] * 6), st.tuples(*[finite] * 6))
def test_line_commutator_is_half_the_commutator(a, b):
    A, B = mv(a, _pga.LINE), mv(b, _pga.LINE)
    expected = 0.5 * (A * B - B * A)
    assert np.allclose(MK.line_commutator(a, b), coeffs(expected, _pga.LINE), rtol=0, atol=1e-12)
    assert np.abs(np.delete(np.asarray(expected.value), list(_pga.LINE))).max() < 1e-12


@given(even8)
def test_mrev_is_reversion(a):
    assert np.array_equal(MK.mrev(a), coeffs(~mv(a, _pga.MOTOR)))


@pytest.mark.parametrize("kind", ["plane", "line", "point"])
@given(q=quat, t=vec3, x=st.tuples(*[finite] * 6))
def test_sandwiches_are_cliffords_for_unit_motors(kind, q, t, x):
    indices = {"plane": _pga.PLANE, "line": _pga.LINE, "point": _pga.POINT}[kind]
    x = x[: len(indices)]
    M = unit_motor(q, t)
    expected = M * mv(x, indices) * ~M
    kernel = getattr(MK, f"sandwich_{kind}")
    got = kernel(tuple(coeffs(M)), x)
    # The cubic products reach ~10 * 10² * 10 = 1e4: a few roundings of that.
    assert np.allclose(got, coeffs(expected, indices), rtol=0, atol=1e-10)
    others = np.delete(np.asarray(expected.value), list(indices))
    assert np.abs(others).max() < 1e-10  # a unit motor keeps the grade


@given(quat, quat)
def test_dual_parts_are_the_rotor_isomorphism_and_e0123_times_it(r, d):
    motor = rotor_of(r) + I * rotor_of(d)
    assert MK.dual_parts(tuple(coeffs(motor))) == (tuple(r), tuple(d))
    assert np.array_equal(MK.from_dual_parts(r, d), coeffs(motor))
    assert list(MK.from_dual_parts((0.0, 0.0, 0.0, 0.0), (1.0, 2.0, 3.0, 4.0))) == [
        0.0, 2.0, 3.0, 4.0, 0.0, 0.0, 0.0, 1.0,
    ]  # d = (e0123, e01, e02, e03) coefficients, no signs  # fmt: skip


@given(quat, vec3)
def test_motor_from_pose_is_translator_times_rotor(q, t):
    n = np.sqrt(sum(c * c for c in q))
    q = tuple(c / n for c in q)
    expected = coeffs(translator(t) * rotor_of(q))
    assert np.allclose(MK.motor_from_pose(q, t), expected, rtol=0, atol=1e-13)
    assert np.allclose(MK.translation(tuple(expected)), t, rtol=0, atol=1e-12)


def test_the_translator_moves_points_by_plus_t():
    t = np.array([1.0, -2.0, 0.5])
    T = translator(t)
    for x in ([0.0, 0.0, 0.0], [3.0, 1.0, -4.0]):
        assert np.allclose((T * point_mv(x) * ~T).value, point_mv(np.add(x, t)).value)
    # and the opposite sign, 1 + ½ e0 t, moves them by −t: the choice is not idle.
    other = 1 + 0.5 * (e0 * (t[0] * e1 + t[1] * e2 + t[2] * e3))
    assert np.allclose((other * point_mv([0.0, 0.0, 0.0]) * ~other).value, point_mv(-t).value)
