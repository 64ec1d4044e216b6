"""Splitting methods: the free body as a composition of exactly solvable rotations.

Free rigid body, H = Σ L_k² / (2 I_k) in body momenta L = I ω. Each term's flow is exact:
H_k turns the body about its axis k at the rate L_k / I_k, so q ← q ⊗ Exp(φ e_k) and the
body momentum turns the other way, L ← Exp(φ e_k)* L Exp(φ e_k), with φ = τ L_k / I_k
(McLachlan, PRL 71 (1993) 3043; Touma & Wisdom, AJ 107 (1994) 1189). Each sub-flow is the
exact flow of a Hamiltonian invariant under space rotations, so every composition keeps
|L|, the space-frame L and |q| to rounding, is symplectic (Lie–Poisson), and the symmetric
compositions are time-reversible; the energy error stays bounded, with no drift.

* ``split2``  — Strang: 1(h/2) 2(h/2) 3(h) 2(h/2) 1(h/2). Order 2.
* ``split4``  — Suzuki's fractal composition of five Strang steps (p, p, 1−4p, p, p),
  p = 1/(4 − 4^{1/3}). Order 4.
* ``split4_yoshida`` — Yoshida's triple jump (γ₁, γ₂, γ₁), γ₁ = 1/(2 − 2^{1/3}). Order 4.
* ``split6``  — Yoshida's 7-stage order-6 composition (solution A, Phys. Lett. A 150
  (1990) 262). Order 6.
* ``split_sym`` — symmetric top plus remainder (Celledoni, Fassò, Säfström & Zanna, SIAM
  J. Sci. Comput. 30 (2008) 2084): the two closest moments I_p, I_r form a symmetric top
  (I⊥ = I_p, axis k), solved exactly — q ← q ⊗ Exp(τ L/I_p) ⊗ Exp(τ ν e_k),
  ν = (1/I_k − 1/I_p) L_k — and the remainder (1/I_r − 1/I_p) L_r²/2 is a rotation about
  axis r: Strang rem(h/2) sym(h) rem(h/2). Order 2, with an error constant ∝ |I_r − I_p|.

Torqued problems (a torque that depends on orientation only, such as gravity on a heavy
top): kick–drift–kick, L += h/2 τ(q); free flow for h; L += h/2 τ(q), composed exactly
as above for orders 4 and 6. The kick is the exact flow of the potential, so the same
properties hold, except the space-frame L, which the torque changes. A torque that reads ω
(damping) makes the kick inexact and the composition first order (measured: log₂ error
ratios 1.0 for every splitting under isotropic damping), so these methods declare
``torques = ORIENTATION_TORQUES`` and refuse such a torque unless the problem accepts
the lower order.

A body moving through space (the ``motion`` kind): its centre of mass drifts on a straight
line, exactly, while the body turns about it by the free-rotation composition; a force
and a torque of pose and time kick v_c += h F/m and L += h τ. So ``split2``, ``split4``,
``split4_yoshida`` and ``split6`` carry the centre of mass on the exact line of free
flight and on the exact parabola of uniform gravity (the kick of a constant force is its
exact flow), with the rotation's accuracy being the splitting's. Both motion paths run it
through their centre of mass (``o_centre``, ``o_from_centre``).

Step limits (warn): a sub-flow turns L about axis i by h·L_i/I_i ≤ h|L|/I_min, and the
compositions' error terms are nested commutators of these turns; from 1 rad per step the
leading term no longer bounds them, and the thin axis (whose rate is L_i/I_min) is lost.
The axis splittings warn from h|L|/I_min = 1; ``split_sym``, whose only approximation is
its remainder rotation h·L_r(1/I_r − 1/I_p), from h|L|·|1/I_r − 1/I_p| = 1.
"""

from __future__ import annotations

from .._kernels import qmul_exp
from ._rigid import momenta, rates, rotate_about, symmetric_pair
from .base import FREE, MOTION, ORIENTATION_TORQUES, TORQUED, register
from .limits import principal_rotation_angle, symmetric_remainder_angle
from .slots import o_centre, o_from_centre, o_from_quat, o_normalize, o_quat, torque, wrench
from .template import TemplateIntegrator

# The step templates below are not in __all__: they are source the code generator
# specialises (ga_rotors.integrators._source), not functions to call; the public entry
# is the registered integrator, run through Integrator.run.
__all__ = [
    "SPLIT2",
    "SPLIT4",
    "SPLIT4_YOSHIDA",
    "SPLIT6",
    "SPLIT_SYM",
    "SUZUKI4",
    "YOSHIDA4",
    "YOSHIDA6",
]

