"""Euler-angle, quaternion and rotor rates <-> body angular velocity, against finite differences."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from ga_rotors import _kernels, euler, kinematics
from ga_rotors.errors import InputError

angle = st.floats(-math.pi, math.pi)
nutation = st.floats(0.05, math.pi - 0.05)  # away from the poles, where the inverse exists
rate = st.floats(-20.0, 20.0)


def numeric_body_omega(angles, rates, dt=1e-6):
    """ω = 2 vec(q* q̇) with q̇ from a central difference of q(ψ, θ, φ): independent of eq. 15.

    Error (dt²/6)|q⃛| ≲ 1e-12 · (|rates| + 1)³ for these ranges.
    """
    a = np.asarray(angles, dtype=float)
    r = np.asarray(rates, dtype=float)
    qp = euler.to_quaternion("ZYZ", a + dt * r)
    qm = euler.to_quaternion("ZYZ", a - dt * r)
    q = euler.to_quaternion("ZYZ", a)
    if np.dot(qp, q) < 0:
        qp = -qp
    if np.dot(qm, q) < 0:
        qm = -qm
    return kinematics.body_omega_from_quaternion_rate(q, (qp - qm) / (2 * dt))


@given(angle, angle, angle, rate, rate, rate)
def test_body_omega_from_zyz_rates_matches_finite_differences(psi, theta, phi, dpsi, dth, dphi):
    w = kinematics.body_omega_from_zyz_rates([psi, theta, phi], [dpsi, dth, dphi])
    fd = numeric_body_omega([psi, theta, phi], [dpsi, dth, dphi])
    scale = abs(dpsi) + abs(dth) + abs(dphi) + 1.0
    assert np.allclose(w, fd, rtol=0, atol=1e-8 * scale)


@given(angle, nutation, angle, rate, rate, rate)
def test_zyz_rates_invert_body_omega(psi, theta, phi, dpsi, dth, dphi):
    angles = [psi, theta, phi]
    w = kinematics.body_omega_from_zyz_rates(angles, [dpsi, dth, dphi])
    back = kinematics.zyz_rates_from_body_omega(angles, w)
    # ψ̇ carries 1/sin θ ≤ 20 of amplification on a few ulps of |ω| ≤ 60
    assert np.allclose(back, [dpsi, dth, dphi], rtol=0, atol=1e-12 * 60 * 20)


@given(angle, nutation, angle, rate, rate, rate)
def test_compiled_kernels_equal_the_vectorised_forms(psi, theta, phi, w1, w2, w3):
    angles, w = (psi, theta, phi), (w1, w2, w3)
    rates = _kernels.zyz_rates(angles, w)
    assert np.allclose(rates, kinematics.zyz_rates_from_body_omega(angles, w), rtol=1e-14,
                       atol=1e-12)  # fmt: skip
    assert np.allclose(_kernels.zyz_omega(angles, rates), w, rtol=0, atol=1e-10)


def test_rates_are_undefined_exactly_at_the_pole():
    with pytest.raises(InputError, match=r"\|sin θ\| <= 1e-14 \(gimbal lock\) at index \(1,\)"):
        kinematics.zyz_rates_from_body_omega([[0.1, 0.5, 0.2], [0.1, 0.0, 0.2]], [0.0, 1.0, 2.0])
    # the forward map is regular there: only ψ̇ + φ̇ reaches ω₃
    w = kinematics.body_omega_from_zyz_rates([0.3, 0.0, 0.0], [1.0, 0.0, 2.0])
    assert w.tolist() == [0.0, 0.0, 3.0]


@pytest.mark.parametrize("theta", [math.pi, 1e-320, -1e-15, 2 * math.pi, math.pi - 1e-15], ids=str)
def test_rates_near_the_pole_are_refused_like_at_it(theta):
    # In float64 sin(π) = 1.2e-16, not 0: the rates came out ±8e15 (θ = π) or inf
    # (θ = 1e-320) with no error. Within GIMBAL_TOLERANCE they are refused like θ = 0.
    with pytest.raises(InputError, match=r"gimbal lock"):
        kinematics.zyz_rates_from_body_omega([0.0, theta, 0.0], [1.0, 0.0, 0.0])
    # just outside the tolerance the answer is finite and inverts the forward map
    theta = math.asin(2 * euler.GIMBAL_TOLERANCE)
    rates = kinematics.zyz_rates_from_body_omega([0.0, theta, 0.0], [1e-20, 0.0, 0.0])
    back = kinematics.body_omega_from_zyz_rates([0.0, theta, 0.0], rates)
    assert np.all(np.isfinite(rates)) and np.allclose(back, [1e-20, 0.0, 0.0], rtol=1e-6, atol=0)


def test_rates_that_overflow_are_refused():
    with pytest.raises(InputError, match="overflow"):
        kinematics.zyz_rates_from_body_omega([0.0, 1e-13, 0.0], [1e300, 0.0, 0.0])


@given(st.tuples(*(st.floats(-1, 1),) * 4).filter(lambda q: sum(c * c for c in q) > 0.1),
       st.tuples(rate, rate, rate))  # fmt: skip
def test_quaternion_rate_round_trip(q, w):
    q = np.array(q) / np.linalg.norm(q)
    qdot = kinematics.quaternion_rate(q, w)
    assert abs(np.dot(q, qdot)) < 1e-13 * (1 + np.abs(w).max())  # tangent to the sphere
    assert np.allclose(kinematics.body_omega_from_quaternion_rate(q, qdot), w, atol=1e-12 * 60)


def test_rotor_rate_agrees_with_the_quaternion_rate_through_the_isomorphism():
    from ga_rotors import isomorphism, rotor

    rng = np.random.default_rng(7)
    for _ in range(20):
        q = rng.normal(size=4)
        q /= np.linalg.norm(q)
        w = rng.normal(size=3)
        R = rotor.from_quaternion(q)
        Rdot = kinematics.rotor_rate(R, w)
        expected = isomorphism.to_even(kinematics.quaternion_rate(q, w))
        assert np.allclose(np.asarray(Rdot.value), expected, atol=1e-14)
        assert np.allclose(kinematics.body_omega_from_rotor_rate(R, Rdot), w, atol=1e-14)


def test_bad_inputs_name_themselves():
    with pytest.raises(InputError, match="angles and rates: shapes"):
        kinematics.body_omega_from_zyz_rates(np.zeros((2, 3)), np.zeros((3, 3)))
    with pytest.raises(InputError, match="q: expected unit quaternions"):
        kinematics.quaternion_rate([2.0, 0, 0, 0], [0, 0, 1.0])
    with pytest.raises(InputError, match="w: expected one angular velocity"):
        kinematics.rotor_rate(1.0, np.zeros((2, 3)))


@pytest.mark.parametrize("seq", euler.SEQUENCES)
def test_body_omega_from_any_euler_sequence_matches_finite_differences(seq):
    # Oracle: ω = 2 vec(q* q̇), q̇ from a central difference of scipy's rotation, which
    # defines every sequence independently of ga_rotors.euler. Error O(dt²) ≈ 1e-12.
    from scipy.spatial.transform import Rotation

    angles, rates, dt = np.array([0.4, -0.7, 1.2]), np.array([0.5, 0.25, -2.0]), 1e-6

    def quat(a):
        return np.roll(Rotation.from_euler(seq, a).as_quat(), 1)  # scipy: scalar last

    qdot = (quat(angles + dt * rates) - quat(angles - dt * rates)) / (2 * dt)
    oracle = kinematics.body_omega_from_quaternion_rate(quat(angles), qdot)
    got = kinematics.body_omega_from_euler_rates(seq, angles, rates)
    assert np.allclose(got, oracle, rtol=0, atol=1e-8)


def test_body_omega_from_euler_rates_is_the_papers_formula_for_zyz():
    rng = np.random.default_rng(5)
    a, r = rng.normal(size=(50, 3)), rng.normal(size=(50, 3))
    general = kinematics.body_omega_from_euler_rates("ZYZ", a, r)
    assert np.allclose(general, kinematics.body_omega_from_zyz_rates(a, r), rtol=0, atol=1e-14)
