"""Agreement: formulas derived by symbolic/ evaluate to what the numeric package computes.

Each test lambdifies an expression that `symbolic` derived (or checked) exactly and
compares it with a public function of ga_rotors on random inputs. The two sides share no
code: symbolic builds everything from Hamilton's unit table, Cl(p,q) blade products and
rotation matrices; ga_rotors from its compiled kernels and clifford.

Tolerances: both sides evaluate short formulas (at most ~20 floating-point operations
on O(1) numbers, sines and cosines correct to 1 ulp), so each side is within ~20 eps of
the exact value and their difference within 40 eps ≈ 9e-15; TOL = 1e-14 is that bound.
Angle extractions are compared away from gimbal lock (sin θ ≥ 0.1), where the condition
number 1/sin θ ≤ 10 gives ANGLE_TOL = 1e-13.
"""

from __future__ import annotations

import numpy as np
import pytest
import sympy

from ga_rotors import _kernels, euler, isomorphism, kinematics, matrix, rotor
from ga_rotors import quaternion as Q
from ga_rotors.symbolic import hamilton, rotations, rotors
from ga_rotors.symbolic.audit import notes, paper_dynamics, paper_kinematics
from ga_rotors.symbolic.audit.common import ANGLES, OMEGA, RATES, zyz_body_rates
from ga_rotors.symbolic.isomorphisms import quaternion_to_rotor

TOL = 1e-14
ANGLE_TOL = 1e-13
N = 200

q_sym = hamilton.symbols("q")
p_sym = hamilton.symbols("p")
v_sym = sympy.symbols("v1:4", real=True)


@pytest.fixture(scope="module")
def rng():
    return np.random.default_rng(20240611)


def _unit_quaternions(rng, n=N):
    q = rng.normal(size=(n, 4))
    q /= np.linalg.norm(q, axis=1, keepdims=True)
    return q


def _f(args, exprs):
    """A NumPy function of column arrays returning an array (..., len(exprs))."""
    f = sympy.lambdify(args, list(exprs), "numpy")

    def call(*cols):
        out = f(*cols)
        return np.stack(
            [np.broadcast_to(np.asarray(o, dtype=float), np.shape(cols[0])) for o in out], axis=-1
        )

    return call


def _same_rotation(a, b):
    """Unit quaternions equal up to the overall sign (q and −q are one rotation)."""
    return np.minimum(np.abs(a - b).max(axis=-1), np.abs(a + b).max(axis=-1))


def test_hamilton_product_matches_quaternion_multiply(rng):
    f = _f((*q_sym, *p_sym), hamilton.mul(q_sym, p_sym))
    q, p = rng.normal(size=(N, 4)), rng.normal(size=(N, 4))
    np.testing.assert_allclose(f(*q.T, *p.T), Q.multiply(q, p), rtol=0, atol=TOL * 10)


def test_inverse_is_conjugate_over_norm_squared(rng):
    n2 = hamilton.norm2(q_sym)
    f = _f(q_sym, [c / n2 for c in hamilton.conj(q_sym)])
    q = rng.normal(size=(N, 4))
    np.testing.assert_allclose(f(*q.T), Q.inverse(q), rtol=1e-14, atol=0)


def test_rotation_matrix_matches_matrix_from_quaternion(rng):
    m = rotors.rotor_sandwich().matrix  # derived from R v R̃ (= q v q*), no unit assumption
    f = _f(q_sym, list(m))
    q = _unit_quaternions(rng)
    np.testing.assert_allclose(
        f(*q.T).reshape(N, 3, 3), matrix.from_quaternion(q), rtol=0, atol=TOL
    )


def test_isomorphism_coefficients_match_the_numeric_table():
    # φ(q) = w − x e23 − y e31 − z e12 in clifford's blade order: exactly the numeric table.
    coeffs = quaternion_to_rotor(q_sym).coefficients()
    for k in range(4):
        unit = [0.0] * 4
        unit[k] = 1.0
        ours = [float(c.subs(dict(zip(q_sym, unit, strict=True)))) for c in coeffs]
        assert ours == isomorphism.to_even(unit).tolist()


def test_rotor_sandwich_matches_rotor_apply(rng):
    r = quaternion_to_rotor(q_sym)
    image = r * rotors.vector(v_sym) * r.reverse()
    f = _f((*q_sym, *v_sym), rotors.vector_part(image))
    q, v = _unit_quaternions(rng, 20), rng.normal(size=(20, 3))
    got = f(*q.T, *v.T)
    for k in range(20):
        np.testing.assert_allclose(
            got[k], rotor.apply(rotor.from_quaternion(q[k]), v[k]), rtol=0, atol=TOL * 4
        )


