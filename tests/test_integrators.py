"""The integrator interface: registry, code generation, torques, caching, RK4's order."""

from __future__ import annotations

import math
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest
from _torques_for_tests import (
    constant_body_torque,
    constant_omega,
    counting_torque,
    linear_damping,
    wobble,
)

from ga_rotors import _kernels as K
from ga_rotors.errors import InputError
from ga_rotors.integrators import (
    FREE,
    KINEMATIC,
    MOTION,
    TORQUED,
    PrescribedOmega,
    Problem,
    TemplateIntegrator,
    TorqueTerm,
    _cache,
    _runner,
    _source,
    catalogue,
    get,
    names,
)
from ga_rotors.integrators.slots import TemplateSlotError, torque

ROOT = Path(__file__).resolve().parent.parent
DISK = (0.0028125, 0.0028125, 0.005625)
IDENTITY = np.array([1.0, 0.0, 0.0, 0.0])


def test_registry_lists_rk4_with_its_declarations():
    assert {"rk4", "rk4_renorm"} <= set(names())
    rows = {r["name"]: r for r in catalogue()}
    assert rows["rk4"]["order"] == 4 and rows["rk4"]["conserves"] == []
    assert rows["rk4"]["problems"] == sorted([FREE, TORQUED, KINEMATIC, MOTION])
    assert rows["rk4"]["paths"] == ["euler", "motor", "quaternion", "rotor"]
    assert rows["rk4_renorm"]["conserves"] == ["unit_norm"]
    with pytest.raises(InputError, match="unknown integrator 'nope'"):
        get("nope")


def test_template_slots_refuse_to_run_uninstantiated():
    from ga_rotors.integrators.rk4 import rk4_step

    with pytest.raises(TemplateSlotError, match="template slot 'o_rate'"):
        rk4_step(0.0, (1.0, 0.0, 0.0, 0.0), (0.0, 0.0, 1.0), 0.1, DISK, np.zeros(0))


def test_free_module_has_no_torque_at_all():
    text = _source.source(get("rk4"), Problem(DISK), "quaternion")[0]
    assert "torque" not in text
    assert "free_euler_rates(inertia, w)" in text
    spec = _cache.specialise(get("rk4"), Problem(DISK), "quaternion")
    assert not hasattr(spec.module, "torque")


def test_only_declared_torques_enter_the_source():
    problem = Problem(DISK, (TorqueTerm(counting_torque, (0.0, 0.0, 0.0, 0.0)),))
    text = _source.source(get("rk4"), problem, "rotor")[0]
    assert "counting_torque" in text
    assert "tripwire_torque" not in text and "constant_body_torque" not in text
    two = Problem(
        DISK,
        (TorqueTerm(constant_body_torque, (1.0, 2.0, 3.0)), TorqueTerm(linear_damping, (0.5,))),
    )
    text = _source.source(get("rk4"), two, "rotor")[0]
    assert "params[0:3]" in text and "params[3:4]" in text


def test_declared_torque_runs_exactly_once_per_stage():
    # Call the compiled loop directly with our own params array, so the kernel's
    # evaluation counter (params[0]) can be read back: RK4 evaluates f four times a step.
    problem = Problem(DISK, (TorqueTerm(counting_torque, (0.0, 0.0, 0.0, 0.0)),))
    spec = _cache.specialise(get("rk4"), problem, "quaternion")
    params = np.zeros(4)
    n = 250
    out_t, out_x, out_w = np.empty(n + 1), np.empty((n + 1, 4)), np.empty((n + 1, 3))
    rows = spec.module.loop(
        IDENTITY, np.array([0.1, 0.2, 3.0]), 0.0, 1e-3, 0, n, 1, DISK, params,
        out_t, out_x, out_w, np.zeros(0),
    )  # fmt: skip
    assert rows == n + 1
    assert params[0] == 4 * n


