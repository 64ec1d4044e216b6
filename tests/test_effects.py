"""Effects: torque kernels against independent oracles, and the physics they imply."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

from ga_rotors import effects, shapes
from ga_rotors import quaternion as Q
from ga_rotors.errors import SceneError
from ga_rotors.scene import Scene, run_scene
from ga_rotors.trust import ENV, allow_user_code

RNG = np.random.default_rng(11)


def random_states(n=20):
    q = Q.normalize(RNG.normal(size=(n, 4)))
    w = RNG.normal(size=(n, 3))
    return q, w


def matrix(q) -> np.ndarray:
    """Oracle: scipy's rotation matrix (body -> space) of a scalar-first quaternion."""
    return Rotation.from_quat(np.roll(q, -1)).as_matrix()


@pytest.mark.parametrize("compiled", [True, False], ids=["compiled", "python"])
def test_kernels_match_numpy_oracles(compiled):
    q_all, w_all = random_states()
    for q, w in zip(q_all, w_all, strict=True):
        q, w = tuple(q), tuple(w)
        M = matrix(q)
        weight, r = RNG.normal(size=3), RNG.normal(size=3)
        C = RNG.normal(size=(3, 3))
        tau = RNG.normal(size=3)
        call = {
            "gravity": (np.cross(r, M.T @ weight), np.r_[weight, r]),
            "space_torque": (M.T @ tau, tau),
            "body_torque": (tau, tau),
            "isotropic_damping": (-0.7 * np.array(w), np.array([0.7])),
            "damping": (-C @ w, C.ravel()),
        }
        for name, (expected, params) in call.items():
            kernel = getattr(effects, name)
            f = kernel if compiled else kernel.py_func
            got = np.array(f(0.0, q, w, np.ascontiguousarray(params)))
            assert np.allclose(got, expected, rtol=0, atol=1e-14), name


_COMPONENT = st.floats(-2.0, 2.0, allow_nan=False)
_LEVEL = st.floats(-1e3, 1e3, allow_nan=False)


@given(q=st.tuples(_COMPONENT, _COMPONENT, _COMPONENT, _COMPONENT), fz=_LEVEL, rz=_LEVEL)
def test_vertical_gravity_is_gravity_for_its_weight_and_lever(q, fz, rz):
    # Any q (the formula holds for q* f q with |q| ≠ 1 too): a few roundings of the
    # torque's scale |fz rz| |q|² apart (or of the smallest normal number, underflowing).
    p = np.array([0.0, 0.0, fz, 0.0, 0.0, rz])
    w = (0.0, 0.0, 0.0)
    tol = 1e-14 * abs(fz * rz) * (1.0 + np.dot(q, q)) + 1e-300
    for kernel, general in (
        (effects.vertical_gravity, effects.gravity),
        (effects.vertical_gravity.py_func, effects.gravity.py_func),
    ):
        assert np.allclose(kernel(0.0, q, w, p), general(0.0, q, w, p), rtol=0, atol=tol)
    assert effects.vertical_gravity(0.0, q, w, p) == effects.vertical_gravity.py_func(0.0, q, w, p)


def test_a_scene_runs_the_specialised_gravity_kernel_only_where_it_applies():
    from ga_rotors.scene import load_scene

    top = load_scene("heavy_top").replace({"output.quantities": ["angles"], "output.plots": []})
    changed = {
        "heavy top": {},
        "lever off the axis": {"effects[0].pivot_to_com": [0.01, 0.0, 0.04]},
        "tilted gravity": {"effects[0].g": [0.5, 0.0, -9.8]},
    }
    got = {k: top.replace(c).torques()[0].kernel for k, c in changed.items()}
    assert got == {
        "heavy top": effects.vertical_gravity,
        "lever off the axis": effects.gravity,
        "tilted gravity": effects.gravity,
    }


def test_parallel_axis_theorem_against_point_masses():
    # A cloud of point masses: inertia about the centre of mass and about a pivot, summed
    # directly, must agree with I_cm + m(|r|² 1 − r rᵀ) to rounding.
    x = RNG.normal(size=(50, 3))
    m = RNG.uniform(0.5, 2.0, size=50)
    com = (m[:, None] * x).sum(0) / m.sum()

    def inertia(points):
        return sum(
            mi * (p @ p * np.eye(3) - np.outer(p, p)) for mi, p in zip(m, points, strict=True)
        )

    pivot = np.array([0.3, -1.2, 0.8])
    about_pivot = effects.inertia_about_pivot(inertia(x - com), m.sum(), com - pivot)
    assert np.allclose(about_pivot, inertia(x - pivot), rtol=1e-13, atol=1e-13)


