"""Force kernels used only by the tests (importable by generated modules)."""

import math

from ga_rotors._jit import jit


@jit
def linear_air_drag(t, q, c, w, v, p):
    """F = −b v at the centre of mass, b = p[0]: a user's own linear drag."""
    return (-p[0] * v[0], -p[0] * v[1], -p[0] * v[2], 0.0, 0.0, 0.0)


@jit
def not_finite(t, q, c, w, v, p):
    """Returns NaN: refused by the trial call."""
    return (math.nan, 0.0, 0.0, 0.0, 0.0, 0.0)


@jit
def three_numbers(t, q, c, w, v, p):
    """A torque's three numbers where a force's six are due."""
    return (0.0, 0.0, 0.0)


@jit
def four_arguments(t, q, w, p):
    """A torque kernel's signature."""
    return (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)


def plain_python(t, q, c, w, v, p):
    """Not compiled: refused."""
    return (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
