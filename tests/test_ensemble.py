"""The batched RK4 ensemble: the same trajectory as the single-body RK4, bit for bit."""

from __future__ import annotations

import numpy as np
import pytest

from ga_rotors.ensemble import benchmark, rk4_free
from ga_rotors.errors import InputError
from ga_rotors.integrators import Problem, get


def test_each_body_follows_the_single_body_rk4_exactly():
    rng = np.random.default_rng(7)
    n = 300  # more than one chunk, and a partial last chunk
    q = rng.normal(size=(4, n))
    q /= np.linalg.norm(q, axis=0)
    w = rng.normal(size=(3, n))
    inertia = (1.0, 2.0, 3.5)
    qe, we = q.copy(), w.copy()
    rk4_free(inertia, qe, we, 0.01, 50)
    for i in (0, 17, 255, 256, 299):
        run = get("rk4").run(Problem(inertia), "quaternion", q[:, i], w[:, i], 0.0, 0.01, 50, 50)
        assert np.array_equal(run.x[-1], qe[:, i]) and np.array_equal(run.w[-1], we[:, i])


def test_rejects_wrong_layout():
    q = np.zeros((3, 4))
    with pytest.raises(InputError, match="q: expected a C-contiguous float64 array"):
        rk4_free((1.0, 2.0, 3.0), q, np.zeros((3, 4)), 0.1, 1)
    with pytest.raises(InputError, match="same number of bodies"):
        rk4_free((1.0, 2.0, 3.0), np.zeros((4, 4)), np.zeros((3, 5)), 0.1, 1)


def test_benchmark_reports_a_rate():
    assert "million body-steps/s" in benchmark(bodies=512, steps=10, repeats=1)


@pytest.mark.parametrize(
    ("argv", "says"),
    [
        (["--bodies", "-5"], "bodies: expected a positive integer, got -5"),  # was a traceback
        (["--bodies", "0"], "bodies: expected a positive integer, got 0"),  # was "0 million"
        (["--steps", "0"], "steps: expected a positive integer, got 0"),
        (["--bodies", "10000000000"], "bodies: 1e+10 bodies need 1.04e+03 GiB of arrays"),
        (["--steps", "100000000"], "steps: 1e+04 bodies x 1e+08 steps is 1e+12 body-steps"),
    ],
)
def test_bench_ensemble_refuses_absurd_sizes_in_one_line(capsys, argv, says):
    from ga_rotors.cli import main

    assert main(["bench", "ensemble", *argv]) == 2
    err = capsys.readouterr().err
    assert says in err and err.count("\n") == 1 and "Traceback" not in err


# ---------------------------------------------------------------------------- real scenes

from ga_rotors import paths as _paths  # noqa: E402
from ga_rotors.ensemble import run_samples, scene_samples  # noqa: E402
from ga_rotors.errors import SceneError  # noqa: E402
from ga_rotors.scene import load_scene  # noqa: E402
from ga_rotors.scene import run_scene as run_one  # noqa: E402


def single_run(scene, times, start=None):
    """The single run's orientation and ω of the scene's first path at ``times``, in the
    scene's body frame.

    A scene whose principal axes are its body axes: :func:`run_scene`. Otherwise (a full
    tensor, or a pivot off the axis of symmetry) ``simulate`` of the scene's body given
    with its principal rotation, from ``start`` (q, ω in the body frame: the samples'),
    answering in that frame as every output must (issue 30)."""
    from ga_rotors import simulate
    from ga_rotors.body import RigidBody

    spec = _paths.get(scene.paths[0])
    if scene.principal_rotation == (1.0, 0.0, 0.0, 0.0):
        tr = run_one(scene)
    else:
        body = RigidBody(scene.body.moments, scene.principal_rotation)
        tr = simulate(
            body, *start, duration=scene.data["time"]["duration"], step=scene.step,
            paths=scene.paths[0], integrator=scene.method, torques=scene.torques(),
            accept_lower_order=scene.data["integrator"].get("accept_lower_order", False),
            sample_every=scene.sample_every, t0=scene.data["time"]["start"],
        )  # fmt: skip
    q = spec.load().quaternions(tr[spec.array])
    rows = [int(np.argmin(np.abs(tr.t - t))) for t in times]
    assert np.allclose(tr.t[rows], times, rtol=0, atol=1e-12)
    return q[rows], tr.w[rows]