@pytest.mark.parametrize(
    "seq", [s.upper() for s in rotations.SEQUENCES] + list(rotations.SEQUENCES)
)
def test_euler_sequences_match_euler_to_quaternion_and_scipy(rng, seq):
    from scipy.spatial.transform import Rotation

    a, b, c = sympy.symbols("a b c", real=True)
    fq = _f((a, b, c), rotations.euler_quaternion(seq, (a, b, c)))
    fm = _f((a, b, c), list(rotations.euler_matrix(seq, (a, b, c))))
    angles = rng.uniform(-np.pi, np.pi, size=(50, 3))
    assert _same_rotation(fq(*angles.T), euler.to_quaternion(seq, angles)).max() < TOL
    np.testing.assert_allclose(
        fm(*angles.T).reshape(50, 3, 3),
        Rotation.from_euler(seq, angles).as_matrix(),
        rtol=0,
        atol=TOL,
    )


def test_paper_eq24_components_match_euler_zyz(rng):
    f = _f(ANGLES, paper_kinematics.printed24())  # (24) as printed, minus restored in q0
    angles = rng.uniform(-np.pi, np.pi, size=(N, 3))
    assert _same_rotation(f(*angles.T), euler.to_quaternion("ZYZ", angles)).max() < TOL


def test_body_rates_eq15_match_kinematics(rng):
    omega, _ = zyz_body_rates()
    f = _f((*ANGLES, *RATES), omega)
    angles, rates = rng.uniform(-3, 3, size=(N, 3)), rng.normal(size=(N, 3))
    np.testing.assert_allclose(
        f(*angles.T, *rates.T),
        kinematics.body_omega_from_zyz_rates(angles, rates),
        rtol=0,
        atol=TOL * 4,
    )


def test_inverse_rates_eq19_match_kinematics(rng):
    f = _f((*ANGLES, *OMEGA), paper_dynamics.printed19(minus=True))
    angles = rng.uniform(-3, 3, size=(N, 3))
    angles[:, 1] = rng.uniform(0.1, np.pi - 0.1, size=N)  # 1/sin θ ≤ 10
    w = rng.normal(size=(N, 3))
    np.testing.assert_allclose(
        f(*angles.T, *w.T), kinematics.zyz_rates_from_body_omega(angles, w), rtol=0, atol=ANGLE_TOL
    )


def test_quaternion_kinematics_matches_quaternion_rate(rng):
    rate = rotors.rotor_kinematics().quaternion_rate  # ½ q ⊗ (0, ω), derived from Ṙ = ½RΩ
    w_sym = sympy.symbols("omega1:4", real=True)
    f = _f((*q_sym, *w_sym), rate)
    q, w = _unit_quaternions(rng), rng.normal(size=(N, 3))
    np.testing.assert_allclose(f(*q.T, *w.T), kinematics.quaternion_rate(q, w), rtol=0, atol=TOL)


def test_rotor_rate_matches_kinematics_rotor_rate(rng):
    w_sym = sympy.symbols("omega1:4", real=True)
    r = quaternion_to_rotor(q_sym)
    rate = r * rotors.dual_bivector(w_sym) / 2
    f = _f((*q_sym, *w_sym), rate.coefficients())
    q, w = _unit_quaternions(rng, 10), rng.normal(size=(10, 3))
    got = f(*q.T, *w.T)
    for k in range(10):
        expected = kinematics.rotor_rate(rotor.from_quaternion(q[k]), w[k]).value
        np.testing.assert_allclose(got[k], expected, rtol=0, atol=TOL)


def test_euler_equations_match_body_euler_rates(rng):
    ix, iy, iz, mx, my, mz = sympy.symbols("I_x I_y I_z M_x M_y M_z", positive=True)
    wx, wy, wz = OMEGA
    derived = (
        (iy - iz) / ix * wy * wz + mx / ix,
        (iz - ix) / iy * wz * wx + my / iy,
        (ix - iy) / iz * wx * wy + mz / iz,
    )
    assert paper_dynamics.eq18().checks_ok  # the form above is the one (17) was solved into
    f = sympy.lambdify((ix, iy, iz, *OMEGA, mx, my, mz), derived)
    for _ in range(50):
        inertia = tuple(rng.uniform(1, 2, size=3))
        w, tau = tuple(rng.normal(size=3)), tuple(rng.normal(size=3))
        np.testing.assert_allclose(
            f(*inertia, *w, *tau), _kernels.euler_rates(inertia, w, tau), rtol=1e-14, atol=TOL
        )


