"""Whole rigid motion (rotation and translation) on the motor and quaternion paths.

Oracles: the exact free flight of ga_rotors.reference.rigid_motion (the centre of mass on
its parabola, the exact tops about it, for any body-frame origin), clifford's Cl(3,0,1)
products for the motor path's Euler–Poincaré equation, and the two paths against each
other (different equations of the same motion).
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from ga_rotors import RigidBody, cross_check, forces, simulate
from ga_rotors import quaternion as Q
from ga_rotors.errors import InputError
from ga_rotors.paths import motor as motor_path
from ga_rotors.paths import pose as pose_path
from ga_rotors.reference.rigid_motion import FreeFlight

# A tennis racket (kg m², kg), thrown spinning near its middle axis, its frame at the
# handle's end, 0.15 m from the centre of mass.
RACKET = (0.011, 0.023, 0.031)
MASS = 0.31
HANDLE = (0.0, 0.15, 0.0)
Q0 = [1.0, 0.0, 0.0, 0.0]
W0 = [0.05, 12.0, 0.1]
P0 = [0.0, 0.0, 1.5]
V0 = [3.0, 0.0, 5.0]


def _errors(tr, ref):
    """Largest geodesic angle (rad) and distance (m) of each path from the reference."""
    exact = ref.state(tr.t)
    return {
        p: (float(np.max(Q.distance(Q.normalize(tr.quaternions(p)), exact.q))),
            float(np.abs(tr.positions(p) - exact.position).max()))
        for p in tr.paths
    }  # fmt: skip


def _thrown(body, step=1e-3, **options):
    return simulate(body, Q0, W0, duration=1.0, step=step, position=P0, velocity=V0,
                    forces=[forces.uniform_gravity(body)], paths=("motor", "quaternion"),
                    **options)  # fmt: skip


def test_a_thrown_racket_flies_on_the_exact_parabola_on_both_paths():
    body = RigidBody(RACKET, mass=MASS, centre_of_mass=HANDLE)
    tr = _thrown(body, sample_every=50)
    ref = FreeFlight(RACKET, MASS, Q0, W0, P0, V0, centre_of_mass=HANDLE)
    # RK4 at h = 1 ms on a 12 rad/s spin: (h|ω|)⁴-sized errors per unit time, ~1e-9
    for path, (angle, distance) in _errors(tr, ref).items():
        assert angle < 1e-8 and distance < 1e-8, (path, angle, distance)
    exact = ref.state(tr.t)
    assert np.abs(tr.velocities() - exact.velocity).max() < 1e-8
    assert np.abs(tr.w - exact.w).max() < 1e-7
    [check] = cross_check(tr)
    assert check.paths == ("motor", "quaternion")
    assert check.max_angle < 1e-8 and check.max_distance < 1e-8
    assert "m apart" in str(check)


def test_the_error_falls_as_h_to_the_fourth():
    body = RigidBody(RACKET, mass=MASS, centre_of_mass=HANDLE)
    ref = FreeFlight(RACKET, MASS, Q0, W0, P0, V0, centre_of_mass=HANDLE)
    coarse, fine = (_errors(_thrown(body, step=h, sample_every=int(0.5 / h)), ref)
                    for h in (1e-2, 5e-3))  # fmt: skip
    for path in ("motor", "quaternion"):
        for k in range(2):  # the angle and the distance
            order = np.log2(coarse[path][k] / fine[path][k])
            assert 3.6 < order < 4.4, (path, k, order)


def test_a_body_given_by_a_turned_tensor_answers_in_its_own_frame():
    c, s = np.cos(0.3), np.sin(0.3)
    turn = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
    offset = (0.05, 0.1, -0.02)
    body = RigidBody.from_tensor(turn @ np.diag(RACKET) @ turn.T, mass=MASS,
                                 centre_of_mass=offset)  # fmt: skip
    tr = _thrown(body, sample_every=100)
    ref = FreeFlight(body, MASS, Q0, W0, P0, V0, centre_of_mass=offset)
    for path, (angle, distance) in _errors(tr, ref).items():
        assert angle < 1e-8 and distance < 1e-8, (path, angle, distance)
    assert np.abs(tr.w - ref.state(tr.t).w).max() < 1e-7  # ω in the tensor's frame
    # the motor hands out the pose of the user's frame: its point s is the centre of mass
    centre = tr.motors("motor")
    from ga_rotors import motor

    assert np.allclose(motor.apply(centre, offset), ref.state(tr.t).centre_of_mass,
                       rtol=0, atol=1e-8)  # fmt: skip
    assert np.allclose(tr.motors("quaternion"), tr.motors("motor"), rtol=0, atol=1e-8)


def test_without_forces_the_centre_moves_on_a_straight_line_bit_for_bit_on_the_pose_path():
    body = RigidBody(RACKET, mass=MASS)
    tr = simulate(body, Q0, W0, duration=1.0, step=1e-2, position=P0, velocity=V0,
                  paths=("quaternion",))  # fmt: skip
    c = tr["q_com"][:, 4:]
    assert np.array_equal(c[:, 1], np.zeros(len(tr)))  # no velocity along y: exactly 0
    assert np.allclose(c, np.add(P0, np.outer(tr.t, V0)), rtol=0, atol=1e-13)


def _line(u, m):
    """The line −I₃u − e0 m as clifford's (e01, e02, e03, e12, e13, e23) coefficients."""
    return np.array([-m[0], -m[1], -m[2], -u[2], u[1], -u[0]])


