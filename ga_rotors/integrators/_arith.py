"""Tuple arithmetic the integrator templates share: x + h·k and RK4's weighted sum.

Written for 3- and 4-tuples (vectors, Euler angles, quaternions, rotors); the orientation
paths bind the right size to the template slots ``o_axpy``/``o_rk4``/``o_load``/``o_store``.
"""

from __future__ import annotations

from math import isfinite

from .._jit import jit


@jit
def axpy3(x, h, k):
    """x + h·k for 3-tuples."""
    return (x[0] + h * k[0], x[1] + h * k[1], x[2] + h * k[2])


@jit
def axpy4(x, h, k):
    """x + h·k for 4-tuples."""
    return (x[0] + h * k[0], x[1] + h * k[1], x[2] + h * k[2], x[3] + h * k[3])


@jit
def rk4_sum3(x, h, k1, k2, k3, k4):
    """x + h/6 · (k1 + 2 k2 + 2 k3 + k4) for 3-tuples."""
    c = h / 6.0
    return (
        x[0] + c * (k1[0] + 2.0 * (k2[0] + k3[0]) + k4[0]),
        x[1] + c * (k1[1] + 2.0 * (k2[1] + k3[1]) + k4[1]),
        x[2] + c * (k1[2] + 2.0 * (k2[2] + k3[2]) + k4[2]),
    )


@jit
def rk4_sum4(x, h, k1, k2, k3, k4):
    """x + h/6 · (k1 + 2 k2 + 2 k3 + k4) for 4-tuples."""
    c = h / 6.0
    return (
        x[0] + c * (k1[0] + 2.0 * (k2[0] + k3[0]) + k4[0]),
        x[1] + c * (k1[1] + 2.0 * (k2[1] + k3[1]) + k4[1]),
        x[2] + c * (k1[2] + 2.0 * (k2[2] + k3[2]) + k4[2]),
        x[3] + c * (k1[3] + 2.0 * (k2[3] + k3[3]) + k4[3]),
    )


@jit
def load3(a):
    """The first three entries of a 1-D array as a tuple."""
    return (a[0], a[1], a[2])


@jit
def load4(a):
    """The first four entries of a 1-D array as a tuple."""
    return (a[0], a[1], a[2], a[3])


@jit
def store3(out, row, x):
    """out[row, :3] = x."""
    out[row, 0] = x[0]
    out[row, 1] = x[1]
    out[row, 2] = x[2]


@jit
def store4(out, row, x):
    """out[row, :4] = x."""
    out[row, 0] = x[0]
    out[row, 1] = x[1]
    out[row, 2] = x[2]
    out[row, 3] = x[3]


@jit
def finite_row(out, row):
    """True when every entry of out[row] is finite."""
    for j in range(out.shape[1]):
        if not isfinite(out[row, j]):
            return False
    return True


# Whole rigid motion (ga_rotors.paths.motor, ga_rotors.paths.pose): its rates (ω, v) are
# 6 numbers, its poses 7 (q, c) or 8 (a motor). Written out like the 3- and 4-tuples: a
# loop over a tuple's entries would not compile to straight-line code.


@jit
def axpy6(x, h, k):
    """x + h·k for 6-tuples."""
    return (x[0] + h * k[0], x[1] + h * k[1], x[2] + h * k[2], x[3] + h * k[3],
            x[4] + h * k[4], x[5] + h * k[5])  # fmt: skip


@jit
def axpy7(x, h, k):
    """x + h·k for 7-tuples."""
    return (x[0] + h * k[0], x[1] + h * k[1], x[2] + h * k[2], x[3] + h * k[3],
            x[4] + h * k[4], x[5] + h * k[5], x[6] + h * k[6])  # fmt: skip


@jit
def axpy8(x, h, k):
    """x + h·k for 8-tuples."""
    return (x[0] + h * k[0], x[1] + h * k[1], x[2] + h * k[2], x[3] + h * k[3],
            x[4] + h * k[4], x[5] + h * k[5], x[6] + h * k[6], x[7] + h * k[7])  # fmt: skip


