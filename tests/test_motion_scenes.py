"""Scenes of bodies moving through space: the keys, their mistakes, the bundled scenes'
accuracy against independent closed forms, user forces on the opt-in, files, sweeps.

The oracles are written out here, not taken from ``ga_rotors.reference``: the centre of
mass of a thrown body on c₀ + ċ₀ t + ½ g t², a damped ball's v₀ e^(−bt/m), a zero-length
spring's harmonic oscillator, a circular orbit's radius. The loops compiled here are few
(rk4 under gravity and central gravity on both paths, as the bundled scenes run, rk4 with
a user drag and with a spring on the motor path); every run is short.
"""

from __future__ import annotations

import math
import sys
from functools import cache

import numpy as np
import pytest

from ga_rotors import quaternion as Q
from ga_rotors.errors import SceneError
from ga_rotors.scene import Scene, load_scene, report, run_pieces, run_scene
from ga_rotors.scene.force_types import FORCE_TYPES

G = 9.80665


@cache
def bundled_run(name: str):
    scene = load_scene(name)
    tr = run_scene(scene)
    return scene, tr, report(scene, tr)


def moving(**changes) -> dict:
    """A small moving body: the base the mistakes below change."""
    data = {
        "body": {"moments": [1.0, 2.0, 2.5], "mass": 1.0},
        "time": {"duration": 0.1},
        "integrator": {"step": 0.01},
        "initial": {"velocity": [1.0, 0.0, 0.0]},
    }
    data.update(changes)
    return data


# ---------------------------------------------------------------------------- bundled


@pytest.mark.parametrize("name", ["thrown_racket", "satellite_orbit"])
def test_bundled_motion_scenes_state_their_accuracy_and_their_paths_agree(name):
    scene, tr, rep = bundled_run(name)
    assert scene.moves and scene.paths == ["motor", "quaternion"]
    assert all(info["complete"] for info in tr.meta["paths"].values())
    # the bar: the two paths within 1e-8 rad and 1e-8 of the scene's length scale
    scale = float(np.linalg.norm(tr.positions(), axis=1).max())
    assert rep.values["length_scale"] == pytest.approx(scale, rel=1e-12)
    assert rep.values["motor_vs_quaternion"] <= 1e-8
    assert rep.values["motor_vs_quaternion_distance"] <= 1e-8 * scale
    gap = np.linalg.norm(tr.positions("motor") - tr.positions("quaternion"), axis=1).max()
    assert rep.values["motor_vs_quaternion_distance"] == pytest.approx(gap, rel=1e-12)
    # every balance stated, and held to RK4's error (and Simpson's on the samples)
    assert {"balance_energy", "balance_linear_momentum", "balance_angular_momentum"} <= set(
        rep.values
    )
    for key, value in rep.values.items():
        if key.startswith("balance_"):
            assert value < 1e-8, key
    text = str(rep)
    assert "accuracy: measured by" in text and "the paths' cross-check" in text
    assert "the energy and momentum balances" in text


def test_the_racket_flips_while_its_centre_of_mass_flies_its_parabola():
    scene, tr, rep = bundled_run("thrown_racket")
    # the centre of mass from the quaternion path's own state, against the parabola
    # written out here: c₀ = p₀ + q₀ s q₀*, ċ₀ = v₀ + ω_space × (q₀ s q₀*)
    s = np.array(scene.data["body"]["centre_of_mass"])
    lever = Q.rotate(scene.orientation, s)
    c0 = np.array(scene.data["initial"]["position"]) + lever
    cdot0 = np.array(scene.data["initial"]["velocity"]) + np.cross(
        Q.rotate(scene.orientation, scene.angular_velocity), lever
    )
    t = tr.t[:, None]
    parabola = c0 + cdot0 * t + 0.5 * np.array([0.0, 0.0, -G]) * t * t
    centre = tr["q_com"][:, 4:]
    assert np.abs(centre - parabola).max() < 1e-12 * np.abs(parabola).max() * 10
    # the handle is where the scene puts it: the centre less the turned lever
    handle = centre - Q.rotate(Q.normalize(tr.quaternions("quaternion")), s)
    assert np.abs(handle - tr.positions("motor")).max() < 1e-8
    # the middle-axis spin reverses exactly once in the second of flight
    w1 = tr.w[:, 0]
    assert w1[0] > 11.0 and w1[-1] < -11.0
    assert np.count_nonzero(np.diff(np.sign(w1))) == 1
    # the exact free flight measures both paths, and the summary says so
    assert scene.exact == "free_flight"
    for path in ("motor", "quaternion"):
        assert rep.values[f"error_{path}"] < 1e-9
        assert rep.values[f"position_error_{path}"] < 1e-8 * rep.values["length_scale"]


