"""Every bundled scene runs in full and meets its exact solution within derived bounds.

Error models used below (h the step, T the duration, |ω| the rotation rate):

* RK4 on the orientation of a body turning at |ω|: the quaternion turns at half the
  angle, and RK4's stability function misses exp(z) by z⁵/120 per step, so the phase
  error is (|ω|h/2)⁵/120 per step, the geodesic angle twice that, and after T/h steps
  T|ω|(|ω|h)⁴/1920. Torque-free symmetric tops sit on this leading term (the paper's
  scene: 5.0e-9 rad predicted, 5.0e-9 measured); the bounds allow a factor 2 for the
  next-order terms and the variation of ω.
* Rotor versus quaternion path: the same arithmetic in a different order, so they differ
  by rounding only: at most ~10 roundings of ε = 2.2e-16 per step, accumulated linearly
  (a worst case; a random walk would give √N).
"""

from __future__ import annotations

import math
from functools import cache
from pathlib import Path

import numpy as np
import pytest

from ga_rotors.paper import _generate_scenes as gen
from ga_rotors.paper import figures as paper_figures
from ga_rotors.paper import models as paper_models
from ga_rotors.scene import bundled, load_scene, report, run_scene
from ga_rotors.scene.figures import DIGEST_PREFIX, data_digest

EPS = np.finfo(float).eps
FIGURES = Path(__file__).resolve().parents[1] / "docs" / "figures" / "scenes"


@cache
def run(name: str):
    scene = load_scene(name)
    tr = run_scene(scene)
    return scene, tr, report(scene, tr)


def rk4_orientation_bound(scene, tr) -> float:
    """2 × T |ω| (|ω| h)⁴ / 1920 with the largest |ω| of the run."""
    w = float(np.linalg.norm(tr.w, axis=1).max())
    T, h = scene.data["time"]["duration"], scene.step
    return 2.0 * T * w * (w * h) ** 4 / 1920.0


def test_paper_scenes_are_generated_from_the_papers_constants():
    for name, text in gen.generate().items():
        committed = (gen.TARGET / name).read_text(encoding="utf-8")
        assert committed == text, "run: python -m ga_rotors.paper._generate_scenes"
    s = load_scene("paper_0.001deg")
    assert s.body.moments == paper_models.MODELS["paper"].moments
    assert s.steps == paper_models.STEPS and s.step == paper_models.STEP
    assert np.allclose(s.euler_angles, np.radians([0.0, paper_models.THETA0_DEG[1], 0.0]),
                       rtol=0, atol=0)  # fmt: skip
    assert load_scene("spinning_disk").body.moments == paper_models.MODELS["disk"].moments


def test_paper_scene_starts_where_the_paper_command_starts():
    from ga_rotors.kinematics import body_omega_from_zyz_rates

    s = load_scene("paper_15deg")
    w = body_omega_from_zyz_rates([0.0, math.radians(15.0), 0.0], paper_models.RATES)
    assert np.allclose(s.angular_velocity, w, rtol=0, atol=4 * EPS * 15.7)


@pytest.mark.parametrize("name", sorted(bundled()))
def test_every_bundled_scene_runs_and_its_paths_agree(name):
    scene, tr, rep = run(name)
    assert all(info["complete"] for info in tr.meta["paths"].values())
    if {"rotor", "quaternion"} <= set(scene.paths):
        assert rep.values["rotor_vs_quaternion"] <= 10 * EPS * scene.steps
    for path in ("rotor", "quaternion"):
        if path in scene.paths:
            # Unit norm drifts by RK4's amplitude error only: (|ω|h)⁶/576 per step
            # (|R(iy)|² = 1 − y⁶/72 + …, half-angle y = |ω|h/2), plus rounding.
            w = float(np.linalg.norm(tr.w, axis=1).max())
            bound = scene.steps * ((w * scene.step) ** 6 / 576 + 10 * EPS)
            assert rep.values[f"norm_drift_{path}"] <= bound


@pytest.mark.parametrize("name", ["paper_15deg", "paper_0.001deg", "spinning_disk",
                                  "fast_spinner"])  # fmt: skip
def test_torque_free_symmetric_tops_meet_the_rk4_error_model(name):
    scene, tr, rep = run(name)
    assert scene.exact == "symmetric_top"
    bound = rk4_orientation_bound(scene, tr)
    for path in ("rotor", "quaternion"):
        assert 0.1 * bound < rep.values[f"error_{path}"] <= bound  # the model, not luck
    for key in ("drift_energy", "drift_momentum_norm", "drift_space_momentum"):
        assert rep.values[key] <= bound  # ω's error is of the orientation's order


def test_the_euler_path_is_fine_at_15_degrees_and_reports_trouble_near_zero():
    scene, tr, rep = run("paper_15deg")
    assert rep.values["error_euler"] <= rk4_orientation_bound(scene, tr)
    assert tr.meta["paths"]["euler"]["watch"]["unresolved_steps"] == 0
    _, tr, _ = run("paper_0.001deg")
    assert tr.meta["paths"]["euler"]["watch"]["unresolved_steps"] > 0


