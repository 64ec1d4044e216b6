"""The gyroscope: three paths for one motion, the exact symmetric top, RK4's error model.

Error model used throughout (derived in docs/gyroscope.md): for a rotation at constant rate
|ω|, one RK4 step multiplies q by the degree-4 Taylor polynomial of exp(h ω̂/2), whose
eigenvalues are e^{±iy}, y = h|ω|/2. The remainder (iy)⁵/5! is a pure phase: each step
lags by y⁵/120 in the half-angle, 2y⁵/120 in the rotation angle. Over T/h steps the
geodesic error is T h⁴ |ω|⁵ / 1920 (global ∝ h⁴ T from a local C h⁵).
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from ga_rotors import euler, shapes, simulate
from ga_rotors.crosscheck import cross_check
from ga_rotors.errors import GimbalLockWarning, InputError, IntegrationStoppedWarning
from ga_rotors.kinematics import body_omega_from_zyz_rates
from ga_rotors.paper import models as paper_models
from ga_rotors.paper.runs import run_all
from ga_rotors.reference.symmetric_top import SymmetricTop

# The paper's four runs, made once for the module by the first test that needs them (at
# import they compiled three loops while the whole suite was being collected).
KEYS = [f"{model}_{theta:g}deg" for model in paper_models.MODELS
        for theta in paper_models.THETA0_DEG]  # fmt: skip


@pytest.fixture(scope="module")
def by_key():
    runs = {s.key: s for s in run_all()}
    assert sorted(runs) == sorted(KEYS)
    return runs


def rk4_rotation_error(w_norm: float, h: float, t: float) -> float:
    """Leading-order RK4 geodesic error for rotation at rate |ω|: T h⁴ |ω|⁵ / 1920."""
    return t * h**4 * w_norm**5 / 1920.0


@pytest.mark.parametrize("key", sorted(KEYS))
def test_rotor_and_quaternion_paths_agree_to_roundoff(key, by_key):
    # Same ODE in isomorphic algebras, same arithmetic up to term order: they differ by
    # accumulated rounding, ~1e-16 per step over 1e4 steps in the worst case.
    s = by_key[key]
    assert s.rotor_vs_quaternion <= 1e-12
    assert s.rotor_vs_quaternion <= 1e4 * np.finfo(float).eps


@pytest.mark.parametrize("key", sorted(KEYS))
def test_rotor_path_error_is_rk4s_rotation_error(key, by_key):
    # Both bodies spin at |ω| ≈ 15.72 rad/s about an axis ω is nearly parallel to; the
    # transverse part (0.02 rad/s) changes the error by O(|ω⊥|/|ω|) ~ 1e-3 relative, and the
    # truncation of the series by O(y²) ~ 6e-5: 2% covers both with margin.
    s = by_key[key]
    tr = s.trajectory
    predicted = rk4_rotation_error(np.linalg.norm(tr.w[0]), tr.meta["step"], tr.t[-1])
    for name in ("R", "q"):
        assert 0.98 <= s.max_error[name] / predicted <= 1.02, (name, s.max_error[name], predicted)


def test_omega_along_the_papers_x3_axis_stays_exactly_constant(by_key):
    # I_y3 = I_z3 exactly, so ω̇_x3 = (I_y3 - I_z3) ω_y3 ω_z3 / I_x3 is exactly 0.0 every stage.
    for theta in paper_models.THETA0_DEG:
        w = by_key[f"paper_{theta:g}deg"].trajectory.w
        assert np.all(w[:, 0] == w[0, 0])
    # while (ω_y3, ω_z3) turn at rate ω_x3 = -0.0052 rad/s: ω_z3 drops by ~0.021 in 10 s
    w = by_key["paper_15deg"].trajectory.w
    assert np.ptp(w[:, 2]) > 1e-2


def test_disk_spin_along_its_symmetry_axis_stays_exactly_constant(by_key):
    for theta in paper_models.THETA0_DEG:
        w = by_key[f"disk_{theta:g}deg"].trajectory.w
        assert np.all(w[:, 2] == w[0, 2])


def test_euler_angle_path_is_fine_away_from_the_pole(by_key):
    for model in paper_models.MODELS:
        s = by_key[f"{model}_15deg"]
        assert s.watch["unresolved_steps"] == 0 and s.watch["pole_crossings"] == 0
        assert s.watch["complete"] and s.watch["first_unresolved"] is None
        # the angle rates are slow here: this path is even more accurate than RK4 on q
        assert s.max_error["euler"] < s.max_error["R"]


def test_euler_angle_path_trouble_near_theta_zero_is_detected_and_reported(by_key):
    for model in paper_models.MODELS:
        s = by_key[f"{model}_0.001deg"]
        w = s.watch
        assert w["complete"]  # it never produced a non-finite state
        assert w["unresolved_steps"] > 10 and w["pole_crossings"] >= 1
        assert 0.0 < w["first_unresolved"] < 1.0
        assert w["min_abs_sin_theta"] < 1e-5 and w["max_turn"] > 1.0
        tr = s.trajectory
        for name in tr.names:
            assert np.isfinite(tr[name]).all(), name
        # the rotation it carries is wrong by orders of magnitude more than RK4's error
        assert s.max_error["euler"] > 1e3 * s.max_error["R"]


def test_psi_plus_phi_is_well_defined_through_the_near_pole_passes(by_key):
    # ψ and φ swing by ~π each as θ passes near 0; their sum does not. From the rotor path:
    # the largest jump of ψ + φ between samples is the spin ω·h (~0.016 rad), while ψ alone
    # jumps by about π.
    for model in paper_models.MODELS:
        a = by_key[f"{model}_0.001deg"].trajectory.angles
        psi_jump = np.abs(np.diff(a[:, 0])).max()
        sum_jump = np.abs(np.diff(np.unwrap(a[:, 0] + a[:, 2]))).max()
        assert psi_jump > 1.0 and sum_jump < 0.02


def test_euler_path_started_exactly_at_the_pole_stops_without_nan():
    angles = np.zeros(3)
    w0 = body_omega_from_zyz_rates(angles, paper_models.RATES)
    with pytest.warns(IntegrationStoppedWarning, match="euler path of rk4 stopped at t = 0 s"):
        tr = simulate(shapes.disk(2.0, 0.075), [1.0, 0, 0, 0], w0, duration=1.0, step=1e-3,
                      paths=("rotor", "euler"), euler_angles=angles)  # fmt: skip
    status = tr.meta["paths"]["euler"]
    assert not status["complete"] and status["samples"] == 1 and status["ended_at"] == 0.0
    assert status["watch"]["first_unresolved"] == 0.0
    assert tr.euler.shape == (1, 3) and np.isfinite(tr.euler).all()
    assert tr["rotor_blades"].shape == (1001, 4) and tr.meta["paths"]["rotor"]["complete"]
    text = tr.to_csv()
    assert "nan" not in text.lower()


def test_exact_pole_without_explicit_angles_warns_of_gimbal_lock():
    with pytest.raises(GimbalLockWarning):
        simulate((1.0, 1.0, 2.0), [1.0, 0, 0, 0], [0.0, 0.0, 1.0], duration=0.1, step=0.01,
                 paths=("euler",))  # fmt: skip


def test_closed_form_symmetric_top_satisfies_the_equations_of_motion():
    # Independent check of the closed form: central differences of q(t) give
    # ω = 2 vec(q* q̇) (error (Δt)² |ω|³/24 ~ 1e-10 for Δt = 1e-5), which must equal the
    # closed form's own ω(t); and that ω must satisfy Euler's equations (central
    # difference of ω against I⁻¹((Iω)×ω)).
    from ga_rotors._kernels import euler_rates
    from ga_rotors.kinematics import body_omega_from_quaternion_rate

    moments = (0.3, 0.7, 0.7)  # symmetry axis x, like the paper's model
    top = SymmetricTop(moments, euler.to_quaternion("ZYZ", [0.4, 1.1, -0.3]), [2.0, -1.5, 0.8])
    dt = 1e-5
    for t in (0.0, 0.37, 2.5, 9.9):
        q, w = top.at([t - dt, t, t + dt])
        qdot = (q[2] - q[0]) / (2 * dt)
        w_fd = body_omega_from_quaternion_rate(q[1], qdot)
        assert np.allclose(w_fd, w[1], rtol=0, atol=1e-8)
        dw = (w[2] - w[0]) / (2 * dt)
        assert np.allclose(dw, euler_rates(moments, tuple(w[1]), (0.0, 0.0, 0.0)), atol=1e-7)
    assert top.axis == 0


def test_closed_form_matches_a_fine_independent_integration():
    # scipy's DOP853 at rtol 1e-13 on (q, ω) with the plain-numpy right-hand side.
    from scipy.integrate import solve_ivp

    moments = np.array(shapes.disk(2.0, 0.075))
    q0 = euler.to_quaternion("ZYZ", [0.0, math.radians(15.0), 0.0])
    w0 = body_omega_from_zyz_rates([0.0, math.radians(15.0), 0.0], paper_models.RATES)

    def rhs(t, y):
        q0_, q1, q2, q3, w1, w2, w3 = y
        return [
            0.5 * (-q1 * w1 - q2 * w2 - q3 * w3),
            0.5 * (q0_ * w1 + q2 * w3 - q3 * w2),
            0.5 * (q0_ * w2 - q1 * w3 + q3 * w1),
            0.5 * (q0_ * w3 + q1 * w2 - q2 * w1),
            (moments[1] - moments[2]) * w2 * w3 / moments[0],
            (moments[2] - moments[0]) * w3 * w1 / moments[1],
            (moments[0] - moments[1]) * w1 * w2 / moments[2],
        ]

    t = np.linspace(0.0, 2.0, 5)
    sol = solve_ivp(rhs, (0, 2.0), [*q0, *w0], method="DOP853", rtol=1e-13, atol=1e-14,
                    t_eval=t)  # fmt: skip
    top = SymmetricTop(moments, q0, w0)
    err = top.orientation_error(t, sol.y[:4].T / np.linalg.norm(sol.y[:4], axis=0)[:, None])
    assert err.max() < 1e-10  # DOP853's own error at this tolerance over 2 s (~31 rad turned)


def test_symmetric_top_refuses_asymmetric_bodies():
    with pytest.raises(InputError, match="no two exactly equal"):
        SymmetricTop((1.0, 2.0, 3.0), [1.0, 0, 0, 0], [0.0, 0.0, 1.0])


def test_cross_check_needs_two_paths():
    tr = simulate((1.0, 2.0, 3.0), [1.0, 0, 0, 0], [0.0, 0.0, 1.0], duration=0.1, step=0.01)
    with pytest.raises(InputError, match="needs two paths"):
        cross_check(tr)
    with pytest.raises(InputError, match="no 'quaternion' path"):
        tr.quaternions("quaternion")


# ------------------------------------------------------------ invariants vs the error model

ASYMMETRIC = (1.0, 2.0, 3.0)
W0 = (1.0, 0.5, 2.0)


def _drifts(h: float, duration: float) -> np.ndarray:
    tr = simulate(ASYMMETRIC, [1.0, 0, 0, 0], W0, duration=duration, step=h,
                  outputs=("energy", "L", "L_space"))  # fmt: skip
    lnorm = np.linalg.norm(tr.L, axis=1)
    return np.array(
        [
            np.abs(tr.energy / tr.energy[0] - 1.0).max(),
            np.abs(lnorm / lnorm[0] - 1.0).max(),
            np.linalg.norm(tr.L_space - tr.L_space[0], axis=1).max() / lnorm[0],
        ]
    )


def test_invariant_drift_stays_within_rk4s_h4_t_model():
    # Global error of a 4th-order method: |drift| ≲ C' h⁴ T. C' is measured once, at
    # h = 0.02 over T = 10 (asymmetric top, so energy and |L| are not conserved by
    # symmetry); the model must then bound every finer step and longer span.
    h0, t0 = 0.02, 10.0
    c = _drifts(h0, t0) / (h0**4 * t0)
    for h, t in ((0.01, 10.0), (0.005, 10.0), (0.01, 20.0), (0.005, 20.0)):
        d = _drifts(h, t)
        assert np.all(d <= c * h**4 * t), (h, t, d, c * h**4 * t)
    orders = np.log2(_drifts(0.01, 10.0) / _drifts(0.005, 10.0))
    assert np.all(orders > 3.9), orders


def test_invariants_of_the_paper_scenes(by_key):
    # Symmetric bodies: RK4 rotates (ω1, ω2) with a per-step amplitude error (νh)⁶/144, far
    # below round-off here, so energy and |L| hold to rounding (~1e4 steps × eps); the
    # space-frame L inherits the orientation error, bounded by |L| × the geodesic error.
    eps = np.finfo(float).eps
    for s in by_key.values():
        tr = s.trajectory
        body = s.model.moments
        e = 0.5 * np.einsum("ni,i,ni->n", tr.w, np.array(body), tr.w)
        assert np.abs(e / e[0] - 1).max() < 1e4 * eps
        lb = tr.w * np.array(body)
        q = tr.quaternions("rotor")
        from ga_rotors.quaternion import rotate

        ls = rotate(q, lb)
        drift = np.linalg.norm(ls - ls[0], axis=1) / np.linalg.norm(lb[0])
        assert drift.max() <= s.max_error["R"] + 1e4 * eps


def test_non_unit_orientation_norm_drift_matches_rk4_amplitude_error(by_key):
    # |R| after T/h steps: RK4's amplification |P4(iy)|² = 1 - y⁶/72 + O(y⁸) per step,
    # so | |R| - 1 | ≈ (T/h) y⁶/144 with y = h|ω|/2: 1.6e-11 for the paper's run.
    for s in by_key.values():
        tr = s.trajectory
        y = tr.meta["step"] * np.linalg.norm(tr.w[0]) / 2
        predicted = tr.t[-1] / tr.meta["step"] * y**6 / 144
        assert 0.95 <= s.norm_drift / predicted <= 1.05, (s.key, s.norm_drift, predicted)


def test_gimbal_warning_is_not_raised_for_the_papers_near_pole_samples(by_key):
    # θ comes within ~1e-7 rad of 0, still far above the gimbal tolerance (1e-14 rad).
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        euler.from_quaternion(by_key["disk_0.001deg"].trajectory.quaternions("rotor"), "ZYZ")
