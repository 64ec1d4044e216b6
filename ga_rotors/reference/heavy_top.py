r"""The heavy symmetric (Lagrange) top, exactly: :math:`\cos\theta(t)` through Jacobi's
:math:`\operatorname{sn}`, :math:`\psi(t)` and :math:`\phi(t)` through elliptic integrals of
the third kind.

Goldstein, *Classical Mechanics* §5.7, rederived for this package's conventions and checked
against a 30-digit Taylor integration (``tests/test_reference_heavy.py``).

Model. A body with principal moments :math:`(I_\perp, I_\perp, I_3)` about a fixed point,
centre of mass on the body z axis at distance :math:`l`, gravity :math:`-g\hat z` (space).
In the body frame the torque is :math:`\tau = mgl\,(Z \times e_3) = mgl\,(Z_y, -Z_x, 0)`,
:math:`Z = q^* \hat z q` the body components of the vertical, and the energy is
:math:`E = \tfrac12 \sum_k I_k \omega_k^2 + mgl Z_z`. Orientation in the paper's intrinsic
z–y′–z″ angles, :math:`q = q_z(\psi) \otimes q_y(\theta) \otimes q_z(\phi)`: :math:`\psi`
precession, :math:`\theta` nutation (the symmetry axis's angle from the vertical),
:math:`\phi` spin.

Solution. :math:`\omega_3 = L_3/I_3` and :math:`L_Z` are constant; with
:math:`u = \cos\theta`, :math:`a = L_3/I_\perp`, :math:`b = L_Z/I_\perp`,
:math:`\alpha = 2E'/I_\perp` (:math:`E' = E - \tfrac12 I_3\omega_3^2`),
:math:`\beta = 2mgl/I_\perp`:

.. math::

    \begin{aligned}
    \dot u^2 &= f(u) = (1 - u^2)(\alpha - \beta u) - (b - au)^2
      = \beta (u - u_1)(u - u_2)(u - u_3), \\
    u(t) &= u_1 + (u_2 - u_1) \operatorname{sn}^2(\lambda t + r_0 \mid m), \quad
      m = \frac{u_2 - u_1}{u_3 - u_1}, \quad
      \lambda = \tfrac12 \sqrt{\beta (u_3 - u_1)}, \\
    \dot\psi &= \frac{b - au}{1 - u^2} = \frac{b - a}{2(1 - u)} + \frac{b + a}{2(1 + u)}, \\
    \dot\phi &= \omega_3 - u\dot\psi
      = \omega_3 - a - \frac{b - a}{2(1 - u)} + \frac{b + a}{2(1 + u)},
    \end{aligned}

and :math:`1 \mp u = (1 \mp u_1)(1 - n_\pm \operatorname{sn}^2)` with
:math:`n_+ = (u_2 - u_1)/(1 - u_1)`, :math:`n_- = -(u_2 - u_1)/(1 + u_1)`, so
:math:`\int \mathrm{d}t/(1 \mp u)` is :func:`ga_rotors.reference.elliptic.pi_integral` in
closed form.

Precision. The coefficients of the cubic are computed exactly (rational arithmetic on the
float inputs, the orientation taken as the rotation :math:`q/\lvert q \rvert`) and rounded
once, in two expansions, about :math:`u_0` and about the upright vertical:

.. math::

    \begin{aligned}
    f(u_0 + x) &= \dot u_0^2 + f'(u_0)\, x + \tfrac12 f''(u_0)\, x^2 + \beta x^3, \\
    f(1 - v) &= -(b - a)^2 + \bigl(2(\alpha - \beta) - 2a(b - a)\bigr) v
      + \bigl(2\beta - (\alpha - \beta) - a^2\bigr) v^2 - \beta v^3.
    \end{aligned}

Each root is taken from the nearer centre, so :math:`u_2 - u_1` (steady precession,
:math:`m \to 0`) and :math:`u_3 - u_2` (the separatrix, :math:`m \to 1`: the top rising to
within :math:`(u_3 - u_2)^{1/2}` of the unstable upright position) are sums of roots known
to a few ulps of their own size: the textbook route (roots of :math:`f` from
:math:`\alpha, \beta, a, b` in floats) loses half the digits of :math:`u_2 - u_1`, and even
the expansion about :math:`u_0` alone moved :math:`u_3 - u_2` by
:math:`\sim \varepsilon / (u_3 - u_2)` next to the separatrix (relative error 1e-4 in
:math:`1 - m` at 1e-6, 1.8e-4 rad after one period). The starting phase :math:`r_0` is
read from :math:`\operatorname{sn} r_0 \propto \sqrt{u_0 - u_1}`,
:math:`\operatorname{cn} r_0 \propto \sqrt{u_2 - u_0}` by
:func:`ga_rotors.reference.elliptic.jacobi_argument` (through the amplitude,
:math:`F(\phi_0 \mid m)` would multiply the rounding of :math:`\phi_0` by
:math:`1/\operatorname{dn}(r_0) \approx 1/\sqrt{1 - m}` next to :math:`u_2`: 1.2e-9 rad at
:math:`1 - m = 10^{-14}`). Every state carries a rounding-error bound
(:attr:`State.error`) and :meth:`HeavyTop.state` raises
:class:`ga_rotors.errors.PrecisionError` above ``max_error``; the constructor raises it
when :math:`1 - m` is not a normal float (:math:`u_3 - u_2` within rounding of the
separatrix) or the motion reaches a vertical exactly.

Frames. A body given by a rotated tensor (:meth:`ga_rotors.body.RigidBody.from_tensor`) is
solved in its principal frame, whose z axis is the symmetry axis carrying the centre of
mass (as :func:`gravity_torque` acts in ``simulate``, which integrates in that frame), and
answered in the user's body frame (:meth:`~ga_rotors.body.RigidBody.to_principal`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

import numpy as np
from scipy.optimize import brentq

from .._jit import jit
from .._validate import as_float_array, require_unit
from ..body import RigidBody
from ..effects import vertical_gravity
from ..errors import InputError, PrecisionError
from ..integrators.base import TorqueTerm
from . import elliptic
from .asymmetric_top import State, _orientation_error, _times

__all__ = ["HeavyTop", "State", "gravity_torque"]

_EPS = float(np.finfo(float).eps)


def _root(g, lo, hi):
    """A root of g in [lo, hi]; an end point when g has one sign there (the root is within
    the rounding of g from it)."""
    g_lo, g_hi = g(lo), g(hi)
    if g_lo == 0.0 or ((g_lo > 0.0) == (g_hi > 0.0) and abs(g_lo) <= abs(g_hi)):
        return lo
    if g_hi == 0.0 or (g_lo > 0.0) == (g_hi > 0.0):
        return hi
    try:
        return brentq(g, lo, hi, xtol=1e-300, rtol=4 * _EPS, maxiter=500)
    except RuntimeError:  # no convergence: gravity below the rounding (mgl = 1e-320 ...)
        raise PrecisionError(
            f"the heavy-top reference cannot locate a root of its cubic in [{lo:.17g}, "
            f"{hi:.17g}] (gravity too weak against the spin for float64?)"
        ) from None


def gravity_torque(mgl: float) -> TorqueTerm:
    """The heavy top's gravity as an integrator torque term: mgl · (Z_y, −Z_x, 0) in the body.

    It is the scene engine's gravity effect for the weight (0, 0, −mgl) acting at unit
    distance along body +z, τ = ẑ × (q* (−mgl ẑ) q) = −mgl ẑ × Z = mgl · (Z_y, −Z_x, 0),
    Z = q* ẑ q, with the kernel a scene with that weight and lever runs
    (:func:`ga_rotors.effects.vertical_gravity`: 8 operations a stage instead of the
    general kernel's rotation and cross product, about 40).

    Examples
    --------
    >>> from ga_rotors.integrators import Problem
    >>> problem = Problem((1.0, 1.0, 0.5), torques=(gravity_torque(2.0),))
    >>> gravity_torque(2.0).params, gravity_torque(2.0).kernel.__name__
    ((0.0, 0.0, -2.0, 0.0, 0.0, 1.0), 'vertical_gravity')
    """
    weight_and_lever = (0.0, 0.0, -float(mgl), 0.0, 0.0, 1.0)
    return TorqueTerm(vertical_gravity, weight_and_lever, name="gravity", depends_on_omega=False)


#: Times :func:`_state_loop` takes through each of its passes at once (its scratch
#: arrays: 7 x 32 KiB).
_CHUNK = 4096


@jit
def _state_loop(t, constants, m, m1, means, roots, c, q_out, w_out, err_out):
    """:meth:`HeavyTop.state` at each time of ``t`` (from the solution's constants):
    orientations, body rates and rounding-error bounds into the three arrays. Returns
    whether every value is finite.

    :data:`_CHUNK` times at a time: their arguments reduced, their sn, cn, dn
    (:func:`~ga_rotors.reference.elliptic.sncndn_many`) and both Π-integrals
    (:func:`~ga_rotors.reference.elliptic.pi_pairs`), each many arguments in lockstep,
    then each state (:func:`_state_row`).

    The elliptic functions it calls are compiled into it, and numba keys its cached
    machine code on this file alone: a change to :mod:`~ga_rotors.reference.elliptic`
    reaches this loop once this file changes too (or the cache is cleared)."""
    rate, r0, k, n_p, n1_p, complete_p, n_m, n1_m, complete_m = constants[:9]
    bad = 0.0
    size = min(t.shape[0], _CHUNK)
    js, rs, sns, cns, dns = (np.empty(size), np.empty(size), np.empty(size), np.empty(size),
                             np.empty(size))  # fmt: skip
    pluses, minuses = np.empty(size), np.empty(size)
    for start in range(0, t.shape[0], _CHUNK):
        rows = min(_CHUNK, t.shape[0] - start)
        for i in range(rows):  # reduced once for sn, Π₊, Π₋
            js[i], rs[i] = elliptic.reduce_argument(rate * t[start + i] + r0, k)
        elliptic.sncndn_many(rs[:rows], m, m1, means, roots, c, sns[:rows], cns[:rows],
                             dns[:rows])  # fmt: skip
        elliptic.pi_pairs(rs[:rows], js[:rows], sns[:rows], cns[:rows], dns[:rows], n_p,
                          n1_p, complete_p, n_m, n1_m, complete_m, pluses[:rows],
                          minuses[:rows])  # fmt: skip
        for i in range(rows):
            bad += _state_row(t[start + i], js[i], rs[i], sns[i], cns[i], dns[i], pluses[i],
                              minuses[i], constants, q_out[start + i], w_out[start + i],
                              err_out, start + i)  # fmt: skip
    return bad == 0.0


@jit
def _state_row(ti, j, r, s, cr, d, pi_plus, pi_minus, constants, q_row, w_row, err_out, i):
    """One sample of :func:`_state_loop` from its reduced argument, sn, cn, dn and both
    Π: its orientation, body rate and bound into ``q_row``, ``w_row`` and ``err_out[i]``;
    returns 0.0, or nan when a value is not finite."""
    (rate, r0, _, n_p, n1_p, _, n_m, _, _, p0_p, scale_p, p0_m, scale_m, om1, op1, psi0, phi0,
     w3, a, half_bma, half_bpa, udot_scale, phase_gain, sin_min) = constants  # fmt: skip
    # divisions by constants as products by their reciprocals (a rounding more each, far
    # inside the bound's 16 ulps; a division costs several products)
    per_scale_p, per_scale_m = 1.0 / scale_p, 1.0 / scale_m
    gain, unit = phase_gain / rate, 16.0 * _EPS / sin_min
    phase = rate * ti + r0
    sign = elliptic.half_period_sign(j)
    sn, cn, dn = sign * s, sign * cr, d
    one_minus = om1 * (n1_p + n_p * cn * cn)
    one_plus = op1 * (1.0 - n_m * sn * sn)
    p_plus = (pi_plus - p0_p) * per_scale_p
    p_minus = (pi_minus - p0_m) * per_scale_m
    psi = psi0 + half_bma * p_plus + half_bpa * p_minus
    phi = phi0 + (w3 - a) * ti - half_bma * p_plus + half_bpa * p_minus
    # q = q_z(ψ) ⊗ q_y(θ) ⊗ q_z(φ) = (c cos Σ, −s sin Δ, s cos Δ, c sin Σ) with
    # Σ, Δ = (ψ ± φ)/2 and c, s = cos(θ/2), sin(θ/2) = √(1 + u), √(1 − u) over their
    # norm (θ = 2 atan2(√(1 − u), √(1 + u)), read without the arctangent)
    root_minus, root_plus = math.sqrt(one_minus), math.sqrt(one_plus)
    norm = math.sqrt(one_minus + one_plus)
    half_sin, half_cos = root_minus * (1.0 / norm), root_plus * (1.0 / norm)
    half_sum, half_diff = 0.5 * (psi + phi), 0.5 * (psi - phi)
    cs, ss, cd, sd = (
        math.cos(half_sum),
        math.sin(half_sum),
        math.cos(half_diff),
        math.sin(half_diff),
    )
    q = (half_cos * cs, -half_sin * sd, half_sin * cd, half_cos * ss)
    # Body rates from the angles' rates (z–y′–z″): ω = (−ψ̇ sθ cφ + θ̇ sφ, ψ̇ sθ sφ + θ̇ cφ, ω₃).
    sin_t = root_minus * root_plus
    psidot = half_bma / one_minus + half_bpa / one_plus
    # θ̇ = −u̇ / sin θ, u̇ = 2 (u₂ − u₁) λ sn cn dn
    thetadot = -(udot_scale * sn * cn * dn) / sin_t
    cphi, sphi = cs * cd + ss * sd, ss * cd - cs * sd  # φ = Σ − Δ
    w = (-psidot * sin_t * cphi + thetadot * sphi, psidot * sin_t * sphi + thetadot * cphi, w3)
    # A few ulps of the phase r (|r| + |r₀| + 1) move ψ and φ at most by the largest of
    # their rates over λ: ½|b − a|/(1 − u) peaks at u₂ (1 − u₂, not 1 − u₁: they differ
    # most next to the separatrix), ½|b + a|/(1 + u) at u₁; the Π-integrals carry a
    # few ulps of |Π(n₊; r)| ≤ |r|/(1 − n₊) = |r| (1 − u₁)/(1 − u₂), the same term
    # (``phase_gain``). Measured errors against a 34-54-digit oracle are 22-290x below
    # this bound, next to the separatrix (1 − m down to 1e-14) as far from it
    # (tests/test_reference_heavy.py).
    err = unit * (
        1.0 + (abs(phase) + abs(r0) + 1.0) * gain + abs(psi) + abs(phi) + abs(w3 - a) * abs(ti)
    )
    for n in range(4):
        q_row[n] = q[n]
    for n in range(3):
        w_row[n] = w[n]
    err_out[i] = err
    return (q[0] + q[1] + q[2] + q[3] + w[0] + w[1]) * 0.0


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
        (I⊥, I⊥, I₃) about the fixed point: the first two equal. A RigidBody's
        ``principal_rotation`` is honoured: orientation and angular velocity, given and
        returned, are those of the user's body frame.
    mgl : float
        Mass × gravity × distance of the centre of mass along the principal +z axis
        (> 0): body +z when the body is given by its principal moments.
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
        self.body = body if isinstance(body, RigidBody) else None
        moments = body.moments if isinstance(body, RigidBody) else body
        inertia = as_float_array(moments, "moments", last=3)
        if inertia.shape != (3,) or not np.all(inertia > 0):
            raise InputError(f"moments: expected 3 positive moments, got {inertia}")
        if inertia[0] != inertia[1]:
            turned = self.body is not None and not self.body.is_principal
            raise InputError(
                f"moments: a symmetric top needs I1 == I2 (symmetry axis = body z), got {inertia}"
                + (
                    "; these are the principal moments of a turned tensor, in increasing order "
                    "(RigidBody.from_tensor), so a top whose distinct moment is the smallest has "
                    "its symmetry axis on principal x, not on principal z where gravity_torque "
                    "puts the centre of mass"
                    if turned
                    else ""
                )
            )
        if not (math.isfinite(mgl) and mgl > 0):
            raise InputError(f"mgl: expected a positive finite number, got {mgl!r}")
        w = as_float_array(angular_velocity, "angular_velocity", last=3)
        given = as_float_array(orientation, "orientation", last=4)
        q = require_unit(given, "orientation")
        if w.shape != (3,) or q.shape != (4,):
            raise InputError("orientation, angular_velocity: expected shapes (4,) and (3,)")
        self.moments = tuple(float(x) for x in inertia)
        self.mgl = float(mgl)
        self.w0 = tuple(float(x) for x in w)
        self.q0 = tuple(float(x) for x in q)
        # The solution is computed for the rotation given/|given| exactly: renormalising in
        # floats turns it by an ulp, which next to the separatrix moves 1 − m by ~ε/(1 − m)
        # relative (2.8e-10 at 1 − m = 1e-14). In a turned frame, given ⊗ P is solved.
        given, wp = self._to_principal(given, w)
        self._given = tuple(float(x) for x in given)
        self._w0 = tuple(float(x) for x in wp)
        self._setup()

    def _to_principal(self, q, w):
        return (q, w) if self.body is None else self.body.to_principal(q, w)

    def _from_principal(self, q, w):
        return (q, w) if self.body is None else self.body.from_principal(q, w)

    def energy(self, q, w):
        """Total energy ½ Σ I_k ω_k² + mgl cos θ for states (q, ω) of shape (..., 4), (..., 3)
        (of the user's body frame, as :meth:`state` returns them)."""
        q, w = self._to_principal(np.asarray(q, float), np.asarray(w, float))
        zz = q[..., 0] ** 2 - q[..., 1] ** 2 - q[..., 2] ** 2 + q[..., 3] ** 2
        return 0.5 * (w * w * np.asarray(self.moments)).sum(-1) + self.mgl * zz

    def _setup(self):
        ip, i3, mgl = Fraction(self.moments[0]), Fraction(self.moments[2]), Fraction(self.mgl)
        w1, w2, w3 = (Fraction(x) for x in self._w0)
        qw, qx, qy, qz = (Fraction(x) for x in self._given)
        # Exact rational arithmetic on the float inputs (the rotation q/|q|): next to the
        # separatrix the coefficients below are O(1) terms cancelling to O(u₃ − u₂), and any
        # rounding here would move the nearly double root pair by ~ulp/(u₃ − u₂).
        rho = qw * qw + qx * qx + qy * qy + qz * qz
        zx, zy = 2 * (qx * qz - qw * qy) / rho, 2 * (qy * qz + qw * qx) / rho
        v0 = 2 * (qx * qx + qy * qy) / rho  # 1 − u₀
        p0 = 2 * (qw * qw + qz * qz) / rho  # 1 + u₀
        if v0 == 0 or p0 == 0:
            raise InputError(
                "the symmetry axis is vertical (θ0 = 0 or π), where the z–y′–z″ "
                "angles of the heavy-top solution are singular; tilt it",
                key="orientation",
            )
        u0 = (p0 - v0) / 2
        wp2 = w1 * w1 + w2 * w2
        h0 = w1 * zx + w2 * zy  # b − a u₀
        a = i3 * w3 / ip
        beta = 2 * mgl / ip
        udot = zx * w2 - zy * w1
        bma, bpa = h0 - a * v0, h0 + a * p0  # b − a, b + a: f(±1) = −(b ∓ a)²
        for value, name in ((bpa, "lower"), (bma, "upper")):
            if value == 0:
                raise PrecisionError(
                    f"heavy top: the motion reaches the {name} vertical (|cos θ| = 1); the "
                    "z–y′–z″ solution is singular there"
                )
        # f(u₀ + x) = c0 + c1 x + c2 x² + β x³ and f(1 − v) = e0 + e1 v + e2 v² − β v³:
        # u₁ is nearest u₀, u₃ nearest 1, u₂ is taken from whichever centre is nearer.
        c = (udot * udot, -2 * u0 * wp2 - beta * v0 * p0 + 2 * a * h0, -wp2 + 2 * beta * u0 - a * a)
        big_a = wp2 - beta * v0  # α − β
        e = (-bma * bma, 2 * big_a - 2 * a * bma, 2 * beta - big_a - a * a)
        x1, x2, v2, v3 = self._roots(c, e, float(beta), v0, p0)
        one_minus, one_plus = float(v0), float(p0)
        if x2 is None:
            x2 = one_minus - v2
        if v2 is None:
            v2 = one_minus - x2
        d21, d32 = x2 - x1, v2 - v3  # sums of non-negative terms: no cancellation
        d31 = d21 + d32
        self._d21 = d21
        self.m = d21 / d31
        self.m1 = d32 / d31
        self.rate = 0.5 * math.sqrt(float(beta) * d31)
        if not self.m1 >= np.finfo(float).tiny:
            raise PrecisionError(
                f"heavy top: 1 − m = {self.m1:.3g} is not a normal float (u₃ − u₂ within "
                "rounding of the unstable vertical separatrix); no periodic solution to this "
                "precision"
            )
        self._om1 = one_minus - x1  # 1 − u₁
        self._op1 = one_plus + x1  # 1 + u₁
        self._om2 = v2  # 1 − u₂
        self._n_plus, self._n1_plus = d21 / self._om1, v2 / self._om1
        if self._n_plus >= 1.0:
            raise PrecisionError(
                f"heavy top: the symmetry axis rises to {math.sqrt(2.0 * v2):.3g} rad of the "
                "upright vertical (1 − u₂ < ε(1 − u₁)/2: n₊ = 1 in floats), where the "
                "z–y′–z″ solution's precession integral is singular to this precision"
            )
        self._n_minus = -d21 / self._op1
        self._n1_minus = (one_plus + x2) / self._op1
        # sn²r₀ = (u₀ − u₁)/(u₂ − u₁), cn²r₀ = (u₂ − u₀)/(u₂ − u₁), sn r₀ with the sign of u̇₀:
        # read straight into Carlson's R_F (jacobi_argument), not through the amplitude,
        # whose rounding F(φ | m) multiplies by 1/dn(r₀) ≈ 1/√(1 − m) next to u₂.
        sn0 = math.copysign(math.sqrt(-x1), 1.0 if udot >= 0 else -1.0)
        self._r0 = elliptic.jacobi_argument(sn0, math.sqrt(x2), self.m, self.m1) if d21 else 0.0
        self._a = float(a)
        self._w3 = float(w3)
        self._b_minus_a = float(bma)
        self._b_plus_a = float(bpa)
        self._gauss = elliptic.GaussTransform(self.m, self.m1)
        self._p0 = (float(self._pi_plus(self._r0)), float(self._pi_minus(self._r0)))
        # ψ₀, φ₀ from q0 = q_z(ψ₀) q_y(θ₀) q_z(φ₀): (ψ+φ)/2 = atan2(z, w), (ψ−φ)/2 = atan2(−x, y).
        qw, qx, qy, qz = self._given
        s, d = math.atan2(qz, qw), math.atan2(-qx, qy)
        self._psi0, self._phi0 = s + d, s - d
        self._sin_min = math.sqrt(min(self._om1 * (2 - self._om1), self._op1 * (2 - self._op1)))
        gauss = self._gauss
        half_bma, half_bpa = 0.5 * self._b_minus_a, 0.5 * self._b_plus_a
        self._constants = (
            self.rate, self._r0, gauss.k,
            self._n_plus, self._n1_plus, gauss.complete_pi(self._n_plus, self._n1_plus),
            self._n_minus, self._n1_minus, gauss.complete_pi(self._n_minus, self._n1_minus),
            self._p0[0], self.rate * self._om1, self._p0[1], self.rate * self._op1,
            self._om1, self._op1, self._psi0, self._phi0, self._w3, self._a, half_bma, half_bpa,
            2.0 * self._d21 * self.rate,
            1.0 + abs(half_bma) / self._om2 + abs(half_bpa) / self._op1, self._sin_min,
        )  # fmt: skip

    @staticmethod
    def _roots(c, e, beta, v0, p0):
        """u₁ = u₀ + x₁, u₂ = u₀ + x₂ = 1 − v₂, u₃ = 1 − v₃ from the exact coefficients.

        Returns (x₁, x₂, v₂, v₃) with one of x₂, v₂ None (the centre u₂ was not taken
        from). Each root comes from the expansion about the nearer centre, whose rounded
        coefficients (relative error ε/2 each) fix it to a few ulps of its distance from
        that centre: x₁ ≤ 0 from u₀, v₃ ≤ 0 from 1, and u₂ ∈ [u₀, 1] from u₀ if f at the
        midpoint (evaluated exactly) is ≤ 0, else from 1.
        """
        c0, c1, c2 = c
        mid = v0 / 2
        f_mid = c0 + mid * (c1 + mid * (c2 + Fraction(beta) * mid))
        c0, c1, c2 = (float(x) for x in c)
        e0, e1, e2 = (float(x) for x in e)
        v0, p0, mid = float(v0), float(p0), float(mid)

        def fx(x):
            return c0 + x * (c1 + x * (c2 + beta * x))

        def gx(x):  # f(u₀ + x)/x when x = 0 is a root (θ̇₀ = 0)
            return c1 + x * (c2 + beta * x)

        def fv(v):
            return e0 + v * (e1 + v * (e2 - beta * v))

        turning = c0 == 0.0
        if turning and c1 == 0.0:  # steady precession: u₁ = u₂ = u₀
            x1, x2, v2 = 0.0, 0.0, None
        elif turning and c1 < 0.0:  # released at u₂ = u₀
            x1, x2, v2 = _root(gx, -p0, 0.0), 0.0, None
        else:
            x1 = 0.0 if turning else _root(fx, -p0, 0.0)
            if f_mid <= 0:
                x2, v2 = _root(gx if turning else fx, 0.0, mid), None
            else:
                x2, v2 = None, _root(fv, 0.0, mid)
        hi = 1.0
        while fv(-hi) < 0.0:
            hi = 2.0 * hi
        v3 = _root(fv, -hi, 0.0)
        return x1, x2, v2, v3

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
        if self.m1 < elliptic.MIN_M1:
            raise PrecisionError(
                f"heavy top reference: 1 − m = {self.m1:.3g} is below {elliptic.MIN_M1:.2g}, "
                "where the Jacobi elliptic functions lose their accuracy (u₃ − u₂ within "
                "~1e-154 of the unstable vertical separatrix)"
            )
        q, w, err = np.empty((t.size, 4)), np.empty((t.size, 3)), np.empty(t.size)
        finite = _state_loop(t, self._constants, *self._gauss.args, q, w, err)
        if self.body is not None and not self.body.is_principal:
            q, w = self._from_principal(q, w)
            err = err + 4.0 * _EPS  # q ⊗ P*: a few roundings
        worst = float(err.max())
        if not (worst <= max_error) or not finite:
            raise PrecisionError(
                f"heavy top reference: rounding-error bound {worst:.3g} rad exceeds "
                f"max_error={max_error:.3g} rad; shorten the time span or raise max_error",
                bound=worst,
            )
        return State(q, w, err)
