r"""A symmetric top under isotropic viscous damping :math:`\tau = -c\,\omega`, exactly
(:math:`\omega(t)` always; the orientation too when the body is a sphere).

Derivation. Let :math:`k` be the symmetry axis (moments :math:`I_\perp, I_\perp, I_k`) and
:math:`(a, b, k)` a cyclic order of the axes. Euler's equations with
:math:`\tau = -c\,\omega` read

.. math::

    \begin{aligned}
    I_k \dot\omega_k &= -c\,\omega_k, \\
    I_\perp \dot\omega_a &= (I_\perp - I_k)\, \omega_b \omega_k - c\,\omega_a, \\
    I_\perp \dot\omega_b &= (I_k - I_\perp)\, \omega_k \omega_a - c\,\omega_b.
    \end{aligned}

The first gives :math:`\omega_k(t) = \omega_k(0)\, e^{-ct/I_k}`: the gyroscopic term has no
component along :math:`k`. With :math:`z = \omega_a + i\,\omega_b` the other two are one
complex equation, :math:`\dot z = -\bigl(i\,\Omega(t) + c/I_\perp\bigr)\, z` with
:math:`\Omega = (I_\perp - I_k)\, \omega_k / I_\perp`, so

.. math::

    \begin{aligned}
    z(t) &= z(0)\, e^{-ct/I_\perp} e^{-i\Phi(t)}, \\
    \Phi(t) &= \int_0^t \Omega = \frac{I_\perp - I_k}{I_\perp}\, \omega_k(0)\,
      \frac{I_k \bigl(1 - e^{-ct/I_k}\bigr)}{c}.
    \end{aligned}

The transverse rate :math:`\lvert z \rvert` decays as :math:`e^{-ct/I_\perp}` while its
phase turns by :math:`\Phi`, which tends to the finite limit
:math:`(I_\perp - I_k)\, \omega_k(0)\, I_k / (I_\perp c)`: damping stops the body-frame
precession after a finite angle.
:math:`\lvert L \rvert^2 = I_\perp^2 \lvert z \rvert^2 + I_k^2 \omega_k^2` is the sum of two
exponentials, so :math:`\lvert L \rvert` decays as a single exponential :math:`e^{-ct/I}`
only for a sphere (:math:`I_\perp = I_k = I`), where additionally
:math:`\dot\omega = -(c/I)\, \omega` keeps :math:`\omega`'s direction :math:`\hat u` fixed
in the body *and* in space and the orientation is

.. math::

    q(t) = q_0 \otimes \operatorname{Exp}\bigl(\theta(t)\, \hat u\bigr), \qquad
    \theta(t) = \lvert \omega_0 \rvert\, \frac{I \bigl(1 - e^{-ct/I}\bigr)}{c}.

The factor :math:`(1 - e^{-x})/c` is evaluated as :math:`-\operatorname{expm1}(-x)/c` (no
cancellation for small :math:`ct`), and at :math:`c = 0` as its limit :math:`t`, so the
torque-free symmetric top's body rates are the special case.
"""

from __future__ import annotations

import math

import numpy as np

from .._validate import as_float_array, require_unit
from ..body import RigidBody
from ..errors import InputError
from .symmetric_top import symmetry_axis

__all__ = ["DampedSymmetricTop"]


def _decayed_time(c: float, inertia: float, t: np.ndarray) -> np.ndarray:
    """∫₀ᵗ e^(−cs/I) ds = I (1 − e^(−ct/I))/c, and t at c = 0."""
    if c == 0.0:
        return t
    return -np.expm1(-c * t / inertia) * (inertia / c)


