"""The torque-free asymmetric top, exactly: Jacobi elliptic functions plus closed-form quadrature.

Landau & Lifshitz, *Mechanics* §37, rederived here for any ordering of the moments and
checked against a 30-digit Taylor integration (``tests/test_reference_asymmetric.py``).

Axes. With the moments sorted, let b be the middle axis and, with L² = |Iω|², E the kinetic
energy, a the axis the angular momentum circulates around: the largest-moment axis when
L² > 2E·I_b, the smallest when L² < 2E·I_b; c is the remaining one. Then, with u = λt + u₀::

    ω_a = α dn(u|m),  ω_b = β sn(u|m),  ω_c = γ cn(u|m)

    α² = (L² − 2E I_c) / (I_a (I_a − I_c)),   γ² = (2E I_a − L²) / (I_c (I_a − I_c)),
    β² = (2E I_a − L²) / (I_b (I_a − I_b)),   λ² = (I_a − I_b)(L² − 2E I_c) / (I_a I_b I_c),
    m  = (I_b − I_c)(2E I_a − L²) / ((I_a − I_b)(L² − 2E I_c)),
    1 − m = (I_a − I_c)(L² − 2E I_b) / ((I_a − I_b)(L² − 2E I_c)),

γ > 0, sign α = sign ω_a(0), sign β = σ sign(α (I_c − I_a)), σ = +1 when (a, b, c) is a
cyclic order of (1, 2, 3) and −1 otherwise (Euler's equation for ω_b). The
differences 2E I_a − L² = Σ_k I_k (I_a − I_k) ω_k² etc. are formed in exact rational
arithmetic from the float inputs and rounded once, so m and 1 − m are correctly rounded
however close the motion is to the separatrix L² = 2E I_b (where plain float arithmetic
leaves 1 − m with no correct digit).

Orientation. Let P be the fixed rotation taking body axis a to z (a cyclic relabelling of
the body axes, so the relabelled frame stays right-handed), and write the relabelled
orientation in intrinsic z–x′–z″ angles about the space direction of L::

    q(t) = Q₀ ⊗ R_z(ψ) ⊗ R_x(θ) ⊗ R_z(φ) ⊗ P,    P L_body / |L| = (sin θ sin φ, sin θ cos φ, cos θ).

θ and φ are fixed by L in the body; the precession angle ψ obeys (L&L 37.16)
ψ̇ = |L| (2E − I_a ω_a²) / (L² − I_a² ω_a²), which with dn² = 1 − m sn² becomes::

    ψ̇ = |L| / I_a + |L| (1/I_c − 1/I_a) / (1 − n sn² u),
    n = −I_a (I_b − I_c) / (I_c (I_a − I_b)) < 0,

integrated in closed form by :func:`ga_rotors.reference.elliptic.pi_integral` (elliptic
integral of the third kind), so no numerical quadrature is involved. Q₀ ⊗ R_z(ψ₀) is fixed
by the initial orientation.

Precision. Every result carries an error bound in radians (:attr:`State.error`), from the
rounding of the phase u and the angle ψ (both grow linearly in t) and of the elliptic
function values (the starting phase u₀ is read from sn₀, cn₀ by
:func:`ga_rotors.reference.elliptic.jacobi_argument`, well conditioned next to the middle
axis, where going through the amplitude would amplify its rounding by 1/√(1 − m));
:meth:`AsymmetricTop.state` raises :class:`ga_rotors.errors.PrecisionError`
when the bound exceeds ``max_error`` instead of returning a degraded answer. The constructor
raises it when 1 − m, correctly rounded, is not a normal float (motion within ~1e-154 of the
separatrix, off it): a subnormal or zero 1 − m would give a wrong flip period.

Frames. A body given by a rotated tensor (:meth:`ga_rotors.body.RigidBody.from_tensor`) is
solved in its principal frame and answered in the user's body frame, as ``simulate``
integrates it (:meth:`~ga_rotors.body.RigidBody.to_principal`). Its principal moments and
axes are the tensor's only to within the diagonalisation's residual
(:attr:`~ga_rotors.body.RigidBody.tensor_residual`), and carrying ω into the principal frame
rounds it by a few ulps. The flow amplifies such a change of the initial state, next to
the separatrix by orders of magnitude at each flip (1e-16 of ω moved the answer by 3e-12
rad after one flip of a motion 1e-9 from it), so the error bound of such a body adds the
answer's own sensitivity: the state is solved again from ω moved by that radius along each
principal axis and from each moment moved by the residual, and the distances to those
answers (summed in quadrature for ω, in full for the moments, doubled for the second
order) are added to the bound, with the axes' own error. A body given by its principal
moments has no such term (its inputs are exact).
"""

