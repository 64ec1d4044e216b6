"""Extreme bodies stay numerically stable: nearly spherical, spherical, flat, rod-like (issue 7).

One named test per case, each asserting an exact solution or a bound derived next to it.
Notation as in tests/test_stability_dynamics.py: u = 2⁻⁵³, N steps of size h, walk(k, N)
the 6σ round-off random walk of k roundings per step.
"""

from __future__ import annotations

import cmath
import math

import numpy as np
import pytest

from ga_rotors import quaternion as Q
from ga_rotors import shapes
from ga_rotors.body import MIN_MOMENT_RATIO, RigidBody
from ga_rotors.errors import InputError, PrecisionError, StepLimitWarning
from ga_rotors.integrators import Problem, get
from ga_rotors.reference.asymmetric_top import AsymmetricTop
from ga_rotors.reference.symmetric_top import SymmetricTop

U = 2.0**-53
Q0 = np.array([0.3, 0.1, 0.9, 0.2]) / math.sqrt(0.95)
W0 = (1.0, 0.5, 0.2)


def walk(k: int, n: int) -> float:
    return 6.0 * U * math.sqrt(k * n / 3.0)


def rk4_phase_lag(y: float) -> float:
    """arg R(iy) − y for RK4's R(z) = 1 + z + z²/2 + z³/6 + z⁴/24 (exactly, not a series)."""
    z = 1j * y
    return cmath.phase(1 + z + z**2 / 2 + z**3 / 6 + z**4 / 24) - y


# The turn per step of a rotation at constant rate |ω| (angle y = h|ω| per step, half-angle
# y/2 in q), by method: q̇ = ½ q ⊗ (0, ω) is linear with constant coefficients, so an RK
# method multiplies q by R(h A), A² = −|ω|²/4: a turn of 2·arg R(iy/2); the implicit
# midpoint's R is the Cayley map, 2·2·atan(y/4); the discrete Moser–Veselov step for
# I = 1 reads sin θ = y (its equation, variational.py), θ = asin y; the Lie-group methods
# (rkmk4, cf4) and split_sym move q by exact exponentials: y.
TURN = {
    "rk4": lambda y: y + 2 * rk4_phase_lag(y / 2),
    "rk4_renorm": lambda y: y + 2 * rk4_phase_lag(y / 2),
    "midpoint": lambda y: 4 * math.atan(y / 4),
    "lgvi": math.asin,
    "rkmk4": lambda y: y,
    "cf4": lambda y: y,
    "split_sym": lambda y: y,
}
SPHERE_H, SPHERE_N = 0.05, 200  # y = h|ω| = 0.057: RK4's lag 5.8e-8 rad, far above rounding


def _turn_error(body, name):
    run = get(name).run(Problem(body), "quaternion", Q0, W0, 0.0, SPHERE_H, SPHERE_N, 1)
    assert run.complete
    y = SPHERE_H * math.sqrt(sum(w * w for w in W0))
    predicted = SPHERE_N * abs(TURN[name](y) - y)
    return run, predicted


# --- inertia the body accepts, and the limit --------------------------------------------


@pytest.mark.parametrize(
    "moments", [(1.0, 1.0, 1e-310), (1.0, 1.0, 5e-324), (1e308, 1e308, 1e308), (1e-308,) * 3]
)
def test_rod_limit_moment_whose_inverse_is_not_a_normal_float_is_rejected(moments):
    # 1e-310 is subnormal: 1/I = inf, and every loop divides by I (ω = L/I, τ/I). It used
    # to be accepted, and the first step returned inf with no error.
    with pytest.raises(InputError, match=r"^moments: .*normal floats"):
        RigidBody(moments)
    with pytest.raises(InputError, match=r"^moments: "):
        RigidBody(shapes.rod(1.0, 1.0, 1e-160))  # I₃ = 5e-321


def test_rod_limit_thinner_than_min_moment_ratio_is_rejected():
    RigidBody((1.0, 1.0, MIN_MOMENT_RATIO))  # the limit itself is a body
    with pytest.raises(InputError, match=r"^moments: smallest/largest principal moment"):
        RigidBody((1.0, 1.0, 0.99 * MIN_MOMENT_RATIO))
    # Why: the triangle check's slack 1e-12·ΣI exceeds a thinner axis, and let through a
    # body with the Euler coefficient (I₁ − I₂)/I₃ = −2e8 (a real body's is ≤ 1).
    with pytest.raises(InputError, match=r"^moments: smallest/largest"):
        RigidBody((1.0, 1.0 + 2e-12, 1e-20))


# --- nearly spherical: (1, 1 + 1e-6, 1 + 2e-6) --------------------------------------------

