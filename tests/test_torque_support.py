"""Integrators declare which torques they integrate at their order; torques declare whether
they read ω; a combination that would silently lose order is refused (or explicitly
accepted) in the Python API, in scenes and in the accuracy study."""

from __future__ import annotations

import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from _torques_for_tests import constant_body_torque, linear_damping

from ga_rotors import effects, simulate
from ga_rotors.errors import InputError, SceneError
from ga_rotors.integrators import (
    ANY_TORQUE,
    ORIENTATION_TORQUES,
    TORQUED,
    Problem,
    TorqueTerm,
    catalogue,
    get,
    torque_conflict,
)
from ga_rotors.reference.damped_top import DampedSymmetricTop
from ga_rotors.scene import load_scene

ROOT = Path(__file__).resolve().parent.parent

# A damped symmetric top: ω(t) is exact (reference/damped_top.py). c/I = 0.3 and 0.15, the
# wobble turns at (I⊥ − I₃) ω₃ / I⊥ = −2 rad/s: every term of the error expansion is O(1).
BODY, C, W0, T = (1.0, 1.0, 2.0), 0.3, (0.4, -0.3, 2.0), 2.0
Q0 = np.array([0.3, 0.1, 0.9, 0.2]) / math.sqrt(0.95)
DAMPING = TorqueTerm(effects.isotropic_damping, (C,))

ORIENTATION_ONLY = [c["name"] for c in catalogue() if c["torques"] == ORIENTATION_TORQUES]


def observed_orders(name, counts):
    """log₂ of successive ω-error ratios at T for the given step counts (damping accepted)."""
    exact = DampedSymmetricTop(BODY, C, Q0, W0).angular_velocity([T])[0]
    problem = Problem(BODY, (DAMPING,), accept_lower_order=True)
    errors = []
    for n in counts:
        run = get(name).run(problem, "quaternion", Q0, np.array(W0), 0.0, T / n, n, n)
        errors.append(np.abs(run.w[-1] - exact).max())
    errors = np.array(errors)
    assert errors.min() > 1e-11  # far above rounding (~1e-15 here): the ratios are real
    return np.log2(errors[:-1] / errors[1:])


def test_the_declarations():
    rows = {c["name"]: c for c in catalogue()}
    assert sorted(ORIENTATION_ONLY) == ["lgvi", "split2", "split4", "split4_yoshida", "split6"]
    assert rows["split_sym"]["torques"] == "none"  # free-only: no torqued step at all
    for name, row in rows.items():
        if name not in ORIENTATION_ONLY and TORQUED in row["problems"]:
            assert row["torques"] == ANY_TORQUE, name
    # Built-in effects know whether they read ω; a user kernel is assumed to.
    reads = {name: kind.reads_omega({"depends_on_omega": True}) for name, kind in
             effects.EFFECTS.items()}  # fmt: skip
    assert reads == {"gravity": False, "damping": True, "body_torque": False,
                     "space_torque": False, "user": True}  # fmt: skip
    assert TorqueTerm(linear_damping, (0.1,)).depends_on_omega is True
    with pytest.raises(InputError, match="depends_on_omega"):
        TorqueTerm(linear_damping, (0.1,), depends_on_omega="no")


@pytest.mark.parametrize("name", ORIENTATION_ONLY)
def test_orientation_only_methods_fall_to_order_one_with_damping(name):
    # The reason for the declaration: a kick L += h τ(q, ω) is not the exact flow of a
    # torque that reads ω, and the composition loses its symmetry. From n = 100 every ratio
    # is within 0.05 of 1 for all five (measured: 1.00–1.04); ±0.15 as in the order tests.
    orders = observed_orders(name, (100, 200, 400))
    assert np.all(np.abs(orders - 1.0) <= 0.15), orders
    assert get(name).order >= 2  # so this is a loss, not the declared order


@pytest.mark.parametrize(
    ("name", "counts"),
    [("rk4", (25, 50, 100)), ("cg3", (25, 50, 100)), ("midpoint", (25, 50, 100)),
     ("cf4", (25, 50, 100)), ("rkmk4", (25, 50, 100)), ("lie_euler", (200, 400, 800))],
)  # fmt: skip
def test_any_torque_methods_keep_their_order_with_damping(name, counts):
    # Runge–Kutta-type methods evaluate the whole vector field, torque included: with the
    # same damping they keep their declared order (measured ratios within 0.05 of it).
    orders = observed_orders(name, counts)
    assert get(name).torques == ANY_TORQUE
    assert np.all(np.abs(orders - get(name).order) <= 0.15), orders


def test_simulate_refuses_a_torque_that_reads_omega_naming_both():
    with pytest.raises(InputError, match=r"split2 \(order 2\).*'isotropic_damping' reads ω"):
        simulate(BODY, Q0, W0, duration=0.1, step=0.01, integrator="split2", torques=[DAMPING])
    # The same problem through Integrator.run, and a user kernel (which may read ω).
    user = TorqueTerm(constant_body_torque, (0.0, 0.0, 0.1))
    with pytest.raises(InputError, match=r"lgvi .*'constant_body_torque' reads ω"):
        get("lgvi").run(Problem(BODY, (user,)), "quaternion", Q0, W0, 0.0, 0.01, 10, 10)