@jit
def rk4_sum6(x, h, k1, k2, k3, k4):
    """x + h/6 · (k1 + 2 k2 + 2 k3 + k4) for 6-tuples."""
    a = rk4_sum3((x[0], x[1], x[2]), h, (k1[0], k1[1], k1[2]), (k2[0], k2[1], k2[2]),
                 (k3[0], k3[1], k3[2]), (k4[0], k4[1], k4[2]))  # fmt: skip
    b = rk4_sum3((x[3], x[4], x[5]), h, (k1[3], k1[4], k1[5]), (k2[3], k2[4], k2[5]),
                 (k3[3], k3[4], k3[5]), (k4[3], k4[4], k4[5]))  # fmt: skip
    return (a[0], a[1], a[2], b[0], b[1], b[2])


@jit
def rk4_sum7(x, h, k1, k2, k3, k4):
    """x + h/6 · (k1 + 2 k2 + 2 k3 + k4) for 7-tuples."""
    a = rk4_sum4((x[0], x[1], x[2], x[3]), h, (k1[0], k1[1], k1[2], k1[3]),
                 (k2[0], k2[1], k2[2], k2[3]), (k3[0], k3[1], k3[2], k3[3]),
                 (k4[0], k4[1], k4[2], k4[3]))  # fmt: skip
    b = rk4_sum3((x[4], x[5], x[6]), h, (k1[4], k1[5], k1[6]), (k2[4], k2[5], k2[6]),
                 (k3[4], k3[5], k3[6]), (k4[4], k4[5], k4[6]))  # fmt: skip
    return (a[0], a[1], a[2], a[3], b[0], b[1], b[2])


@jit
def rk4_sum8(x, h, k1, k2, k3, k4):
    """x + h/6 · (k1 + 2 k2 + 2 k3 + k4) for 8-tuples."""
    a = rk4_sum4((x[0], x[1], x[2], x[3]), h, (k1[0], k1[1], k1[2], k1[3]),
                 (k2[0], k2[1], k2[2], k2[3]), (k3[0], k3[1], k3[2], k3[3]),
                 (k4[0], k4[1], k4[2], k4[3]))  # fmt: skip
    b = rk4_sum4((x[4], x[5], x[6], x[7]), h, (k1[4], k1[5], k1[6], k1[7]),
                 (k2[4], k2[5], k2[6], k2[7]), (k3[4], k3[5], k3[6], k3[7]),
                 (k4[4], k4[5], k4[6], k4[7]))  # fmt: skip
    return (a[0], a[1], a[2], a[3], b[0], b[1], b[2], b[3])


@jit
def load6(a):
    """The first six entries of a 1-D array as a tuple."""
    return (a[0], a[1], a[2], a[3], a[4], a[5])


@jit
def load7(a):
    """The first seven entries of a 1-D array as a tuple."""
    return (a[0], a[1], a[2], a[3], a[4], a[5], a[6])


@jit
def load8(a):
    """The first eight entries of a 1-D array as a tuple."""
    return (a[0], a[1], a[2], a[3], a[4], a[5], a[6], a[7])


@jit
def store6(out, row, x):
    """out[row, :6] = x."""
    out[row, 0] = x[0]
    out[row, 1] = x[1]
    out[row, 2] = x[2]
    out[row, 3] = x[3]
    out[row, 4] = x[4]
    out[row, 5] = x[5]


@jit
def store7(out, row, x):
    """out[row, :7] = x."""
    store4(out, row, (x[0], x[1], x[2], x[3]))
    out[row, 4] = x[4]
    out[row, 5] = x[5]
    out[row, 6] = x[6]


@jit
def store8(out, row, x):
    """out[row, :8] = x."""
    store4(out, row, (x[0], x[1], x[2], x[3]))
    out[row, 4] = x[4]
    out[row, 5] = x[5]
    out[row, 6] = x[6]
    out[row, 7] = x[7]
