r"""The quaternion path of a whole rigid motion: the orientation q and the centre of mass.

State: the unit quaternion q (w, x, y, z) of the principal frame, body to space, and the
position c of the centre of mass in space, 7 numbers. Rates: the body angular velocity ω
(principal frame) and the velocity :math:`v_c` of the centre of mass in space, 6 numbers.
Rotation about the centre of mass and translation of it separate (Euler's and Newton's
equations):

.. math::

    \dot q = \tfrac12 q \otimes (0, \omega), \quad \dot c = v_c, \qquad
    \mathsf{I}_c\dot\omega = (\mathsf{I}_c\omega) \times \omega + \tau_c, \quad
    m \dot v_c = F,

the classical form the motor path (:mod:`ga_rotors.paths.motor`) is cross-checked against:
that path integrates the body-frame origin's motor and velocity line instead, and couples
rotation and translation whenever the origin is not the centre of mass.

Binds the template slots ``o_*`` of :mod:`ga_rotors.integrators.slots` for the ``motion``
problem kind (the orientation-only quaternion path is :mod:`ga_rotors.paths.quaternion`).
"""

from __future__ import annotations

import numpy as np

from .._jit import jit
from .._kernels import euler_rates, free_euler_rates, qmul_pure, qnormalize
from ..integrators._arith import axpy7 as axpy  # noqa: F401 (a slot, bound by name)
from ..integrators._arith import load7 as load  # noqa: F401 (a slot, bound by name)
from ..integrators._arith import rk4_sum7 as rk4_sum  # noqa: F401 (a slot, bound by name)
from ..integrators._arith import store7 as store  # noqa: F401 (a slot, bound by name)
from ..integrators._rigid import turn

# The slot kernels are the OrientationPath protocol, bound by name (ga_rotors.paths),
# compiled and unchecked: internal, so not in __all__.
__all__ = ["DIM", "NSTATS"]

DIM = 7
NSTATS = 0


@jit
def rate(x, w):
    r""":math:`(\dot q, \dot c) = (\tfrac12 q \otimes (0, \omega), v_c)`.

    Examples
    --------
    >>> rate((1.0, 0.0, 0.0, 0.0, 5.0, 5.0, 5.0), (0.0, 0.0, 2.0, 1.0, 2.0, 3.0))
    (-0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 3.0)
    """
    d = qmul_pure((x[0], x[1], x[2], x[3]), (w[0], w[1], w[2]))
    return (0.5 * d[0], 0.5 * d[1], 0.5 * d[2], 0.5 * d[3], w[3], w[4], w[5])


@jit
def flow(x, h, w):
    r"""The exact flow of constant rates for a time h: :math:`(q \otimes \mathrm{Exp}(h\omega),
    c + h v_c)`.

    Examples
    --------
    >>> flow((1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0), 2.0, (0.0, 0.0, 0.0, 1.0, 0.0, 0.0))
    (1.0, 0.0, 0.0, 0.0, 2.0, 0.0, 0.0)
    """
    q = turn((x[0], x[1], x[2], x[3]), h, (w[0], w[1], w[2]))
    return (q[0], q[1], q[2], q[3], x[4] + h * w[3], x[5] + h * w[4], x[6] + h * w[5])


@jit
def normalize(x):
    """q back onto the unit sphere; c as it is."""
    q = qnormalize((x[0], x[1], x[2], x[3]))
    return (q[0], q[1], q[2], q[3], x[4], x[5], x[6])


@jit
def to_quat(x):
    """The orientation q."""
    return (x[0], x[1], x[2], x[3])


@jit
def centre_of_mass(x, w, body):
    """(q, c, ω, v_c): the state itself, split."""
    return (x[0], x[1], x[2], x[3]), (x[4], x[5], x[6]), (w[0], w[1], w[2]), (w[3], w[4], w[5])


@jit
def from_centre_of_mass(q, c, om, vc, body):
    """The state of (q, c, ω, v_c): joined."""
    return (q[0], q[1], q[2], q[3], c[0], c[1], c[2]), (om[0], om[1], om[2], vc[0], vc[1], vc[2])


