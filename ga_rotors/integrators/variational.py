"""The discrete Moser–Veselov rigid body as a Lie group variational integrator (LGVI).

Lee, Leok & McClamroch (2005), in quaternions. Body momentum Π = I ω, J_d = ½ tr(I) 1 − I.
One step solves for the relative rotation F = (s, v) (a unit quaternion) in::

    h Π_k + ½ h² M_k = F J_d − J_d Fᵀ   ⇔   h Π_k + ½ h² M_k = 2 (s I v + v × I v)

(the right-hand form follows from F = (s² − |v|²) 1 + 2 v vᵀ + 2 s v̂ and the identities
x̂ J + J x̂ = ((tr J) 1 − J) x̂ and a bᵀ − b aᵀ = (b × a)̂), then::

    q_{k+1} = q_k ⊗ F,   Π_{k+1} = F* Π_k F + ½ h (F* M_k F + M_{k+1}),

with M the body torque (zero for the free body, which makes this the discrete Moser–Veselov
top). The equation for v is solved by Newton's method from v ≈ h ω / 2 to a relative
change of 1e-15 (3 or 4 iterations at the step sizes that matter).

Step limit: for a rotation about principal axis k the equation reads I_k sin θ = h I_k ω_k
(θ the step's rotation angle), so it has a solution only while h|ω_k| ≤ 1, and near 1 the
discrete rotation θ = asin(h ω_k) is far from the exact h ω_k. Past the limit Newton's
iterates leave the unit ball (a NaN) or stop converging; either way the step returns NaN,
so the loop ends and reports the run incomplete instead of returning a wrong rotation.

Order 2, symplectic, time-reversible; for the free body |Π| and the space-frame momentum
q Π q* are conserved exactly (Π only ever turns by F*·F, and q by ⊗F), up to the Newton
tolerance and rounding, and the energy error stays bounded.

Step limit (raise): h|ω| < 1, the step at which sin θ = h ω_k loses its solution about a
principal axis; a run starting past it is refused with an InputError (there is no
degraded answer to give: it would stop at its first step).
"""

from __future__ import annotations

import math
from math import sqrt

from .._kernels import cross, qconj, qmul, qrotate
from ._rigid import momenta, rates, solve3
from .base import FREE, ORIENTATION_TORQUES, TORQUED, register
from .limits import moser_veselov
from .slots import o_from_quat, o_quat, torque
from .template import TemplateIntegrator

# The step templates below are not in __all__: they are source the code generator
# specialises (ga_rotors.integrators._source), not functions to call; the public entry
# is the registered integrator, run through Integrator.run.
__all__ = ["LGVI", "NEWTON_STALLED", "RESIDUAL_ROUNDING"]

#: Newton's last correction (relative) below which 30 iterations are accepted: quadratic
#: convergence leaves only rounding once a correction is this small (the Jacobian's
#: conditioning near the step limit can hold the correction above the 1e-15 target).
NEWTON_STALLED = 1e-10

#: Residual, relative to the size of the equation's terms, at which a stalled Newton
#: iterate solves the equation to rounding (a few roundings per term, with margin).
RESIDUAL_ROUNDING = 64 * 2.220446049250313e-16