def test_undeclared_torque_is_never_evaluated_uncompiled(tmp_path):
    # Uncompiled (NUMBA_DISABLE_JIT=1) the generated module is plain Python, so a tripwire
    # kernel that raises would surface; it is registered as a valid kernel but declared
    # nowhere, and the declared kernel's calls are counted.
    script = textwrap.dedent(
        """
        import numpy as np
        import _torques_for_tests as T
        from ga_rotors.integrators import Problem, TorqueTerm, get
        from ga_rotors.integrators import _cache

        TorqueTerm(T.tripwire_torque)            # a valid kernel: only undeclared
        problem = Problem((1.0, 2.0, 3.0), (TorqueTerm(T.counting_torque, (0, 0, 0, 0)),))
        spec = _cache.specialise(get("rk4"), problem, "rotor")
        params = np.zeros(4)
        out = np.empty(6), np.empty((6, 4)), np.empty((6, 3))
        rows = spec.module.loop(np.array([1.0, 0, 0, 0]), np.array([0.1, 0.2, 0.3]), 0.0, 0.01, 0,
                         5, 1, (1.0, 2.0, 3.0), params, *out, np.zeros(0))
        free = _cache.specialise(get("rk4"), Problem((1.0, 2.0, 3.0)), "rotor")
        free.module.loop(np.array([1.0, 0, 0, 0]), np.array([0.1, 0.2, 0.3]), 0.0, 0.01, 0, 5,
                  1, (1.0, 2.0, 3.0), np.zeros(0), *out, np.zeros(0))
        print(rows, int(params[0]), hasattr(free.module, "torque"))
        """
    )
    env = {
        **os.environ,
        "NUMBA_DISABLE_JIT": "1",
        "GA_ROTORS_CACHE_DIR": str(tmp_path),
        "PYTHONPATH": os.pathsep.join([str(ROOT), str(ROOT / "tests")]),
    }
    proc = subprocess.run(
        [sys.executable, "-c", script], env=env, capture_output=True, text=True, timeout=120
    )
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.split() == ["6", "20", "False"]


def test_constant_axial_torque_spins_up_exactly():
    # ω3(t) = ω3(0) + τ t / I3 is quadratic-free (linear in t): RK4 integrates it exactly,
    # up to the rounding of 1000 additions (~1000 ulp of 10 rad/s ≈ 2e-12).
    tau, h, n = 0.01, 1e-3, 1000
    problem = Problem(DISK, (TorqueTerm(constant_body_torque, (0.0, 0.0, tau)),))
    r = get("rk4").run(problem, "rotor", IDENTITY, np.array([0.0, 0.0, 2.0]), 0.0, h, n, 10)
    expected = 2.0 + tau * r.t / DISK[2]
    assert np.max(np.abs(r.w[:, 2] - expected)) <= 1000 * np.spacing(expected.max())
    assert np.all(r.w[:, :2] == 0.0)


def test_damping_torque_decays_like_the_exponential():
    # ω̇ = -(c/I) ω on the symmetry axis: RK4's global error for e^{-λt} is
    # T λ (hλ)⁴/120 relative; λ = c/I3 = 17.8/s, h = 1e-3 -> ~1.5e-9 at T = 1.
    c = 0.1
    lam = c / DISK[2]
    problem = Problem(DISK, (TorqueTerm(linear_damping, (c,)),))
    r = get("rk4").run(problem, "quaternion", IDENTITY, np.array([0.0, 0.0, 5.0]), 0.0, 1e-3,
                       1000, 100)  # fmt: skip
    rel = np.abs(r.w[:, 2] / (5.0 * np.exp(-lam * r.t)) - 1.0)
    bound = r.t * lam * (1e-3 * lam) ** 4 / 120
    assert np.all(rel <= 2.0 * bound + 1e-14)


def _exact_constant_rotation(w, t):
    return np.array([K.quat_from_rotvec(tuple(np.asarray(w) * ti)) for ti in t])


