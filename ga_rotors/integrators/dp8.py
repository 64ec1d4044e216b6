"""Fixed-step Dormand–Prince 8: the order-8 solution of DOP853 as a compiled loop.

The same 12-stage tableau scipy's adaptive DOP853 uses (Hairer, Nørsett & Wanner, *Solving
ODEs I*, II.10; coefficients as in ``scipy.integrate._ivp.dop853_coefficients``, and
``tests/test_integrator_orders.py`` checks they are identical), without the error estimate:
a fixed step, compiled and specialised like every other method. Its use is the
high-accuracy end of the work-precision study: order 8 reaches 1e-12 rad in a few hundred
steps, so far less rounding accumulates than in the tens of thousands of steps an
order-4 method needs there. Conserves nothing exactly.

How the step is written, and why. Each stage and the update form their weighted sum of
stage rates first and add it to the state once, x + h·(Σ b_j k_j), as Hairer's DOP853
does: adding the eight increments to the state one at a time rounded the state eight
times per step, and on the fast spinner (1000 rad/s) round-off then dominated from 8000
steps on, 3.1e-12 rad there and 7.8e-12 at 11312 against a 30-digit integration; summed
first, 2.9e-13 and 3.4e-13 (``tests/test_integrator_orders.py``). The stages are written
out one by one, the coefficients indexed by constants, so the compiled step keeps every
stage rate in registers instead of allocating stage arrays each step and looping over
the tableau's zeros (118 against 165 ns per step on the far asymmetric top, measured
under load). A sum starts from −0.0, the one constant LLVM may drop exactly
(−0.0 + y = y for every y), so starting it costs nothing.

Step limit (warn), as for RK4: a step scales the linearised wobble by R(ihν), R the
tableau's own stability polynomial 1 + z bᵀ(I − zA)⁻¹𝟙 (degree 12; |R(iy)| < 1 for small
y); N·|ln |R(ihν)|²| ≥ 1 warns (ν with |ω|/2, q being stepped by the same tableau).
"""

from __future__ import annotations

from .base import FREE, MOTION, TORQUED, register
from .limits import stability_polynomial, wobble_damping
from .slots import accel, o_axpy, o_load, o_rate, r_axpy, r_load
from .template import TemplateIntegrator

# The step templates below are not in __all__: they are source the code generator
# specialises (ga_rotors.integrators._source), not functions to call; the public entry
# is the registered integrator, run through Integrator.run.
__all__ = ["DP8", "STAGES", "A", "B", "C"]

STAGES = 12
# A[i * 12 + j], row-major, 12 x 12 (lower triangular).
# The tableau is laid out by hand; ruff would put one number per line.
# fmt: off
A = (
    0.0, 0.0, 0.0,
    0.0, 0.0, 0.0,
    0.0, 0.0, 0.0,
    0.0, 0.0, 0.0,
    0.05260015195876773, 0.0, 0.0,
    0.0, 0.0, 0.0,
    0.0, 0.0, 0.0,
    0.0, 0.0, 0.0,
    0.0197250569845379, 0.0591751709536137, 0.0,
    0.0, 0.0, 0.0,
    0.0, 0.0, 0.0,
    0.0, 0.0, 0.0,
    0.02958758547680685, 0.0, 0.08876275643042054,
    0.0, 0.0, 0.0,
    0.0, 0.0, 0.0,
    0.0, 0.0, 0.0,
    0.2413651341592667, 0.0, -0.8845494793282861,
    0.924834003261792, 0.0, 0.0,
    0.0, 0.0, 0.0,
    0.0, 0.0, 0.0,
    0.037037037037037035, 0.0, 0.0,
    0.17082860872947386, 0.12546768756682242, 0.0,
    0.0, 0.0, 0.0,
    0.0, 0.0, 0.0,
    0.037109375, 0.0, 0.0,
    0.17025221101954405, 0.06021653898045596, -0.017578125,
    0.0, 0.0, 0.0,
    0.0, 0.0, 0.0,
    0.03709200011850479, 0.0, 0.0,
    0.17038392571223998, 0.10726203044637328, -0.015319437748624402,
    0.008273789163814023, 0.0, 0.0,
    0.0, 0.0, 0.0,
    0.6241109587160757, 0.0, 0.0,
    -3.3608926294469414, -0.868219346841726, 27.59209969944671,
    20.154067550477894, -43.48988418106996, 0.0,
    0.0, 0.0, 0.0,
    0.47766253643826434, 0.0, 0.0,
    -2.4881146199716677, -0.590290826836843, 21.230051448181193,
    15.279233632882423, -33.28821096898486, -0.020331201708508627,
    0.0, 0.0, 0.0,
    -0.9371424300859873, 0.0, 0.0,
    5.186372428844064, 1.0914373489967295, -8.149787010746927,
    -18.52006565999696, 22.739487099350505, 2.4936055526796523,
    -3.0467644718982196, 0.0, 0.0,
    2.273310147516538, 0.0, 0.0,
    -10.53449546673725, -2.0008720582248625, -17.9589318631188,
    27.94888452941996, -2.8589982771350235, -8.87285693353063,
    12.360567175794303, 0.6433927460157636, 0.0,
)
B = (
    0.054293734116568765, 0.0, 0.0,
    0.0, 0.0, 4.450312892752409,
    1.8915178993145003, -5.801203960010585, 0.3111643669578199,
    -0.1521609496625161, 0.20136540080403034, 0.04471061572777259,
)
C = (
    0.0, 0.05260015195876773, 0.0789002279381516,
    0.1183503419072274, 0.2816496580927726, 0.3333333333333333,
    0.25, 0.3076923076923077, 0.6512820512820513,
    0.6, 0.8571428571428571, 1.0,
)
# fmt: on

