"""Lie-group integrators: the orientation moves only by exponentials, so it stays on the unit
sphere to rounding (Hairer, Lubich & Wanner IV.8; Iserles, Munthe-Kaas, Nørsett & Zanna 2000).

Kinematics q̇ = ½ q ⊗ (0, ω) (body rate, right action): a constant ω for a time h moves q to
q ⊗ Exp(h ω), Exp the unit quaternion of a rotation vector. Each method below is the
textbook left-action method mirrored for the right action (write p = q⁻¹, ṗ = −½ (0, ω) ⊗ p:
exponents keep their coefficients, products reverse their order). ω lives in a vector
space, where every method reduces to its underlying Runge–Kutta tableau.

* ``lie_euler``  — q ⊗ Exp(h ω), ω + h ω̇. Order 1.
* ``rkmk4``     — Runge–Kutta–Munthe-Kaas with the classical RK4 tableau in the algebra,
  u̇ = dexp⁻¹₋ᵤ(ω) = ω + ½ u × ω + (1/12) u × (u × ω) truncated after the terms order 4
  needs (Munthe-Kaas, BIT 38 (1998) 92). Order 4.
* ``cf4``       — commutator-free order 4 (Celledoni, Marthinsen & Owren 2003): RK4's
  stages, q₄ = q₂ ⊗ Exp(h/2 (2ω₃ − ω₁)), and the update as two exponentials,
  q ⊗ Exp(h/12 (3ω₁ + 2ω₂ + 2ω₃ − ω₄)) ⊗ Exp(h/12 (−ω₁ + 2ω₂ + 2ω₃ + 3ω₄)), no commutators.
  Order 4 (the other order of the two factors is only order 2: the observed-order test
  tells them apart).
* ``cg3``       — Crouch–Grossman order 3 (Crouch & Grossman 1993, the 3-stage method with
  c = (0, 3/4, 17/24)). Order 3.
* ``magnus4``   — fourth-order Magnus for a prescribed ω(t): two Gauss points and one
  commutator, Ω = h/2 (ω₁ + ω₂) + (√3/12) h² ω₁ × ω₂. Order 4 (kinematic problems).

A body moving through space (the ``motion`` kind) runs ``cf4`` in the group of its path:
each stage and the update move the pose by the path's exact flow of frozen rates
(``o_flow``), the motor exponential M exp(h B/2) on the motor path (SE(3), rotation and
translation screwed together), q ⊗ Exp(hω) beside c + h v_c on the quaternion path
(SO(3) × R³); the rates (ω, v) step by RK4's tableau as ω does.

Step limits (warn): q moves by exact exponentials, but ω is stepped by a Runge–Kutta
formula whose stability polynomial R scales the linearised wobble by |R(ihν)|² per step:
1 + (hν)² for Lie–Euler (its energy grows: at hν = 1 it doubles every step), Taylor to z⁴
for RKMK4 and CF4, and CG3's tableau (Taylor to z³) for CG3. A run warns once
N·|ln |R(ihν)|²| ≥ 1 (:func:`ga_rotors.integrators.limits.wobble_damping`).
"""

from __future__ import annotations

from .._kernels import cross
from ._arith import axpy3, rk4_sum3
from ._rigid import turn
from .base import FREE, KINEMATIC, MOTION, TORQUED, register
from .limits import stability_polynomial, wobble_damping
from .slots import accel, o_flow, o_from_quat, o_quat, omega, r_axpy, r_load, r_rk4
from .template import TemplateIntegrator

# The step templates below are not in __all__: they are source the code generator
# specialises (ga_rotors.integrators._source), not functions to call; the public entry
# is the registered integrator, run through Integrator.run.
__all__ = [
    "CF4",
    "CG3",
    "CG3_A21",
    "CG3_A31",
    "CG3_A32",
    "CG3_B",
    "LIE_EULER",
    "MAGNUS4",
    "MAGNUS_C1",
    "MAGNUS_C2",
    "MAGNUS_K",
    "RKMK4",
]