def test_the_satellite_keeps_its_orbit_and_trades_spin_for_orbit():
    scene, tr, rep = bundled_run("satellite_orbit")
    r0 = np.linalg.norm(scene.position)
    assert math.isclose(np.linalg.norm(scene.velocity), math.sqrt(3.986004418e14 / r0),
                        rel_tol=1e-9)  # fmt: skip
    radius = np.linalg.norm(tr.positions(), axis=1)
    assert np.abs(radius / r0 - 1.0).max() < 1e-6  # circular, to the gradient's nudge
    assert scene.exact is None and "balances" in scene.exact_reason
    text = str(rep)
    assert "angular momentum about (0, 0, 0): conserved" in text
    assert "total energy: conserved" in text
    assert "not available: an exact error" in text
    # the gravity gradient turns the body: its rates change by far more than RK4's error
    assert np.abs(tr.w - tr.w[0]).max() > 1e-5


def test_a_summary_in_pieces_is_the_summary_of_the_whole_run():
    scene = load_scene("thrown_racket").replace({"time.duration": 0.2})
    whole = report(scene, run_scene(scene))
    from ga_rotors.scene.summary import summary_for

    summary = summary_for(scene)
    for piece in run_pieces(scene, chunk_steps=60):
        summary.add(piece)
    pieces = summary.report()
    assert pieces.values.keys() == whole.values.keys()
    for key, value in whole.values.items():
        assert pieces.values[key] == pytest.approx(value, rel=1e-9, abs=1e-16), key


# ---------------------------------------------------------------------------- mistakes


@pytest.mark.parametrize(
    ("change", "key"),
    [
        ({"body": {"moments": [1.0, 2.0, 2.5]}}, "body.mass"),
        ({"forces": [{"type": "spring", "anchor": [0.0, 0.0, 1.0]}]}, "forces[0].stiffness"),
        ({"forces": [{"type": "linear_drag", "coeficient": 0.1}]}, "forces[0].coeficient"),
        ({"forces": [{"type": "gravity"}]}, "forces[0].type"),
        ({"forces": [{"g": [0.0, 0.0, -1.0]}]}, "forces[0].type"),
        ({"forces": ["uniform_gravity"]}, "forces[0]"),
        ({"forces": {"type": "uniform_gravity"}}, "forces"),
        ({"forces": [{"type": "uniform_gravity", "g": [0.0, 0.0]}]}, "forces[0].g"),
        ({"forces": [{"type": "uniform_gravity", "g": [0.0, 0.0, 0.0]}]}, "forces[0].g"),
        (
            {"forces": [{"type": "spring", "stiffness": -1.0, "anchor": [0, 0, 1]}]},
            "forces[0].stiffness",
        ),
        (
            {"forces": [{"type": "point_force", "force": [1, 0, 0], "fixed_in": "bdy"}]},
            "forces[0].fixed_in",
        ),
        ({"forces": [{"type": "central_gravity", "mu": 0.0}]}, "forces[0].mu"),
        ({"forces": [{"type": "user", "function": "os.system"}]}, "forces[0].function"),
        ({"effects": [{"type": "gravity", "pivot_to_com": [0.0, 0.0, 0.1]}]}, "initial.velocity"),
        ({"integrator": {"step": 0.01, "paths": ["rotor"]}}, "integrator.paths[0]"),
        ({"integrator": {"step": 0.01, "paths": ["motor", "euler"]}}, "integrator.paths[1]"),
        ({"initial": {"velocity": [1.0, 0.0]}}, "initial.velocity"),
        ({"initial": {"position": [0.0, 0.0, math.inf]}}, "initial.position[2]"),
        ({"initial": {"velocity": [1e300, 0.0, 0.0]}}, "initial.velocity"),
        (
            {"body": {"moments": [1.0, 2.0, 2.5], "mass": 1.0, "centre_of_mass": [0, 1e308, 0]}},
            "body.centre_of_mass",
        ),  # its lever's moment m|s|² overflows: the ensemble's samples came out NaN
        ({"initial": {"position": [1e300, 0, 0], "velocity": [1.0, 0, 0]}}, "initial.position"),
        ({"initial": {"positon": [0.0, 0.0, 1.0]}}, "initial.positon"),
        (
            {"body": {"moments": [1.0, 2.0, 2.5], "mass": 1.0, "centre_of_mass": [0, 1]}},
            "body.centre_of_mass",
        ),
        ({"output": {"quantities": ["total_energy"]}}, "output.quantities[0]"),
        ({"output": {"plots": ["invariants"]}}, "output.plots[0]"),
        (
            {
                "forces": [{"type": "linear_drag", "coefficient": 0.1}],
                "integrator": {"method": "split2", "step": 0.01, "paths": ["motor"]},
            },
            "integrator.method",
        ),
    ],
)
def test_every_mistake_is_one_line_naming_the_file_and_the_key(change, key):
    with pytest.raises(SceneError) as caught:
        Scene(moving(**change), file="bad.toml")
    assert caught.value.file == "bad.toml" and caught.value.key == key
    assert "\n" not in str(caught.value) and str(caught.value).startswith(f"bad.toml: {key}:")


