"""Ensembles and sweeps of bodies moving through space, on the batched loops.

The oracle of every batched sample is the single run of the same scene with the sample's
values (``run_scene``, the path the sweep integrates on), which the batched loop must
equal bit for bit: the same step compiled into the motion kind's batched loop template.
The runs are short (tens of steps) and serial, the loop the sweep's tasks compile.
"""

from __future__ import annotations

import numpy as np
import pytest

from ga_rotors.ensemble import run_samples, scene_samples
from ga_rotors.errors import InputError, SceneError
from ga_rotors.scene import load_scene, run_scene
from ga_rotors.sweep import budget, load_sweep, open_sweep, run_sweep

TIMES = [0.025, 0.05]


@pytest.fixture(scope="module")
def racket():
    return load_scene("thrown_racket").replace({"time.duration": 0.05})


def single_runs(scene, changes, times):
    """Each sample's (q, w, position, velocity) at ``times`` from its own scene run."""
    t0, h = scene.data["time"]["start"], scene.step
    marks = np.rint((np.asarray(times) - t0) / h).astype(int)
    every = int(np.gcd.reduce(marks))
    n = len(next(iter(changes.values())))
    out = []
    for i in range(n):
        change = {k: np.asarray(v)[i].tolist() for k, v in changes.items()}
        change.update({"time.output_step": every * h, "integrator.paths": [scene.paths[0]],
                       "output.quantities": [], "output.plots": []})  # fmt: skip
        tr = run_scene(scene.replace(change))
        rows = marks // every
        out.append((tr.quaternions()[rows], tr.w[rows], tr.positions()[rows],
                    tr.velocities()[rows]))  # fmt: skip
    return out


def assert_equals_single_runs(scene, changes, times=TIMES, exact=True):
    run = run_samples(scene_samples(scene, changes), times, parallel=False)
    assert run.position.shape == run.velocity.shape == (len(times), len(run.q[0]), 3)
    for i, expected in enumerate(single_runs(scene, changes, times)):
        got = (run.q[:, i], run.w[:, i], run.position[:, i], run.velocity[:, i])
        for name, a, b in zip(("q", "w", "position", "velocity"), got, expected, strict=True):
            if exact:
                assert np.array_equal(a, b), (name, i, np.abs(a - b).max())
            else:
                np.testing.assert_allclose(a, b, rtol=0, atol=1e-12, err_msg=f"{name} {i}")
    return run


@pytest.mark.parametrize("first", ["motor", "quaternion"])
def test_thrown_racket_samples_equal_their_single_runs_bit_for_bit(racket, first):
    scene = racket.replace({"integrator.paths": [first]})
    # the start in space and the spin: mapped without a scene per sample
    changes = {"initial.velocity[0]": [1.0, 3.0],
               "initial.position": [[0.0, 0.0, 1.5], [1.0, -2.0, 0.5]],
               "initial.angular_velocity.body[0]": [11.0, 12.5]}  # fmt: skip
    assert_equals_single_runs(scene, changes)


def test_body_and_force_parameters_vary_per_sample(racket):
    # mass, centre of mass and the force's g: a scene per sample, the force's parameters
    # (m g) in each body's own row of the batch
    scene = racket.replace({"integrator.paths": ["motor"]})
    changes = {"body.mass": [0.3, 0.5, 0.32], "body.centre_of_mass[1]": [0.3, 0.1, 0.0],
               "forces[0].g": [[0.0, 0.0, -9.8], [0.0, 0.0, -1.6], [1.0, 0.0, -9.8]]}  # fmt: skip
    samples = scene_samples(scene, changes)
    assert samples.params[:, 2].tolist() == pytest.approx([-0.3 * 9.8, -0.5 * 1.6, -0.32 * 9.8])
    assert samples.motion[:, 0].tolist() == [0.3, 0.5, 0.32]
    assert len(samples.terms) == 1  # one kernel set: one batch
    run = assert_equals_single_runs(scene, changes)
    # the lighter pull and the centre of mass at the origin show in the flight
    assert run.position[-1, 1, 2] > run.position[-1, 0, 2]