from __future__ import annotations

import math
import sys
from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from .. import quaternion as Q
from .._validate import as_float_array, require_unit
from ..body import RigidBody
from ..errors import InputError, PrecisionError
from . import elliptic

__all__ = ["AsymmetricTop", "State"]

_EPS = float(np.finfo(float).eps)

# Cyclic relabellings (proper rotations) taking body axis a to z: P v P* has a-th
# component of v as its z component. Index = a.
_RELABEL = (
    (0.5, -0.5, -0.5, -0.5),  # x -> z, y -> x, z -> y
    (0.5, 0.5, 0.5, 0.5),  # y -> z, z -> x, x -> y
    (1.0, 0.0, 0.0, 0.0),
)


@dataclass(frozen=True)
class State:
    """Exact state at the requested times.

    Attributes
    ----------
    q : ndarray, shape (n, 4)
        Orientation, body to space, unit quaternions (scalar first).
    w : ndarray, shape (n, 3)
        Body angular velocity (in the user's body frame, as ``q``).
    error : ndarray, shape (n,)
        Bound on the geodesic error of ``q`` from floating-point rounding, radians.

    Examples
    --------
    >>> top = AsymmetricTop((1.0, 2.0, 3.0), (1.0, 0.0, 0.0, 0.0), (1.0, 0.5, 0.2))
    >>> s = top.state([0.0, 1.0, 2.0])
    >>> s.q.shape, s.w.shape, s.error.shape
    ((3, 4), (3, 3), (3,))
    >>> bool(Q.distance(s.q[0], (1.0, 0.0, 0.0, 0.0)) <= s.error[0])  # q(0) = q0, to the bound
    True
    """

    q: np.ndarray
    w: np.ndarray
    error: np.ndarray


def axis_rotation(axis: int, angle) -> np.ndarray:
    """Unit quaternions of rotations by ``angle`` (array) about body axis 0, 1 or 2."""
    unit = np.zeros(3)
    unit[axis] = 1.0
    return Q.from_axis_angle(unit, np.asarray(angle, dtype=float))


