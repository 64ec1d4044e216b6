"""Running scenes: only what is declared is integrated, evaluated or computed."""

from __future__ import annotations

import itertools
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

from ga_rotors import effects
from ga_rotors.body import RigidBody
from ga_rotors.errors import SceneError
from ga_rotors.integrators import Problem, TemplateIntegrator, _runner, _source, get
from ga_rotors.scene import Scene, load_scene, run_scene
from ga_rotors.scene import run as scene_run

ROOT = Path(__file__).resolve().parent.parent

#: One scene entry per effect type, and the kernel each must put in the generated loop.
ENTRIES = {
    "gravity": ({"type": "gravity", "pivot_to_com": [0.0, 0.0, 0.1]}, "vertical_gravity"),
    "gravity_off_axis": ({"type": "gravity", "pivot_to_com": [0.01, 0.0, 0.1]}, "gravity"),
    "damping": ({"type": "damping", "coefficient": 1e-3}, "isotropic_damping"),
    "damping3": ({"type": "damping", "coefficient": [1e-3, 2e-3, 3e-3]}, "damping"),
    "body_torque": ({"type": "body_torque", "torque": [0.0, 0.0, 1e-3]}, "body_torque"),
    "space_torque": ({"type": "space_torque", "torque": [1e-3, 0.0, 0.0]}, "space_torque"),
    "user": ({"type": "user", "function": "_torques_for_tests:linear_damping",
              "params": [1e-3]}, "linear_damping"),
}  # fmt: skip
KERNELS = {kernel for _, kernel in ENTRIES.values()}


def scene_with(*entries) -> Scene:
    return Scene({
        "body": {"shape": "disk", "mass": 2.0, "radius": 0.075},
        "initial": {"angular_velocity": {"body": [0.3, 0.1, 15.0], "units": "rad/s"}},
        "time": {"duration": 0.05},
        "integrator": {"step": 1e-3, "paths": ["rotor", "quaternion"]},
        "effects": list(entries),
    })  # fmt: skip


def generated_source(scene: Scene, path: str) -> str:
    problem = Problem(scene.body.moments, scene.torques())
    return _source.source(get(scene.data["integrator"]["method"]), problem, path)[0]


def imported_kernels(text: str) -> set[str]:
    """Names of effect kernels the generated module imports as torque terms."""
    names = set()
    for line in text.splitlines():
        if " as _term_" in line:
            names.add(line.split(" import ")[1].split(" as ")[0])
    return names


@pytest.mark.parametrize("name", sorted(ENTRIES))
def test_only_the_declared_effect_is_in_the_generated_loop(name, tests_code):
    entry, kernel = ENTRIES[name]
    for path in ("rotor", "quaternion"):
        text = generated_source(scene_with(entry), path)
        assert imported_kernels(text) == {kernel}
        assert "def torque(" in text


def test_two_effects_make_a_sum_of_exactly_two_terms():
    s = scene_with(ENTRIES["gravity"][0], ENTRIES["space_torque"][0])
    text = generated_source(s, "rotor")
    assert imported_kernels(text) == {"vertical_gravity", "space_torque"}
    assert "params[0:6]" in text and "params[6:9]" in text


def test_no_effects_means_no_torque_in_the_source_at_all():
    text = generated_source(scene_with(), "rotor")
    assert "torque" not in text and not imported_kernels(text)
    assert "free_euler_rates(inertia, w)" in text