def test_a_full_inertia_tensor_turns_in_and_out_as_the_single_run(racket):
    tensor = [[0.0151, 0.001, 0.0], [0.001, 0.0015, 0.0], [0.0, 0.0, 0.0166]]
    scene = racket.replace({"body": {"tensor": tensor, "mass": 0.32,
                                     "centre_of_mass": [0.0, 0.33, 0.0]},
                            "integrator.paths": ["motor"]})  # fmt: skip
    assert scene.principal_rotation != (1.0, 0.0, 0.0, 0.0)
    assert_equals_single_runs(scene, {"initial.velocity[2]": [1.0, 2.0]}, exact=False)


SATELLITE = {"time.duration": 40.0, "time.output_step": 20.0, "integrator.paths": ["motor"]}


def test_satellite_moments_reach_the_gravity_gradient_parameters():
    # the central field's parameters hold the moments: a scene per sample, never the
    # vectorised mapping that would leave them the scene's
    scene = load_scene("satellite_orbit").replace(SATELLITE)
    samples = scene_samples(scene, {"body.moments[0]": [250.0, 200.0]})
    one = scene_samples(scene.replace({"body.moments[0]": 200.0}), n=1)
    assert samples.params[1].tolist() == one.params[0].tolist() != samples.params[0].tolist()


@pytest.mark.long  # compiles the central field's batched loop, which no other test needs
def test_satellite_samples_equal_their_single_runs():
    scene = load_scene("satellite_orbit").replace(SATELLITE)
    assert_equals_single_runs(scene, {"body.moments[0]": [250.0, 200.0]}, times=[20.0, 40.0])


def test_a_bad_sample_is_named():
    with pytest.raises(SceneError, match=r"body.mass: sample 1: expected a finite positive"):
        scene_samples("thrown_racket", {"body.mass": [0.3, -1.0]})
    with pytest.raises(SceneError, match="velocity"):
        scene_samples("thrown_racket", {"initial.velocity[0]": [1.0, np.inf]})


SWEEP = """
[sweep]
scene = "thrown_racket"
samples = 3
seed = 5
chunk = 2
times = [0.025, 0.05]
[set]
"time.duration" = 0.05
"integrator.paths" = ["motor"]
[grid]
"body.mass" = [0.3, 0.4]
[[draw]]
key = "initial.velocity[0]"
uniform = [1.0, 3.0]
"""


# a force's parameter varies too: g's components (g set whole first, as the scene's
# default is not a key of the file)
FORCE_SWEEP = SWEEP.replace('"body.mass" = [0.3, 0.4]', '"forces[0].g[2]" = [-9.8, -1.6]')
FORCE_SWEEP = FORCE_SWEEP.replace("[grid]", '"forces[0].g" = [0.0, 0.0, -9.8]\n[grid]')


@pytest.mark.parametrize("text", [SWEEP, FORCE_SWEEP], ids=["mass", "gravity"])
def test_a_motion_sweep_runs_batched_and_equals_the_single_runs(tmp_path, text):
    ds = open_sweep(run_sweep(text, tmp_path / "s.zarr", client="sync"))
    assert ds["position"].attrs["units"] == "m" and ds["velocity"].attrs["units"] == "m/s"
    sweep = load_sweep(text)
    values = sweep.values(0, sweep.size)
    position = ds["position"].values.reshape(sweep.size, 2, 3)
    q = ds["q"].values.reshape(sweep.size, 2, 4)
    for i, (q1, _, p1, _) in enumerate(single_runs(sweep.scene, values, TIMES)):
        assert np.array_equal(position[i], p1) and np.array_equal(q[i], q1)
    # the nominal run's angle is zero where the draw sits on its centre; elsewhere finite
    assert np.isfinite(ds["angle_from_nominal"].values).all()


def test_the_budget_counts_a_moving_body_s_position_and_velocity():
    moving = load_sweep(SWEEP)
    text = SWEEP.replace("thrown_racket", "intermediate_axis_flip")
    text = text.replace('"integrator.paths" = ["motor"]', "")
    turning = load_sweep(text.replace("initial.velocity[0]", "initial.angular_velocity.body[0]"))
    a, b = budget.estimate(moving, threads=1), budget.estimate(turning, threads=1)
    assert a.files > b.files and a.bytes > b.bytes  # two more variables, a longer state


