"""Hard dynamical cases stay numerically stable: one named test per case (issue 7).

Every bound below is derived (error model, exact solution, or a round-off count) in the
comment next to it. Shared notation: u = 2⁻⁵³ (unit round-off), N steps of size h.

Round-off random walk: a step that rounds an invariant k times, each by a relative error
uniform in [−u, u] (variance u²/3), in directions that do not repeat from step to step,
leaves after N steps a relative error of standard deviation σ = u·√(kN/3); bounds use 6σ
(a 6σ excursion has probability ~1e-9 per sample). A bias that repeats every step grows
like N instead and breaks this bound (it did: see test_long_run_split_keeps_momentum...).
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from ga_rotors import quaternion as Q
from ga_rotors import shapes, simulate
from ga_rotors.errors import (
    InputError,
    IntegrationStoppedWarning,
    PrecisionError,
    StepLimitWarning,
)
from ga_rotors.integrators import Problem, get
from ga_rotors.paths import get as get_path
from ga_rotors.reference import elliptic
from ga_rotors.reference.asymmetric_top import AsymmetricTop
from ga_rotors.reference.symmetric_top import SymmetricTop

U = 2.0**-53
EPS = np.finfo(float).eps


def walk(k: int, n: int) -> float:
    """6σ of the round-off random walk of k roundings per step over n steps (relative)."""
    return 6.0 * U * math.sqrt(k * n / 3.0)


def rk_amplification(b, a, y: float) -> float:
    """|R(iy)|² for the Runge–Kutta tableau (A, b): R(z) = 1 + z bᵀ(I − zA)⁻¹ 1."""
    a = np.asarray(a, dtype=complex)
    z = 1j * y
    stages = np.linalg.solve(np.eye(len(b)) - z * a, np.ones(len(b)))
    return abs(1.0 + z * np.dot(b, stages)) ** 2


RK4_TABLEAU = (
    (1 / 6, 1 / 3, 1 / 3, 1 / 6),
    ((0, 0, 0, 0), (0.5, 0, 0, 0), (0, 0.5, 0, 0), (0, 0, 1, 0)),
)
RK3_TABLEAU = ((1 / 6, 2 / 3, 1 / 6), ((0, 0, 0), (0.5, 0, 0), (-1, 2, 0)))


def quaternions(tr, path):
    spec = get_path(path)
    return Q.normalize(spec.load().quaternions(getattr(tr, spec.array)))


# --- gimbal lock of the z–y′–z″ path -----------------------------------------------------

DISK = shapes.disk(2.0, 0.075)
GIMBAL_W = (0.02, 0.03, 15.7)  # the paper's spin with a small wobble
GIMBAL_H, GIMBAL_T = 1e-3, 10.0
GIMBAL_N = 10_000


def _gimbal_run(theta0):
    q0 = Q.from_axis_angle([0.0, 1.0, 0.0], theta0)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        tr = simulate(DISK, q0, GIMBAL_W, duration=GIMBAL_T, step=GIMBAL_H,
                      paths=("rotor", "quaternion", "euler"), euler_angles=(0.0, theta0, 0.0),
                      sample_every=10)  # fmt: skip
    top = SymmetricTop(DISK, q0, GIMBAL_W)
    exact, _ = top.at(tr.t)
    errors = {}
    for path in ("rotor", "quaternion", "euler"):
        q = quaternions(tr, path)
        errors[path] = Q.distance(exact[: q.shape[0]], q).max()
    return tr, errors, [w for w in caught if w.category is IntegrationStoppedWarning]


def _rk4_spin_error():
    """RK4's geodesic error on a spin at rate |ω|, N steps: the derivation.

    q̇ = ½ q ⊗ (0, ω) with ω nearly constant (here |ω⊥|/|ω| = 2.3e-3) is a rotation at
    half-rate y/h, y = h|ω|/2, and RK4's step multiplies it by
    R(iy) = e^{iy} (1 − i y⁵/120 + O(y⁶)): a half-angle lag of y⁵/120, i.e. a rotation
    lag of y⁵/60 per step, N y⁵/60 after N steps (y = 7.85e-3: 4.97e-9 rad). Corrections:
    relative O(y) from the y⁶ term, O(|ω⊥|/|ω|) from the wobble: 1 % covers both.
    """
    y = GIMBAL_H * float(np.linalg.norm(GIMBAL_W)) / 2.0
    return GIMBAL_N * y**5 / 60.0


@pytest.mark.parametrize("theta0", [0.5, 0.01, 1e-6, 0.0])
def test_gimbal_lock_rotor_and_quaternion_error_does_not_depend_on_theta0(theta0):
    predicted = _rk4_spin_error()
    _, errors, _ = _gimbal_run(theta0)
    _, reference, _ = _gimbal_run(0.5)
    for path in ("rotor", "quaternion"):
        assert abs(errors[path] / predicted - 1.0) <= 0.01, (path, errors[path], predicted)
        # Free problem: ω never depends on q, and RK4 is linear in q, so starting from
        # q_y(θ₀) ⊗ q₀ gives q_y(θ₀) ⊗ (the run from q₀) exactly; the exact solution has the
        # same structure, so the errors differ by rounding only: ~10 roundings of a unit
        # quaternion per step, walk(16, N) = 8e-14 relative to |q| = 1.
        assert abs(errors[path] - reference[path]) <= walk(16, GIMBAL_N)


@pytest.mark.parametrize("theta0", [0.5, 0.01, 1e-6, 0.0])
def test_gimbal_lock_euler_path_reports_its_trouble_never_nan(theta0):
    tr, errors, stopped = _gimbal_run(theta0)
    status = tr.meta["paths"]["euler"]
    watch = status["watch"]
    assert np.isfinite(tr.euler).all()
    # The watch is sound: a run it calls resolved (no step turning ψ by more than 0.1 rad)
    # is within RK4's error model, as accurate as the rotor path's bound.
    if watch["unresolved_steps"] == 0:
        assert status["complete"] and not stopped
        assert errors["euler"] <= 1.01 * _rk4_spin_error()
        assert watch["min_abs_sin_theta"] >= 0.9 * math.sin(theta0)
    if theta0 == 1e-6:
        # The body axis cones around L at ~6e-4 rad, so it passes the pole: flagged, and
        # the answer is off by far more than the bound (the flag is needed).
        assert watch["unresolved_steps"] > 0 and watch["pole_crossings"] > 0
        assert errors["euler"] > 100 * _rk4_spin_error()
    if theta0 == 0.0:
        # sin θ = 0 exactly: the rates are undefined at the first step; the path stops,
        # says so, and a warning reaches the caller.
        assert not status["complete"] and status["ended_at"] == 0.0
        assert watch["first_unresolved"] == 0.0
        assert len(stopped) == 1 and "euler path" in str(stopped[0].message)
    if theta0 >= 0.01:
        assert watch["unresolved_steps"] == 0


# --- intermediate-axis flips ----------------------------------------------------------

FLIP_BODY = (1.0, 2.0, 3.0)
FLIP_H = 1e-3


def _crossings(t, y):
    s = np.nonzero(np.sign(y[:-1]) != np.sign(y[1:]))[0]
    return t[s] - y[s] * (t[s + 1] - t[s]) / (y[s + 1] - y[s])


@pytest.mark.parametrize("eps", [0.1, 1e-3, 1e-6])
def test_intermediate_axis_flip_times_agree_with_2K_over_rate(eps):
    from scipy.special import ellipe

    w0 = (eps, 1.0, eps)
    top = AsymmetricTop(FLIP_BODY, (1.0, 0.0, 0.0, 0.0), w0)
    period = top.flip_period
    k = elliptic.complete_first(top.m, top.m1)
    assert period == pytest.approx(2.0 * k / top.rate, rel=4 * EPS)
    n = round(3.2 * period / FLIP_H)
    run = get("rk4").run(Problem(FLIP_BODY), "quaternion", (1.0, 0, 0, 0), w0, 0.0, FLIP_H, n, 1)
    flips = _crossings(run.t, run.w[:, 1])
    exact = _crossings(run.t, top.angular_velocity(run.t)[:, 1])
    assert len(flips) == len(exact) == 3
    assert np.allclose(np.diff(exact), period, rtol=0, atol=1e-9)
    # Flip-time error from the run's own invariant errors. m₁ ∝ L² − 2E I_b =: s, so
    # δm₁/m₁ ≤ (2|L| δ|L| + 2 I_b δE)/s (+ the same for the denominator, smaller), the
    # period 2K/λ moves by δK/K with dK/dm₁ = −(E(m) − m₁K)/(2 m m₁) (DLMF 19.4.1), and a
    # flip at t_j by t_j δK/K. RK4's phase error at fixed invariants, λ⁵h⁴/120 per unit time,
    # is 5e-16: negligible; linear interpolation of the crossing is exact to O(h³) there
    # (sn'' = 0 at sn = 0).
    inertia = np.array(FLIP_BODY)
    lnorm = np.linalg.norm(run.w * inertia, axis=1)
    energy = 0.5 * (run.w**2 * inertia).sum(1)
    sep = 2.0 * eps**2  # L² − 2E I_b = Σ I_k (I_k − I_b) ω_k² = −ε² + 3ε²
    dsep = (
        2 * lnorm[0] * np.abs(lnorm - lnorm[0]).max() + 2 * 2.0 * np.abs(energy - energy[0]).max()
    )
    dm1 = top.m1 * (dsep / sep + dsep / lnorm[0] ** 2)
    dk = (ellipe(top.m) - top.m1 * k) / (2 * top.m * top.m1) * dm1
    bound = exact * dk / k + 1e-12 * exact
    assert np.all(np.abs(flips - exact) <= bound), (flips - exact, bound)


@pytest.mark.parametrize("name", ["split4", "lgvi", "rk4"])
def test_intermediate_axis_flip_invariants_within_method_bound(name):
    # ε = 1e-3, 3 flips (88 s, 88 000 steps), k roundings of each invariant per step
    # (split4: 5 Strang stages × 5 axis rotations × 4 + 2 conversions = 102; lgvi: Newton to
    # 1e-15 relative, one rotation and the conversions, ~40; RK4: ~30). split4 and lgvi
    # conserve |L| by construction and RK4's truncation error in E and |L| at h = 1e-3 is
    # O(h⁴λ⁵) ≈ 1e-15 per unit time, so what remains is rounding. Near the steady rotation
    # about the middle axis the inputs of each step repeat almost exactly (L ≈ (ε, 2, 3ε),
    # the same small angles every step), so the roundings repeat too and add up coherently:
    # the bound is the linear worst case k·u·N, not the random walk (measured for split4:
    # 9e-12 = 0.9 ulp per step; the random walk would allow 1.2e-12 and fails).
    w0 = (1e-3, 1.0, 1e-3)
    top = AsymmetricTop(FLIP_BODY, (1.0, 0.0, 0.0, 0.0), w0)
    n = round(3.2 * top.flip_period / FLIP_H)
    run = get(name).run(Problem(FLIP_BODY), "quaternion", (1.0, 0, 0, 0), w0, 0.0, FLIP_H, n, 1)
    assert run.complete and len(_crossings(run.t, run.w[:, 1])) == 3
    inertia = np.array(FLIP_BODY)
    lnorm = np.linalg.norm(run.w * inertia, axis=1)
    energy = 0.5 * (run.w**2 * inertia).sum(1)
    coherent = {"split4": 102, "lgvi": 40, "rk4": 30}[name] * U * n
    assert np.abs(lnorm / lnorm[0] - 1).max() <= coherent
    # Energy: conserved to the same rounding by RK4 (truncation negligible, above) and
    # bounded for the Lie–Poisson methods: backward error analysis gives E − Ẽ = O((hλ)^p)
    # relative, λ = 0.58 the orbit's rate (p = 4: 1e-13; lgvi p = 2: 3.4e-7), plus rounding.
    order = get(name).order
    truncation = 0.0 if name == "rk4" else (FLIP_H * top.rate) ** order
    assert np.abs(energy / energy[0] - 1).max() <= truncation + coherent


# --- fast spin: 1000 rad/s at h = 1 ms ------------------------------------------------

# A flat disk (I₃ = I₁ + I₂, the triangle limit) spinning at 1000 rad/s with a 5.8 rad/s
# wobble. Torque-free symmetric top: ω₃ is constant and ω⊥ turns at ν = (1 − I₃/I⊥) ω₃ =
# −1000 rad/s, a LINEAR system ω̇⊥ = ν J ω⊥, so every Runge–Kutta method's ω update is
# exactly its stability function: E⊥ = ½ I⊥ |ω⊥|² is multiplied by |R(ihν)|² every step.
FAST_BODY, FAST_W, FAST_H, FAST_N = (1.0, 1.0, 2.0), (5.0, 3.0, 1000.0), 1e-3, 1000


# Methods this run takes past their declared step limit (docs/stability.md, step limits):
# the run must say so (StepLimitWarning); the others must stay silent.
FAST_PAST_LIMIT = {"rk4", "rk4_renorm", "rkmk4", "cf4", "cg3", "lie_euler", "split2", "split4",
                   "split6"}  # fmt: skip


def _fast(name):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", StepLimitWarning)
        run = get(name).run(Problem(FAST_BODY), "quaternion", (1.0, 0, 0, 0), FAST_W, 0.0,
                            FAST_H, FAST_N, 1)  # fmt: skip
    said = [w for w in caught if issubclass(w.category, StepLimitWarning)]
    assert len(said) == (name in FAST_PAST_LIMIT), (name, [str(w.message) for w in said])
    return run


@pytest.mark.parametrize(
    "name, tableau",
    [("rk4", RK4_TABLEAU), ("rk4_renorm", RK4_TABLEAU), ("rkmk4", RK4_TABLEAU),
     ("cf4", RK4_TABLEAU), ("cg3", RK3_TABLEAU), ("dp8", None)],
)  # fmt: skip
def test_fast_spin_explicit_rk_damps_the_wobble_exactly_as_its_stability_function(name, tableau):
    from ga_rotors.integrators import dp8

    b, a = (dp8.B, np.array(dp8.A).reshape(dp8.STAGES, -1)) if tableau is None else tableau
    rho = rk_amplification(b, a, FAST_H * 1000.0)  # hν = −1; |R(iy)| is even in y
    run = _fast(name)
    assert run.complete
    # The spin itself is untouched: (I₁ − I₂) = 0 makes ω̇₃ exactly 0 in every stage.
    assert np.all(run.w[:, 2] == 1000.0)
    e_perp = 0.5 * (run.w[:, 0] ** 2 + run.w[:, 1] ** 2)
    predicted = e_perp[0] * rho ** np.arange(FAST_N + 1)
    # RK4: ρ = 0.98785, the wobble's energy loses 1.2 % per step (ρ^1000 = 5e-6): the
    # method silently kills the nutation, by exactly this much and not more. Rounding: ~8
    # roundings of ω per stage, 4–12 stages: walk(100, N) relative.
    assert np.allclose(e_perp, predicted, rtol=walk(100, FAST_N) * FAST_N, atol=0)


def test_fast_spin_lie_euler_blows_up_by_its_stability_function():
    # Explicit Euler on ω: |1 + ihν|² = 2, so E⊥ doubles every step (2^1000 ≈ 1e301 after
    # 1 s, still finite); log₂ of the growth per step is 1 to rounding.
    run = _fast("lie_euler")
    e_perp = 0.5 * (run.w[:, 0] ** 2 + run.w[:, 1] ** 2)
    growth = np.log2(e_perp[-1] / e_perp[0]) / FAST_N
    assert abs(growth - 1.0) <= walk(8, FAST_N)


def test_fast_spin_midpoint_keeps_energy_but_lags_the_phase():
    # The implicit midpoint map of ω̇⊥ = νJω⊥ is the Cayley transform: |ω⊥| exact, the
    # turn per step 2·atan(h|ν|/2) = 0.9273 rad instead of 1 rad (ω₁ + iω₂ turns at
    # +(I₃ − I₁)/I₂ ω₃ = +1000 rad/s).
    run = _fast("midpoint")
    assert run.complete
    wp = run.w[:, 0] + 1j * run.w[:, 1]
    assert np.abs(np.abs(wp) / abs(wp[0]) - 1).max() <= walk(40, FAST_N)
    turn = np.angle(wp[1:] / wp[:-1])
    assert np.allclose(turn, 2.0 * math.atan(0.5), rtol=0, atol=1e-12)


@pytest.mark.parametrize("name", ["split2", "split4", "split6", "split_sym"])
def test_fast_spin_splitting_stays_bounded(name):
    run = _fast(name)
    inertia = np.array(FAST_BODY)
    L = run.w * inertia
    lnorm = np.linalg.norm(L, axis=1)
    # |L| and the space-frame L conserved by construction: round-off walk only (k ≤ 142).
    assert np.abs(lnorm / lnorm[0] - 1).max() <= walk(142, FAST_N)
    ls = Q.rotate(Q.normalize(run.x), L)
    assert np.abs(ls - ls[0]).max() <= walk(142, FAST_N) * lnorm[0] * 4
    # Energy: E = |L|²/2 − L₃²/4 here, so δE = −L₃ δL₃/2. Every sub-step rotates L exactly;
    # L₃ moves only through the small rotations about axes 1, 2 (angles h|ω⊥|/2 per half
    # step) and the symmetric composition undoes their first order, so |δL₃| stays below
    # |L⊥| h|ω⊥| and |δE|/E ≤ L₃|L⊥| h|ω⊥| / (2E) = 3.4e-5 (measured ≤ 1.4e-6).
    e = 0.5 * (run.w**2 * inertia).sum(1)
    wperp = math.hypot(FAST_W[0], FAST_W[1])
    bound = L[0, 2] * wperp * FAST_H * wperp / (2 * e[0])
    assert np.abs(e / e[0] - 1).max() <= bound
    if name == "split_sym":
        # The disk IS its symmetric part (remainder coefficient 1/I₂ − 1/I₁ = 0): exact.
        exact, _ = SymmetricTop(FAST_BODY, (1.0, 0, 0, 0), FAST_W).at(run.t)
        # angle turned 1000 rad; each step composes ~3 exact rotations: walk(24, N) rad·|ω|h
        assert Q.distance(exact, Q.normalize(run.x)).max() <= walk(24, FAST_N) * 1000.0


def test_fast_spin_lgvi_past_its_step_limit_is_refused():
    # h|ω₃| = 1 is the discrete Moser–Veselov limit (sin θ = hω₃ has no solution beyond):
    # before the fix Newton's unconverged iterate went on for 32 steps, then a NaN; then the
    # run stopped at t = 0; now lgvi's declared step limit refuses it before any step.
    with pytest.raises(InputError, match=r"step: lgvi cannot step h·\|ω\| = 1 \(limit 1\)"):
        simulate(FAST_BODY, (1.0, 0, 0, 0), FAST_W, duration=1.0, step=FAST_H,
                 paths="quaternion", integrator="lgvi")  # fmt: skip
    # Just inside the limit (hω₃ = 0.9) it runs, conserving |L| by construction.
    run = get("lgvi").run(Problem(FAST_BODY), "quaternion", (1.0, 0, 0, 0), (5.0, 3.0, 900.0),
                          0.0, FAST_H, FAST_N, 1)  # fmt: skip
    lnorm = np.linalg.norm(run.w * np.array(FAST_BODY), axis=1)
    assert run.complete and np.abs(lnorm / lnorm[0] - 1).max() <= walk(40, FAST_N)


def test_fast_spin_midpoint_that_cannot_converge_stops_instead_of_garbage():
    # Fixed-point sweeps contract by ~h|ω|/4: at h|ω| = 4 they do not converge. Before the
    # fix the step returned the unconverged iterate: |q| = 9e34 after 0.1 s, complete=True.
    with pytest.warns(StepLimitWarning, match=r"midpoint.*h·ν = 4"):
        run = get("midpoint").run(Problem(FAST_BODY), "quaternion", (1.0, 0, 0, 0),
                                  (0, 0, 4000.0), 0.0, FAST_H, 100, 1)  # fmt: skip
    assert not run.complete and np.isfinite(run.x).all() and np.isfinite(run.w).all()
    # Inside its declared limit (hν = 1.5 < 2: the sweep contracts by 0.75) it runs, silently.
    ok = get("midpoint").run(Problem(FAST_BODY), "quaternion", (1.0, 0, 0, 0), (0, 0, 1500.0),
                             0.0, FAST_H, 100, 1)  # fmt: skip
    assert ok.complete and abs(np.linalg.norm(ok.x[-1]) - 1) <= walk(40, 100)


# --- long runs: 10⁶ steps --------------------------------------------------------------

LONG_BODY, LONG_W, LONG_H, LONG_N = (1.0, 2.0, 3.0), (1.0, 0.5, 0.2), 0.01, 10**6
LONG_Q0 = np.array([0.3, 0.1, 0.9, 0.2]) / math.sqrt(0.95)
# roundings of L per step: 4 per axis rotation (2 products, 1 sum, the angle) + 2 for the
# L ↔ ω conversions; split2 5 rotations, split4 25, split6 35, split_sym 3 plus one
# quat_from_rotvec, lgvi one qrotate (15 products) and Newton's last correction.
LONG_K = {"split2": 22, "split4": 102, "split6": 142, "split_sym": 16, "lgvi": 40}


@pytest.mark.parametrize("name", sorted(LONG_K))
def test_long_run_split_keeps_momentum_to_roundoff_walk_and_energy_bounded(name):
    inertia = np.array(LONG_BODY)
    problem = Problem(LONG_BODY)
    run = get(name).run(problem, "quaternion", LONG_Q0, LONG_W, 0.0, LONG_H, LONG_N, 1000)
    L = run.w * inertia
    lnorm = np.linalg.norm(L, axis=1)
    # 6σ of the walk: split6 4.4e-12, split2 1.7e-12. Before the fix of rotate_about
    # (cos φ computed as c² − s² of a nearly constant half angle: the same rounding every
    # step) split4/split6 drifted linearly to 1.0e-11/1.2e-11 and failed this.
    bound = walk(LONG_K[name], LONG_N)
    assert np.abs(lnorm / lnorm[0] - 1).max() <= bound
    ls = Q.rotate(Q.normalize(run.x), L)
    assert (np.linalg.norm(ls - ls[0], axis=1) / lnorm[0]).max() <= bound + walk(16, LONG_N)
    # Energy: backward error analysis, E − Ẽ is a function of L on the (closed) orbit, so
    # |E_n − E_0| ≤ max − min of E over one orbit period (taken from a 40 s run sampled every
    # step, 7.5 periods of ω) plus the walk of E (twice that of |L|, E being quadratic).
    short = get(name).run(problem, "quaternion", LONG_Q0, LONG_W, 0.0, LONG_H, 4000, 1)
    e_short = 0.5 * (short.w**2 * inertia).sum(1)
    e = 0.5 * (run.w**2 * inertia).sum(1)
    assert np.abs(e - e[0]).max() <= np.ptp(e_short) + 2 * bound * e[0]


@pytest.mark.parametrize(
    "name, body, w0",
    [("split_sym", LONG_BODY, LONG_W), ("split_sym", (1.0, 1.0, 2.0), (0.0, 0.0, 5.0)),
     ("rkmk4", (1.0, 1.0, 2.0), (0.0, 0.0, 5.0)), ("cf4", (1.0, 1.0, 2.0), (0.0, 0.0, 5.0))],
)  # fmt: skip
def test_long_run_unit_norm_is_a_random_walk_not_a_drift(name, body, w0):
    # split_sym's symmetric-top flow turns q by the angle h|L|/I_p, the same every step
    # (|L| is conserved), and a steady spin turns every method by the same angle every step:
    # cos of that angle rounded to the same float each time, |exp| = 1 + δ with one fixed
    # δ ≤ u/2, and |q| drifted linearly: split_sym 2.1e-11 (asymmetric), 4e-11 (spin),
    # rkmk4 3.9e-11, cf4 1.0e-10 in 10⁶ steps. Now q ⊗ exp is q + q ⊗ (exp − 1): the
    # rounding lands on q's components, which change every step, ≤ 3 q-updates per step of
    # ~2 roundings each of |q| = 1: walk(8, N) = 1.1e-12.
    run = get(name).run(Problem(body), "quaternion", LONG_Q0, w0, 0.0, LONG_H, LONG_N, 1000)
    assert run.complete
    drift = np.abs(np.linalg.norm(run.x, axis=1) - 1.0).max()
    assert drift <= walk(8, LONG_N), drift


def test_long_run_rk4_energy_drifts_linearly_at_the_predicted_rate():
    # Symmetric top (I⊥ = 1, I₃ = 2), ω₃ = 5: ω⊥ turns at ν = −5, hν = 0.05. RK4 multiplies
    # E⊥ by ρ = |R(0.05i)|² = 1 − y⁶/72 + y⁸/576 each step (exactly: the ω equation is
    # linear), so E drifts at dE/dt = E⊥ ln ρ / h = −3.1e-9 E⊥ per second, linearly to
    # 2e-4 relative over 10⁶ steps (curvature N ln ρ / 2 = 1.1e-4 of the slope).
    body, w0 = (1.0, 1.0, 2.0), (0.3, 0.4, 5.0)
    run = get("rk4").run(Problem(body), "quaternion", LONG_Q0, w0, 0.0, LONG_H, LONG_N, 1000)
    e_perp = 0.5 * (run.w[:, 0] ** 2 + run.w[:, 1] ** 2)
    rho = rk_amplification(*RK4_TABLEAU, LONG_H * 5.0)
    slope = np.polyfit(run.t, e_perp, 1)[0]
    predicted = e_perp[0] * math.log(rho) / LONG_H
    assert abs(slope / predicted - 1) <= 2e-4  # curvature 1.1e-4 + rounding
    # The exact geometric decay, from ln ρ = log1p(−y⁶/72 + y⁸/576) (ρ rounded to a float
    # and raised to 10⁶ would carry 1e-10 of its own rounding).
    y = LONG_H * 5.0
    steps = np.rint(run.t / LONG_H)
    predicted = e_perp[0] * np.exp(steps * math.log1p(-(y**6) / 72 + y**8 / 576))
    gap = np.abs(e_perp / predicted - 1).max()
    assert gap <= walk(100, LONG_N)


# --- near the separatrix -----------------------------------------------------------------


def test_separatrix_reference_refuses_subnormal_one_minus_m():
    # ω = (ε, 1, ε) on (1, 2, 3): 1 − m = 2ε². Below ε ≈ 1e-154 it is subnormal (ε = 1e-160:
    # 2e-320, three digits) or 0 (ε = 1e-170), and the reference used to return the
    # separatrix motion, which never flips, for a motion that flips every ~1300 s.
    for eps in (1e-155, 1e-160, 1e-170):
        with pytest.raises(PrecisionError, match="smallest normal float"):
            AsymmetricTop(FLIP_BODY, (1.0, 0, 0, 0), (eps, 1.0, eps))
    # Just outside (1 − m = 2e-300, normal): K still right, against mpmath at 400 digits.
    import mpmath as mp

    top = AsymmetricTop(FLIP_BODY, (1.0, 0, 0, 0), (1e-150, 1.0, 1e-150))
    with mp.workdps(400):
        k = mp.ellipk(1 - 2 * mp.mpf(1e-150) ** 2)  # m₁ = 2ε², exact at 400 digits
    assert elliptic.complete_first(top.m, top.m1) == pytest.approx(float(k), rel=4 * EPS)


def test_separatrix_reference_raises_where_its_bound_crosses_max_error():
    import mp_oracle

    # 1 − m = 2e-12, starting next to the middle axis: the starting phase u₀ used to be
    # F(atan2(sn₀, cn₀) | m), which amplified the rounding of the amplitude by
    # 1/dn(u₀) ≈ 7e5 and put 1.1e-11 rad of error near a flip under a bound of 1.5e-12;
    # elliptic.jacobi_argument reads u₀ from sn₀, cn₀ to a few ulps (the bound's model).
    top = AsymmetricTop(FLIP_BODY, LONG_Q0, (1e-6, 1.0, 1e-6))
    limit = 1.5e-12  # the bound grows from 7e-13 at t = 0 to 1.7e-12 at 60 s
    times = np.linspace(0.0, 60.0, 601)
    bound = top.state(times, max_error=np.inf).error
    first_over = int(np.argmax(bound > limit))
    assert 0 < first_over < len(times) - 1  # the threshold lies inside the span
    t_in, t_out = times[first_over - 1], times[first_over]
    with pytest.raises(PrecisionError):
        top.state([t_out], max_error=limit)
    inside = top.state([t_in], max_error=limit)
    # Just inside, the answer is right within its own bound: 30-digit Taylor oracle.
    (y,) = mp_oracle.integrate(FLIP_BODY, LONG_Q0, (1e-6, 1.0, 1e-6), [t_in])
    want = np.array([float(v) for v in y[:4]])
    assert Q.distance(want, inside.q[0]) <= inside.error[0]
