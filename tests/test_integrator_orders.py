"""Observed order of every integrator on exact references, and what each one declares it
conserves.

Order: the geodesic error at a fixed final time for step counts n₀·2^k; log₂ of successive
error ratios must lie within ±0.15 of the declared order. How the ranges were chosen: from
a sweep of n = 10·2^k (k = 0…9) per method and problem, n₀ is the smallest count from which
every ratio is within 0.1 of the order (the pre-asymptotic regime ends there: below it
the next term of the error expansion is more than ~7 % of the leading one), and the finest
count keeps the error ≥ 1e-11 rad, a hundred times above the rounding floor of these runs
(≈ 1e-13 rad, where split6's error flattens out in the sweep). The floor is asserted, so a
range that drifts into round-off fails loudly instead of passing by luck.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from ga_rotors import quaternion as Q
from ga_rotors.errors import StepLimitWarning
from ga_rotors.integrators import PrescribedOmega, Problem, get
from ga_rotors.reference.asymmetric_top import AsymmetricTop
from ga_rotors.reference.coning import Coning, coning_rate
from ga_rotors.reference.heavy_top import HeavyTop, gravity_torque

Q0 = np.array([0.3, 0.1, 0.9, 0.2]) / math.sqrt(0.95)
FREE_BODY, FREE_W, FREE_T = (1.0, 2.0, 3.0), (1.0, 0.5, 0.2), 4.0
# A slow heavy top nutating past the horizontal (θ from 68° to 100°).
HEAVY_BODY, HEAVY_MGL, HEAVY_W, HEAVY_T = (1.0, 1.0, 0.3), 1.0, (1.0, -0.5, 3.0), 6.0
Q_HEAVY = np.array([0.6, 0.2, -0.5, 0.4])

# name -> (n₀, halvings, final time) on the free asymmetric top
FREE_RANGES = {
    "rk4": (20, 4, FREE_T),
    "rk4_renorm": (20, 4, FREE_T),
    "lie_euler": (400, 3, FREE_T),
    "rkmk4": (20, 4, FREE_T),
    "cf4": (20, 4, FREE_T),
    "cg3": (20, 4, FREE_T),
    "split2": (20, 4, FREE_T),
    "split4": (10, 4, FREE_T),
    "split4_yoshida": (20, 4, FREE_T),
    "split6": (40, 3, 16.0),  # order 6 spans 64³ in three halvings: a longer run
    "split_sym": (20, 4, FREE_T),
    "lgvi": (40, 4, FREE_T),
    "midpoint": (20, 4, FREE_T),
}
# name -> (n₀, halvings) on the heavy top
HEAVY_RANGES = {
    "rk4": (320, 4),
    "lie_euler": (1280, 3),
    "rkmk4": (320, 4),
    "cf4": (320, 4),
    "cg3": (320, 4),
    "split2": (80, 4),
    "split4": (40, 4),
    "split6": (20, 4),
    "lgvi": (160, 4),
    "midpoint": (160, 4),
}


def _observed(errors):
    errors = np.asarray(errors)
    return np.log2(errors[:-1] / errors[1:])


def _errors(name, problem, q0, w0, duration, want, n0, halvings):
    out = []
    for k in range(halvings + 1):
        n = n0 * 2**k
        with warnings.catch_warnings():
            # A step sweep measures the error of coarse steps on purpose (as the accuracy
            # study does); the step-limit warning is for runs whose user would not see it.
            warnings.simplefilter("ignore", StepLimitWarning)
            run = get(name).run(problem, "quaternion", q0, w0, 0.0, duration / n, n, n)
        out.append(Q.distance(want, Q.normalize(run.x[-1])))
    return out


def _check(name, errors):
    order = get(name).order
    assert errors[-1] >= 1e-11, f"{name}: finest step near round-off ({errors[-1]:.2g} rad)"
    observed = _observed(errors)
    assert np.all(np.abs(observed - order) <= 0.15), (name, order, observed)


@pytest.mark.parametrize("name", list(FREE_RANGES))
def test_observed_order_on_the_free_asymmetric_top(name):
    n0, halvings, duration = FREE_RANGES[name]
    top = AsymmetricTop(FREE_BODY, Q0, FREE_W)
    want = top.at([duration])[0][0]
    errors = _errors(name, Problem(FREE_BODY), Q0, FREE_W, duration, want, n0, halvings)
    _check(name, errors)


@pytest.mark.parametrize("name", list(HEAVY_RANGES))
def test_observed_order_on_the_heavy_top(name):
    q0 = Q_HEAVY / np.linalg.norm(Q_HEAVY)
    top = HeavyTop(HEAVY_BODY, HEAVY_MGL, q0, HEAVY_W)
    want = top.at([HEAVY_T])[0][0]
    problem = Problem(HEAVY_BODY, torques=(gravity_torque(HEAVY_MGL),))
    errors = _errors(name, problem, q0, HEAVY_W, HEAVY_T, want, *HEAVY_RANGES[name])
    _check(name, errors)


@pytest.mark.parametrize("name,n0", [("magnus4", 20), ("rk4", 20), ("lie_euler", 200)])
def test_observed_order_on_prescribed_coning(name, n0):
    cone = Coning(2.0, 1.3, Q0)
    want = cone.at([FREE_T])[0]
    problem = Problem(omega=PrescribedOmega(coning_rate, cone.params))
    out = []
    for k in range(4):
        n = n0 * 2**k
        run = get(name).run(problem, "quaternion", Q0, None, 0.0, FREE_T / n, n, n)
        out.append(Q.distance(want, Q.normalize(run.x[-1])))
    _check(name, out)


# A racket thrown under gravity, its frame at the handle (0.15 m from the centre of mass),
# spun at 12 rad/s near its middle axis; 1 s. (method, path) -> (n₀, halvings), chosen as
# above from a sweep of n = 10·2^k, for the angle and the body origin's position alike
# (rk4 is measured in tests/test_motion.py).
RACKET, RACKET_MASS, HANDLE = (0.011, 0.023, 0.031), 0.31, (0.0, 0.15, 0.0)
MOTION_RANGES = {
    ("cf4", "motor"): (80, 4),
    ("cf4", "quaternion"): (40, 4),
    ("dp8", "motor"): (10, 2),
    ("split2", "motor"): (160, 4),
    ("split4", "quaternion"): (40, 4),
    ("split6", "motor"): (20, 3),
}


@pytest.mark.parametrize("name,path", list(MOTION_RANGES))
def test_observed_order_on_a_thrown_body(name, path):
    from ga_rotors import RigidBody, forces
    from ga_rotors.paths import resolve
    from ga_rotors.reference.rigid_motion import FreeFlight

    body = RigidBody(RACKET, mass=RACKET_MASS, centre_of_mass=HANDLE)
    q0, w0, p0, v0 = np.array([1.0, 0, 0, 0]), [0.05, 12.0, 0.1], [0, 0, 1.5], [3.0, 0, 5.0]
    exact = FreeFlight(RACKET, RACKET_MASS, q0, w0, p0, v0, centre_of_mass=HANDLE).state([1.0])
    problem = Problem(RACKET, mass=RACKET_MASS, centre_of_mass=HANDLE,
                      forces=(forces.uniform_gravity(body),))  # fmt: skip
    module = resolve(path, moves=True).load()
    x0, r0 = module.initial_state(q0, p0, w0, v0, HANDLE)
    n0, halvings = MOTION_RANGES[name, path]
    angles, distances = [], []
    for k in range(halvings + 1):
        n = n0 * 2**k
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", StepLimitWarning)
            x = get(name).run(problem, path, x0, r0, 0.0, 1.0 / n, n, n).x[-1]
        angles.append(Q.distance(exact.q[0], Q.normalize(module.quaternions(x))))
        distances.append(np.linalg.norm(module.positions(x, HANDLE) - exact.position[0]))
    _check(name, angles)
    _check(name, distances)  # metres, on a flight of a few metres


def test_rk4_on_euler_angles_has_order_4_away_from_gimbal_lock():
    # The z–y′–z″ path's RK4 is the paper's third path: order 4 while sin θ stays away from 0.
    from ga_rotors.euler import from_quaternion, to_quaternion

    top = AsymmetricTop(FREE_BODY, Q0, FREE_W)
    want = top.at([FREE_T])[0][0]
    x0 = from_quaternion(Q0, "ZYZ")
    out = []
    for k in range(5):
        n = 40 * 2**k
        run = get("rk4").run(Problem(FREE_BODY), "euler", x0, FREE_W, 0.0, FREE_T / n, n, n)
        out.append(Q.distance(want, to_quaternion("ZYZ", run.x[-1])))
    _check("rk4", out)


EPS = np.finfo(float).eps


@pytest.mark.parametrize(
    "name",
    ["rk4_renorm", "lie_euler", "rkmk4", "cf4", "cg3", "split2", "split4", "split4_yoshida",
     "split6", "split_sym", "lgvi", "midpoint"],
)  # fmt: skip
def test_declared_invariants_hold_to_rounding(name):
    """Each property in ``conserves`` holds to a rounding budget over 2000 steps.

    Budget: every step adds O(10) roundings of each invariant's size, in random directions
    (√n growth), bounded here by the linear worst case 64·ε·n relative.
    """
    integ = get(name)
    inertia = np.array(FREE_BODY)
    n = 2000
    run = integ.run(Problem(FREE_BODY), "quaternion", Q0, FREE_W, 0.0, 0.01, n, 100)
    q, w = run.x, run.w
    budget = 64 * EPS * n
    if "unit_norm" in integ.conserves:
        assert np.abs(np.linalg.norm(q, axis=1) - 1).max() <= budget
    lb = w * inertia
    if "momentum_norm" in integ.conserves:
        l0 = np.linalg.norm(lb[0])
        assert np.abs(np.linalg.norm(lb, axis=1) - l0).max() <= budget * l0
    if "space_momentum" in integ.conserves:
        ls = Q.rotate(Q.normalize(q), lb)
        assert np.abs(ls - ls[0]).max() <= budget * np.linalg.norm(ls[0])
    if "energy" in integ.conserves:
        e = 0.5 * (w * w * inertia).sum(1)
        assert np.abs(e - e[0]).max() <= budget * e[0]


def test_axis_rotation_kernel_matches_the_general_formulas():
    from ga_rotors import _kernels as K
    from ga_rotors.integrators._rigid import rotate_about

    q = tuple(Q0)
    L = (0.3, -1.2, 2.5)
    for axis in range(3):
        v = [0.0, 0.0, 0.0]
        v[axis] = 0.7
        r = K.quat_from_rotvec(tuple(v))
        q1, L1 = rotate_about(q, L, axis, 0.7)
        assert np.allclose(q1, K.qmul(q, r), rtol=0, atol=4 * EPS)
        assert np.allclose(L1, K.qrotate(K.qconj(r), L), rtol=0, atol=16 * EPS)


def test_dp8_uses_scipys_dop853_tableau():
    from scipy.integrate._ivp import dop853_coefficients as d

    from ga_rotors.integrators import dp8

    n = d.N_STAGES
    assert dp8.STAGES == n
    assert np.array_equal(np.array(dp8.A).reshape(n, n), d.A[:n, :n])
    assert np.array_equal(dp8.B, d.B) and np.array_equal(dp8.C, d.C[:n])


def test_dp8_observed_order_on_the_fast_spinner():
    # Order 8 gains 256× a halving, so between its pre-asymptotic regime and round-off there
    # is room for three halvings only on a problem with a large error constant: the fast
    # spinner (1000 rad/s). n = 360·2^k gave ratios 7.93, 8.00, 8.01; the finest error,
    # 5.3e-11, is a hundred times above round-off (~3e-13 rad from n = 8000). (From
    # n = 500, 4000 steps' 3.4e-12 is only ten times above it: that ratio read 8.19.)
    from ga_rotors.accuracy import cases, measure

    case = cases()["fast_spinner"]
    errors = [measure(case, "dp8", 360 * 2**k, repeats=1).error for k in range(4)]
    assert errors[-1] >= 1e-11
    observed = _observed(errors)
    assert np.all(np.abs(observed - 8) <= 0.15), observed


def test_dp8_round_off_floor_on_the_fast_spinner():
    # Each stage's and the update's weighted sum is formed first and added to the state
    # once. Adding the eight increments of the update one at a time rounded the state eight
    # times per step: against the 30-digit oracle the error was then 3.1e-12 and 7.8e-12
    # rad at n = 8000 and 11312 (past n = 8000 round-off dominates, and grows with n);
    # summed first, 2.9e-13 and 3.4e-13.
    from mp_oracle import integrate

    from ga_rotors.accuracy import cases
    from ga_rotors.accuracy.measuring import runner, sample_times

    case = cases()["fast_spinner"]
    times = sample_times(case)[1:]
    oracle = np.array(
        [[float(v) for v in y[:4]] for y in integrate(case.moments, case.q0, case.w0, times)]
    )
    for n in (8000, 11312):
        got = runner(case, "dp8", n)[0]().x[1:]
        assert np.max(Q.distance(oracle, Q.normalize(got))) < 6e-13, n