def test_rod_hanging_from_its_end_has_the_textbook_inertia():
    m, length, radius = 2.0, 1.0, 0.01
    body = {"shape": "rod", "mass": m, "length": length, "radius": radius}
    g = {"type": "gravity", "pivot_to_com": [0.0, 0.0, -length / 2]}
    s = Scene({"body": body, "time": {"duration": 1.0}, "integrator": {"step": 0.1},
               "effects": [g]})  # fmt: skip
    expected = m * radius**2 / 4 + m * length**2 / 3  # about an end, transverse
    assert np.allclose(s.body.moments, (expected, expected, m * radius**2 / 2), rtol=1e-15)
    assert s.principal_rotation == (1.0, 0.0, 0.0, 0.0)
    assert s.exact is None  # centre of mass below the pivot (−z): not the Lagrange form


def _off_axis_gravity_scene(step: float) -> Scene:
    # A box on a pivot off every principal axis: the pivot inertia is a full tensor, the
    # integration frame differs from the body frame, and the torque's r must follow.
    return Scene({
        "body": {"shape": "box", "mass": 1.5, "a": 0.3, "b": 0.2, "c": 0.1},
        "initial": {"orientation": {"axis": [1, 1, 0], "angle": 40, "units": "deg"},
                    "angular_velocity": {"body": [1.0, -2.0, 8.0], "units": "rad/s"}},
        "time": {"duration": 1.0},
        "integrator": {"step": step, "paths": ["quaternion"]},
        "effects": [{"type": "gravity", "pivot_to_com": [0.05, -0.03, 0.08]}],
        "output": {"quantities": ["total_energy"]},
    })  # fmt: skip


def test_off_axis_pivot_conserves_total_energy_at_rk4_order():
    # If r or the inertia were in the wrong frame, T + V would drift at O(1) whatever the
    # step; with both right, the drift is RK4's truncation error, O(h⁴): halving h divides
    # it by 16 (leading order; the ratio is 16 × (1 + O(h))).
    drifts = []
    for h in (4e-3, 2e-3):
        s = _off_axis_gravity_scene(h)
        assert s.principal_rotation != (1.0, 0.0, 0.0, 0.0)
        e = run_scene(s).total_energy
        drifts.append(np.abs(e - e[0]).max() / np.abs(e).max())
    assert drifts[0] > 1e-12  # far above rounding: the truncation error is what we measure
    assert 12.0 < drifts[0] / drifts[1] < 20.0


def test_space_torque_changes_the_space_momentum_linearly():
    tau = np.array([0.02, -0.01, 0.03])
    s = Scene({
        "body": {"moments": [0.01, 0.02, 0.025]},
        "initial": {"angular_velocity": {"body": [1.0, 2.0, 5.0], "units": "rad/s"}},
        "time": {"duration": 2.0},
        "integrator": {"step": 1e-3, "paths": ["rotor"]},
        "effects": [{"type": "space_torque", "torque": tau.tolist()}],
        "output": {"quantities": ["L_space"]},
    })  # fmt: skip
    tr = run_scene(s)
    free = tr.L_space - tr.t[:, None] * tau
    # RK4 error model: orientation error ~ T|ω|(|ω|h)⁴/1920 ≈ 2·5.5·(5.5e-3)⁴/1920 ≈ 5e-12
    # rad, times |L| ≈ 0.13: ~1e-12 in L. Allow 1e-11 (next-order terms, ω not constant).
    assert np.abs(free - free[0]).max() < 1e-11