def test_zyz_extraction_corrected_eq38_to_40_matches_euler_from_quaternion(rng):
    q0, q1, q2, q3 = q_sym
    psi = sympy.atan2(2 * (q2 * q3 - q0 * q1), 2 * (q1 * q3 + q0 * q2))  # (38) as atan2
    theta = 2 * sympy.atan2(sympy.sqrt(q1**2 + q2**2), sympy.sqrt(q0**2 + q3**2))  # (39) fixed
    phi = sympy.atan2(2 * (q2 * q3 + q0 * q1), -2 * (q1 * q3 - q0 * q2))  # (40) as atan2
    f = _f(q_sym, (psi, theta, phi))
    angles = rng.uniform(-3, 3, size=(N, 3))
    angles[:, 1] = rng.uniform(0.1, np.pi - 0.1, size=N)
    q = euler.to_quaternion("ZYZ", angles)
    got = f(*q.T)
    np.testing.assert_allclose(got, euler.from_quaternion(q, "ZYZ"), rtol=0, atol=ANGLE_TOL)
    np.testing.assert_allclose(got, angles, rtol=0, atol=ANGLE_TOL)


#: m[a] − m[b] = 4 q0 q_k (zero-based matrix indices), from the audit's N16 derivation.
ANTISYMMETRIC = {1: ((2, 1), (1, 2)), 2: ((0, 2), (2, 0)), 3: ((1, 0), (0, 1))}


def test_matrix_to_quaternion_branch_formulas_match_matrix_to_quaternion(rng):
    # The notes' trace branch (exact where q0 > 0) and the largest-diagonal branches the
    # audit derived (4 q_k² = 1 + 2 m_kk − trace, m_ik + m_ki = 4 q_i q_k), each used
    # where it is best conditioned.
    assert notes.n16_matrix_to_quaternion().checks_ok
    q = _unit_quaternions(rng)
    m = matrix.from_quaternion(q)
    tr = np.trace(m, axis1=1, axis2=2)
    ours = np.empty_like(q)
    for n in range(N):
        k = int(np.argmax([tr[n], m[n, 0, 0], m[n, 1, 1], m[n, 2, 2]]))
        if k == 0:
            ours[n] = notes._notes_to_quaternion(m[n])
            continue
        a = np.zeros(4)
        a[k] = np.sqrt(1 + 2 * m[n, k - 1, k - 1] - tr[n]) / 2
        (r1, c1), (r2, c2) = ANTISYMMETRIC[k]
        a[0] = (m[n, r1, c1] - m[n, r2, c2]) / (4 * a[k])
        for i in {1, 2, 3} - {k}:
            a[i] = (m[n, i - 1, k - 1] + m[n, k - 1, i - 1]) / (4 * a[k])
        ours[n] = a
    # Each branch divides by a component ≥ 1/2, so the error stays within a few TOL.
    assert _same_rotation(ours, matrix.to_quaternion(m)).max() < 10 * TOL
    assert _same_rotation(ours, q).max() < 10 * TOL


def test_aerospace_corrected_notes_formula_matches_euler_zyx(rng):
    psi, phi, theta = sympy.symbols("ψ φ θ", real=True)
    corrected = notes._printed_aerospace(psi, phi, theta, signs=(-1, -1))
    f = _f((psi, phi, theta), corrected)
    angles = rng.uniform(-3, 3, size=(N, 3))  # columns ψ (roll), φ (pitch), θ (yaw)
    zyx = euler.to_quaternion("ZYX", angles[:, [2, 1, 0]])
    assert _same_rotation(f(*angles.T), zyx).max() < TOL


def test_angle_axis_latitude_longitude_match_quaternion(rng):
    q = _unit_quaternions(rng)
    q[q[:, 0] < 0] *= -1  # the notes' axis q⃗/|q⃗| is the numeric axis when q0 ≥ 0
    q0, q1, q2, q3 = q.T
    vec = np.hypot(np.hypot(q1, q2), q3)
    np.testing.assert_allclose(2 * np.arctan2(vec, q0), Q.angle(q), rtol=0, atol=TOL)
    np.testing.assert_allclose(q[:, 1:] / vec[:, None], Q.axis(q), rtol=0, atol=TOL)
    lat, lon = Q.latitude_longitude(q)
    np.testing.assert_allclose(np.arctan(q3 / np.hypot(q1, q2)), lat, rtol=0, atol=TOL)  # N19
    np.testing.assert_allclose(np.arctan2(q2, q1), lon, rtol=0, atol=TOL)  # N20 with atan2