def test_undeclared_effects_are_never_evaluated_uncompiled(tmp_path):
    # Uncompiled, the generated module is plain Python: every undeclared effect kernel is
    # replaced by a tripwire that raises, and the declared one by a counter. RK4 evaluates
    # the torque four times a step, on each of the two paths.
    script = textwrap.dedent(
        """
        import sys
        import ga_rotors.effects as E
        from ga_rotors.scene import Scene
        from ga_rotors.scene import run_scene

        def tripwire(name):
            def kernel(t, q, w, p):
                raise AssertionError(f"undeclared effect {name} was evaluated")
            kernel.__module__, kernel.__qualname__ = "ga_rotors.effects", name
            kernel.__name__ = name
            return kernel

        calls = []
        declared = E.space_torque
        def space_torque(t, q, w, p):
            calls.append(t)
            return declared(t, q, w, p)
        space_torque.__module__ = "ga_rotors.effects"

        for name in ("gravity", "vertical_gravity", "isotropic_damping", "damping", "body_torque"):
            setattr(E, name, tripwire(name))
        E.space_torque = space_torque
        s = Scene({
            "body": {"moments": [1.0, 2.0, 2.5]},
            "initial": {"angular_velocity": {"body": [0.1, 0.2, 0.3], "units": "rad/s"}},
            "time": {"duration": 0.05},
            "integrator": {"step": 0.01, "paths": ["rotor", "quaternion"]},
            "effects": [{"type": "space_torque", "torque": [0.0, 0.0, 1.0]}],
        })
        tr = run_scene(s)
        print(len(calls), tr.names)
        """
    )
    env = {
        **os.environ,
        "NUMBA_DISABLE_JIT": "1",
        "GA_ROTORS_CACHE_DIR": str(tmp_path),
        "PYTHONPATH": os.pathsep.join([str(ROOT), str(ROOT / "tests")]),
    }
    proc = subprocess.run(
        [sys.executable, "-c", script], env=env, capture_output=True, text=True, timeout=300
    )
    assert proc.returncode == 0, proc.stderr
    count, names = proc.stdout.split(" ", 1)
    assert int(count) == 4 * 5 * 2
    assert names.strip() == "('t', 'w', 'rotor_blades', 'q')"


def test_undeclared_paths_are_never_integrated(monkeypatch):
    ran, inside = [], []

    def recorder(original):
        # every path is one Integrator.run (which may call the base class's run): the
        # outermost call is the one recorded
        def recording(self, problem, path, *args, **kwargs):
            if not inside:
                ran.append(path)
            inside.append(path)
            try:
                return original(self, problem, path, *args, **kwargs)
            finally:
                inside.pop()

        return recording

    for name in ("run",):
        monkeypatch.setattr(TemplateIntegrator, name, recorder(getattr(TemplateIntegrator, name)))
    for paths in (["quaternion"], ["euler", "rotor"]):
        ran.clear()
        s = load_scene("spinning_disk").replace(
            {"time.duration": 0.05, "integrator.paths": paths, "output.quantities": []}
        )
        tr = run_scene(s)
        assert sorted(ran) == sorted(paths)
        assert set(tr.meta["paths"]) == set(paths)


def test_nothing_is_computed_for_outputs_nobody_asked_for(monkeypatch):
    def tripwire(*args, **kwargs):
        raise AssertionError("computed an output nobody asked for")

    s = load_scene("heavy_top").replace({"time.duration": 0.01, "output.quantities": []})
    from ga_rotors.scene import exact
    from ga_rotors.trajectory import Trajectory

    monkeypatch.setattr(scene_run, "_quantities", tripwire)
    monkeypatch.setattr(exact, "build", tripwire)
    monkeypatch.setattr(Trajectory, "quaternions", tripwire)
    tr = run_scene(s)
    assert tr.names == ("t", "w", "rotor_blades", "q")

    # Asking for one quantity computes that one: energy comes from simulate itself, and the
    # exact solution is still not touched.
    monkeypatch.undo()
    monkeypatch.setattr(exact, "build", tripwire)
    tr = run_scene(s.replace({"output.quantities": ["energy", "potential_energy"]}))
    assert tr.names == ("t", "w", "rotor_blades", "q", "energy", "potential_energy")