def test_body_torque_spins_up_a_sphere_exactly():
    # ω̇ = τ/I is constant, so RK4 (exact for polynomials of degree ≤ 4) gives ω = τ t/I to
    # rounding, and the body turns about the fixed axis τ̂ by |τ| t²/(2I).
    tau = np.array([0.0, 0.3, 0.4])
    inertia = shapes.sphere(2.0, 0.5)[0]
    s = Scene({
        "body": {"shape": "sphere", "mass": 2.0, "radius": 0.5},
        "time": {"duration": 1.0},
        "integrator": {"step": 1e-3, "paths": ["quaternion"]},
        "effects": [{"type": "body_torque", "torque": tau.tolist()}],
    })  # fmt: skip
    tr = run_scene(s)
    assert np.allclose(tr.w, tr.t[:, None] * tau / inertia, rtol=0, atol=1e-13)
    angle = np.linalg.norm(tau) * tr.t**2 / (2 * inertia)
    exact = Q.from_axis_angle(tau, angle)
    # Per-step error of RK4 on q̇ = ½ q ω(t) with ω linear in t: O(h⁵ |ω̇|...) ≈ 1e-15.
    assert Q.distance(exact, tr.q).max() < 1e-12


def test_per_axis_damping_follows_the_principal_frame():
    R = Rotation.from_rotvec([0.4, 0.1, -0.3]).as_matrix()
    tensor = R @ np.diag([1.0, 2.0, 2.5]) @ R.T
    c = np.array([0.1, 0.2, 0.3])
    s = Scene({"body": {"tensor": tensor.tolist()}, "time": {"duration": 1.0},
               "integrator": {"step": 0.1},
               "effects": [{"type": "damping", "coefficient": c.tolist()}]})  # fmt: skip
    (term,) = s.torques()
    M = Q.to_matrix(s.principal_rotation)
    w_p = np.array([0.3, -0.5, 1.0])
    tau_p = np.array(effects.damping.py_func(0.0, (1, 0, 0, 0), tuple(w_p), np.array(term.params)))
    assert np.allclose(M @ tau_p, -np.diag(c) @ (M @ w_p), atol=1e-15)


# ---------------------------------------------------------------------------- user torques

USER = """
import numba

@numba.njit(cache=False)
def spin_up(t, q, w, p):
    return (0.0, 0.0, p[0])

def plain(t, q, w, p):
    return (0.0, 0.0, 1.0)

@numba.njit(cache=False)
def two_args(t, q):
    return (0.0, 0.0, 1.0)

@numba.njit(cache=False)
def broken(t, q, w, p):
    return (0.0, 0.0, p[5])

@numba.njit(cache=False)
def short(t, q, w, p):
    return (0.0, 1.0)
"""


@pytest.fixture
def user_scene(tmp_path, monkeypatch):
    """Write a scene file and a torque module next to it (not on sys.path)."""
    import sys

    name = f"user_torques_{tmp_path.name}"
    (tmp_path / f"{name}.py").write_text(USER + f"\nopen({str(tmp_path / 'imported')!r}, 'w')\n")

    def make(function: str, params=(2.0,)) -> Scene:
        path = tmp_path / "user.toml"
        path.write_text(
            '[body]\nshape = "sphere"\nmass = 1.0\nradius = 1.0\n'
            '[time]\nduration = 0.1\n[integrator]\nstep = 0.01\npaths = ["quaternion"]\n'
            f'[[effects]]\ntype = "user"\nfunction = "{name}:{function}"\n'
            f"params = {list(params)}\n"
        )
        from ga_rotors.scene import load_scene

        return load_scene(path)

    monkeypatch.setattr(sys, "path", list(sys.path))
    yield make, tmp_path
    sys.modules.pop(name, None)


def test_user_torque_from_the_scene_directory_runs(user_scene):
    make, where = user_scene
    s = make("spin_up", params=(0.4,))
    assert not (where / "imported").exists()  # loading a scene imports nothing
    with allow_user_code(where):
        tr = run_scene(s)
    inertia = 0.4  # ⅖ m R²
    assert np.allclose(tr.w[:, 2], 0.4 * tr.t / inertia, rtol=0, atol=1e-14)
    assert tr.meta["torques"] == ["spin_up"]
    assert str(where) not in __import__("sys").path  # the directory was only borrowed


@pytest.mark.parametrize(
    ("function", "message"),
    [
        ("plain", "is a plain Python function; expected a numba-compiled kernel"),
        ("two_args", "takes 2 arguments; expected kernel(t, q, w, p)"),
        ("broken", "raised IndexError"),
        ("short", "must return three finite numbers"),
        ("missing", "has no attribute 'missing'"),
    ],
)
def test_bad_user_torques_fail_with_the_key(user_scene, function, message):
    make, where = user_scene
    s = make(function)
    with pytest.raises(SceneError) as info, allow_user_code(where):
        run_scene(s)
    assert info.value.key == "effects[0].function" and message in str(info.value)