class DampedSymmetricTop:
    r"""Exact body rates of a symmetric top with :math:`\tau = -c\,\omega`; orientation for a
    sphere.

    Parameters
    ----------
    body : RigidBody or array_like (3,)
        Principal moments with two exactly equal (the third axis is the symmetry axis). A
        RigidBody's ``principal_rotation`` is honoured: orientation and angular velocity,
        given and returned, are those of the user's body frame (the torque
        :math:`-c\,\omega` is the same in every frame).
    c : float
        Damping coefficient (N·m·s), :math:`c \ge 0`.
    orientation : array_like (4,)
        Initial body->space unit quaternion.
    angular_velocity : array_like (3,)
        Initial body angular velocity (rad/s).

    Examples
    --------
    A sphere: :math:`\omega` keeps its direction and decays as :math:`e^{-ct/I}`.

    >>> top = DampedSymmetricTop((2.0, 2.0, 2.0), 0.5, [1.0, 0, 0, 0], [0.0, 0.0, 4.0])
    >>> w = top.angular_velocity([0.0, 4.0])
    >>> w[:, 2].round(12).tolist(), round(4.0 * math.exp(-1.0), 12)
    ([4.0, 1.471517764686], 1.471517764686)
    """

    def __init__(self, body, c, orientation, angular_velocity):
        self.body = body if isinstance(body, RigidBody) else RigidBody(body)
        moments = self.body.moments
        k = symmetry_axis(moments)
        i1, i2, i3 = moments
        if (
            isinstance(c, bool)
            or not isinstance(c, int | float)
            or not (math.isfinite(c) and c >= 0)
        ):
            raise InputError(f"c: expected a finite damping coefficient ≥ 0, got {c!r}")
        w0 = as_float_array(angular_velocity, "angular_velocity", last=3)
        q0 = require_unit(as_float_array(orientation, "orientation", last=4), "orientation")
        if w0.shape != (3,) or q0.shape != (4,):
            raise InputError("orientation and angular_velocity: expected shapes (4,) and (3,)")
        self.moments = tuple(moments)
        self.axis = k
        self.c = float(c)
        self.q0 = q0
        self.w0 = w0
        self._q0, self._w0 = self.body.to_principal(q0, w0)  # solved in the principal frame
        self.spherical = i1 == i2 == i3

    def angular_velocity(self, t) -> np.ndarray:
        """Body angular velocity (n, 3) at times ``t`` (s, from the initial state)."""
        return self.body.from_principal(None, self._angular_velocity(t))[1]

    def _angular_velocity(self, t) -> np.ndarray:
        t = as_float_array(t, "t").reshape(-1)
        k = self.axis
        a, b = (k + 1) % 3, (k + 2) % 3
        i_k, i_perp = self.moments[k], self.moments[a]
        out = np.empty((t.shape[0], 3))
        out[:, k] = self._w0[k] * np.exp(-self.c * t / i_k)
        phase = (i_perp - i_k) / i_perp * self._w0[k] * _decayed_time(self.c, i_k, t)
        z = (self._w0[a] + 1j * self._w0[b]) * np.exp(-self.c * t / i_perp - 1j * phase)
        out[:, a], out[:, b] = z.real, z.imag
        return out

    def momentum_norm(self, t) -> np.ndarray:
        r""":math:`\lvert L(t) \rvert` (kg·m²/s)."""
        return np.linalg.norm(self._angular_velocity(t) * np.asarray(self.moments), axis=-1)

    def at(self, t) -> tuple[np.ndarray, np.ndarray]:
        """Orientations (n, 4) and body rates (n, 3); the orientation needs a sphere.

        Examples
        --------
        >>> top = DampedSymmetricTop((1.0, 1.0, 1.0), 1.0, [1.0, 0, 0, 0], [0.0, 0.0, 2.0])
        >>> q, _ = top.at([1e9])                       # turns by |ω₀| I / c = 2 rad in all
        >>> q.round(12).tolist()
        [[0.540302305868, 0.0, 0.0, 0.841470984808]]
        """
        from .. import quaternion as Q

        if not self.spherical:
            raise InputError(
                f"body: the damped top's orientation is exact only for a sphere; moments "
                f"{self.moments} are not all equal (its angular velocity is exact)"
            )
        t = as_float_array(t, "t").reshape(-1)
        # A sphere turns about the fixed direction of ω in any body frame: no frame change.
        speed = float(np.linalg.norm(self.w0))
        w = self.angular_velocity(t)
        if speed == 0.0:
            return np.tile(self.q0, (t.shape[0], 1)), w
        turned = speed * _decayed_time(self.c, self.moments[0], t)
        rotvec = turned[:, None] * (self.w0 / speed)
        return Q.multiply(self.q0, Q.from_rotation_vector(rotvec)), w

    def orientation_error(self, t, q) -> np.ndarray:
        """Geodesic angle (rad) between ``q`` (n, 4) and the exact orientations at ``t``."""
        from ..quaternion import distance

        ref, _ = self.at(t)
        return np.atleast_1d(distance(ref, as_float_array(q, "q", last=4).reshape(-1, 4)))
