"""Scene files: the schema, defaults, every orientation and angular-velocity form, errors."""

from __future__ import annotations

import copy
import math

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from ga_rotors import quaternion as Q
from ga_rotors import shapes
from ga_rotors.body import RigidBody
from ga_rotors.errors import InputError, SceneError
from ga_rotors.scene import Scene, bundled, dumps_toml, load_scene


def minimal(**sections) -> dict:
    data = {
        "body": {"moments": [1.0, 2.0, 2.5]},
        "time": {"duration": 1.0},
        "integrator": {"step": 0.01},
    }
    data.update(sections)
    return data


def scene_error(data, file="<dict>") -> SceneError:
    with pytest.raises(SceneError) as info:
        Scene(data, file=file)
    return info.value


def as_scipy(q) -> Rotation:
    q = np.asarray(q)
    return Rotation.from_quat([q[1], q[2], q[3], q[0]])  # scipy is scalar-last


# ---------------------------------------------------------------------------- defaults


def test_minimal_scene_resolves_every_default():
    s = Scene(minimal())
    d = s.data
    assert d["scene"] == {"name": "scene", "description": ""}
    assert d["initial"]["orientation"] == {"quaternion": [1.0, 0.0, 0.0, 0.0]}
    assert d["initial"]["angular_velocity"] == {"body": [0.0, 0.0, 0.0], "units": "rad/s"}
    assert d["time"] == {"start": 0.0, "duration": 1.0, "output_step": 0.01}
    assert d["integrator"] == {"method": "rk4", "step": 0.01, "paths": ["rotor"]}
    assert d["effects"] == []
    assert d["output"] == {
        "quantities": [],
        "plots": [],
        "figure_format": "png",
        "data": ["netcdf"],  # the binary default (npz without the results extra)
        "summary": True,
    }
    assert (s.steps, s.sample_every, s.kind) == (100, 1, "free")


@pytest.mark.parametrize("name", sorted(bundled()))
def test_resolved_scene_round_trips_through_toml(name):
    s = load_scene(name)
    again = Scene.from_toml(s.to_toml(), file="again.toml")
    assert again.data == s.data
    assert np.array_equal(again.orientation, s.orientation)
    assert np.array_equal(again.angular_velocity, s.angular_velocity)


def test_dumps_toml_keeps_awkward_strings():
    import tomllib

    for text in ['a\nb"""c\\n \t\x01 é', "x\n", "\n", "trail\\"]:
        data = {"scene": {"description": text}}
        assert tomllib.loads(dumps_toml(data)) == data


def test_file_name_is_the_default_scene_name(tmp_path):
    path = tmp_path / "my_top.toml"
    path.write_text(dumps_toml(minimal()))
    assert load_scene(path).name == "my_top"
    assert load_scene(str(path)).file == str(path)


# ---------------------------------------------------------------------------- bodies


def test_shape_body_uses_the_shapes_table():
    s = Scene(minimal(body={"shape": "cylinder", "mass": 12.0, "radius": 1.0, "height": 2.0}))
    assert s.body.moments == shapes.cylinder(12.0, 1.0, 2.0)
    assert s.mass == 12.0


def test_full_tensor_body_is_diagonalised_and_its_frame_recorded():
    R = Rotation.from_rotvec([0.3, -0.2, 0.5]).as_matrix()
    tensor = R @ np.diag([1.0, 2.0, 2.5]) @ R.T
    s = Scene(minimal(body={"tensor": tensor.tolist()}))
    assert np.allclose(s.body.moments, (1.0, 2.0, 2.5), rtol=1e-14)
    # P takes principal axes to the scene's body axes: M(P) diag(I) M(P)ᵀ = tensor.
    M = Q.to_matrix(s.principal_rotation)
    assert np.allclose(M @ np.diag(s.body.moments) @ M.T, tensor, atol=1e-14)
    # The scene's orientation is the one it wrote (its body frame); the loops start from
    # q_user ⊗ P (identity user orientation here), and the body carries P.
    assert np.array_equal(s.orientation, [1.0, 0.0, 0.0, 0.0])
    assert np.allclose(s.principal_orientation, s.principal_rotation, atol=0)
    assert s.body.principal_rotation == s.principal_rotation


