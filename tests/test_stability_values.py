"""Stability suite, values and inputs: degenerate values, non-unit inputs, fuzzed conversions.

One named test per hard case of issue 7 (the dynamics half is test_stability_dynamics.py);
docs/stability.md ("Degenerate values and inputs") is the table these tests back.

Budgets: U = 2⁻⁵³ is the unit round-off (half an ulp of 1). A correctly rounded operation
adds at most U relative error, a libm function (sin, cos, atan2, hypot) at most one ulp,
2U. Each assertion counts the roundings on its path; a geodesic angle is twice the
vector-part error of the quaternion it measures.

Also run uncompiled (``test_stability_values_agree_uncompiled``, tests/uncompiled.py): the
kernels and loops give the same answers as plain Python.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from oracles import U, random_axes, random_unit, rotation_error
from scipy.spatial.transform import Rotation
from uncompiled import uncompiled_twin

from ga_rotors import _kernels as K
from ga_rotors import euler, isomorphism, kinematics, matrix, rotor, simulate
from ga_rotors import paths as P
from ga_rotors import quaternion as Q
from ga_rotors.body import RigidBody
from ga_rotors.errors import GimbalLockWarning, InputError, SceneError
from ga_rotors.integrators import Problem, get
from ga_rotors.scene import Scene

AXIS = np.array([2.0, -3.0, 6.0]) / 7.0  # a unit axis with no zero component
BASE = np.array([0.3, -0.5, 0.7, 0.2]) / math.sqrt(0.87)  # a generic unit quaternion
BLADES = rotor.layout().blades
E12, E23, E31 = BLADES["e12"], BLADES["e23"], BLADES["e3"] * BLADES["e1"]
TINY_ANGLES = [0.0, 1e-300, 1e-200, 1e-100, 1e-20, 1e-12, 1e-9]
SUBNORMAL = math.ldexp(1.0, -1030)  # below the smallest normal 2⁻¹⁰²²; halving is exact


def mv(q):
    """Any array of 4 numbers as an even multivector, through the coefficient table (no
    validation: the tests feed it non-unit and non-finite values on purpose)."""
    from clifford import MultiVector

    c = np.zeros(8)
    for component, blade, sign in isomorphism.ISOMORPHISM:
        c[blade] = sign * q[component]
    return MultiVector(rotor.layout(), c)


def bivector(r):
    """−I r / 2: the bivector whose exp is the rotor of rotation vector r."""
    return -0.5 * (r[0] * E23 + r[1] * E31 + r[2] * E12)


# =========================================================================================
# Degenerate values
# =========================================================================================

# --- ω = 0, 1e-300, 1e-9 through the exp/log kernels -------------------------------------


@pytest.mark.parametrize("angle", [*TINY_ANGLES, SUBNORMAL])
def test_degenerate_omega_exp_log_kernels_exact(angle):
    r = tuple(angle * AXIS) if angle != SUBNORMAL else (angle, 0.0, 0.0)
    q = K.quat_from_rotvec(r)
    # cos(|r|/2) rounds to 1 below |r| ~ 1e-8: the scalar part is exactly 1
    assert q[0] == 1.0
    # vector part = r/2: 0.5·r exact, hypot3 (2 libm calls, 4U), sin(s)/s (sin is s itself
    # here: 1 division, U), the product (U): 6U relative. A product underflowing to 0 or a
    # sin(s)/s = 0/0 would be off by 100 %.
    assert np.allclose(q[1:], 0.5 * np.array(r), rtol=6 * U, atol=0)
    assert K.qexp_pure(tuple(0.5 * np.array(r))) == q
    # back: hypot3 (4U), atan2 (2U), division and product (2U), doubling exact: 8U, plus
    # the 6U of q: 14U
    back = np.array(K.rotvec_from_quat(q))
    assert np.allclose(back, r, rtol=14 * U, atol=0)
    assert np.all(np.isfinite(back)) and (angle > 0) == bool(np.any(back))


@pytest.mark.parametrize("s", [0.0, 1e-300, 1e-9])
def test_degenerate_omega_kinematics_rates_exact(s):
    w = s * AXIS
    # at the identity q̇ = ½ (0, ω): every product is by 0 or 1, so exact
    assert np.array_equal(kinematics.quaternion_rate([1.0, 0, 0, 0], w), [0.0, *(0.5 * w)])
    Rdot = kinematics.rotor_rate(rotor.from_quaternion([1.0, 0, 0, 0]), w)
    assert np.array_equal(Rdot.value, bivector(w).value)
    # at a generic q: each rate component is 4 products summed (4U of |q||ω| = |ω|), and
    # ω = 2 vec(q* q̇) adds 5 more roundings per component: 9U·|ω| per component, 16U in norm
    qdot = kinematics.quaternion_rate(BASE, w)
    back = kinematics.body_omega_from_quaternion_rate(BASE, qdot)
    assert np.linalg.norm(back - w) <= 16 * U * s
    R = rotor.from_quaternion(BASE)
    back = kinematics.body_omega_from_rotor_rate(R, kinematics.rotor_rate(R, w))
    assert np.linalg.norm(back - w) <= 16 * U * s


# The integrators' single steps. Every template integrator on the quaternion path; on the
# rotor path the steps are the same templates over signed permutations of the same state
# (tests/test_rotor_kernels.py), except the rate-based ones, which use the generated rotor
# rate: rk4 and rk4_renorm run there too. The Euler-angle path: rk4, dop853 and dp8.
STEPPERS = [
    *[(name, "quaternion") for name in ("cf4", "cg3", "dop853", "dp8", "lgvi", "lie_euler",
                                        "midpoint", "rk4", "rk4_renorm", "rkmk4", "split2",
                                        "split4", "split4_yoshida", "split6", "split_sym")],
    ("rk4", "rotor"), ("rk4_renorm", "rotor"),
    ("rk4", "euler"), ("dop853", "euler"), ("dp8", "euler"),
]  # fmt: skip
STEP = 1e-3


def one_step(name, path, q0, w, body):
    module = P.get(path).load()
    start = euler.from_quaternion(q0, "ZYZ") if path == "euler" else q0
    run = get(name).run(Problem(body), path, module.initial_state(start), w, 0.0, STEP, 1, 1)
    assert run.complete and np.all(np.isfinite(run.x)) and np.all(np.isfinite(run.w))
    return module.quaternions(run.x)[-1], run.w[-1]


@pytest.mark.parametrize("name, path", STEPPERS)
@pytest.mark.parametrize("s", [0.0, 1e-300, 1e-9])
def test_degenerate_omega_single_step_of_every_integrator(name, path, s):
    # Two bodies where ω is exactly constant: a sphere (ω along a generic axis) and an
    # asymmetric body spinning about a principal axis. The exact step is q0 ⊗ exp(ωh/2);
    # the truncation error ~(|ω|h)^(p+1) underflows, so only rounding is left. A step
    # composes sub-rotations whose weights sum in magnitude to at most 5.71 (split6's
    # YOSHIDA6); each carries ~4 roundings relative to its size: 24U relative error in the
    # vector part and in ω. At the identity that vector part is ωh/2 itself, so a tiny ω
    # lost to underflow, or a sin(x)/x = 0/0, fails by 100 %.
    for body, w in (((1.0, 1.0, 1.0), s * AXIS), ((1.0, 2.0, 3.0), np.array([s, 0.0, 0.0]))):
        exact = Q.from_rotation_vector(w * STEP)
        if path == "euler":
            # the angles' path: from a generic orientation (θ = 0 is gimbal lock, the
            # dynamics suite's case); the conversion to angles and back is 16U in angle
            q0 = Q.from_axis_angle([1.0, 2.0, 0.5], 0.8)
            q, w1 = one_step(name, path, q0, w, body)
            assert Q.distance(Q.normalize(q), Q.multiply(q0, exact)) <= 16 * U
        else:
            q, w1 = one_step(name, path, np.array([1.0, 0.0, 0.0, 0.0]), w, body)
            assert q[0] == 1.0
            assert np.all(np.abs(q[1:] - exact[1:]) <= 24 * U * np.abs(exact[1:]))
        assert np.all(np.abs(w1 - w) <= 24 * U * s)


# --- exp and log at 0, tiny, π − 1e-12, exactly π and π + tiny ---------------------------


@pytest.mark.parametrize("alpha", TINY_ANGLES)
def test_exp_log_at_zero_and_tiny_angles_quaternion_module(alpha):
    # moved from test_quaternion.py (test_angle_exact_at_tiny_angles)
    q = Q.from_axis_angle(AXIS, alpha)
    assert math.isclose(Q.angle(q), alpha, rel_tol=2 * U)
    if alpha > 0:
        assert np.allclose(Q.axis(q), AXIS, rtol=0, atol=2 * U)
    # the notes' 2 acos(w) returns exactly 0 below ~1e-8
    assert alpha > 1e-8 or 2 * math.acos(q[0]) == 0.0
    # exp/log of the pure quaternion (0, r/2): the same 6U and 14U as the kernels
    r = alpha * AXIS
    assert np.allclose(Q.exp([0.0, *(r / 2)])[1:], r / 2, rtol=6 * U, atol=0)
    assert np.allclose(Q.log(q)[1:], r / 2, rtol=14 * U, atol=0)
    assert np.allclose(Q.to_rotation_vector(Q.from_rotation_vector(r)), r, rtol=14 * U, atol=0)


@pytest.mark.parametrize("alpha", TINY_ANGLES)
def test_exp_log_at_zero_and_tiny_angles_rotor_module(alpha):
    # moved from test_rotor.py (test_exp_log_exact_at_tiny_angles)
    B = bivector(alpha * AXIS)  # −I u α/2
    R = rotor.exp(B)
    assert R.value[0] == 1.0 or alpha > 1e-8
    assert np.allclose(rotor.log(R).value, B.value, rtol=2 * U, atol=0)
    assert math.isclose(rotor.to_axis_angle(R)[1], alpha, rel_tol=2 * U)


@pytest.mark.parametrize("eps", [0.0, 1e-12, 1e-8])
def test_log_at_and_near_half_turn_kernels(eps):
    # moved from test_kernels.py (test_log_exact_near_half_turn)
    axis = np.array([1.0, 2.0, 2.0]) / 3.0
    angle = math.pi - eps
    q = K.quat_from_rotvec(tuple(angle * axis))
    back = np.array(K.rotvec_from_quat(q))
    # one rounding each in angle*axis, sin/cos, hypot, atan2 and the norm: 4 ulp of pi.
    # (2*acos(w) is also accurate here, w ≈ 0; acos loses digits only where |w| → 1.)
    assert math.isclose(np.linalg.norm(back), angle, rel_tol=0, abs_tol=4 * math.ulp(math.pi))
    assert np.allclose(back / np.linalg.norm(back), axis, atol=1e-15)


@pytest.mark.parametrize("eps", [0.0, 1e-12, 1e-9])
def test_angle_at_and_near_half_turn_quaternion_module(eps):
    # moved from test_quaternion.py (test_angle_exact_at_and_near_half_turn)
    u = np.array([1.0, 2.0, 2.0]) / 3.0
    q = Q.from_axis_angle(u, math.pi - eps)
    # 2 atan2 keeps the angle to a few ulp of pi; 2 acos(w) would be off by ~1e-8 here
    assert math.isclose(Q.angle(q), math.pi - eps, rel_tol=0, abs_tol=4 * math.ulp(math.pi))
    assert np.allclose(Q.axis(q), u, rtol=0, atol=2 * U)


@pytest.mark.parametrize("eps", [0.0, 1e-12])
def test_exp_log_at_and_near_half_turn_rotor_module(eps):
    # moved from test_rotor.py (test_exp_log_exact_at_and_near_half_turn)
    u = np.array([1.0, 2.0, 2.0]) / 3.0
    alpha = math.pi - eps
    R = rotor.from_axis_angle(u, alpha)
    B = rotor.log(R)
    half = math.sqrt(sum(B.value[k] ** 2 for k in (4, 5, 6)))
    assert math.isclose(2 * half, alpha, rel_tol=0, abs_tol=4 * math.ulp(math.pi))
    assert np.allclose(rotor.exp(B).value, R.value, rtol=0, atol=4 * U)


HALF_TURN_AXES = [*np.eye(3), *random_axes(60, 5)]


@pytest.mark.parametrize("u", HALF_TURN_AXES, ids=lambda u: np.array2string(u, precision=2))
@pytest.mark.parametrize("beyond", [0.0, 1e-12, 1e-300])
def test_log_at_exactly_pi_and_beyond_has_norm_pi_and_the_same_rotation(u, beyond):
    # q = (0, u) exactly is the half-turn (trace −1); past it, (−ε, u) with ε = tiny sin
    # is the rotation by π + 2ε about u = π − 2ε about −u. The rotation vector has norm
    # ≤ π (atan2: 2U; hypot3 4U; scaling 2U → 8U relative ≈ 3 ulp of π) and maps back to
    # the same rotation: geodesic angle ≤ 2 × (8U + the 6U of exp) ≈ 28U.
    q = Q.normalize([-beyond, *u])
    r = Q.to_rotation_vector(q)
    expected = math.pi - 2 * beyond
    assert math.isclose(np.linalg.norm(r), expected, rel_tol=8 * U)
    assert Q.distance(Q.from_rotation_vector(r), q) <= 28 * U
    assert np.dot(r, u) * (1 if beyond == 0 else -1) >= 0  # past π the axis flips to −u
    # the quaternion log keeps the sign: |vector part| = π/2 + ε, exp(log q) = q to 4U
    assert np.allclose(Q.exp(Q.log(q)), q, rtol=0, atol=4 * U)
    # the rotor: log has |B| = half the angle of R (not of −R), exp(log R) = R
    R = rotor.from_quaternion(q)
    B = rotor.log(R)
    assert math.isclose(2 * math.hypot(*B.value[4:7]), 2 * math.atan2(1.0, -beyond), rel_tol=8 * U)
    assert np.allclose(rotor.exp(B).value, R.value, rtol=0, atol=4 * U)
    assert np.allclose(rotor.to_rotation_vector(R), r, rtol=0, atol=8 * U * math.pi)


def test_log_at_plus_and_minus_one_documented_z_axis():
    # moved from test_kernels.py (test_log_of_minus_one_chooses_z_axis), test_quaternion.py
    # (test_log_of_minus_one_chooses_z) and test_rotor.py (test_log_at_plus_and_minus_one)
    assert K.qlog_unit((-1.0, 0.0, 0.0, 0.0)) == (0.0, 0.0, math.pi)
    assert K.qlog_unit((1.0, 0.0, 0.0, 0.0)) == (0.0, 0.0, 0.0)
    assert K.rotvec_from_quat((-1.0, 0.0, 0.0, 0.0)) == (0.0, 0.0, 0.0)
    assert np.array_equal(Q.log([-2.0, 0, 0, 0]), [math.log(2.0), 0, 0, math.pi])
    assert np.array_equal(rotor.log(1.0 + 0 * E12).value, np.zeros(8))
    B = rotor.log(-1.0 + 0 * E12)
    assert np.array_equal(B.value, (-math.pi * E12).value)  # documented: the z axis
    assert np.allclose(rotor.exp(B).value, (-1.0 + 0 * E12).value, rtol=0, atol=2 * U)


# --- matrix → quaternion at trace −1 -------------------------------------------------------


@pytest.mark.parametrize("axis", [0, 1, 2])
def test_matrix_to_quaternion_at_trace_minus_one_coordinate_axes_exact(axis):
    # moved from test_kernels.py (test_matrix_to_quaternion_exact_at_half_turns)
    m = [1.0 if k == axis else -1.0 for k in range(3)]
    q = K.quat_from_matrix((m[0], 0.0, 0.0, 0.0, m[1], 0.0, 0.0, 0.0, m[2]))
    expected = [0.0, 0.0, 0.0, 0.0]
    expected[1 + axis] = 1.0
    assert q == tuple(expected)
    assert np.array_equal(matrix.to_quaternion(np.diag(m)), expected)
    assert np.array_equal(rotor.to_quaternion(rotor.from_matrix(np.diag(m))), expected)


def test_matrix_to_quaternion_at_trace_minus_one_random_axes():
    # moved from test_matrix.py (test_half_turns_about_random_axes_trace_minus_one)
    u = random_axes(33, 50)
    m = 2.0 * np.einsum("ni,nj->nij", u, u) - np.eye(3)  # half-turn: 2uuᵀ − I, trace −1
    q = matrix.to_quaternion(m)
    # the notes' q0 = √(1 + tr)/2 = 0 and they divide by 4 q0: nan. Here: exact.
    assert np.all(np.isfinite(q)) and np.all(np.abs(q[:, 0]) <= 4 * U)
    assert np.allclose(np.abs(np.einsum("ni,ni->n", q[:, 1:], u)), 1.0, rtol=0, atol=8 * U)
    assert rotation_error(q, Rotation.from_matrix(m)).max() <= 16 * U
    # the rotor module goes through the same branch
    for k in range(0, 50, 10):
        assert Q.distance(rotor.to_quaternion(rotor.from_matrix(m[k])), q[k]) <= 4 * U


@pytest.mark.parametrize("axis", [0, 1, 2])
@pytest.mark.parametrize("eps", [0.0, 1e-15, 1e-12, 1e-8])
def test_matrix_to_quaternion_at_trace_minus_one_plus_tiny(axis, eps):
    # moved from test_matrix.py (test_near_half_turn_about_coordinate_axes); trace −1 + tiny
    # is the rotation by π − eps (trace 1 + 2 cos α ≈ −1 + eps²)
    r = np.zeros(3)
    r[axis] = np.pi - eps
    m = Rotation.from_rotvec(r).as_matrix()
    q = matrix.to_quaternion(m)
    # m's entries carry ~2U each; the branch takes a square root and divides by ≥ 1/2:
    # 8U relative in the angle
    assert abs(Q.angle(q) - (np.pi - eps)) <= 8 * U * np.pi
    u = random_axes(61, 1)[0]
    m = Rotation.from_rotvec((np.pi - eps) * u).as_matrix()
    assert Q.distance(matrix.to_quaternion(m), Q.from_rotation_vector((np.pi - eps) * u)) <= 16 * U


# --- slerp between q and −q, and between nearly equal rotations -----------------------------


def test_slerp_between_q_and_minus_q_is_q():
    # moved from test_kernels.py (test_slerp_of_q_and_minus_q_stays_put), test_quaternion.py
    # (test_slerp_q_to_minus_q_is_constant) and test_rotor.py (part of
    # test_slerp_of_r_and_minus_r_is_constant_and_nearly_equal_is_exact).
    # Documented choice: q and −q are one rotation; the path is constant and keeps the
    # sign of the first argument. q* ⊗ (−q) = −1 to 2U (a 4-term sum of squares), negated
    # to +1: the log is 0 to 2U and the result is q to 2U per component.
    q = random_unit(19, 1)[0]
    for t in (0.0, 0.3, 0.5, 1.0):
        assert np.allclose(K.qslerp(tuple(q), tuple(-q), t), q, rtol=0, atol=2 * U)
    assert np.allclose(Q.slerp(q, -q, np.linspace(0, 1, 5)), q, rtol=0, atol=2 * U)
    R = rotor.from_quaternion(q)
    for t in (0.0, 0.5, 1.0):
        assert np.allclose(rotor.slerp(R, -R, t).value, R.value, rtol=0, atol=4 * U)


@pytest.mark.parametrize("delta", [0.0, 1e-300, 1e-15, 1e-12, 1e-9])
def test_slerp_between_nearly_equal_rotations(delta):
    # moved from test_quaternion.py (test_slerp_exact_for_nearly_equal_rotations), bound
    # tightened; plus the rotor module
    # (1) From the identity the interpolant is (1, t·δ/2·u): log (14U) and exp (6U) of a
    # tiny vector, relative: 20U of the vector part. No 0/0 from sin((1−t)Ω)/sin Ω.
    b = Q.from_rotation_vector(delta * AXIS)
    for t in (0.25, 0.5):
        mid = Q.slerp([1.0, 0, 0, 0], b, t)
        assert mid[0] == 1.0
        assert np.allclose(mid[1:], t * b[1:], rtol=20 * U, atol=0)
        R = rotor.slerp(rotor.from_quaternion([1.0, 0, 0, 0]), rotor.from_quaternion(b), t)
        assert np.allclose(rotor.to_quaternion(R), mid, rtol=20 * U, atol=0)
    # (2) From a generic a, b = a ⊗ exp(δ/2 u) is itself rounded (2U per component), then
    # a* ⊗ b (4 products summed, 4U) and a ⊗ exp(...) (4U): 10U per vector component,
    # a geodesic angle of ≤ 20U (absolute: δ below 1e-15 is below the grid of a and b).
    a = random_unit(18, 1)[0]
    b = Q.multiply(a, Q.from_rotation_vector(delta * AXIS))
    mid = Q.slerp(a, b, 0.5)
    want = Q.multiply(a, Q.from_rotation_vector(0.5 * delta * AXIS))
    assert np.all(np.isfinite(mid)) and Q.distance(mid, want) <= 20 * U
    R = rotor.slerp(rotor.from_quaternion(a), rotor.from_quaternion(b), 0.5)
    assert Q.distance(rotor.to_quaternion(R), want) <= 20 * U


# --- geodesic distance at both ends ---------------------------------------------------------


@pytest.mark.parametrize("delta", [0.0, 1e-15, 1e-12, 1e-9, 1e-6, 1.0, math.pi - 1e-9, math.pi])
def test_geodesic_distance_at_zero_and_pi(delta):
    # moved from test_kernels.py (test_geodesic_angle_resolves_small_and_large); plus the
    # quaternion and rotor modules, and the double cover at both ends
    a = tuple(BASE)
    b = K.qmul(a, K.quat_from_rotvec((0.0, delta, 0.0)))
    # b's components are rounded (half an ulp, ~1e-16 each), so differences are resolved
    # to ~1e-15 rad; 2*acos(.) would bottom out near 1e-8 rad.
    assert math.isclose(K.geodesic_angle(a, b), delta, rel_tol=1e-12, abs_tol=1e-15)
    minus_b = tuple(-c for c in b)
    assert math.isclose(K.geodesic_angle(a, minus_b), delta, rel_tol=1e-12, abs_tol=1e-15)
    # the public function renormalises both arguments (≤ 2U per component each): the
    # angle moves by at most 2 × (2U + 2U)
    assert math.isclose(Q.distance(BASE, b), K.geodesic_angle(a, b), rel_tol=0, abs_tol=8 * U)
    Ra, Rb = rotor.from_quaternion(BASE), rotor.from_quaternion(b)
    assert math.isclose(rotor.distance(Ra, Rb), delta, rel_tol=1e-12, abs_tol=1e-15)
    assert math.isclose(rotor.distance(Ra, -Rb), delta, rel_tol=1e-12, abs_tol=1e-15)
    # never above π, whatever the rounding
    assert 0.0 <= Q.distance(BASE, b) <= math.pi


def test_geodesic_distance_exact_at_zero_and_pi():
    # q vs q and vs −q: exactly 0; q vs q ⊗ (0, u): the vector part of q* ⊗ b is u to 4U
    # and its scalar part 0 to 4U, so the angle is π − 8U at worst, never above π
    for q in random_unit(62, 10):
        # q* ⊗ q has a zero vector part up to the rounding of its products (compiled code
        # may contract them into FMAs, leaving ≤ U each, two per component): ≤ 8U
        assert Q.distance(q, q) <= 8 * U and Q.distance(q, -q) <= 8 * U
        for u in np.eye(3):
            d = Q.distance(q, Q.multiply(q, [0.0, *u]))
            assert math.pi - 8 * U <= d <= math.pi


# =========================================================================================
# Non-unit inputs
# =========================================================================================

# Every function that requires a unit quaternion or rotor, and the name its errors use.
R_BASE = rotor.from_quaternion(BASE)
UNIT_REQUIRED = {
    "quaternion.rotate": (lambda q: Q.rotate(q, [1.0, 2.0, 3.0]), "q"),
    "quaternion.angle": (Q.angle, "q"),
    "quaternion.axis": (Q.axis, "q"),
    "quaternion.latitude_longitude": (lambda q: np.array(Q.latitude_longitude(q)), "q"),
    "quaternion.to_axis_angle": (lambda q: np.append(*Q.to_axis_angle(q)), "q"),
    "quaternion.to_rotation_vector": (Q.to_rotation_vector, "q"),
    "quaternion.slerp(q0)": (lambda q: Q.slerp(q, BASE, 0.3), "q0"),
    "quaternion.slerp(q1)": (lambda q: Q.slerp(BASE, q, 0.3), "q1"),
    "quaternion.distance(q0)": (lambda q: Q.distance(q, [0.0, 1.0, 0, 0]), "q0"),
    "quaternion.distance(q1)": (lambda q: Q.distance([0.0, 1.0, 0, 0], q), "q1"),
    "quaternion.to_matrix": (Q.to_matrix, "q"),
    "quaternion.to_euler": (lambda q: Q.to_euler(q, "ZYX"), "q"),
    "rotor.from_quaternion": (lambda q: rotor.from_quaternion(q).value, "q"),
    "rotor.to_quaternion": (lambda q: rotor.to_quaternion(mv(q)), "R"),
    "rotor.compose": (lambda q: rotor.compose(R_BASE, mv(q)).value, r"rotors\[1\]"),
    "rotor.inverse": (lambda q: rotor.inverse(mv(q)).value, "R"),
    "rotor.apply": (lambda q: rotor.apply(mv(q), [1.0, 2.0, 3.0]), "R"),
    "rotor.log": (lambda q: rotor.log(mv(q)).value, "R"),
    "rotor.slerp(R0)": (lambda q: rotor.slerp(mv(q), R_BASE, 0.3).value, "R0"),
    "rotor.slerp(R1)": (lambda q: rotor.slerp(R_BASE, mv(q), 0.3).value, "R1"),
    "rotor.distance": (lambda q: rotor.distance(mv(q), mv([0.0, 1.0, 0, 0])), "R0"),
    "rotor.to_axis_angle": (lambda q: np.append(*rotor.to_axis_angle(mv(q))), "R"),
    "rotor.to_rotation_vector": (lambda q: rotor.to_rotation_vector(mv(q)), "R"),
    "rotor.to_matrix": (lambda q: rotor.to_matrix(mv(q)), "R"),
    "rotor.to_euler": (lambda q: rotor.to_euler(mv(q), "ZYZ"), "R"),
    "kinematics.quaternion_rate": (lambda q: kinematics.quaternion_rate(q, [1.0, 2, 3]), "q"),
    "kinematics.body_omega_from_quaternion_rate": (
        lambda q: kinematics.body_omega_from_quaternion_rate(q, [0.0, 1, 2, 3]), "q"),
    "kinematics.rotor_rate": (lambda q: kinematics.rotor_rate(mv(q), [1.0, 2, 3]).value, "R"),
    "kinematics.body_omega_from_rotor_rate": (
        lambda q: kinematics.body_omega_from_rotor_rate(mv(q), mv([0.0, 1, 2, 3])), "R"),
    "RigidBody(principal_rotation)": (
        lambda q: np.array(RigidBody((1.0, 2.0, 2.5), tuple(q)).principal_rotation),
        "principal_rotation"),
    "RigidBody.space_momentum": (
        lambda q: RigidBody((1.0, 2.0, 2.5)).space_momentum(q, [1.0, 2, 3]), "q"),
}  # fmt: skip


@pytest.mark.parametrize("function", sorted(UNIT_REQUIRED))
@pytest.mark.parametrize("scale", [1 + 1e-8, 1 - 1e-8, 1 + 0.99e-6])
def test_non_unit_inputs_within_tolerance_are_renormalised(function, scale):
    # Within UNIT_TOLERANCE (1e-6, docs/conventions.md §8) the input is divided by its
    # norm: the ×scale here, the norm and the division round once each, so the
    # renormalised q is within 3U per component of the unit one (|δq| ≤ 6U). Every
    # output here is a rotation matrix, a rotated vector, an angle or an axis, Lipschitz
    # in q with constant ≤ 4 (matrix entries are quadratic in q): 24U of the output's
    # size, plus the computation's own rounding on both sides (≤ 6U each): 36U.
    call, _ = UNIT_REQUIRED[function]
    want = np.asarray(call(BASE.copy()), dtype=float)
    got = np.asarray(call(BASE * scale), dtype=float)
    assert np.allclose(got, want, rtol=0, atol=36 * U * max(1.0, np.linalg.norm(want)))


BAD_NORMS = {"0.5": 0.5, "2": 2.0, "1e-300": 1e-300, "1e300": 1e300, "zero": 0.0,
             "1+2e-6": 1 + 2e-6}  # fmt: skip
BAD_VALUES = {"nan": [np.nan, 0, 0, 0], "inf": [0, np.inf, 0, 0], "-inf": [0, 0, 0, -np.inf]}


@pytest.mark.parametrize("function", sorted(UNIT_REQUIRED))
@pytest.mark.parametrize("bad", [*BAD_NORMS, *BAD_VALUES])
def test_badly_non_unit_inputs_are_rejected_naming_the_argument(function, bad):
    call, name = UNIT_REQUIRED[function]
    q = BASE * BAD_NORMS[bad] if bad in BAD_NORMS else np.array(BAD_VALUES[bad], dtype=float)
    expected = "contains" if bad in BAD_VALUES else "expected unit"
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no overflow/invalid RuntimeWarning on the way...
        # ...except from the kernels run uncompiled (the NUMBA_DISABLE_JIT twin), where they
        # compute on NumPy scalars, which warn where compiled code silently gives inf
        warnings.filterwarnings("ignore", category=RuntimeWarning, module=r"ga_rotors\._kernels")
        with pytest.raises(InputError, match=rf"^{name}: {expected}"):
            call(q)


def test_qunit_kernel_renormalises_within_tolerance_and_nans_beyond():
    # moved from test_kernels.py (test_qunit_renormalises_within_tolerance_and_nans_beyond):
    # the loops' in-kernel check, which the errors above are reported from
    assert K.qunit((1.0 + 1e-7, 0.0, 0.0, 0.0), 1e-6) == (1.0, 0.0, 0.0, 0.0)
    bad_norms = [(1.1, 0, 0, 0), (math.nan, 0, 0, 0), (math.inf, 0, 0, 0), (1e-300, 0, 0, 0),
                 (1e300, 1e300, 0, 0), (0.0, 0, 0, 0)]  # fmt: skip
    for bad in bad_norms:
        assert all(math.isnan(c) for c in K.qunit(bad, 1e-6))


def test_rotate_renormalises_within_tolerance_and_names_q_beyond():
    # moved from test_quaternion.py: a batch is reported at the first bad index
    q = np.array([1.0 + 5e-7, 0, 0, 0])
    assert np.array_equal(Q.rotate(q, [1.0, 2.0, 3.0]), [1.0, 2.0, 3.0])
    with pytest.raises(InputError, match=r"q: expected unit quaternions .* at index \(1,\)"):
        Q.rotate([[1.0, 0, 0, 0], [1.01, 0, 0, 0]], [1.0, 0, 0])


@pytest.mark.parametrize("scale", [1e-300, 1e-150, 0.5, 2.0, 1e150, 1e300])
def test_normalize_accepts_any_nonzero_magnitude_and_rejects_zero(scale):
    # normalize is the one place non-unit input is the point: exact at every magnitude
    # (the norm is scaled, no square under- or overflows): hypot (2U) and a division (U)
    assert np.allclose(Q.normalize(BASE * scale), BASE, rtol=0, atol=3 * U)
    got = rotor.to_quaternion(rotor.normalize(mv(BASE * scale)))
    assert np.allclose(got, BASE, rtol=0, atol=3 * U)
    with pytest.raises(InputError, match=r"^q: expected nonzero"):
        Q.normalize([0.0, 0, 0, 0])
    with pytest.raises(InputError, match=r"^R: expected nonzero values"):
        rotor.normalize(mv([0.0, 0, 0, 0]))


@pytest.mark.parametrize("scale", [1e-300, 1.0, 1e300])
def test_odd_parts_are_rejected_at_every_magnitude(scale):
    # the odd-part test is relative to the multivector's size (isomorphism.from_even), so
    # neither a huge odd part (whose square overflows) nor a tiny multivector that is all
    # odd slips through
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for c in ([scale, scale, 0, 0, 0, 0, 0, 0], [0, 0, 0, 0, scale, 0, 0, scale]):
            with pytest.raises(InputError, match="R: expected an even multivector"):
                isomorphism.from_even(c)
        # round-off-sized odd parts (1e-9 of the size) are dropped
        assert np.array_equal(
            isomorphism.from_even([scale, 1e-9 * scale, 0, 0, 0, 0, 0, 0]), [scale, 0, 0, 0]
        )
    from clifford import MultiVector

    odd = MultiVector(rotor.layout(), np.array([scale, scale, 0, 0, 0, 0, 0, 0]))
    with pytest.raises(InputError, match="R: expected an even multivector"):
        rotor.normalize(odd)
    with pytest.raises(InputError, match="Rdot: expected an even multivector"):
        kinematics.body_omega_from_rotor_rate(R_BASE, odd)


def test_rotation_matrix_within_tolerance_is_accepted_and_projected():
    # moved from test_matrix.py (test_slightly_non_orthonormal_matrix_is_accepted_and_projected
    # and test_tolerance_matches_the_unit_quaternion_tolerance): s·R is accepted exactly
    # when |s − 1| <= UNIT_TOLERANCE, as for quaternions, and the result is unit to 2U
    r = Rotation.from_rotvec([0.3, 0.0, 0.0]).as_matrix()
    for s in (1 + 1e-8, 1 - 1e-8, 1 + 0.99e-6):
        q = matrix.to_quaternion(s * r)
        assert np.isclose(np.linalg.norm(q), 1.0, rtol=0, atol=2 * U)
        assert Q.distance(q, [math.cos(0.15), math.sin(0.15), 0, 0]) <= 16 * U
    for s in (1 + 1.01e-6, 0.5, 2.0, 1e-300, 1e300, 0.0):
        with pytest.raises(InputError, match=r"^m: expected an orthonormal matrix"):
            matrix.to_quaternion(s * r)
    with pytest.raises(InputError, match=r"^m: contains nan"):
        matrix.to_quaternion(np.full((3, 3), np.nan))


# --- integrator initial states ---------------------------------------------------------


def _spin(orientation, paths=("rotor", "quaternion")):
    return simulate((1.0, 2.0, 3.0), orientation, [0.4, -0.2, 0.9], duration=0.05,
                    step=0.01, paths=paths)  # fmt: skip


@pytest.mark.parametrize("scale", [1 + 1e-8, 1 - 1e-8])
def test_initial_state_within_tolerance_is_renormalised_in_simulate(scale):
    # simulate renormalises the initial orientation (2U per component, see above) and
    # integrates from it: the run equals the run from the unit quaternion to those 2U
    # carried through 5 RK4 steps of a well-conditioned flow (≤ 4U)
    ref, tr = _spin(BASE), _spin(BASE * scale)
    assert np.allclose(tr.q, ref.q, rtol=0, atol=4 * U)
    assert np.allclose(tr["rotor_blades"], ref["rotor_blades"], rtol=0, atol=4 * U)
    assert np.allclose(tr.w, ref.w, rtol=0, atol=4 * U)
    assert abs(np.linalg.norm(tr.q[0]) - 1.0) <= 2 * U


@pytest.mark.parametrize("bad", [*BAD_NORMS, *BAD_VALUES])
def test_initial_state_badly_non_unit_is_rejected_in_simulate(bad):
    q = BASE * BAD_NORMS[bad] if bad in BAD_NORMS else np.array(BAD_VALUES[bad], dtype=float)
    expected = "contains" if bad in BAD_VALUES else "expected unit"
    with pytest.raises(InputError, match=rf"^orientation: {expected}"):
        _spin(q)


SCENE = {"body": {"moments": [1.0, 2.0, 2.5]}, "time": {"duration": 0.1},
         "integrator": {"step": 0.01}}  # fmt: skip


def _scene(orientation):
    return Scene({**SCENE, "initial": {"orientation": orientation}})


@pytest.mark.parametrize("scale", [1 + 1e-8, 1 - 1e-8])
def test_initial_state_within_tolerance_is_renormalised_in_scenes(scale):
    q = BASE * scale
    s = _scene({"quaternion": q.tolist()})
    assert np.allclose(s.orientation, BASE, rtol=0, atol=3 * U)
    c = rotor.from_quaternion(BASE).value * scale  # the rotor form: blade names
    s = _scene({"rotor": {"1": c[0], "e12": c[4], "e13": c[5], "e23": c[6]}})
    assert np.allclose(s.orientation, BASE, rtol=0, atol=3 * U)


@pytest.mark.parametrize("bad", ["0.5", "2", "zero", "1+2e-6"])
def test_initial_state_badly_non_unit_is_rejected_in_scenes(bad):
    q = BASE * BAD_NORMS[bad]
    with pytest.raises(SceneError, match=r"initial\.orientation\.quaternion: expected unit"):
        _scene({"quaternion": q.tolist()})
    c = rotor.from_quaternion(BASE).value * BAD_NORMS[bad]
    with pytest.raises(SceneError, match=r"initial\.orientation\.rotor: expected unit"):
        _scene({"rotor": {"1": c[0], "e12": c[4], "e13": c[5], "e23": c[6]}})


# =========================================================================================
# Fuzzing the value-level API
# =========================================================================================

# Quaternions of any magnitude: a direction times 10^k, k from −300 to 300.
direction = st.tuples(*(st.floats(-1.0, 1.0, allow_nan=False),) * 4).filter(
    lambda c: sum(x * x for x in c) > 1e-6
)
any_magnitude = st.builds(lambda c, k: np.array(c) * 10.0**k, direction, st.integers(-300, 300))
any_vector = st.builds(
    lambda c, k: np.array(c) * 10.0**k,
    st.tuples(*(st.floats(-1.0, 1.0, allow_nan=False),) * 3),
    st.integers(-300, 300),
)


@given(any_magnitude)
def test_fuzz_conversion_round_trips_from_any_magnitude(raw):
    # normalize (3U, exact at any magnitude) then every representation and back. Each
    # round trip's budget, as a geodesic angle: matrix 16U (3 roundings per entry, a sqrt,
    # a division and a normalisation), rotation vector and axis–angle 28U (log 8U, exp 6U,
    # doubled), rotor 4U (coefficient copies are exact; renormalisation ~2U).
    q = Q.normalize(raw)
    assert np.all(np.isfinite(q)) and abs(np.linalg.norm(q) - 1.0) <= 4 * U
    assert Q.distance(matrix.to_quaternion(Q.to_matrix(q)), q) <= 16 * U
    assert Q.distance(Q.from_rotation_vector(Q.to_rotation_vector(q)), q) <= 28 * U
    assert Q.distance(Q.from_axis_angle(*Q.to_axis_angle(q)), q) <= 28 * U
    assert Q.distance(rotor.to_quaternion(rotor.from_quaternion(q)), q) <= 4 * U
    assert np.linalg.norm(Q.to_rotation_vector(q)) <= math.pi * (1 + 8 * U)


@given(any_magnitude, st.sampled_from(euler.SEQUENCES))
def test_fuzz_euler_all_24_sequences_from_any_magnitude(raw, seq):
    # angles and back: 32U as a geodesic angle (three axis rotations of 6U each, two
    # products, atan2s of the extraction), plus at gimbal lock the documented move of at
    # most 2·GIMBAL_TOLERANCE when the third angle is forced to 0
    q = Q.normalize(raw)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", GimbalLockWarning)
        angles, locked = euler.from_quaternion(q, seq, return_gimbal=True)
    assert np.all(np.isfinite(angles))
    bound = 32 * U + (2 * euler.GIMBAL_TOLERANCE if locked else 0.0)
    assert Q.distance(euler.to_quaternion(seq, angles), q) <= bound


@given(any_vector)
def test_fuzz_rotation_vectors_of_any_magnitude(r):
    # from 1e-300 rad (exact: vector part r/2) to 1e300 rad (the angle reduced exactly by
    # libm's sin and cos): a finite unit quaternion, whose rotation vector (norm ≤ π) gives
    # the same rotation back, 28U as above
    q = Q.from_rotation_vector(r)
    assert np.all(np.isfinite(q)) and abs(np.linalg.norm(q) - 1.0) <= 8 * U
    back = Q.to_rotation_vector(q)
    assert np.linalg.norm(back) <= math.pi * (1 + 8 * U)
    assert Q.distance(Q.from_rotation_vector(back), q) <= 28 * U
    if math.hypot(*r) < 1.0:  # below π no wrap: the vector itself comes back, 14U
        assert np.allclose(back, r, rtol=0, atol=14 * U * np.abs(r).max())


bad_component = st.sampled_from([np.nan, np.inf, -np.inf])


@given(st.integers(0, 3), bad_component)
def test_fuzz_non_finite_values_are_rejected_naming_the_argument(k, bad):
    q = BASE.copy()
    q[k] = bad
    for call, name in UNIT_REQUIRED.values():
        with pytest.raises(InputError, match=rf"^{name}: contains"):
            call(q)
    v = np.array([0.1, 0.2, 0.3])
    v[k % 3] = bad
    for call, name in (
        (Q.from_rotation_vector, "r"),
        (lambda a: Q.from_axis_angle(a, 0.5), "axis"),
        (lambda a: euler.to_quaternion("ZYX", a), "angles"),
        (lambda a: Q.exp([0.0, *a]), "q"),
        (lambda a: rotor.from_rotation_vector(a), "r"),
    ):
        with pytest.raises(InputError, match=rf"^{name}: contains"):
            call(v)
    m = np.eye(3)
    m[k % 3, (k + 1) % 3] = bad
    with pytest.raises(InputError, match=r"^m: contains"):
        matrix.to_quaternion(m)


test_stability_values_agree_uncompiled = uncompiled_twin(__file__)
