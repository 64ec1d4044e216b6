"""Fixed-step Dormand–Prince 8: the order-8 solution of DOP853 as a compiled loop.

The same 12-stage tableau scipy's adaptive DOP853 uses (Hairer, Nørsett & Wanner, *Solving
ODEs I*, II.10; coefficients as in ``scipy.integrate._ivp.dop853_coefficients``, and
``tests/test_integrator_orders.py`` checks they are identical), without the error estimate:
a fixed step, compiled and specialised like every other method. Its use is the
high-accuracy end of the work-precision study: order 8 reaches 1e-12 rad in a few hundred
steps, so far less rounding accumulates than in the tens of thousands of steps an
order-4 method needs there. Conserves nothing exactly.

Step limit (warn), as for RK4: a step scales the linearised wobble by R(ihν), R the
tableau's own stability polynomial 1 + z bᵀ(I − zA)⁻¹𝟙 (degree 12; |R(iy)| < 1 for small
y); N·|ln |R(ihν)|²| ≥ 1 warns (ν with |ω|/2, q being stepped by the same tableau).
"""

from __future__ import annotations

import numpy as np

from ._arith import axpy3
from .base import FREE, TORQUED, register
from .limits import stability_polynomial, wobble_damping
from .slots import accel, o_axpy, o_load, o_rate
from .template import TemplateIntegrator

# The step templates below are not in __all__: they are source the code generator
# specialises (ga_rotors.integrators._codegen), not functions to call; the public entry
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


def dp8_step(t, x, w, h, inertia, params):
    """One step of the 12-stage, order-8 Dormand–Prince method."""
    kx = np.empty((STAGES, len(x)))
    kw = np.empty((STAGES, 3))
    for i in range(STAGES):
        xs = x
        ws = w
        for j in range(i):
            a = A[i * STAGES + j]
            if a != 0.0:
                xs = o_axpy(xs, h * a, o_load(kx[j]))
                ws = axpy3(ws, h * a, (kw[j, 0], kw[j, 1], kw[j, 2]))
        dx = o_rate(xs, ws)
        dw = accel(t + C[i] * h, xs, ws, inertia, params)
        for m in range(len(x)):
            kx[i, m] = dx[m]
        kw[i, 0] = dw[0]
        kw[i, 1] = dw[1]
        kw[i, 2] = dw[2]
    for i in range(STAGES):
        b = B[i]
        if b != 0.0:
            x = o_axpy(x, h * b, o_load(kx[i]))
            w = axpy3(w, h * b, (kw[i, 0], kw[i, 1], kw[i, 2]))
    return x, w


DP8 = register(
    TemplateIntegrator(
        name="dp8",
        order=8,
        description="fixed-step Dormand–Prince 8 (DOP853's order-8 tableau), compiled",
        conserves=frozenset(),
        paths=frozenset({"rotor", "quaternion", "euler"}),
        steps={FREE: dp8_step, TORQUED: dp8_step},
        # R from the tableau itself (degree 12, not e^z's Taylor polynomial past z⁸).
        step_limit=wobble_damping(stability_polynomial(A, B), steps_q=True),
        evaluations=STAGES,
    )
)