def test_body_angular_velocity_is_carried_into_the_principal_frame():
    R = Rotation.from_rotvec([0.3, -0.2, 0.5]).as_matrix()
    tensor = R @ np.diag([1.0, 2.0, 2.5]) @ R.T
    w_user = np.array([0.3, -1.0, 2.0])
    s = Scene(minimal(body={"tensor": tensor.tolist()},
                      initial={"angular_velocity": {"body": w_user.tolist(),
                                                    "units": "rad/s"}}))  # fmt: skip
    M = Q.to_matrix(s.principal_rotation)
    assert np.array_equal(s.angular_velocity, w_user)  # the scene's body frame, as written
    assert np.allclose(M @ s.principal_angular_velocity, w_user, atol=1e-15)
    # Same kinetic energy and the same space angular momentum in both descriptions.
    assert np.isclose(s.body.energy(s.angular_velocity), 0.5 * w_user @ tensor @ w_user)
    principal = RigidBody(s.body.moments)
    assert np.isclose(principal.energy(s.principal_angular_velocity), s.body.energy(w_user))
    L_space = Q.rotate(s.orientation, s.body.momentum(s.angular_velocity))
    assert np.allclose(L_space, tensor @ w_user, atol=1e-15)
    L_body = principal.momentum(s.principal_angular_velocity)
    L_principal = Q.rotate(s.principal_orientation, L_body)
    assert np.allclose(L_principal, tensor @ w_user, atol=1e-15)


# ---------------------------------------------------------------------------- orientations


def orientation(**form) -> np.ndarray:
    return Scene(minimal(initial={"orientation": form})).orientation


def test_every_orientation_form_gives_the_same_rotation():
    target = Rotation.from_euler("ZYZ", [20.0, 35.0, -50.0], degrees=True)
    w, x, y, z = np.roll(target.as_quat(), 1)
    axis = target.as_rotvec() / np.linalg.norm(target.as_rotvec())
    forms = [
        {"euler": [20.0, 35.0, -50.0], "sequence": "ZYZ", "units": "deg"},
        {"euler": np.radians([20.0, 35.0, -50.0]).tolist(), "sequence": "ZYZ", "units": "rad"},
        {"euler": target.as_euler("xyz").tolist(), "sequence": "xyz", "units": "rad"},
        {"quaternion": [w, x, y, z]},
        # R = w − x e23 − y e31 − z e12, written with either order of each bivector.
        {"rotor": {"1": w, "e23": -x, "e31": -y, "e12": -z}},
        {"rotor": {"1": w, "e32": x, "e13": y, "e21": z}},
        {"axis": axis.tolist(), "angle": float(np.degrees(target.magnitude())), "units": "deg"},
    ]
    for form in forms:
        q = orientation(**form)
        assert (as_scipy(q) * target.inv()).magnitude() < 1e-15, form


def test_euler_angles_of_zyz_scenes_go_to_the_euler_path_exactly():
    s = Scene(minimal(initial={"orientation": {"euler": [0.0, 0.001, 0.0], "sequence": "ZYZ",
                                               "units": "deg"}}))  # fmt: skip
    assert s.euler_angles.tolist() == [0.0, math.radians(0.001), 0.0]
    other = Scene(minimal(initial={"orientation": {"euler": [0.0, 0.1, 0.0], "sequence": "ZYX",
                                                   "units": "deg"}}))  # fmt: skip
    assert other.euler_angles is None  # extracted from the quaternion by simulate


# ---------------------------------------------------------------------------- angular velocity


