"""Integrator.run's one compiled call (step limit, loop and watch in the generated module's
``judged_run``) gives what the general path gives: the same samples bit for bit, the same
verdicts on the step limit, the same refusals of bad input with the same words."""

from __future__ import annotations

import warnings

import numpy as np
import pytest
from _torques_for_tests import constant_body_torque, constant_omega
from hypothesis import given, settings
from hypothesis import strategies as st

from ga_rotors.errors import InputError, StepLimitWarning
from ga_rotors.integrators import (
    KINEMATIC,
    PrescribedOmega,
    Problem,
    TemplateIntegrator,
    TorqueTerm,
    _runner,
    catalogue,
    get,
    loops,
)
from ga_rotors.integrators.limits import WATCH_GROWTH, StepLimit, watch_candidates
from ga_rotors.integrators.rk4 import rk4_step

BODY = (1.0, 2.0, 3.0)
Q0 = np.array([0.5, 0.5, 0.5, 0.5])
W0 = np.array([1.0, 0.5, 0.2])
TEMPLATED = [c["name"] for c in catalogue() if isinstance(get(c["name"]), TemplateIntegrator)]
DYNAMIC = [name for name in TEMPLATED if set(get(name).problems) - {KINEMATIC}]
MEASURED = [name for name in DYNAMIC if get(name).step_limit is not None]


def _general(method, problem, path, x0, w0, h, nsteps, every):
    """The same run by the general path: the step limit judged in Python
    (Integrator.check_step), the loop called chunk by chunk with progress."""
    return method.run(problem, path, x0, w0, 0.0, h, nsteps, every, progress=lambda done: None)


def _same(a, b):
    assert a.complete == b.complete and a.source == b.source
    for name in ("t", "x", "w", "stats"):
        assert np.array_equal(getattr(a, name), getattr(b, name)), name


@pytest.mark.parametrize("name", DYNAMIC)
def test_the_one_call_gives_the_general_paths_samples_bit_for_bit(name):
    method, problem = get(name), Problem(BODY)
    fast = method.run(problem, "quaternion", Q0, W0, 0.0, 1e-3, 37, 5)
    _same(fast, _general(method, problem, "quaternion", Q0, W0, 1e-3, 37, 5))
    _same(fast, method.run(problem, "quaternion", Q0, W0, 0.0, 1e-3, 37, 5, where=None))


@pytest.mark.parametrize(
    "problem, path, w0",
    [
        (Problem(BODY), "euler", W0),  # a path with watch statistics (copied per run)
        (Problem(BODY, (TorqueTerm(constant_body_torque, (0.1, 0.0, 0.3)),)), "rotor", W0),
        (Problem(omega=PrescribedOmega(constant_omega, (0.0, 0.0, 2.0))), "quaternion", None),
    ],
    ids=["euler", "torqued", "kinematic"],
)
def test_every_problem_kind_and_path_agrees_with_the_general_path(problem, path, w0):
    x0 = np.array([0.3, 0.4, 0.5]) if path == "euler" else Q0
    fast = get("rk4").run(problem, path, x0, w0, 0.0, 1e-3, 40, 7)
    _same(fast, _general(get("rk4"), problem, path, x0, w0, 1e-3, 40, 7))


@pytest.mark.parametrize(
    "x0, w0",
    [
        ((0.5, 0.5, 0.5, 0.5), (1.0, 0.5, 0.2)),  # tuples
        (Q0.astype(np.float32), W0.astype(np.float32)),
        (np.repeat(Q0, 2)[::2], np.repeat(W0, 2)[::2]),  # strided views
        (np.frombuffer(Q0.tobytes()), np.frombuffer(W0.tobytes())),  # read-only arrays
        ([1, 0, 0, 0], [0, 0, 2]),  # integers
    ],
    ids=["tuples", "float32", "strided", "read-only", "integers"],
)
def test_states_of_any_numeric_form_run_as_their_float64_values(x0, w0):
    method, problem = get("rk4"), Problem(BODY)
    expected = method.run(
        problem, "quaternion", np.asarray(x0, dtype=np.float64),
        np.asarray(w0, dtype=np.float64), 0.0, 1e-3, 20, 20,
    )  # fmt: skip
    _same(method.run(problem, "quaternion", x0, w0, 0.0, 1e-3, 20, 20), expected)


