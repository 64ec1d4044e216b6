r"""Orientation rates <-> body angular velocity: Euler angles (ZYZ), quaternions, rotors.

The paper's angles are intrinsic z–y′–z″ (ψ precession, θ nutation, φ spin) with
:math:`q = q_z(\psi) \otimes q_y(\theta) \otimes q_z(\varphi)`. Differentiating, the body
angular velocity is the sum of the three angle rates, each about its axis carried into the
body frame:

.. math::

    \omega = \dot\varphi\, e_z + \dot\theta\, R_z(-\varphi)\, e_y
        + \dot\psi\, R_z(-\varphi) R_y(-\theta)\, e_z,

.. math::

    \begin{aligned}
    \omega_1 &= -\dot\psi \sin\theta \cos\varphi + \dot\theta \sin\varphi \\
    \omega_2 &= \dot\psi \sin\theta \sin\varphi + \dot\theta \cos\varphi \\
    \omega_3 &= \dot\psi \cos\theta + \dot\varphi
    \end{aligned}

(the paper's eq. 15, whose minus signs were lost in print). Its inverse (eq. 19)

.. math::

    \begin{aligned}
    \dot\theta &= \omega_1 \sin\varphi + \omega_2 \cos\varphi \\
    \dot\psi &= (\omega_2 \sin\varphi - \omega_1 \cos\varphi) / \sin\theta \\
    \dot\varphi &= \omega_3 - \dot\psi \cos\theta
    \end{aligned}

is singular at :math:`\sin\theta = 0`, where only :math:`\psi + \varphi` (θ = 0) or
:math:`\psi - \varphi` (θ = π) is defined: the coordinates' nature, not a property of the
motion. ``symbolic/`` checks both maps with SymPy;
the tests check them against finite differences of the quaternion.

Quaternion and rotor rates (docs/conventions.md):
:math:`\dot q = \tfrac12 q \otimes (0, \omega)`, :math:`\dot R = \tfrac12 R \Omega` with
:math:`\Omega = -I \omega`, and back
:math:`\omega = 2 \operatorname{vec}(q^* \otimes \dot q) = \langle 2 I \tilde R \dot R \rangle_1`
(:math:`I^2 = -1` turns Ω into ω).
"""

from __future__ import annotations

import numpy as np

from ._validate import as_float_array, require_unit
from .errors import InputError
from .euler import GIMBAL_TOLERANCE
from .isomorphism import from_even

__all__ = [
    "body_omega_from_euler_rates",
    "body_omega_from_quaternion_rate",
    "body_omega_from_rotor_rate",
    "body_omega_from_zyz_rates",
    "quaternion_rate",
    "rotor_rate",
    "zyz_rates_from_body_omega",
]


def _pairs(a, b, name_a, name_b, last_a=3, last_b=3):
    a = as_float_array(a, name_a, last=last_a)
    b = as_float_array(b, name_b, last=last_b)
    try:
        shape = np.broadcast_shapes(a.shape[:-1], b.shape[:-1])
    except ValueError:
        raise InputError(
            f"{name_a} and {name_b}: shapes {a.shape} and {b.shape} do not broadcast"
        ) from None
    return np.broadcast_to(a, (*shape, last_a)), np.broadcast_to(b, (*shape, last_b))


def body_omega_from_zyz_rates(angles, rates) -> np.ndarray:
    """Body angular velocity from ZYZ Euler angles and their time derivatives.

    Parameters
    ----------
    angles : array_like, shape (..., 3)
        Intrinsic ZYZ angles (ψ, θ, φ) in radians.
    rates : array_like, shape (..., 3)
        (ψ̇, θ̇, φ̇) in rad/s.

    Returns
    -------
    ndarray, shape (..., 3)
        Body-frame ω (rad/s).

    Examples
    --------
    The paper's initial state: a fast spin φ̇ about the body z axis plus slow ψ̇ and θ̇.

    >>> w = body_omega_from_zyz_rates([0.0, np.radians(15), 0.0], [0.02, 0.02, 15.7])
    >>> w.round(6).tolist()
    [-0.005176, 0.02, 15.719319]
    """
    a, r = _pairs(angles, rates, "angles", "rates")
    _, theta, phi = np.moveaxis(a, -1, 0)
    dpsi, dtheta, dphi = np.moveaxis(r, -1, 0)
    st, ct, sp, cp = np.sin(theta), np.cos(theta), np.sin(phi), np.cos(phi)
    return np.stack(
        [-dpsi * st * cp + dtheta * sp, dpsi * st * sp + dtheta * cp, dpsi * ct + dphi], axis=-1
    )