def test_motion_keys_on_a_body_turning_about_a_fixed_point_are_refused():
    still = {
        "body": {"moments": [1.0, 2.0, 2.5], "centre_of_mass": [0.0, 0.1, 0.0]},
        "time": {"duration": 0.1},
        "integrator": {"step": 0.01},
    }
    with pytest.raises(SceneError, match=r"body\.centre_of_mass: only for a body moving"):
        Scene(still)
    del still["body"]["centre_of_mass"]
    for key, value in (("integrator.paths", ["motor"]), ("output.plots", ["position"])):
        with pytest.raises(SceneError) as caught:
            Scene(still).replace({key: value})
        assert caught.value.key == f"{key}[0]"


def test_the_guards_count_forces_with_the_effects():
    weight = {"type": "uniform_gravity"}
    with pytest.raises(SceneError, match="0 effects and 65 forces"):
        Scene(moving(forces=[weight] * 65))
    torque = {"type": "body_torque", "torque": [0.0, 0.0, 0.0]}
    with pytest.raises(SceneError, match="40 effects and 30 forces") as caught:
        Scene(moving(forces=[weight] * 30, effects=[torque] * 40))
    assert caught.value.key == "forces"
    # a deep nest inside a force is the nesting guard's, before anything is read
    deep: object = 1.0
    for _ in range(200):
        deep = [deep]
    with pytest.raises(SceneError):
        Scene(moving(forces=[{"type": "linear_drag", "coefficient": deep}]))
    # the compile-time estimate counts every compiled term, forces too
    from ga_rotors.scene.budget import estimate
    from ga_rotors.scene.schema import compile_seconds

    scene = Scene(moving(forces=[weight] * 20, effects=[torque] * 10))
    assert estimate(scene).compile_seconds == pytest.approx(
        compile_seconds(30, scene.method.evaluations)
    )


def test_a_motion_scene_round_trips_and_a_rotation_scene_is_unchanged():
    scene = load_scene("thrown_racket")
    assert Scene.from_toml(scene.to_toml()).data == scene.data
    assert scene.data["forces"] == [{"type": "uniform_gravity", "g": [0.0, 0.0, -G]}]
    heavy = load_scene("heavy_top")
    assert "forces" not in heavy.data and "position" not in heavy.data["initial"]
    assert not heavy.moves and heavy.forces() == ()
    lines = scene.describe().splitlines()
    assert any("initial position (0, 0, 1.5) m" in line for line in lines)


def test_the_docs_describe_every_force_key():
    from pathlib import Path

    from ga_rotors.scene.schema import MOTION_KEYS

    text = (Path(__file__).resolve().parent.parent / "docs" / "scenes.md").read_text()
    keys = {"forces", "centre_of_mass", *MOTION_KEYS}
    for kind in FORCE_TYPES.values():
        keys |= {kind.name} | {k.name for k in kind.keys}
    assert not sorted(k for k in keys if f"`{k}`" not in text and f"[[{k}]]" not in text)


# ---------------------------------------------------------------------------- forces


def test_a_spring_at_the_centre_of_mass_is_a_harmonic_oscillator():
    k, m = 8.0, 2.0
    scene = Scene(
        {
            "body": {"moments": [0.1, 0.2, 0.25], "mass": m},
            "initial": {
                "position": [1.0, 0.0, 0.0],
                "velocity": [0.0, 0.5, 0.0],
                "angular_velocity": {"body": [0.3, 2.0, 0.1], "units": "rad/s"},
            },
            "forces": [{"type": "spring", "stiffness": k, "anchor": [0.0, 0.0, 0.0]}],
            "time": {"duration": 2.0, "output_step": 0.1},
            "integrator": {"step": 1e-3},
        }
    )
    assert scene.exact == "spring_at_centre_of_mass"
    tr = run_scene(scene)
    omega = math.sqrt(k / m)
    t = tr.t[:, None]
    expected = np.array([1.0, 0.0, 0.0]) * np.cos(omega * t) + np.array(
        [0.0, 0.5, 0.0]
    ) / omega * np.sin(omega * t)
    assert np.abs(tr.positions() - expected).max() < 1e-9
    rep = report(scene, tr)
    assert rep.values["position_error_motor"] < 1e-9 and rep.values["error_motor"] < 1e-9
    assert rep.values["balance_energy"] < 1e-10
    # off the centre of mass the spring has no closed form: the balances measure it
    off = scene.replace({"forces[0].at": [0.1, 0.0, 0.0]})
    assert off.exact is None and "balances" in off.exact_reason