def test_angular_velocity_forms_and_units_agree():
    euler = {"euler": [10.0, 40.0, 70.0], "sequence": "ZYZ", "units": "deg"}
    rates = np.array([0.3, -0.2, 2.0])  # rad/s
    base = Scene(minimal(initial={"orientation": euler,
                                  "angular_velocity": {"euler_rates": rates.tolist(),
                                                       "units": "rad/s"}}))  # fmt: skip
    w_body = base.angular_velocity
    # Oracle: ω_body = 2 vec(q* q̇) with q̇ from central differences of scipy's rotation.
    h = 1e-6
    angles = np.radians([10.0, 40.0, 70.0])
    qp = np.roll(Rotation.from_euler("ZYZ", angles + h * rates).as_quat(), 1)
    qm = np.roll(Rotation.from_euler("ZYZ", angles - h * rates).as_quat(), 1)
    q = base.orientation
    oracle = 2.0 * Q.multiply(Q.conjugate(q), (qp - qm) / (2 * h))[1:]
    assert np.allclose(w_body, oracle, atol=1e-8)  # central difference: O(h²) ≈ 1e-12

    w_space = Q.rotate(q, w_body)
    for form in (
        {"body": w_body.tolist(), "units": "rad/s"},
        {"space": w_space.tolist(), "units": "rad/s"},
        {"body": np.degrees(w_body).tolist(), "units": "deg/s"},
        {"body": (w_body * 60 / (2 * np.pi)).tolist(), "units": "rpm"},
        {"euler_rates": np.degrees(rates).tolist(), "units": "deg/s"},
    ):
        s = Scene(minimal(initial={"orientation": euler, "angular_velocity": form}))
        assert np.allclose(s.angular_velocity, w_body, rtol=1e-14, atol=1e-15), form


# ---------------------------------------------------------------------------- time


def test_output_step_sets_the_sampling():
    s = Scene(minimal(time={"duration": 1.0, "output_step": 0.05}))
    assert (s.steps, s.sample_every) == (100, 5)


# ---------------------------------------------------------------------------- errors


def change(data: dict, path: str, value) -> dict:
    data = copy.deepcopy(data)
    keys = path.split(".")
    node = data
    for k in keys[:-1]:
        node = node.setdefault(k, {})
    if value is _DELETE:
        del node[keys[-1]]
    else:
        node[keys[-1]] = value
    return data


_DELETE = object()
EULER = {"euler": [0.0, 15.0, 0.0], "sequence": "ZYZ", "units": "deg"}


