"""A symmetric top under isotropic viscous damping τ = −c ω, exactly (ω(t) always; the
orientation too when the body is a sphere).

Derivation. Let k be the symmetry axis (moments I⊥, I⊥, I_k) and (a, b, k) a cyclic order
of the axes. Euler's equations with τ = −c ω read::

    I_k ω̇_k = −c ω_k
    I⊥ ω̇_a = (I⊥ − I_k) ω_b ω_k − c ω_a
    I⊥ ω̇_b = (I_k − I⊥) ω_k ω_a − c ω_b

The first gives ω_k(t) = ω_k(0) e^(−ct/I_k): the gyroscopic term has no component along k.
With z = ω_a + i ω_b the other two are one complex equation, ż = −(iΩ(t) + c/I⊥) z with
Ω = (I⊥ − I_k) ω_k / I⊥, so::

    z(t) = z(0) e^(−ct/I⊥) e^(−iΦ(t)),
    Φ(t) = ∫₀ᵗ Ω = (I⊥ − I_k)/I⊥ · ω_k(0) · I_k (1 − e^(−ct/I_k))/c

The transverse rate |z| decays as e^(−ct/I⊥) while its phase turns by Φ, which tends to
the finite limit (I⊥ − I_k) ω_k(0) I_k/(I⊥ c): damping stops the body-frame precession
after a finite angle. |L|² = I⊥²|z|² + I_k² ω_k² is the sum of two exponentials, so |L|
decays as a single exponential e^(−ct/I) only for a sphere (I⊥ = I_k = I), where
additionally ω̇ = −(c/I) ω keeps ω's direction û fixed in the body *and* in space and the
orientation is q(t) = q₀ ⊗ Exp(θ(t) û), θ(t) = |ω₀| I (1 − e^(−ct/I))/c.

The factor (1 − e^(−x))/c is evaluated as −expm1(−x)/c (no cancellation for small ct), and
at c = 0 as its limit t, so the torque-free symmetric top's body rates are the special case.
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
    """Exact body rates of a symmetric top with τ = −c ω; orientation for a sphere.

    Parameters
    ----------
    body : RigidBody or array_like (3,)
        Principal moments with two exactly equal (the third axis is the symmetry axis). A
        RigidBody's ``principal_rotation`` is honoured: orientation and angular velocity,
        given and returned, are those of the user's body frame (the torque −c ω is the
        same in every frame).
    c : float
        Damping coefficient (N·m·s), ≥ 0.
    orientation : array_like (4,)
        Initial body->space unit quaternion.
    angular_velocity : array_like (3,)
        Initial body angular velocity (rad/s).

    Examples
    --------
    A sphere: ω keeps its direction and decays as e^(−ct/I).

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
        """|L(t)| (kg·m²/s)."""
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