def test_orientation_torques_and_explicit_acceptance_run():
    # A kernel that vouches for not reading ω is taken at full order: a constant body
    # torque is an exact kick, and split2 against a fine RK4 run (error ~1e-12, far below
    # split2's) shows order 2 (measured ratios within 0.02 of it).
    steady = TorqueTerm(constant_body_torque, (0.0, 0.0, 0.1), depends_on_omega=False)
    fine = simulate(BODY, Q0, W0, duration=1.0, step=1 / 800, torques=[steady]).w[-1]
    errors = [
        np.abs(simulate(BODY, Q0, W0, duration=1.0, step=1 / n, integrator="split2",
                        torques=[steady]).w[-1] - fine).max()
        for n in (20, 40, 80)
    ]  # fmt: skip
    assert np.all(np.abs(np.log2(np.array(errors[:-1]) / errors[1:]) - 2.0) <= 0.15), errors
    tr = simulate(BODY, Q0, W0, duration=0.1, step=0.01, integrator="split2",
                  torques=[DAMPING], accept_lower_order=True)  # fmt: skip
    assert tr.meta["paths"]["rotor"]["complete"]
    assert torque_conflict(get("rk4"), [DAMPING]) is None


SCENE = """
[body]
moments = [1.0, 1.0, 2.0]
[initial]
angular_velocity = {{ body = [0.4, -0.3, 2.0], units = "rad/s" }}
[time]
duration = 0.1
[integrator]
method = "split4"
step = 0.01
{extra}
[[effects]]
type = "{effect}"
{effect_keys}
"""


def _scene(tmp_path, effect="damping", effect_keys="coefficient = 0.3", extra=""):
    path = tmp_path / "damped.toml"
    path.write_text(SCENE.format(effect=effect, effect_keys=effect_keys, extra=extra))
    return path


def test_scene_refuses_at_integrator_method_naming_file_and_effect(tmp_path, tests_code):
    with pytest.raises(SceneError) as info:
        load_scene(_scene(tmp_path))
    text = str(info.value)
    assert "damped.toml: integrator.method: split4 (order 4)" in text, text
    assert "effects[0] (damping)" in text and "accept_lower_order" in text
    # Accepted explicitly, it loads and runs.
    scene = load_scene(_scene(tmp_path, extra="accept_lower_order = true"))
    assert scene.data["integrator"]["accept_lower_order"] is True
    # A user kernel is assumed to read ω unless its entry says otherwise.
    user = 'function = "_torques_for_tests:constant_body_torque"\nparams = [0.0, 0.0, 0.1]'
    with pytest.raises(SceneError, match=r"effects\[0\] \(user\)"):
        load_scene(_scene(tmp_path, "user", user))
    scene = load_scene(_scene(tmp_path, "user", user + "\ndepends_on_omega = false"))
    (term,) = scene.torques()
    assert term.depends_on_omega is False


def test_cli_run_reports_the_refusal(tmp_path):
    path = _scene(tmp_path)
    proc = subprocess.run(
        [sys.executable, "-m", "ga_rotors", "run", str(path)],
        cwd=ROOT, capture_output=True, text=True, timeout=120,
    )  # fmt: skip
    assert proc.returncode == 2
    assert proc.stderr.startswith("ga-rotors: error: ") and "integrator.method" in proc.stderr
    assert "Traceback" not in proc.stderr


def test_accuracy_study_offers_only_methods_that_keep_their_order():
    from dataclasses import dataclass

    from ga_rotors import accuracy

    heavy = accuracy.cases()["heavy_top"]  # gravity: every torqued method, splittings too
    assert set(ORIENTATION_ONLY) <= set(accuracy.methods_for(heavy))

    @dataclass(frozen=True)
    class Damped(accuracy.Case):
        @property
        def problem(self):
            return Problem(self.moments, (DAMPING,))

    damped = Damped("damped", "damped", BODY, tuple(Q0), W0, T, None)
    methods = accuracy.methods_for(damped)
    assert "rk4" in methods and not set(ORIENTATION_ONLY) & set(methods)
    refused = accuracy.measure(damped, "split2", 10, repeats=1)  # not run there, no crash
    assert refused.note.startswith("not run: ") and "split2" in refused.note
    assert refused.error == np.inf


def test_docs_catalogue_table_states_each_methods_torques():
    text = (ROOT / "docs" / "accuracy.md").read_text()
    rows = {c["name"]: c["torques"] for c in catalogue()}
    seen = set()
    for line in text.splitlines():
        cells = [c.strip() for c in line.replace("\\|", "¦").split("|")[1:-1]]
        if len(cells) == 3 and cells[0].startswith("`"):
            for name in (n.strip(" `") for n in cells[0].split(",")):
                if name in rows:
                    assert cells[1].split(" (")[0] == rows[name], (name, cells[1])
                    seen.add(name)
    assert seen == set(rows)
