"""Forces on a moving body: kernels against their potentials, exact references, balances.

Oracles: the harmonic oscillator of a zero-length spring at the centre of mass
(ga_rotors.reference.rigid_motion.SpringAtCentreOfMass, gravity too), the closed form of
linear drag (v_c = v₀ e^(−bt/m)), finite differences of each declared potential, and the
balance laws of mechanics (ga_rotors.balances) for a mix of every force.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from ga_rotors import RigidBody, balances, cross_check, simulate
from ga_rotors import forces as F
from ga_rotors import quaternion as Q
from ga_rotors.errors import InputError
from ga_rotors.reference.rigid_motion import FreeFlight, SpringAtCentreOfMass

MOMENTS = (0.011, 0.023, 0.031)
MASS = 0.31
Q0 = Q.normalize([0.9, 0.1, -0.2, 0.3])
W0 = [0.4, 6.0, -0.3]


def _exact_errors(tr, ref):
    exact = ref.state(tr.t)
    return max(
        max(float(np.max(Q.distance(Q.normalize(tr.quaternions(p)), exact.q))),
            float(np.abs(tr.positions(p) - exact.position).max()))
        for p in tr.paths
    )  # fmt: skip


def test_a_spring_at_the_centre_of_mass_is_the_exact_oscillator_beside_the_free_top():
    offset = (0.02, 0.15, -0.01)
    body = RigidBody(MOMENTS, mass=MASS, centre_of_mass=offset)
    spring = F.spring(body, 12.0, [0.5, 0.0, 1.0], at=offset)
    weight = F.uniform_gravity(body)
    assert sorted(spring.conserves) == ["angular_momentum", "energy", "spin"]
    tr = simulate(body, Q0, W0, duration=2.0, step=1e-3, position=[0.0, 0.0, 1.2],
                  velocity=[0.3, -0.2, 0.5], forces=[spring, weight],
                  paths=("motor", "quaternion"), sample_every=20)  # fmt: skip
    ref = SpringAtCentreOfMass(MOMENTS, MASS, 12.0, Q0, W0, [0.0, 0.0, 1.2], [0.3, -0.2, 0.5],
                               anchor=[0.5, 0.0, 1.0], gravity=(0.0, 0.0, -F.STANDARD_GRAVITY),
                               centre_of_mass=offset)  # fmt: skip
    assert _exact_errors(tr, ref) < 1e-9
    [check] = cross_check(tr)
    assert check.max_angle < 1e-9 and check.max_distance < 1e-9


def test_linear_drag_slows_the_centre_exponentially():
    body = RigidBody(MOMENTS, mass=MASS, centre_of_mass=(0.0, 0.1, 0.0))
    b, v0 = 0.05, np.array([3.0, 1.0, 5.0])
    drag = F.linear_drag(body, b)
    tr = simulate(body, Q0, W0, duration=2.0, step=1e-3, velocity=v0, forces=[drag],
                  paths=("quaternion",), sample_every=100)  # fmt: skip
    decay = np.exp(-b * tr.t / MASS)[:, None]
    ref = FreeFlight(MOMENTS, MASS, Q0, W0, [0.0] * 3, v0, gravity=(0.0, 0.0, 0.0),
                     centre_of_mass=(0.0, 0.1, 0.0))  # the rotation is the free top's  # fmt: skip
    free = ref.state(tr.t)
    c0, vc0 = ref.c0, ref.cdot0
    centre = c0 + vc0 * MASS / b * (1.0 - decay)
    assert np.abs(tr["q_com"][:, 4:] - centre).max() < 1e-11
    assert np.max(Q.distance(Q.normalize(tr.quaternions()), free.q)) < 1e-9
    # the drag reads the velocity: the splittings, exact only for forces of pose, refuse it
    with pytest.raises(InputError, match=r"^integrator: split2 .* force 'linear_drag' reads the"):
        simulate(body, Q0, W0, duration=2.0, step=1e-3, velocity=v0,
                 forces=[F.linear_drag(body, b)], integrator="split2")  # fmt: skip


def test_every_force_together_keeps_the_balance_laws():
    """A body on a spring at a point off its centre of mass, pushed by a thrust fixed in the
    body, pulled by a constant space force at another point, slowed by drag, with gravity:
    no exact solution, but energy, momentum and angular momentum balance."""
    body = RigidBody(MOMENTS, mass=MASS, centre_of_mass=(0.0, 0.12, 0.0))
    terms = [
        F.spring(body, 8.0, [0.0, 0.0, 2.0], at=(0.05, 0.3, 0.0), rest_length=0.4),
        F.point_force(body, [0.0, 0.0, 0.2], at=(0.0, 0.3, 0.0), fixed_in="body"),
        F.point_force(body, [0.1, 0.0, 0.0], at=(0.0, -0.05, 0.02)),
        F.linear_drag(body, 0.02),
        F.uniform_gravity(body),
    ]
    tr = simulate(body, Q0, W0, duration=1.0, step=1e-3, position=[0.0, 0.0, 1.5],
                  velocity=[0.3, -0.2, 0.5], forces=terms,
                  paths=("motor", "quaternion"))  # fmt: skip
    [check] = cross_check(tr)
    assert check.max_angle < 1e-9 and check.max_distance < 1e-9
    rows = {row.name: row for row in balances.balances(tr, body, terms)}
    assert set(rows) == {"energy", "linear_momentum", "angular_momentum"}
    assert not any(row.conserved for row in rows.values())
    for row in rows.values():  # RK4's error (~1e-12) and Simpson's on 1 ms samples
        assert row.relative < 1e-9, str(row)
    # without drag and thrust the rest conserves energy, exactly as the balance states
    conservative = [terms[0], terms[2], terms[4]]
    assert balances.conserved(conservative)["energy"]
    # and a wrong force set is caught: the balance of the run against gravity alone fails
    wrong = {row.name: row for row in balances.balances(tr, body, [terms[4]])}
    assert wrong["energy"].relative > 1e-3 and wrong["linear_momentum"].relative > 1e-3


def test_a_satellite_keeps_its_energy_and_angular_momentum_about_the_earth():
    """One orbit at 7000 km, attitude and orbit together under the Earth's field and its
    gravity gradient, the frame at a docking port 1 m from the centre of mass."""
    sat = RigidBody((10.0, 12.0, 8.0), mass=100.0, centre_of_mass=(-1.0, 0.0, 0.0))
    field = F.central_gravity(sat)
    r0 = 7.0e6
    tr = simulate(sat, Q.from_axis_angle([0.3, 0.2, 1.0], 0.4), [0.001, -0.0005, 0.0012],
                  duration=5828.0, step=2.0, position=[r0, 0.0, 0.0],
                  velocity=[0.0, np.sqrt(F.EARTH_MU / r0), 0.0], forces=[field],
                  paths=("motor", "quaternion"), sample_every=31)  # fmt: skip
    [check] = cross_check(tr)  # ≤ 1e-8 rad and ≤ 1e-8 of the orbit's radius
    assert check.max_angle < 1e-8 and check.max_distance < 1e-8 * r0
    rows = {row.name: row for row in balances.balances(tr, sat, [field])}
    assert rows["energy"].conserved and rows["angular_momentum"].conserved
    assert rows["angular_momentum"].label == "angular momentum about (0, 0, 0)"
    # RK4 at 2 s a step: the orbit's phase error per step ~(1e-3)⁵, energy kept to 1e-11
    assert rows["energy"].relative < 1e-10 and rows["angular_momentum"].relative < 1e-10
    # the gravity gradient turns the body: the spin alone is not kept
    assert not balances.conserved([field])["spin"]


@settings(max_examples=25, deadline=None)
@given(st.lists(st.floats(-1.0, 1.0), min_size=13, max_size=13))
def test_each_potential_is_minus_the_work_of_its_force(v):
    """F = −∂V/∂c and τ = −∂V/∂θ (a turn by θ about a body axis), central differences."""
    body = RigidBody(MOMENTS, mass=MASS, centre_of_mass=(0.0, 0.1, 0.0))
    q = tuple(Q.normalize(np.add(v[0:4], [2.0, 0.0, 0.0, 0.0])))
    c = np.array(v[4:7])
    at = np.array(v[7:10]) * 0.3
    for term in (F.uniform_gravity(body, g=v[10:13]),
                 F.spring(body, 7.0, [0.2, -0.1, 0.3], at=at, rest_length=0.1),
                 F.point_force(body, v[10:13], at=at),
                 F.central_gravity(body, 3.0, np.add(v[10:13], [4.0, 0.0, 0.0]))):  # fmt: skip
        p = np.asarray(term.params)
        f = np.array(term.kernel(0.0, q, tuple(c), (0.0,) * 3, (0.0,) * 3, p))
        d = 1e-6
        for k in range(3):
            e = np.eye(3)[k] * d
            up, down = term.potential(q, tuple(c + e), p), term.potential(q, tuple(c - e), p)
            grad = (up - down) / (2 * d)
            assert abs(f[k] + grad) < 1e-6 * (1.0 + abs(f[k])), (term.name, k)
            turn = [np.cos(d / 2), *(np.sin(d / 2) * np.eye(3)[k])]
            back = [np.cos(d / 2), *(-np.sin(d / 2) * np.eye(3)[k])]
            plus = term.potential(tuple(Q.multiply(q, turn)), tuple(c), p)
            minus = term.potential(tuple(Q.multiply(q, back)), tuple(c), p)
            assert abs(f[3 + k] + (plus - minus) / (2 * d)) < 1e-6 * (1.0 + abs(f[3 + k]))


def test_bad_force_declarations_get_one_line_naming_the_key():
    body = RigidBody(MOMENTS, mass=MASS)
    with pytest.raises(InputError, match=r"^stiffness: expected a positive number"):
        F.spring(body, -1.0, [0.0, 0.0, 1.0])
    with pytest.raises(InputError, match=r"^anchor: expected"):
        F.spring(body, 1.0, [0.0, 1.0])
    with pytest.raises(InputError, match=r"^fixed_in: expected 'space' or 'body'"):
        F.point_force(body, [1.0, 0.0, 0.0], fixed_in="world")
    with pytest.raises(InputError, match=r"^coefficient: .*expected finite"):
        F.linear_drag(body, float("nan"))
    with pytest.raises(InputError, match=r"^body: linear_drag: expected the RigidBody"):
        F.linear_drag(MASS, 0.1)
