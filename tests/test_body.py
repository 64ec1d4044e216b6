"""RigidBody validation and Euler's equations."""

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from ga_rotors import shapes
from ga_rotors._kernels import euler_rates, free_euler_rates
from ga_rotors.body import RigidBody
from ga_rotors.errors import InputError

moment = st.floats(0.1, 10.0)
rate = st.floats(-50.0, 50.0)


@given(moment, moment, moment, rate, rate, rate)
def test_torque_free_euler_rates_conserve_energy_and_momentum(i1, i2, i3, w1, w2, w3):
    inertia, w = (i1, i2, i3), (w1, w2, w3)
    dw = np.array(euler_rates(inertia, w, (0.0, 0.0, 0.0)))
    I, w = np.array(inertia), np.array(w)
    scale = (I * w * w).sum() * (1 + np.abs(w).max()) + 1e-300
    assert abs(np.dot(I * w, dw)) <= 1e-12 * scale  # dE/dt = I w . w'
    assert abs(np.dot(I * w, I * dw)) <= 1e-12 * scale * I.max()  # d|L|^2/dt


def test_euler_rates_match_vector_form():
    I = np.array([1.0, 2.0, 3.5])
    w = np.array([0.3, -1.2, 2.0])
    tau = np.array([0.1, 0.2, -0.3])
    expected = (np.cross(I * w, w) + tau) / I
    assert np.allclose(euler_rates(tuple(I), tuple(w), tuple(tau)), expected, rtol=1e-15)


def test_symmetric_axis_rate_is_exactly_constant():
    # the paper's body: I2 = I3 makes the x3 rate's derivative exactly zero
    assert euler_rates((0.0056, 0.0028, 0.0028), (0.7, -3.1, 15.7), (0.0, 0.0, 0.0))[0] == 0.0


@pytest.mark.parametrize(
    "moments, fragment",
    [
        ((1.0, 1.0, 2.5), "triangle inequality"),
        ((0.0, 1.0, 1.0), "must be positive"),
        ((-1.0, 1.0, 1.0), "must be positive"),
        ((1.0, float("nan"), 1.0), "nan"),
        ((1.0, 2.0), "shape"),
    ],
)
def test_impossible_inertia_is_rejected(moments, fragment):
    with pytest.raises(InputError, match=fragment):
        RigidBody(moments)


def test_flat_body_is_accepted_within_round_off():
    # a thin box: I3 = I1 + I2 exactly in exact arithmetic, a few ulps off in floats
    flat = shapes.box(3.0, 0.7, 1.3, 1e-300)
    RigidBody(flat)
    assert math.isclose(flat[2], flat[0] + flat[1], rel_tol=1e-15)


@pytest.mark.parametrize("name", sorted(shapes.SHAPES))
def test_every_shape_is_a_valid_body(name):
    fn, dims = shapes.SHAPES[name]
    RigidBody(fn(2.0, *[0.3 + 0.1 * k for k in range(len(dims))]))


def test_shapes_reject_bad_dimensions():
    with pytest.raises(InputError, match="radius"):
        shapes.disk(1.0, -1.0)
    with pytest.raises(InputError, match="mass"):
        shapes.sphere(float("inf"), 1.0)


@given(moment, moment, moment, rate, rate, rate)
def test_free_euler_rates_is_euler_rates_without_torque(i1, i2, i3, w1, w2, w3):
    inertia, w = (i1, i2, i3), (w1, w2, w3)
    assert euler_rates(inertia, w, (0.0, 0.0, 0.0)) == free_euler_rates(inertia, w)
    tau = (0.3, -0.2, 0.1)
    with_tau = np.array(euler_rates(inertia, w, tau))
    assert np.allclose(with_tau - np.array(free_euler_rates(inertia, w)), np.array(tau) / inertia,
                       rtol=1e-12, atol=1e-12 * np.abs(with_tau).max())  # fmt: skip


def test_space_momentum_is_body_momentum_rotated_to_space():
    from oracles import to_scipy

    body = RigidBody((1.0, 2.0, 3.0))
    q = np.array([0.5, 0.5, -0.5, 0.5])  # 120° about (1, -1, 1)/√3
    w = np.array([[0.3, -1.0, 2.0], [1.0, 0.0, 0.0]])
    expected = to_scipy(q).apply(w * np.array([1.0, 2.0, 3.0]))
    assert np.allclose(body.space_momentum(q, w), expected, rtol=0, atol=1e-15)


def test_space_momentum_is_conserved_by_a_torque_free_step():
    # d/dt (q L q*) = q (ω × L + L̇) q* = q (ω × L + (L × ω)) q* = 0: check at one state
    from ga_rotors import quaternion as Q

    body = RigidBody((1.0, 2.0, 2.5))
    q, w, h = Q.from_rotation_vector([0.2, -0.4, 0.9]), np.array([0.3, -1.2, 2.0]), 1e-6
    dq = 0.5 * Q.multiply(q, np.concatenate([[0.0], w]))
    dw = np.array(euler_rates(body.moments, tuple(w), (0.0, 0.0, 0.0)))
    ahead = body.space_momentum(Q.normalize(q + h * dq), w + h * dw)
    behind = body.space_momentum(Q.normalize(q - h * dq), w - h * dw)
    # central difference: O(h²) truncation (~1e-12) plus round-off 1e-16 / h (~1e-10)
    assert np.allclose((ahead - behind) / (2 * h), 0.0, atol=1e-9)


def test_from_tensor_principal_rotation_rebuilds_the_tensor():
    from ga_rotors import matrix

    c, s = np.cos(0.3), np.sin(0.3)
    R = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]]) @ np.array([[1, 0, 0], [0, c, -s], [0, s, c]])
    tensor = R @ np.diag([1.0, 2.0, 2.5]) @ R.T
    body = RigidBody.from_tensor(tensor)
    P = matrix.from_quaternion(body.principal_rotation)
    assert np.allclose(P @ np.diag(body.moments) @ P.T, tensor, rtol=0, atol=1e-14)


def test_energy_and_momentum_of_a_turned_tensor_read_the_users_frame():
    # Issue 10's trap for the references, in the body itself: for RigidBody.from_tensor(T),
    # simulate returns ω in the frame T was written in, and energy / momentum must read it
    # there (½ ωᵀTω, Tω), not as principal-frame components.
    from ga_rotors import quaternion as Q

    turn = Q.to_matrix(Q.from_axis_angle([1.0, -2.0, 0.5], 1.1))
    tensor = turn @ np.diag([1.0, 2.0, 2.5]) @ turn.T
    body = RigidBody.from_tensor(tensor)
    w = np.array([[0.3, -1.2, 0.7], [2.0, 0.1, -0.4]])
    assert np.allclose(body.energy(w), 0.5 * np.einsum("ni,ij,nj->n", w, tensor, w),
                       rtol=1e-14, atol=0)  # fmt: skip
    assert np.allclose(body.momentum(w), w @ tensor.T, rtol=0, atol=1e-14)
    q = Q.from_axis_angle([0.2, 0.3, 1.0], 0.8)
    assert np.allclose(body.space_momentum(q, w), Q.rotate(q, w @ tensor.T), rtol=0, atol=1e-14)
