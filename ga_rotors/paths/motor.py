r"""The motor path: whole rigid motion as a motor of Cl(3,0,1) and its body velocity line.

State: the unit motor :math:`M = T(p)\,R(q)` of the frame the body is integrated in
(its origin the body-frame origin, its axes the principal axes), 8 numbers in the order of
:mod:`ga_rotors.motor` (1, e01, e02, e03, e12, e13, e23, e0123). Rates: the body velocity
line :math:`B = -I_3\omega - e_0 v`, kept as its two vectors, the body angular velocity ω
and the velocity v of the body-frame origin, both in body components (6 numbers, ω first,
as every kind's rates begin with ω).

Kinematics: :math:`\dot M = \tfrac12 M B` (:func:`rate`, one product with a bivector,
generated from clifford's table).

Dynamics, the Euler–Poincaré equation of a rigid body for its velocity line
(``docs/conventions.md`` §11):

.. math::

    \dot\Pi = \Pi \times B + W, \qquad \Pi = \mathcal I[B], \qquad
    \dot B = \mathcal I^{-1}[\Pi \times B + W],

with :math:`X \times Y = \tfrac12 (XY - YX)`, the momentum line
:math:`\Pi = -I_3 P - e_0 H` (P = m v_c the linear momentum, H the angular momentum about
the body origin), the force line :math:`W = -I_3 F - e_0 \tau_O` (the force and its moment
about the body origin, body components) and the inertia map :math:`\mathcal I` of a body
whose centre of mass sits at s from the origin: :math:`P = m (v + \omega \times s)`,
:math:`H = \mathsf{I}_c \omega + s \times P`. The map is inverted in closed form through
the centre of mass (:func:`accel`): :math:`\mathsf{I}_c\dot\omega = (\mathsf{I}_c\omega)
\times \omega + \tau_c` with :math:`\tau_c = \tau_O - s \times F`,
:math:`\dot v_c = F/m - \omega \times v_c` and :math:`\dot v = \dot v_c - \dot\omega
\times s`, which is the same equation term by term (``tests/test_motion.py`` checks it
against clifford's products) and keeps Euler's equations in the form whose symmetric-top
rate stays exactly constant.

Binds the template slots ``o_*`` of :mod:`ga_rotors.integrators.slots` for the
``motion`` problem kind.
"""

from __future__ import annotations

import numpy as np

from .._jit import jit
from .._kernels import cross, euler_rates, free_euler_rates, qconj, qrotate
from .._motor_kernels import dual_parts, mmul, mmul_line, motor_from_pose, translation
from ..integrators._arith import axpy8 as axpy  # noqa: F401 (a slot, bound by name)
from ..integrators._arith import load8 as load  # noqa: F401 (a slot, bound by name)
from ..integrators._arith import rk4_sum8 as rk4_sum  # noqa: F401 (a slot, bound by name)
from ..integrators._arith import store8 as store  # noqa: F401 (a slot, bound by name)
from ..motor._screw import mexp, mnormalize

# The slot kernels are the OrientationPath protocol, bound by name (ga_rotors.paths),
# compiled and unchecked: internal, so not in __all__.
__all__ = ["DIM", "NSTATS"]

DIM = 8
NSTATS = 0


@jit
def velocity_line(w):
    """The bivector B = −I₃ω − e0 v (e01, e02, e03, e12, e13, e23) of the rates (ω, v).

    Examples
    --------
    >>> velocity_line((0.0, 0.0, 1.0, 1.0, 0.0, 0.0))    # turn about z, move along x
    (-1.0, -0.0, -0.0, -1.0, 0.0, -0.0)
    """
    return (-w[3], -w[4], -w[5], -w[2], w[1], -w[0])


@jit
def rate(x, w):
    r""":math:`\dot M = \tfrac12 M B`.

    Examples
    --------
    At the identity, Ṁ is half the velocity line (its e12 part −½ω₃, e01 part −½v₁):

    >>> rate((1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0), (0.0, 0.0, 2.0, 4.0, 0.0, 0.0))
    (0.0, -2.0, -0.0, -0.0, -1.0, 0.0, -0.0, 0.0)
    """
    b = velocity_line(w)  # halved first: six multiplications instead of eight
    return mmul_line(x, (0.5 * b[0], 0.5 * b[1], 0.5 * b[2], 0.5 * b[3], 0.5 * b[4],
                         0.5 * b[5]))  # fmt: skip