SUZUKI4 = (
    1.0 / (4.0 - 4.0 ** (1.0 / 3.0)),
    1.0 / (4.0 - 4.0 ** (1.0 / 3.0)),
    1.0 - 4.0 / (4.0 - 4.0 ** (1.0 / 3.0)),
    1.0 / (4.0 - 4.0 ** (1.0 / 3.0)),
    1.0 / (4.0 - 4.0 ** (1.0 / 3.0)),
)
YOSHIDA4 = (
    1.0 / (2.0 - 2.0 ** (1.0 / 3.0)),
    -(2.0 ** (1.0 / 3.0)) / (2.0 - 2.0 ** (1.0 / 3.0)),
    1.0 / (2.0 - 2.0 ** (1.0 / 3.0)),
)
_W1, _W2, _W3 = -1.17767998417887, 0.235573213359357, 0.784513610477560
YOSHIDA6 = (_W3, _W2, _W1, 1.0 - 2.0 * (_W1 + _W2 + _W3), _W1, _W2, _W3)


def free_strang(q, L, h, inertia):
    """Strang splitting of the free body into axis rotations 1 2 3 2 1."""
    q, L = rotate_about(q, L, 0, 0.5 * h * L[0] / inertia[0])
    q, L = rotate_about(q, L, 1, 0.5 * h * L[1] / inertia[1])
    q, L = rotate_about(q, L, 2, h * L[2] / inertia[2])
    q, L = rotate_about(q, L, 1, 0.5 * h * L[1] / inertia[1])
    q, L = rotate_about(q, L, 0, 0.5 * h * L[0] / inertia[0])
    return q, L


def kick(t, q, L, h, inertia, params):
    """L += h τ(q): the exact flow of an orientation-dependent torque."""
    tau = torque(t, q, rates(L, inertia), params)
    return (L[0] + h * tau[0], L[1] + h * tau[1], L[2] + h * tau[2])


def kdk(t, q, L, h, inertia, params):
    """Kick–drift–kick: half kick, free Strang drift, half kick."""
    L = kick(t, q, L, 0.5 * h, inertia, params)
    q, L = free_strang(q, L, h, inertia)
    return q, kick(t + h, q, L, 0.5 * h, inertia, params)


def compose_free(q, L, h, inertia, weights):
    """Strang steps of sizes w·h for w in ``weights`` (a symmetric composition)."""
    for c in weights:
        q, L = free_strang(q, L, c * h, inertia)
    return q, L


def compose_kdk(t, q, L, h, inertia, params, weights):
    """Kick–drift–kick steps of sizes w·h for w in ``weights``, time advanced along."""
    for c in weights:
        q, L = kdk(t, q, L, c * h, inertia, params)
        t += c * h
    return q, L


def split2_step(t, x, w, h, inertia, params):
    q, L = free_strang(o_quat(x), momenta(w, inertia), h, inertia)
    return o_from_quat(q), rates(L, inertia)


def split4_step(t, x, w, h, inertia, params):
    q, L = compose_free(o_quat(x), momenta(w, inertia), h, inertia, SUZUKI4)
    return o_from_quat(q), rates(L, inertia)


def split4_yoshida_step(t, x, w, h, inertia, params):
    q, L = compose_free(o_quat(x), momenta(w, inertia), h, inertia, YOSHIDA4)
    return o_from_quat(q), rates(L, inertia)


def split6_step(t, x, w, h, inertia, params):
    q, L = compose_free(o_quat(x), momenta(w, inertia), h, inertia, YOSHIDA6)
    return o_from_quat(q), rates(L, inertia)


def kdk2_step(t, x, w, h, inertia, params):
    q, L = kdk(t, o_quat(x), momenta(w, inertia), h, inertia, params)
    return o_from_quat(q), rates(L, inertia)


def kdk4_step(t, x, w, h, inertia, params):
    q, L = compose_kdk(t, o_quat(x), momenta(w, inertia), h, inertia, params, SUZUKI4)
    return o_from_quat(q), rates(L, inertia)


def kdk4_yoshida_step(t, x, w, h, inertia, params):
    q, L = compose_kdk(t, o_quat(x), momenta(w, inertia), h, inertia, params, YOSHIDA4)
    return o_from_quat(q), rates(L, inertia)


def kdk6_step(t, x, w, h, inertia, params):
    q, L = compose_kdk(t, o_quat(x), momenta(w, inertia), h, inertia, params, YOSHIDA6)
    return o_from_quat(q), rates(L, inertia)


def flight_drift(q, c, L, v, h, inertia):
    """Free flight for a time h: the centre of mass on its straight line (exact), the body
    turned about it by the Strang splitting."""
    q, L = free_strang(q, L, h, inertia)
    return q, (c[0] + h * v[0], c[1] + h * v[1], c[2] + h * v[2]), L


def flight_kick(t, q, c, L, v, h, inertia, params):
    """L += h τ, v_c += h F/m: the exact flow of a wrench of pose and time."""
    f = wrench(t, q, c, rates(L, inertia), v, params)
    k = h / inertia[3]
    return (
        (L[0] + h * f[3], L[1] + h * f[4], L[2] + h * f[5]),
        (v[0] + k * f[0], v[1] + k * f[1], v[2] + k * f[2]),
    )


def flight_kdk(t, q, c, L, v, h, inertia, params):
    """Kick–drift–kick of a moving body."""
    L, v = flight_kick(t, q, c, L, v, 0.5 * h, inertia, params)
    q, c, L = flight_drift(q, c, L, v, h, inertia)
    L, v = flight_kick(t + h, q, c, L, v, 0.5 * h, inertia, params)
    return q, c, L, v