NEAR_SPHERE = (1.0, 1.0 + 1e-6, 1.0 + 2e-6)


def test_nearly_spherical_reference_is_accurate_or_raises():
    import mp_oracle

    top = AsymmetricTop(NEAR_SPHERE, Q0, W0)
    # ω turns in the body at λ = 1.5e-6 rad/s: one flip period is 2.2e6 s (25 days).
    assert top.rate < 2e-6 and top.flip_period > 2e6
    times = [1.0, 10.0, 100.0]
    state = top.state(times, max_error=1e-12)
    oracle = mp_oracle.integrate(NEAR_SPHERE, Q0, W0, times)
    for y, q, bound in zip(oracle, state.q, state.error, strict=True):
        assert Q.distance(np.array([float(v) for v in y[:4]]), q) <= bound
    # Its rounding bound grows with t (4.6e-15 rad/s): past max_error it says so.
    with pytest.raises(PrecisionError):
        top.state([1e6])


@pytest.mark.parametrize("name", sorted(TURN))
def test_nearly_spherical_methods_turn_as_on_a_sphere(name):
    run, predicted = _turn_error(NEAR_SPHERE, name)
    exact = AsymmetricTop(NEAR_SPHERE, Q0, W0).state(run.t).q
    error = Q.distance(exact, Q.normalize(run.x)).max()
    # The sphere's turn-per-step error (TURN) plus: ω and its axis move by at most
    # 2δ|ω|T ≈ 2.5e-5 relative over the run (δ = 2e-6, |ω|T = 11): 1e-4 relative covers
    # it; rounding of q: walk(40, N) rad, and the reference's own bound (< 1e-13).
    assert abs(error - predicted) <= 1e-4 * predicted + walk(40, SPHERE_N) + 1e-13


@pytest.mark.parametrize("name", ["split2", "split4", "split6"])
def test_nearly_spherical_splitting_keeps_momentum_and_energy(name):
    run = get(name).run(Problem(NEAR_SPHERE), "quaternion", Q0, W0, 0.0, SPHERE_H, SPHERE_N, 1)
    inertia = np.array(NEAR_SPHERE)
    L = run.w * inertia
    lnorm = np.linalg.norm(L, axis=1)
    assert np.abs(lnorm / lnorm[0] - 1).max() <= walk(142, SPHERE_N)
    # At fixed |L| the energy Σ L_k²/(2I_k) can only move within [|L|²/(2I₃), |L|²/(2I₁)]:
    # |ΔE|/E ≤ (I₃ − I₁)/I₁ = 2e-6, whatever the method does to L's direction.
    e = 0.5 * (run.w**2 * inertia).sum(1)
    assert np.abs(e / e[0] - 1).max() <= (NEAR_SPHERE[2] - NEAR_SPHERE[0]) + walk(142, SPHERE_N)


# --- exactly spherical --------------------------------------------------------------------


@pytest.mark.parametrize("name", sorted(TURN))
def test_spherical_body_every_method_turns_by_its_stability_function(name):
    # A sphere: ω is exactly constant ((I_j − I_k) = 0), the motion q₀ ⊗ Exp(tω), and each
    # method's error is its turn per step (TURN) times N, to rounding only.
    sphere = (1.0, 1.0, 1.0)
    run, predicted = _turn_error(sphere, name)
    assert np.all(run.w == np.array(W0))
    exact, _ = SymmetricTop(sphere, Q0, W0).at(run.t)
    error = Q.distance(exact, Q.normalize(run.x)).max()
    assert abs(error - predicted) <= walk(40, SPHERE_N) + 1e-9 * predicted


# --- flat: I₃ = I₁ + I₂ -------------------------------------------------------------------

PLATE = shapes.box(3.0, 0.7, 1.3, 1e-300)  # a plate of zero thickness: I₃ = I₁ + I₂ exactly
PLATE_W = (0.4, 1.0, 0.7)


def test_flat_plate_reference_keeps_the_in_plane_rate():
    # On the triangle limit Euler's equations read ω̇₁ = −ω₂ω₃, ω̇₂ = ω₃ω₁, so ω₁² + ω₂²
    # is constant (it is (2E I₃ − L²)/(I₁I₂)). The exact reference keeps it to rounding:
    # sn² + cn² = 1 and dn² = 1 − m sn² to a few ulps.
    assert PLATE[0] + PLATE[1] == PLATE[2]
    s = AsymmetricTop(PLATE, Q0, PLATE_W).state(np.linspace(0.0, 20.0, 201))
    wp = s.w[:, 0] ** 2 + s.w[:, 1] ** 2
    assert np.abs(wp / wp[0] - 1).max() <= 16 * U


