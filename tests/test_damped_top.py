"""The damped symmetric top's exact solution against an adaptive integration and limits."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from ga_rotors import quaternion as Q
from ga_rotors.errors import InputError
from ga_rotors.reference.damped_top import DampedSymmetricTop
from ga_rotors.reference.symmetric_top import SymmetricTop


def euler_damped(moments, c):
    inertia = np.asarray(moments)

    def rhs(t, y):
        q, w = y[:4], y[4:]
        wdot = (np.cross(inertia * w, w) - c * w) / inertia
        qdot = 0.5 * Q.multiply(q, np.r_[0.0, w])
        return np.r_[qdot, wdot]

    return rhs


@pytest.mark.parametrize(
    "moments", [(1.0, 1.0, 1.8), (2.0, 1.2, 1.2), (1.5, 0.9, 1.5), (1.3, 1.3, 1.3)]
)
def test_body_rates_match_an_adaptive_integration(moments):
    c, w0 = 0.3, np.array([0.4, -0.7, 5.0])
    top = DampedSymmetricTop(moments, c, [1.0, 0.0, 0.0, 0.0], w0)
    t = np.linspace(0.0, 6.0, 13)
    sol = solve_ivp(euler_damped(moments, c), (0, 6), np.r_[1.0, 0, 0, 0, w0],
                    method="DOP853", rtol=1e-13, atol=1e-14, t_eval=t)  # fmt: skip
    # DOP853 at rtol 1e-13 over a few hundred steps: ~1e-12 at worst on |ω| ≈ 5.
    assert np.abs(sol.y[4:].T - top.angular_velocity(t)).max() < 5e-12
    if top.spherical:
        ref, _ = top.at(t)
        assert Q.distance(ref, Q.normalize(sol.y[:4].T)).max() < 5e-12


def test_without_damping_it_is_the_free_symmetric_top():
    moments, q0, w0 = (1.0, 1.0, 1.8), Q.normalize([0.9, 0.1, -0.3, 0.2]), [0.4, -0.7, 5.0]
    t = np.linspace(0.0, 10.0, 11)
    free = SymmetricTop(moments, q0, w0).at(t)[1]
    assert np.allclose(DampedSymmetricTop(moments, 0.0, q0, w0).angular_velocity(t), free,
                       rtol=0, atol=1e-13)  # fmt: skip


def test_momentum_of_a_sphere_decays_as_one_exponential():
    top = DampedSymmetricTop((2.0, 2.0, 2.0), 0.5, [1.0, 0, 0, 0], [1.0, 2.0, 2.0])
    t = np.array([0.0, 1.0, 7.0])
    assert np.allclose(top.momentum_norm(t), 2.0 * 3.0 * np.exp(-0.25 * t), rtol=1e-15)


def test_phase_turns_by_a_finite_total_angle():
    # Φ(∞) = (I⊥ − I₃) ω₃(0) I₃ / (I⊥ c): the transverse rate's phase stops turning.
    moments, c = (1.0, 1.0, 1.8), 0.2
    top = DampedSymmetricTop(moments, c, [1, 0, 0, 0], [1.0, 0.0, 5.0])
    w = top.angular_velocity([500.0])[0]
    phase = np.arctan2(-w[1], w[0])  # z = e^(−iΦ) |z|
    total = (1.0 - 1.8) * 5.0 * 1.8 / (1.0 * c)
    assert np.isclose(np.mod(phase - total + np.pi, 2 * np.pi) - np.pi, 0.0, atol=1e-9)


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (((1.0, 2.0, 2.5), 0.1), "no two exactly equal"),
        (((1.0, 1.0, 1.5), -0.1), "damping coefficient ≥ 0"),
    ],
)
def test_bad_arguments(args, message):
    with pytest.raises(InputError, match=message):
        DampedSymmetricTop(*args, [1, 0, 0, 0], [0, 0, 1])


def test_orientation_needs_a_sphere():
    top = DampedSymmetricTop((1.0, 1.0, 1.5), 0.1, [1, 0, 0, 0], [0, 0, 1])
    with pytest.raises(InputError, match="only for a sphere"):
        top.at([1.0])