def test_quantities_are_what_they_say():
    from ga_rotors import quaternion as Q

    s = load_scene("heavy_top").replace({
        "time.duration": 0.2,
        "output.quantities": ["energy", "potential_energy", "total_energy", "L", "L_space",
                              "omega_space", "angles", "error", "omega_error"],
    })  # fmt: skip
    tr = run_scene(s)
    q = Q.normalize(tr.q)
    weight, r = s.gravity
    assert np.allclose(tr.potential_energy, -(Q.rotate(q, r) @ weight), rtol=0, atol=1e-15)
    assert np.allclose(tr.total_energy, tr.energy + tr.potential_energy, rtol=0, atol=1e-15)
    assert np.allclose(tr.omega_space, Q.rotate(q, tr.w), rtol=0, atol=1e-13)
    assert np.allclose(tr.L_space, Q.rotate(q, tr.L), rtol=0, atol=1e-15)
    assert tr.error_rotor.max() < 1e-10 and tr.error_quaternion.max() < 1e-10
    assert tr.omega_error.max() < 1e-9
    assert np.allclose(tr.angles[0], np.radians([0.0, 30.0, 0.0]), atol=1e-15)


@pytest.mark.parametrize("case", ["heavy top", "pivot off every principal axis, drifted norm"])
def test_energy_columns_are_the_array_formulas_bit_for_bit(case):
    # The energy columns come from one compiled pass (scene.run); they must be the
    # array functions' numbers exactly: normalise, rotate the lever, matrix-vector
    # product, einsum. The second case runs RK4 at a coarse step on the quaternion path
    # (no renormalisation: |q| drifts from 1) in a principal frame turned from the body's.
    from ga_rotors import quaternion as Q

    if case == "heavy top":
        s = load_scene("heavy_top").replace({"time.duration": 1.0})
    else:
        s = Scene({
            "body": {"shape": "box", "mass": 1.5, "a": 0.3, "b": 0.2, "c": 0.1},
            "initial": {"angular_velocity": {"body": [1.0, -2.0, 8.0], "units": "rad/s"}},
            "time": {"duration": 2.0},
            "integrator": {"method": "rk4", "step": 0.02, "paths": ["quaternion"]},
            "effects": [{"type": "gravity", "pivot_to_com": [0.05, -0.03, 0.08]}],
        })  # fmt: skip
        assert s.principal_rotation != (1.0, 0.0, 0.0, 0.0)
    tr = run_scene(s.replace({"output.quantities": ["potential_energy", "total_energy"]}))
    if case != "heavy top":
        assert np.abs(np.linalg.norm(tr.quaternions(), axis=1) - 1.0).max() > 1e-9
    # the samples are the scene's body frame's; the lever s.gravity is principal, where
    # the body's own conversion takes them
    q, w = s.body.to_principal(tr.quaternions(), tr.w)
    weight, r = s.gravity
    potential = -(Q.rotate(Q.normalize(q), r) @ weight)
    assert np.array_equal(tr.potential_energy, potential)
    assert np.array_equal(tr.total_energy, RigidBody(s.body.moments).energy(w) + potential)
    # and the same energies as the scene's body frame has them (to rounding)
    lever = Q.rotate(s.principal_rotation, r)
    assert np.allclose(tr.potential_energy, -(Q.rotate(Q.normalize(tr.quaternions()), lever)
                                               @ weight), rtol=0, atol=1e-14)  # fmt: skip
    assert np.allclose(tr.total_energy - tr.potential_energy, s.body.energy(tr.w), rtol=1e-14)