@settings(max_examples=30, deadline=None)
@given(st.lists(st.floats(-3, 3), min_size=19, max_size=19),
       st.floats(0.1, 5.0), st.floats(0.1, 2.0))  # fmt: skip
def test_the_motor_path_solves_the_euler_poincare_equation_of_its_velocity_line(v, mass, i1):
    """Ḃ = I⁻¹[Π × B + W] with clifford's commutator: the motor path's ``accel``, whose
    inertia map is inverted in closed form through the centre of mass."""
    clifford = pytest.importorskip("clifford")
    del clifford
    from clifford import pga

    moments = (i1, i1 + 0.5, i1 + 0.7)
    s = np.array(v[0:3]) / 3.0
    body = (*moments, mass, *s)
    q = Q.normalize(np.add(v[3:7], [4.0, 0.0, 0.0, 0.0]))
    x = tuple(motor_path.initial_state(q, v[7:10], [0.0] * 3, [0.0] * 3, s)[0])
    w, vel = np.array(v[10:13]), np.array(v[13:16])
    force, torque_c = np.array(v[16:19]), np.array(v[0:3]) * 0.7
    f = (*force, *torque_c)
    got = motor_path.accel(x, (*w, *vel), body, f)

    # the inertia map about the body origin, and the force line, in body components
    vc = vel + np.cross(w, s)
    momentum = mass * vc
    spin = np.array(moments) * w + np.cross(s, momentum)
    f_body = Q.rotate(Q.conjugate(q), force)
    moment = torque_c + np.cross(s, f_body)

    def mv(line):
        value = np.zeros(16)
        value[5:11] = line
        return pga.layout.MultiVector(value)

    B, Pi, W = mv(_line(w, vel)), mv(_line(momentum, spin)), mv(_line(f_body, moment))
    rate = (0.5 * (Pi * B - B * Pi) + W).value[5:11]  # Π̇ = Π × B + W
    dP, dH = np.array([-rate[5], rate[4], -rate[3]]), -rate[0:3]  # Π̇ = −I₃Ṗ − e0 Ḣ
    # the inertia map is linear and fixed in the body: Ṗ = m (v̇ + ω̇ × s) and
    # Ḣ = I ω̇ + s × Ṗ, solved for (ω̇, v̇)
    dw = (dH - np.cross(s, dP)) / np.array(moments)
    dv = dP / mass - np.cross(dw, s)
    assert np.allclose(got, np.concatenate([dw, dv]), rtol=1e-11, atol=1e-11)


def test_the_pose_and_motor_states_describe_the_same_body():
    q = Q.normalize([0.9, 0.1, -0.3, 0.2])
    s = np.array([0.1, -0.2, 0.3])
    args = (q, [1.0, 2.0, 3.0], [0.4, -0.5, 0.6], [-1.0, 0.5, 2.0], s)
    xm, wm = motor_path.initial_state(*args)
    xp, wp = pose_path.initial_state(*args)
    body = (1.0, 2.0, 2.5, 3.0, *s)
    for path, x, w in ((motor_path, xm, wm), (pose_path, xp, wp)):
        assert np.allclose(path.positions(x, s), [1.0, 2.0, 3.0], rtol=0, atol=1e-15)
        assert np.allclose(path.velocities(x, w, s), [-1.0, 0.5, 2.0], rtol=0, atol=1e-15)
    centre_m = motor_path.centre_of_mass(tuple(xm), tuple(wm), body)
    centre_p = pose_path.centre_of_mass(tuple(xp), tuple(wp), body)
    assert np.allclose(np.concatenate(centre_m), np.concatenate(centre_p), rtol=0, atol=1e-15)
    back = motor_path.from_centre_of_mass(*centre_m, body)
    assert np.allclose(back[0], xm, rtol=0, atol=1e-15)
    assert np.allclose(back[1], wm, rtol=0, atol=1e-15)


