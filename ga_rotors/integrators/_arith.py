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