def test_chunked_loops_give_the_same_samples(monkeypatch):
    # Progress runs the compiled loop in chunks restarted from the stored samples; the
    # states and the Euler path's watch statistics must be identical to one call.
    s = load_scene("paper_0.001deg").replace({"time.duration": 2.0, "output.quantities": []})
    whole = run_scene(s)
    monkeypatch.setattr(_runner, "CHUNK_STEPS", 300)  # 7 chunks of 300 steps (30 samples)
    calls = []
    chunked = run_scene(s, progress=lambda done, total: calls.append((done, total)))
    for name in whole.names:
        assert np.array_equal(whole[name], chunked[name]), name
    a, b = whole.meta["paths"]["euler"]["watch"], chunked.meta["paths"]["euler"]["watch"]
    # Times inside a chunk are (t0 + k·chunk·h) + i·h instead of t0 + (k·chunk + i)·h: the
    # time the watch records may differ in the last bits (two roundings), nothing else.
    when_a, when_b = a.pop("first_unresolved"), b.pop("first_unresolved")
    assert a == b and abs(when_a - when_b) <= 4 * np.spacing(when_a)
    assert calls[-1] == (3 * 2000, 3 * 2000) and len(calls) == 3 * 7
    assert all(a[0] < b[0] for a, b in itertools.pairwise(calls))


def test_numba_failure_of_a_user_kernel_names_the_effect(tmp_path, monkeypatch):
    # A kernel that works in Python but not in nopython mode (it calls a plain Python
    # helper) passes the trial call and then fails to compile: the error names the effect.
    (tmp_path / "bad_kernel_mod.py").write_text(
        "import numba\n\ndef helper(t):\n    return 1.0\n\n"
        "@numba.njit(cache=False)\ndef k(t, q, w, p):\n    return (0.0, 0.0, helper(t))\n"
    )
    monkeypatch.setenv("GA_ROTORS_ALLOW_USER_CODE", str(tmp_path))
    s = Scene({"body": {"moments": [1, 2, 2.5]}, "time": {"duration": 0.1},
               "integrator": {"step": 0.05},
               "effects": [{"type": "user", "function": "bad_kernel_mod:k"}]})  # fmt: skip
    from ga_rotors.errors import SceneError

    with pytest.raises(SceneError, match=r"effects\[0\]\.function: numba could not compile"):
        run_scene(s)


def test_effects_table_kernels_are_module_level_and_documented():
    for name, kind in effects.EFFECTS.items():
        assert kind.name == name and kind.doc
        for key in kind.keys:
            assert key.doc, (name, key.name)


def test_an_adaptive_scene_runs_at_its_tolerance():
    from ga_rotors.scene import report

    errors = {}
    for tol in (1e-8, 1e-11):
        s = load_scene("intermediate_axis_flip").replace({
            "integrator.method": "dop853", "integrator.tolerance": tol, "time.duration": 3.0,
            "integrator.step": 0.005, "output.quantities": [],
        })  # fmt: skip
        rep = report(s, run_scene(s))
        assert rep.lines[0].startswith(f"scene intermediate_axis_flip: dop853, adaptive at "
                                       f"tolerance {tol:g}")  # fmt: skip
        errors[tol] = rep.values["error_rotor"]
    # A tighter tolerance must buy accuracy (DOP853 is order 8: far more than 10×).
    assert errors[1e-11] < errors[1e-8] / 10


def test_an_exact_reference_that_refuses_the_state_names_the_file_and_key(tmp_path):
    """The heavy-top reference is singular with the symmetry axis upright: a scene asking
    for its error gets one line naming the file and initial.orientation, not a bare
    reference message."""
    import ga_rotors.scene.loading as loading

    text = loading.bundled_path("heavy_top").read_text(encoding="utf-8")
    text = text.replace("euler = [0.0, 30.0, 0.0]", "euler = [0.0, 0.0, 0.0]")
    path = tmp_path / "upright.toml"
    path.write_text(text, encoding="utf-8")
    scene = load_scene(path)
    with pytest.raises(SceneError) as info:
        _ = scene.exact_solution
    assert info.value.file.endswith("upright.toml")
    assert info.value.key == "initial.orientation"
    assert "symmetry axis is vertical" in info.value.detail
    assert "\n" not in str(info.value)