def body_omega_from_euler_rates(seq: str, angles, rates) -> np.ndarray:
    """Body angular velocity from Euler angles of any sequence and their rates (radians).

    For an intrinsic sequence 'IJK', q = q_i(a) ⊗ q_j(b) ⊗ q_k(c) and each rate turns
    about its own axis carried into the body frame by the rotations after it::

        ω = ċ e_k + ḃ · q_k(c)* e_j q_k(c) + ȧ · (q_j(b) q_k(c))* e_i (q_j(b) q_k(c))

    An extrinsic 'ijk' with angles (a, b, c) is the intrinsic 'KJI' with (c, b, a).
    Regular everywhere (it is the Euler-angle *inverse* that is singular at gimbal lock).

    Parameters
    ----------
    seq : str
        One of :data:`ga_rotors.euler.SEQUENCES`.
    angles, rates : array_like, shape (..., 3)
        Angles (rad) and their time derivatives (rad/s), in the sequence's order.

    Examples
    --------
    The paper's ZYZ case, the same as :func:`body_omega_from_zyz_rates`:

    >>> w = body_omega_from_euler_rates("ZYZ", [0.0, np.radians(15), 0.0], [0.02, 0.02, 15.7])
    >>> w.round(6).tolist()
    [-0.005176, 0.02, 15.719319]
    """
    from . import quaternion as Q
    from .euler import parse_sequence

    i, j, k, extrinsic = parse_sequence(seq)
    a, r = _pairs(angles, rates, "angles", "rates")
    if extrinsic:
        i, k = k, i
        a, r = a[..., ::-1], r[..., ::-1]
    axes = np.eye(3)
    q_k = Q.from_axis_angle(axes[k], a[..., 2])
    q_jk = Q.multiply(Q.from_axis_angle(axes[j], a[..., 1]), q_k)
    return (
        r[..., 2, None] * axes[k]
        + r[..., 1, None] * Q.rotate(Q.conjugate(q_k), axes[j])
        + r[..., 0, None] * Q.rotate(Q.conjugate(q_jk), axes[i])
    )


def zyz_rates_from_body_omega(angles, w) -> np.ndarray:
    """(ψ̇, θ̇, φ̇) from ZYZ angles and body angular velocity (the paper's eq. 19, corrected).

    Parameters
    ----------
    angles : array_like, shape (..., 3)
        Intrinsic ZYZ angles (ψ, θ, φ) in radians, away from gimbal lock.
    w : array_like, shape (..., 3)
        Body-frame angular velocity (rad/s).

    Returns
    -------
    ndarray, shape (..., 3)

    Raises
    ------
    InputError
        Where |sin θ| <= :data:`ga_rotors.euler.GIMBAL_TOLERANCE` (1e-14), the tolerance
        at which :func:`ga_rotors.euler.from_quaternion` reports gimbal lock: ψ̇ and φ̇
        are not defined at sin θ = 0 (only ψ̇ ± φ̇ is), and within it sin θ is rounding
        (θ = π gives sin θ = 1.2e-16, which made ψ̇ 8e15 times too large, silently).

    Examples
    --------
    >>> angles = [0.3, 0.7, -1.1]
    >>> w = body_omega_from_zyz_rates(angles, [0.02, 0.02, 15.7])
    >>> np.round(zyz_rates_from_body_omega(angles, w), 12)
    array([ 0.02,  0.02, 15.7 ])
    """
    a, w = _pairs(angles, w, "angles", "w")
    _, theta, phi = np.moveaxis(a, -1, 0)
    st = np.sin(theta)
    locked = np.abs(st) <= GIMBAL_TOLERANCE
    if np.any(locked):
        where = tuple(int(i) for i in np.argwhere(np.atleast_1d(locked))[0])
        raise InputError(
            f"|sin θ| <= {GIMBAL_TOLERANCE:g} (gimbal lock) at index {where}; the ZYZ "
            "rates ψ̇ and φ̇ are undefined there (only ψ̇ + φ̇ at θ = 0, ψ̇ − φ̇ at θ = π)",
            key="angles",
        )
    sp, cp = np.sin(phi), np.cos(phi)
    w1, w2, w3 = np.moveaxis(w, -1, 0)
    with np.errstate(over="ignore", invalid="ignore"):
        dpsi = (w2 * sp - w1 * cp) / st
        out = np.stack([dpsi, w1 * sp + w2 * cp, w3 - dpsi * np.cos(theta)], axis=-1)
    if not np.all(np.isfinite(out)):
        raise InputError("the ZYZ rates overflow float64 (|ω| / |sin θ| too large)", key="w")
    return out