def test_unimportable_user_module_is_a_scene_error(tmp_path):
    s = Scene({"body": {"moments": [1, 2, 2.5]}, "time": {"duration": 1.0},
               "integrator": {"step": 0.5},
               "effects": [{"type": "user", "function": "no_such_pkg.torques:f"}]})  # fmt: skip
    with pytest.raises(SceneError) as info, allow_user_code(tmp_path):
        run_scene(s)
    assert info.value.key == "effects[0].function"
    assert "no module 'no_such_pkg' in the allowed folders" in str(info.value)


# ---------------------------------------------------------------------------- trust model


def test_a_scene_runs_no_code_without_the_opt_in(user_scene, monkeypatch):
    # The scene's own folder holds the module, and it is on sys.path too: still nothing
    # is imported, and the one-line refusal names both ways to opt in.
    make, where = user_scene
    monkeypatch.delenv(ENV, raising=False)
    monkeypatch.syspath_prepend(str(where))
    s = make("spin_up")
    with pytest.raises(SceneError) as info:
        run_scene(s)
    text = str(info.value)
    assert info.value.key == "effects[0].function" and "\n" not in text
    assert "--allow-user-code" in text and ENV in text
    assert not (where / "imported").exists()


@pytest.mark.parametrize("function", ["os:system", "json:loads", "ga_rotors.effects:gravity"])
def test_installed_modules_are_never_user_code(tmp_path, function):
    # With an opt-in for a folder, a name that resolves anywhere else on sys.path (the
    # standard library, ga_rotors itself) is refused, imported or not.
    s = Scene({"body": {"moments": [1, 2, 2.5]}, "time": {"duration": 1.0},
               "integrator": {"step": 0.5},
               "effects": [{"type": "user", "function": function}]})  # fmt: skip
    with pytest.raises(SceneError) as info, allow_user_code(tmp_path):
        run_scene(s)
    assert info.value.key == "effects[0].function"
    assert "allowed folders" in str(info.value)


def test_user_code_from_another_folder_is_refused(user_scene, tmp_path_factory):
    make, where = user_scene
    other = tmp_path_factory.mktemp("elsewhere")
    s = make("spin_up")
    with pytest.raises(SceneError, match=r"no module .* in the allowed folders"):
        with allow_user_code(other):
            run_scene(s)
    assert not (where / "imported").exists()


def test_env_setting_opts_in(user_scene, monkeypatch):
    make, where = user_scene
    monkeypatch.setenv(ENV, str(where))
    tr = run_scene(make("spin_up", params=(0.4,)))
    assert tr.meta["torques"] == ["spin_up"] and (where / "imported").exists()


def test_cli_run_asks_for_the_flag_and_runs_with_it(tmp_path):
    import subprocess
    import sys

    (tmp_path / "cli_torque_mod.py").write_text(USER)
    scene = tmp_path / "user.toml"
    scene.write_text(
        '[body]\nshape = "sphere"\nmass = 1.0\nradius = 1.0\n'
        '[time]\nduration = 0.02\n[integrator]\nstep = 0.01\npaths = ["quaternion"]\n'
        '[[effects]]\ntype = "user"\nfunction = "cli_torque_mod:spin_up"\nparams = [1.0]\n'
    )
    env = {k: v for k, v in __import__("os").environ.items() if k != ENV}
    base = [sys.executable, "-m", "ga_rotors", "run", str(scene), "--out", str(tmp_path / "o")]
    refused = subprocess.run(base, capture_output=True, text=True, timeout=300, env=env)
    assert refused.returncode == 2, refused.stderr
    assert refused.stderr.count("\n") == 1 and "--allow-user-code" in refused.stderr
    ran = subprocess.run(
        [*base, "--allow-user-code"], capture_output=True, text=True, timeout=300, env=env
    )
    assert ran.returncode == 0, ran.stderr
    assert "torques: spin_up" in ran.stdout
    named = subprocess.run(  # the folder named explicitly
        [*base, "--allow-user-code", str(tmp_path)], capture_output=True, text=True,
        timeout=300, env=env,
    )  # fmt: skip
    assert named.returncode == 0 and "torques: spin_up" in named.stdout, named.stderr