# Crouch–Grossman 3 (Crouch & Grossman, J. Nonlinear Sci. 3 (1993) 1).
CG3_A21 = 0.75
CG3_A31 = 119.0 / 216.0
CG3_A32 = 17.0 / 108.0
CG3_B = (13.0 / 51.0, -2.0 / 3.0, 24.0 / 17.0)
# Two-point Gauss–Legendre nodes and the Magnus commutator weight.
MAGNUS_C1 = 0.5 - 3.0**0.5 / 6.0
MAGNUS_C2 = 0.5 + 3.0**0.5 / 6.0
MAGNUS_K = 3.0**0.5 / 12.0


def lie_euler_step(t, x, w, h, inertia, params):
    """q ⊗ Exp(h ω), ω + h ω̇."""
    dw = accel(t, x, w, inertia, params)
    return o_from_quat(turn(o_quat(x), h, w)), axpy3(w, h, dw)


def lie_euler_kinematic_step(t, x, h, params):
    """q ⊗ Exp(h ω(t))."""
    return o_from_quat(turn(o_quat(x), h, omega(t, params)))


def dexpinv(u, w):
    """dexp⁻¹₋ᵤ(ω) to the terms an order-4 method needs: ω + ½ u × ω + (1/12) u × (u × ω)."""
    c = cross(u, w)
    d = cross(u, c)
    k = 1.0 / 12.0
    return (
        w[0] + 0.5 * c[0] + k * d[0],
        w[1] + 0.5 * c[1] + k * d[1],
        w[2] + 0.5 * c[2] + k * d[2],
    )


def rkmk4_step(t, x, w, h, inertia, params):
    """RKMK with RK4's tableau: stages q ⊗ Exp(U_i), U_i = h Σ a_ij dexp⁻¹(U_j, ω_j)."""
    half = 0.5 * h
    q = o_quat(x)
    k1u = w
    k1w = accel(t, x, w, inertia, params)
    u2 = (half * k1u[0], half * k1u[1], half * k1u[2])
    w2 = axpy3(w, half, k1w)
    k2u = dexpinv(u2, w2)
    k2w = accel(t + half, o_from_quat(turn(q, 1.0, u2)), w2, inertia, params)
    u3 = (half * k2u[0], half * k2u[1], half * k2u[2])
    w3 = axpy3(w, half, k2w)
    k3u = dexpinv(u3, w3)
    k3w = accel(t + half, o_from_quat(turn(q, 1.0, u3)), w3, inertia, params)
    u4 = (h * k3u[0], h * k3u[1], h * k3u[2])
    w4 = axpy3(w, h, k3w)
    k4u = dexpinv(u4, w4)
    k4w = accel(t + h, o_from_quat(turn(q, 1.0, u4)), w4, inertia, params)
    c = h / 6.0
    u = (
        c * (k1u[0] + 2.0 * (k2u[0] + k3u[0]) + k4u[0]),
        c * (k1u[1] + 2.0 * (k2u[1] + k3u[1]) + k4u[1]),
        c * (k1u[2] + 2.0 * (k2u[2] + k3u[2]) + k4u[2]),
    )
    w_new = rk4_sum3(w, h, k1w, k2w, k3w, k4w)
    return o_from_quat(turn(q, 1.0, u)), w_new


def cf4_step(t, x, w, h, inertia, params):
    """Commutator-free 4 (CMO 2003), mirrored for the body-frame kinematics."""
    half = 0.5 * h
    q = o_quat(x)
    k1w = accel(t, x, w, inertia, params)
    q2 = turn(q, half, w)
    w2 = axpy3(w, half, k1w)
    k2w = accel(t + half, o_from_quat(q2), w2, inertia, params)
    q3 = turn(q, half, w2)
    w3 = axpy3(w, half, k2w)
    k3w = accel(t + half, o_from_quat(q3), w3, inertia, params)
    q4 = turn(q2, half, (2.0 * w3[0] - w[0], 2.0 * w3[1] - w[1], 2.0 * w3[2] - w[2]))
    w4 = axpy3(w, h, k3w)
    k4w = accel(t + h, o_from_quat(q4), w4, inertia, params)
    c = h / 12.0
    early = tuple_combo(3.0, 2.0, 2.0, -1.0, w, w2, w3, w4)
    late = tuple_combo(-1.0, 2.0, 2.0, 3.0, w, w2, w3, w4)
    q_new = turn(turn(q, c, early), c, late)
    w_new = rk4_sum3(w, h, k1w, k2w, k3w, k4w)
    return o_from_quat(q_new), w_new