def test_a_user_force_runs_only_on_the_opt_in(tmp_path, monkeypatch):
    monkeypatch.delenv("GA_ROTORS_ALLOW_USER_CODE", raising=False)
    data = moving(
        forces=[{"type": "user", "function": "_forces_for_tests:linear_air_drag", "params": [0.1]}]
    )
    scene = Scene(data, file="ball.toml")  # loading and showing run nothing
    assert "_forces_for_tests" not in sys.modules
    scene.to_toml()
    scene.describe()
    with pytest.raises(SceneError) as caught:
        run_scene(scene)
    assert caught.value.key == "forces[0].function"
    assert "the scene asks to run code" in str(caught.value)
    assert "_forces_for_tests" not in sys.modules


@pytest.mark.usefixtures("tests_code")
def test_a_user_force_is_integrated_on_the_opt_in():
    b, m, v0 = 0.1, 1.0, 1.0
    scene = Scene(
        moving(
            forces=[
                {
                    "type": "user",
                    "function": "_forces_for_tests:linear_air_drag",
                    "params": [b],
                    "depends_on_velocity": True,
                }
            ]
        )
    )
    tr = run_scene(scene)
    exact = v0 * np.exp(-b * tr.t / m)  # m v̇ = −b v
    assert np.abs(tr.velocities()[:, 0] - exact).max() < 1e-12
    rep = report(scene, tr)
    assert rep.values["balance_energy"] < 1e-9  # its work integrated, nothing it conserves
    assert "energy: balanced" in str(rep)


@pytest.mark.usefixtures("tests_code")
@pytest.mark.parametrize(
    ("function", "says"),
    [
        ("_forces_for_tests:plain_python", "a plain Python function"),
        ("_forces_for_tests:four_arguments", "takes 4 arguments"),
        ("_forces_for_tests:three_numbers", "six finite numbers"),
        ("_forces_for_tests:not_finite", "six finite numbers"),
        ("_forces_for_tests:missing", "has no attribute"),
        ("os:system", "outside the allowed folders"),
    ],
)
def test_a_bad_user_force_is_one_line_naming_its_function(function, says):
    scene = Scene(moving(forces=[{"type": "user", "function": function}]), file="bad.toml")
    with pytest.raises(SceneError) as caught:
        scene.forces()
    assert caught.value.key == "forces[0].function" and says in str(caught.value)
    assert "\n" not in str(caught.value)


# ---------------------------------------------------------------------------- files, sweeps


def test_ga_rotors_run_writes_position_and_velocity_with_their_units(tmp_path, capsys):
    xr = pytest.importorskip("xarray")
    from ga_rotors.cli import main

    assert main(["run", "thrown_racket", "--out", str(tmp_path), "--no-progress"]) == 0
    printed = capsys.readouterr().out
    assert "accuracy: measured by the error against the exact solution" in printed
    ds = xr.open_dataset(tmp_path / "thrown_racket.nc")
    assert ds["position"].attrs["units"] == "m" and ds["velocity"].attrs["units"] == "m/s"
    assert list(ds["position"].dims) == ["time", "space_axis"]
    assert "origin 0.33 m from the centre of mass" in ds.attrs["body_frame"]
    _, tr, _ = bundled_run("thrown_racket")
    assert np.array_equal(ds["position"].values, tr.positions())
    summary = (tmp_path / "thrown_racket.summary.txt").read_text()
    assert "motor vs quaternion" in summary
    ds.close()


def test_a_sweep_over_the_racket_s_spin(tmp_path):
    pytest.importorskip("zarr")
    from ga_rotors.sweep import load_sweep, open_sweep, run_sweep

    text = (
        '[sweep]\nscene = "thrown_racket"\nsamples = 3\nseed = 5\ntimes = [0.1, 0.2]\n'
        '[set]\n"time.duration" = 0.2\n'
        '[[draw]]\nkey = "initial.angular_velocity.body[2]"\nnormal = [0.05, 0.02]\n'
    )
    sweep = load_sweep(text)
    run_sweep(text, tmp_path / "racket.zarr", client="sync")
    ds = open_sweep(tmp_path / "racket.zarr")
    assert ds["position"].attrs["units"] == "m" and ds["position"].shape == (3, 2, 3)
    # each sample is the scene run with its drawn value, bit for bit
    drawn = ds["initial_angular_velocity_body_2"].values
    one = run_scene(
        sweep.scene.replace(
            {"initial.angular_velocity.body[2]": float(drawn[1]), "integrator.paths": ["motor"]}
        )
    )
    rows = np.searchsorted(one.t, [0.1, 0.2])
    assert np.array_equal(ds["position"].values[1], one.positions()[rows])
    assert np.array_equal(ds["w"].values[1], one.w[rows])