@pytest.mark.parametrize(
    ("path", "value", "key", "message"),
    [
        # unknown keys, with the close match suggested
        ("time.duraton", 1.0, "time.duraton", "did you mean 'duration'"),
        ("bodyy", {}, "bodyy", "did you mean 'body'"),
        ("body.mass_kg", 1.0, "body.mass_kg", "did you mean 'mass'"),
        (
            "initial.orientation",
            {"quaternon": [1, 0, 0, 0]},
            "initial.orientation.quaternon",
            "did you mean 'quaternion'",
        ),
        ("output.plot", ["omega"], "output.plot", "did you mean 'plots'"),
        # wrong types
        (
            "time.duration",
            "10",
            "time.duration",
            "expected a finite positive number (s), got string '10'",
        ),
        ("time.duration", True, "time.duration", "got boolean true"),
        ("body.moments", [1.0, "2", 3.0], "body.moments[1]", "expected a finite number"),
        ("body.moments", [1.0, 2.0], "body.moments", "expected an array of 3 numbers"),
        ("integrator.paths", "rotor", "integrator.paths", "expected an array"),
        ("output.summary", "yes", "output.summary", "expected true or false"),
        ("initial", [1, 2], "initial", "expected a table"),
        # impossible inertia
        ("body.moments", [1.0, 1.0, 3.0], "body.moments", "triangle inequality"),
        ("body.moments", [1.0, -2.0, 2.0], "body.moments", "must be positive"),
        (
            "body",
            {"tensor": [[1, 0, 0], [0, 1, 0], [0, 0, -1]]},
            "body.tensor",
            "positive definite",
        ),
        ("body", {"tensor": [[1, 0.5, 0], [0, 1, 0], [0, 0, 1]]}, "body.tensor", "symmetric"),
        ("body", {"shape": "disk", "mass": 1.0, "radius": 0.0}, "body.radius", "finite positive"),
        ("body", {"shape": "disk", "mass": 1.0}, "body.radius", "a disk needs mass and radius"),
        (
            "body",
            {"shape": "disk", "mass": 1.0, "radius": 1.0, "height": 1.0},
            "body.height",
            "a disk takes radius",
        ),
        ("body", {"shape": "cube", "mass": 1.0}, "body.shape", "unknown value 'cube'"),
        (
            "body",
            {"moments": [1, 2, 2.5], "tensor": [[1, 0, 0], [0, 1, 0], [0, 0, 1]]},
            "body",
            "exactly one of moments, tensor, shape; got moments and tensor",
        ),
        # zero and negative durations and steps
        ("time.duration", 0.0, "time.duration", "finite positive"),
        ("time.duration", -1.0, "time.duration", "finite positive"),
        ("integrator.step", 0, "integrator.step", "finite positive"),
        ("integrator.step", 0.3, "integrator.step", "divides time.duration"),
        ("time.output_step", 0.015, "time.output_step", "whole multiple of integrator.step"),
        ("time.start", float("nan"), "time.start", "finite number"),
        # missing units (never guessed)
        (
            "initial.orientation",
            {"euler": [0, 15, 0], "sequence": "ZYZ"},
            "initial.orientation.units",
            'missing; angles are ambiguous without units: expected one of "rad", "deg"',
        ),
        (
            "initial.orientation",
            {"axis": [0, 0, 1], "angle": 30},
            "initial.orientation.units",
            "missing",
        ),
        (
            "initial.angular_velocity",
            {"body": [0, 0, 1]},
            "initial.angular_velocity.units",
            "angular rates are ambiguous",
        ),
        (
            "initial.orientation",
            {"euler": [0, 15, 0], "units": "deg"},
            "initial.orientation.sequence",
            "missing",
        ),
        (
            "initial.orientation",
            {"euler": [0, 15, 0], "sequence": "ZYZ", "units": "degrees"},
            "initial.orientation.units",
            "did you mean 'deg'",
        ),
        # unknown names
        ("integrator.method", "rk45", "integrator.method", "did you mean 'rk4'"),
        (
            "initial.orientation",
            {"euler": [0, 1, 0], "sequence": "ZYY", "units": "deg"},
            "initial.orientation.sequence",
            "unknown value 'ZYY'",
        ),
        (
            "integrator.paths",
            ["rotor", "quaternions"],
            "integrator.paths[1]",
            "did you mean 'quaternion'",
        ),
        ("integrator.paths", ["rotor", "rotor"], "integrator.paths[1]", "listed twice"),
        ("integrator.paths", [], "integrator.paths", "at least one"),
        ("output.quantities", ["energy", "enrgy"], "output.quantities[1]", "did you mean 'energy'"),
        ("output.data", ["hdf5"], "output.data[0]", "expected one of csv, npz, netcdf"),
        # orientations that are not rotations
        (
            "initial.orientation",
            {"quaternion": [2, 0, 0, 0]},
            "initial.orientation.quaternion",
            "expected unit quaternions",
        ),
        (
            "initial.orientation",
            {"rotor": {"1": 1.0, "e1": 0.1}},
            "initial.orientation.rotor.e1",
            "unknown key",
        ),
        (
            "initial.orientation",
            {"rotor": {"e12": 0.6, "e21": 0.8}},
            "initial.orientation.rotor.e21",
            "the same blade as 'e12'",
        ),
        (
            "initial.orientation",
            {"axis": [0, 0, 0], "angle": 1, "units": "rad"},
            "initial.orientation.axis",
            "nonzero",
        ),
        (
            "initial.orientation",
            {"quaternion": [1, 0, 0, 0], "units": "deg"},
            "initial.orientation.units",
            "unknown key",
        ),
        (
            "initial.angular_velocity",
            {"euler_rates": [0, 0, 1], "units": "rad/s"},
            "initial.angular_velocity.euler_rates",
            "give initial.orientation as euler",
        ),
        # scene names are file names
        ("scene.name", "../evil", "scene.name", "a file name"),
        # outputs that need what the scene does not have
        ("output.quantities", ["potential_energy"], "output.quantities[0]", "needs gravity"),
    ],
)
def test_bad_scenes_name_the_file_the_key_and_what_was_expected(path, value, key, message):
    err = scene_error(change(minimal(), path, value), file="bad.toml")
    assert err.file == "bad.toml" and err.key == key, str(err)
    assert str(err).startswith(f"bad.toml: {key}: ")
    assert message in str(err), str(err)
    assert isinstance(err, InputError) and isinstance(err, ValueError)


