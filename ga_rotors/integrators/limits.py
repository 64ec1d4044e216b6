"""Step limits: how far each fixed-step integrator's step can go before it degrades.

Each integrator declares ``step_limit(inertia, w0, h, nsteps) -> StepLimit`` (or None:
no limit) and ``step_limit_action`` ("warn" or "raise"); :meth:`Integrator.check_step`
evaluates it on the initial state. The quantities (derived in ``docs/stability.md``,
"Step limits"):

* ν, the linearisation's rate: the spectral radius of ∂ω̇/∂ω at ω₀ for the torque-free
  body (a torque is not included: its own rate is the user's to bound), and at least
  |ω|/2 for a method that steps q by a Runge–Kutta formula (q̇ = ½ q ⊗ ω has eigenvalues
  ±i|ω|/2). About a stable principal axis ±iν are the wobble's eigenvalues.
* A Runge–Kutta-type method (stability polynomial R from its tableau) scales the wobble's
  energy by |R(ihν)|² per step: :func:`wobble_damping` limits N·|ln |R(ihν)|²| to 1.
"""

from __future__ import annotations

import cmath
import math
from collections.abc import Sequence
from typing import NamedTuple

__all__ = [
    "PHASE_LIMIT",
    "StepLimit",
    "fixed_point_sweep",
    "linear_rate",
    "moser_veselov",
    "principal_rotation_angle",
    "stability_polynomial",
    "symmetric_remainder_angle",
    "wobble_damping",
]


class StepLimit(NamedTuple):
    """A step limit evaluated on one problem: ``value`` must stay below ``limit``.

    ``effect`` says what happens at this value (used in the warning).

    Examples
    --------
    >>> StepLimit("h·ν", 0.5, 2.0, "").exceeded
    False
    """

    quantity: str
    value: float
    limit: float
    effect: str

    @property
    def exceeded(self) -> bool:
        """Whether ``value`` is at or past ``limit`` (NaN counts as past)."""
        return not self.value < self.limit


def linear_rate(inertia, w, steps_q: bool = False) -> float:
    """ν: the spectral radius of ∂ω̇/∂ω for I ω̇ = (I ω) × ω at ``w``; with ``steps_q``
    at least |ω|/2, the rate of q̇ = ½ q ⊗ ω.

    Examples
    --------
    The flat disk (1, 1, 2) spinning at 1000 rad/s about its axis wobbles at
    (I₃ − I₁)/I₁ · ω₃ = 1000 rad/s:

    >>> round(linear_rate((1.0, 1.0, 2.0), (0.0, 0.0, 1000.0)), 9)
    1000.0
    >>> linear_rate((1.0, 1.0, 1.0), (0.0, 0.0, 3.0), steps_q=True)
    1.5
    """
    import numpy as np

    moments = np.asarray(inertia, dtype=float)
    w = np.asarray(w, dtype=float)

    def skew(v):
        return np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])

    # d/dω [I⁻¹((Iω) × ω)] = I⁻¹([Iω]× − [ω]× I)
    jac = (skew(moments * w) - skew(w) * moments) / moments[:, None]
    nu = float(np.max(np.abs(np.linalg.eigvals(jac))))
    return max(nu, 0.5 * float(np.linalg.norm(w))) if steps_q else nu


def stability_polynomial(a, b) -> tuple[float, ...]:
    """Coefficients c_k of R(z) = Σ c_k z^k = 1 + z bᵀ(I − zA)⁻¹𝟙 for an explicit tableau
    (A strictly lower triangular, so the series ends at z^s).

    Examples
    --------
    >>> a = ((0, 0, 0, 0), (0.5, 0, 0, 0), (0, 0.5, 0, 0), (0, 0, 1, 0))
    >>> [round(c, 15) for c in stability_polynomial(a, (1 / 6, 1 / 3, 1 / 3, 1 / 6))]
    [1.0, 1.0, 0.5, 0.166666666666667, 0.041666666666667]
    """
    import numpy as np

    b = np.asarray(b, dtype=float)
    a = np.asarray(a, dtype=float).reshape(len(b), len(b))  # also a flat, row-major A
    coeffs, v = [1.0], np.ones(len(b))
    for _ in range(len(b)):
        coeffs.append(float(b @ v))
        v = a @ v
    return tuple(coeffs)