@jit
def flow(x, h, w):
    r"""The exact flow of constant rates for a time h: :math:`M \exp(\tfrac h2 B)`.

    Examples
    --------
    A unit speed along x for 2 s moves the origin to x = 2:

    >>> flow((1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0), 2.0, (0.0, 0.0, 0.0, 1.0, 0.0, 0.0))
    (1.0, -1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    """
    b = velocity_line(w)
    k = 0.5 * h
    return mmul(x, mexp((k * b[0], k * b[1], k * b[2], k * b[3], k * b[4], k * b[5])))


@jit
def normalize(x):
    """The nearest unit motor (:func:`ga_rotors.motor._screw.mnormalize`)."""
    return mnormalize(x)


@jit
def to_quat(x):
    """The rotor part of M as a quaternion (its orientation).

    Examples
    --------
    >>> to_quat((0.6, 1.0, 2.0, 3.0, -0.8, 0.0, 0.0, 4.0))
    (0.6, -0.0, 0.0, 0.8)
    """
    return dual_parts(x)[0]


@jit
def centre_of_mass(x, w, body):
    """(q, c, ω, v_c): the orientation, the centre of mass and its velocity in space, and
    ω, of the state (M; ω, v) of a body (I₁, I₂, I₃, m, s₁, s₂, s₃).

    Examples
    --------
    A body at rest at the origin, turning at 1 rad/s about z, its centre of mass 1 m
    along its x axis: the centre moves at 1 m/s along y.

    >>> body = (1.0, 1.0, 1.0, 2.0, 1.0, 0.0, 0.0)
    >>> q, c, om, v = centre_of_mass((1.0,) + (0.0,) * 7, (0.0, 0.0, 1.0, 0.0, 0.0, 0.0), body)
    >>> c, v
    ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0))

    M is read as it is, a unit motor to the integrator's error (as the quaternion path
    hands a force its q). A method that goes through the centre of mass and back every
    step (the splittings) normalises M first (``o_normalize``): the translation of a motor
    whose rotor part is off unit norm by δ is off by 2δ, and the same δ step after step
    drifted the position by 1e-11 m in 2560 steps of split4. Normalising here instead,
    in every stage of every method, cost a square root and two divisions a stage (RK4 under
    gravity: 267 against 81 ns a step).
    """
    q = dual_parts(x)[0]
    p = translation(x)
    om = (w[0], w[1], w[2])
    s = (body[4], body[5], body[6])
    lever = qrotate(q, s)
    arm = cross(om, s)
    vc = qrotate(q, (w[3] + arm[0], w[4] + arm[1], w[5] + arm[2]))
    return q, (p[0] + lever[0], p[1] + lever[1], p[2] + lever[2]), om, vc


@jit
def from_centre_of_mass(q, c, om, vc, body):
    """The state (M; ω, v) of the orientation q, the centre of mass c and its velocity v_c
    in space and the body ω: the inverse of :func:`centre_of_mass`.

    Examples
    --------
    >>> body = (1.0, 1.0, 1.0, 2.0, 1.0, 0.0, 0.0)
    >>> x, w = from_centre_of_mass((1.0, 0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 0.0, 1.0),
    ...                            (0.0, 1.0, 0.0), body)
    >>> x, w
    ((1.0, -0.0, -0.0, -0.0, -0.0, 0.0, -0.0, 0.0), (0.0, 0.0, 1.0, 0.0, 0.0, 0.0))
    """
    s = (body[4], body[5], body[6])
    lever = qrotate(q, s)
    x = motor_from_pose(q, (c[0] - lever[0], c[1] - lever[1], c[2] - lever[2]))
    v = qrotate(qconj(q), vc)
    arm = cross(om, s)
    return x, (om[0], om[1], om[2], v[0] - arm[0], v[1] - arm[1], v[2] - arm[2])


@jit
def _translation_rates(w, dw, s, f_body, inv_mass):
    """v̇ = v̇_c − ω̇ × s with v̇_c = F/m − ω × v_c (body components)."""
    om = (w[0], w[1], w[2])
    arm = cross(om, s)
    vc = (w[3] + arm[0], w[4] + arm[1], w[5] + arm[2])
    turn = cross(om, vc)
    spin = cross(dw, s)
    return (
        f_body[0] * inv_mass - turn[0] - spin[0],
        f_body[1] * inv_mass - turn[1] - spin[1],
        f_body[2] * inv_mass - turn[2] - spin[2],
    )