@pytest.mark.parametrize("path", ["rotor", "quaternion"])
def test_rk4_kinematic_order_is_four(path):
    # q̇ = ½ q ⊗ (0, ω), ω constant: eigenvalues ±i|ω|/2, so the global error is
    # ≈ T (|ω|/2)(h|ω|/2)⁴/120 and halving h divides it by 16 (log2 ratio 4).
    w = np.array([0.3, -1.1, 2.5])
    omega = PrescribedOmega(constant_omega, tuple(w))
    from ga_rotors.paths import get as get_path

    errors = []
    for n in (50, 100, 200, 400):
        h = 2.0 / n
        x0 = get_path(path).load().initial_state(IDENTITY)
        r = get("rk4").run(Problem(omega=omega), path, x0, None, 0.0, h, n, n)
        q = get_path(path).load().quaternions(r.x[-1])
        errors.append(K.geodesic_angle(tuple(q), tuple(_exact_constant_rotation(w, [2.0])[0])))
    orders = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert np.all(np.abs(orders - 4.0) < 0.1), orders


def test_kinematic_loop_records_the_prescribed_omega():
    omega = PrescribedOmega(wobble, (0.2, 3.0, 10.0))
    r = get("rk4").run(Problem(omega=omega), "quaternion", IDENTITY, None, 0.0, 1e-3, 100, 25)
    expected = np.stack(
        [0.2 * np.cos(3.0 * r.t), 0.2 * np.sin(3.0 * r.t), np.full_like(r.t, 10.0)], axis=1
    )
    assert np.array_equal(r.w, expected)
    assert r.t.tolist() == [0.0, 0.025, 0.05, 0.075, 0.1]


def test_renormalised_rk4_keeps_unit_norm_to_roundoff():
    w0 = np.array([3.0, 0.01, 0.2])
    r = get("rk4_renorm").run(Problem((1.0, 2.0, 3.0)), "rotor", IDENTITY, w0, 0.0, 0.01,
                              2000, 1)  # fmt: skip
    # one normalisation leaves | |x| - 1 | within a few ulp (sqrt and 4 divisions)
    assert np.max(np.abs(np.linalg.norm(r.x, axis=1) - 1.0)) <= 4 * np.finfo(float).eps


def test_unsupported_combinations_are_refused():
    with pytest.raises(InputError, match="cannot step the 'euler' path"):
        get("rk4_renorm").check(Problem(DISK), "euler")
    with pytest.raises(InputError, match="expected a compiled kernel defined at module level"):
        TorqueTerm(lambda t, q, w, p: (0.0, 0.0, 0.0))
    with pytest.raises(InputError, match="expected signature kernel\\(t, p\\)"):
        PrescribedOmega(constant_body_torque)
    with pytest.raises(InputError, match="parameters must be finite"):
        TorqueTerm(constant_body_torque, (1.0, math.nan, 0.0))


def _bad_step(t, x, w, h, inertia, params):
    return x, torque_like(w)  # noqa: F821 - deliberately unresolvable


def test_template_with_an_unresolvable_global_fails_in_one_line():
    bad = TemplateIntegrator(
        name="bad", order=1, description="", conserves=frozenset(),
        paths=frozenset({"quaternion"}), steps={FREE: _bad_step}, evaluations=1,
    )  # fmt: skip
    says = "template _bad_step of bad: 'torque_like' is not defined in its module test_integrators"
    with pytest.raises(InputError, match=says):  # generation never guesses
        _source.source(bad, Problem(DISK), "quaternion")
    with pytest.raises(InputError, match=says):
        bad.run(Problem(DISK), "quaternion", IDENTITY, np.zeros(3), 0.0, 0.1, 1, 1)


def _helper_not_declared(w):
    return (w[0], w[1], w[2])


def _step_with_a_missing_helper(t, x, w, h, inertia, params):
    return x, _helper_not_declared(w)