def _ln_gain(coeffs: Sequence[float], y: float) -> float:
    """ln |R(iy)|²."""
    r = sum(c * (1j * y) ** k for k, c in enumerate(coeffs))
    return math.log(abs(r) ** 2) if r != 0 else -math.inf


#: Orientation error (rad) from the phase of a Runge–Kutta step on q alone, over the whole
#: run, past which the run warns: 0.1 rad (6°) is an error nobody would accept unannounced,
#: and still far above what a step that resolves the rotation gives (the paper's scene:
#: 5e-9 rad).
PHASE_LIMIT = 0.1


def wobble_damping(coeffs: Sequence[float], steps_q: bool, phase_on_q: bool | None = None):
    """The step limit of a Runge–Kutta-type method with stability polynomial ``coeffs``:
    N·|ln |R(ihν)|²| < 1, the wobble's energy changed by less than a factor e over the run;
    and, for a method that moves q by the tableau (``phase_on_q``, default ``steps_q``; also
    rk4_renorm, whose renormalisation fixes |q| but not its phase), the orientation's lag
    2N·|arg(R(iy) e^{−iy})| < :data:`PHASE_LIMIT` with y = h|ω|/2, the turn of q per step:
    q̇ = ½ q ⊗ ω is linear with eigenvalues ±i|ω|/2, so each step turns q by arg R(iy)
    instead of y and the body lags its spin (the fast spinner on (1, 1.5, 2): 0.48 rad in
    1 s at h|ω| = 1, while the wobble's energy changes by less than a factor e). The limit
    returned is the one further past (or nearer to) its bound.

    Examples
    --------
    RK4 on the fast disk of ``docs/stability.md``, 1000 steps at hν = 1:

    >>> rk4 = wobble_damping((1, 1, 1 / 2, 1 / 6, 1 / 24), steps_q=True)
    >>> lim = rk4((1.0, 1.0, 2.0), (5.0, 3.0, 1000.0), 1e-3, 1000)
    >>> lim.quantity, round(lim.value, 2), lim.exceeded
    ('N·|ln|R(ihν)|²|', 12.22, True)
    """

    def limit(inertia, w, h, nsteps) -> StepLimit:
        y = h * linear_rate(inertia, w, steps_q)
        ln_gain = _ln_gain(coeffs, y)
        total = nsteps * ln_gain
        amplitude = math.exp(0.5 * total) if total < 1400 else math.inf
        effect = (
            f"at hν = {y:.3g} each step scales the wobble's energy by |R(ihν)|² = "
            f"{math.exp(ln_gain):.6g}, so over {nsteps} steps its amplitude (‖ω⊥‖ about a "
            f"principal axis{', and |q|' if steps_q else ''}) is "
            + (f"damped × {amplitude:.3g}" if total < 0 else f"amplified × {amplitude:.3g}")
        )
        damping = StepLimit("N·|ln|R(ihν)|²|", abs(total), 1.0, effect)
        if not (steps_q if phase_on_q is None else phase_on_q):
            return damping
        y = 0.5 * h * _speed(w)
        r = sum(c * (1j * y) ** k for k, c in enumerate(coeffs))
        per_step = abs(cmath.phase(r * cmath.exp(-1j * y))) if r != 0 else math.pi
        lag = 2.0 * nsteps * per_step
        phase = StepLimit(
            "2N·|arg R(iy)e^(−iy)|",
            lag,
            PHASE_LIMIT,
            f"each step turns the body by 2·arg R(iy) instead of h|ω| = {2 * y:.3g} rad, so "
            f"over {nsteps} steps its orientation lags its spin by {lag:.3g} rad",
        )
        return max(damping, phase, key=lambda s: s.value / s.limit)

    return limit