def tuple_combo(a, b, c, d, v1, v2, v3, v4):
    """a v1 + b v2 + c v3 + d v4 for 3-tuples."""
    return (
        a * v1[0] + b * v2[0] + c * v3[0] + d * v4[0],
        a * v1[1] + b * v2[1] + c * v3[1] + d * v4[1],
        a * v1[2] + b * v2[2] + c * v3[2] + d * v4[2],
    )


#: The start of a weighted sum of rates (r_load reads as many entries as the rates have):
#: −0.0 + y = y exactly, so starting from it costs nothing.
NEG_ZERO = (-0.0,) * 8


def rate_combo(a, b, c, d, v1, v2, v3, v4):
    """a v1 + b v2 + c v3 + d v4 for rates of any size, summed in :func:`tuple_combo`'s
    order."""
    s = r_axpy(r_axpy(r_load(NEG_ZERO), a, v1), b, v2)
    return r_axpy(r_axpy(s, c, v3), d, v4)


def cf4_flow_step(t, x, w, h, inertia, params):
    """Commutator-free 4 on the path's own group: the stages of :func:`cf4_step`, each pose
    moved by the path's exact flow of the frozen rates (``o_flow``)."""
    half = 0.5 * h
    k1w = accel(t, x, w, inertia, params)
    x2 = o_flow(x, half, w)
    w2 = r_axpy(w, half, k1w)
    k2w = accel(t + half, x2, w2, inertia, params)
    x3 = o_flow(x, half, w2)
    w3 = r_axpy(w, half, k2w)
    k3w = accel(t + half, x3, w3, inertia, params)
    x4 = o_flow(x2, half, r_axpy(r_axpy(r_load(NEG_ZERO), 2.0, w3), -1.0, w))
    w4 = r_axpy(w, h, k3w)
    k4w = accel(t + h, x4, w4, inertia, params)
    c = h / 12.0
    early = rate_combo(3.0, 2.0, 2.0, -1.0, w, w2, w3, w4)
    late = rate_combo(-1.0, 2.0, 2.0, 3.0, w, w2, w3, w4)
    return o_flow(o_flow(x, c, early), c, late), r_rk4(w, h, k1w, k2w, k3w, k4w)


def cg3_step(t, x, w, h, inertia, params):
    """Crouch–Grossman 3: stages and update as products of exponentials of frozen rates."""
    q = o_quat(x)
    k1w = accel(t, x, w, inertia, params)
    q2 = turn(q, CG3_A21 * h, w)
    w2 = axpy3(w, CG3_A21 * h, k1w)
    k2w = accel(t + CG3_A21 * h, o_from_quat(q2), w2, inertia, params)
    q3 = turn(turn(q, CG3_A31 * h, w), CG3_A32 * h, w2)
    # Weighted sums of stage rates are formed first and added to ω once (one rounding of
    # ω per stage, as in dp8), each starting from −0.0, which the compiler drops exactly.
    w3 = axpy3(w, h, axpy3(axpy3((-0.0, -0.0, -0.0), CG3_A31, k1w), CG3_A32, k2w))
    k3w = accel(t + (CG3_A31 + CG3_A32) * h, o_from_quat(q3), w3, inertia, params)
    b1, b2, b3 = CG3_B
    q_new = turn(turn(turn(q, b1 * h, w), b2 * h, w2), b3 * h, w3)
    w_new = axpy3(w, h, axpy3(axpy3(axpy3((-0.0, -0.0, -0.0), b1, k1w), b2, k2w), b3, k3w))
    return o_from_quat(q_new), w_new