def test_a_template_calling_a_helper_missing_from_helpers_is_one_line():
    # Before, numba's 35-line TypingError ("Untyped global name ..."), at the first run.
    mine = TemplateIntegrator(
        name="missing_helper", order=1, description="", conserves=frozenset(),
        paths=frozenset({"quaternion"}), steps={FREE: _step_with_a_missing_helper},
        evaluations=1,
    )  # fmt: skip
    with pytest.raises(InputError) as caught:
        mine.run(Problem(DISK), "quaternion", IDENTITY, np.zeros(3), 0.0, 0.1, 1, 1)
    message = str(caught.value)
    assert message == (
        "template _step_with_a_missing_helper of missing_helper calls _helper_not_declared, "
        "a plain Python function that is not among its helpers: add _helper_not_declared to "
        "helpers= (or compile it as a kernel)"
    )
    declared = TemplateIntegrator(
        name="declared_helper", order=1, description="", conserves=frozenset(),
        paths=frozenset({"quaternion"}), steps={FREE: _step_with_a_missing_helper},
        helpers=(_helper_not_declared,), evaluations=1,
    )  # fmt: skip
    text = _source.source(declared, Problem(DISK), "quaternion")[0]
    assert "def _helper_not_declared(w):" in text


def test_state_that_stops_being_finite_ends_the_run_early():
    # Euler-angle path started exactly at θ = 0 with ω₂ sin φ − ω₁ cos φ ≠ 0: ψ̇ = x/0.
    r = get("rk4").run(Problem(DISK), "euler", np.zeros(3), np.array([0.1, 0.2, 15.0]), 0.0,
                       1e-3, 100, 1)  # fmt: skip
    assert not r.complete
    assert np.isfinite(r.x).all() and np.isfinite(r.w).all()
    assert r.t.tolist() == [0.0]


def test_unwritable_cache_falls_back_to_the_next_directory(tmp_path, monkeypatch):
    # A regular file where the directory should be cannot be written into, even by root.
    blocker = tmp_path / "file"
    blocker.write_text("not a directory")
    good = tmp_path / "ok" / "generated"
    monkeypatch.setattr(_cache, "_candidates", lambda: [blocker / "generated", good])
    _cache.cache_location.cache_clear()
    try:
        assert _cache.cache_location() == good
    finally:
        _cache.cache_location.cache_clear()


def test_cache_falls_back_to_memory_when_nothing_is_writable(tmp_path, monkeypatch):
    blocker = tmp_path / "file"
    blocker.write_text("not a directory")
    monkeypatch.setattr(_cache, "_candidates", lambda: [blocker / "generated"])
    monkeypatch.setattr(_cache, "_MEMO", {})
    _cache.cache_location.cache_clear()
    try:
        assert _cache.cache_location() is None
        problem = Problem(omega=PrescribedOmega(constant_omega, (0.0, 0.0, 1.0)))
        spec = _cache.specialise(get("rk4"), problem, "quaternion")
        assert spec.path is None and "cache=False" in spec.source
        r = get("rk4").run(problem, "quaternion", IDENTITY, None, 0.0, 0.5, 2, 1)
        assert r.source is None and r.complete
    finally:
        _cache.cache_location.cache_clear()


def test_generated_file_is_named_by_content_and_written_once(tmp_path, monkeypatch):
    monkeypatch.setattr(_cache, "_candidates", lambda: [tmp_path / "generated"])
    monkeypatch.setattr(_cache, "_MEMO", {})
    _cache.cache_location.cache_clear()
    try:
        problem = Problem(omega=PrescribedOmega(constant_omega, (0.0, 0.0, 1.0)))
        spec = _cache.specialise(get("rk4"), problem, "rotor")
        assert spec.path.parent == tmp_path / "generated"
        assert spec.path.read_text() == spec.source
        before = spec.path.stat().st_mtime_ns
        _cache._write_once(spec.path, spec.source)  # identical: untouched (numba keys on mtime)
        assert spec.path.stat().st_mtime_ns == before
        assert [p.name for p in spec.path.parent.iterdir() if p.name.startswith(".")] == []
    finally:
        _cache.cache_location.cache_clear()