@pytest.mark.parametrize(
    "args, message",
    [
        (((1.0, 0.0, 0.0), W0, 10, 1), r"x0: expected shape \(4,\), got \(3,\)"),
        ((Q0, (1.0, 2.0), 10, 1), r"w0: expected shape \(3,\), got \(2,\)"),
        ((np.eye(4), W0, 10, 1), r"x0: expected shape \(4,\), got \(4, 4\)"),
        ((Q0, W0, 0, 1), "nsteps: expected a positive integer, got 0"),
        ((Q0, W0, 10.0, 1), "nsteps: expected a positive integer, got 10.0"),
        ((Q0, W0, 10, 0), "every: expected a positive integer, got 0"),
    ],
    ids=["x0 size", "w0 size", "x0 matrix", "no steps", "float steps", "every 0"],
)
def test_bad_input_gets_the_same_line_on_both_paths(args, message):
    method, problem = get("rk4"), Problem(BODY)
    x0, w0, nsteps, every = args
    with pytest.raises(InputError, match=message):
        method.run(problem, "quaternion", x0, w0, 0.0, 1e-3, nsteps, every)
    with pytest.raises(InputError, match=message):
        _general(method, problem, "quaternion", x0, w0, 1e-3, nsteps, every)


def test_run_past_the_limit_warns_once_and_returns_the_unjudged_run():
    # 1000 steps at h|ω| = 1 on the fast spinner: far past rk4's limit
    method, problem, w0 = get("rk4"), Problem(BODY), (5.0, 3.0, 1000.0)
    with pytest.warns(StepLimitWarning, match="h: rk4 cannot step") as caught:
        fast = method.run(problem, "quaternion", Q0, w0, 0.0, 1e-3, 1000, 100)
    assert len(caught) == 1 and caught[0].filename == __file__
    _same(fast, method.run(problem, "quaternion", Q0, w0, 0.0, 1e-3, 1000, 100, where=None))


def test_lgvi_past_its_limit_is_refused_before_any_step():
    with pytest.raises(InputError, match=r"h: lgvi cannot step h·\|ω\| = 2 \(limit 1\)"):
        get("lgvi").run(Problem(BODY), "quaternion", Q0, (0.0, 0.0, 200.0), 0.0, 0.01, 5, 1)


def _plain_limit(inertia, w, h, nsteps):
    """A user's step limit in plain Python (no compiled measure): h|ω| < 0.5."""
    value = h * float(np.linalg.norm(w))
    return StepLimit("h·|ω|", value, 0.5, lambda: "too coarse for this test")


def test_a_plain_python_limit_is_judged_before_the_run():
    mine = TemplateIntegrator(
        name="rk4_plain_limit", order=4, description="rk4 with a plain Python limit",
        conserves=(), paths=("quaternion",), steps={"free": rk4_step},
        step_limit=_plain_limit, evaluations=4,
    )  # fmt: skip
    with pytest.warns(StepLimitWarning, match="h: rk4_plain_limit cannot step h·|ω| = 1"):
        mine.run(Problem(BODY), "quaternion", Q0, (0.0, 0.0, 10.0), 0.0, 0.1, 3, 1)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        mine.run(Problem(BODY), "quaternion", Q0, (0.0, 0.0, 1.0), 0.0, 0.1, 3, 1)


_rate = st.floats(-300.0, 300.0)
_moment = st.floats(0.05, 20.0)