@pytest.mark.parametrize(
    ("effects", "key", "message"),
    [
        (
            [{"type": "gravty", "pivot_to_com": [0, 0, 1]}],
            "effects[0].type",
            "did you mean 'gravity'",
        ),
        ([{"pivot_to_com": [0, 0, 1]}], "effects[0].type", "missing"),
        ([{"type": "gravity"}], "effects[0].pivot_to_com", "missing"),
        (
            [{"type": "gravity", "pivot_to_com": [0, 0, 1], "mass": 1}],
            "effects[0].mass",
            "unknown key",
        ),
        ([{"type": "gravity", "pivot_to_com": [0, 0, 1]}], "body.mass", "needs the mass"),
        ([{"type": "damping", "coefficient": -1.0}], "effects[0].coefficient", "≥ 0"),
        (
            [{"type": "gravity", "pivot_to_com": [0, 0, 1], "g": [0, 0, 0]}],
            "effects[0].g",
            "nonzero",
        ),
        ([{"type": "damping", "coefficient": [1.0, 2.0]}], "effects[0].coefficient", "array of 3"),
        ([{"type": "body_torque", "torque": [1, 2]}], "effects[0].torque", "array of 3"),
        (
            [{"type": "user", "function": "os.system"}],
            "effects[0].function",
            "'package.module:function'",
        ),
        (
            [{"type": "user", "function": "m:f", "params": ["x"]}],
            "effects[0].params[0]",
            "finite number",
        ),
        (["gravity"], "effects[0]", "expected a table"),
    ],
)
def test_bad_effects(effects, key, message):
    err = scene_error(minimal(effects=effects), file="fx.toml")
    assert err.key == key and message in str(err), str(err)


def test_gravity_is_declared_at_most_once():
    g = {"type": "gravity", "pivot_to_com": [0, 0, 0.1]}
    body = {"moments": [1.0, 1.0, 1.5], "mass": 1.0}
    err = scene_error(minimal(body=body, effects=[g, g]))
    assert err.key == "effects[1]" and "at most once" in str(err)


def test_inertia_given_about_the_pivot_must_leave_a_body_about_the_centre_of_mass():
    # About the pivot, I⊥ = 0.01 cannot hold a 1 kg mass 0.2 m away (m l² = 0.04).
    g = {"type": "gravity", "pivot_to_com": [0, 0, 0.2], "inertia_about": "pivot"}
    err = scene_error(minimal(body={"moments": [0.01, 0.01, 0.015], "mass": 1.0}, effects=[g]))
    assert err.key == "effects[0].inertia_about" and "not a rigid body" in str(err)


def test_error_output_needs_an_exact_solution():
    data = minimal(effects=[{"type": "body_torque", "torque": [0, 0, 1]}],
                   output={"plots": ["omega", "error"]})  # fmt: skip
    err = scene_error(data)
    assert err.key == "output.plots[1]" and "needs an exact solution" in str(err)
    assert "body_torque" in str(err)


def test_integrator_must_support_the_paths():
    data = minimal(integrator={"step": 0.01, "method": "rk4_renorm", "paths": ["euler"]})
    err = scene_error(data)
    assert err.key == "integrator.paths" and "cannot step the 'euler' path" in str(err)


def test_toml_syntax_errors_name_the_file_and_line():
    with pytest.raises(SceneError, match=r"^x\.toml: not valid TOML: .*line 2"):
        Scene.from_toml("[body]\nmoments = 1 2\n", file="x.toml")


def test_unknown_scene_name_suggests_a_bundled_one():
    with pytest.raises(SceneError, match="did you mean 'heavy_top'"):
        load_scene("heavy_tops")


def test_scene_files_are_data_never_code(tmp_path):
    # Strings that look like code stay strings: a number given as an expression is a type
    # error, and nothing in the file is evaluated.
    path = tmp_path / "sneaky.toml"
    marker = tmp_path / "pwned"
    path.write_text(
        "[body]\nmoments = [1, 2, 2.5]\n[time]\n"
        f"duration = \"__import__('pathlib').Path('{marker}').touch() or 1\"\n"
        "[integrator]\nstep = 0.01\n"
    )
    with pytest.raises(SceneError, match=r"time\.duration: expected a finite positive number"):
        load_scene(path)
    assert not marker.exists()