def fixed_point_sweep(inertia, w, h, nsteps) -> StepLimit:
    """Implicit midpoint by fixed-point sweeps: the sweep's map has derivative (h/2)·∂f,
    whose spectral radius is hν/2 (ν with |ω|/2: the sweep also solves for q), so it
    contracts only while hν < 2.

    Examples
    --------
    >>> fixed_point_sweep((1.0, 1.0, 1.0), (0.0, 0.0, 3.0), 1.0, 10).value
    1.5
    """
    y = h * linear_rate(inertia, w, steps_q=True)
    return StepLimit(
        "h·ν",
        y,
        2.0,
        f"the fixed-point sweep contracts by hν/2 = {y / 2:.3g} per sweep; from 1 it "
        "diverges and the run stops (NaN), just below it it needs many sweeps",
    )


def moser_veselov(inertia, w, h, nsteps) -> StepLimit:
    """lgvi solves h Π = sin θ ⋯ for the step's rotation: about a principal axis (and on
    a sphere) it reads sin θ = h|ω|, with no solution from h|ω| = 1.

    Examples
    --------
    >>> moser_veselov((1.0, 2.0, 3.0), (0.0, 0.0, 2.0), 0.5, 1).exceeded
    True
    """
    y = h * _speed(w)
    return StepLimit(
        "h·|ω|",
        y,
        1.0,
        "its discrete Moser–Veselov equation, sin θ = h|ω| about a principal axis, has "
        "no solution there",
    )


def _speed(w) -> float:
    """|ω| (or the length of any 3-vector), without overflow or underflow."""
    return math.hypot(*(float(c) for c in w))


def _momentum(inertia, w) -> float:
    """|L| = |I ω| (principal frame)."""
    return _speed([float(i) * float(c) for i, c in zip(inertia, w, strict=True)])


def principal_rotation_angle(inertia, w, h, nsteps) -> StepLimit:
    """An axis splitting turns L about axis i by h·L_i/I_i ≤ h|L|/I_min per sub-flow; its
    error terms are nested commutators of those turns, powers of that angle times |L|/I_i:
    from 1 rad per step the leading term no longer bounds them and the thin axis is lost.

    Examples
    --------
    >>> principal_rotation_angle((1.0, 1.0, 1e-6), (1.0, 0.5, 0.3), 0.01, 1000).exceeded
    True
    """
    momentum = _momentum(inertia, w)
    y = h * momentum / min(float(i) for i in inertia)
    return StepLimit(
        "h·|L|/I_min",
        y,
        1.0,
        f"a sub-flow may turn L by up to {y:.3g} rad per step, past the splitting's error "
        "expansion: the thinnest axis' rate is lost (use split_sym or a Runge–Kutta method)",
    )


def symmetric_remainder_angle(inertia, w, h, nsteps) -> StepLimit:
    """split_sym's only approximation is its remainder rotation, h·L_r·(1/I_r − 1/I_p) about
    axis r, bounded by h|L|·|1/I_r − 1/I_p|: the same angle bound as the axis splittings.

    Examples
    --------
    >>> symmetric_remainder_angle((1.0, 1.0, 2.0), (0.0, 0.0, 1000.0), 1e-3, 1000).value
    0.0
    """
    from .splitting import symmetric_pair

    inertia = tuple(float(i) for i in inertia)
    _, p, r = symmetric_pair(inertia)
    momentum = _momentum(inertia, w)
    y = h * momentum * abs(1.0 / inertia[r] - 1.0 / inertia[p])
    return StepLimit(
        "h·|L|·|1/I_r − 1/I_p|",
        y,
        1.0,
        f"the remainder rotation may turn L by up to {y:.3g} rad per step, past the "
        "Strang composition's error expansion",
    )