@settings(max_examples=60, deadline=None)
@given(
    st.sampled_from(MEASURED),
    st.tuples(_moment, _moment, _moment),
    st.tuples(_rate, _rate, _rate),
    st.floats(1e-5, 0.05),
    st.integers(1, 3000),
)
def test_the_compiled_verdict_is_the_step_limits_own_numbers(name, inertia, w0, h, nsteps):
    # The generated module's limit (judged_run's value and bound) against the StepLimit the
    # integrator's step_limit builds in Python: the same kernel, so the same bits.
    method, problem = get(name), Problem(inertia)
    if name == "split_sym" or nsteps > 50:  # keep each example's run short
        nsteps = min(nsteps, 50)
    prep = _runner.prepared(method, problem, "quaternion", checked=True)
    _, value, bound, _ = _runner.run_prepared(prep, Q0, w0, 0.0, h, nsteps, nsteps, loops.JUDGE)
    expected = method.step_limit(inertia, w0, h, nsteps)
    assert (value, bound) == (expected.value, expected.limit)


def _candidates_oracle(w, inertia):
    """watch_candidates in numpy: the new highs of |ω|² and |L|², kept where their level
    floor(log(size) / (2 ln WATCH_GROWTH)) passes the previous high's."""
    w = np.asarray(w, dtype=float)
    marked = np.zeros(len(w), dtype=bool)
    for size in (np.sum(w * w, axis=1), np.sum((w * inertia) ** 2, axis=1)):
        high = np.maximum.accumulate(size)
        records = np.concatenate([[0], 1 + np.flatnonzero(size[1:] > high[:-1])])
        with np.errstate(divide="ignore"):
            level = np.floor(np.log(size[records]) * (0.5 / np.log(WATCH_GROWTH)))
        new = np.concatenate([[np.isfinite(level[0])], level[1:] > level[:-1]])
        marked[records[new]] = True
    return np.flatnonzero(marked).tolist()


@settings(max_examples=100, deadline=None)
@given(st.lists(st.tuples(_rate, _rate, _rate), min_size=1, max_size=40))
def test_watch_candidates_are_the_new_highs_of_omega_and_momentum(rows):
    assert watch_candidates(np.array(rows), BODY).tolist() == _candidates_oracle(rows, BODY)


@pytest.mark.parametrize(
    "rows",
    [
        [[0.0, 0.0, 0.0], [0.0, 0.0, 1.0]],  # at rest first: no level, then one
        [[0.0, 0.0, 1.0], [0.0, 0.0, np.nan], [0.0, 0.0, 5.0]],  # NaN ends the highs
        [[0.0, 0.0, np.inf], [0.0, 0.0, 1.0]],  # an infinite first sample is no level
        [[0.0, 0.0, 1.0]] * 5,  # constant: the first sample only
    ],
    ids=["from rest", "nan", "inf", "constant"],
)
def test_watch_candidates_named_cases(rows):
    with np.errstate(invalid="ignore"):
        expected = _candidates_oracle(rows, BODY)
    assert watch_candidates(np.array(rows), BODY).tolist() == expected


def test_the_fused_watch_finds_the_sample_watch_step_warns_about():
    # A constant torque spins the body up past rk4's limit during the run.
    torque = TorqueTerm(constant_body_torque, (0.0, 0.0, 30.0), depends_on_omega=False)
    method, problem = get("rk4"), Problem((1.0, 1.5, 2.0), (torque,))
    prep = _runner.prepared(method, problem, "quaternion", checked=True)
    result, value, bound, crossing = _runner.run_prepared(
        prep, Q0, (0.0, 0.0, 10.0), 0.0, 0.01, 2000, 10, prep.flags | loops.WATCH
    )
    assert value < bound and crossing > 0
    with pytest.warns(StepLimitWarning, match="crosses its step limit"):
        found = method.watch_step(problem, result.t, result.w, 0.01, 2000)
    assert found[0] == result.t[crossing]


# ---------------------------------------------------------------------------- simulate