def check_samples_follow_single_runs(scene, changes, times):
    from ga_rotors import quaternion as Q

    samples = scene_samples(scene, changes)
    run = run_samples(samples, times)
    assert run.t.tolist() == list(times)
    n = len(samples)
    for i in sorted({0, n // 2, n - 1}):
        one = scene.replace({k: np.asarray(v)[i].tolist() for k, v in changes.items()})
        start = samples.orientation[i], samples.angular_velocity[i]
        # the sample's start is the scene's, turned from its principal frame to its body's
        turn = np.array(one.principal_rotation)
        assert np.allclose(Q.multiply(start[0], turn), one.orientation, rtol=0, atol=1e-15)
        assert np.allclose(Q.rotate(Q.conjugate(turn), start[1]), one.angular_velocity,
                           rtol=1e-15, atol=0)  # fmt: skip
        q, w = single_run(one, times, start)
        assert np.array_equal(run.q[:, i], q), i  # bit for bit, not close
        assert np.array_equal(run.w[:, i], w), i
    return run


def test_a_sample_of_a_gravity_scene_is_the_single_run_of_that_scene_bit_for_bit():
    scene = load_scene("heavy_top").replace({"time.duration": 0.05})  # rotor path first
    # a disk's mass cancels from its motion; the pivot distance does not
    pivots = [[0.0, 0.0, 0.03], [0.0, 0.0, 0.04], [0.0, 0.0, 0.05]]
    changes = {"body.mass": [0.8, 1.0, 1.3], "effects[0].pivot_to_com": pivots}
    run = check_samples_follow_single_runs(scene, changes, [0.01, 0.05])
    assert not np.array_equal(run.q[-1, 0], run.q[-1, 2])  # the samples do differ


def test_vectorised_samples_of_a_free_scene_follow_single_runs_bit_for_bit():
    scene = load_scene("intermediate_axis_flip").replace(
        {
            "time.duration": 0.1,
            "integrator.paths": ["quaternion"],
            "body": {"moments": [1.0e-4, 2.0e-4, 2.6e-4]},
        }
    )
    rng = np.random.default_rng(3)
    changes = {
        "body.moments": np.column_stack(
            [np.full(300, 1.0e-4), 2.0e-4 + 1e-5 * rng.random(300), np.full(300, 2.6e-4)]
        ),
        "initial.angular_velocity.body[1]": 10.0 + rng.normal(size=300),
    }
    check_samples_follow_single_runs(scene, changes, [0.05, 0.1])


def test_the_vectorised_mapping_equals_a_scene_per_sample():
    scene = load_scene("intermediate_axis_flip")
    omega = np.array([[0.0, 10.0, 0.01], [0.1, 9.0, 0.0], [0.0, 11.0, -0.2]])
    fast = scene_samples(scene, {"initial.angular_velocity.body": omega})
    for i in range(3):
        one = scene.replace({"initial.angular_velocity.body": omega[i].tolist()})
        assert np.array_equal(fast.angular_velocity[i], one.angular_velocity)
        assert tuple(fast.inertia[i]) == one.body.moments


def test_a_scene_with_off_diagonal_inertia_gives_states_in_the_tensors_frame():
    # Issue 30: every output in the frame the user wrote the body in, as simulate() with
    # the tensor's body answers; the loop integrates in the principal frame, turned into
    # it and back at the edges with SceneSamples.principal.
    from ga_rotors import simulate
    from ga_rotors.body import RigidBody

    tensor = [[2.0e-4, 1.0e-5, 0.0], [1.0e-5, 3.0e-4, 0.0], [0.0, 0.0, 4.0e-4]]
    scene = load_scene("intermediate_axis_flip").replace(
        {"body": {"tensor": tensor}, "time.duration": 0.02}
    )
    assert scene.principal_rotation != (1.0, 0.0, 0.0, 0.0)
    rates = [[0.0, 10.0, 0.01], [0.1, 12.0, 0.0]]
    samples = scene_samples(scene, {"initial.angular_velocity.body": rates})
    # the samples' start is the scene's, in the tensor's frame (as written in the file)
    assert np.allclose(samples.angular_velocity, rates, rtol=1e-15, atol=1e-15)
    start = scene.data["initial"]["orientation"]["quaternion"]
    assert np.allclose(samples.orientation, [start] * 2, rtol=0, atol=1e-15)
    run = run_samples(samples, [0.01, 0.02])
    body = RigidBody.from_tensor(tensor)
    for i in range(2):
        tr = simulate(body, samples.orientation[i], samples.angular_velocity[i], duration=0.02,
                      step=scene.step, paths=scene.paths[0], integrator=scene.method)  # fmt: skip
        rows = [10, 20]  # of 21 samples, one a step
        assert np.array_equal(tr.t[rows], run.t)
        assert np.array_equal(run.q[:, i], tr.quaternions()[rows]), i  # bit for bit
        assert np.array_equal(run.w[:, i], tr.w[rows]), i


def test_a_bad_sample_is_named_by_the_scene_key():
    scene = load_scene("intermediate_axis_flip").replace({"body": {"moments": [1, 2, 2.5]}})
    with pytest.raises(SceneError, match=r"body\.moments: sample 1: .*positive"):
        scene_samples(scene, {"body.moments": [[1.0, 2.0, 3.0], [1.0, -2.0, 3.0]]})


@pytest.mark.parametrize(
    ("moments", "message"),
    [
        ([2.0, 2.0, 1e-13], "too thin a body"),
        ([1e-310, 2.0, 2.0], "normal floats"),
        ([1.0, 2.0, 3.5], "triangle inequality"),
    ],
)
def test_a_bad_sample_between_the_first_and_the_last_is_named_too(moments, message):
    # The vectorised mapping checks its first and last sample against a Scene; the others
    # must not slip past the body's checks (a too thin body passed the old gate and ran).
    scene = load_scene("intermediate_axis_flip").replace({"body": {"moments": [1, 2, 2.5]}})
    values = np.tile([1.0, 2.0, 2.5], (5, 1))
    values[2] = moments
    with pytest.raises(SceneError, match=rf"body\.moments: sample 2: .*{message}"):
        scene_samples(scene, {"body.moments": values})


def test_ensembles_refuse_what_they_cannot_run_exactly():
    scene = load_scene("intermediate_axis_flip").replace({"time.duration": 0.01})
    samples = scene_samples(scene, n=2)
    with pytest.raises(InputError, match="times: expected increasing times on the step grid"):
        run_samples(samples, [0.0105])
    with pytest.raises(InputError, match="times"):
        run_samples(samples, [0.02])
    euler = scene_samples(scene.replace({"integrator.paths": ["euler"]}), n=2)
    with pytest.raises(InputError, match="quaternion or rotor path"):
        run_samples(euler)
    with pytest.raises(InputError, match="one value per sample"):
        scene_samples(scene, {"body.moments": 1.0})


EVERY_EFFECT = [
    {"type": "gravity", "pivot_to_com": [0.0, 0.0, 0.04]},
    {"type": "damping", "coefficient": [1e-5, 2e-5, 3e-5]},
    {"type": "body_torque", "torque": [1e-4, 0.0, -2e-4]},
    {"type": "space_torque", "torque": [0.0, 3e-4, 1e-4]},
]


# Each case compiles a batch of its own (~20 s on an empty cache). split4 calls every
# effect through the torque slot and reads the moments through rates(L, inertia); rk4's
# way (accel) is checked by default in the tests below (a user kernel, gravity kernels).
@pytest.mark.parametrize("method", [pytest.param("rk4", marks=pytest.mark.long), "split4"])
def test_every_built_in_effect_at_once_follows_the_single_run_bit_for_bit(method):
    # The built-in torques read their parameters as a tuple per sample (so the loop over
    # bodies vectorises); the single run reads them from an array: same values, same sums.
    scene = load_scene("heavy_top").replace(
        {
            "time.duration": 0.02,
            "integrator.method": method,
            "integrator.accept_lower_order": True,  # damping depends on ω
            "effects": EVERY_EFFECT,
            "output.quantities": ["angles"],
            "output.plots": [],
        }
    )
    changes = {
        "effects[1].coefficient": [[1e-5, 2e-5, 3e-5], [4e-5, 1e-5, 2e-5], [0.0, 0.0, 1e-4]],
        "effects[3].torque[1]": [3e-4, -1e-3, 0.0],
        "initial.angular_velocity.body[2]": [60.0, 55.0, 70.0],
    }
    check_samples_follow_single_runs(scene, changes, [0.01, 0.02])


USER_KERNEL = """
import numba
import numpy as np

@numba.njit(cache=False)
def pull(t, q, w, p):
    # an array operation on p: the ensemble must hand this kernel an array, not a tuple
    return (0.0, 0.0, np.sum(p[:2]) * q[0])
"""


def test_a_user_kernel_gets_its_parameters_as_an_array_and_follows_the_single_run(tmp_path):
    from ga_rotors.trust import allow_user_code

    (tmp_path / "ens_user_kernel.py").write_text(USER_KERNEL)
    (tmp_path / "user.toml").write_text(
        "[body]\nmoments = [1.0, 2.0, 2.5]\n"
        '[initial.angular_velocity]\nbody = [0.1, 2.0, 0.3]\nunits = "rad/s"\n'
        '[time]\nduration = 0.05\n[integrator]\nstep = 0.001\npaths = ["quaternion"]\n'
        '[[effects]]\ntype = "user"\nfunction = "ens_user_kernel:pull"\n'
        "params = [0.5, 0.25, 9.0]\n"
    )
    scene = load_scene(tmp_path / "user.toml")
    with allow_user_code(tmp_path):
        changes = {"effects[0].params": [[0.5, 0.25, 9.0], [1.0, 0.0, 9.0], [0.0, 2.0, 9.0]]}
        run = check_samples_follow_single_runs(scene, changes, [0.05])
    assert not np.array_equal(run.q[-1, 0], run.q[-1, 2])


def test_samples_whose_gravity_kernels_differ_each_run_their_single_runs_kernel():
    # A lever on the symmetry axis runs vertical_gravity in a single run, a lever off it
    # the general gravity: the batch runs each sample with its own (one batch per set).
    from ga_rotors import effects

    scene = load_scene("heavy_top").replace(
        {"time.duration": 0.02, "output.quantities": ["angles"], "output.plots": []}
    )
    pivots = [[0.0, 0.0, 0.03], [0.002, 0.0, 0.04], [0.0, 0.0, 0.05], [0.0, 0.001, 0.05]]
    changes = {"effects[0].pivot_to_com": pivots}
    samples = scene_samples(scene, changes)
    kernels = [samples.terms[k][0].kernel for k in samples.kernels]
    assert kernels == [effects.vertical_gravity, effects.gravity] * 2
    run = run_samples(samples, [0.01, 0.02])
    for i in range(4):
        start = samples.orientation[i], samples.angular_velocity[i]
        one = scene.replace({"effects[0].pivot_to_com": pivots[i]})
        q, w = single_run(one, [0.01, 0.02], start)
        assert np.array_equal(run.q[:, i], q) and np.array_equal(run.w[:, i], w), i


@pytest.mark.parametrize("method", ["lgvi", pytest.param("cf4", marks=pytest.mark.long)])
def test_samples_of_other_fixed_step_methods_follow_single_runs_bit_for_bit(method):
    # Their steps read the 9-tuple inertia the batch passes (moments, then each body's
    # stored Euler coefficients): lgvi indexes the moments, cf4 goes through accel (as
    # rk4 and split4 above and dp8 do: by default only lgvi's way is added to rk4's; dp8
    # left out even in the long mode: 23 s of compiling on an empty cache).
    scene = load_scene("heavy_top").replace(
        {"time.duration": 0.005, "integrator.method": method, "integrator.paths": ["quaternion"]}
    )
    changes = {"effects[0].pivot_to_com[2]": [0.03, 0.04, 0.05],
               "initial.angular_velocity.body[2]": [60.0, 55.0, 70.0]}  # fmt: skip
    check_samples_follow_single_runs(scene, changes, [0.005])


from ga_rotors.integrators.rk4 import RK4, rk4_step  # noqa: E402


def _unpacking_step(t, x, w, h, inertia, params):
    """rk4_step for a template that unpacks inertia into three names."""
    i1, i2, i3 = inertia
    return rk4_step(t, x, w, h, (i1, i2, i3), params)


def test_a_step_that_unpacks_inertia_gets_the_moments_alone(monkeypatch):
    # The batch's 9-tuple cannot be unpacked into three names: such a template is
    # compiled again with the moments alone (each stage divides; same numbers).
    from ga_rotors.integrators import TemplateIntegrator, base

    mine = TemplateIntegrator(
        name="rk4_unpacking", order=4, description="rk4 unpacking its inertia",
        conserves=(), paths=("quaternion",), steps={"torqued": _unpacking_step},
        helpers=(rk4_step,), step_limit=RK4.step_limit, evaluations=4,
    )  # fmt: skip
    monkeypatch.setitem(base._REGISTRY, mine.name, mine)
    scene = load_scene("heavy_top").replace(
        {"time.duration": 0.003, "integrator.method": mine.name,
         "integrator.paths": ["quaternion"]}
    )  # fmt: skip
    changes = {"initial.angular_velocity.body[2]": [60.0, 55.0]}
    check_samples_follow_single_runs(scene, changes, [0.003])


@pytest.mark.parametrize("scene", ["intermediate_axis_flip", "heavy_top"])
def test_running_the_same_samples_twice_gives_the_same_run_and_leaves_them_as_they_were(scene):
    # scene_samples stores ω in the layout the loops read, and the loops integrate their
    # state in place: without a copy the first run overwrote the samples' initial rates,
    # and a second run of the same samples started from the first one's end.
    s = load_scene(scene).replace({"time.duration": 0.05})
    samples = scene_samples(s, {"body.mass": np.array([1.0, 2.0])} if scene == "heavy_top"
                            else None, n=2)  # fmt: skip
    before = {k: v.copy() for k, v in vars(samples).items() if isinstance(v, np.ndarray)}
    first, second = run_samples(samples), run_samples(samples)
    for name, value in before.items():
        assert np.array_equal(getattr(samples, name), value), name
    assert np.array_equal(first.q, second.q) and np.array_equal(first.w, second.w)


def test_the_vectorised_gate_refuses_exactly_what_its_conditions_say():
    # _refused's branch-free pass against the same conditions in numpy, sample by sample,
    # on values at and past each limit: not finite (moments or rates), too small, too
    # large, too thin, outside the triangle, and good ones.
    from ga_rotors.body import MIN_MOMENT_RATIO
    from ga_rotors.ensemble import _refused

    tiny = np.finfo(float).tiny
    good = [1.0, 2.0, 2.5]
    bad_moments = [
        [np.nan, 2.0, 2.5], [1.0, np.inf, 2.5], [tiny / 2, tiny / 2, tiny / 2],
        [1.0, 1.01 / tiny, 1.01 / tiny], [1.0, 1.0, MIN_MOMENT_RATIO / 2],
        [1.0, 2.0, 3.0 + 1e-9], [3.5, 1.0, 2.0],
    ]  # fmt: skip
    edge_moments = [[1.0, 2.0, 3.0], [tiny, tiny, tiny], [1.0, 1.0, MIN_MOMENT_RATIO]]
    rates = [[0.1, 0.2, 0.3], [np.nan, 0.0, 0.0], [0.0, 0.0, -np.inf]]

    def expected(m, w):
        s, lo, hi = sum(m), min(m), max(m)
        return not (np.all(np.isfinite(m)) and np.all(np.isfinite(w))) or (
            lo < tiny or hi > 1 / tiny or lo / hi < MIN_MOMENT_RATIO
            or any(x > s - x for x in m)
        )  # fmt: skip

    for m in [good, *bad_moments, *edge_moments]:
        for w in rates:
            for where in (0, 3, 6):  # alone among good samples: first, middle, last
                moments = np.tile(good, (7, 1))
                omega = np.tile(rates[0], (7, 1))
                moments[where], omega[where] = m, w
                assert _refused(moments, omega, tiny, MIN_MOMENT_RATIO) == expected(m, w), (m, w)


@pytest.mark.parametrize(
    ("spin", "says"),
    [(1e9, "rad per step, beyond 1000"), (1e160, "the kinetic energy overflows float64")],
)
def test_a_vectorised_sample_beyond_the_scene_s_magnitude_checks_is_named(spin, says):
    # The fast route (rates set in one pass, only its first and last samples built as
    # scenes) once skipped the checks a scene makes of its own rate for the samples between,
    # so a sample spinning 1e6 rad a step ran as if it could be integrated.
    scene = load_scene("spinning_disk").replace(
        {"initial.angular_velocity": {"body": [0.0, 0.0, 15.0], "units": "rad/s"}}
    )
    with pytest.raises(SceneError, match=f"initial.angular_velocity: sample 1: .*{says}"):
        scene_samples(scene, {"initial.angular_velocity.body[2]": np.array([1.0, spin, 1.0])})