def test_vector_field_is_the_loops_right_hand_side():
    from ga_rotors._kernels import euler_rates
    from ga_rotors.kinematics import quaternion_rate

    tau = (0.01, -0.02, 0.005)
    problem = Problem(DISK, (TorqueTerm(constant_body_torque, tau),))
    f = _runner.vector_field(problem, "quaternion")
    q = np.array([0.9, 0.1, -0.3, 0.2])
    q /= np.linalg.norm(q)
    w = np.array([0.3, -1.0, 15.0])
    got = f(0.5, np.concatenate([q, w]))
    assert np.allclose(got[:4], quaternion_rate(q, w), rtol=0, atol=1e-15)
    assert np.allclose(got[4:], euler_rates(DISK, tuple(w), tau), rtol=1e-15, atol=0)
    free = _runner.vector_field(Problem(DISK), "rotor")
    assert "torque" not in _cache.specialise(None, Problem(DISK), "rotor", "rhs").source
    assert free(0.0, np.array([1.0, 0, 0, 0, 0, 0, 2.0])).tolist() == [0, -1.0, 0, 0, 0, 0, 0]
    kin = _runner.vector_field(Problem(omega=PrescribedOmega(wobble, (0.2, 3.0, 10.0))), "euler")
    assert kin(0.0, np.array([0.0, 0.5, 0.0])).shape == (3,)
    with pytest.raises(InputError, match="y: expected shape \\(7,\\)"):
        f(0.0, np.zeros(4))


def test_scipy_dop853_on_the_vector_field_reaches_the_exact_top():
    from scipy.integrate import solve_ivp

    from ga_rotors.reference.symmetric_top import SymmetricTop

    w0 = np.array([0.1, 0.0, 15.0])
    f = _runner.vector_field(Problem(DISK), "quaternion")
    sol = solve_ivp(f, (0.0, 1.0), [*IDENTITY, *w0], method="DOP853", rtol=1e-12, atol=1e-13)
    q = sol.y[:4, -1] / np.linalg.norm(sol.y[:4, -1])
    err = SymmetricTop(DISK, IDENTITY, w0).orientation_error([1.0], q[None, :])
    assert err[0] < 1e-9  # DOP853's error at rtol 1e-12 over 15 rad of turning


def test_a_problem_of_an_unregistered_kind_is_refused_in_one_line():
    with pytest.raises(InputError, match="kind: unknown problem kind 'nope'; expected one of"):
        get("rk4").run(Problem(DISK, kind="nope"), "quaternion", IDENTITY, np.zeros(3), 0.0,
                       0.1, 1, 1)  # fmt: skip
    with pytest.raises(InputError, match="kind: these arguments make a 'free' problem"):
        Problem(DISK, kind=KINEMATIC)


def test_a_kind_that_lacks_a_slot_its_step_calls_is_refused_in_one_line():
    # a free step that calls torque(), which only a torqued problem's kind generates
    from ga_rotors.integrators.kinds import KINDS

    assert "torque" not in KINDS[FREE].slots
    mine = TemplateIntegrator(
        name="torque_on_free", order=1, description="", conserves=frozenset(),
        paths=frozenset({"quaternion"}), steps={FREE: _calls_torque}, evaluations=1,
    )  # fmt: skip
    with pytest.raises(InputError, match="its free step calls torque\\(\\), which free "
                                         "problems do not have"):  # fmt: skip
        _source.source(mine, Problem(DISK), "quaternion")


def _calls_torque(t, x, w, h, inertia, params):
    return x, torque(t, x, w, params)
