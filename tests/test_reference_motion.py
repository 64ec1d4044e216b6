"""The exact rigid motions (ga_rotors.reference.rigid_motion) against an independent oracle:
the Newton–Euler equations written about the body origin (not the centre of mass: the
coupled form, with the parallel-axis inertia and the first moment m s), integrated by
scipy's DOP853 at rtol 1e-12, plus the invariants each motion keeps.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from ga_rotors import motor
from ga_rotors import quaternion as Q
from ga_rotors.body import RigidBody
from ga_rotors.errors import InputError
from ga_rotors.reference.rigid_motion import FreeFlight, SpringAtCentreOfMass


def skew(s):
    return np.array([[0.0, -s[2], s[1]], [s[2], 0.0, -s[0]], [-s[1], s[0], 0.0]])


def newton_euler(body: RigidBody, mass, q0, w0, p0, v0, s, force, times):
    """(q, p) at ``times`` from the equations about the body origin O, s = O→centre (body).

    Unknowns: orientation q, body angular velocity ω, origin position p (space), origin
    velocity in body axes u. With the CM's acceleration u̇ + ω×u + ω̇×s + ω×(ω×s):
      m u̇ − m [s]× ω̇ = F_b − m ω×u − m ω×(ω×s)
      m [s]× u̇ + I_O ω̇ = s×F_b − ω×(I_O ω) − m s×(ω×u),   I_O = I_c + m(|s|² 1 − s sᵀ),
    F_b the body components of ``force(c, q)``, c = p + q s q* the centre of mass.
    """
    R0 = Q.to_matrix(body.principal_rotation)
    inertia = R0 @ np.diag(body.moments) @ R0.T + mass * (s @ s * np.eye(3) - np.outer(s, s))
    lhs = np.block([[mass * np.eye(3), -mass * skew(s)], [mass * skew(s), inertia]])

    def rhs(_, y):
        q, w, p, u = y[:4] / np.linalg.norm(y[:4]), y[4:7], y[7:10], y[10:13]
        R = Q.to_matrix(q)
        f = R.T @ force(p + R @ s, q)
        b = np.r_[f - mass * np.cross(w, u) - mass * np.cross(w, np.cross(w, s)),
                  np.cross(s, f) - np.cross(w, inertia @ w) - mass * np.cross(s, np.cross(w, u))]
        acc = np.linalg.solve(lhs, b)
        return np.r_[0.5 * Q.multiply(q, np.r_[0.0, w]), acc[3:], R @ u, acc[:3]]  # fmt: skip

    u0 = Q.to_matrix(q0).T @ v0
    sol = solve_ivp(rhs, (0.0, times[-1]), np.r_[q0, w0, p0, u0], method="DOP853",
                    t_eval=times, rtol=1e-12, atol=1e-12)  # fmt: skip
    y = sol.y.T
    return Q.normalize(y[:, :4]), y[:, 7:10]


BODIES = {
    "asymmetric": RigidBody((0.011, 0.023, 0.031)),  # a tennis racket's proportions
    "symmetric": RigidBody((0.02, 0.02, 0.035)),
    "turned tensor": RigidBody.from_tensor(
        [[0.02, 0.003, 0.0], [0.003, 0.025, 0.001], [0.0, 0.001, 0.03]]
    ),
}
q0 = Q.from_rotation_vector([0.3, -0.2, 0.9])
w0 = np.array([0.4, 9.0, 0.3])  # near the middle axis of the asymmetric body
p0, v0 = np.array([0.0, 0.0, 1.5]), np.array([3.0, 0.5, 6.0])
offset = np.array([0.05, -0.12, 0.02])  # body origin 13 cm from the centre of mass
times = np.linspace(0.0, 1.2, 7)


@pytest.mark.parametrize("name", BODIES)
def test_free_flight_is_newton_euler_about_an_offset_origin(name):
    body, mass, g = BODIES[name], 0.31, np.array([0.0, 0.0, -9.81])
    flight = FreeFlight(body, mass, q0, w0, p0, v0, gravity=g, centre_of_mass=offset)
    q, p = flight.at(times)
    q_ref, p_ref = newton_euler(body, mass, q0, w0, p0, v0, offset, lambda c, q: mass * g, times)
    # measured: 8e-15 to 8e-14 rad and 2e-12 to 3.5e-12 m, the integration's own error
    assert Q.distance(q, q_ref).max() < 1e-11
    assert np.abs(p - p_ref).max() < 2e-11


@pytest.mark.parametrize("name", ["asymmetric", "symmetric"])
def test_spring_at_the_centre_of_mass_is_newton_euler_about_an_offset_origin(name):
    body, mass, k = BODIES[name], 0.31, 25.0
    anchor, g = np.array([0.5, 0.0, 1.0]), np.array([0.0, 0.0, -9.81])
    spring = SpringAtCentreOfMass(body, mass, k, q0, w0, p0, v0, anchor=anchor, gravity=g,
                                  centre_of_mass=offset)  # fmt: skip
    q, p = spring.at(times)
    force = lambda c, q: -k * (c - anchor) + mass * g  # noqa: E731
    q_ref, p_ref = newton_euler(body, mass, q0, w0, p0, v0, offset, force, times)
    # measured: 8e-15 to 8e-14 rad and 2e-12 to 3.5e-12 m, the integration's own error
    assert Q.distance(q, q_ref).max() < 1e-11
    assert np.abs(p - p_ref).max() < 2e-11


def test_the_centre_of_mass_is_the_moved_offset_and_the_motors_are_the_poses():
    flight = FreeFlight(BODIES["asymmetric"], 0.31, q0, w0, p0, v0, centre_of_mass=offset)
    s = flight.state(times)
    M = flight.motors(times)
    assert np.allclose(motor.apply(M, offset), s.centre_of_mass, rtol=0, atol=1e-14)
    back_q, back_p = motor.to_pose(M)
    assert np.array_equal(back_p, s.position) or np.abs(back_p - s.position).max() < 1e-14
    assert Q.distance(back_q, s.q).max() < 1e-15
    # the parabola exactly: ċ is linear in t, c(t) the closed form
    assert np.allclose(np.diff(s.velocity + np.cross(Q.rotate(s.q, s.w), s.centre_of_mass
                                                     - s.position), axis=0),
                       np.diff(times)[:, None] * flight.gravity, rtol=0, atol=1e-13)  # fmt: skip


@pytest.mark.parametrize("kind", ["flight", "spring"])
def test_energy_and_momenta_are_conserved(kind):
    body, mass = BODIES["asymmetric"], 0.31
    if kind == "flight":
        motion = FreeFlight(body, mass, q0, w0, p0, v0, centre_of_mass=offset)
    else:
        motion = SpringAtCentreOfMass(body, mass, 25.0, q0, w0, p0, v0, anchor=[1.0, 0, 0],
                                      gravity=[0, 0, -9.81], centre_of_mass=offset)  # fmt: skip
    s = motion.state(np.linspace(0.0, 5.0, 11))
    c = s.centre_of_mass
    cdot = s.velocity + np.cross(Q.rotate(s.q, s.w), c - s.position)
    energy = 0.5 * mass * np.einsum("ij,ij->i", cdot, cdot) + body.energy(s.w)
    energy -= mass * c @ motion.gravity
    if kind == "spring":
        stretch = c - motion.anchor
        energy += 0.5 * motion.stiffness * np.einsum("ij,ij->i", stretch, stretch)
    assert np.allclose(energy, motion.energy(), rtol=1e-13, atol=0)
    L = Q.rotate(s.q, body.momentum(s.w))  # about the centre of mass: no torque there
    assert np.abs(L - L[0]).max() < 1e-13
    if kind == "flight":
        t = np.linspace(0.0, 5.0, 11)[:, None]
        assert np.allclose(mass * cdot, motion.momentum() + mass * motion.gravity * t,
                           rtol=0, atol=1e-13)  # fmt: skip


def test_at_rest_without_gravity_nothing_moves():
    flight = FreeFlight((1.0, 2.0, 3.0), 1.0, q0, [0.0, 0.0, 0.0], p0, [0.0, 0.0, 0.0],
                        gravity=[0.0, 0.0, 0.0], centre_of_mass=offset)  # fmt: skip
    q, p = flight.at([0.0, 1e3])
    assert np.array_equal(p, [p0, p0]) and Q.distance(q[1], q0) == 0.0


def test_spring_in_equilibrium_stays_and_long_runs_keep_the_period():
    spring = SpringAtCentreOfMass((1.0, 1.0, 1.0), 2.0, 8.0, [1.0, 0, 0, 0], [0.0, 0.0, 0.0],
                                  [0.0, 0.0, -2.4516625], [0.0, 0.0, 0.0],
                                  gravity=[0.0, 0.0, -9.80665])  # fmt: skip
    assert np.allclose(spring.equilibrium, [0.0, 0.0, -2.4516625], rtol=0, atol=1e-15)
    assert np.abs(spring.state([0.0, 7.3, 1e4]).position - spring.equilibrium).max() < 1e-15
    moving = SpringAtCentreOfMass((1.0, 1.0, 1.0), 2.0, 8.0, [1.0, 0, 0, 0], [0.0, 0.0, 0.0],
                                  [1.0, 0.0, 0.0], [0.0, 0.0, 0.0])  # fmt: skip
    n = 10**6  # periods of π s: the phase 2·10⁶ π carries a few ulps of itself
    assert np.allclose(moving.state([n * np.pi]).position, [[1.0, 0.0, 0.0]], rtol=0, atol=1e-9)


def test_bad_arguments_are_named():
    good = dict(body=(1.0, 2.0, 3.0), mass=1.0, orientation=[1.0, 0, 0, 0],
                angular_velocity=[0, 0, 1.0], position=[0, 0, 0], velocity=[0, 0, 0])  # fmt: skip
    for change, message in [
        ({"mass": 0.0}, "mass: expected one positive number"),
        ({"mass": [1.0, 2.0]}, "mass: expected one positive number"),
        ({"position": [0.0, 0.0]}, r"position: expected an array of shape \(\.\.\., 3\)"),
        ({"velocity": [[0.0, 0, 0]]}, "velocity: expected one vector"),
        ({"orientation": [2.0, 0, 0, 0]}, "orientation: expected unit quaternions"),
    ]:
        with pytest.raises(InputError, match=message):
            FreeFlight(**{**good, **change})
    with pytest.raises(InputError, match="stiffness: expected one positive number"):
        SpringAtCentreOfMass(stiffness=-1.0, **good)
    with pytest.raises(InputError, match="centre_of_mass: contains nan"):
        FreeFlight(**good, centre_of_mass=[0.0, np.nan, 0.0])