@jit
def accel(x, w, body, f):
    """Ḃ as (ω̇, v̇) under the wrench f = (F in space, τ about the centre of mass in the
    body): the Euler–Poincaré equation, the inertia map inverted through the centre of
    mass (see the module's text).

    Examples
    --------
    A body at rest at the identity pose, its centre of mass 1 m along y, pulled by 2 N
    along x through the centre of mass: it does not turn, and its origin accelerates with
    the centre, F/m.

    >>> body = (1.0, 1.0, 1.0, 2.0, 0.0, 1.0, 0.0)
    >>> accel((1.0,) + (0.0,) * 7, (0.0,) * 6, body, (2.0, 0.0, 0.0, 0.0, 0.0, 0.0))
    (0.0, 0.0, 0.0, 1.0, 0.0, 0.0)
    """
    q = dual_parts(x)[0]
    om = (w[0], w[1], w[2])
    dw = euler_rates(body, om, (f[3], f[4], f[5]))
    f_body = qrotate(qconj(q), (f[0], f[1], f[2]))
    dv = _translation_rates(w, dw, (body[4], body[5], body[6]), f_body, 1.0 / body[3])
    return (dw[0], dw[1], dw[2], dv[0], dv[1], dv[2])


@jit
def free_accel(x, w, body):
    """Ḃ as (ω̇, v̇) with no force and no torque: the free body's Euler–Poincaré equation.

    Examples
    --------
    Spinning about its z axis with the centre of mass 1 m along x, the body origin
    circles the centre: v = ω × (−s) stays constant in the body, as v̇ = 0 says.

    >>> body = (1.0, 1.0, 1.0, 2.0, 1.0, 0.0, 0.0)
    >>> free_accel((1.0,) + (0.0,) * 7, (0.0, 0.0, 1.0, 0.0, -1.0, 0.0), body)
    (0.0, 0.0, 0.0, -0.0, -0.0, -0.0)
    """
    om = (w[0], w[1], w[2])
    dw = free_euler_rates(body, om)
    dv = _translation_rates(w, dw, (body[4], body[5], body[6]), (0.0, 0.0, 0.0), 0.0)
    return (dw[0], dw[1], dw[2], dv[0], dv[1], dv[2])


# ------------------------------------------------- a body frame at the centre of mass


@jit
def centred_centre_of_mass(x, w, body):
    """:func:`centre_of_mass` of a body whose frame is at its centre of mass (s = 0): the
    origin's position and velocity.

    Examples
    --------
    >>> body = (1.0, 1.0, 1.0, 2.0, 0.0, 0.0, 0.0)
    >>> centred_centre_of_mass((1.0, -0.5, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0),
    ...                        (0.0, 0.0, 1.0, 0.0, 3.0, 0.0), body)[1:]
    ((1.0, 0.0, 0.0), (0.0, 0.0, 1.0), (0.0, 3.0, 0.0))
    """
    q = dual_parts(x)[0]
    return q, translation(x), (w[0], w[1], w[2]), qrotate(q, (w[3], w[4], w[5]))


@jit
def centred_accel(x, w, body, f):
    r""":func:`accel` of a body whose frame is at its centre of mass (s = 0): the inertia
    map is diagonal, :math:`\dot v = F/m - \omega \times v`, the terms of the lever s
    gone (12 of an RK4 stage's 100 multiplications; the general kernel gives the same
    numbers, up to the sign of a zero).

    Examples
    --------
    Spinning about z at 1 rad/s and moving along x at 1 m/s, pulled by 2 N along z: the
    body velocity turns (−ω × v along −y) and the pull accelerates it at F/m.

    >>> body = (1.0, 1.0, 1.0, 2.0, 0.0, 0.0, 0.0)
    >>> centred_accel((1.0,) + (0.0,) * 7, (0.0, 0.0, 1.0, 1.0, 0.0, 0.0), body,
    ...               (0.0, 0.0, 2.0, 0.0, 0.0, 0.0))
    (0.0, 0.0, 0.0, 0.0, -1.0, 1.0)
    """
    q = dual_parts(x)[0]
    om = (w[0], w[1], w[2])
    dw = euler_rates(body, om, (f[3], f[4], f[5]))
    f_body = qrotate(qconj(q), (f[0], f[1], f[2]))
    k = 1.0 / body[3]
    turn = cross(om, (w[3], w[4], w[5]))
    return (dw[0], dw[1], dw[2], f_body[0] * k - turn[0], f_body[1] * k - turn[1],
            f_body[2] * k - turn[2])  # fmt: skip


@jit
def centred_free_accel(x, w, body):
    """:func:`free_accel` of a body whose frame is at its centre of mass (s = 0).

    Examples
    --------
    >>> centred_free_accel((1.0,) + (0.0,) * 7, (0.0, 0.0, 1.0, 1.0, 0.0, 0.0),
    ...                    (1.0, 1.0, 1.0, 2.0, 0.0, 0.0, 0.0))
    (0.0, 0.0, 0.0, -0.0, -1.0, -0.0)
    """
    om = (w[0], w[1], w[2])
    dw = free_euler_rates(body, om)
    turn = cross(om, (w[3], w[4], w[5]))
    return (dw[0], dw[1], dw[2], -turn[0], -turn[1], -turn[2])