class AsymmetricTop:
    """Exact torque-free motion of a rigid body with three distinct principal moments.

    Parameters
    ----------
    body : RigidBody or array_like, shape (3,)
        Principal moments (any order), pairwise distinct; a symmetric body has the
        closed form of :mod:`ga_rotors.reference.symmetric_top`. A RigidBody's
        ``principal_rotation`` is honoured: orientation and angular velocity, given and
        returned, are those of the user's body frame.
    orientation : array_like, shape (4,)
        Initial orientation, body to space (unit within
        :data:`ga_rotors._validate.UNIT_TOLERANCE`, renormalised).
    angular_velocity : array_like, shape (3,)
        Initial body angular velocity.

    Attributes
    ----------
    energy, momentum : float
        Kinetic energy E and |L|.
    m, m1 : float
        Elliptic parameter and 1 − m, each correctly rounded from the exact invariants.
    rate : float
        λ, the rate of the Jacobi argument u = λt + u₀.
    flip_period : float
        2K(m)/λ: the time between successive sign changes of the middle-axis rate ω_b
        (the flips of the intermediate-axis effect near the separatrix); ``inf`` on the
        separatrix.

    Examples
    --------
    >>> top = AsymmetricTop((1.0, 2.0, 3.0), (1.0, 0.0, 0.0, 0.0), (0.1, 2.0, 0.05))
    >>> s = top.state([0.0, 1.5])
    >>> bool(np.allclose(s.w[0], (0.1, 2.0, 0.05), rtol=0, atol=1e-15))
    True
    >>> bool(s.error.max() < 1e-12)
    True
    >>> round(top.flip_period, 6)
    8.782751
    """

    def __init__(self, body, orientation, angular_velocity):
        self.body = body if isinstance(body, RigidBody) else RigidBody(body)
        inertia = self.body.moments
        if len(set(inertia)) < 3:
            raise InputError(
                f"moments: expected three distinct principal moments, got {inertia}; "
                "a symmetric body is solved by ga_rotors.reference.symmetric_top"
            )
        w = as_float_array(angular_velocity, "angular_velocity", last=3)
        if w.shape != (3,):
            raise InputError(f"angular_velocity: expected shape (3,), got {w.shape}")
        q = require_unit(as_float_array(orientation, "orientation", last=4), "orientation")
        if q.shape != (4,):
            raise InputError(f"orientation: expected one quaternion of shape (4,), got {q.shape}")
        self.moments = inertia
        self.w0 = tuple(float(x) for x in w)
        self.q0 = tuple(float(x) for x in q)
        qp, wp = self.body.to_principal(self.q0, self.w0)
        self._q0 = tuple(float(x) for x in qp)  # the principal frame's, solved below
        self._w0 = tuple(float(x) for x in wp)
        try:
            self._setup()
        except OverflowError:  # an invariant (L², 2E·I) beyond float64, exact but unroundable
            raise InputError(
                f"|Iω| = {math.hypot(*(i * w for i, w in zip(inertia, wp, strict=True))):.3g}: "
                "its square overflows float64; rescale the units",
                key="angular_velocity",
            ) from None
        self._axes_error, self._neighbours = 0.0, ()
        if not self.body.is_principal or self.body.tensor_residual > 0.0:
            self._neighbours = self._neighbouring_tops()

    def _neighbouring_tops(self) -> tuple:
        """The principal frame's motion from states as far from this one as the body's
        rounding may put it: ω moved along each principal axis by the axes' error and the
        frame change's rounding, each moment moved by the diagonalisation's residual (the
        moments' tops last). Their distances from this answer measure its sensitivity."""
        from ..body import FRAME_CHANGE_ULPS

        inertia, w = np.array(self.moments), np.array(self._w0)
        residual = self.body.tensor_residual
        gap = min(abs(inertia[i] - inertia[j]) for i, j in ((0, 1), (1, 2), (0, 2)))
        self._axes_error = residual / gap  # rad (Davis–Kahan)
        radius = float(np.linalg.norm(w)) * (self._axes_error + FRAME_CHANGE_ULPS * _EPS)
        states = [(inertia, w + radius * np.eye(3)[k]) for k in range(3) if radius > 0.0]
        self._moved_rates = len(states)
        states += [(inertia + residual * np.eye(3)[k], w) for k in range(3) if residual > 0.0]
        tops = []
        for moments, rates in states:
            try:
                tops.append(AsymmetricTop(moments, self._q0, rates))
            except (InputError, PrecisionError):
                raise PrecisionError(
                    "asymmetric top reference: the body's own rounding (its diagonalisation "
                    f"{residual:.2g} kg·m², the frame change of ω) reaches a state this "
                    "reference cannot solve: the motion is too close to the separatrix for "
                    "the body as given (give it by its principal moments)"
                ) from None
        return tuple(tops)

    # -- invariants, exactly ------------------------------------------------------------

    def _setup(self):
        inertia, w = self.moments, self._w0
        ex_i = [Fraction(x) for x in inertia]
        ex_w = [Fraction(x) for x in w]

        def excess(k):
            """2E I_k − L² = Σ_j I_j (I_k − I_j) ω_j², exactly."""
            return sum(ex_i[j] * (ex_i[k] - ex_i[j]) * ex_w[j] ** 2 for j in range(3))

        two_e = sum(ex_i[j] * ex_w[j] ** 2 for j in range(3))
        l2 = sum((ex_i[j] * ex_w[j]) ** 2 for j in range(3))
        self.energy = float(two_e / 2)
        self.momentum = math.sqrt(float(l2))
        order = sorted(range(3), key=lambda k: inertia[k])
        lo, b, hi = order
        sep = -excess(b)  # L² − 2E I_b
        a, c = (hi, lo) if sep >= 0 else (lo, hi)
        self._axes = (a, b, c)
        self._steady = sum(1 for x in w if x == 0.0) >= 2
        self.m = self.m1 = 0.0
        self.rate = 0.0
        self.flip_period = math.inf
        if self._steady:
            return  # rotation about a principal axis (or rest): q0 ⊗ exp(ω t / 2)
        ia, ib, ic = ex_i[a], ex_i[b], ex_i[c]
        d_a = excess(a)  # 2E I_a − L², sign of (I_a − I_c)
        d_c = -excess(c)  # L² − 2E I_c, sign of (I_a − I_c)
        self.m = float((ib - ic) * d_a / ((ia - ib) * d_c))
        exact_m1 = (ia - ic) * sep / ((ia - ib) * d_c)
        self.m1 = float(exact_m1)
        if sep and self.m1 < sys.float_info.min:
            # 1 − m is subnormal (a few digits left) or underflowed to 0, which would turn
            # a flipping motion into the separatrix's, which never flips: K(m), the flip
            # period and every phase past the first flip would be wrong, silently.
            raise PrecisionError(
                f"asymmetric top reference: 1 − m = {float(exact_m1):.3g} is below the "
                "smallest normal float; the motion is too close to the separatrix for "
                "double precision (move the initial ω off it by more than ~1e-154 relative)"
            )
        self.rate = math.sqrt(float((ia - ib) * d_c / (ia * ib * ic)))
        self._n = float(-ia * (ib - ic) / (ic * (ia - ib)))
        amp_a = math.sqrt(float(d_c / (ia * (ia - ic))))
        amp_b = math.sqrt(float(d_a / (ib * (ia - ib))))
        amp_c = math.sqrt(float(d_a / (ic * (ia - ic))))
        alpha = math.copysign(amp_a, w[a])
        parity = 1.0 if (b - a) % 3 == 1 else -1.0  # +1 when (a, b, c) is cyclic
        beta = amp_b if parity * float(ic - ia) * alpha > 0 else -amp_b
        self._amp = (alpha, beta, amp_c)
        self._coef = self.momentum * float((ia - ic) / (ia * ic)) / self.rate
        sn0 = w[b] / beta if amp_b else 0.0
        cn0 = w[c] / amp_c if amp_c else 1.0
        self._u0 = elliptic.jacobi_argument(sn0, cn0, self.m, self.m1)
        if self.m1 > 0.0:
            self.flip_period = 2.0 * elliptic.complete_first(self.m, self.m1) / self.rate
        self._relabel = _RELABEL[a]
        e0 = self._direction(np.array([w]))
        self._frame0 = Q.multiply(
            Q.multiply(self._q0, Q.conjugate(self._relabel)),
            Q.conjugate(self._nutation_spin(e0)[0]),
        )
        self._pi0 = float(elliptic.pi_integral(self._u0, self._n, self.m, self.m1))

    def _direction(self, w):
        """P L_body / |L|: the relabelled body components of the unit momentum."""
        return Q.rotate(self._relabel, w * np.asarray(self.moments)) / self.momentum

    @staticmethod
    def _nutation_spin(e):
        """R_x(θ) ⊗ R_z(φ) with (sin θ sin φ, sin θ cos φ, cos θ) = e."""
        theta = np.arctan2(np.hypot(e[:, 0], e[:, 1]), e[:, 2])
        phi = np.arctan2(e[:, 0], e[:, 1])
        return Q.multiply(axis_rotation(0, theta), axis_rotation(2, phi))

    # -- the solution ---------------------------------------------------------------

    def angular_velocity(self, t):
        """Body angular velocity ω(t), shape (n, 3).

        Examples
        --------
        >>> top = AsymmetricTop((1.0, 2.0, 3.0), (1.0, 0.0, 0.0, 0.0), (1.0, 0.5, 0.2))
        >>> w = top.angular_velocity([0.0, 3.0])
        >>> bool(np.isclose(top.energy, 0.5 * (w[1] ** 2 * (1, 2, 3)).sum(), rtol=1e-14))
        True
        """
        return self.body.from_principal(None, self._angular_velocity(_times(t)))[1]

    def _argument(self, u):
        """The Jacobi arguments u, reduced (:class:`elliptic.JacobiArgument`)."""
        if self.m1 < elliptic.MIN_M1:
            raise PrecisionError(
                f"asymmetric top reference: 1 − m = {self.m1:.3g} is below "
                f"{elliptic.MIN_M1:.2g}, where the Jacobi elliptic functions lose their "
                "accuracy; the motion is too close to the separatrix for double precision "
                "(move the initial ω off it by more than ~1e-77 relative)"
            )
        return elliptic.JacobiArgument(u, self.m, self.m1)

    def _angular_velocity(self, t, arg=None):
        """ω(t) in the principal frame, shape (n, 3) (``arg``: the Jacobi arguments of
        ``t``, :class:`~ga_rotors.reference.elliptic.JacobiArgument`, when the caller has
        them)."""
        if self._steady:
            return np.tile(self._w0, (t.size, 1))
        if arg is None:
            arg = self._argument(self.rate * t + self._u0)
        sn, cn, dn = arg.jacobi()
        a, b, c = self._axes
        out = np.empty((t.size, 3))
        out[:, a] = self._amp[0] * dn
        out[:, b] = self._amp[1] * sn
        out[:, c] = self._amp[2] * cn
        return out

    def state(self, t, max_error: float = 1e-10) -> State:
        """Orientation and angular velocity at times ``t``, with an error bound.

        Parameters
        ----------
        t : array_like
            Time(s), any sign.
        max_error : float
            Raise :class:`ga_rotors.errors.PrecisionError` if the rounding-error bound
            on any orientation exceeds this many radians.

        Examples
        --------
        >>> top = AsymmetricTop((2.0, 1.0, 3.0), (1.0, 0.0, 0.0, 0.0), (0.3, 1.0, -0.2))
        >>> s = top.state(np.linspace(0.0, 10.0, 5))
        >>> L = Q.rotate(s.q, s.w * (2.0, 1.0, 3.0))  # space-frame angular momentum
        >>> bool(np.allclose(L, L[0], rtol=0, atol=1e-13))
        True
        """
        t = _times(t)
        state = self._principal_state(t)
        if self._neighbours:
            # the answer's sensitivity to the body's rounding (module notes: Frames)
            moved = [Q.distance(state.q, top._principal_state(t).q) for top in self._neighbours]
            rates = np.sqrt(sum(d * d for d in moved[: self._moved_rates]))
            moments = sum(moved[self._moved_rates :], np.zeros(t.size))
            error = state.error + 2.0 * (rates + moments) + self._axes_error
            state = State(state.q, state.w, error)
        return self._checked(self._user_frame(state), max_error)

    def _principal_state(self, t) -> State:
        """:meth:`state` in the principal frame, with its own rounding bound, unchecked."""
        if self._steady:
            w = self._angular_velocity(t)
            half = 0.5 * t[:, None] * np.asarray(self._w0)
            rot = Q.exp(np.concatenate([np.zeros((t.size, 1)), half], axis=1))
            q = Q.multiply(self._q0, rot)
            err = 8.0 * _EPS * (1.0 + np.abs(t) * np.abs(self._w0).max())
            return State(q, w, err)
        u = self.rate * t + self._u0
        arg = self._argument(u)  # reduced once for ω and Π
        w = self._angular_velocity(t, arg)
        pi = arg.pi_integral(self._n)
        psi = self.momentum * t / self.moments[self._axes[0]] + self._coef * (pi - self._pi0)
        e = self._direction(w)
        q = Q.multiply(
            Q.multiply(self._frame0, axis_rotation(2, psi)),
            Q.multiply(self._nutation_spin(e), self._relabel),
        )
        q = q * np.where(q[:, :1] < 0.0, -1.0, 1.0)
        return State(q, w, self._rounding_bound(t, u, pi, e))

    def _user_frame(self, state: State) -> State:
        """``state`` (principal frame) in the user's body frame; q ⊗ P* adds a few ulps."""
        if self.body.is_principal:
            return state
        q, w = self.body.from_principal(state.q, state.w)
        return State(q, w, state.error + 4.0 * _EPS)

    def _rounding_bound(self, t, u, pi, e):
        """Bound on the geodesic error of q from rounding, radians.

        First-order propagation of a phase error. The computed u = λt + u₀ is off by
        δu = δu₀ + (a few ulps of |λt|, of |u| and of the 2jK removed by the reduction).
        Q₀ is fitted to the input ω, not to u₀, so it does not move; what moves is
        ψ − ψ₀ = |L|t/I_a + coef (Π(u) − Π(u₀)), by coef (g(u) δu − g(u₀) δu₀) with
        g = 1/(1 − n sn²) ∈ (0, 1] (n < 0), and the body direction e of L, by
        |de/du| δu ≤ max I · |dω/du| δu / |L|, which the z–x′–z″ angles turn into
        (1 + 1/sin θ) |de|. δu₀ is a few ulps of |u₀| + 2K because u₀ comes from
        :func:`elliptic.jacobi_argument` (sn₀, cn₀ straight into Carlson's R_F); taken
        through the amplitude, F(atan2(sn₀, cn₀) | m) multiplied the ulp of φ₀ ≈ π/2 by
        1/dn(u₀) ≈ 1/√(1 − m) when the motion starts next to the middle axis (1.1e-11 rad
        at 1 − m = 2e-12, near a flip, against a bound of 1.5e-12: issue 7). With
        2jK ≤ |u| + K ≤ 2|u| and |u₀| ≥ K on the branch that adds 2K, every δu is a few
        ulps of arg = |u| + |u₀| + 1. The elliptic function values carry a few ulps of
        their reduced argument (a phase error of the same size) plus an absolute ulp.
        ψ's terms each carry a few ulps of their size, and θ, φ are read from e with an
        absolute error of ε / sin θ. 16 covers the few roundings of each term; measured
        errors against the 30-digit oracle are 30-1400x below this bound (median ~70x: it
        sums worst cases of roundings that partly cancel), near the separatrix as far from
        it (tests/test_reference_asymmetric.py).
        """
        alpha, beta, gamma = self._amp
        dw_du = abs(alpha) * self.m + abs(beta) + abs(gamma)
        sin_theta = np.hypot(e[:, 0], e[:, 1])
        arg = np.abs(u) + abs(self._u0) + 1.0
        de_du = max(self.moments) * dw_du / self.momentum
        return (
            16.0
            * _EPS
            * (
                1.0
                + np.abs(self.momentum * t / self.moments[self._axes[0]])
                + np.abs(self._coef) * (np.abs(pi) + abs(self._pi0) + arg)
                + (arg * de_du + 1.0) / sin_theta
            )
        )

    def at(self, t) -> tuple[np.ndarray, np.ndarray]:
        """Orientations (n, 4) and body angular velocities (n, 3) at times ``t``.

        Same as :meth:`state` with its default ``max_error`` (raises
        :class:`ga_rotors.errors.PrecisionError` rather than return a degraded answer).

        Examples
        --------
        >>> top = AsymmetricTop((1.0, 2.0, 3.0), (1.0, 0.0, 0.0, 0.0), (0.1, 2.0, 0.05))
        >>> q, w = top.at([0.0, 1.0])
        >>> q.shape, w.shape
        ((2, 4), (2, 3))
        """
        s = self.state(t)
        return s.q, s.w

    def orientation_error(self, t, q) -> np.ndarray:
        """Geodesic angle (rad) between orientations ``q`` (n, 4) and the exact ones at ``t``.

        Examples
        --------
        >>> top = AsymmetricTop((1.0, 2.0, 3.0), (1.0, 0.0, 0.0, 0.0), (0.1, 2.0, 0.05))
        >>> q, _ = top.at([0.5, 1.0])
        >>> top.orientation_error([0.5, 1.0], q).tolist()
        [0.0, 0.0]
        """
        return _orientation_error(self.at(t)[0], q)

    @staticmethod
    def _checked(state: State, max_error: float) -> State:
        worst = float(state.error.max()) if state.error.size else 0.0
        if not (worst <= max_error) or not np.isfinite(state.q).all():
            raise PrecisionError(
                f"asymmetric top reference: rounding-error bound {worst:.3g} rad exceeds "
                f"max_error={max_error:.3g} rad at these times; shorten the time span or "
                "raise max_error",
                bound=worst,
            )
        return state


def _orientation_error(ref, q) -> np.ndarray:
    q = as_float_array(q, "q", last=4).reshape(-1, 4)
    if q.shape != ref.shape:
        raise InputError(f"q: expected {ref.shape[0]} orientations, got shape {q.shape}")
    return np.atleast_1d(Q.distance(ref, q))


def _times(t) -> np.ndarray:
    t = as_float_array(t, "t")
    return np.atleast_1d(t).ravel()
