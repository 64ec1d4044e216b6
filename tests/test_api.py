"""The public API (issue 10): one import, one ``simulate``, trajectories that cannot be
misread, a scene layer that computes each derived value once, errors that carry their key.
Each test is one trap a new user fell into."""

from __future__ import annotations

import ast
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.spatial.transform import Rotation

import ga_rotors as gr
from ga_rotors import quaternion

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "ga_rotors"


# ------------------------------------------------------------------ one import away


def test_import_ga_rotors_loads_nothing_heavy():
    code = (
        "import sys, ga_rotors\n"
        "heavy = [m for m in ('numpy', 'numba', 'clifford', 'scipy', 'sympy', 'matplotlib')"
        " if m in sys.modules]\n"
        "print(heavy, sorted(m for m in sys.modules if m.startswith('ga_rotors')))"
    )
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    out = subprocess.run(
        [sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True
    ).stdout
    assert out.strip() == "[] ['ga_rotors']"


def test_every_public_name_resolves_and_is_listed():
    assert set(gr.__all__) <= set(dir(gr))
    for name in gr.__all__:
        assert getattr(gr, name) is not None, name
    with pytest.raises(AttributeError, match="no attribute 'simulat'"):
        _ = gr.simulat


def test_there_is_one_public_simulate():
    # The scene runner is run_scene; no other public module defines a function `simulate`.
    definers = []
    for path in PACKAGE.rglob("*.py"):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in tree.body:
            if isinstance(node, ast.FunctionDef) and node.name == "simulate":
                definers.append(path.relative_to(ROOT).as_posix())
    assert definers == ["ga_rotors/simulation.py"]
    from ga_rotors.simulation import simulate

    assert gr.simulate is simulate and callable(gr.simulate)


def test_importing_the_module_does_not_shadow_the_function():
    # A submodule import sets the package attribute of its name: none may be a public function.
    import ga_rotors.scene.run
    import ga_rotors.simulation

    assert callable(gr.simulate) and callable(gr.run_scene)
    import ga_rotors.scene as scene
    import ga_rotors.scene.summary  # noqa: F401

    assert callable(scene.report) and callable(scene.run_scene)


# ------------------------------------------------------------------ the misread R


def _oracle(moments, q0, w0, duration):
    """Euler's equations and q̇ = ½ q ⊗ (0, ω) by scipy's DOP853 at rtol 1e-13."""
    inertia = np.array(moments)

    def rhs(_, y):
        q, w = y[:4], y[4:]
        dq = 0.5 * quaternion.multiply(q, np.concatenate([[0.0], w]))
        dw = np.cross(inertia * w, w) / inertia
        return np.concatenate([dq, dw])

    sol = solve_ivp(rhs, (0.0, duration), np.concatenate([q0, w0]), method="DOP853",
                    rtol=1e-13, atol=1e-13)  # fmt: skip
    q = sol.y[:4, -1]
    return q / np.linalg.norm(q)


def test_the_final_orientation_read_as_euler_angles_is_scipys():
    # The trap: tr.R[-1] (rotor blades 1, e12, e13, e23) passed to to_euler gave
    # [144.59, 3.21, -14.88] for [14.88, 3.21, -144.59]. The orientation now comes by name.
    q0 = quaternion.from_axis_angle([1.0, -2.0, 0.5], 0.8)
    w0 = np.array([0.3, -1.2, 0.7])
    tr = gr.simulate([1, 2, 3], q0, w0, duration=10, step=1e-3)
    got = quaternion.to_euler(tr.quaternions()[-1], "ZYX", degrees=True)
    q = _oracle((1.0, 2.0, 3.0), q0, w0, 10.0)
    expected = Rotation.from_quat([q[1], q[2], q[3], q[0]]).as_euler("ZYX", degrees=True)
    assert np.allclose(got, expected, rtol=0, atol=1e-6)
    # Both orientation forms, for every path, are the same rotation.
    for path in ("rotor", "quaternion"):
        tr2 = gr.simulate([1, 2, 3], q0, w0, duration=10, step=1e-3, paths=path)
        from_rotors = np.array([gr.rotor.to_quaternion(R) for R in tr2.rotors()[-3:]])
        assert quaternion.distance(from_rotors, tr2.quaternions()[-3:]).max() < 1e-15
        assert quaternion.distance(tr2.quaternions()[-1], q) < 1e-9


def test_no_quaternion_shaped_array_hides_its_meaning():
    tr = gr.simulate([1, 2, 3], [1.0, 0, 0, 0], [0.1, 0.2, 0.3], duration=0.1, step=1e-2,
                     paths=("rotor", "quaternion"), outputs=("L",))  # fmt: skip
    with pytest.raises(AttributeError, match=r"tr\.quaternions\(\)"):
        _ = tr.R
    four = [name for name in tr.names if tr[name].ndim == 2 and tr[name].shape[1] == 4]
    labels = {name: tr.components[name] for name in four}
    assert labels == {"rotor_blades": ("1", "e12", "e13", "e23"), "q": ("w", "x", "y", "z")}
    header = tr.to_csv().splitlines()[0]
    assert "rotor_blades_e12" in header and ",R_" not in header
    # The raw blades differ from the quaternion exactly where the isomorphism says.
    assert not np.allclose(tr["rotor_blades"][-1], tr.q[-1])
    assert np.allclose(tr.quaternions("rotor"), tr.q, rtol=0, atol=1e-15)


def test_quaternions_are_converted_once_and_cannot_be_changed(monkeypatch):
    from ga_rotors.paths import rotor

    calls = []
    real = rotor.quaternions
    monkeypatch.setattr(rotor, "quaternions", lambda x: calls.append(1) or real(x))
    tr = gr.simulate([1, 2, 3], [1.0, 0, 0, 0], [0.1, 0.2, 0.3], duration=0.1, step=1e-2)
    assert tr.quaternions() is tr.quaternions("rotor") and len(calls) == 1
    with pytest.raises(ValueError, match="read-only"):
        tr.quaternions()[0, 0] = 2.0
    with pytest.raises(gr.InputError, match="no 'euler' path"):
        tr.quaternions("euler")


# ------------------------------------------------------------------ the scene layer, once


def test_a_scene_run_builds_each_derived_value_once(monkeypatch, tmp_path):
    from ga_rotors.integrators import base
    from ga_rotors.paths import rotor
    from ga_rotors.reference import heavy_top
    from ga_rotors.scene import report, write_outputs

    scene = gr.load_scene("heavy_top").replace({
        "time.duration": 0.2, "output.quantities": ["total_energy", "error", "omega_error"],
        "output.plots": ["angles", "invariants", "error"], "output.data": ["npz"],
    })  # fmt: skip
    counts = {"exact": 0, "resolve": 0, "orientation": 0}
    real_init, real_get, real_quats = heavy_top.HeavyTop.__init__, base.get, rotor.quaternions

    def init(self, *args, **kwargs):
        counts["exact"] += 1
        real_init(self, *args, **kwargs)

    def get(name):
        counts["resolve"] += 1
        return real_get(name)

    def quats(x):
        counts["orientation"] += 1
        return real_quats(x)

    monkeypatch.setattr(heavy_top.HeavyTop, "__init__", init)
    monkeypatch.setattr(base, "get", get)
    monkeypatch.setattr(rotor, "quaternions", quats)
    tr = gr.run_scene(scene)
    summary = str(report(scene, tr))
    written = write_outputs(scene, tr, tmp_path / "out", summary)
    assert [p.suffix for p in written] == [".npz", ".png", ".txt", ".toml"]
    assert counts == {"exact": 1, "resolve": 0, "orientation": 1}


def test_scene_modules_read_no_private_name_of_another_module():
    offenders = []
    for path in (PACKAGE / "scene").glob("*.py"):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.ImportFrom):
                private = [a.name for a in node.names if a.name.startswith("_")]
                offenders += [f"{path.name}: from {node.module} import {n}" for n in private]
            elif isinstance(node, ast.Attribute) and node.attr.startswith("_"):
                base_name = getattr(node.value, "id", None)
                if base_name not in ("self", "cls", None) and not node.attr.startswith("__"):
                    offenders.append(f"{path.name}:{node.lineno}: {base_name}.{node.attr}")
    assert not offenders