#: The start of every stage sum, as a path state and as rates (o_load and r_load read as
#: many entries as the path's state and the kind's rates have).
NEG_ZERO = (-0.0,) * 8


def dp8_step(t, x, w, h, inertia, params):
    """One step of the 12-stage, order-8 Dormand–Prince method (see the module notes)."""
    zx, zw = o_load(NEG_ZERO), r_load(NEG_ZERO)
    k1x, k1w = o_rate(x, w), accel(t + C[0] * h, x, w, inertia, params)
    # stage 2
    sx, sw = o_axpy(zx, A[1 * 12 + 0], k1x), r_axpy(zw, A[1 * 12 + 0], k1w)
    xs, ws = o_axpy(x, h, sx), r_axpy(w, h, sw)
    k2x, k2w = o_rate(xs, ws), accel(t + C[1] * h, xs, ws, inertia, params)
    # stage 3
    sx, sw = o_axpy(zx, A[2 * 12 + 0], k1x), r_axpy(zw, A[2 * 12 + 0], k1w)
    sx, sw = o_axpy(sx, A[2 * 12 + 1], k2x), r_axpy(sw, A[2 * 12 + 1], k2w)
    xs, ws = o_axpy(x, h, sx), r_axpy(w, h, sw)
    k3x, k3w = o_rate(xs, ws), accel(t + C[2] * h, xs, ws, inertia, params)
    # stage 4
    sx, sw = o_axpy(zx, A[3 * 12 + 0], k1x), r_axpy(zw, A[3 * 12 + 0], k1w)
    sx, sw = o_axpy(sx, A[3 * 12 + 2], k3x), r_axpy(sw, A[3 * 12 + 2], k3w)
    xs, ws = o_axpy(x, h, sx), r_axpy(w, h, sw)
    k4x, k4w = o_rate(xs, ws), accel(t + C[3] * h, xs, ws, inertia, params)
    # stage 5
    sx, sw = o_axpy(zx, A[4 * 12 + 0], k1x), r_axpy(zw, A[4 * 12 + 0], k1w)
    sx, sw = o_axpy(sx, A[4 * 12 + 2], k3x), r_axpy(sw, A[4 * 12 + 2], k3w)
    sx, sw = o_axpy(sx, A[4 * 12 + 3], k4x), r_axpy(sw, A[4 * 12 + 3], k4w)
    xs, ws = o_axpy(x, h, sx), r_axpy(w, h, sw)
    k5x, k5w = o_rate(xs, ws), accel(t + C[4] * h, xs, ws, inertia, params)
    # stage 6
    sx, sw = o_axpy(zx, A[5 * 12 + 0], k1x), r_axpy(zw, A[5 * 12 + 0], k1w)
    sx, sw = o_axpy(sx, A[5 * 12 + 3], k4x), r_axpy(sw, A[5 * 12 + 3], k4w)
    sx, sw = o_axpy(sx, A[5 * 12 + 4], k5x), r_axpy(sw, A[5 * 12 + 4], k5w)
    xs, ws = o_axpy(x, h, sx), r_axpy(w, h, sw)
    k6x, k6w = o_rate(xs, ws), accel(t + C[5] * h, xs, ws, inertia, params)
    # stage 7
    sx, sw = o_axpy(zx, A[6 * 12 + 0], k1x), r_axpy(zw, A[6 * 12 + 0], k1w)
    sx, sw = o_axpy(sx, A[6 * 12 + 3], k4x), r_axpy(sw, A[6 * 12 + 3], k4w)
    sx, sw = o_axpy(sx, A[6 * 12 + 4], k5x), r_axpy(sw, A[6 * 12 + 4], k5w)
    sx, sw = o_axpy(sx, A[6 * 12 + 5], k6x), r_axpy(sw, A[6 * 12 + 5], k6w)
    xs, ws = o_axpy(x, h, sx), r_axpy(w, h, sw)
    k7x, k7w = o_rate(xs, ws), accel(t + C[6] * h, xs, ws, inertia, params)
    # stage 8
    sx, sw = o_axpy(zx, A[7 * 12 + 0], k1x), r_axpy(zw, A[7 * 12 + 0], k1w)
    sx, sw = o_axpy(sx, A[7 * 12 + 3], k4x), r_axpy(sw, A[7 * 12 + 3], k4w)
    sx, sw = o_axpy(sx, A[7 * 12 + 4], k5x), r_axpy(sw, A[7 * 12 + 4], k5w)
    sx, sw = o_axpy(sx, A[7 * 12 + 5], k6x), r_axpy(sw, A[7 * 12 + 5], k6w)
    sx, sw = o_axpy(sx, A[7 * 12 + 6], k7x), r_axpy(sw, A[7 * 12 + 6], k7w)
    xs, ws = o_axpy(x, h, sx), r_axpy(w, h, sw)
    k8x, k8w = o_rate(xs, ws), accel(t + C[7] * h, xs, ws, inertia, params)
    # stage 9
    sx, sw = o_axpy(zx, A[8 * 12 + 0], k1x), r_axpy(zw, A[8 * 12 + 0], k1w)
    sx, sw = o_axpy(sx, A[8 * 12 + 3], k4x), r_axpy(sw, A[8 * 12 + 3], k4w)
    sx, sw = o_axpy(sx, A[8 * 12 + 4], k5x), r_axpy(sw, A[8 * 12 + 4], k5w)
    sx, sw = o_axpy(sx, A[8 * 12 + 5], k6x), r_axpy(sw, A[8 * 12 + 5], k6w)
    sx, sw = o_axpy(sx, A[8 * 12 + 6], k7x), r_axpy(sw, A[8 * 12 + 6], k7w)
    sx, sw = o_axpy(sx, A[8 * 12 + 7], k8x), r_axpy(sw, A[8 * 12 + 7], k8w)
    xs, ws = o_axpy(x, h, sx), r_axpy(w, h, sw)
    k9x, k9w = o_rate(xs, ws), accel(t + C[8] * h, xs, ws, inertia, params)
    # stage 10
    sx, sw = o_axpy(zx, A[9 * 12 + 0], k1x), r_axpy(zw, A[9 * 12 + 0], k1w)
    sx, sw = o_axpy(sx, A[9 * 12 + 3], k4x), r_axpy(sw, A[9 * 12 + 3], k4w)
    sx, sw = o_axpy(sx, A[9 * 12 + 4], k5x), r_axpy(sw, A[9 * 12 + 4], k5w)
    sx, sw = o_axpy(sx, A[9 * 12 + 5], k6x), r_axpy(sw, A[9 * 12 + 5], k6w)
    sx, sw = o_axpy(sx, A[9 * 12 + 6], k7x), r_axpy(sw, A[9 * 12 + 6], k7w)
    sx, sw = o_axpy(sx, A[9 * 12 + 7], k8x), r_axpy(sw, A[9 * 12 + 7], k8w)
    sx, sw = o_axpy(sx, A[9 * 12 + 8], k9x), r_axpy(sw, A[9 * 12 + 8], k9w)
    xs, ws = o_axpy(x, h, sx), r_axpy(w, h, sw)
    k10x, k10w = o_rate(xs, ws), accel(t + C[9] * h, xs, ws, inertia, params)
    # stage 11
    sx, sw = o_axpy(zx, A[10 * 12 + 0], k1x), r_axpy(zw, A[10 * 12 + 0], k1w)
    sx, sw = o_axpy(sx, A[10 * 12 + 3], k4x), r_axpy(sw, A[10 * 12 + 3], k4w)
    sx, sw = o_axpy(sx, A[10 * 12 + 4], k5x), r_axpy(sw, A[10 * 12 + 4], k5w)
    sx, sw = o_axpy(sx, A[10 * 12 + 5], k6x), r_axpy(sw, A[10 * 12 + 5], k6w)
    sx, sw = o_axpy(sx, A[10 * 12 + 6], k7x), r_axpy(sw, A[10 * 12 + 6], k7w)
    sx, sw = o_axpy(sx, A[10 * 12 + 7], k8x), r_axpy(sw, A[10 * 12 + 7], k8w)
    sx, sw = o_axpy(sx, A[10 * 12 + 8], k9x), r_axpy(sw, A[10 * 12 + 8], k9w)
    sx, sw = o_axpy(sx, A[10 * 12 + 9], k10x), r_axpy(sw, A[10 * 12 + 9], k10w)
    xs, ws = o_axpy(x, h, sx), r_axpy(w, h, sw)
    k11x, k11w = o_rate(xs, ws), accel(t + C[10] * h, xs, ws, inertia, params)
    # stage 12
    sx, sw = o_axpy(zx, A[11 * 12 + 0], k1x), r_axpy(zw, A[11 * 12 + 0], k1w)
    sx, sw = o_axpy(sx, A[11 * 12 + 3], k4x), r_axpy(sw, A[11 * 12 + 3], k4w)
    sx, sw = o_axpy(sx, A[11 * 12 + 4], k5x), r_axpy(sw, A[11 * 12 + 4], k5w)
    sx, sw = o_axpy(sx, A[11 * 12 + 5], k6x), r_axpy(sw, A[11 * 12 + 5], k6w)
    sx, sw = o_axpy(sx, A[11 * 12 + 6], k7x), r_axpy(sw, A[11 * 12 + 6], k7w)
    sx, sw = o_axpy(sx, A[11 * 12 + 7], k8x), r_axpy(sw, A[11 * 12 + 7], k8w)
    sx, sw = o_axpy(sx, A[11 * 12 + 8], k9x), r_axpy(sw, A[11 * 12 + 8], k9w)
    sx, sw = o_axpy(sx, A[11 * 12 + 9], k10x), r_axpy(sw, A[11 * 12 + 9], k10w)
    sx, sw = o_axpy(sx, A[11 * 12 + 10], k11x), r_axpy(sw, A[11 * 12 + 10], k11w)
    xs, ws = o_axpy(x, h, sx), r_axpy(w, h, sw)
    k12x, k12w = o_rate(xs, ws), accel(t + C[11] * h, xs, ws, inertia, params)
    # the update, its sum formed before it is added to the state
    sx, sw = o_axpy(zx, B[0], k1x), r_axpy(zw, B[0], k1w)
    sx, sw = o_axpy(sx, B[5], k6x), r_axpy(sw, B[5], k6w)
    sx, sw = o_axpy(sx, B[6], k7x), r_axpy(sw, B[6], k7w)
    sx, sw = o_axpy(sx, B[7], k8x), r_axpy(sw, B[7], k8w)
    sx, sw = o_axpy(sx, B[8], k9x), r_axpy(sw, B[8], k9w)
    sx, sw = o_axpy(sx, B[9], k10x), r_axpy(sw, B[9], k10w)
    sx, sw = o_axpy(sx, B[10], k11x), r_axpy(sw, B[10], k11w)
    sx, sw = o_axpy(sx, B[11], k12x), r_axpy(sw, B[11], k12w)
    return o_axpy(x, h, sx), r_axpy(w, h, sw)


DP8 = register(
    TemplateIntegrator(
        name="dp8",
        order=8,
        description="fixed-step Dormand–Prince 8 (DOP853's order-8 tableau), compiled",
        conserves=frozenset(),
        paths=frozenset({"rotor", "quaternion", "euler", "motor"}),
        steps={FREE: dp8_step, TORQUED: dp8_step, MOTION: dp8_step},
        # R from the tableau itself (degree 12, not e^z's Taylor polynomial past z⁸).
        step_limit=wobble_damping(stability_polynomial(A, B), steps_q=True),
        evaluations=STAGES,
    )
)
