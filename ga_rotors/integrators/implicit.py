"""Implicit midpoint on (orientation, ω): y₁ = y₀ + h f((y₀ + y₁)/2).

Solved for the slope k = f(y₀ + h/2 k) by fixed-point iteration until k stops changing
(to 2 ulps of its size; contraction factor ≈ h |∂f/∂y|/2, so 6–10 sweeps at the step sizes
of the accuracy study; at most 60). The iteration contracts only while h·|ω| stays below
about 4 (the kinematics alone contribute h|ω|/4); a step whose slope still changes by more
than :data:`STALLED` after 60 sweeps returns NaN, so the loop stops and reports it
(``complete`` False) rather than return an unconverged state. Order 2, time-reversible.
It preserves every quadratic invariant exactly (Cooper 1987): |q|² and |R|² of the
kinematics, and for the free body the energy ½ ωᵀIω and |L|² = |Iω|², up to the
iteration's tolerance and rounding.

Step limit (warn): the sweep's map has derivative (h/2)·∂f(ω, q), spectral radius hν/2
with ν the larger of the wobble's rate and |ω|/2; it contracts only while hν < 2
(:func:`ga_rotors.integrators.limits.fixed_point_sweep`).
"""

from __future__ import annotations

import math

from ._arith import axpy3
from .base import FREE, TORQUED, register
from .limits import fixed_point_sweep
from .slots import accel, o_axpy, o_rate
from .template import TemplateIntegrator

# The step templates below are not in __all__: they are source the code generator
# specialises (ga_rotors.integrators._source), not functions to call; the public entry
# is the registered integrator, run through Integrator.run.
__all__ = ["MIDPOINT", "STALLED"]

#: Relative change of the slope below which a sweep that ran out of iterations is accepted:
#: rounding in f (a few ulps, amplified by 1/(1 − contraction)) can keep the change above
#: the 2-ulp target without the iteration being wrong; 64 ulps is the floor of that noise.
STALLED = 64 * 2.220446049250313e-16


def midpoint_step(t, x, w, h, inertia, params):
    """Implicit midpoint by fixed-point iteration on the slope."""
    half = 0.5 * h
    kx = o_rate(x, w)
    kw = accel(t, x, w, inertia, params)
    for _ in range(60):
        xm = o_axpy(x, half, kx)
        wm = axpy3(w, half, kw)
        nx = o_rate(xm, wm)
        nw = accel(t + half, xm, wm, inertia, params)
        change = 0.0
        size = 0.0
        for j in range(len(nx)):
            change = max(change, abs(nx[j] - kx[j]))
            size = max(size, abs(nx[j]))
        for j in range(3):
            change = max(change, abs(nw[j] - kw[j]))
            size = max(size, abs(nw[j]))
        kx, kw = nx, nw
        if change <= 4.4e-16 * size:
            break
    if not change <= STALLED * size:
        # Diverging or still far from the fixed point (h·|ω| ≳ 3): a NaN ends the run,
        # which the loop reports, instead of an unconverged step passed off as midpoint.
        kx = o_axpy(kx, math.nan, kx)
        kw = axpy3(kw, math.nan, kw)
    return o_axpy(x, h, kx), axpy3(w, h, kw)


MIDPOINT = register(
    TemplateIntegrator(
        name="midpoint",
        order=2,
        description="implicit midpoint rule (fixed-point iteration)",
        conserves=frozenset({"unit_norm", "energy", "momentum_norm", "time_reversible"}),
        paths=frozenset({"rotor", "quaternion"}),
        steps={FREE: midpoint_step, TORQUED: midpoint_step},
        step_limit=fixed_point_sweep,
        evaluations=1,  # its fixed-point sweeps are not counted
    )
)
