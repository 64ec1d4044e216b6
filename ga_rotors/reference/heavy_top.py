"""The heavy symmetric (Lagrange) top, exactly: cos θ(t) through Jacobi's sn, ψ(t) and φ(t)
through elliptic integrals of the third kind.

Goldstein, *Classical Mechanics* §5.7, rederived for this package's conventions and checked
against a 30-digit Taylor integration (``tests/test_reference_heavy.py``).

Model. A body with principal moments (I⊥, I⊥, I₃) about a fixed point, centre of mass on the
body z axis at distance l, gravity −g ẑ (space). In the body frame the torque is
τ = mgl · (Z × e₃) = mgl · (Z_y, −Z_x, 0), Z = q* ẑ q the body components of the vertical,
and the energy is E = ½ Σ I_k ω_k² + mgl Z_z. Orientation in the paper's intrinsic z–y′–z″
angles, q = q_z(ψ) ⊗ q_y(θ) ⊗ q_z(φ): ψ precession, θ nutation (the symmetry axis's angle
from the vertical), φ spin.

Solution. ω₃ = L₃/I₃ and L_Z are constant; with u = cos θ, a = L₃/I⊥, b = L_Z/I⊥,
α = 2E′/I⊥ (E′ = E − ½I₃ω₃²), β = 2mgl/I⊥::

    u̇² = f(u) = (1 − u²)(α − βu) − (b − au)² = β (u − u₁)(u − u₂)(u − u₃),
    u(t) = u₁ + (u₂ − u₁) sn²(λt + r₀ | m),  m = (u₂ − u₁)/(u₃ − u₁),  λ = ½√(β (u₃ − u₁)),
    ψ̇ = (b − au)/(1 − u²) = (b − a)/(2(1 − u)) + (b + a)/(2(1 + u)),
    φ̇ = ω₃ − u ψ̇ = ω₃ − a − (b − a)/(2(1 − u)) + (b + a)/(2(1 + u)),

and 1 ∓ u = (1 ∓ u₁)(1 − n_± sn²) with n₊ = (u₂ − u₁)/(1 − u₁), n₋ = −(u₂ − u₁)/(1 + u₁), so
∫ dt/(1 ∓ u) is :func:`ga_rotors.reference.elliptic.pi_integral` in closed form.

Precision. The roots are found for the cubic in x = u − u₀ whose coefficients come
straight from the initial state (u̇₀², f′(u₀), f″(u₀)/2, β): near steady precession u₁ and u₂
nearly coincide, and the textbook route (roots of f from α, β, a, b) loses half the digits
of u₂ − u₁, while here the nutation amplitude keeps an absolute error at the ulp level.
Every state carries a rounding-error bound (:attr:`State.error`) and
:meth:`HeavyTop.state` raises :class:`ga_rotors.errors.PrecisionError` above ``max_error``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from .. import quaternion as Q
from .._validate import as_float_array, require_unit
from ..body import RigidBody
from ..effects import gravity
from ..errors import InputError, PrecisionError
from ..integrators.base import TorqueTerm
from . import elliptic
from .asymmetric_top import State, _orientation_error, _times, axis_rotation

__all__ = ["HeavyTop", "State", "gravity_torque"]

_EPS = float(np.finfo(float).eps)


def gravity_torque(mgl: float) -> TorqueTerm:
    """The heavy top's gravity as an integrator torque term: mgl · (Z_y, −Z_x, 0) in the body.

    It is the scene engine's gravity effect (:func:`ga_rotors.effects.gravity`, one kernel for
    every weight) with weight (0, 0, −mgl) acting at unit distance along body +z:
    τ = ẑ × (q* (−mgl ẑ) q) = −mgl ẑ × Z = mgl · (Z_y, −Z_x, 0), Z = q* ẑ q.

    Examples
    --------
    >>> from ga_rotors.integrators import Problem
    >>> problem = Problem((1.0, 1.0, 0.5), torques=(gravity_torque(2.0),))
    >>> gravity_torque(2.0).params
    (0.0, 0.0, -2.0, 0.0, 0.0, 1.0)
    """
    return TorqueTerm(
        gravity, (0.0, 0.0, -float(mgl), 0.0, 0.0, 1.0), name="gravity", depends_on_omega=False
    )


@dataclass(frozen=True)
class Nutation:
    """Nutation of the heavy top: bounds of θ, period, and mean precession rate.

    Attributes
    ----------
    theta_min, theta_max : float
        Bounds of θ (radians): arccos u₂ and arccos u₁.
    period : float
        Time between successive θ maxima, 2K(m)/λ.
    mean_precession : float
        ψ advance per nutation period divided by the period (rad/s).
    """

    theta_min: float
    theta_max: float
    period: float
    mean_precession: float


class HeavyTop:
    """Exact motion of a heavy symmetric top about a fixed point.

    Parameters
    ----------
    body : RigidBody or array_like, shape (3,)
        (I⊥, I⊥, I₃) about the fixed point: the first two equal.
    mgl : float
        Mass × gravity × distance of the centre of mass along body +z (> 0).
    orientation : array_like, shape (4,)
        Initial orientation (body to space); the symmetry axis must not be vertical
        (0 < θ₀ < π), where the z–y′–z″ angles are singular.
    angular_velocity : array_like, shape (3,)
        Initial body angular velocity.

    Examples
    --------
    >>> q0 = (np.cos(0.25), 0.0, np.sin(0.25), 0.0)
    >>> top = HeavyTop((1.0, 1.0, 0.5), 1.0, q0, (0.0, 0.0, 10.0))
    >>> nut = top.nutation()
    >>> round(float(np.degrees(nut.theta_min)), 9), round(float(np.degrees(nut.theta_max)), 4)
    (28.647889757, 31.1037)
    >>> s = top.state([0.0, 2.0])
    >>> bool(np.isclose(top.energy(s.q[1], s.w[1]), top.energy(s.q[0], s.w[0]), rtol=1e-14))
    True
    """

    def __init__(self, body, mgl, orientation, angular_velocity):
        moments = body.moments if isinstance(body, RigidBody) else body
        inertia = as_float_array(moments, "moments", last=3)
        if inertia.shape != (3,) or not np.all(inertia > 0):
            raise InputError(f"moments: expected 3 positive moments, got {inertia}")
        if inertia[0] != inertia[1]:
            raise InputError(
                f"moments: a symmetric top needs I1 == I2 (symmetry axis = body z), got {inertia}"
            )
        if not (math.isfinite(mgl) and mgl > 0):
            raise InputError(f"mgl: expected a positive finite number, got {mgl!r}")
        w = as_float_array(angular_velocity, "angular_velocity", last=3)
        q = require_unit(as_float_array(orientation, "orientation", last=4), "orientation")
        if w.shape != (3,) or q.shape != (4,):
            raise InputError("orientation, angular_velocity: expected shapes (4,) and (3,)")
        self.moments = tuple(float(x) for x in inertia)
        self.mgl = float(mgl)
        self.w0 = tuple(float(x) for x in w)
        self.q0 = tuple(float(x) for x in q)
        self._setup()

    def energy(self, q, w):
        """Total energy ½ Σ I_k ω_k² + mgl cos θ for states (q, ω) of shape (..., 4), (..., 3)."""
        q, w = np.asarray(q, float), np.asarray(w, float)
        zz = q[..., 0] ** 2 - q[..., 1] ** 2 - q[..., 2] ** 2 + q[..., 3] ** 2
        return 0.5 * (w * w * np.asarray(self.moments)).sum(-1) + self.mgl * zz

    def _setup(self):
        ip, _, i3 = self.moments
        w1, w2, w3 = self.w0
        qw, qx, qy, qz = self.q0
        zx, zy = 2.0 * (qx * qz - qw * qy), 2.0 * (qy * qz + qw * qx)
        one_minus = 2.0 * (qx * qx + qy * qy)  # 1 − u₀ and 1 + u₀ without cancellation
        one_plus = 2.0 * (qw * qw + qz * qz)
        if one_minus == 0.0 or one_plus == 0.0:
            raise InputError(
                "orientation: the symmetry axis is vertical (θ0 = 0 or π), where the z–y′–z″ "
                "angles of the heavy-top solution are singular; tilt it"
            )
        u0 = 0.5 * (one_plus - one_minus)
        s0 = zx * zx + zy * zy  # sin²θ₀
        wp2 = w1 * w1 + w2 * w2
        h0 = w1 * zx + w2 * zy  # b − a u₀
        a = i3 * w3 / ip
        beta = 2.0 * self.mgl / ip
        udot = zx * w2 - zy * w1
        # f(u₀ + x) = c0 + c1 x + c2 x² + β x³, each coefficient from the state directly.
        c0 = udot * udot
        c1 = -2.0 * u0 * wp2 - beta * s0 + 2.0 * a * h0
        c2 = -wp2 + 2.0 * beta * u0 - a * a
        scale = abs(c0) + abs(c1) + abs(c2) + beta

        def f(x):
            return c0 + x * (c1 + x * (c2 + beta * x))

        x1, x2, x3 = self._roots(f, c0, c1, c2, beta, one_plus, one_minus)
        d21, d31, d32 = x2 - x1, x3 - x1, x3 - x2
        self._u = (u0 + x1, u0 + x2, u0 + x3)
        self.m = d21 / d31
        self.m1 = d32 / d31
        self.rate = 0.5 * math.sqrt(beta * d31)
        if self.m1 <= 0.0:
            raise PrecisionError(
                "heavy top: u₂ = u₃ (the unstable vertical separatrix); no periodic solution"
            )
        self._om1 = one_minus - x1  # 1 − u₁
        self._op1 = one_plus + x1  # 1 + u₁
        self._n_plus, self._n1_plus = d21 / self._om1, (one_minus - x2) / self._om1
        self._n_minus = -d21 / self._op1
        self._n1_minus = (one_plus + x2) / self._op1
        sgn = 1.0 if udot >= 0.0 else -1.0
        amp = math.atan2(sgn * math.sqrt(max(-x1, 0.0)), math.sqrt(max(x2, 0.0)))
        self._r0 = float(elliptic.incomplete_first(amp, self.m, self.m1))
        self._a = a
        self._w3 = w3
        self._b_minus_a = h0 - a * one_minus
        self._b_plus_a = h0 + a * one_plus
        self._p0 = (self._pi_plus(self._r0), self._pi_minus(self._r0))
        # ψ₀, φ₀ from q0 = q_z(ψ₀) q_y(θ₀) q_z(φ₀): (ψ+φ)/2 = atan2(z, w), (ψ−φ)/2 = atan2(−x, y).
        s, d = math.atan2(qz, qw), math.atan2(-qx, qy)
        self._psi0, self._phi0 = s + d, s - d
        self._scale = scale
        self._sin_min = math.sqrt(min(self._om1 * (2 - self._om1), self._op1 * (2 - self._op1)))

    @staticmethod
    def _roots(f, c0, c1, c2, beta, one_plus, one_minus):
        """Roots x₁ ≤ 0 ≤ x₂ ≤ x₃ of f(u₀ + x), x₁ ≥ −(1 + u₀), x₂ ≤ 1 − u₀ ≤ x₃."""
        if c0 == 0.0:
            # θ̇₀ = 0: x = 0 is a turning point; deflate to β x² + c2 x + c1 = 0 (stable form).
            disc = math.sqrt(max(c2 * c2 - 4.0 * beta * c1, 0.0))
            qq = -0.5 * (c2 + math.copysign(disc, c2))
            others = [qq / beta, c1 / qq if qq else 0.0]
            return tuple(sorted([0.0, *others]))
        for end, name in ((-one_plus, "lower"), (one_minus, "upper")):
            if f(end) > 0.0:
                raise PrecisionError(
                    f"heavy top: the motion reaches the {name} vertical (|cos θ| = 1) within "
                    "rounding; the z–y′–z″ solution is singular there"
                )
        x1 = brentq(f, -one_plus, 0.0, xtol=1e-300, rtol=4 * _EPS, maxiter=500)
        x2 = brentq(f, 0.0, one_minus, xtol=1e-300, rtol=4 * _EPS, maxiter=500)
        hi = 2.0 * one_minus + 1.0
        while f(hi) < 0.0:
            hi = 2.0 * hi
        x3 = brentq(f, one_minus, hi, xtol=1e-300, rtol=4 * _EPS, maxiter=500)
        return x1, x2, x3

    def _pi_plus(self, r):
        return elliptic.pi_integral(r, self._n_plus, self.m, self.m1, self._n1_plus)

    def _pi_minus(self, r):
        return elliptic.pi_integral(r, self._n_minus, self.m, self.m1, self._n1_minus)

    def nutation(self) -> Nutation:
        """Bounds of θ, nutation period and mean precession rate."""
        k = elliptic.complete_first(self.m, self.m1)
        period = 2.0 * k / self.rate
        dpsi = self._psi_increment(np.array([self._r0 + 2.0 * k]))[0]
        theta_max = 2.0 * math.atan2(math.sqrt(self._om1), math.sqrt(self._op1))
        om2 = self._om1 * self._n1_plus
        theta_min = 2.0 * math.atan2(math.sqrt(om2), math.sqrt(2.0 - om2))
        return Nutation(theta_min, theta_max, period, dpsi / period)

    def _psi_increment(self, r):
        p_plus = (self._pi_plus(r) - self._p0[0]) / (self.rate * self._om1)
        p_minus = (self._pi_minus(r) - self._p0[1]) / (self.rate * self._op1)
        return 0.5 * self._b_minus_a * p_plus + 0.5 * self._b_plus_a * p_minus

    def at(self, t) -> tuple[np.ndarray, np.ndarray]:
        """Orientations (n, 4) and body angular velocities (n, 3) at times ``t``
        (:meth:`state` with its default ``max_error``)."""
        s = self.state(t)
        return s.q, s.w

    def orientation_error(self, t, q) -> np.ndarray:
        """Geodesic angle (rad) between orientations ``q`` (n, 4) and the exact ones at ``t``."""
        return _orientation_error(self.at(t)[0], q)

    def state(self, t, max_error: float = 1e-10) -> State:
        """Orientation and body angular velocity at times ``t``, with an error bound.

        Examples
        --------
        >>> top = HeavyTop((2.0, 2.0, 1.0), 3.0, (0.9, 0.3, 0.3, 0.1), (0.5, -0.2, 8.0))
        >>> s = top.state([0.0])
        >>> bool(np.allclose(s.q[0], np.array(top.q0), atol=1e-15))
        True
        """
        t = _times(t)
        r = self.rate * t + self._r0
        sn, cn, dn = elliptic.jacobi(r, self.m, self.m1)
        one_minus = self._om1 * (self._n1_plus + self._n_plus * cn * cn)
        one_plus = self._op1 * (1.0 - self._n_minus * sn * sn)
        theta = 2.0 * np.arctan2(np.sqrt(one_minus), np.sqrt(one_plus))
        p_plus = (self._pi_plus(r) - self._p0[0]) / (self.rate * self._om1)
        p_minus = (self._pi_minus(r) - self._p0[1]) / (self.rate * self._op1)
        half_bma, half_bpa = 0.5 * self._b_minus_a, 0.5 * self._b_plus_a
        psi = self._psi0 + half_bma * p_plus + half_bpa * p_minus
        phi = self._phi0 + (self._w3 - self._a) * t - half_bma * p_plus + half_bpa * p_minus
        q = Q.multiply(
            Q.multiply(axis_rotation(2, psi), axis_rotation(1, theta)), axis_rotation(2, phi)
        )
        # Body rates from the angles' rates (z–y′–z″): ω = (−ψ̇ sθ cφ + θ̇ sφ, ψ̇ sθ sφ + θ̇ cφ, ω₃).
        sin_t = np.sqrt(one_minus * one_plus)
        psidot = half_bma / one_minus + half_bpa / one_plus
        # θ̇ = −u̇ / sin θ, u̇ = 2 (u₂ − u₁) λ sn cn dn
        udot = 2.0 * (self._u[1] - self._u[0]) * self.rate * sn * cn * dn
        thetadot = -udot / sin_t
        cphi, sphi = np.cos(phi), np.sin(phi)
        w = np.stack(
            [
                -psidot * sin_t * cphi + thetadot * sphi,
                psidot * sin_t * sphi + thetadot * cphi,
                np.full_like(t, self._w3),
            ],
            axis=-1,
        )
        err = (
            16.0
            * _EPS
            * (
                1.0
                + (np.abs(r) + abs(self._r0) + 1.0)
                * (1.0 + abs(half_bma) / self._om1 + abs(half_bpa) / self._op1)
                / self.rate
                + np.abs(psi)
                + np.abs(phi)
                + abs(self._w3 - self._a) * np.abs(t)
            )
            / self._sin_min
        )
        worst = float(err.max())
        if not (worst <= max_error) or not np.isfinite(q).all():
            raise PrecisionError(
                f"heavy top reference: rounding-error bound {worst:.3g} rad exceeds "
                f"max_error={max_error:.3g} rad; shorten the time span or raise max_error"
            )
        return State(q, w, err)
