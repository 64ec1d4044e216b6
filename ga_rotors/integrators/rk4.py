"""Classical RK4 on (orientation, ω): the paper's method, with and without renormalising.

One step of size h, for ẏ = f(t, y) with y = (x, ω), x the path's orientation state::

    k1 = f(t, y), k2 = f(t + h/2, y + h/2 k1), k3 = f(t + h/2, y + h/2 k2),
    k4 = f(t + h, y + h k3),  y ← y + h/6 (k1 + 2k2 + 2k3 + k4)

Order 4; it conserves nothing exactly: the norm of q or R, the energy and |L| drift by
O(h⁴) per unit time (the tests measure the constants by step halving). ``rk4_renorm``
projects q or R back to unit norm after each step, which makes the norm exact and leaves
the order at 4 (the projection moves the state by O(h⁵), the size of the step's error).

Step limit (warn): on the linearised wobble ẏ = iνy a step multiplies y by R(ihν),
R(z) = 1 + z + z²/2 + z³/6 + z⁴/24, and |R(iy)|² = 1 − y⁶/72 + y⁸/576 < 1 for 0 < y < 2√2:
the wobble's energy decays (and for ``rk4`` |q|, whose rate is |ω|/2) with no sign of it in
the state. A run warns once N·|ln |R(ihν)|²| ≥ 1, the energy changed by a factor e
(:func:`ga_rotors.integrators.limits.wobble_damping`).
"""

from __future__ import annotations

from .base import FREE, KINEMATIC, MOTION, TORQUED, register
from .limits import wobble_damping
from .slots import accel, o_axpy, o_normalize, o_rate, o_rk4, omega, r_axpy, r_rk4
from .template import TemplateIntegrator

# The step templates below are not in __all__: they are source the code generator
# specialises (ga_rotors.integrators._source), not functions to call; the public entry
# is the registered integrator, run through Integrator.run.
__all__ = ["RK4", "RK4_RENORM"]


def rk4_step(t, x, w, h, inertia, params):
    """One RK4 step of the dynamics (ẇ from ``accel``, ẋ from the path's kinematics),
    on any problem kind's state layout (the rate's arithmetic is the kind's)."""
    half = 0.5 * h
    k1x = o_rate(x, w)
    k1w = accel(t, x, w, inertia, params)
    x2 = o_axpy(x, half, k1x)
    w2 = r_axpy(w, half, k1w)
    k2x = o_rate(x2, w2)
    k2w = accel(t + half, x2, w2, inertia, params)
    x3 = o_axpy(x, half, k2x)
    w3 = r_axpy(w, half, k2w)
    k3x = o_rate(x3, w3)
    k3w = accel(t + half, x3, w3, inertia, params)
    x4 = o_axpy(x, h, k3x)
    w4 = r_axpy(w, h, k3w)
    k4x = o_rate(x4, w4)
    k4w = accel(t + h, x4, w4, inertia, params)
    return o_rk4(x, h, k1x, k2x, k3x, k4x), r_rk4(w, h, k1w, k2w, k3w, k4w)


def rk4_renorm_step(t, x, w, h, inertia, params):
    """RK4, then back onto the unit sphere."""
    x, w = rk4_step(t, x, w, h, inertia, params)
    return o_normalize(x), w


def rk4_kinematic_step(t, x, h, params):
    """One RK4 step of ẋ = kinematics(x, ω(t)) for a prescribed ω(t)."""
    half = 0.5 * h
    wm = omega(t + half, params)
    k1 = o_rate(x, omega(t, params))
    k2 = o_rate(o_axpy(x, half, k1), wm)
    k3 = o_rate(o_axpy(x, half, k2), wm)
    k4 = o_rate(o_axpy(x, h, k3), omega(t + h, params))
    return o_rk4(x, h, k1, k2, k3, k4)


def rk4_renorm_kinematic_step(t, x, h, params):
    """Kinematic RK4, then back onto the unit sphere."""
    return o_normalize(rk4_kinematic_step(t, x, h, params))


#: RK4's stability polynomial: any 4-stage explicit method of order 4 has R(z) = Σ_{k≤4} z^k/k!.
RK4_POLYNOMIAL = (1.0, 1.0, 1.0 / 2.0, 1.0 / 6.0, 1.0 / 24.0)

RK4 = register(
    TemplateIntegrator(
        name="rk4",
        order=4,
        description="classical Runge–Kutta 4 on (orientation, ω): the paper's method",
        conserves=frozenset(),
        paths=frozenset({"rotor", "quaternion", "euler", "motor"}),
        steps={
            FREE: rk4_step,
            TORQUED: rk4_step,
            KINEMATIC: rk4_kinematic_step,
            MOTION: rk4_step,
        },
        # |R(iy)|² = 1 − y⁶/72 + y⁸/576 < 1: the wobble and |q| (q̇ has rate |ω|/2) decay.
        step_limit=wobble_damping(RK4_POLYNOMIAL, steps_q=True),
        evaluations=4,
    )
)

RK4_RENORM = register(
    TemplateIntegrator(
        name="rk4_renorm",
        order=4,
        description="classical RK4, orientation renormalised to unit norm after each step",
        conserves=frozenset({"unit_norm"}),
        paths=frozenset({"rotor", "quaternion", "motor"}),
        steps={
            FREE: rk4_renorm_step,
            TORQUED: rk4_renorm_step,
            KINEMATIC: rk4_renorm_kinematic_step,
            MOTION: rk4_renorm_step,
        },
        helpers=(rk4_step, rk4_kinematic_step),
        # |q| is projected back each step: only the wobble of ω is damped by |R(ihν)|².
        step_limit=wobble_damping(RK4_POLYNOMIAL, steps_q=False, phase_on_q=True),
        evaluations=4,
    )
)