def test_replace_changes_keys_by_dotted_path():
    s = load_scene("heavy_top")
    t = s.replace({"time.duration": 0.5, "effects[0].pivot_to_com": [0.0, 0.0, 0.05]})
    assert t.steps == 5000 and t.data["effects"][0]["pivot_to_com"] == [0.0, 0.0, 0.05]
    assert s.steps == 30_000  # the original is untouched


def test_docs_describe_every_key_of_the_schema():
    from pathlib import Path

    from ga_rotors import effects
    from ga_rotors.scene.formats import FORMATS
    from ga_rotors.scene.schema import PLOTS, QUANTITIES, SECTIONS
    from ga_rotors.shapes import SHAPES

    text = (Path(__file__).resolve().parent.parent / "docs" / "scenes.md").read_text()
    keys = set(SECTIONS) | set(QUANTITIES) | set(PLOTS) | set(FORMATS) | set(SHAPES)
    keys |= {"name", "description", "moments", "tensor", "shape", "mass", "quaternion",
             "euler", "sequence", "units", "rotor", "axis", "angle", "body", "space",
             "euler_rates", "start", "duration", "output_step", "method", "step", "paths",
             "quantities", "plots", "data", "summary"}  # fmt: skip
    keys |= {d for _, dims in SHAPES.values() for d in dims}
    for kind in effects.EFFECTS.values():
        keys |= {kind.name} | {k.name for k in kind.keys}
    forms = ("`{}`", "`{} ", "`[{}]`", "`[[{}]]`", "`[{}.", '`"{}"`')
    missing = sorted(k for k in keys if not any(f.format(k) in text for f in forms))
    assert not missing, f"docs/scenes.md does not describe {missing}"


def test_adaptive_methods_take_a_tolerance_and_fixed_step_methods_refuse_one():
    s = Scene(minimal(integrator={"method": "dop853", "tolerance": 1e-12},
                      time={"duration": 1.0, "output_step": 0.1}))  # fmt: skip
    assert s.data["integrator"] == {"method": "dop853", "step": 0.1, "tolerance": 1e-12,
                                    "paths": ["rotor"]}  # fmt: skip
    assert (s.steps, s.sample_every) == (10, 1)
    assert Scene.from_toml(s.to_toml()).data == s.data
    default = Scene(minimal(integrator={"method": "dop853", "step": 0.01}))
    from ga_rotors.integrators import get

    assert default.data["integrator"]["tolerance"] == get("dop853").rtol
    cases = [
        ({"step": 0.01, "tolerance": 1e-9}, "integrator.tolerance", "rk4 is a fixed-step method"),
        ({"method": "dop853", "tolerance": 2.0}, "integrator.tolerance", "expected < 1"),
        ({"method": "dop853"}, "integrator.step", "dop853 is adaptive"),
        ({"method": "rk4"}, "integrator.step", "missing; rk4 is a fixed-step method"),
    ]
    for integrator, key, message in cases:
        err = scene_error(minimal(integrator=integrator))
        assert err.key == key and message in str(err), str(err)


@pytest.mark.parametrize(
    ("key", "message"),
    [
        ("body.moments[0]", "the scene has no body.moments; set body.moments whole"),
        ("effects[3].torque", "effects has 1 entry here; set effects whole"),
        ("initial.angular_velocity.body[5]", "initial.angular_velocity.body has 3 entries"),
        ("time.duration.x", "time.duration is a value, not a table"),
        ("body.moments[x]", "expected a dotted key path"),
        ("time..duration", "expected a dotted key path"),
    ],
)
def test_replace_with_a_key_the_scene_cannot_take_is_one_line_naming_it(key, message):
    """Scene.replace keys come from users (sweep files' [set], scripts): a path past a
    list's end or through a value is one SceneError naming the path, not an IndexError."""
    with pytest.raises(SceneError) as info:
        load_scene("heavy_top").replace({key: 1.0})
    assert info.value.key == key and message in str(info.value)
    assert "\n" not in str(info.value)


def test_replace_sets_list_entries_and_new_table_keys_still_validate():
    s = load_scene("heavy_top").replace({"initial.angular_velocity.body[2]": 50.0})
    assert s.data["initial"]["angular_velocity"]["body"][2] == 50.0
    with pytest.raises(SceneError, match=r"output\.nope: unknown key"):
        load_scene("heavy_top").replace({"output.nope": 1})