def magnus4_kinematic_step(t, x, h, params):
    """Fourth-order Magnus: q ⊗ Exp(h/2 (ω₁ + ω₂) + (√3/12) h² ω₁ × ω₂), Gauss nodes."""
    w1 = omega(t + MAGNUS_C1 * h, params)
    w2 = omega(t + MAGNUS_C2 * h, params)
    c = cross(w1, w2)
    k = MAGNUS_K * h * h
    half = 0.5 * h
    v = (
        half * (w1[0] + w2[0]) + k * c[0],
        half * (w1[1] + w2[1]) + k * c[1],
        half * (w1[2] + w2[2]) + k * c[2],
    )
    return o_from_quat(turn(o_quat(x), 1.0, v))


_SPHERE = frozenset({"rotor", "quaternion"})


#: The stability polynomials of the ω update (q moves by exact exponentials, so only the
#: wobble of ω is damped or amplified): Lie–Euler is explicit Euler, 1 + z; RKMK4 and CF4
#: reduce to 4-stage order-4 methods on a vector space (Taylor to z⁴); CG3 is 3-stage order 3.
LIE_EULER_POLYNOMIAL = (1.0, 1.0)
ORDER4_POLYNOMIAL = (1.0, 1.0, 1.0 / 2.0, 1.0 / 6.0, 1.0 / 24.0)
CG3_POLYNOMIAL = stability_polynomial(
    ((0.0, 0.0, 0.0), (CG3_A21, 0.0, 0.0), (CG3_A31, CG3_A32, 0.0)), CG3_B
)


def _lie(name, order, description, steps, helpers=(), polynomial=None, *, evaluations,
         paths=_SPHERE):  # fmt: skip
    """Register a Lie-group method: unit norm by construction, sphere paths (and for a
    moving body the motor path) only."""
    return register(
        TemplateIntegrator(
            name=name,
            order=order,
            description=description,
            conserves=frozenset({"unit_norm"}),
            paths=paths,
            steps=steps,
            helpers=helpers,
            step_limit=None if polynomial is None else wobble_damping(polynomial, steps_q=False),
            evaluations=evaluations,
        )
    )


LIE_EULER = _lie(
    "lie_euler",
    1,
    "Lie–Euler: q ⊗ Exp(hω), ω + hω̇",
    {FREE: lie_euler_step, TORQUED: lie_euler_step, KINEMATIC: lie_euler_kinematic_step},
    polynomial=LIE_EULER_POLYNOMIAL,
    evaluations=1,
)
RKMK4 = _lie(
    "rkmk4",
    4,
    "Runge–Kutta–Munthe-Kaas with RK4's tableau and a truncated dexp⁻¹",
    {FREE: rkmk4_step, TORQUED: rkmk4_step},
    (dexpinv,),
    polynomial=ORDER4_POLYNOMIAL,
    evaluations=4,
)
CF4 = _lie(
    "cf4",
    4,
    "commutator-free Lie group method of order 4 (Celledoni–Marthinsen–Owren)",
    {FREE: cf4_step, TORQUED: cf4_step, MOTION: cf4_flow_step},
    (tuple_combo, rate_combo),
    polynomial=ORDER4_POLYNOMIAL,
    evaluations=4,
    paths=_SPHERE | {"motor"},
)
CG3 = _lie(
    "cg3",
    3,
    "Crouch–Grossman order 3: products of exponentials of frozen rates",
    {FREE: cg3_step, TORQUED: cg3_step},
    polynomial=CG3_POLYNOMIAL,
    evaluations=3,
)
MAGNUS4 = _lie(
    "magnus4",
    4,
    "fourth-order Magnus expansion for a prescribed ω(t) (two Gauss points)",
    {KINEMATIC: magnus4_kinematic_step},
    evaluations=2,  # ω(t) at two Gauss points
)