def test_a_refused_sample_of_a_motion_sweep_is_one_line(tmp_path):
    text = SWEEP.replace("[0.3, 0.4]", "[0.3, -0.4]")
    with pytest.raises(InputError) as info:
        run_sweep(text, tmp_path / "bad.zarr", client="sync")
    message = str(info.value)
    assert "\n" not in message and "body.mass" in message and "grid point 1" in message
    assert not (tmp_path / "bad.zarr").exists()


def test_a_moving_body_s_result_file_has_one_unit_a_variable_and_its_body_and_forces(
    racket, tmp_path
):
    pytest.importorskip("pint_xarray")
    import json

    import cf_xarray.units

    from ga_rotors import results

    tr = run_scene(racket)  # both paths: the motor and q with the centre of mass
    ds = results.to_dataset(tr, racket)
    assert {"motor", "q_com"}.isdisjoint(ds.data_vars)
    assert ds["motor_dual"].attrs["units"] == "m" and ds["com_position"].attrs["units"] == "m"
    assert ds["motor_rotor"].attrs["units"] == ds["q"].attrs["units"] == "1"
    # the parts are the raw states' columns, nothing lost
    motor, q_com = tr["motor"], tr["q_com"]
    assert np.array_equal(ds["motor_rotor"].values, motor[:, [0, 4, 5, 6]])
    assert np.array_equal(ds["motor_dual"].values, motor[:, [1, 2, 3, 7]])
    assert np.array_equal(ds["com_position"].values, q_com[:, 4:])
    # the centre of mass the quaternion path carries is the origin's position moved by q s
    from ga_rotors import quaternion as Q

    lever = Q.rotate(Q.normalize(ds["q"].values), [0.0, 0.33, 0.0])
    np.testing.assert_allclose(ds["com_position"].values - lever, ds["position"].values,
                               atol=1e-9)  # fmt: skip
    for registry in (None, cf_xarray.units.units):
        quantified = ds.pint.quantify(unit_registry=registry)
        metre = quantified["position"].data.units
        assert quantified["motor_dual"].data.units == metre
        assert quantified["com_position"].data.units == metre
    assert (ds.attrs["body_mass"], ds.attrs["body_mass_units"]) == (0.32, "kg")
    assert ds.attrs["body_centre_of_mass"] == [0.0, 0.33, 0.0]
    assert ds.attrs["body_centre_of_mass_units"] == "m"
    assert ds.attrs["forces"] == "uniform_gravity"
    (force,) = json.loads(ds.attrs["forces_json"])
    assert force["type"] == "uniform_gravity"
    assert force["parameters"] == pytest.approx([0.0, 0.0, -0.32 * 9.80665])
    # written and read back, and as CSV columns with their units
    back = results.read(results.write(tr, tmp_path / "run.nc", scene=racket))
    assert back["motor_dual"].attrs["units"] == "m" and back.attrs["body_mass"] == 0.32
    header = results.write_csv(tr).splitlines()[0]
    assert "motor_dual_e01 [m]" in header and "com_position_x [m]" in header
    assert "motor_rotor_1 [1]" in header and "q_w [1]" in header


def test_an_npz_archive_keeps_the_raw_states_and_names_their_parts_units(racket, tmp_path):
    import json
    import zipfile

    from ga_rotors import results

    tr = run_scene(racket)
    path = results.write_npz(tr, tmp_path / "run.npz", scene=racket)
    with zipfile.ZipFile(path) as zf:
        info = json.loads(zf.read("attributes.json"))
    assert np.array_equal(np.load(path)["motor"], tr["motor"])  # what the viewer reads
    parts = info["variables"]["motor"]["parts"]
    assert parts["motor_dual"]["units"] == "m" and parts["motor_dual"]["columns"] == [1, 2, 3, 7]
    assert info["variables"]["q_com"]["parts"]["com_position"]["units"] == "m"
    assert info["attributes"]["body_mass"] == 0.32