def test_a_run_longer_than_the_references_default_span_reports_its_bound():
    """Past ~560 s the heavy-top reference's rounding bound passes its default 1e-10 rad and
    the reference called directly refuses; a scene run of 800 s asking for ``error`` still
    runs, its error columns are the reference's values, and the summary and the data
    attributes state the bound (which grows with time) instead of aborting the run."""
    from ga_rotors import quaternion as Q
    from ga_rotors.errors import PrecisionError
    from ga_rotors.results.dataset import run_attributes
    from ga_rotors.scene.summary import report

    s = load_scene("heavy_top").replace({
        "time.duration": 800.0, "time.output_step": 1.0, "integrator.step": 0.001,
        "output.quantities": ["error", "omega_error"],
    })  # fmt: skip
    exact = s.exact_solution
    with pytest.raises(PrecisionError):
        exact.model.state([800.0])  # the reference's own default refuses this span
    tr = run_scene(s)
    q_ref, w_ref, bound = exact.state(tr.t)
    assert 1e-10 < bound[-1] < 1e-8 and bound[0] < 1e-13
    q_rotor = Q.normalize(tr.quaternions("rotor"))
    assert np.array_equal(tr.error_rotor, Q.distance(q_ref, q_rotor))
    assert np.array_equal(tr.omega_error, np.linalg.norm(tr.w - w_ref, axis=-1))
    rep = report(s, tr)
    assert 1e-10 < rep.values["exact_bound"] < 1e-8
    assert f"rounding bound {rep.values['exact_bound']:.1e} rad" in str(rep)
    assert rep.values["error_rotor"] == tr.error_rotor.max()
    bound = run_attributes(tr.meta, s, tr.t)["exact_error_bound"]
    assert bound == pytest.approx(rep.values["exact_bound"], rel=0.05)


# ---------------------------------------------------------------------------- one frame

#: A tensor whose principal axes are turned from the axes it is written in (issue 30).
TURNED_TENSOR = [[2.0, 0.3, 0.1], [0.3, 1.5, -0.2], [0.1, -0.2, 1.0]]


def turned_scene(**changes) -> Scene:
    return Scene({
        "body": {"tensor": TURNED_TENSOR},
        "initial": {"angular_velocity": {"body": [0.0, 0.0, 1.0], "units": "rad/s"}},
        "time": {"duration": 1.0},
        "integrator": {"step": 0.01, "paths": ["rotor", "quaternion"]},
        "output": {"quantities": ["angles", "energy", "L", "L_space"], "data": ["csv"]},
        **changes,
    })  # fmt: skip