def test_simulate_takes_arrays_and_sequences_to_the_same_bits():
    from ga_rotors import simulate

    kw = {"duration": 0.05, "step": 1e-3, "paths": ("quaternion", "rotor"), "sample_every": 7}
    a = simulate(BODY, Q0, W0, **kw)
    b = simulate(list(BODY), Q0.tolist(), W0.tolist(), **kw)
    assert a.names == b.names and a.meta == b.meta
    for name in a.names:
        assert np.array_equal(a[name], b[name]), name


@pytest.mark.parametrize(
    "orientation, angular_velocity, message",
    [
        ([np.nan, 0, 0, 1], W0, r"orientation: contains nan at index \(0,\)"),
        ([1.0, 0, np.inf, 0], W0, r"orientation: contains inf at index \(2,\)"),
        ([2.0, 0, 0, 0], W0, "orientation: expected unit quaternions"),
        ([1.0, 0, 0], W0, r"orientation: expected an array of shape \(\.\.\., 4\)"),
        (Q0, [1.0, np.nan, 0], r"angular_velocity: contains nan at index \(1,\)"),
        (Q0, [1.0, 2.0], r"angular_velocity: expected an array of shape \(\.\.\., 3\)"),
    ],
)
def test_simulate_refuses_bad_arrays_as_it_refuses_bad_lists(
    orientation, angular_velocity, message
):
    from ga_rotors import simulate

    for q, w in (
        (orientation, angular_velocity),
        (np.array(orientation, dtype=float), np.array(angular_velocity, dtype=float)),
    ):
        with np.errstate(invalid="ignore"), pytest.raises(InputError, match=message):
            simulate(BODY, q, w, duration=0.01, step=1e-3)


def test_what_simulate_remembers_never_lets_a_bad_argument_pass_twice():
    from ga_rotors import simulate

    for _ in range(2):
        with pytest.raises(InputError, match="does not divide"):
            simulate(BODY, Q0, W0, duration=1.0, step=0.3)
        with pytest.raises(InputError, match="triangle inequality"):
            simulate((1.0, 1.0, 3.0), Q0, W0, duration=0.01, step=1e-3)
        with pytest.raises(InputError, match="duration: expected a number"):
            simulate(BODY, Q0, W0, duration=True, step=1e-3)


@pytest.mark.parametrize("t0", [0.0, -0.0, 0.37, -2.5])
@pytest.mark.parametrize("every", [1, 3, 7])
@pytest.mark.parametrize("progress", [None, lambda done, total: None], ids=["one call", "chunks"])
@pytest.mark.parametrize("method", ["rk4", "dop853"])
def test_simulates_times_are_the_grid_t0_plus_k_h(t0, every, progress, method):
    from ga_rotors import simulate

    h, n = 1e-3, 20
    tr = simulate(BODY, Q0, W0, duration=n * h, step=h, sample_every=every, t0=t0,
                  paths="quaternion", progress=progress, integrator=method)  # fmt: skip
    k = np.concatenate([np.arange(0, n + 1, every), [n] if n % every else []])
    assert np.array_equal(tr.t, t0 + h * k)
    assert np.signbit(tr.t[0]) == (t0 < 0)  # -0.0 starts at +0.0, as the grid does


def test_simulates_step_limit_warnings_point_at_its_caller():
    from ga_rotors import simulate
    from ga_rotors.effects import body_torque

    with pytest.warns(StepLimitWarning, match="rk4 cannot step") as past:
        simulate(BODY, Q0, (5.0, 3.0, 1000.0), duration=1.0, step=1e-3, paths="quaternion")
    spin = TorqueTerm(body_torque, (0.0, 0.0, 30.0), depends_on_omega=False)
    with pytest.warns(StepLimitWarning, match="rk4 crosses its step limit") as crossing:
        simulate((1.0, 1.5, 2.0), Q0, (0.0, 0.0, 10.0), duration=20.0, step=0.01,
                 paths="quaternion", torques=[spin], sample_every=10)  # fmt: skip
    assert [w.filename for w in (*past, *crossing)] == [__file__, __file__]