def quaternion_rate(q, w) -> np.ndarray:
    r""":math:`\dot q = \tfrac12 q \otimes (0, \omega)` for unit quaternions q (w, x, y, z) and
    body ω.

    Examples
    --------
    >>> quaternion_rate([1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 2.0])
    array([0., 0., 0., 1.])
    """
    q, w = _pairs(q, w, "q", "w", last_a=4)
    q = require_unit(q, "q")
    q0, q1, q2, q3 = np.moveaxis(q, -1, 0)
    w1, w2, w3 = np.moveaxis(w, -1, 0)
    return 0.5 * np.stack(
        [
            -q1 * w1 - q2 * w2 - q3 * w3,
            q0 * w1 + q2 * w3 - q3 * w2,
            q0 * w2 - q1 * w3 + q3 * w1,
            q0 * w3 + q1 * w2 - q2 * w1,
        ],
        axis=-1,
    )


def body_omega_from_quaternion_rate(q, qdot) -> np.ndarray:
    r""":math:`\omega = 2 \operatorname{vec}(q^* \otimes \dot q)` for unit q: the inverse of
    :func:`quaternion_rate`.

    The scalar part q·q̇, which the rate of a unit quaternion does not have, is dropped:
    ω is that of q̇'s projection onto the tangent space at q (the least-squares ω for a
    q̇ taken from finite differences, where q·q̇ ≈ −h|ω|²/8 is not zero).

    Examples
    --------
    >>> body_omega_from_quaternion_rate([1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 1.0])
    array([0., 0., 2.])
    """
    q, d = _pairs(q, qdot, "q", "qdot", last_a=4, last_b=4)
    q = require_unit(q, "q")
    q0, q1, q2, q3 = np.moveaxis(q, -1, 0)
    d0, d1, d2, d3 = np.moveaxis(d, -1, 0)
    # vec((q0, -q⃗) ⊗ (d0, d⃗)) = q0 d⃗ - d0 q⃗ - q⃗ × d⃗
    return 2.0 * np.stack(
        [
            q0 * d1 - d0 * q1 - (q2 * d3 - q3 * d2),
            q0 * d2 - d0 * q2 - (q3 * d1 - q1 * d3),
            q0 * d3 - d0 * q3 - (q1 * d2 - q2 * d1),
        ],
        axis=-1,
    )


def _cl3():
    from .rotor import layout  # the one shared Cl(3) layout (building one costs ~1 s)

    lay = layout()
    return lay, lay.blades


def _unit_rotor(R):
    """R checked like every rotor argument (Cl(3), even, finite, unit within
    UNIT_TOLERANCE) and renormalised; InputError naming ``R`` otherwise."""
    from . import rotor

    return rotor.from_quaternion(rotor.to_quaternion(R))


def rotor_rate(R, w):
    r""":math:`\dot R = \tfrac12 R \Omega`, :math:`\Omega = -I \omega`, for a clifford rotor R and
    body angular velocity ω.

    Parameters
    ----------
    R : clifford.MultiVector
        A unit rotor of Cl(3,0) (within ``UNIT_TOLERANCE`` of unit norm: renormalised;
        otherwise, or odd or non-finite, :class:`~ga_rotors.errors.InputError`).
    w : array_like, shape (3,)
        Body angular velocity.

    Examples
    --------
    >>> from ga_rotors import rotor
    >>> R = rotor.from_quaternion([1.0, 0.0, 0.0, 0.0])
    >>> rotor_rate(R, [0.0, 0.0, 2.0])  # rotation about z: Ṙ = -e12
    -(1.0^e12)
    """
    blades = _cl3()[1]
    w = as_float_array(w, "w", last=3)
    if w.shape != (3,):
        raise InputError(f"expected one angular velocity of shape (3,), got {w.shape}", key="w")
    R = _unit_rotor(R)
    vec = w[0] * blades["e1"] + w[1] * blades["e2"] + w[2] * blades["e3"]
    omega = -(blades["e123"] * vec)
    return 0.5 * R * omega


def body_omega_from_rotor_rate(R, Rdot) -> np.ndarray:
    r""":math:`\omega = \langle 2 I \tilde R \dot R \rangle_1`: the body angular velocity of a unit
    rotor moving at Ṙ.

    As in :func:`body_omega_from_quaternion_rate`, the part of Ṙ along R (the scalar of
    R̃Ṙ) is dropped.

    Examples
    --------
    >>> from ga_rotors import rotor
    >>> R = rotor.from_quaternion([1.0, 0.0, 0.0, 0.0])
    >>> body_omega_from_rotor_rate(R, rotor_rate(R, [0.1, 0.2, 0.3]))
    array([0.1, 0.2, 0.3])
    """
    layout, blades = _cl3()
    R = _unit_rotor(R)
    if getattr(Rdot, "layout", None) != layout:
        raise InputError("expected a clifford MultiVector of the Cl(3) layout", key="Rdot")
    from_even(Rdot.value, name="Rdot")  # finite and even, as the rate of a rotor is
    v = (2.0 * blades["e123"] * ~R * Rdot)(1)
    return np.array([v[blades["e1"]], v[blades["e2"]], v[blades["e3"]]], dtype=np.float64)