def test_heavy_top_matches_the_lagrange_solution():
    scene, tr, rep = run("heavy_top")
    exact = scene.exact_solution
    nut = exact.model.nutation()
    e_orient = max(rep.values["error_rotor"], rep.values["error_quaternion"])
    # The angle between two orientations bounds the angle between their symmetry axes,
    # hence |Δθ|; the Hermite interpolant adds Δ⁴ max|u⁽⁴⁾|/384 in u = cos θ (u⁽⁴⁾ from
    # the exact solution by finite differences), divided by sin θ for θ.
    t = np.linspace(0.0, nut.period, 4001)
    u = exact.model.at(t)[0]
    u = 1.0 - 2.0 * (u[:, 1] ** 2 + u[:, 2] ** 2)  # cos θ = z-component of q e₃ q*
    d4 = np.abs(np.diff(u, 4)).max() / (t[1] - t[0]) ** 4
    delta = scene.data["time"]["output_step"]
    interp = delta**4 * d4 / 384
    for key in ("theta_min", "theta_max"):
        theta = rep.values[f"{key}_exact"]
        assert rep.values[f"{key}_error"] <= e_orient + interp / math.sin(theta), key
    # Extremum times: the Hermite derivative misses by ≤ (√3/216) Δ³ max|u⁽⁴⁾|, moving the
    # extremum by that over |ü| there; the integration error moves u̇ by ≤ |ω|·e_orient.
    # The period is the span between the first and last maxima over N − 1 periods.
    d2 = np.abs(np.diff(u, 2) / (t[1] - t[0]) ** 2)
    u_ddot = d2[np.argmin(u[1:-1])]  # |ü| at the maximum of θ
    w = float(np.linalg.norm(tr.w, axis=1).max())
    shift = ((math.sqrt(3) / 216) * delta**3 * d4 + w * e_orient) / u_ddot
    periods = round(scene.data["time"]["duration"] / nut.period) - 1
    assert rep.values["period_error"] <= 2 * shift / periods
    # Mean precession: the same two end times, at the largest precession rate |ψ̇|.
    psi_rate = 2 * nut.mean_precession  # released from rest: ψ̇ runs from 0 to ~2× mean
    span = periods * nut.period
    assert rep.values["mean_precession_error"] <= (2 * shift * psi_rate + 2 * e_orient) / span
    # The fast-top approximation mgl/(I₃ω₃) is what the exact solution corrects.
    mgl = 1.0 * 9.80665 * 0.04
    assert abs(nut.mean_precession - mgl / (scene.body.moments[2] * 60.0)) > 0.5


def test_heavy_top_converges_to_the_lagrange_solution_at_fourth_order():
    # Gravity makes ω change, so the pure-rotation model above does not apply; instead the
    # error against the exact solution must fall 16-fold when h halves (RK4, order 4):
    # only a simulation converging to that very solution does so.
    errors = []
    for h in (4e-4, 2e-4):
        scene = load_scene("heavy_top").replace({"time.duration": 1.0, "integrator.step": h,
                                                 "time.output_step": 2e-3})  # fmt: skip
        errors.append(report(scene, run_scene(scene)).values["error_rotor"])
    assert errors[1] > 1e3 * EPS  # well above rounding
    assert 12.0 < errors[0] / errors[1] < 20.0


def test_intermediate_axis_flips_every_2K_over_lambda():
    scene, tr, rep = run("intermediate_axis_flip")
    model = scene.exact_solution.model
    assert model.m1 < 1e-5  # near the separatrix: long, sharp flips
    flips = round(scene.data["time"]["duration"] / model.flip_period)
    assert rep.values["flip_period_exact"] == model.flip_period and flips >= 4
    # A crossing of ω₂ moves by (ω error)/|ω̇₂| there; |ω̇₂| = |(I₃ − I₁) ω₃ ω₁ / I₂| at the
    # crossing, where |ω₁|, |ω₃| are at their largest (the dn and cn amplitudes).
    i1, i2, i3 = scene.body.moments
    amplitude = np.abs(tr.w).max(axis=0)
    rate = abs(i3 - i1) * amplitude[0] * amplitude[2] / i2
    # Hermite: ω₂ ~ β sn(λt): 4th derivative ≤ |β| λ⁴ (a few), error Δ⁴|ω⁽⁴⁾|/384 in value.
    delta = scene.data["time"]["output_step"]
    interp = delta**4 * amplitude[1] * model.rate**4 * 16 / 384
    shift = (rep.values["omega_error"] + interp) / rate
    assert rep.values["flip_period_error"] <= 2 * shift


def test_damped_top_follows_the_exact_decay():
    scene, tr, rep = run("damped_top")
    model = scene.exact_solution.model
    # |L| decays as two exponentials; at the end it matches to the ω error's order.
    assert rep.values["momentum_final"] < 0.2 * np.linalg.norm(scene.body.momentum(tr.w[0]))
    rel = abs(rep.values["momentum_final"] - rep.values["momentum_final_exact"])
    assert rel <= rep.values["omega_error"] * max(scene.body.moments)
    # The body rates: RK4's phase error of the wobble turning at Ω(t) = (I⊥ − I₃)ω₃/I⊥
    # accumulates as h⁴ ∫ Ω⁵/120 dt, on an amplitude |ω⊥(t)|; a factor 2 as above.
    t = tr.t
    w_exact = model.angular_velocity(t - t[0])
    i_perp, i_k = scene.body.moments[0], scene.body.moments[2]
    omega = (i_perp - i_k) / i_perp * w_exact[:, 2]
    phase = np.concatenate([[0.0], np.cumsum(np.abs(omega[1:]) ** 5 * np.diff(t))])
    bound = 2 * (scene.step**4 / 120 * phase * np.hypot(w_exact[:, 0], w_exact[:, 1])).max()
    assert 0.1 * bound < rep.values["omega_error"] <= bound


@pytest.mark.parametrize("name", sorted(bundled()))
def test_committed_figures_show_what_the_code_computes(name):
    scene, tr, _ = run(name)
    png = FIGURES / f"{name}.png"
    assert png.exists(), "run: ga-rotors scenes --figures docs/figures/scenes"
    stored = paper_figures.read_digest(png, DIGEST_PREFIX)
    assert stored == data_digest(scene, tr), "run: ga-rotors scenes --figures docs/figures/scenes"
