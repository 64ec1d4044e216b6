"""simulate(): the Python entry point, its validation and bookkeeping."""

from __future__ import annotations

import numpy as np
import pytest
from _torques_for_tests import constant_body_torque

from ga_rotors import shapes, simulate
from ga_rotors.errors import InputError
from ga_rotors.integrators import TorqueTerm

DISK = shapes.disk(2.0, 0.075)
Q0 = [1.0, 0.0, 0.0, 0.0]


def test_only_requested_paths_and_outputs_are_present():
    tr = simulate(DISK, Q0, [0.1, 0.0, 3.0], duration=0.1, step=1e-3, paths=["quaternion"])
    assert tr.names == ("t", "w", "q")
    tr = simulate(DISK, Q0, [0.1, 0.0, 3.0], duration=0.1, step=1e-3,
                  paths=["quaternion", "rotor"], outputs=["energy"])  # fmt: skip
    assert tr.names == ("t", "w", "rotor_blades", "q", "energy")
    assert tr.meta["primary"] == "rotor" and set(tr.meta["paths"]) == {"rotor", "quaternion"}


def test_sampling_keeps_the_last_step():
    tr = simulate(DISK, Q0, [0.0, 0.0, 1.0], duration=0.01, step=1e-3, sample_every=4)
    assert np.allclose(tr.t, [0.0, 0.004, 0.008, 0.01], rtol=0, atol=1e-15)
    assert tr["rotor_blades"].shape == tr.quaternions().shape == (4, 4)


def test_torqued_run_records_its_torques():
    tau = TorqueTerm(constant_body_torque, (0.0, 0.0, 1e-3))
    tr = simulate(DISK, Q0, [0.0, 0.0, 1.0], duration=0.1, step=1e-3, torques=[tau])
    assert tr.meta["problem"] == "torqued" and tr.meta["torques"] == ["constant_body_torque"]
    assert tr.w[-1, 2] > 1.0


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"step": 0.3}, "does not divide duration"),
        ({"step": -1e-3}, "step: expected a finite positive"),
        ({"duration": float("inf")}, "duration: expected a finite positive"),
        ({"paths": ["matrix"]}, "unknown path 'matrix'"),
        ({"paths": []}, "expected at least one"),
        ({"integrator": "nope"}, "unknown integrator"),
        ({"integrator": "rk4_renorm", "paths": ["euler"]}, "cannot step the 'euler' path"),
        ({"outputs": ["power"]}, "unknown output 'power'"),
        ({"sample_every": 0}, "sample_every: expected a positive integer"),
        ({"orientation": [2.0, 0.0, 0.0, 0.0]}, "orientation: expected unit quaternions"),
        ({"angular_velocity": [1.0, 2.0]}, "angular_velocity: expected an array of shape"),
        ({"body": (1.0, 1.0, 3.0)}, "triangle inequality"),
        ({"paths": ["euler"], "euler_angles": [0.0, 0.5, 0.0]}, "same rotation"),
    ],
)
def test_bad_arguments_name_themselves(kwargs, message):
    args = {"body": DISK, "orientation": Q0, "angular_velocity": [0.0, 0.0, 1.0],
            "duration": 1.0, "step": 1e-3} | kwargs  # fmt: skip
    body, q, w = args.pop("body"), args.pop("orientation"), args.pop("angular_velocity")
    with pytest.raises(InputError, match=message):
        simulate(body, q, w, **args)


def test_step_that_divides_up_to_representation_is_accepted():
    tr = simulate(DISK, Q0, [0.0, 0.0, 1.0], duration=0.3, step=0.1)
    assert tr.meta["steps"] == 3


def test_body_from_a_rotated_tensor_moves_like_its_principal_body():
    # The same physical body, described in a frame turned by P from its principal axes:
    # space-frame motion (a material vector, L_space, energy) must be identical.
    from ga_rotors import quaternion as Q
    from ga_rotors.body import RigidBody

    P = Q.from_axis_angle([1.0, 2.0, -0.5], 0.7)
    moments = np.array([1.0, 2.0, 2.5])
    m = Q.to_matrix(P)
    rotated = RigidBody.from_tensor(m @ np.diag(moments) @ m.T)
    P_found = np.array(rotated.principal_rotation)
    q_user = Q.from_axis_angle([0.3, -0.2, 1.0], 0.4)
    w_user = np.array([0.5, -1.0, 2.0])
    tr = simulate(rotated, q_user, w_user, duration=2.0, step=1e-3,
                  paths=("rotor", "quaternion"), outputs=("energy", "L_space"))  # fmt: skip
    # reference: the principal body, started from the same physical state
    ref = simulate(RigidBody(tuple(rotated.moments)), Q.multiply(q_user, P_found),
                   Q.rotate(Q.conjugate(P_found), w_user), duration=2.0, step=1e-3,
                   paths=("quaternion",), outputs=("energy", "L_space"))  # fmt: skip
    v_user = np.array([0.2, 0.7, -0.4])  # a material vector in the user's frame
    got = Q.rotate(tr.q, v_user)
    expected = Q.rotate(ref.q, Q.rotate(Q.conjugate(P_found), v_user))
    assert np.allclose(got, expected, rtol=0, atol=1e-13)
    assert np.allclose(tr.L_space, ref.L_space, rtol=0, atol=1e-13)
    assert np.allclose(tr.energy, ref.energy, rtol=1e-14)
    assert np.allclose(tr.q[0], q_user, atol=1e-15) and np.allclose(tr.w[0], w_user, atol=1e-14)
    with pytest.raises(InputError, match="Euler-angle path integrates the angles of the principal"):
        simulate(rotated, q_user, w_user, duration=0.1, step=1e-3, paths=("euler",))