def compose_flight(t, q, c, L, v, h, inertia, params, weights):
    """Kick–drift–kick steps of sizes w·h for w in ``weights``, time advanced along."""
    for k in weights:
        q, c, L, v = flight_kdk(t, q, c, L, v, k * h, inertia, params)
        t += k * h
    return q, c, L, v


def _flight_step(t, x, w, h, inertia, params, weights):
    """A composition of kick–drift–kick steps, run on the centre of mass of either path
    (the pose normalised first: a motor's translation scales with its norm, and going to
    the centre of mass and back every step would repeat that scaling)."""
    q, c, om, v = o_centre(o_normalize(x), w, inertia)
    q, c, L, v = compose_flight(t, q, c, momenta(om, inertia), v, h, inertia, params, weights)
    return o_from_centre(q, c, rates(L, inertia), v, inertia)


STRANG = (1.0,)


def split2_motion_step(t, x, w, h, inertia, params):
    return _flight_step(t, x, w, h, inertia, params, STRANG)


def split4_motion_step(t, x, w, h, inertia, params):
    return _flight_step(t, x, w, h, inertia, params, SUZUKI4)


def split4_yoshida_motion_step(t, x, w, h, inertia, params):
    return _flight_step(t, x, w, h, inertia, params, YOSHIDA4)


def split6_motion_step(t, x, w, h, inertia, params):
    return _flight_step(t, x, w, h, inertia, params, YOSHIDA6)


def symmetric_flow(q, L, h, inertia, k, p):
    """Exact flow of |L|²/(2I_p) + (1/I_k − 1/I_p) L_k²/2 (a symmetric top) for a time h."""
    a = 1.0 / inertia[p]
    q = qmul_exp(q, (0.5 * h * a * L[0], 0.5 * h * a * L[1], 0.5 * h * a * L[2]))
    return rotate_about(q, L, k, h * (1.0 / inertia[k] - a) * L[k])


def split_sym_step(t, x, w, h, inertia, params):
    k, p, r = symmetric_pair(inertia)
    c = 1.0 / inertia[r] - 1.0 / inertia[p]
    q, L = o_quat(x), momenta(w, inertia)
    q, L = rotate_about(q, L, r, 0.5 * h * c * L[r])
    q, L = symmetric_flow(q, L, h, inertia, k, p)
    q, L = rotate_about(q, L, r, 0.5 * h * c * L[r])
    return o_from_quat(q), rates(L, inertia)


_SPHERE = frozenset({"rotor", "quaternion"})
_FREE_PROPS = frozenset(
    {"unit_norm", "momentum_norm", "space_momentum", "symplectic", "time_reversible"}
)
_HELPERS = (free_strang, kick, kdk, compose_free, compose_kdk, flight_drift, flight_kick,
            flight_kdk, compose_flight, _flight_step)  # fmt: skip


def _splitting(name, order, description, free_step, torqued_step=None, motion_step=None, *,
               evaluations):  # fmt: skip
    steps = {FREE: free_step}
    if torqued_step is not None:
        steps[TORQUED] = torqued_step
    if motion_step is not None:
        steps[MOTION] = motion_step
    return register(
        TemplateIntegrator(
            name=name,
            order=order,
            description=description,
            conserves=_FREE_PROPS,
            paths=_SPHERE | ({"motor"} if motion_step is not None else set()),
            steps=steps,
            helpers=_HELPERS,
            torques=ORIENTATION_TORQUES,
            step_limit=principal_rotation_angle,
            evaluations=evaluations,
        )
    )


SPLIT2 = _splitting(
    "split2",
    2,
    "Lie–Poisson Strang splitting into exact axis rotations (torqued: kick–drift–kick)",
    split2_step,
    kdk2_step,
    split2_motion_step,
    evaluations=1,
)
SPLIT4 = _splitting(
    "split4",
    4,
    "Suzuki's 5-stage composition of the Strang splitting",
    split4_step,
    kdk4_step,
    split4_motion_step,
    evaluations=5,
)
SPLIT4_YOSHIDA = _splitting(
    "split4_yoshida",
    4,
    "Yoshida's triple jump of the Strang splitting",
    split4_yoshida_step,
    kdk4_yoshida_step,
    split4_yoshida_motion_step,
    evaluations=3,
)
SPLIT6 = _splitting(
    "split6",
    6,
    "Yoshida's 7-stage order-6 composition of the Strang splitting",
    split6_step,
    kdk6_step,
    split6_motion_step,
    evaluations=7,
)
SPLIT_SYM = register(
    TemplateIntegrator(
        name="split_sym",
        order=2,
        description="exact symmetric top plus a remainder rotation, Strang-composed",
        conserves=_FREE_PROPS,
        paths=_SPHERE,
        steps={FREE: split_sym_step},
        helpers=(symmetric_flow,),
        torques=ORIENTATION_TORQUES,  # no torqued step yet; a kick would need this too
        step_limit=symmetric_remainder_angle,
        evaluations=1,
    )
)