#: The kernels bound instead of :func:`centre_of_mass`, :func:`accel` and
#: :func:`free_accel` when a single run's body frame is at its centre of mass
#: (``ga_rotors.integrators._source``; a batch's bodies each carry their own s, so a
#: batched loop keeps the general kernels).
CENTRED = {
    "centre_of_mass": "centred_centre_of_mass",
    "accel": "centred_accel",
    "free_accel": "centred_free_accel",
}


@jit
def watch(t, x, w, h, stats):
    """Nothing to watch: a motor has no coordinate singularity."""


# ---------------------------------------------------------------------------- Python side


def initial_state(q0, position, w0, velocity, centre_of_mass):
    """The path's state (M; ω, v) of the orientation q0 (principal frame), the body
    origin's position and velocity in space, the body ω (principal frame) and the centre
    of mass (principal frame): two float64 arrays.

    Examples
    --------
    >>> x, w = initial_state([1.0, 0, 0, 0], [1.0, 0, 0], [0.0, 0, 2.0], [0.0, 3.0, 0],
    ...                      [0.0, 0, 0])
    >>> x.tolist(), w.tolist()
    ([1.0, -0.5, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0], [0.0, 0.0, 2.0, 0.0, 3.0, 0.0])
    """
    from .. import motor
    from .. import quaternion as Q

    q0 = np.asarray(q0, dtype=np.float64)
    v_body = Q.rotate(Q.conjugate(q0), np.asarray(velocity, dtype=np.float64))
    x = motor.from_pose(q0, position)
    # along the last axis: rows of many bodies' starts at once, as an ensemble makes them
    return x, np.concatenate([np.asarray(w0, dtype=np.float64), v_body], axis=-1)


def quaternions(states: np.ndarray) -> np.ndarray:
    """The orientations (..., 4) of motors (..., 8): their rotor parts as quaternions.

    Examples
    --------
    >>> quaternions([[0.6, 1.0, 2.0, 3.0, -0.8, 0.0, 0.0, 4.0]]) + 0.0
    array([[0.6, 0. , 0. , 0.8]])
    """
    m = np.asarray(states, dtype=np.float64)
    return np.stack([m[..., 0], -m[..., 6], m[..., 5], -m[..., 4]], axis=-1)


def positions(states: np.ndarray, centre_of_mass) -> np.ndarray:
    """Where the body origin is (..., 3), in space: the translation t of each motor
    M = T(t) R(r), t = −2 d r* for M = R(r) + e0123 R(d) (as the kernel ``translation``),
    divided by |r|² (an integrator that does not renormalise lets |M| drift by its error:
    the motion is that of M/|r|).

    Examples
    --------
    >>> from ga_rotors import motor
    >>> positions(motor.from_pose([0.0, 0, 0, 1.0], [1.0, 2.0, 3.0]), [0.5, 0, 0])
    array([1., 2., 3.])
    """
    from .. import quaternion as Q

    m = np.asarray(states, dtype=np.float64)
    d = np.stack([m[..., 7], m[..., 1], m[..., 2], m[..., 3]], axis=-1)
    r = quaternions(m)
    scale = -2.0 / np.einsum("...i,...i->...", r, r)
    return scale[..., None] * Q.multiply(d, Q.conjugate(r))[..., 1:]


def velocities(states: np.ndarray, rates: np.ndarray, centre_of_mass) -> np.ndarray:
    """The body origin's velocity (..., 3) in space: M's rotation of the body v.

    Examples
    --------
    >>> from ga_rotors import motor
    >>> M = motor.from_pose([0.0, 0, 0, 1.0], [1.0, 2.0, 3.0])
    >>> velocities(M, [0.0, 0, 0, 1.0, 0, 0], [0.5, 0, 0])
    array([-1.,  0.,  0.])
    """
    from .. import quaternion as Q

    turn = Q.normalize(quaternions(states))
    return Q.rotate(turn, np.asarray(rates, dtype=np.float64)[..., 3:6])


def to_user_frame(states: np.ndarray, principal_rotation) -> np.ndarray:
    """Motors of the principal frame -> motors of the user's body frame, M R(P)~ (the
    frames share their origin, the body-frame origin).

    Examples
    --------
    >>> to_user_frame(np.array([[1.0, 0, 0, 0, 0, 0, 0, 0]]), [1.0, 0, 0, 0]).tolist()
    [[1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]]
    """
    from .. import motor
    from .. import quaternion as Q

    back = motor.from_quaternion(Q.conjugate(np.asarray(principal_rotation, dtype=np.float64)))
    return motor.compose(states, back)