@pytest.mark.parametrize("name", ["rk4", "split4"])
def test_flat_plate_motion_converges_to_the_exact_solution_at_order_4(name):
    # Error model of an order-4 method: e(h) = C h⁴ + O(h⁵), so e(2h)/e(h) = 16 + O(hλ),
    # λ ≈ |ω| = 1.3 rad/s: at h = 0.01 the correction is a few % (measured 16.4 and 16.0).
    top = AsymmetricTop(PLATE, Q0, PLATE_W)
    errors = []
    for h in (0.02, 0.01):
        n = round(20.0 / h)
        run = get(name).run(Problem(PLATE), "quaternion", Q0, PLATE_W, 0.0, h, n, n)
        errors.append(Q.distance(top.state(run.t).q, Q.normalize(run.x))[-1])
    assert abs(errors[0] / errors[1] / 16.0 - 1.0) <= 0.05, errors


# --- rod-like: (1, 1, 1e-6), (1, 1, 1e-12) ------------------------------------------------

ROD_W = (1.0, 0.5, 0.3)


@pytest.mark.parametrize("thin", [1e-6, 1e-12])
def test_rod_like_rk4_keeps_the_spin_and_damps_exactly_as_its_stability_function(thin):
    # Symmetric rod: ω₃ is exactly constant ((I₁ − I₂) = 0 in every stage) and ω⊥ turns at
    # ν = (1 − I₃/I⊥) ω₃ by a linear equation, so |ω⊥|² is multiplied by |R(ihν)|² per step
    # (as on the fast-spinning disk of test_stability_dynamics).
    rod, h, n = (1.0, 1.0, thin), 0.01, 1000
    run = get("rk4").run(Problem(rod), "quaternion", Q0, ROD_W, 0.0, h, n, 1)
    assert np.all(run.w[:, 2] == ROD_W[2])
    # |R(iy)|² = 1 − y⁶/72 + y⁸/576, y = hν = 0.003: 1 − 1e-17, taken through log1p (ρ
    # rounded to a float would carry 1e-16 per step of its own rounding).
    y = h * (1.0 - thin) * ROD_W[2]
    decay = np.exp(np.arange(n + 1) * math.log1p(-(y**6) / 72 + y**8 / 576))
    wp = run.w[:, 0] ** 2 + run.w[:, 1] ** 2
    assert np.allclose(wp, wp[0] * decay, rtol=walk(100, n), atol=0)


@pytest.mark.parametrize("thin", [1e-6, 1e-12])
def test_rod_like_split_sym_is_exact(thin):
    # split_sym's symmetric top is the rod itself (remainder coefficient 1/I₂ − 1/I₁ = 0):
    # the exact flow, to rounding of the turned angle (|ω|T = 11.6 rad over 10 s).
    rod, h, n = (1.0, 1.0, thin), 0.01, 1000
    run = get("split_sym").run(Problem(rod), "quaternion", Q0, ROD_W, 0.0, h, n, 10)
    exact, _ = SymmetricTop(rod, Q0, ROD_W).at(run.t)
    assert Q.distance(exact, Q.normalize(run.x)).max() <= walk(24, n) * 12.0
    assert np.allclose(run.w[:, 2], ROD_W[2], rtol=walk(24, n), atol=0)


@pytest.mark.parametrize("thin", [1e-6, 1e-12])
def test_rod_like_axis_splitting_loses_the_thin_axis(thin):
    # split2 splits H into L_k²/(2I_k): its error constant grows with the fastest of those
    # flows, |L|/I₃ = 1.1/thin rad/s, so h|L|/I₃ = 1.1e4 (and 1.1e10) is far past any step
    # a Strang splitting resolves. |L| and the space-frame L still hold to rounding (they
    # hold by construction), but the rate about the thin axis, L₃/I₃, is lost: the
    # truncation error in L₃, O(h²|L|²) absolute, is divided by I₃. Documented: on
    # rod-like bodies use split_sym, RK or lgvi-free methods, not the axis splittings.
    rod, h, n = (1.0, 1.0, thin), 0.01, 1000
    with pytest.warns(StepLimitWarning, match=r"split2.*h·\|L\|/I_min"):  # and says so
        run = get("split2").run(Problem(rod), "quaternion", Q0, ROD_W, 0.0, h, n, 1)
    L = run.w * np.array(rod)
    lnorm = np.linalg.norm(L, axis=1)
    assert np.abs(lnorm / lnorm[0] - 1).max() <= walk(22, n)
    assert np.abs(run.w[:, 2] - ROD_W[2]).max() > 1.0  # wrong by more than its size