def test_bad_motion_requests_get_one_line_naming_the_argument():
    ball = RigidBody((1.0, 1.0, 1.0), mass=1.0)
    with pytest.raises(InputError, match=r"^body.mass: a body moving through space needs"):
        simulate((1.0, 1.0, 1.0), Q0, W0, duration=1.0, step=0.5, position=P0)
    with pytest.raises(InputError, match=r"^paths: the 'euler' path integrates the orientat"):
        simulate(ball, Q0, W0, duration=1.0, step=0.5, position=P0, paths="euler")
    with pytest.raises(InputError, match=r"^paths: the 'motor' path integrates a whole rigid"):
        simulate(ball, Q0, W0, duration=1.0, step=0.5, paths="motor")
    with pytest.raises(InputError, match=r"^position: expected .*shape .*3"):
        simulate(ball, Q0, W0, duration=1.0, step=0.5, position=[1.0, 2.0])
    with pytest.raises(InputError, match=r"^velocity: .*finite"):
        simulate(ball, Q0, W0, duration=1.0, step=0.5, velocity=[1.0, np.nan, 0.0])
    with pytest.raises(InputError, match=r"^forces: expected ForceTerm items"):
        simulate(ball, Q0, W0, duration=1.0, step=0.5, forces=["gravity"])
    with pytest.raises(InputError, match=r"^body.mass: uniform_gravity acts on a body with"):
        forces.uniform_gravity(RigidBody((1.0, 1.0, 1.0)))
    with pytest.raises(InputError, match=r"^path: this trajectory is a rotation about a fixed"):
        simulate((1.0, 1.0, 1.0), Q0, [0.0, 0.0, 0.1], duration=1.0, step=0.5).positions()


def test_a_batch_of_thrown_bodies_is_each_bodys_own_run_bit_for_bit():
    """The batched loop (ensembles) takes the very step a single run compiles (its
    scheduling over threads is the rotations', tests/test_ensemble.py)."""
    from ga_rotors.integrators import Batch, Problem, get
    from ga_rotors.paths import resolve

    body = RigidBody(RACKET, mass=MASS, centre_of_mass=HANDLE)
    problem = Problem(RACKET, mass=MASS, centre_of_mass=HANDLE,
                      forces=(forces.uniform_gravity(body),))  # fmt: skip
    rng = np.random.default_rng(3)
    n = 300  # more than one block of the batched loop (256)
    q = Q.normalize(rng.normal(size=(n, 4)))
    w, p, v = rng.normal(size=(n, 3)) * 5, rng.normal(size=(n, 3)), rng.normal(size=(n, 3))
    for path in ("motor", "quaternion"):
        module = resolve(path, moves=True).load()
        starts = [module.initial_state(q[i], p[i], w[i], v[i], HANDLE) for i in range(n)]
        x0, r0 = np.array([s[0] for s in starts]), np.array([s[1] for s in starts])
        batch = Batch(problem, np.tile(problem.body, (n, 1)))
        run = get("rk4").run(batch, path, x0, r0, 0.0, 1e-3, 40, [10, 40], parallel=False)
        assert run.x.shape == (2, n, module.DIM) and run.w.shape == (2, n, 6)
        for i in (0, 255, 256, n - 1):
            one = get("rk4").run(problem, path, x0[i], r0[i], 0.0, 1e-3, 40, 10)
            assert np.array_equal(one.x[[1, 4]], run.x[:, i]), (path, i)
            assert np.array_equal(one.w[[1, 4]], run.w[:, i]), (path, i)


def test_velocity_lines_are_the_space_angular_velocity_and_the_velocity_at_the_origin():
    body = RigidBody(RACKET, mass=MASS, centre_of_mass=HANDLE)
    tr = _thrown(body, sample_every=100)
    from ga_rotors import motor

    w_space, v_origin = motor.velocities(tr.velocity_lines())
    q = Q.normalize(tr.quaternions())
    assert np.allclose(w_space, Q.rotate(q, tr.w), rtol=0, atol=1e-12)
    # the body point now at the space origin moves at v − ω × p (v, p the frame origin's)
    expected = tr.velocities() - np.cross(w_space, tr.positions())
    assert np.allclose(v_origin, expected, rtol=0, atol=1e-11)