@jit
def accel(x, w, body, f):
    """(ω̇, v̇_c) under the wrench f = (F in space, τ about the centre of mass in the body):
    Euler's equations and Newton's law.

    Examples
    --------
    >>> accel((1.0,) + (0.0,) * 6, (0.0,) * 6, (1.0, 1.0, 1.0, 2.0, 0.0, 1.0, 0.0),
    ...       (2.0, 0.0, 0.0, 0.0, 0.0, 0.0))
    (0.0, 0.0, 0.0, 1.0, 0.0, 0.0)
    """
    dw = euler_rates(body, (w[0], w[1], w[2]), (f[3], f[4], f[5]))
    k = 1.0 / body[3]
    return (dw[0], dw[1], dw[2], f[0] * k, f[1] * k, f[2] * k)


@jit
def free_accel(x, w, body):
    """(ω̇, v̇_c) of the free body: Euler's equations, a constant v_c."""
    dw = free_euler_rates(body, (w[0], w[1], w[2]))
    return (dw[0], dw[1], dw[2], 0.0, 0.0, 0.0)


@jit
def watch(t, x, w, h, stats):
    """Nothing to watch: a quaternion has no coordinate singularity."""


# ---------------------------------------------------------------------------- Python side


def initial_state(q0, position, w0, velocity, centre_of_mass):
    """The path's state (q, c; ω, v_c) of the orientation q0 (principal frame), the body
    origin's position and velocity in space, the body ω (principal frame) and the centre
    of mass s (principal frame, from the origin): c = p + q s q*, v_c = v + (q ω q*) × (q s q*).

    Examples
    --------
    >>> x, w = initial_state([1.0, 0, 0, 0], [1.0, 0, 0], [0.0, 0, 2.0], [0.0, 3.0, 0],
    ...                      [0.5, 0, 0])
    >>> x.tolist(), w.tolist()
    ([1.0, 0.0, 0.0, 0.0, 1.5, 0.0, 0.0], [0.0, 0.0, 2.0, 0.0, 4.0, 0.0])
    """
    from .. import quaternion as Q

    q0 = np.asarray(q0, dtype=np.float64)
    lever = Q.rotate(q0, np.asarray(centre_of_mass, dtype=np.float64))
    c = np.asarray(position, dtype=np.float64) + lever
    vc = np.asarray(velocity, dtype=np.float64) + np.cross(Q.rotate(q0, w0), lever)
    # along the last axis: rows of many bodies' starts at once, as an ensemble makes them
    return (np.concatenate([q0, c], axis=-1),
            np.concatenate([np.asarray(w0, dtype=np.float64), vc], axis=-1))  # fmt: skip


def quaternions(states: np.ndarray) -> np.ndarray:
    """The orientations (..., 4) of states (..., 7)."""
    return np.asarray(states, dtype=np.float64)[..., :4]


def positions(states: np.ndarray, centre_of_mass) -> np.ndarray:
    """Where the body origin is (..., 3): c − q s q* (q and s in the same body frame).

    Examples
    --------
    >>> positions([[0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 0.0]], [1.0, 0.0, 0.0])   # turned 180° about z
    array([[2., 1., 0.]])
    """
    from .. import quaternion as Q

    x = np.asarray(states, dtype=np.float64)
    return x[..., 4:7] - Q.rotate(Q.normalize(x[..., :4]), np.asarray(centre_of_mass, dtype=float))


def velocities(states: np.ndarray, rates: np.ndarray, centre_of_mass) -> np.ndarray:
    """The body origin's velocity (..., 3) in space: v_c − (q ω q*) × (q s q*).

    Examples
    --------
    >>> velocities([[1.0, 0, 0, 0, 0, 0, 0]], [[0.0, 0.0, 1.0, 0.0, 1.0, 0.0]], [1.0, 0, 0])
    array([[0., 0., 0.]])
    """
    from .. import quaternion as Q

    x, w = np.asarray(states, dtype=np.float64), np.asarray(rates, dtype=np.float64)
    q = Q.normalize(x[..., :4])
    lever = Q.rotate(q, np.asarray(centre_of_mass, dtype=float))
    return w[..., 3:6] - np.cross(Q.rotate(q, w[..., :3]), lever)


def to_user_frame(states: np.ndarray, principal_rotation) -> np.ndarray:
    """States of the principal frame -> of the user's body frame: q ⊗ P*, c unchanged."""
    from .. import quaternion as Q

    x = np.array(states, dtype=np.float64)
    x[..., :4] = Q.multiply(x[..., :4], Q.conjugate(np.asarray(principal_rotation, dtype=float)))
    return x
