"""Every fixed-step integrator declares its step limit; a run past it warns (or, for lgvi,
is refused), and one just inside it does not."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from ga_rotors import simulate
from ga_rotors.errors import InputError, StepLimitWarning
from ga_rotors.integrators import Problem, catalogue, get

BODY = (1.0, 1.5, 2.0)
W0 = (5.0, 3.0, 100.0)
N = 100
LIMITED = [c["name"] for c in catalogue() if c["step_limit"] != "none"]


def _step_at(name: str, fraction: float) -> float:
    """The step h at which the declared quantity is ``fraction`` of its limit (bisection on
    h: every quantity grows monotonically with h over [0, h_hi])."""
    from scipy.optimize import brentq

    lim = get(name).step_limit

    def gap(h):
        q = lim(BODY, W0, h, N)
        return q.value - fraction * q.limit

    hi = 1e-4
    while gap(hi) < 0:
        hi *= 2
    return brentq(gap, 0.0, hi, xtol=1e-15, rtol=1e-12)


def test_every_fixed_step_method_declares_a_limit():
    assert set(LIMITED) == {c["name"] for c in catalogue()} - {"dop853", "magnus4"}


@pytest.mark.parametrize("name", LIMITED)
def test_step_limit_warns_just_past_and_not_just_below(name):
    # 1% either side of the limit, the step solved from the declared quantity itself.
    method, problem = get(name), Problem(BODY)
    below, past = _step_at(name, 0.99), _step_at(name, 1.01)
    with warnings.catch_warnings():
        warnings.simplefilter("error", StepLimitWarning)
        assert not method.check_step(problem, W0, below, N).exceeded
    if method.step_limit_action == "raise":
        with pytest.raises(InputError, match=f"h: {name} cannot step"):
            method.run(problem, "quaternion", (1.0, 0, 0, 0), W0, 0.0, past, 1, 1)
    else:
        with pytest.warns(StepLimitWarning, match=f"step: {name} cannot step"):
            method.check_step(problem, W0, past, N)


def test_fast_spin_rk4_warns_by_how_much_the_wobble_is_damped():
    # docs/stability.md's fast disk: ω⊥ turns at ν = 1000 rad/s, hν = 1, and each step
    # scales it by |R(i)| = sqrt(0.987847); the warning's factor is that to the 1000th power,
    # which the run reproduces (ω⊥ obeys a linear equation: to rounding, 1000 steps × 8u).
    with pytest.warns(StepLimitWarning, match=r"rk4 cannot step .* damped × 0.00221") as rec:
        tr = simulate((1.0, 1.0, 2.0), (1.0, 0, 0, 0), (5.0, 3.0, 1000.0), duration=1.0,
                      step=1e-3, paths="quaternion", integrator="rk4")  # fmt: skip
    assert len(rec) == 1
    measured = np.hypot(*tr.w[-1, :2]) / math.hypot(5.0, 3.0)
    assert abs(measured / 0.00221 - 1) < 0.5e-2 / 0.221  # the message's 3 digits


@pytest.mark.parametrize("name", ["rk4", "rk4_renorm"])
def test_fast_spin_rk4_warns_that_the_orientation_lags_the_spin(name):
    # On (1, 1.5, 2) at 1000 rad/s the wobble changes by less than a factor e (0.49 < 1) but
    # q̇ = ½ q ⊗ ω turns by arg R(iy) instead of y = h|ω|/2 = 0.5 per step: the predicted lag
    # 2N·|arg R(iy)e^(−iy)| = 0.475 rad is the run's orientation error (docs/stability.md,
    # fast spin: 0.48 rad for both), up to the wobble's own contribution, O(|ω⊥|/|ω|) = 6e-3
    # relative. Renormalising |q| (rk4_renorm) does not touch the phase.
    from ga_rotors.reference.asymmetric_top import AsymmetricTop

    w0 = (5.0, 3.0, 1000.0)
    with pytest.warns(StepLimitWarning, match=r"lags its spin by 0.475 rad") as rec:
        tr = simulate(BODY, (1.0, 0, 0, 0), w0, duration=1.0, step=1e-3, paths="quaternion",
                      integrator=name)  # fmt: skip
    assert len(rec) == 1
    exact = AsymmetricTop(BODY, (1.0, 0, 0, 0), w0).at([1.0])[0][0]
    from ga_rotors import quaternion as Q

    error = Q.distance(exact, Q.normalize(tr.q[-1]))
    assert abs(error / 0.4752 - 1) < 2 * math.hypot(5.0, 3.0) / 1000.0, error


def test_lgvi_refuses_a_step_past_h_omega_1():
    with pytest.raises(InputError, match=r"lgvi cannot step h·\|ω\| = 1.1 \(limit 1\)"):
        simulate(BODY, (1.0, 0, 0, 0), (0.0, 0.0, 110.0), duration=0.1, step=0.01,
                 paths="quaternion", integrator="lgvi")  # fmt: skip


def test_scene_and_cli_name_the_file_and_integrator_step(tmp_path, capsys):
    from ga_rotors.cli import main
    from ga_rotors.scene import load_scene, run_scene

    # 500 steps at hν = 0.846: N·|ln|R|²| = 500 × 0.00465 = 2.3, past 1.
    scene = load_scene("fast_spinner").replace(
        {"integrator.step": 1e-3, "time.duration": 0.5, "time.output_step": 1e-3}
    )
    path = tmp_path / "coarse.toml"
    path.write_text(scene.to_toml())
    with pytest.warns(StepLimitWarning, match=r"coarse.toml: integrator.step: rk4 cannot"):
        run_scene(str(path))
    assert main(["run", str(path), "--out", str(tmp_path / "out")]) == 0
    err = capsys.readouterr().err
    lines = [line for line in err.splitlines() if "StepLimit" in line or "cannot step" in line]
    assert len(lines) == 1 and lines[0].startswith("ga-rotors: warning: ")
    assert "Traceback" not in err


def _eig_rate(inertia, w):
    """ν by a 3×3 eigenvalue solve of ∂ω̇/∂ω = I⁻¹([Iω]× − [ω]× I): the oracle."""
    moments, w = np.asarray(inertia, dtype=float), np.asarray(w, dtype=float)

    def skew(v):
        return np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])

    jac = (skew(moments * w) - skew(w) * moments) / moments[:, None]
    return float(np.max(np.abs(np.linalg.eigvals(jac))))


_moment = st.floats(0.01, 100.0)
_rate = st.floats(-1e3, 1e3)


@given(st.tuples(_moment, _moment, _moment), st.tuples(_rate, _rate, _rate))
def test_linear_rate_in_closed_form_matches_the_eigenvalue_solve(inertia, w):
    from ga_rotors.integrators.limits import linear_rate

    expected = _eig_rate(inertia, w)
    scale = max(abs(c) for c in w) * max(inertia) / min(inertia)
    assert linear_rate(inertia, w) == pytest.approx(expected, rel=1e-6, abs=1e-9 * scale)


@pytest.mark.parametrize(
    "inertia, w",
    [
        ((1.0, 1.0, 1.0), (1.0, 2.0, 3.0)),  # sphere: J = 0
        ((1.0, 1.0, 2.0), (0.0, 0.0, 1000.0)),  # symmetric, about the axis: ±iν
        ((1.0, 2.0, 3.0), (0.0, 2.0, 0.0)),  # middle axis: real ±ν (unstable)
        ((1.0, 2.0, 3.0), (1.0, 0.5, 0.2)),  # generic: p, q both nonzero
        ((1.0, 2.0, 3.0), (0.0, 0.0, 0.0)),  # at rest
        ((1.0, 2.0, 3.0), (1e-3, 2.0, 1e-3)),  # next to the separatrix
    ],
)
def test_linear_rate_named_cases(inertia, w):
    from ga_rotors.integrators.limits import linear_rate

    assert linear_rate(inertia, w) == pytest.approx(_eig_rate(inertia, w), rel=1e-9, abs=1e-12)


def test_step_limit_text_is_built_only_when_asked():
    calls = []
    lim = get("rk4").step_limit(BODY, W0, 1e-5, N)
    assert not lim.exceeded
    explain = lim.explain
    lim = lim._replace(explain=lambda: calls.append(1) or explain())
    assert calls == [] and "orientation lags" in lim.effect and calls == [1]


def _spin_up_scene(duration: float):
    from ga_rotors.scene import Scene

    # A constant torque of 10 N·m about axis 3 (I₃ = 2): ω₃ = 10 + 5 t exactly, so rk4 at
    # h = 0.01 starts far within its limit and leaves it during the run.
    return Scene({"body": {"moments": list(BODY)},
                  "initial": {"angular_velocity": {"body": [0.0, 0.0, 10.0], "units": "rad/s"}},
                  "time": {"duration": duration},
                  "integrator": {"method": "rk4", "step": 0.01, "paths": ["quaternion"]},
                  "effects": [{"type": "body_torque", "torque": [0.0, 0.0, 10.0]}]})  # fmt: skip


def test_a_torque_spinning_past_the_limit_warns_at_the_first_sample_past_it():
    from ga_rotors.scene import run_scene

    duration, h = 20.0, 0.01
    nsteps = round(duration / h)
    lim = get("rk4").step_limit
    # The oracle: the closed-form ω(t) on the step grid, its first step past the limit.
    grid = h * np.arange(nsteps + 1)
    past = [lim(BODY, (0.0, 0.0, 10.0 + 5.0 * t), h, nsteps).exceeded for t in grid]
    t_cross = grid[past.index(True)]
    assert not past[0] and 1.0 < t_cross < duration - 1.0  # a crossing mid-run
    with pytest.warns(StepLimitWarning) as caught:
        run_scene(_spin_up_scene(duration))
    assert len(caught) == 1
    text = str(caught[0].message)
    assert text.startswith("<dict>: integrator.step: rk4 crosses its step limit at t = ")
    t_warned = float(text.split("at t = ")[1].split(" s")[0])
    # checked where |ω| grows by WATCH_GROWTH = 0.1 %: at most 0.1 % of 60 rad/s late
    assert t_cross <= t_warned <= t_cross + 0.001 * (10.0 + 5.0 * t_cross) / 5.0 + h


def test_a_run_that_stays_within_the_limit_does_not_warn():
    from ga_rotors.scene import run_scene

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        run_scene(_spin_up_scene(0.5))  # ω₃ reaches 12.5 rad/s: well within


def test_watch_step_ignores_runs_without_a_limit_or_a_body():
    t, w = np.array([0.0, 1.0]), np.array([[0.0, 0.0, 1.0], [0.0, 0.0, 1e6]])
    assert get("dop853").watch_step(Problem(BODY), t, w, 0.01, 100) is None
    assert get("rk4").watch_step(Problem(BODY), t[:0], w[:0], 0.01, 100) is None
    with pytest.warns(StepLimitWarning, match="at t = 1 s"):
        assert get("rk4").watch_step(Problem(BODY), t, w, 0.01, 100)[0] == 1.0
