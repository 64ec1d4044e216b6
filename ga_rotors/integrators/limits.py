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

Each limit here is *measured* by one compiled kernel, ``measure(inertia, w, h, nsteps,
*constants) -> (value, limit)``, attached to the limit function (:func:`measured`): the
generated loop module judges the limit with it inside the compiled call of a run
(:meth:`Integrator.run`'s verdict and :func:`watch_candidates`'s samples cost no Python),
and the limit function builds its :class:`StepLimit` (the words) from the same numbers,
so a run and its message can never disagree. A limit without a ``measure`` (a user's plain
Python function) is judged in Python before the run.
"""

from __future__ import annotations

import cmath
import math
from collections.abc import Callable, Sequence
from typing import NamedTuple

import numpy as np

from .._jit import jit
from ..errors import InputError
from ._rigid import symmetric_pair

__all__ = [
    "PHASE_LIMIT",
    "WATCH_GROWTH",
    "StepLimit",
    "fixed_point_sweep",
    "measured",
    "moser_veselov",
    "principal_rotation_angle",
    "stability_polynomial",
    "symmetric_remainder_angle",
    "watch_candidates",
    "wobble_damping",
]


class StepLimit(NamedTuple):
    """A step limit evaluated on one problem: ``value`` must stay below ``limit``.

    ``explain()`` says what happens at this value (the warning's text, :attr:`effect`): a
    function, so the text is built only when a run is past the limit and warns, not on
    every run (it would cost more than the check itself).

    Examples
    --------
    >>> lim = StepLimit("h·ν", 2.5, 2.0, lambda: "the sweep diverges")
    >>> lim.exceeded, lim.effect
    (True, 'the sweep diverges')
    """

    quantity: str
    value: float
    limit: float
    explain: Callable[[], str]

    @property
    def effect(self) -> str:
        """What happens at this value, in words."""
        return self.explain()

    @property
    def exceeded(self) -> bool:
        """Whether ``value`` is at or past ``limit`` (NaN counts as past)."""
        return not self.value < self.limit


def measured(measure, constants: tuple = ()):
    """Attach the compiled ``measure`` (and its trailing ``constants``) to a step-limit
    function, so a generated loop can judge the limit itself (see the module's text).

    ``measure(inertia, w, h, nsteps, *constants)`` returns (value, limit), the numbers of
    the :class:`StepLimit` the function builds; it must be a compiled kernel defined at
    module level (the generated module imports it), ``constants`` numbers, booleans or
    tuples of numbers (written into the generated module as literals).

    Examples
    --------
    >>> moser_veselov.measure.__name__, moser_veselov.constants
    ('_speed_measure', ())
    >>> rk4_limit = wobble_damping((1.0, 1.0, 0.5), steps_q=True)
    >>> rk4_limit.constants
    ((1.0, 1.0, 0.5), True, True)
    """

    def attach(limit):
        limit.measure, limit.constants = measure, tuple(constants)
        return limit

    return attach


@jit
def linear_rate(inertia, w, steps_q=False):
    """ν: the spectral radius of ∂ω̇/∂ω for I ω̇ = (I ω) × ω at ``w``; with ``steps_q``
    at least |ω|/2, the rate of q̇ = ½ q ⊗ ω.

    In closed form: with k₁ = (I₂ − I₃)/I₁ and cyclically, the Jacobian is
    [[0, k₁ω₃, k₁ω₂], [k₂ω₃, 0, k₂ω₁], [k₃ω₂, k₃ω₁, 0]], traceless, so its eigenvalues are
    the roots of λ³ + pλ + q with p = −(k₁k₂ω₃² + k₃k₁ω₂² + k₂k₃ω₁²), q = −2k₁k₂k₃ω₁ω₂ω₃
    (:func:`largest_root`), compiled: a 3×3 eigenvalue solve cost 20 µs per run.

    Examples
    --------
    The flat disk (1, 1, 2) spinning at 1000 rad/s about its axis wobbles at
    (I₃ − I₁)/I₁ · ω₃ = 1000 rad/s:

    >>> round(linear_rate((1.0, 1.0, 2.0), (0.0, 0.0, 1000.0)), 9)
    1000.0
    >>> linear_rate((1.0, 1.0, 1.0), (0.0, 0.0, 3.0), True)
    1.5
    """
    i1, i2, i3 = float(inertia[0]), float(inertia[1]), float(inertia[2])
    w1, w2, w3 = float(w[0]), float(w[1]), float(w[2])
    k1, k2, k3 = (i2 - i3) / i1, (i3 - i1) / i2, (i1 - i2) / i3
    p = -(k1 * k2 * w3 * w3 + k3 * k1 * w2 * w2 + k2 * k3 * w1 * w1)
    q = -2.0 * k1 * k2 * k3 * w1 * w2 * w3
    nu = largest_root(p, q)
    if steps_q:
        return max(nu, 0.5 * math.hypot(math.hypot(w1, w2), w3))
    return nu


@jit
def largest_root(p, q):
    """The largest |λ| among the roots of λ³ + pλ + q (real p, q).

    Three real roots (discriminant −4p³ − 27q² > 0): the trigonometric form. Otherwise one
    real root r (Cardano) and the quadratic λ² + rλ + (p + r²) left after dividing it out,
    whose complex pair has |λ|² = p + r².

    Examples
    --------
    λ³ − 7λ + 6 = (λ − 1)(λ − 2)(λ + 3); λ³ + λ = λ(λ² + 1):

    >>> round(largest_root(-7.0, 6.0), 12), round(largest_root(1.0, 0.0), 12)
    (3.0, 1.0)
    """
    if p == 0.0 and q == 0.0:
        return 0.0
    if p < 0.0 and -4.0 * p * p * p - 27.0 * q * q > 0.0:
        m = 2.0 * math.sqrt(-p / 3.0)
        arg = max(-1.0, min(1.0, 3.0 * q / (p * m)))
        theta = math.acos(arg) / 3.0
        best = 0.0
        for k in range(3):
            best = max(best, abs(m * math.cos(theta - 2.0 * math.pi * k / 3.0)))
        return best
    d = math.sqrt(max(0.0, 0.25 * q * q + p * p * p / 27.0))
    r = np.cbrt(-0.5 * q + d) + np.cbrt(-0.5 * q - d)
    disc = -3.0 * r * r - 4.0 * p
    if disc < 0.0:
        pair = math.sqrt(max(0.0, p + r * r))
    else:
        pair = 0.5 * (abs(r) + math.sqrt(disc))
    return max(abs(r), pair)


def stability_polynomial(a, b) -> tuple[float, ...]:
    """Coefficients c_k of R(z) = Σ c_k z^k = 1 + z bᵀ(I − zA)⁻¹𝟙 for an explicit tableau
    (A strictly lower triangular, so the series ends at z^s).

    Examples
    --------
    >>> a = ((0, 0, 0, 0), (0.5, 0, 0, 0), (0, 0.5, 0, 0), (0, 0, 1, 0))
    >>> [round(c, 15) for c in stability_polynomial(a, (1 / 6, 1 / 3, 1 / 3, 1 / 6))]
    [1.0, 1.0, 0.5, 0.166666666666667, 0.041666666666667]
    """

    b = np.asarray(b, dtype=float)
    a = np.asarray(a, dtype=float).reshape(len(b), len(b))  # also a flat, row-major A
    coeffs, v = [1.0], np.ones(len(b))
    for _ in range(len(b)):
        coeffs.append(float(b @ v))
        v = a @ v
    return tuple(coeffs)


@jit
def _at_iy(coeffs, y):
    """R(iy) = Σ c_k (iy)^k, by Horner's rule."""
    z = 1j * y
    r = 0j
    for k in range(len(coeffs) - 1, -1, -1):
        r = r * z + coeffs[k]
    return r


@jit
def _ln_gain(coeffs, y):
    """ln |R(iy)|²."""
    r = abs(_at_iy(coeffs, y))
    return math.log(r * r) if r != 0.0 else -math.inf


@jit
def _wobble(coeffs, inertia, w, h, nsteps, steps_q, on_q):
    """(hν, ln |R(ihν)|², y = h|ω|/2, lag) of :func:`wobble_damping`, compiled."""
    y = h * linear_rate(inertia, w, steps_q)
    gain = _ln_gain(coeffs, y)
    turn = 0.5 * h * math.hypot(math.hypot(float(w[0]), float(w[1])), float(w[2]))
    lag = 0.0
    if on_q:
        r = _at_iy(coeffs, turn)
        per_step = abs(cmath.phase(r * cmath.exp(-1j * turn))) if r != 0 else math.pi
        lag = 2.0 * nsteps * per_step
    return y, gain, turn, lag


#: Orientation error (rad) from the phase of a Runge–Kutta step on q alone, over the whole
#: run, past which the run warns: 0.1 rad (6°) is an error nobody would accept unannounced,
#: and still far above what a step that resolves the rotation gives (the paper's scene:
#: 5e-9 rad).
PHASE_LIMIT = 0.1


@jit
def _wobble_measure(inertia, w, h, nsteps, coeffs, steps_q, on_q):
    """(value, limit) of :func:`wobble_damping`: the damping's N·|ln |R(ihν)|²| against 1,
    or, where it is further past (or nearer to) its bound, the phase lag against
    :data:`PHASE_LIMIT`."""
    _, gain, _, lag = _wobble(coeffs, inertia, w, h, nsteps, steps_q, on_q)
    damping = abs(nsteps * gain)
    if not on_q or damping / 1.0 >= lag / PHASE_LIMIT:
        return damping, 1.0
    return lag, PHASE_LIMIT


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

    coeffs = tuple(float(c) for c in coeffs)
    on_q = bool(steps_q if phase_on_q is None else phase_on_q)
    steps_q = bool(steps_q)

    @measured(_wobble_measure, (coeffs, steps_q, on_q))
    def limit(inertia, w, h, nsteps) -> StepLimit:
        inertia, w, h, nsteps = _floats(inertia, "inertia"), _floats(w, "w"), float(h), int(nsteps)
        value, bound = _wobble_measure(inertia, w, h, nsteps, coeffs, steps_q, on_q)
        if bound == 1.0:

            def damping_effect():
                y, ln_gain, _, _ = _wobble(coeffs, inertia, w, h, nsteps, steps_q, on_q)
                total = nsteps * ln_gain
                amplitude = math.exp(0.5 * total) if total < 1400 else math.inf
                return (
                    f"at hν = {y:.3g} each step scales the wobble's energy by |R(ihν)|² = "
                    f"{math.exp(ln_gain):.6g}, so over {nsteps} steps its amplitude (‖ω⊥‖ "
                    f"about a principal axis{', and |q|' if steps_q else ''}) is "
                    + (f"damped × {amplitude:.3g}" if total < 0 else f"amplified × {amplitude:.3g}")
                )

            return StepLimit("N·|ln|R(ihν)|²|", value, bound, damping_effect)

        def phase_effect():
            turn = _wobble(coeffs, inertia, w, h, nsteps, steps_q, on_q)[2]
            return (
                f"each step turns the body by 2·arg R(iy) instead of h|ω| = {2 * turn:.3g} "
                f"rad, so over {nsteps} steps its orientation lags its spin by {value:.3g} rad"
            )

        return StepLimit("2N·|arg R(iy)e^(−iy)|", value, bound, phase_effect)

    return limit


def _floats(v, name: str) -> np.ndarray:
    """``v`` as a float64 array of three numbers (one compiled signature for tuples, lists
    and arrays; a compiled kernel must never read past the end of a shorter one)."""
    if type(v) is not np.ndarray or v.dtype != np.float64:
        v = np.asarray(v, dtype=np.float64)
    if v.shape != (3,):
        raise InputError(f"expected 3 numbers, got shape {v.shape}", key=name)
    return v


@jit
def _sweep_measure(inertia, w, h, nsteps):
    """(h·ν, 2) of :func:`fixed_point_sweep`."""
    return h * linear_rate(inertia, w, True), 2.0


@measured(_sweep_measure)
def fixed_point_sweep(inertia, w, h, nsteps) -> StepLimit:
    """Implicit midpoint by fixed-point sweeps: the sweep's map has derivative (h/2)·∂f,
    whose spectral radius is hν/2 (ν with |ω|/2: the sweep also solves for q), so it
    contracts only while hν < 2.

    Examples
    --------
    >>> fixed_point_sweep((1.0, 1.0, 1.0), (0.0, 0.0, 3.0), 1.0, 10).value
    1.5
    """
    y, bound = _sweep_measure(_floats(inertia, "inertia"), _floats(w, "w"), float(h), int(nsteps))
    return StepLimit(
        "h·ν",
        y,
        bound,
        lambda: (
            f"the fixed-point sweep contracts by hν/2 = {y / 2:.3g} per sweep; from 1 it "
            "diverges and the run stops (NaN), just below it it needs many sweeps"
        ),
    )


@jit
def _speed_measure(inertia, w, h, nsteps):
    """(h·|ω|, 1) of :func:`moser_veselov`; |ω| without overflow or underflow."""
    return h * math.hypot(math.hypot(w[0], w[1]), w[2]), 1.0


@measured(_speed_measure)
def moser_veselov(inertia, w, h, nsteps) -> StepLimit:
    """lgvi solves h Π = sin θ ⋯ for the step's rotation: about a principal axis (and on
    a sphere) it reads sin θ = h|ω|, with no solution from h|ω| = 1.

    Examples
    --------
    >>> moser_veselov((1.0, 2.0, 3.0), (0.0, 0.0, 2.0), 0.5, 1).exceeded
    True
    """
    y, bound = _speed_measure(_floats(inertia, "inertia"), _floats(w, "w"), float(h), int(nsteps))
    return StepLimit(
        "h·|ω|",
        y,
        bound,
        lambda: (
            "its discrete Moser–Veselov equation, sin θ = h|ω| about a principal axis, "
            "has no solution there"
        ),
    )


@jit
def _momentum(inertia, w):
    """|L| = |I ω| (principal frame), without overflow or underflow."""
    return math.hypot(math.hypot(inertia[0] * w[0], inertia[1] * w[1]), inertia[2] * w[2])


@jit
def _principal_measure(inertia, w, h, nsteps):
    """(h·|L|/I_min, 1) of :func:`principal_rotation_angle`."""
    return h * _momentum(inertia, w) / min(inertia[0], min(inertia[1], inertia[2])), 1.0


@measured(_principal_measure)
def principal_rotation_angle(inertia, w, h, nsteps) -> StepLimit:
    """An axis splitting turns L about axis i by h·L_i/I_i ≤ h|L|/I_min per sub-flow; its
    error terms are nested commutators of those turns, powers of that angle times |L|/I_i:
    from 1 rad per step the leading term no longer bounds them and the thin axis is lost.

    Examples
    --------
    >>> principal_rotation_angle((1.0, 1.0, 1e-6), (1.0, 0.5, 0.3), 0.01, 1000).exceeded
    True
    """
    y, bound = _principal_measure(
        _floats(inertia, "inertia"), _floats(w, "w"), float(h), int(nsteps)
    )
    return StepLimit(
        "h·|L|/I_min",
        y,
        bound,
        lambda: (
            f"a sub-flow may turn L by up to {y:.3g} rad per step, past the splitting's "
            "error expansion: the thinnest axis' rate is lost (use split_sym or a Runge–Kutta "
            "method)"
        ),
    )


@jit
def _remainder_measure(inertia, w, h, nsteps):
    """(h·|L|·|1/I_r − 1/I_p|, 1) of :func:`symmetric_remainder_angle`."""
    _, p, r = symmetric_pair(inertia)
    return h * _momentum(inertia, w) * abs(1.0 / inertia[r] - 1.0 / inertia[p]), 1.0


@measured(_remainder_measure)
def symmetric_remainder_angle(inertia, w, h, nsteps) -> StepLimit:
    """split_sym's only approximation is its remainder rotation, h·L_r·(1/I_r − 1/I_p) about
    axis r, bounded by h|L|·|1/I_r − 1/I_p|: the same angle bound as the axis splittings.

    Examples
    --------
    >>> symmetric_remainder_angle((1.0, 1.0, 2.0), (0.0, 0.0, 1000.0), 1e-3, 1000).value
    0.0
    """
    y, bound = _remainder_measure(
        _floats(inertia, "inertia"), _floats(w, "w"), float(h), int(nsteps)
    )
    return StepLimit(
        "h·|L|·|1/I_r − 1/I_p|",
        y,
        bound,
        lambda: (
            f"the remainder rotation may turn L by up to {y:.3g} rad per step, past the "
            "Strang composition's error expansion"
        ),
    )


#: After a run, the step limit is evaluated again at each sample where |ω| or |L| first
#: grows by this factor past every earlier sample's (:func:`watch_candidates`): the
#: crossing it reports is at most that much growth late, and a long run costs few checks.
WATCH_GROWTH = 1.001


@jit
def _watch_candidates(w, rows, inertia):
    """The sample indices :func:`watch_candidates` returns, for the first ``rows`` rows."""
    marked = np.zeros(rows, dtype=np.bool_)
    scale = 0.5 / math.log(WATCH_GROWTH)
    for moment in (False, True):
        high = -1.0
        level = -math.inf
        for i in range(rows):
            a, b, c = w[i, 0], w[i, 1], w[i, 2]
            if moment:
                a, b, c = a * inertia[0], b * inertia[1], c * inertia[2]
            size = a * a + b * b + c * c
            if i > 0 and not size > high:
                if size != size:  # NaN: no later sample sets a high (as a running max)
                    high = math.nan
                continue
            high = size
            new = np.floor(math.log(size) * scale) if size > 0.0 else -math.inf
            if (new > level) if i > 0 else math.isfinite(new):
                marked[i] = True
            level = new
    return np.flatnonzero(marked)


def watch_candidates(w, inertia) -> np.ndarray:
    """The samples at which a run's step limit is judged again after the run: those where
    |ω|² or |L|² (``w`` the samples' body ω, principal frame) sets a new high that passes
    every earlier high's level by a factor :data:`WATCH_GROWTH` in |ω| or |L| (the
    quantities of the step limits grow with them), the first sample included. Compiled:
    the generated loop of a run calls the same kernel on its samples.

    Examples
    --------
    |ω| grows by 10 % from sample 2 on; sample 1 repeats sample 0, sample 3 only 0.01 %:

    >>> w = np.array([[0, 0, 1.0], [0, 0, 1.0], [0, 0, 1.1], [0, 0, 1.1001]])
    >>> watch_candidates(w, (1.0, 2.0, 3.0)).tolist()
    [0, 2]
    """
    w = np.ascontiguousarray(w, dtype=np.float64).reshape(-1, 3)
    return _watch_candidates(w, w.shape[0], _floats(inertia, "inertia"))