def test_a_tensor_scene_answers_in_the_frame_it_is_written_in(tmp_path):
    """Issue 30 item 1: a tensor body's run gave q, ω, L, the angles and the files in the
    principal frame (a scene started at the identity with ω = (0, 0, 1) wrote a first CSV
    row with ω = (0.086, −0.156, 0.984), 0.91 rad from simulate's answer), while
    simulate(RigidBody.from_tensor(...)) answers in the tensor's frame. Now every output
    is in the frame the scene writes the body in, and says so."""
    from ga_rotors import quaternion as Q
    from ga_rotors import simulate
    from ga_rotors.errors import GimbalLockWarning
    from ga_rotors.scene import stream_scene

    scene = turned_scene()
    assert scene.principal_rotation != (1.0, 0.0, 0.0, 0.0)
    assert np.array_equal(scene.orientation, [1.0, 0.0, 0.0, 0.0])
    assert np.array_equal(scene.angular_velocity, [0.0, 0.0, 1.0])
    with pytest.warns(GimbalLockWarning, match="at 1 of 101"):  # θ = 0 at the identity
        tr = run_scene(scene)
    assert "not principal" in tr.meta["body_frame"]
    # (0, 0, 1) to the frame change's rounding, there and back (a few ulps)
    assert np.allclose(tr.w[0], [0.0, 0.0, 1.0], rtol=0, atol=1e-15)
    assert np.allclose(tr.quaternions()[0], [1.0, 0.0, 0.0, 0.0], rtol=0, atol=1e-15)
    body = RigidBody.from_tensor(TURNED_TENSOR)
    with pytest.warns(GimbalLockWarning, match="at 1 of 101"):
        alone = simulate(
            body,
            [1.0, 0.0, 0.0, 0.0],
            [0.0, 0.0, 1.0],
            duration=1.0,
            step=0.01,
            paths=("rotor", "quaternion"),
            outputs=("L", "angles"),
        )
    for path in ("rotor", "quaternion"):
        assert Q.distance(tr.quaternions(path), alone.quaternions(path)).max() < 1e-14
    assert np.allclose(tr.w, alone.w, rtol=0, atol=1e-14)
    assert np.allclose(tr.L, alone.L, rtol=0, atol=1e-14)
    assert np.allclose(tr.L, tr.w @ np.array(TURNED_TENSOR).T, rtol=0, atol=1e-14)  # L = T ω
    assert np.allclose(tr.angles[1:], alone.angles[1:], rtol=0, atol=1e-12)
    # the data file says the same from its first row
    files, _ = stream_scene(scene.replace({"output.quantities": ["L"]}), tmp_path / "run")
    header, first = [line for line in files[0].read_text().splitlines()
                     if line and not line.startswith("#")][:2]  # fmt: skip
    at = [i for i, name in enumerate(header.split(",")) if name.startswith("w_")]
    row = np.array(first.split(","), dtype=float)
    assert np.allclose(row[at], [0.0, 0.0, 1.0], rtol=0, atol=1e-15)


def test_a_turned_scene_starts_where_the_scene_says_and_its_summary_holds():
    """A scene's orientation given as Euler angles with a turned tensor: the run's first
    sample is that orientation (not q ⊗ P), and the summary's invariants and exact error
    are read in that frame (they would show a frame mismatch as a large drift)."""
    from ga_rotors import euler
    from ga_rotors.scene.summary import report

    scene = turned_scene(initial={
        "orientation": {"euler": [20.0, 40.0, 10.0], "sequence": "ZYZ", "units": "deg"},
        "angular_velocity": {"body": [0.5, -1.0, 2.0], "units": "rad/s"},
    })  # fmt: skip
    tr = run_scene(scene.replace({"output.quantities": ["angles", "error"]}))
    assert np.allclose(tr.angles[0], np.radians([20.0, 40.0, 10.0]), rtol=0, atol=1e-14)
    assert np.allclose(tr.quaternions()[0], euler.to_quaternion("ZYZ", np.radians(
        [20.0, 40.0, 10.0])), rtol=0, atol=1e-15)  # fmt: skip
    rep = report(scene, tr)
    assert rep.values["drift_space_momentum"] < 1e-9 and rep.values["error_rotor"] < 1e-8


def test_a_turned_body_cannot_take_the_euler_angle_path():
    """The Euler-angle path integrates the principal frame's angles, which are not the
    scene's body frame's: refused at the key, in one line, as simulate refuses it."""
    with pytest.raises(SceneError) as info:
        turned_scene(integrator={"step": 0.01, "paths": ["rotor", "euler"]})
    assert info.value.key == "integrator.paths"
    assert "body.tensor is not diagonal" in info.value.detail and "\n" not in str(info.value)


def test_a_reference_beyond_the_scenes_bound_says_what_the_scene_can_change():
    """Issue 30 item 12: a scene's exact reference past its 1e-6 rad bound said "shorten the
    time span or raise max_error", and no scene key or flag raises it. It now names the
    bound, the time and time.duration."""
    from ga_rotors.errors import PrecisionError

    exact = load_scene("heavy_top").exact_solution
    with pytest.raises(PrecisionError) as info:
        exact.state([0.0, 1e8])
    message = str(info.value)
    assert "max_error" not in message and "shorten time.duration" in message
    assert "by t = 1e+08 s" in message and info.value.bound > 1e-6