# ------------------------------------------------------------------ errors as data


def test_no_module_parses_an_error_message_for_its_key():
    offenders = [
        path.relative_to(ROOT).as_posix()
        for path in PACKAGE.rglob("*.py")
        if 'str(exc).partition(": ")' in path.read_text(encoding="utf-8")
    ]
    assert not offenders


@pytest.mark.parametrize(
    ("changes", "key"),
    [
        ({"body.moments": [1.0, 1.0, 3.0]}, "body.moments"),
        ({"initial.orientation": {"quaternion": [2.0, 0, 0, 0]}}, "initial.orientation.quaternion"),
        ({"integrator.paths": ["euler"], "integrator.method": "lie_euler"}, "integrator.paths"),
    ],
    ids=["triangle-inequality", "non-unit-quaternion", "path-the-method-cannot-run"],
)
def test_scene_errors_carry_their_key(changes, key):
    base_scene = {"body": {"moments": [1.0, 2.0, 3.0]}, "time": {"duration": 1.0},
                  "integrator": {"step": 0.1}}  # fmt: skip
    scene = gr.Scene(base_scene)
    with pytest.raises(gr.SceneError) as caught:
        scene.replace(changes)
    exc = caught.value
    assert (exc.file, exc.key) == ("<dict>", key)
    assert str(exc) == f"<dict>: {key}: {exc.detail}" and not exc.detail.startswith(f"{key}:")


def test_input_errors_carry_their_argument():
    with pytest.raises(gr.InputError) as caught:
        gr.RigidBody((1.0, 1.0, 3.0))
    assert caught.value.key == "moments" and str(caught.value).startswith("moments: ")
    assert "triangle" in caught.value.detail and not caught.value.detail.startswith("moments:")