def discrete_rotation(g, inertia, guess):
    """Unit quaternion F = (s, v) with 2 (s I v + v × I v) = g, by Newton's method."""
    v = guess
    # indexed, not unpacked: a batched loop passes a body's moments followed by more
    # numbers (ga_rotors.ensemble); the first three are the moments either way
    i1, i2, i3 = inertia[0], inertia[1], inertia[2]
    best, best_v, best_scale = math.inf, v, 0.0
    for _ in range(30):
        s = sqrt(1.0 - (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]))
        jv = (i1 * v[0], i2 * v[1], i3 * v[2])
        c = cross(v, jv)
        r = (
            2.0 * (s * jv[0] + c[0]) - g[0],
            2.0 * (s * jv[1] + c[1]) - g[1],
            2.0 * (s * jv[2] + c[2]) - g[2],
        )
        resid = abs(r[0]) + abs(r[1]) + abs(r[2])
        if resid < best:
            best, best_v = resid, v
            best_scale = 0.0
            for k in range(3):
                best_scale += abs(g[k]) + 2.0 * (abs(s * jv[k]) + abs(c[k]))
        # d/dv: 2 [s I − (I v) vᵀ / s − (I v)̂ + v̂ I]
        a = (
            2.0 * (s * i1 - jv[0] * v[0] / s),
            2.0 * (-jv[0] * v[1] / s + jv[2] - v[2] * i2),
            2.0 * (-jv[0] * v[2] / s - jv[1] + v[1] * i3),
            2.0 * (-jv[1] * v[0] / s - jv[2] + v[2] * i1),
            2.0 * (s * i2 - jv[1] * v[1] / s),
            2.0 * (-jv[1] * v[2] / s + jv[0] - v[0] * i3),
            2.0 * (-jv[2] * v[0] / s + jv[1] - v[1] * i1),
            2.0 * (-jv[2] * v[1] / s - jv[0] + v[0] * i2),
            2.0 * (s * i3 - jv[2] * v[2] / s),
        )
        dv = solve3(a, r)
        v = (v[0] - dv[0], v[1] - dv[1], v[2] - dv[2])
        size = abs(v[0]) + abs(v[1]) + abs(v[2])
        change = abs(dv[0]) + abs(dv[1]) + abs(dv[2])
        if change <= 1e-15 * size or size == 0.0:
            break
    if not change <= NEWTON_STALLED * size:
        # On a rod-like body the Jacobian's condition number is ~I_max/I_min: the thin
        # axis' component of v is determined only to ~u·I_max/I_min relative, and Newton
        # ends cycling between iterates that far apart (1.3e-10 on (10, 10, 1e-7), 1.4e-6 on
        # (10, 10, 1e-10), found by tests/test_stability_fuzz.py). The iterate with the
        # smallest residual is accepted when it solves the equation to the rounding of its
        # terms (RESIDUAL_ROUNDING of their sizes).
        if not best <= RESIDUAL_ROUNDING * best_scale:
            # Past the step limit (module docstring) the equation has no solution: a NaN
            # ends the run, which the loop reports, instead of a wrong rotation.
            return (math.nan, math.nan, math.nan, math.nan)
        v = best_v
    s = sqrt(1.0 - (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]))
    return (s, v[0], v[1], v[2])


def lgvi_free_step(t, x, w, h, inertia, params):
    """Discrete Moser–Veselov step of the free body."""
    pi = momenta(w, inertia)
    f = discrete_rotation(
        (h * pi[0], h * pi[1], h * pi[2]), inertia, (0.5 * h * w[0], 0.5 * h * w[1], 0.5 * h * w[2])
    )
    p = qrotate(qconj(f), pi)
    return o_from_quat(qmul(o_quat(x), f)), (
        p[0] / inertia[0],
        p[1] / inertia[1],
        p[2] / inertia[2],
    )


def lgvi_torqued_step(t, x, w, h, inertia, params):
    """LGVI step with the body torque M(q) (orientation-dependent torques; M_{k+1} is
    evaluated at the ω before its own half kick, exact only when M does not read ω)."""
    q = o_quat(x)
    pi = momenta(w, inertia)
    m0 = torque(t, q, w, params)
    hh = 0.5 * h * h
    g = (h * pi[0] + hh * m0[0], h * pi[1] + hh * m0[1], h * pi[2] + hh * m0[2])
    f = discrete_rotation(g, inertia, (0.5 * h * w[0], 0.5 * h * w[1], 0.5 * h * w[2]))
    fc = qconj(f)
    q1 = qmul(q, f)
    p = qrotate(fc, pi)
    m0r = qrotate(fc, m0)
    m1 = torque(t + h, q1, rates(p, inertia), params)
    half = 0.5 * h
    p = (
        p[0] + half * (m0r[0] + m1[0]),
        p[1] + half * (m0r[1] + m1[1]),
        p[2] + half * (m0r[2] + m1[2]),
    )
    return o_from_quat(q1), rates(p, inertia)


LGVI = register(
    TemplateIntegrator(
        name="lgvi",
        order=2,
        description="Lie group variational integrator (discrete Moser–Veselov top)",
        conserves=frozenset(
            {"unit_norm", "momentum_norm", "space_momentum", "symplectic", "time_reversible"}
        ),
        paths=frozenset({"rotor", "quaternion"}),
        steps={FREE: lgvi_free_step, TORQUED: lgvi_torqued_step},
        helpers=(discrete_rotation,),
        torques=ORIENTATION_TORQUES,  # M(q): with M(ω) the explicit M_{k+1} makes it order 1
        step_limit=moser_veselov,
        step_limit_action="raise",  # no step exists past it: refuse rather than stop at t0
        evaluations=1,  # its Newton iterations for the step's rotation are not counted
    )
)
